"""A failed certificate --against a reference says how the estimated joint differs from it: the
differences a grasp can feel are named, those within the tolerances are not."""

from __future__ import annotations

import numpy as np
import pytest

from simcheck.estimate_diff import joint_differences
from simcheck.scene_joints import SceneJoint


def _door(origin=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0), upper=1.6, type_="revolute") -> SceneJoint:
    a = np.asarray(axis, float)
    return SceneJoint("fridge_door_joint", type_, "body", "door", 0.0, upper, a / np.linalg.norm(a),
                      np.asarray(origin, float))


REF = _door()


@pytest.mark.parametrize("est, says", [
    (_door(origin=(0.016, 0.0, 0.0)), "hinge of fridge_door_joint is 0.016 m from the reference hinge"),
    (_door(origin=(0.0, 0.0, 0.3)), None),                         # slid along its own axis: same hinge line
    (_door(origin=(0.005, 0.0, 0.0)), None),                       # within 1 cm
    (_door(axis=(np.sin(np.radians(3)), 0.0, np.cos(np.radians(3)))), "3 deg off the reference axis"),
    (_door(axis=(np.sin(np.radians(1)), 0.0, np.cos(np.radians(1)))), None),
    (_door(origin=(0.5, 0.0, 0.0)), "(hinged on the wrong side)"),
    (_door(upper=1.8), "exceeds the reference's"),
    (_door(type_="prismatic"), "is prismatic in the estimate but revolute in the reference"),
])
def test_differences_are_named_beyond_their_tolerance(est, says):
    hints = joint_differences(est, REF)
    if says is None:
        assert hints == []
    else:
        assert any(says in h for h in hints), hints


def test_a_joint_missing_from_the_reference_is_named():
    assert joint_differences(REF, None) == ["the reference has no joint 'fridge_door_joint'"]


def test_a_reference_with_the_other_sign_convention_or_a_continuous_hinge_differs_in_nothing():
    """Issue 11: a reference whose door opens toward negative values about the flipped axis, or turns on a
    continuous joint, describes the same motion as the estimate: no difference is named."""
    flipped = SceneJoint("fridge_door_joint", "revolute", "body", "door", -1.6, 0.0, np.array([0.0, 0.0, -1.0]),
                         np.zeros(3))
    assert joint_differences(_door(), flipped) == []
    assert joint_differences(_door(), _door(type_="continuous", upper=0.0)) == []
    wider = SceneJoint("fridge_door_joint", "revolute", "body", "door", -1.2, 0.0, np.array([0.0, 0.0, -1.0]),
                       np.zeros(3))
    assert joint_differences(_door(), wider) == [
        "the estimated opening range of fridge_door_joint (1.600 rad) exceeds the reference's (1.200 rad)"]
    assert "180 deg off" in joint_differences(_door(), _door(axis=(0.0, 0.0, -1.0)))[0]   # same sign: opposite
