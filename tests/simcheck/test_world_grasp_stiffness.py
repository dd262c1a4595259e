"""The grasp spring of the default robot is the Panda's Cartesian stiffness under its joint impedance:
``World.tool_stiffness`` (PyBullet's Jacobian) agrees with the same stiffness from pinocchio's Jacobian."""

import numpy as np
import pinocchio as pin
import pytest

import planners
from simcheck.robot_binding import sim_robot_from_spec
from simcheck.world import World

from simcheck_fixture_plans import CABINET


def test_tool_stiffness_is_the_joint_impedance_seen_at_the_tool():
    spec = planners.default_robot()
    robot = sim_robot_from_spec(spec)
    arm_q = np.array([0.2, 0.4, -0.1, -1.9, 0.3, 1.8, 0.6])                    # the Panda's 7 joints
    q = np.concatenate([[0.3, -0.2, 0.4], [0.1] * (spec.dof - 10), arm_q])     # base x, y, yaw (+ a lift)
    with World(CABINET, robot) as w:
        w.reset_robot(q)
        K = w.tool_stiffness(dict(robot.joint_stiffness))
    model = pin.buildModelFromUrdf(str(spec.urdf))
    data = model.createData()
    qp = pin.neutral(model)
    for name, value in zip(spec.joint_names, q):
        qp[model.joints[model.getJointId(name)].idx_q] = value
    pin.computeJointJacobians(model, data, qp)
    pin.updateFramePlacements(model, data)
    cols = [model.joints[model.getJointId(n)].idx_v for n in spec.arm_joints]
    J = pin.getFrameJacobian(model, data, model.getFrameId(spec.tool_frame), pin.LOCAL_WORLD_ALIGNED)[:3, cols]
    expected = np.linalg.inv(J @ np.diag(1.0 / np.array(spec.joint_stiffness)) @ J.T)
    assert K == pytest.approx(expected, rel=1e-6, abs=1e-3)
    assert np.allclose(K, K.T, atol=1e-3) and np.linalg.eigvalsh(K).min() > 1000.0       # N/m
