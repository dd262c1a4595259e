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
    return wrong.shift_hinge(CAB, DOOR, tmp_path / "shifted.urdf", sideways=0.04), CAB


@pytest.mark.parametrize("case, named", [
    ("type", f"joint {DOOR} is revolute in the estimate but prismatic in the reference"),
    ("range", f"the estimated upper limit of {DOOR} (1.900 rad) exceeds the reference's (0.950 rad)"),
    ("hinge", f"the estimated hinge of {DOOR} is 0.040 m from the reference hinge"),
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


DRAWER = "cabinet1_drawer12_joint"


def _negative_opening(tmp_path):
    """The fixture cabinet as a file with the other sign convention: the door's and the drawer's axes
    flipped and their ranges negative ([-1.9, 0] rad, [-0.35, 0] m); the geometry is where it was."""
    text = CAB.read_text()
    for joint, axis, new_axis, limit, new_limit in [
            (DOOR, 'xyz="0 0 -1"', 'xyz="0 0 1"', 'lower="0.0" upper="1.9"', 'lower="-1.9" upper="0.0"'),
            (DRAWER, 'xyz="1 0 0"', 'xyz="-1 0 0"', 'lower="0.0" upper="0.35"', 'lower="-0.35" upper="0.0"')]:
        head, rest = text.split(f'<joint name="{joint}"', 1)
        block, tail = rest.split("</joint>", 1)
        assert axis in block and limit in block
        text = head + f'<joint name="{joint}"' + block.replace(axis, new_axis).replace(limit, new_limit) + "</joint>" + tail
    out = tmp_path / "negative.urdf"
    out.write_text(text)
    return out


@pytest.mark.parametrize("task, unit", [(f"open-door:{DOOR}", "rad"), (f"open-drawer:{DRAWER}", "m")])
def test_a_joint_that_opens_toward_negative_values_is_certified_on_its_own_urdf(task, unit, tmp_path):
    neg = _negative_opening(tmp_path)
    assert main(["certify", str(neg), "--task", task, "--out", str(tmp_path / "o"), "--no-images"]) == 0
    t = json.loads((tmp_path / "o" / "certificate.json").read_text())["tasks"][0]
    assert t["status"] == "certified" and t["amount"] < 0 and t["unit"] == unit     # opened toward the lower limit


def test_a_reference_with_the_opposite_sign_convention_is_matched_by_direction(tmp_path):
    neg = _negative_opening(tmp_path)
    assert main(["certify", str(CAB), "--task", f"open-door:{DOOR}", "--against", str(neg),
                 "--out", str(tmp_path / "o"), "--no-images"]) == 0
    t = json.loads((tmp_path / "o" / "certificate.json").read_text())["tasks"][0]
    assert t["status"] == "certified" and t["amount"] > 0
    assert t["reference_joint"] == {"name": DOOR, "type": "revolute", "direction": -1, "lower": -1.9, "upper": 0.0}


def test_a_negative_request_is_judged_by_the_joint_value_moving_that_way():
    """Without a planned opening axis (``--robust`` samples), the joint's signed change is judged against
    the signed request: a drawer asked to open by -0.3 m that moved -0.3 m opened all of it."""
    from simcheck.criteria import opened_fraction, opened_overshoot
    from simcheck_rollout_factory import good_rollout
    r = good_rollout(amount=-0.3)
    assert opened_fraction(r).passed and opened_fraction(r).value == pytest.approx(1.0)
    assert opened_overshoot(r).passed


def test_an_explicit_negative_amount_opens_toward_the_lower_limit(tmp_path):
    neg = _negative_opening(tmp_path)
    assert main(["certify", str(neg), "--task", f"open-drawer:{DRAWER}=-0.2", "--out", str(tmp_path / "o"),
                 "--no-images"]) == 0
    t = json.loads((tmp_path / "o" / "certificate.json").read_text())["tasks"][0]
    assert t["status"] == "certified" and t["amount"] == pytest.approx(-0.2)
    assert main(["certify", str(neg), "--task", f"open-drawer:{DRAWER}=0.2", "--out", str(tmp_path / "p"),
                 "--no-images"]) == 2                          # +0.2 leaves the limits [-0.35, 0]
