"""The pure core of robust certification (no PyBullet): sampling perturbed worlds, writing them as URDFs,
the Clopper–Pearson bound, the certificate's "robust" block, and bad input named."""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from planners.scene_urdf import read_scene_urdf
from scenes.outcome import Outcome
from simcheck.errors import SimcheckInputError
from simcheck.estimate_faults import shift_hinge
from simcheck.perturbations import sample_perturbation, sample_perturbations
from simcheck.perturbed_scene import ROOT_JOINT, perturbed_scene_text, write_perturbed_scene
from simcheck.robust_spreads import (DEFAULT_JOINT_SPREADS, DEFAULT_PHYSICS_RANGES, DEFAULT_ROBOT_ERRORS,
                                     check_robust_args, joint_spreads_for)
from simcheck.robust_verdict import SampleResult, robust_block, robust_outcome, success_lower_bound
from simcheck.scene_joints import read_scene_joints

DATA = Path(__file__).parent / "data"
DOOR = "cabinet1_door4_joint"
DRAWER = "cabinet1_drawer2_joint"
UNC = {"axis_deg": 0.5, "origin_m": 0.004, "upper": 0.02, "samples": 10, "method": "bootstrap"}


def _graph(joints: dict, uncertainty: dict | None = UNC) -> dict:
    """A graph.json holding the URDF's movable joints (world frame) with ``uncertainty``."""
    out = []
    for j in joints.values():
        if j.type in ("prismatic", "revolute"):
            d = {"name": j.name, "type": j.type, "axis": j.axis_world.tolist(), "origin": j.origin_world.tolist(),
                 "lower": j.lower, "upper": j.upper}
            if uncertainty is not None:
                d["uncertainty"] = dict(uncertainty)
            out.append(d)
    return {"format": "partscene.graph/1", "objects": [{"joints": out}]}


@pytest.fixture()
def scene_dir(tmp_path) -> Path:
    shutil.copy(DATA / "cabinet.urdf", tmp_path / "scene.urdf")
    (tmp_path / "graph.json").write_text(json.dumps(_graph(read_scene_joints(tmp_path / "scene.urdf"))))
    return tmp_path


def _samples(urdf: Path, joint: str, n: int, seed: int = 0, mode: str = "scan"):
    sj = read_scene_joints(urdf)[joint]
    spreads, centre = joint_spreads_for(urdf, joint, sj.type)
    return sample_perturbations(n, seed, joint, sj.type, sj.axis_world, sj.origin_world, sj.upper, centre, spreads,
                                DEFAULT_PHYSICS_RANGES, DEFAULT_ROBOT_ERRORS, mode=mode)


def test_seeded_sampling_is_deterministic_and_sample_i_does_not_depend_on_n(scene_dir):
    a = _samples(scene_dir / "scene.urdf", DOOR, 8, seed=3)
    b = _samples(scene_dir / "scene.urdf", DOOR, 8, seed=3)
    assert [p.to_dict() for p in a] == [p.to_dict() for p in b]
    longer = _samples(scene_dir / "scene.urdf", DOOR, 20, seed=3)
    assert [p.to_dict() for p in longer[:8]] == [p.to_dict() for p in a]
    other = _samples(scene_dir / "scene.urdf", DOOR, 8, seed=4)
    assert other[0].to_dict() != a[0].to_dict()
    assert len({p.origin for p in a}) == 8, "the worlds must differ"


def test_spreads_are_the_uncertainty_blocks(scene_dir):
    ps = _samples(scene_dir / "scene.urdf", DOOR, 400, seed=1)
    rms_axis = math.sqrt(np.mean([p.axis_off_deg ** 2 for p in ps]))
    rms_origin = math.sqrt(np.mean([p.origin_off_m ** 2 for p in ps]))
    assert rms_axis == pytest.approx(UNC["axis_deg"], rel=0.12)
    assert rms_origin == pytest.approx(UNC["origin_m"], rel=0.12)
    assert np.std([p.upper for p in ps]) == pytest.approx(UNC["upper"], rel=0.12)
    lo, hi = DEFAULT_PHYSICS_RANGES.joint_friction
    assert all(lo <= p.joint_friction <= hi for p in ps)
    assert np.std([p.base_error[0] for p in ps]) == pytest.approx(DEFAULT_ROBOT_ERRORS.base_xy_m, rel=0.12)


