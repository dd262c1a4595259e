"""Hand-made plans for the gantry-gripper fixture robot and the fixture cabinet (no planner needed).

The gantry robot's joints are (x, y, z, yaw) of its hand in the world frame; its tool frame sits
0.07 m in front of the hand along the hand's -x axis, between the fingertips.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from planners.task import OpenTask, PlanResult, PlanStatus, Segment
from simcheck.robot_binding import SimRobot

DATA = Path(__file__).parent / "data"
CABINET = DATA / "cabinet.urdf"
CABINET_BLOCKED = DATA / "cabinet_blocked.urdf"
DRAWER = "cabinet1_drawer2_joint"
DOOR = "cabinet1_door4_joint"
TOOL_OFFSET = 0.07

ROBOT = SimRobot(urdf=DATA / "gantry_gripper.urdf", joint_names=("x_joint", "y_joint", "z_joint", "yaw_joint"),
                 finger_joints=("finger_top_joint", "finger_bottom_joint"), finger_open=(0.0, 0.0),
                 finger_closed=(0.04, 0.04), tool_link="tool", gripper_links=("hand", "finger_top", "finger_bottom", "tool"),
                 finger_links=("finger_top", "finger_bottom"), finger_force=40.0)


def _tool_poses(q: np.ndarray) -> np.ndarray:
    """(n, 4, 4) tool poses of the gantry at joint positions (n, 4)."""
    T = np.repeat(np.eye(4)[None], len(q), axis=0)
    c, s = np.cos(q[:, 3]), np.sin(q[:, 3])
    T[:, 0, 0], T[:, 0, 1], T[:, 1, 0], T[:, 1, 1] = c, -s, s, c
    T[:, :3, 3] = q[:, :3] + np.stack([-TOOL_OFFSET * c, -TOOL_OFFSET * s, np.zeros_like(c)], axis=1)
    return T


def _seg(name, q, gripper, object_q):
    """A :class:`planners.Segment`; ``object_q`` one planned drawer/door value for every sample, or (n,)."""
    q = np.atleast_2d(np.asarray(q, dtype=float))
    return Segment(name, q, np.broadcast_to(np.asarray(object_q, float), len(q)), _tool_poses(q), gripper)


def _plan(kind: str, joint: str, amount: float, segments) -> PlanResult:
    return PlanResult(PlanStatus.OK, f"hand-made plan for {joint}", OpenTask(kind, joint, amount), ROBOT.joint_names,
                      tuple(segments), amount=amount)


def line(a, b, n):
    return np.linspace(np.asarray(a, float), np.asarray(b, float), n)


def drawer_plan(amount: float = 0.3, axis_deg: float = 0.0, handle=(0.29, 0.0, 0.68)) -> PlanResult:
    """Pull the fixture drawer by ``amount`` m along +x rotated by ``axis_deg`` about z (0 = correct)."""
    hx, hy, hz = handle
    grasp = np.array([hx + TOOL_OFFSET, hy, hz, 0.0])
    start = grasp + [0.5, 0.0, 0.1, 0.0]
    pre = grasp + [0.12, 0.0, 0.0, 0.0]
    a = np.deg2rad(axis_deg)
    s = np.linspace(0.0, amount, 31)
    opened = grasp[None, :] + np.stack([s * np.cos(a), s * np.sin(a), 0 * s, 0 * s], axis=1)
    back = opened[-1] + [0.12, 0.0, 0.0, 0.0]
    return _plan("drawer", DRAWER, amount, (
        _seg("approach", line(start, pre, 10), "open", 0.0),
        _seg("grasp", line(pre, grasp, 6), "closed", 0.0),
        _seg("open", opened, "closed", s),
        _seg("release", opened[-1:], "open", amount),
        _seg("retreat", line(opened[-1], back, 6), "open", amount)))


def door_plan(amount: float = 1.2, hinge=(0.25, -0.28), radius_xy=(0.06, 0.48), z: float = 0.25,
              sign: float = -1.0) -> PlanResult:
    """Swing the fixture door about a vertical hinge at ``hinge`` (x, y) by ``amount`` rad.

    The handle sits at ``radius_xy`` in the door frame; ``sign`` is the hinge axis z component (-1: the
    fixture door's true axis). The gripper faces the door (yaw follows the door).
    """
    th = np.linspace(0.0, amount, 61)
    px, py = radius_xy
    # the door frame rotates by sign*th about z
    c, s_ = np.cos(sign * th), np.sin(sign * th)
    hx = hinge[0] + c * px - s_ * py
    hy = hinge[1] + s_ * px + c * py
    nx, ny = c, s_                                        # door outward normal (door frame +x)
    yaw = sign * th
    q_open = np.stack([hx + TOOL_OFFSET * nx, hy + TOOL_OFFSET * ny, np.full_like(th, z), yaw], axis=1)
    grasp = q_open[0]
    start = grasp + [0.5, 0.0, 0.1, 0.0]
    pre = grasp + [0.12, 0.0, 0.0, 0.0]
    end = q_open[-1]
    back = end + [0.12 * nx[-1], 0.12 * ny[-1], 0.0, 0.0]
    return _plan("door", DOOR, amount, (
        _seg("approach", line(start, pre, 10), "open", 0.0),
        _seg("grasp", line(pre, grasp, 6), "closed", 0.0),
        _seg("open", q_open, "closed", th),
        _seg("release", q_open[-1:], "open", amount),
        _seg("retreat", line(end, back, 6), "open", amount)))


def fixture_planner(plans: dict):
    """A planner for :func:`simcheck.certify` that returns the hand-made ``plans`` (joint -> PlanResult),
    and NO_PATH for any other joint."""

    def plan(scene_urdf, task, seed, start=None, scene_state=None):
        if task.joint not in plans:
            return PlanResult(PlanStatus.NO_PATH, f"fixture has no plan for {task.joint}", task, ROBOT.joint_names,
                              amount=task.amount or 0.0)
        return plans[task.joint]

    return plan
