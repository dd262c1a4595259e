"""Finish a door's swing by pushing it: the plan a real robot follows when the end of a downward or upward swing is
out of its reach with the handle held (a dishwasher or oven door whose handle ends near the floor facing it, a
lift-up flap whose handle ends overhead facing up).

The grasped opening goes as far as the robot follows the handle; the fingers let go and the hand backs off (the
door's hinge or stay holds it there); the hand moves to the door's inner face -- now facing the robot's side of
the swing -- and pushes the rest of the way with the open fingers' tips, ``PlannerConfig.push_inset`` in from the
free edge, the fingers spread along the hinge and the tool's approach axis into the face; the push segment ends
with the tips backed off the face, and the hand withdraws along that axis. Only a door on a horizontal hinge is
finished this way (its inner face is reachable from above or below once open; a side-hinged door's inner face
turns away from the robot).

The pushing tool poses put the fingertips on the face (:meth:`planners.pin_world.RobotKinematics.gripper_reach`):
the door moves only because the tips press it. The planning world checks each pushing sample with the door
``PlannerConfig.push_lead`` further open, the face just ahead of the tips, so the tips touching the face are not a
collision while everything else of the robot keeps clear of the door and the scene.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from planners.config import PlannerConfig
from planners.handle import HandleGrasp
from planners.ik import solve_ik
from planners.motion import TrackResult, ik_weights, track_poses
from scenes.description import ShapeKind

__all__ = ["PushFrame", "push_frames", "plan_push", "horizontal_hinge"]

#: a hinge counts as horizontal (the door swings up or down) when its axis is within this of level
_HORIZONTAL = math.radians(25.0)


@dataclass(frozen=True)
class PushFrame:
    """Where the fingertips push a door: ``T_link_tool`` (4, 4), the tool frame in the moving link's frame
    (z into the inner face, y along the hinge, origin ``reach`` behind the face); ``lever`` m, the pushed
    point's distance from the hinge line."""

    T_link_tool: np.ndarray
    lever: float


def horizontal_hinge(world, joint: str, s: float) -> bool:
    """Whether scene joint ``joint`` (revolute or continuous), at value ``s``, turns about an axis within 25 deg of
    level on the robot's floor."""
    j = world.scene.joints[joint]
    if j.type == "prismatic":
        return False
    axis = world.robot.in_root(world.moving_link_pose(s))[:3, :3] @ np.asarray(j.axis, dtype=float)
    return abs(float(axis[2])) / float(np.linalg.norm(axis)) < math.sin(_HORIZONTAL)


def push_frames(world, joint: str, handle: HandleGrasp, grasp_index: int, direction: float,
                cfg: PlannerConfig) -> list[PushFrame]:
    """Pushing tool frames on the inner face of the door that ``joint`` turns (``direction`` +1 / -1: the sign of
    the joint's opening motion), at the handle's place along the hinge, ``cfg.push_inset`` in from the free edge:
    the approach axis into the face, then tilted by each of ``cfg.push_tilts`` toward the hinge (the hand beyond
    the free edge, clear of what the door opens); the fingers spread along the hinge. Empty when the door has no
    box, cylinder or sphere geometry to push (a mesh-only part)."""
    scene = world.scene
    j = scene.joints[joint]
    a = np.asarray(j.axis, dtype=float)
    a = a / np.linalg.norm(a)
    p = handle.T_link_grasps[grasp_index][:3, 3]           # the grasp point, moving-link frame (joint frame)
    r = p - (p @ a) * a
    if np.linalg.norm(r) < cfg.min_handle_lever:
        return []
    u = r / np.linalg.norm(r)                               # from the hinge line toward the free edge
    n_out = direction * np.cross(a, u)                      # the way the door's outer face moves when opening
    link = scene.links[handle.moving_link]
    own = {i for (name, i) in handle.handle_geoms if name == handle.moving_link}
    corners = [s.corners() for i, s in enumerate(link.collisions)
               if s is not None and i not in own and s.kind != ShapeKind.MESH]
    if not corners:
        return []
    c = np.concatenate(corners)
    inner = float((c @ n_out).min())                        # the inner face's plane along n_out
    lever = float((c @ u).max()) - cfg.push_inset
    point = lever * u + inner * n_out + (p @ a) * a         # on the inner face
    out = []
    for tilt in cfg.push_tilts:
        z = math.cos(tilt) * n_out - math.sin(tilt) * u
        R = np.column_stack([np.cross(a, z), a, z])
        reach = world.robot.gripper_reach(R.T @ n_out)      # the fingertips' farthest point toward the face
        T = np.eye(4)
        T[:3, :3] = R
        T[:3, 3] = point - reach * n_out
        out.append(PushFrame(T, lever))
    return out