def test_three_cm_hinge_off_estimate_gets_worlds_centred_on_the_scan_consistent_hinge(scene_dir):
    """graph.json keeps the scan's hinge; the certified URDF's hinge is 3 cm off it: the sampled worlds are
    centred 3 cm away from the estimate, on the scan's hinge (a robust run is not N copies of the estimate)."""
    est = shift_hinge(scene_dir / "scene.urdf", DOOR, scene_dir / "estimate.urdf", sideways=0.03)
    scan_hinge = read_scene_joints(scene_dir / "scene.urdf")[DOOR].origin_world
    est_hinge = read_scene_joints(est)[DOOR].origin_world
    assert np.linalg.norm((est_hinge - scan_hinge)[:2]) == pytest.approx(0.03, abs=1e-6)
    ps = _samples(est, DOOR, 200, seed=0)
    mean = np.mean([p.origin for p in ps], axis=0)
    assert np.linalg.norm((mean - scan_hinge)[:2]) < 0.001
    assert np.mean([p.origin_off_m for p in ps]) == pytest.approx(0.03, abs=0.002)
    # the unmodified estimate: centred on itself
    same = _samples(scene_dir / "scene.urdf", DOOR, 200, seed=0)
    assert np.mean([p.origin_off_m for p in same]) < 0.006


def test_without_graph_json_default_spreads_centred_on_the_urdf(tmp_path):
    shutil.copy(DATA / "cabinet.urdf", tmp_path / "model.urdf")
    spreads, centre = joint_spreads_for(tmp_path / "model.urdf", DOOR, "revolute")
    assert centre is None and spreads == DEFAULT_JOINT_SPREADS["revolute"] and spreads.source == "default"
    ps = _samples(tmp_path / "model.urdf", DOOR, 300)
    rms = math.sqrt(np.mean([p.origin_off_m ** 2 for p in ps]))
    assert rms == pytest.approx(DEFAULT_JOINT_SPREADS["revolute"].origin_m, rel=0.15)


def test_physics_mode_leaves_joint_and_robot_alone(scene_dir):
    urdf = scene_dir / "scene.urdf"
    sj = read_scene_joints(urdf)[DOOR]
    for p, q in zip(_samples(urdf, DOOR, 5, mode="physics"), _samples(urdf, DOOR, 5)):
        assert np.allclose(p.origin, sj.origin_world) and np.allclose(p.axis, sj.axis_world) and p.upper == sj.upper
        assert p.base_error == (0.0, 0.0, 0.0) and p.handle_shift == (0.0, 0.0, 0.0) and p.tracking_gain == 1.0
        assert p.joint_friction == q.joint_friction and p.mass_scale == q.mass_scale


def test_perturbed_urdf_has_the_sampled_joint_and_keeps_the_door_where_it_was(scene_dir):
    src = scene_dir / "scene.urdf"
    p = _samples(src, DOOR, 3, seed=2)[1]
    p = type(p)(**{**p.__dict__, "base_error": (0.0, 0.0, 0.0), "handle_shift": (0.01, 0.0, 0.0)})
    out = write_perturbed_scene(src, p, scene_dir / "w" / "sample1.urdf")
    before, after = read_scene_urdf(src), read_scene_urdf(out)
    sj = read_scene_joints(out)[DOOR]
    assert np.allclose(sj.axis_world, p.axis, atol=1e-6) and np.allclose(sj.origin_world, p.origin, atol=1e-6)
    assert sj.upper == pytest.approx(p.upper)
    door = before.joints[DOOR].child
    for g0, g1 in zip(before.links[door].collisions, after.links[door].collisions):
        assert np.allclose(before.T_world_link(door) @ g0.T_link_shape, after.T_world_link(door) @ g1.T_link_shape,
                           atol=1e-6)
    handle = "cabinet1_handle5"
    moved = after.T_world_link(handle)[:3, 3] - before.T_world_link(handle)[:3, 3]
    assert np.allclose(moved, [0.01, 0.0, 0.0], atol=1e-6)
    text = out.read_text()
    assert f'friction="{p.joint_friction:.6g}"' in text and "lateral_friction" in text
    assert ROOT_JOINT not in text


