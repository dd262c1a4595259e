"""A door whose hinge side the scan leaves undecided (graph.json ``uncertainty.side_undecided``): its other
hinge is the estimated line mirrored across the door's width; a robust certificate hinges half of its
worlds there, and those worlds fail (the plan pulls at the edge that is now the hinge), so the door is not
certified robustly."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from simcheck.certification import certify
from simcheck.errors import SimcheckInputError
from simcheck.hinge_side import other_hinge_origin
from simcheck.perturbations import sample_perturbations
from simcheck.robust_spreads import DEFAULT_PHYSICS_RANGES, JointSpreads, RobotErrors, joint_spreads_for
from simcheck.scene_joints import read_scene_joints
from test_robust import NO_ROBOT_ERRORS, _with_graph

DATA = Path(__file__).parent / "data"
DOOR = "cabinet1_door4_joint"


def _undecided(folder: Path, value=True) -> Path:
    scene = _with_graph(folder, DATA / "cabinet.urdf")
    doc = json.loads((folder / "graph.json").read_text())
    for j in doc["objects"][0]["joints"]:
        if j["name"] == DOOR:
            j["uncertainty"]["side_undecided"] = value
    (folder / "graph.json").write_text(json.dumps(doc))
    return scene


def test_the_other_hinge_lies_at_the_doors_other_edge_at_the_same_depth():
    j = read_scene_joints(DATA / "cabinet.urdf")[DOOR]
    other = other_hinge_origin(DATA / "cabinet.urdf", DOOR, j.axis_world, j.origin_world)
    d = other - j.origin_world
    assert abs(d @ j.axis_world) < 1e-9
    assert np.linalg.norm(d) == pytest.approx(0.56, abs=1e-6)       # the door's width
    assert d[0] == pytest.approx(0.0, abs=1e-9)                     # across its thickness: unchanged


def test_half_of_the_worlds_are_hinged_at_the_other_edge_about_the_reversed_axis(tmp_path):
    scene = _undecided(tmp_path)
    spreads, centre = joint_spreads_for(scene, DOOR, "revolute")
    assert centre.other_origin is not None
    j = read_scene_joints(scene)[DOOR]
    perts = sample_perturbations(40, 0, DOOR, "revolute", j.axis_world, j.origin_world, j.upper, centre, spreads,
                                 DEFAULT_PHYSICS_RANGES, RobotErrors())
    other = [p for p in perts if p.hinge_side == "other"]
    assert 10 <= len(other) <= 30
    for p in perts:
        flipped = p.hinge_side == "other"
        assert (np.asarray(p.axis) @ j.axis_world < 0) == flipped
        hinge = np.asarray(centre.other_origin if flipped else centre.origin)
        assert np.linalg.norm(np.asarray(p.origin) - hinge) < 0.02
    # without the flag no world is flipped, and the other draws are the same
    _, decided = joint_spreads_for(_with_graph(tmp_path / "decided", DATA / "cabinet.urdf"), DOOR, "revolute")
    same = sample_perturbations(40, 0, DOOR, "revolute", j.axis_world, j.origin_world, j.upper, decided, spreads,
                                DEFAULT_PHYSICS_RANGES, RobotErrors())
    assert all(p.hinge_side == "estimated" for p in same)
    assert [p.base_error for p in same] == [p.base_error for p in perts]
    # nor without a graph.json (no centre: the URDF's own joint), a drawer's either
    for jtype in ("revolute", "prismatic"):
        alone = sample_perturbations(40, 0, DOOR, jtype, j.axis_world, j.origin_world, j.upper, None, spreads,
                                     DEFAULT_PHYSICS_RANGES, RobotErrors())
        assert all(p.hinge_side == "estimated" for p in alone)


def test_a_side_undecided_that_is_not_a_boolean_is_named(tmp_path):
    scene = _undecided(tmp_path, value="yes")
    with pytest.raises(SimcheckInputError, match="uncertainty.side_undecided is 'yes'"):
        joint_spreads_for(scene, DOOR, "revolute")


def test_a_door_hinged_at_its_other_edge_does_not_open_so_it_is_not_certified_robustly(tmp_path):
    scene = _undecided(tmp_path / "scene")
    cert = certify(scene, [f"open-door:{DOOR}"], robust=4, seed=5, images=False, out=tmp_path / "out",
                   spreads=NO_ROBOT_ERRORS)
    block = cert[DOOR].robust
    sides = [p["hinge_side"] for p in block["perturbations"]]
    assert "other" in sides and "estimated" in sides, sides
    failed = {f["sample"] for f in block["failures"]}
    assert {i for i, s in enumerate(sides) if s == "other"} <= failed, block["failures"]
    assert cert[DOOR].status.value == "failed"
    # its worlds sample both sides: the plain certificate's caveat is not repeated from the nominal run
    from simcheck.certification import SIDE_CAVEAT
    assert "nominal: certified" in cert[DOOR].reason and SIDE_CAVEAT not in cert[DOOR].reason, cert[DOOR].reason


def test_a_plain_certificate_of_a_side_undecided_door_says_it_holds_for_the_estimated_side_only(tmp_path):
    from simcheck.certification import SIDE_CAVEAT

    undecided = certify(_undecided(tmp_path / "u"), [f"open-door:{DOOR}"], images=False)[DOOR]
    assert undecided.status.value == "certified" and undecided.reason.endswith(SIDE_CAVEAT), undecided.reason
    decided = certify(_with_graph(tmp_path / "d", DATA / "cabinet.urdf"), [f"open-door:{DOOR}"], images=False)[DOOR]
    assert decided.status.value == "certified" and SIDE_CAVEAT not in decided.reason
    assert decided.reason == undecided.reason[:-len(SIDE_CAVEAT) - 2]
    # against a reference the verdict is the reference's: no caveat
    ref = certify(_undecided(tmp_path / "r"), [f"open-door:{DOOR}"], against=DATA / "cabinet.urdf", images=False)[DOOR]
    assert SIDE_CAVEAT not in ref.reason


def test_the_cli_names_a_side_undecided_that_is_not_a_boolean_and_exits_2(tmp_path):
    import subprocess
    import sys

    scene = _undecided(tmp_path / "scene", value="yes")
    r = subprocess.run([sys.executable, "-m", "simcheck", "certify", str(scene), "--task", f"open-door:{DOOR}",
                        "--out", str(tmp_path / "out"), "--robust", "3"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    assert f"joint '{DOOR}': uncertainty.side_undecided is 'yes'" in r.stderr
    assert not (tmp_path / "out" / "certificate.json").exists()


def test_an_unknown_joint_is_named():
    with pytest.raises(SimcheckInputError, match="joint 'nope': not in the scene"):
        other_hinge_origin(DATA / "cabinet.urdf", "nope", (0, 0, 1), (0, 0, 0))