def plan_push(kin, world, frame: PushFrame, s_from: float, s_to: float, q_from: np.ndarray, cfg: PlannerConfig,
              rng, limits: tuple[float, float]):
    """Pre-push configuration, the straight move onto the face and the push from ``s_from`` to ``s_to`` (task joint
    values), starting the IK from ``q_from`` (dof,) (where the robot released the handle): ``(q_pre (dof,),
    line TrackResult, push TrackResult, T_push (m, 4, 4))`` or ``(None, reason)``. ``limits``: the task joint's
    (lower, upper), which the pushing checks' lead stays within."""
    lower, upper = world.robot.lower, world.robot.upper
    step = cfg.open_step_revolute
    sign = 1.0 if s_to >= s_from else -1.0
    n = max(2, int(math.ceil(abs(s_to - s_from) / step)) + 1)
    s_path = np.linspace(s_from, s_to, n)
    lead = cfg.push_lead / max(frame.lever, 1e-3)          # rad: the face ``push_lead`` m ahead of the tips
    s_check = np.clip(s_path + sign * lead, *limits)
    T_push = np.array([world.moving_link_pose(s) @ frame.T_link_tool for s in s_path])
    T_pre = T_push[0].copy()
    T_pre[:3, 3] -= cfg.pregrasp_distance * T_pre[:3, 2]      # backed off along the approach axis
    whole = np.ones(kin.spec.dof, bool)
    weights = ik_weights(kin, cfg, cfg.base_weight)
    world.keep_gripper_clear(True)
    try:
        r = solve_ik(kin.tool_pose_jacobian, T_pre, q_from, lower, upper, whole, weights,
                     pos_tol=cfg.ik_pos_tol, rot_tol=cfg.ik_rot_tol, restarts=cfg.ik_restarts, rng=rng,
                     restart_span=np.full(kin.spec.dof, 0.4),
                     accept=lambda q: not world.in_collision(q, s_from, False))
    finally:
        world.keep_gripper_clear(False)
    if not r.success:
        return None, "no collision-free configuration in front of the door's inner face"
    # the straight move in stops push_lead short of the face; the push touches it and turns the door
    d = cfg.pregrasp_distance - cfg.push_lead
    m = max(2, int(math.ceil(d / 0.01)) + 1)
    T_line = np.array([T_pre] * m)
    T_line[:, :3, 3] = T_pre[:3, 3] + np.linspace(0.0, d, m)[:, None] * T_pre[:3, 2]
    line = track_poses(kin, world, T_line, np.full(m, s_from), r.q, whole, weights, cfg, False)
    if not line.success:
        return None, f"move onto the inner face failed: {line.reason}"
    # ... and ends backing the tips push_lead off the face again: the withdrawal starts clear of it
    T_off = T_push[-1].copy()
    T_off[:3, 3] -= cfg.push_lead * T_off[:3, 2]
    T_push = np.concatenate([T_line[-1:], T_push, T_off[None]])
    s_path = np.concatenate([[s_from], s_path, [s_to]])
    s_check = np.concatenate([[s_check[0]], s_check, [s_check[-1]]])
    push = track_poses(kin, world, T_push, s_check, line.q[-1], whole, weights, cfg, False)
    if not push.success:
        return None, f"push failed at {push.s[-1] - sign * lead:.3f}: {push.reason}"
    # the door's planned values: the checks' values without the lead
    s_door = np.clip(push.s - sign * lead, min(s_from, s_to), max(s_from, s_to))
    push = TrackResult(True, push.q, s_door, push.reason, -1)
    return r.q, line, push, T_push


def held_effort(kin, world, joint: str, q_path: np.ndarray, s_path: np.ndarray, direction: float) -> np.ndarray:
    """(m,) the largest share of its effort limit a robot arm joint needs, statically, to turn the door of
    ``joint`` slowly through the grasped samples ``q_path`` (m, dof) at door values ``s_path`` (m,): the arm's own
    weight plus the force at the tool (no torque: the grasp transmits none) that balances, about the hinge, the
    joint's Coulomb friction and the door's weight (the estimate's ``<dynamics>`` and ``<inertial>``);
    ``direction`` +1 / -1 the sign of the opening motion. The base joints are left out."""
    import pinocchio as pin
    scene = world.scene
    j = scene.joints[joint]
    friction = float(j.dynamics.friction) if j.dynamics is not None else 0.0
    moving = j.child
    T0 = scene.T_world_link(moving, {})
    parts, stack = [moving], [moving]
    while stack:
        for c in scene.child_joints(stack.pop()):
            if c.type == "fixed":
                parts.append(c.child)
                stack.append(c.child)
    masses = [(np.linalg.inv(T0) @ scene.T_world_link(n, {}), scene.links[n].inertial) for n in parts]
    masses = [(T @ m.T_link_com[:, 3], m.mass) for T, m in masses if m is not None and m.mass > 0]
    g = np.array([0.0, 0.0, -9.81])
    model, data = kin.model, kin.data
    cols = np.array([model.joints[model.getJointId(n)].idx_v for n in kin.spec.joint_names])
    limit = np.asarray(model.effortLimit)[cols]
    arm = np.arange(len(kin.spec.base_joints), kin.spec.dof)
    arm = arm[limit[arm] > 0]
    out = np.zeros(len(q_path))
    a_link = np.asarray(j.axis, dtype=float) / np.linalg.norm(j.axis)
    for k, (q, s) in enumerate(zip(q_path, s_path)):
        T = world.moving_link_pose(float(s))
        a = direction * (T[:3, :3] @ a_link)                          # opening sense, world
        h = T[:3, 3]                                                   # on the hinge line (joint frame origin)
        tau_g = sum(float(np.cross((T @ c)[:3] - h, m * g) @ a) for c, m in masses)
        T_tool, J = kin.tool_pose_jacobian(q)
        r = T_tool[:3, 3] - h
        r = r - (r @ a) * a
        lever = float(np.linalg.norm(r))
        force = (friction - tau_g) / max(lever, 1e-3) * np.cross(a, r / max(lever, 1e-9))
        tau = np.asarray(pin.computeGeneralizedGravity(model, data, kin.full_q(q)))[cols] + J[:3].T @ force
        out[k] = float(np.max(np.abs(tau[arm]) / limit[arm]))
    return out
