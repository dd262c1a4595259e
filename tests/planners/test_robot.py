"""The default mobile Panda: one URDF for pinocchio and PyBullet, a spec that matches it."""

from __future__ import annotations

import numpy as np
import pybullet as pb
import pytest

from planners import RobotDescriptionError, RobotSpec, default_robot
from planners.pin_world import RobotKinematics


def test_default_robot_urdf_loads_in_pybullet_with_the_spec_joints(robot):
    cid = pb.connect(pb.DIRECT)
    try:
        body = pb.loadURDF(str(robot.urdf), useFixedBase=True, physicsClientId=cid)
        names = {pb.getJointInfo(body, i, physicsClientId=cid)[1].decode()
                 for i in range(pb.getNumJoints(body, physicsClientId=cid))}
    finally:
        pb.disconnect(cid)
    assert set(robot.joint_names) | set(robot.finger_joints) <= names
    assert robot.dof == 11 and robot.joint_names[:3] == ("base_x", "base_y", "base_yaw")


def test_default_robot_is_cached_and_mesh_paths_are_absolute(robot):
    again = default_robot()
    assert again.urdf == robot.urdf
    text = robot.urdf.read_text()
    assert "package://" not in text
    meshes = [m.split('"')[0] for m in text.split('filename="')[1:]]
    assert meshes and all(m.startswith("/") for m in meshes)


def test_tool_frame_lies_between_the_fingertips_and_arm_sits_at_045m(robot):
    kin = RobotKinematics(robot)
    q = robot.home_q
    T_tool = kin.tool_pose(q)
    left = kin.frame_pose(q, "panda_leftfinger")[:3, 3]
    right = kin.frame_pose(q, "panda_rightfinger")[:3, 3]
    # Fingers are symmetric about the tool's z axis; the tool is ~4.6 cm beyond the finger joints.
    mid = (left + right) / 2
    assert np.linalg.norm(np.cross(T_tool[:3, 2], T_tool[:3, 3] - mid)) < 1e-6
    assert 0.04 < (T_tool[:3, 3] - mid) @ T_tool[:3, 2] < 0.06
    assert abs(kin.frame_pose(q, "panda_link0")[2, 3] - 0.45) < 1e-9


def test_spec_naming_a_missing_joint_is_rejected_with_its_name(robot):
    from dataclasses import replace
    bad = replace(robot, arm_joints=robot.arm_joints[:-1] + ("panda_joint_missing",))
    with pytest.raises(RobotDescriptionError, match="panda_joint_missing"):
        RobotKinematics(bad)


def test_spec_home_of_wrong_length_is_rejected(robot):
    with pytest.raises(ValueError, match="home has 3 values"):
        RobotSpec(urdf=robot.urdf, base_joints=robot.base_joints, arm_joints=robot.arm_joints,
                  finger_joints=robot.finger_joints, tool_frame=robot.tool_frame, base_link=robot.base_link,
                  gripper_links=robot.gripper_links, home=(0.0, 0.0, 0.0))
