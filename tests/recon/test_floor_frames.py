"""The floor and the scan's frame (issue 12 item 5): the floor is estimated and reported, objects stand on
it in the scan's frame, ``level_floor`` rotates by the measured tilt only, and a scan upside down, not
z-up or not in metres is refused with a message that says how to fix it."""

import json
import subprocess
import xml.etree.ElementTree as ET
import sys

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from recon.errors import ScanError
from recon.graph_json import graph_dict, reconstruction_from_dict
from recon.leveling import Floor
from recon.model import JointType
from recon.pipeline import reconstruct_scan
from recon.scan import scan_from_arrays
from recon.scene_mjcf import reconstruction_mjcf


def _scan(synth, T=None, *, floor=True, wall=True, points_per_m2=4000, floor_points=None):
    """The cabinet and the table (on z = 0) with a floor and a wall behind the cabinet, moved by ``T``."""
    props, labels = synth.scan_arrays([synth.cabinet(), synth.table()], points_per_m2=points_per_m2, floor=floor)
    pts = np.c_[props["x"], props["y"], props["z"]]
    obj, part = props["object_id"], props["part_id"]
    extra = []
    rng = np.random.default_rng(5)
    if wall:
        extra.append(np.c_[np.full(3000, -0.03), rng.uniform(-1.5, 1.5, 3000), rng.uniform(0.0, 2.4, 3000)])
    if floor and floor_points is not None:
        keep = (obj >= 0) | (rng.random(len(obj)) < floor_points / max(int((obj < 0).sum()), 1))
        pts, obj, part = pts[keep], obj[keep], part[keep]
    if extra:
        e = np.concatenate(extra)
        pts, obj, part = np.r_[pts, e], np.r_[obj, np.full(len(e), -1)], np.r_[part, np.full(len(e), -1)]
    if T is not None:
        pts = pts @ T[:3, :3].T + T[:3, 3]
    return scan_from_arrays({"x": pts[:, 0], "y": pts[:, 1], "z": pts[:, 2], "object_id": obj, "part_id": part},
                            labels)


def _tilted(deg, height, axis=(0.3, 1.0, 0.0)):
    """The scan frame of a world whose floor is ``height`` m up along its normal, tilted ``deg`` about
    ``axis`` (horizontal)."""
    a = np.asarray(axis, float)
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec(np.radians(deg) * a / np.linalg.norm(a)).as_matrix()
    T[:3, 3] = height * T[:3, 2]
    return T


def _bottom_along(rec, object_id, n):
    return min(float((p.primitive.corners() @ n).min()) for p in rec.object(object_id).parts)


def _mjcf_gravity(rec):
    """scene.xml's ``<option gravity>`` (3,), or None when it keeps MuJoCo's default."""
    option = ET.fromstring(reconstruction_mjcf(rec)).find("option")
    return None if option is None else np.array(option.get("gravity").split(), float)


def _drawer(rec):
    return next(j for j in rec.joints() if j.type is JointType.PRISMATIC)


def test_a_level_scan_reports_its_floor_at_zero_and_keeps_its_objects_on_it(synth):
    rec = reconstruct_scan(_scan(synth))
    f = rec.floor
    assert f.found and abs(f.height_m) < 1e-3 and f.tilt_deg < 0.1
    assert _bottom_along(rec, 1, np.array([0, 0, 1.0])) == pytest.approx(0.0, abs=1e-3)
    assert not any("floor" in w for w in rec.warnings)
    assert _mjcf_gravity(rec) is None                     # MuJoCo's default (0, 0, -9.81)
    doc = graph_dict(rec)
    assert set(doc["floor"]) == {"height_m", "tilt_deg", "normal", "n_points"}
    back = reconstruction_from_dict(json.loads(json.dumps(doc)))
    assert back.floor.height_m == pytest.approx(f.height_m) and np.allclose(back.floor.normal, f.normal)


def test_a_floor_5cm_up_and_tilted_1deg_is_estimated_and_the_objects_stand_on_it(synth):
    T = _tilted(1.0, 0.05)
    n = T[:3, 2]
    rec = reconstruct_scan(_scan(synth, T))
    f = rec.floor
    assert f.height_m == pytest.approx(0.05, abs=0.002) and f.tilt_deg == pytest.approx(1.0, abs=0.05)
    assert np.degrees(np.arccos(f.normal @ n)) < 0.05
    for oid in (1, 2):                                   # in the scan's frame, on the scan's floor
        assert _bottom_along(rec, oid, n) == pytest.approx(0.05, abs=0.002)
    assert np.degrees(np.arccos(abs(_drawer(rec).axis @ T[:3, 0]))) < 1.0
    assert np.allclose(rec.T_world_scan, np.eye(4))
    assert any("--level-floor" in w and "tilted 1.0 deg" in w for w in rec.warnings)
    assert np.allclose(_mjcf_gravity(rec), -9.81 * f.normal, atol=1e-8)   # scene.xml stands on it too

    lev = reconstruct_scan(_scan(synth, T), level_floor=True)
    assert lev.floor.height_m == pytest.approx(0.0, abs=1e-9) and lev.floor.tilt_deg < 1e-6
    assert _bottom_along(lev, 1, np.array([0, 0, 1.0])) == pytest.approx(0.0, abs=1e-3)
    angle = np.degrees(Rotation.from_matrix(lev.T_world_scan[:3, :3]).magnitude())
    assert angle == pytest.approx(1.0, abs=0.05)         # rotated by the measured tilt, nothing more
    assert abs(_drawer(lev).axis[2]) < 0.01


