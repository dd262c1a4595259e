"""The guarded approach of a robust sample: the robot re-perceives the handle once it stands at its stand
pose and corrects the rest of its path for its own base error.

Where this sits: a sampled world (:mod:`simcheck.perturbed_scene`) moves the whole scene by the inverse of
the robot's base error ``T_inv`` (4, 4): the robot stands where it thinks, the scene is elsewhere. A real
mobile manipulator drives to its stand pose, looks at the handle again and finds it where it is relative
to itself, off by a small perception error. It then moves the rest of its path (the grasp, the opening and
everything after it) into the frame it has just localised.

The model (pure numpy, :func:`guarded_plan`):

* the correction ``C = T_inv @ N @ S`` (4, 4, world). ``S`` shifts by the handle's horizontal offset
  from where the scan put it (the sample's ``handle_shift`` x, y): re-perceiving the handle finds it where
  it is. ``N`` is what the re-perception gets wrong -- a turn by ``reperception[2]`` rad about the
  vertical through the handle (the grasp segment's last tool position), then a shift by
  ``(reperception[0], reperception[1])`` m. After the correction the robot stands relative to the scene
  at ``N @ S`` times where the plan put it: the base error and the handle's horizontal offset are gone up
  to the re-perception error.
* the handle's vertical offset (``handle_shift`` z) as re-perceived -- off by the re-perception's vertical
  error ``reperception[3]`` -- is taken up by the arm (a planar base move cannot): with ``kinematics``
  (:class:`planners.pin_world.RobotKinematics`), every configuration from the appended waypoint on is
  re-solved by inverse kinematics (the arm joints after the torso lift, seeded at the planned
  configuration, joint limits kept) so that its tool pose is the planned one raised by that offset; the
  base and the lift keep their planned values. Without ``kinematics`` it stays uncorrected.
* the correction is a rigid transform of the remaining path, executed with physics: one waypoint is
  appended to the approach segment, the approach's last configuration moved by ``C`` (the base drives
  those 1-3 cm, the arm only takes up the vertical offset, gripper open); every later segment's
  configurations are moved by ``C`` (the planar base joints (x, y, yaw), i.e. the arm path rigidly in the
  corrected base frame, then raised as above) and its planned tool poses ``T_world_tool`` by ``C`` and the
  vertical offset. Nothing is teleported.
* what the robot cannot know is not corrected: the opening motion stays the one planned about the
  estimate's joint (hinge line, axis, travel), moved rigidly with the grasp; the sampled world's joint is
  where the scan's uncertainty put it.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from planners.ik import solve_ik
from planners.task import SEGMENT_NAMES, PlanResult
from simcheck.perturbed_scene import base_error_inverse

__all__ = ["correction_transform", "guarded_plan"]

_APPROACH, _GRASP = SEGMENT_NAMES[0], SEGMENT_NAMES[1]


def _planar(yaw: float, xy, about=(0.0, 0.0)) -> np.ndarray:
    """(4, 4) a turn by ``yaw`` rad about the vertical through ``about`` (x, y), then a shift by ``xy`` (m)."""
    c, s = np.cos(yaw), np.sin(yaw)
    R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    p = np.array([float(about[0]), float(about[1]), 0.0])
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p - R @ p + np.array([float(xy[0]), float(xy[1]), 0.0])
    return T


def correction_transform(base_error, reperception, pivot_xy, handle_xy, handle_shift=(0.0, 0.0, 0.0)
                         ) -> np.ndarray:
    """(4, 4) world transform ``C`` the guarded approach applies to the rest of the path (module docstring).

    base_error : (dx m, dy m, dyaw rad) of the sampled world; reperception : (dx m, dy m, dyaw rad), the
    re-perception's error; pivot_xy : (x, y) m where the robot stands (the base error's pivot); handle_xy :
    (x, y) m, world, the handle as planned (the re-perception error's turn is about it); handle_shift :
    (3,) m, world, the handle's true position minus the scan's (its x and y are followed).
    """
    N = _planar(float(reperception[2]), reperception[:2], about=handle_xy)
    return base_error_inverse(base_error, pivot_xy) @ N @ _planar(0.0, handle_shift[:2])


def _moved_base(q: np.ndarray, C: np.ndarray) -> np.ndarray:
    """Copy of ``q`` (n, dof) whose planar base columns (x m, y m, yaw rad: the first three) are moved by the
    planar transform ``C`` (4, 4); the arm columns stay (the arm path moves rigidly with its base)."""
    q = np.array(q, dtype=np.float64)
    xy = q[:, :2] @ C[:2, :2].T + C[:2, 3]
    q[:, 0], q[:, 1] = xy[:, 0], xy[:, 1]
    q[:, 2] += np.arctan2(C[1, 0], C[0, 0])
    return q


def _raised(q: np.ndarray, dz: float, kinematics) -> np.ndarray:
    """Copy of ``q`` (n, dof) whose arm joints after the torso lift are re-solved so that each row's tool pose
    is its own raised by ``dz`` m (world z), orientation kept; base and lift columns unchanged. Each row is
    solved from itself plus the previous row's change (the nearest solution, continuous along the path;
    within the joint limits: where the arm cannot reach, the nearest pose it gets to)."""
    q = np.array(q, dtype=np.float64)
    if dz == 0.0 or kinematics is None:
        return q
    active = np.zeros(q.shape[1], bool)
    active[len(kinematics.spec.base_joints):] = True
    active[kinematics.lift_cols] = False
    change = np.zeros(q.shape[1])
    for i, row in enumerate(q):
        T = kinematics.tool_pose(row)
        T[2, 3] += dz
        seed = np.clip(row + change, kinematics.lower, kinematics.upper)
        q[i] = solve_ik(kinematics.tool_pose_jacobian, T, seed, kinematics.lower, kinematics.upper, active,
                        pos_tol=1e-4, rot_tol=1e-3).q
        change = q[i] - row
    return q


def guarded_plan(plan: PlanResult, base_error, reperception, pivot_xy, handle_shift=(0.0, 0.0, 0.0),
                 kinematics=None) -> PlanResult:
    """``plan`` with the guarded approach's correction (module docstring; arguments as
    :func:`correction_transform`; ``reperception`` may carry a 4th value, its vertical error in m;
    ``kinematics``: the robot's :class:`planners.pin_world.RobotKinematics` on the scene's floor, None: the
    vertical offset is not corrected); the plan itself when it has no approach segment before its grasp
    segment (nothing to correct after) or nothing to correct."""
    names = [s.name for s in plan.segments]
    if _GRASP not in names or names.index(_GRASP) == 0 or names[names.index(_GRASP) - 1] != _APPROACH:
        return plan
    dz = 0.0 if kinematics is None else float(handle_shift[2]) + float((*reperception, 0.0)[3])
    if not any(abs(float(v)) > 0.0 for v in (*base_error, *reperception[:3], *handle_shift[:2], dz)):
        return plan
    k = names.index(_GRASP)
    handle_xy = plan.segments[k].T_world_tool[-1][:2, 3]
    C = correction_transform(base_error, reperception, pivot_xy, handle_xy, handle_shift)
    Cz = C.copy()
    Cz[2, 3] += dz
    a = plan.segments[k - 1]
    approach = dataclasses.replace(
        a, q=np.vstack([a.q, _raised(_moved_base(a.q[-1:], C), dz, kinematics)]),
        object_q=np.append(a.object_q, a.object_q[-1]),
        T_world_tool=np.concatenate([a.T_world_tool, (Cz @ a.T_world_tool[-1])[None]]),
        t=None if a.t is None else np.append(a.t, a.t[-1] + 1.0))
    later = [dataclasses.replace(s, q=_raised(_moved_base(s.q, C), dz, kinematics),
                                 T_world_tool=np.einsum("ij,njk->nik", Cz, s.T_world_tool))
             for s in plan.segments[k:]]
    return dataclasses.replace(plan, segments=(*plan.segments[:k - 1], approach, *later))
