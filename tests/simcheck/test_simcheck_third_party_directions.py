"""``--against`` with a usable estimate that disagrees with its reference: a certification verdict (status
``failed``, exit 1, the difference named), never unusable input (exit 2); the certificate records how the
estimate's joint was matched to the reference's (name, type, limits, direction +1 / -1)."""

import json

import pytest

import simcheck.estimate_faults as wrong
from simcheck.certificate import Certificate
from simcheck.cli import main
from simcheck_fixture_plans import DATA

CAB = DATA / "panda_cabinet.urdf"
DOOR = "cabinet1_door14_joint"


def _estimate_and_reference(case, tmp_path):
    if case == "type":            # the reference's joint of that name is prismatic
        return CAB, wrong.revolute_as_prismatic(CAB, DOOR, tmp_path / "prismatic_ref.urdf")
    if case == "range":           # the reference's door opens half as far as the estimate's
        return CAB, wrong.widen_limits(CAB, DOOR, 0.5, tmp_path / "short_ref.urdf")
    return wrong.shift_hinge(CAB, DOOR, tmp_path / "shifted.urdf", sideways=0.03), CAB


@pytest.mark.parametrize("case, named", [
    ("type", f"joint {DOOR} is revolute in the estimate but prismatic in the reference"),
    ("range", f"the estimated upper limit of {DOOR} (1.900 rad) exceeds the reference's (0.950 rad)"),
    ("hinge", f"the estimated hinge of {DOOR} is 0.030 m from the reference hinge"),
])
def test_a_wrong_estimate_against_its_reference_fails_with_exit_1_naming_the_difference(case, named, tmp_path):
    est, ref = _estimate_and_reference(case, tmp_path)
    assert main(["certify", str(est), "--task", f"open-door:{DOOR}", "--against", str(ref),
                 "--out", str(tmp_path / "o"), "--no-images"]) == 1
    doc = json.loads((tmp_path / "o" / "certificate.json").read_text())
    task = doc["tasks"][0]
    assert task["status"] == "failed" and named in task["reason"]
    assert task["reference_joint"]["name"] == DOOR
    assert task["reference_joint"]["type"] == ("prismatic" if case == "type" else "revolute")
    assert task["reference_joint"]["direction"] in (1, -1)
    assert Certificate.from_dict(doc).tasks[0].reference_joint == task["reference_joint"]
