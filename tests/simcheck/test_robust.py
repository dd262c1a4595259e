"""Robust certification with physics (small): a door estimate whose hinge is 3 cm off the scan's gets fewer
successes than the unmodified one; a failing sample replays alone with the same outcome; the CLI names
bad input and exits 2."""

from __future__ import annotations

import dataclasses
import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from scenes.outcome import Outcome
from simcheck.certificate import Certificate
from simcheck.certification import certify
from simcheck.estimate_faults import shift_hinge
from simcheck.robust_spreads import DEFAULT_SPREADS, RobotErrors
from simcheck.scene_joints import read_scene_joints

DATA = Path(__file__).parent / "data"
DOOR = "cabinet1_door4_joint"
N = 6
NO_ROBOT_ERRORS = dataclasses.replace(DEFAULT_SPREADS, robot=RobotErrors(0.0, 0.0, 0.0, (1.0, 1.0), guarded_approach=False))
"""Robot errors off: the joint and physics spreads decide."""


def _with_graph(folder: Path, urdf: Path) -> Path:
    """``urdf`` copied into ``folder`` as scene.urdf beside a graph.json holding its joints (the scan's
    estimate) with a small uncertainty."""
    folder.mkdir(parents=True, exist_ok=True)
    shutil.copy(urdf, folder / "scene.urdf")
    joints = [{"name": j.name, "type": j.type, "axis": j.axis_world.tolist(), "origin": j.origin_world.tolist(),
               "lower": 0.0, "upper": j.upper,
               "uncertainty": {"axis_deg": 0.3, "origin_m": 0.004, "upper": 0.02, "samples": 10, "method": "bootstrap"}}
              for j in read_scene_joints(folder / "scene.urdf").values() if j.type != "fixed"]
    (folder / "graph.json").write_text(json.dumps({"format": "partscene.graph/1", "objects": [{"joints": joints}]}))
    return folder / "scene.urdf"


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The unmodified door and the one whose hinge is 3 cm off graph.json's, each certified with N
    samples (robot errors off: the joint and physics spreads decide)."""
    tmp = tmp_path_factory.mktemp("robust")
    good = _with_graph(tmp / "good", DATA / "cabinet.urdf")
    off = tmp / "off"
    off.mkdir()
    shutil.copy(good.parent / "graph.json", off / "graph.json")
    shift_hinge(good, DOOR, off / "scene.urdf", sideways=0.03)
    return {name: certify(path, [f"open-door:{DOOR}"], robust=N, images=False, out=tmp / f"out_{name}",
                          spreads=NO_ROBOT_ERRORS) for name, path in (("good", good), ("off", off / "scene.urdf"))}


def test_hinge_three_cm_off_gets_fewer_successes(runs):
    good, off = runs["good"][DOOR].robust, runs["off"][DOOR].robust
    assert good["samples"] == off["samples"] == N
    assert off["successes"] < good["successes"], (good["successes"], off["successes"])
    assert good["successes"] >= N // 2
    assert len(off["failures"]) == N - off["successes"]
    assert runs["off"][DOOR].status is Outcome.FAILED
    # a robust run is not N copies of one world
    assert len({tuple(p["origin"]) for p in good["perturbations"]}) == N


def test_certificate_carries_the_robust_block_and_reads_back(runs):
    cert = runs["off"]
    doc = json.loads(cert.path.read_text())
    block = doc["tasks"][0]["robust"]
    assert list(block)[:7] == ["samples", "successes", "success_lower_bound", "confidence", "worst_margins",
                               "perturbations", "failures"]
    assert block["spreads"]["joint"]["source"] == "graph.json"
    assert Certificate.load(cert.path)[DOOR].robust == block
    # N of N successes gives at most 0.05 ** (1 / N) < 0.9: not certified with so few samples
    assert runs["good"][DOOR].status is Outcome.FAILED
    assert "with 95% confidence" in runs["good"][DOOR].reason


def test_a_failing_sample_replays_alone_with_the_same_outcome(runs, tmp_path):
    block = runs["off"][DOOR].robust
    fail = block["failures"][0]
    scene = Path(runs["off"].scene)
    cert = certify(scene, [f"open-door:{DOOR}"], robust=N, replay_sample=fail["sample"], images=False, out=tmp_path,
                   spreads=NO_ROBOT_ERRORS)
    task = cert[DOOR]
    assert task.robust["replayed_sample"] == fail["sample"] and task.robust["samples"] == 1
    assert task.robust["perturbations"][0] == fail["perturbation"]
    assert task.status.value == fail["outcome"]
    assert (tmp_path / "rollouts" / f"{DOOR}_sample{fail['sample']}.npz").is_file()


@pytest.mark.parametrize("args, field", [(["--robust", "0"], "robust"), (["--robust", "-2"], "robust"),
                                         (["--robust", "5", "--min-success", "1.5"], "min_success"),
                                         (["--robust", "5", "--min-success", "0"], "min_success"),
                                         (["--replay-sample", "1"], "robust"),
                                         (["--robust", "5", "--replay-sample", "7"], "replay_sample")])
def test_cli_names_bad_robust_input_and_exits_2(tmp_path, args, field):
    r = subprocess.run([sys.executable, "-m", "simcheck", "certify", str(DATA / "cabinet.urdf"),
                        "--task", f"open-door:{DOOR}", "--out", str(tmp_path), *args],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    assert f"error: {field}:" in r.stderr


def test_cli_names_a_nan_uncertainty_and_exits_2(tmp_path):
    scene = _with_graph(tmp_path, DATA / "cabinet.urdf")
    doc = json.loads((tmp_path / "graph.json").read_text())
    doc["objects"][0]["joints"][1]["uncertainty"]["origin_m"] = float("nan")
    (tmp_path / "graph.json").write_text(json.dumps(doc))
    r = subprocess.run([sys.executable, "-m", "simcheck", "certify", str(scene), "--task", f"open-door:{DOOR}",
                        "--out", str(tmp_path / "out"), "--robust", "3"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    assert f"joint '{DOOR}': uncertainty.origin_m is nan" in r.stderr


def test_robust_against_a_reference_samples_physics_only_on_copies_of_the_reference(tmp_path):
    ref = _with_graph(tmp_path / "ref", DATA / "cabinet.urdf")
    cert = certify(ref, ["open-drawer:cabinet1_drawer2_joint"], against=ref, robust=2, images=False, out=None)
    block = cert["cabinet1_drawer2_joint"].robust
    assert block["mode"] == "physics" and block["samples"] == 2
    sj = read_scene_joints(ref)["cabinet1_drawer2_joint"]
    for p in block["perturbations"]:
        assert p["axis_off_deg"] == 0.0 and p["origin_off_m"] == 0.0 and p["upper"] == sj.upper
        assert p["base_error"] == [0.0, 0.0, 0.0] and p["tracking_gain"] == 1.0
    assert len({p["joint_friction"] for p in block["perturbations"]}) == 2


def test_robust_against_a_reference_of_the_other_sign_convention_is_matched_by_direction(tmp_path):
    """The samples measure the opening as plain ``--against`` does: along the estimate's opening direction,
    so a reference whose door opens toward negative values is opened, not failed for its sign."""
    from test_simcheck_third_party_directions import CAB, DOOR as CAB_DOOR, _negative_opening

    cert = certify(CAB, [f"open-door:{CAB_DOOR}"], against=_negative_opening(tmp_path), robust=2, images=False,
                   out=None)
    block = cert[CAB_DOOR].robust
    assert block["mode"] == "physics" and block["successes"] == 2, block["failures"]
    assert cert[CAB_DOOR].status is Outcome.FAILED       # 2 of 2 cannot reach the 0.9 bound
