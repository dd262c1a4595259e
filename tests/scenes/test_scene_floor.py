"""The floor a scene stands on (scenes.description.read_scene_floor): recon's graph.json beside the URDF, else
z = 0; a floor that cannot be stood on is refused naming the file and the field."""

import json

import numpy as np
import pytest

from scenes.description import LEVEL_FLOOR, DescriptionError, read_scene_floor


def _graph(tmp_path, doc) -> str:
    (tmp_path / "graph.json").write_text(doc if isinstance(doc, str) else json.dumps(doc))
    return str(tmp_path / "scene.urdf")


def test_without_an_estimated_floor_the_scene_stands_on_z0(tmp_path):
    assert read_scene_floor(tmp_path / "truth.urdf") is LEVEL_FLOOR          # no graph.json
    assert read_scene_floor(_graph(tmp_path, {"objects": []})) is LEVEL_FLOOR
    assert read_scene_floor(_graph(tmp_path, {"floor": {"height_m": 0.0, "normal": [0, 0, 1], "n_points": 0}})) is LEVEL_FLOOR
    assert np.array_equal(LEVEL_FLOOR.T_scene_floor, np.eye(4)) and LEVEL_FLOOR.gravity(9.81).tolist() == [0.0, 0.0, -9.81]


def test_an_estimated_floor_gives_the_floor_frame_and_gravity(tmp_path):
    n = np.array([np.sin(np.radians(1.0)), 0.0, np.cos(np.radians(1.0))])
    f = read_scene_floor(_graph(tmp_path, {"floor": {"height_m": 0.05, "tilt_deg": 1.0, "normal": (2 * n).tolist(),
                                                     "n_points": 900}}))
    assert not f.level and f.tilt_deg == pytest.approx(1.0) and f.source.endswith("graph.json")
    T = f.T_scene_floor
    assert np.allclose(T[:3, 2], n) and np.allclose(T[:3, :3].T @ T[:3, :3], np.eye(3))
    corners = (T @ np.array([[x, y, 0.0, 1.0] for x in (-3, 3) for y in (-3, 3)]).T).T[:, :3]
    assert np.allclose(f.height_of(corners), 0.0)                            # the floor frame's z = 0 is the floor
    assert np.allclose(f.gravity(9.81), -9.81 * n)
    assert f == read_scene_floor(tmp_path / "other.urdf") and hash(f) == hash(read_scene_floor(tmp_path / "x.urdf"))


@pytest.mark.parametrize("doc, says", [
    ("{not json", "cannot read the scene graph"),
    ({"floor": [0, 0, 1]}, "must be an object"),
    ({"floor": {"normal": [0, 0, 1], "n_points": 5}}, "needs 'height_m'"),
    ({"floor": {"height_m": 0.0, "normal": [0, 0, 0], "n_points": 5}}, "zero or non-finite normal"),
    ({"floor": {"height_m": float("nan"), "normal": [0, 0, 1], "n_points": 5}}, "non-finite height_m"),
    ({"floor": {"height_m": 0.0, "normal": [0, 0, -1], "n_points": 5}}, "180.0 deg off +z"),
    ({"floor": {"height_m": 0.0, "normal": [0, 1, 0], "n_points": 5}}, "--level-floor"),
])
def test_a_floor_that_cannot_be_stood_on_is_refused_naming_the_file(tmp_path, doc, says):
    with pytest.raises(DescriptionError) as e:
        read_scene_floor(_graph(tmp_path, doc))
    assert "graph.json" in str(e.value) and says in str(e.value)