def test_base_error_moves_the_whole_scene_by_its_inverse_about_the_pivot(scene_dir):
    src = scene_dir / "scene.urdf"
    p = _samples(src, DRAWER, 1)[0]
    p = type(p)(**{**p.__dict__, "base_error": (0.02, -0.01, np.radians(1.0))})
    pivot = (1.0, 0.5)
    path = scene_dir / "moved.urdf"
    path.write_text(perturbed_scene_text(src, p, pivot))
    before, after = read_scene_urdf(src), read_scene_urdf(path)
    body = "cabinet1_body1"
    c = np.cos(-np.radians(1.0)), np.sin(-np.radians(1.0))
    R = np.array([[c[0], -c[1]], [c[1], c[0]]])
    x0 = before.T_world_link(body)[:2, 3]
    expect = np.array(pivot) + R @ (x0 - np.array(pivot)) - np.array([0.02, -0.01])
    assert np.allclose(after.T_world_link(body)[:2, 3], expect, atol=1e-9)


def test_mass_of_the_moving_part_is_scaled(scene_dir):
    src = scene_dir / "scene.urdf"
    p = _samples(src, DRAWER, 1)[0]
    m0 = read_scene_urdf(src)
    text = perturbed_scene_text(src, p)
    import xml.etree.ElementTree as ET

    def mass(root):
        link = next(l for l in root.findall("link") if l.get("name") == "cabinet1_drawer2")
        return float(link.find("inertial/mass").get("value"))
    assert mass(ET.fromstring(text)) == pytest.approx(mass(ET.parse(src).getroot()) * p.mass_scale)
    assert m0 is not None


def test_clopper_pearson_lower_bound_against_closed_forms():
    # all successes: p^n = alpha; one success: 1 - (1 - p)^n = alpha
    assert success_lower_bound(30, 30) == pytest.approx(0.05 ** (1 / 30), rel=1e-9)   # 0.9050
    assert success_lower_bound(30, 30) >= 0.9 > success_lower_bound(29, 30)
    assert success_lower_bound(1, 20) == pytest.approx(1 - 0.95 ** (1 / 20), rel=1e-9)
    assert success_lower_bound(0, 30) == 0.0
    assert success_lower_bound(10, 10, 0.99) == pytest.approx(0.01 ** 0.1, rel=1e-9)
    bounds = [success_lower_bound(k, 30) for k in range(31)]
    assert bounds == sorted(bounds) and all(b < k / 30 for b, k in zip(bounds[1:], range(1, 31)))
    with pytest.raises(ValueError, match="successes"):
        success_lower_bound(5, 3)


def test_robust_block_has_the_issues_keys_and_decides_the_status(scene_dir):
    ps = _samples(scene_dir / "scene.urdf", DOOR, 4)
    res = [SampleResult(p, Outcome.CERTIFIED, "ok", {"opened_fraction": 0.1 * (i + 1), "grasp_held": 0.5})
           for i, p in enumerate(ps[:3])]
    res.append(SampleResult(ps[3], Outcome.FAILED, "grasp slipped", {"opened_fraction": -0.2}))
    block = robust_block(res, extra={"spreads": {"joint": {"source": "graph.json"}}})
    assert list(block)[:7] == ["samples", "successes", "success_lower_bound", "confidence", "worst_margins",
                               "perturbations", "failures"]
    assert block["samples"] == 4 and block["successes"] == 3 and block["confidence"] == 0.95
    assert block["worst_margins"] == {"opened_fraction": -0.2, "grasp_held": 0.5}
    assert [p["sample"] for p in block["perturbations"]] == [0, 1, 2, 3]
    assert block["failures"] == [{"sample": 3, "perturbation": ps[3].to_dict(), "outcome": "failed",
                                  "reason": "grasp slipped"}]
    assert robust_outcome(block, 0.9) is Outcome.FAILED
    assert robust_outcome(block, block["success_lower_bound"]) is Outcome.CERTIFIED
    json.dumps(block)


