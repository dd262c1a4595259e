"""A plan made on a wrong estimate and executed on the truth is refused by the grasp's force bound (real
planner, mobile Panda, kitchen seed 0): a refrigerator door whose estimated hinge line is 2 cm off
sideways. The stiff arm follows the wrong arc: it pulls more through the grasp than the gripper holds
with its safety factor, or the door does not follow far enough -- not certified; the truth itself is."""

import pytest

from scenes.outcome import Outcome
from simcheck.certification import certify

import simcheck.estimate_faults as wrong
from simcheck_kitchen import kitchen_truth

FRIDGE = "refrigerator3_door14_joint"


@pytest.fixture(scope="module")
def kitchen(tmp_path_factory):
    return kitchen_truth(tmp_path_factory, FRIDGE)


def test_a_hinge_2cm_off_sideways_needs_more_than_the_gripper_holds_with_margin(kitchen, tmp_path):
    truth = kitchen / "truth.urdf"
    est = wrong.shift_hinge(truth, FRIDGE, tmp_path / "estimate.urdf", sideways=0.02)
    task = certify(est, [f"open-door:{FRIDGE}"], against=truth, images=False).tasks[0]
    assert task.status is Outcome.FAILED
    assert task.criterion("grasp_force").threshold == pytest.approx(70.0)           # 140 N / safety factor 2
    # refused by what the real robot would meet: the pull through the fingers, or the door not following
    assert set(task.failed_criteria) & {"grasp_force", "opened_fraction"}, task.reason
    assert "0.020 m from the reference hinge" in task.reason

    ok = certify(truth, [f"open-door:{FRIDGE}"], images=False).tasks[0]
    assert ok.status is Outcome.CERTIFIED and ok.criterion("grasp_force").passed
