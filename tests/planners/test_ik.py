"""Damped-least-squares IK: the SO(3) log against scipy, convergence on reachable poses, column selection."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from planners.ik import rotvec_from_matrix, solve_ik
from planners.pin_world import RobotKinematics


@pytest.mark.parametrize("angle", [0.0, 1e-7, 0.4, 2.5, np.pi - 1e-2, np.pi - 1e-6])
def test_rotvec_matches_scipy(angle):
    rng = np.random.default_rng(0)
    for _ in range(20):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        R = Rotation.from_rotvec(axis * angle).as_matrix()
        got = rotvec_from_matrix(R)
        # Same rotation (a half turn is its own sign flip), within 1e-5 rad near pi, 1e-9 elsewhere.
        assert np.allclose(Rotation.from_rotvec(got).as_matrix(), R, atol=1e-5 if angle > 3 else 1e-9)


def test_ik_reaches_poses_of_random_configurations(robot):
    kin = RobotKinematics(robot)
    rng = np.random.default_rng(1)
    ok = 0
    n = 30
    # restarts: the base within 1 m of its seed (a draw over its +-50 m limits is never within an IK's reach)
    span = np.r_[np.full(3, 1.0), kin.upper[3:] - kin.lower[3:]]
    for _ in range(n):
        q_true = rng.uniform(kin.lower, kin.upper)
        q_true[:3] = rng.uniform(-0.5, 0.5, 3)
        T = kin.tool_pose(q_true)
        r = solve_ik(kin.tool_pose_jacobian, T, robot.home_q, kin.lower, kin.upper, restarts=10, rng=rng,
                     restart_span=span)
        if r.success:
            ok += 1
            assert np.allclose(kin.tool_pose(r.q)[:3, 3], T[:3, 3], atol=1e-3)
            assert np.all(r.q >= kin.lower) and np.all(r.q <= kin.upper)
    assert ok >= 0.9 * n


def test_arm_only_ik_keeps_the_base_fixed(robot):
    kin = RobotKinematics(robot)
    q0 = robot.q_with_base(robot.home_q, 0.3, -0.2, 0.5)
    T = kin.tool_pose(q0)
    T[:3, 3] += [0.05, 0.05, -0.1]
    active = np.r_[np.zeros(3, bool), np.ones(robot.dof - 3, bool)]
    r = solve_ik(kin.tool_pose_jacobian, T, q0, kin.lower, kin.upper, active)
    assert r.success
    assert np.array_equal(r.q[:3], q0[:3])


def test_ik_reports_failure_for_an_unreachable_pose(robot):
    kin = RobotKinematics(robot)
    T = kin.tool_pose(robot.home_q)
    T[:3, 3] += [3.0, 0.0, 0.0]
    active = np.r_[np.zeros(3, bool), np.ones(robot.dof - 3, bool)]
    r = solve_ik(kin.tool_pose_jacobian, T, robot.home_q, kin.lower, kin.upper, active, restarts=2,
                 rng=np.random.default_rng(0))
    assert not r.success and r.pos_error > 1.5