@pytest.mark.parametrize("robust, min_success, field", [
    (0, 0.9, "robust"), (-3, 0.9, "robust"), (2.5, 0.9, "robust"), (True, 0.9, "robust"),
    (10, 0.0, "min_success"), (10, 1.01, "min_success"), (10, -0.5, "min_success"), (10, float("nan"), "min_success"),
])
def test_bad_robust_arguments_are_named(robust, min_success, field):
    with pytest.raises(SimcheckInputError, match=f"^{field}: "):
        check_robust_args(robust, min_success)
    check_robust_args(30, 1.0)


@pytest.mark.parametrize("bad, field", [({"origin_m": float("nan")}, "uncertainty.origin_m"),
                                        ({"axis_deg": -1.0}, "uncertainty.axis_deg"),
                                        ({"upper": "wide"}, "uncertainty.upper"),
                                        ({"upper": None}, "uncertainty.upper")])
def test_bad_uncertainty_block_is_named(tmp_path, bad, field):
    shutil.copy(DATA / "cabinet.urdf", tmp_path / "scene.urdf")
    doc = _graph(read_scene_joints(tmp_path / "scene.urdf"), {**UNC, **bad})
    (tmp_path / "graph.json").write_text(json.dumps(doc).replace("NaN", "NaN"))
    with pytest.raises(SimcheckInputError, match=f"graph.json: joint '{DOOR}': {field} is"):
        joint_spreads_for(tmp_path / "scene.urdf", DOOR, "revolute")


def test_missing_spread_is_named(tmp_path):
    shutil.copy(DATA / "cabinet.urdf", tmp_path / "scene.urdf")
    unc = {k: v for k, v in UNC.items() if k != "axis_deg"}
    (tmp_path / "graph.json").write_text(json.dumps(_graph(read_scene_joints(tmp_path / "scene.urdf"), unc)))
    with pytest.raises(SimcheckInputError, match="uncertainty.axis_deg is missing"):
        joint_spreads_for(tmp_path / "scene.urdf", DOOR, "revolute")


def _written_axis(text: str, joint: str) -> np.ndarray:
    """The ``<axis xyz>`` of ``joint`` as written in URDF ``text`` (raw: the scene readers normalise it)."""
    import xml.etree.ElementTree as ET

    el = next(j for j in ET.fromstring(text).findall("joint") if j.get("name") == joint)
    return np.array([float(x) for x in el.find("axis").get("xyz").split()])


def test_perturbed_axis_is_written_as_a_unit_vector(scene_dir):
    src = scene_dir / "scene.urdf"
    for p in _samples(src, DOOR, 10, seed=5):
        a = _written_axis(perturbed_scene_text(src, p), DOOR)
        assert abs(np.linalg.norm(a) - 1.0) < 1e-12
    p = _samples(src, DRAWER, 1)[0]
    long = type(p)(**{**p.__dict__, "axis": tuple(2.5 * np.asarray(p.axis)), "base_error": (0.0, 0.0, 0.0)})
    out = write_perturbed_scene(src, long, scene_dir / "w" / "long_axis.urdf")      # a caller's unnormalised axis
    assert abs(np.linalg.norm(_written_axis(out.read_text(), DRAWER)) - 1.0) < 1e-12
    assert np.allclose(read_scene_joints(out)[DRAWER].axis_world, p.axis, atol=1e-9)
