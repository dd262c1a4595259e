"""Hand-built rollouts for the pure criterion tests: a clean drawer pull, then one fault at a time."""

from __future__ import annotations

import dataclasses

import numpy as np

from simcheck.rollout import Rollout

SEGMENTS = ("approach", "grasp", "open", "release", "retreat")


def good_rollout(amount: float = 0.3, n_per_segment: int = 20, seed: int = 0) -> Rollout:
    """A drawer opened by ``amount`` along +x, the handle exactly on the plan, settled at the end.

    Samples: n_per_segment per segment, then n_per_segment settling samples (segment -1), at 60 Hz.
    Small seeded noise (< 1 mm) on the measured positions."""
    rng = np.random.default_rng(seed)
    k = n_per_segment
    segment = np.repeat(np.array([0, 1, 2, 3, 4, -1]), k)
    n = len(segment)
    t = np.arange(n) / 60.0
    s = np.zeros(n)
    s[2 * k:3 * k] = np.linspace(0.0, amount, k)
    s[3 * k:] = amount
    handle0 = np.array([1.0, 0.0, 0.8])
    T = np.repeat(np.eye(4)[None], n, axis=0)
    T[:, :3, 3] = handle0 + np.outer(s, [1.0, 0.0, 0.0])
    grasped = (segment == 2) | (np.arange(n) == 2 * k - 1)
    grasp_point = np.full((n, 3), np.nan)
    grasp_point[grasped] = T[grasped, :3, 3] + rng.normal(0, 2e-4, (grasped.sum(), 3))
    tool = T[:, :3, 3] + rng.normal(0, 2e-4, (n, 3))
    planned = np.full((n, 3), np.nan)
    planned[segment == 2] = T[segment == 2, :3, 3]
    qd = np.gradient(s, t)
    dof = 4
    robot_q = np.zeros((n, dof)) + 0.1
    return Rollout(
        joint="cabinet1_drawer2_joint", moving_link="cabinet1_drawer2", handle_link="cabinet1_handle3",
        robot_joint_names=("x", "y", "z", "yaw"), segment_names=SEGMENTS, gripper_links=("hand", "finger_a", "finger_b"),
        requested_amount=amount, object_q0=0.0, grasp_note="", time_step=1 / 240,
        t=t, segment=segment, robot_q=robot_q, robot_lower=-np.ones(dof), robot_upper=np.ones(dof),
        object_q=s, object_qd=qd, T_world_handle=T, tool_pos=tool, grasp_point=grasp_point, planned_tool_pos=planned,
        planned_object_q=np.where(segment == 2, s, np.nan), link_speed=np.abs(qd), link_angular_speed=np.zeros(n),
        grasp_active=grasped, grasp_force=np.where(grasped, 20.0, 0.0), finger_q=np.zeros((n, 2)),
        finger_contacts=np.where(grasped, 2, 0),
        contact_sample=np.array([2 * k + 3, 2 * k + 4]), contact_robot_link=np.array(["finger_a", "finger_b"]),
        contact_scene_link=np.array(["cabinet1_handle3", "cabinet1_handle3"]), contact_force=np.array([40.0, 40.0]),
        contact_depth=np.array([0.001, 0.001]), object_contact_sample=np.zeros(0, int),
        object_contact_link=np.zeros(0, str), object_contact_force=np.zeros(0), wall_time=0.5,
        grasp_turn=np.zeros(n), holding_force=112.0, robot_q_target=robot_q.copy(),
        finger_links=("finger_a", "finger_b"))


def with_(r: Rollout, **changes) -> Rollout:
    """A copy of ``r`` with ``changes``."""
    return dataclasses.replace(r, **changes)
