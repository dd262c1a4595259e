"""scenes.description: the one truth.json reader/writer (format tag checked, atomic write, round trip)."""

from __future__ import annotations

import json

import pytest

from scenes.description import TRUTH_FORMAT, DescriptionError, read_truth_doc, write_truth_doc
from scenes.truth_json import read_truth_json, truth_dict_from_scene, write_truth_json


def test_truth_json_round_trip(tmp_path, kitchen):
    path = write_truth_json(kitchen, tmp_path / "truth.json")
    doc = read_truth_doc(path)
    assert doc["format"] == TRUTH_FORMAT and doc == json.loads(json.dumps(truth_dict_from_scene(kitchen)))
    assert read_truth_json(path).isclose(kitchen, atol=1e-12)
    again = write_truth_doc(doc, tmp_path / "again.json")
    assert again.read_text() == path.read_text()


def test_other_formats_and_broken_files_are_named(tmp_path):
    with pytest.raises(DescriptionError, match=r"x.json: format is 'other/2', expected 'partscene.truth/1'"):
        write_truth_doc({"format": "other/2"}, tmp_path / "x.json")
    (tmp_path / "bad.json").write_text("{")
    with pytest.raises(DescriptionError, match=r"bad.json: not valid JSON"):
        read_truth_doc(tmp_path / "bad.json")
    with pytest.raises(DescriptionError, match=r"gone.json: cannot read"):
        read_truth_doc(tmp_path / "gone.json")


def test_truth_shape_entries_round_trip_with_one_cylinder_convention():
    import numpy as np

    from scenes.description import Shape, shape_from_truth, truth_shape_dict
    T = np.eye(4)
    T[:3, 3] = [0.1, 0.2, 0.3]
    for s in (Shape.box([0.1, 0.2, 0.3], T), Shape.cylinder(0.05, 0.4, T)):
        back = shape_from_truth(json.loads(json.dumps(truth_shape_dict(s))), "x")
        assert back.isclose(s, atol=1e-15)
    assert truth_shape_dict(Shape.cylinder(0.05, 0.4))["radius"] == pytest.approx(0.05)


@pytest.mark.parametrize("entry, message", [
    ({"type": "cone", "T_part_shape": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]},
     r"part 7 shape 0: unknown shape type 'cone'"),
    ({"type": "box", "size": [0.1, -1, 0.1], "T_part_shape": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]},
     r"part 7 shape 0: bad box shape: sizes must be positive"),
    ({"type": "cylinder", "radius": 0.1, "T_part_shape": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]},
     r"bad cylinder shape: KeyError"),
    ({"type": "box", "size": [1, 1, 1], "T_part_shape": [[1, 0], [0, 1]]}, r"shape 0.T_part_shape: expected a finite 4x4"),
    ({"type": "box", "size": [1, 1, 1]}, r"missing field 'T_part_shape'"),
])
def test_malformed_truth_shapes_are_named(entry, message):
    from scenes.description import shape_from_truth
    with pytest.raises(DescriptionError, match=message):
        shape_from_truth(entry, "truth.json: part 7 shape 0")


def test_the_true_scene_holds_what_the_scene_wrote(tmp_path, kitchen):
    import numpy as np

    from scenes.description import JointType, read_true_scene

    true = read_true_scene(write_truth_json(kitchen, tmp_path / "truth.json"))
    assert (true.scene, true.seed) == (kitchen.name, kitchen.seed)
    for obj, t in zip(kitchen.objects, true.objects, strict=True):
        assert (t.id, t.name, t.category) == (obj.id, obj.name, obj.category)
        assert [p.link for p in t.parts] == [obj.link(p) for p in obj.parts]
        for p, tp in zip(obj.parts, t.parts, strict=True):
            assert np.allclose(tp.T_world_part, obj.T_world_object @ p.T_object_part)
            assert all(a.isclose(b, atol=1e-12) for a, b in zip(p.shapes, tp.shapes, strict=True))
        assert [(j.name, j.type, j.child_part_id) for j in t.joints] == [
            (obj.joint_name(j), JointType(j.type), j.child) for j in obj.joints]
        assert t.contacts == tuple(tuple(c) for c in obj.contacts)


def test_a_malformed_true_scene_names_the_object_and_joint(tmp_path, kitchen):
    from scenes.description import true_scene_from_doc

    doc = truth_dict_from_scene(kitchen)
    doc["objects"][0]["joints"][-1]["type"] = "ball"
    obj, joint = doc["objects"][0], doc["objects"][0]["joints"][-1]
    with pytest.raises(DescriptionError, match=rf"t.json object {obj['id']} \({obj['name']}\) joint {joint['name']}: "
                                               r"unknown joint type 'ball'"):
        true_scene_from_doc(doc, "t.json")
