"""A plan made on a wrong estimate and executed on the truth is refused by the grasp's force bound (real
planner, mobile Panda, kitchen seed 0): a refrigerator door whose estimated hinge line is 2 cm off
sideways. The compliant arm follows the wrong arc, the handle holds, the door opens -- but only by
pulling more through the grasp than the gripper holds with its safety factor, so it is not certified;
the truth itself is."""

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
    force = task.criterion("grasp_force")
    assert not force.passed and force.threshold == pytest.approx(70.0) and force.value > 70.0
    assert "safety factor of 2" in force.detail
    assert task.criterion("grasp_held").passed and task.criterion("opened_fraction").passed    # it did open

    ok = certify(truth, [f"open-door:{FRIDGE}"], images=False).tasks[0]
    assert ok.status is Outcome.CERTIFIED and ok.criterion("grasp_force").value < 35.0