def test_without_floor_points_the_frame_is_kept_with_a_warning(synth):
    rec = reconstruct_scan(_scan(synth, floor=False, wall=False))
    assert not rec.floor.found and rec.floor.height_m == 0.0
    assert any("no floor in the scan" in w and "frame is kept" in w for w in rec.warnings)
    top = rec.object(2).part(201).primitive
    assert top.corners()[:, 2].max() == pytest.approx(0.76, abs=0.01)
    assert np.allclose(rec.T_world_scan, np.eye(4))


@pytest.mark.parametrize("rotvec, words", [
    ([np.pi, 0, 0], ["upside down", "above the labelled objects", "--level-floor"]),
    ([-np.pi / 2, 0, 0], ["not z-up", "beside the labelled objects", "+y-up", "--level-floor"]),
])
def test_an_upside_down_or_y_up_scan_is_refused_and_levels_with_level_floor(synth, rotvec, words):
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec(rotvec).as_matrix()
    with pytest.raises(ScanError) as exc:
        reconstruct_scan(_scan(synth, T))
    for w in words:
        assert w in str(exc.value)
    rec = reconstruct_scan(_scan(synth, T), level_floor=True)
    assert abs(_drawer(rec).axis[2]) < 0.02
    body = rec.object(1).part(101).primitive
    assert body.corners()[:, 2].min() == pytest.approx(0.0, abs=0.01)
    assert body.corners()[:, 2].max() == pytest.approx(0.8, abs=0.02)


def test_a_scan_ten_times_too_large_is_refused(synth):
    T = np.diag([10.0, 10.0, 10.0, 1.0])
    with pytest.raises(ScanError) as exc:
        reconstruct_scan(_scan(synth, T))
    msg = str(exc.value)
    assert "implausibly scaled" in msg and "object 1 (cabinet)" in msg and "metres" in msg
    with pytest.raises(ScanError, match="implausibly scaled"):           # no floor to stand on: still refused
        reconstruct_scan(_scan(synth, T, floor=False, wall=False))


def test_a_scan_ten_times_too_small_is_refused(synth):
    T = np.diag([0.1, 0.1, 0.1, 1.0])
    with pytest.raises(ScanError) as exc:
        reconstruct_scan(_scan(synth, T, floor=False, wall=False))
    msg = str(exc.value)
    assert "implausibly scaled" in msg and "smaller than any real one" in msg and "object 1 (cabinet)" in msg


def test_level_floor_never_turns_a_nearly_level_scan_over(synth):
    """The old failure: a sparse floor missing from the plane candidates -> "178.4 deg off"."""
    T = _tilted(2.0, 0.03, axis=(1.0, -0.4, 0.0))
    rec = reconstruct_scan(_scan(synth, T, floor_points=300), level_floor=True)
    angle = np.degrees(Rotation.from_matrix(rec.T_world_scan[:3, :3]).magnitude())
    assert angle == pytest.approx(2.0, abs=0.1)
    body = rec.object(1).part(101).primitive
    assert body.corners()[:, 2].min() == pytest.approx(0.0, abs=0.01)
    assert body.corners()[:, 2].max() == pytest.approx(0.8, abs=0.02)


def test_floor_transform_round_trip():
    f = Floor(np.array([0.01, -0.02, 1.0]), 0.06, 500)
    T = f.T_floor_frame()
    g = f.transformed(T)
    assert np.allclose(g.normal, [0, 0, 1]) and abs(g.height_m) < 1e-12
    back = g.transformed(np.linalg.inv(T))
    assert np.allclose(back.normal, f.normal) and back.height_m == pytest.approx(0.06)


def test_cli_exits_2_on_an_upside_down_scan_naming_the_fix(synth, tmp_path):
    s = _scan(synth, np.diag([1.0, -1.0, -1.0, 1.0]), points_per_m2=2000)
    props = {"x": s.points[:, 0], "y": s.points[:, 1], "z": s.points[:, 2], "object_id": s.object_id,
             "part_id": s.part_id}
    synth.write_ply(tmp_path / "scan.ply", props)
    labels = [{"id": o.id, "category": o.category, "parts": [{"id": p.part_id, "label": p.label} for p in o.parts]}
              for o in s.objects]
    (tmp_path / "labels.json").write_text(json.dumps({"objects": labels}))
    run = subprocess.run([sys.executable, "-m", "recon", "build", str(tmp_path / "scan.ply"), "--labels",
                          str(tmp_path / "labels.json"), "--out", str(tmp_path / "out"), "--no-preview"],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 2, run.stderr
    assert "upside down" in run.stderr and "--level-floor" in run.stderr and "Traceback" not in run.stderr
