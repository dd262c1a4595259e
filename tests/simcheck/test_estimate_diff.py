"""A failed certificate --against a reference says how the estimated joint differs from it: the
differences a grasp can feel are named, those within the tolerances are not."""

from __future__ import annotations

import numpy as np
import pytest

from simcheck.estimate_diff import joint_differences, measured_differences, path_mismatch
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


def test_measured_differences_name_a_hinge_offset_within_the_tolerance_and_its_path_error():
    """A force criterion failed: the hinge offset is named in mm even under the 1 cm tolerance, split along the
    door (toward the grasped point) and along its front normal, with the planned path's error it makes."""
    handle = np.array([0.0, 0.5, 0.0])                      # the door spans +y from the hinge; it opens about +z
    est = _door(origin=(0.006, -0.004, 0.0))                # 4 mm toward the hinge side, 6 mm along -x
    says = measured_differences(est, REF, handle, np.pi / 2)
    assert joint_differences(est, REF) == []
    # opening about +z, the handle at +y starts moving along -x: the front normal is -x
    assert "hinge 7 mm off (-4 mm along the door toward the handle, -6 mm along its front normal)" in says
    assert "axis 0.0 deg off" in says and "opening range 1.600 vs 1.600 rad" in says
    assert "up to 10 mm off the reference's path" in says  # 2 sin(45 deg) x 7.2 mm
    assert measured_differences(_door(type_="prismatic"), REF, handle, 1.0) == ""


@pytest.mark.parametrize("est, amount, expected", [
    (_door(origin=(0.009, 0.0, 0.0)), 1.2, 2 * np.sin(0.6) * 0.009),        # a hinge moved by d: |(I - R) d|
    (_door(origin=(0.009, 0.0, 0.0)), 4.0, 2 * 0.009),                      # past half a turn: at most 2 d
    (_door(), 1.5, 0.0),
])
def test_path_mismatch_of_a_moved_hinge(est, amount, expected):
    assert path_mismatch(est, REF, np.array([0.0, 0.5, 0.0]), amount) == pytest.approx(expected, rel=1e-3, abs=1e-9)


def test_path_mismatch_of_a_tilted_drawer_axis():
    drawer = lambda deg: SceneJoint("d", "prismatic", "b", "d", 0.0, 0.4, np.array([np.cos(np.radians(deg)),
                                                                                     np.sin(np.radians(deg)), 0.0]),
                                     np.zeros(3))
    assert path_mismatch(drawer(3.0), drawer(0.0), np.zeros(3), 0.4) == pytest.approx(0.4 * 2 * np.sin(np.radians(1.5)))
