"""simcheck/plan_timing.py: a given plan's timing judged without PyBullet -- each criterion passes on a plan the
robot can follow and fails, naming the segment, the time and the joint, on one built to fail it."""

import re

import numpy as np
import pytest

from planners.task import Segment
from simcheck.config import DEFAULT_CRITERIA
from simcheck.plan_timing import joint_acceleration, joint_speed, timing_criteria, waypoint_gap

NAMES = ("x", "y")
VMAX = np.array([1.0, 1.0])
AMAX = np.array([4.0, 4.0])


def _seg(name, q, t):
    q = np.asarray(q, dtype=float)
    return Segment(name, q, np.zeros(len(q)), np.full((len(q), 4, 4), np.nan), "open", t=np.asarray(t, float),
                   command="hold")


def _ramp(name, start, end, duration=2.0, n=81):
    """x from ``start`` to ``end`` with a smooth (cosine) speed profile: at rest at both ends."""
    u = (1 - np.cos(np.linspace(0, np.pi, n))) / 2
    q = np.stack([start + (end - start) * u, np.zeros(n)], axis=1)
    return _seg(name, q, np.linspace(0, duration, n))


def test_a_smooth_plan_passes_every_timing_criterion():
    segs = [_ramp("reach", 0.0, 0.5), _ramp("pull", 0.5, 0.2)]
    results = timing_criteria(segs, NAMES, VMAX, AMAX)
    assert [r.name for r in results] == ["waypoint_gap", "joint_speed", "joint_acceleration"]
    assert all(r.passed for r in results), results
    # peak speed of the cosine profile: pi/2 * 0.5 m / 2 s = 0.39 m/s
    assert results[1].value == pytest.approx(np.pi / 2 * 0.5 / 2.0, rel=0.01)


def test_waypoints_too_far_apart_fail_naming_segment_time_and_joint():
    seg = _seg("pull", [[0.0, 0.0], [0.05, 0.0], [0.3, 0.0]], [0.0, 0.5, 1.5])
    r = waypoint_gap([_ramp("reach", 0.2, 0.0), seg], NAMES, units={"x": "m"})
    assert not r.passed and r.value == pytest.approx(0.25) and r.unit == "m"      # the worst joint's unit
    assert "segment 'pull': joint x steps 0.250 m between waypoints 1 and 2, t=0.500-1.500 s" in r.detail


def test_too_fast_fails_naming_segment_time_and_joint():
    fast = _ramp("pull", 0.0, 0.5, duration=0.5)
    r = joint_speed([fast], NAMES, VMAX)
    assert not r.passed and r.value == pytest.approx(np.pi / 2 * 0.5 / 0.5, rel=0.01)
    assert "segment 'pull': joint x at" in r.detail and "limit 1" in r.detail


def test_a_jump_between_segments_is_infinitely_fast():
    r = joint_speed([_ramp("reach", 0.0, 0.5), _ramp("pull", 0.6, 0.2)], NAMES, VMAX)
    assert not r.passed and np.isinf(r.value)
    assert "segment 'pull' starts 0.100 away from where the previous one ended (joint x)" in r.detail
    assert not waypoint_gap([_ramp("reach", 0.0, 0.5), _ramp("pull", 0.9, 0.2)], NAMES).passed


def test_starting_at_full_speed_is_too_hard_an_acceleration():
    # constant 0.8 m/s from rest and back to rest: the velocity step is spread over the 0.1 s window -> 8 m/s^2 > 4
    seg = _seg("reach", np.stack([np.linspace(0, 0.8, 11), np.zeros(11)], axis=1), np.linspace(0, 1.0, 11))
    r = joint_acceleration([seg], NAMES, AMAX)
    assert not r.passed
    assert r.value == pytest.approx(0.8 / DEFAULT_CRITERIA.acceleration_window / 4.0, rel=1e-6)
    assert re.search(r"segment 'reach': joint x accelerates at 8.00 near t=(0.00|1.00) s, limit 4", r.detail)   # start or stop
    assert joint_acceleration([seg], NAMES, ()).passed        # a robot spec without limits: not judged
