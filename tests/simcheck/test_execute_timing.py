"""How the executor times a planner's segment (simcheck.execute.waypoint_timing, command_trajectory): as fast as
the joints' speed limits allow on a uniform path, and with the tool's speed changing no faster than the segment's
own start ramp where the path hands over from a fast joint to a slow one (no PyBullet)."""

import numpy as np
import pytest

from planners.task import Segment
from simcheck.config import DEFAULT_CRITERIA, DEFAULT_PHYSICS
from simcheck.execute import command_trajectory, timed_waypoints, waypoint_timing

VMAX = np.array([1.0, 0.1])                 # a fast joint (a base, m/s) and a slow one (a torso lift, m/s)


def _segment(q, tool):
    T = np.repeat(np.eye(4)[None], len(q), axis=0)
    T[:, :3, 3] = tool
    return Segment("open", np.asarray(q, float), np.zeros(len(q)), T, "closed")


def _hand_over():
    """20 pieces in which the fast joint carries the tool 2 cm each, then 20 in which the slow joint moves
    2 mm each and the tool 0.5 mm: at full speed the tool goes from 1 m/s to 0.025 m/s at the hand-over."""
    x = np.concatenate([np.linspace(0.0, 0.4, 21), np.full(20, 0.4)])
    y = np.concatenate([np.zeros(21), np.linspace(0.002, 0.04, 20)])
    tool = np.zeros((41, 3))
    tool[:, 0] = np.concatenate([x[:21], 0.4 + np.linspace(0.0005, 0.01, 20)])
    return np.stack([x, y], axis=1), tool


def _largest_tool_acceleration(seg, ramp):
    physics = DEFAULT_PHYSICS.replace(ramp_time=ramp)
    t, _, tool = command_trajectory(seg, VMAX, physics)
    steps = np.arange(0.0, t[-1], physics.time_step)
    pos = np.stack([np.interp(steps, t, tool[:, i]) for i in range(3)], axis=1)
    v = np.diff(pos, axis=0) / physics.time_step
    return float(np.linalg.norm(np.diff(v, axis=0), axis=1).max() / physics.time_step)


def test_a_uniform_straight_path_runs_at_full_speed():
    q = np.stack([np.linspace(0.0, 0.3, 31), np.zeros(31)], axis=1)
    plain = timed_waypoints(q, VMAX, DEFAULT_PHYSICS.time_step)
    times, rho = waypoint_timing(q, VMAX, DEFAULT_PHYSICS.time_step, 0.25, q[:, [0, 1, 1]], 1 / 160)
    assert times == pytest.approx(plain) and times[-1] == pytest.approx(0.3)
    assert rho == pytest.approx(0.5)


def test_the_tool_slows_down_before_a_hand_over_instead_of_stopping_in_one_step():
    q, tool = _hand_over()
    seg = _segment(q, tool)
    ramp = DEFAULT_PHYSICS.ramp_time
    bound = 1.0 / ramp                                   # the tool's full speed (1 m/s) per ramp time
    assert _largest_tool_acceleration(seg, 0.0) > 20 * bound     # unramped: 1 m/s to 0.025 m/s in one step
    assert _largest_tool_acceleration(seg, ramp) <= 2 * bound           # a turn and a ramp in one step
    times, rho = waypoint_timing(q, VMAX, DEFAULT_PHYSICS.time_step, ramp, tool, DEFAULT_PHYSICS.time_step)
    plain = timed_waypoints(q, VMAX, DEFAULT_PHYSICS.time_step)
    assert times[-1] > plain[-1]                         # the slow-down costs time ...
    assert times[-1] < plain[-1] + 2 * ramp              # ... about one ramp
    assert (rho[:20] >= 0.5 - 1e-12).all() and (rho[:20] > 0.5).any()    # decelerating into the hand-over


def test_the_approach_runs_faster_with_the_same_accelerations():
    """The approach's top speed is approach_speed_scale x higher, its ramps as much longer: on a path with a turn
    the largest joint acceleration of its commanded trajectory stays what the ordinary timing commands."""
    from simcheck.execute import segment_timing
    vmax = np.array([0.5, 0.8])
    physics = DEFAULT_PHYSICS
    k = physics.approach_speed_scale
    assert k > 1.0
    v, p = segment_timing("grasp", vmax, physics)
    assert np.allclose(v, vmax) and p is physics
    v, p = segment_timing("open", vmax, physics)
    assert np.allclose(v, vmax * physics.open_speed_scale) and p is physics
    v, p = segment_timing("approach", vmax, physics)
    assert np.allclose(v, vmax * k) and p.ramp_time == pytest.approx(physics.ramp_time * k)
    q = np.concatenate([np.stack([np.linspace(0, 1.0, 21), np.zeros(21)], 1),
                        np.stack([np.full(20, 1.0), np.linspace(0.05, 1.0, 20)], 1)])    # an L: one joint, the other
    seg = Segment("approach", q, np.zeros(len(q)), np.repeat(np.eye(4)[None], len(q), axis=0), "open")

    def peak_acceleration(v, p):      # as simcheck's given-plan criterion reads it (plan_timing, 0.1 s window)
        t, qq, _ = command_trajectory(seg, v, p)
        w = DEFAULT_CRITERIA.acceleration_window
        x = np.arange(-w, t[-1] + w, p.time_step)

        def at(y):
            return np.stack([np.interp(y, t, qq[:, j]) for j in range(2)], axis=1)

        return np.abs(at(x + w) - 2 * at(x) + at(x - w)).max() / w ** 2, t[-1]

    a_fast, t_fast = peak_acceleration(*segment_timing("approach", vmax, physics))
    a_slow, t_slow = peak_acceleration(vmax, physics)
    assert a_fast <= a_slow * 1.05 and t_fast < 0.8 * t_slow   # 1.05: the window spans more of the faster path
