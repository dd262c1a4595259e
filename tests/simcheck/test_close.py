"""Close tasks (``close-drawer`` / ``close-door``): the part starts open, the robot shuts it, and it counts as
closed within 2% of its range (1 cm / 2 deg, whichever is larger); a close that does not get there fails."""

import json

import numpy as np
import pytest

import simcheck.estimate_faults as wrong
from planners.config import PlannerConfig, default_amount
from simcheck.cli import main
from simcheck.criteria import closed_gap, rollout_criteria
from simcheck_fixture_plans import DATA
from simcheck_rollout_factory import good_rollout, with_

CAB = DATA / "panda_cabinet.urdf"
DOOR, DRAWER = "cabinet1_door14_joint", "cabinet1_drawer12_joint"
CFG = PlannerConfig()


def test_closed_gap_is_the_opening_left_and_replaces_the_opened_criteria():
    shut = with_(good_rollout(0.3), closing=True, joint_range=0.35, opening_type="prismatic",
                 opening_axis=np.array([1.0, 0.0, 0.0]))
    c = closed_gap(shut)
    assert c.passed and c.value == pytest.approx(0.0, abs=2e-3) and c.threshold == pytest.approx(0.01)
    names = [x.name for x in rollout_criteria(shut)]
    assert "closed_gap" in names and "opened_fraction" not in names and "opened_overshoot" not in names
    half = with_(shut, requested_amount=0.6)           # it started 0.6 open and was shut by 0.3 only
    assert not closed_gap(half).passed and "ended 0.300 m from closed" in closed_gap(half).detail
    door = with_(shut, opening_type="", joint_range=1.9)   # 2% of 1.9 rad is more than 2 deg
    assert closed_gap(door).threshold == pytest.approx(0.038)


@pytest.mark.parametrize("task, start", [(f"close-drawer:{DRAWER}", default_amount("drawer", 0.0, 0.35, CFG)),
                                         (f"close-door:{DOOR}", default_amount("door", 0.0, 1.9, CFG))])
def test_a_close_task_starts_open_and_is_certified_when_shut(task, start, tmp_path):
    assert main(["certify", str(CAB), "--task", task, "--out", str(tmp_path / "o"), "--no-images"]) == 0
    t = json.loads((tmp_path / "o" / "certificate.json").read_text())["tasks"][0]
    joint = task.split(":")[1]
    assert t["status"] == "certified" and t["kind"] == task.split(":")[0]
    assert t["start_state"][joint] == pytest.approx(start) and t["amount"] == pytest.approx(-start)
    gap = next(c for c in t["criteria"] if c["name"] == "closed_gap")
    assert gap["passed"] and gap["value"] < gap["threshold"]


def test_a_close_blocked_by_something_in_the_swing_fails_with_the_gap_left(tmp_path):
    """Planned on the cabinet as it is, executed on one with a box where the door sweeps: the door stops on
    it, short of closed."""
    ref = wrong.blocker_in_swing(CAB, DOOR, tmp_path / "blocked.urdf")
    assert main(["certify", str(CAB), "--task", f"close-door:{DOOR}", "--from", "1.2", "--against", str(ref),
                 "--out", str(tmp_path / "o"), "--no-images"]) == 1
    t = json.loads((tmp_path / "o" / "certificate.json").read_text())["tasks"][0]
    gap = next(c for c in t["criteria"] if c["name"] == "closed_gap")
    assert t["status"] == "failed" and not gap["passed"] and gap["value"] > 0.2, t["reason"]
    assert t["start_state"][DOOR] == pytest.approx(1.2)


def test_a_scenario_opens_then_closes_from_where_the_opening_left_the_door(tmp_path):
    (tmp_path / "scene.urdf").write_bytes(CAB.read_bytes())
    sc = tmp_path / "scenario.yaml"
    sc.write_text(f"scene: scene.urdf\ntasks:\n  - {{kind: open-door, joint: {DOOR}, amount: 1.0}}\n"
                  f"  - close-door:{DOOR}\n  - {{kind: close-drawer, joint: {DRAWER}, from: 0.2}}\n")
    code = main(["run", str(sc), "--out", str(tmp_path / "o"), "--no-images"])
    tasks = json.loads((tmp_path / "o" / "certificate.json").read_text())["tasks"]
    assert code == 0, [t["reason"] for t in tasks]
    assert tasks[1]["start_state"][DOOR] == pytest.approx(1.0, abs=0.1)       # where the opening left it
    assert tasks[2]["start_state"][DRAWER] == pytest.approx(0.2)


def test_robust_certification_of_a_close_task_is_refused_by_name(tmp_path):
    from planners.errors import TaskSpecError
    from simcheck.certification import certify

    with pytest.raises(TaskSpecError, match=f"close-door:{DOOR} would start closed"):
        certify(CAB, [f"close-door:{DOOR}"], robust=4, images=False)
