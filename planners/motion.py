"""Dense joint paths: interpolation, whole-path collision checks, and Cartesian tracking by IK.

Cartesian motions (the straight grasp, the opening that follows the estimated articulation, the
retreat) are tracked by solving IK at closely spaced tool poses, each seeded with the previous
solution; between consecutive solutions the joint path is interpolated linearly at
:attr:`PlannerConfig.max_joint_step` and *every* interpolated sample is collision-checked, so a plan
is checked along its whole length, not only at its waypoints.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from planners.config import PlannerConfig
from planners.ik import solve_ik

__all__ = ["densify", "first_invalid", "TrackResult", "track_poses"]


def densify(q: np.ndarray, s: np.ndarray, max_step: float) -> tuple[np.ndarray, np.ndarray]:
    """Linearly interpolate ``q (n, dof)`` and ``s (n,)`` so no joint moves more than ``max_step`` per sample.

    Returns ``(q (m, dof), s (m,))`` including every original sample.
    """
    q = np.asarray(q, float)
    s = np.asarray(s, float)
    if len(q) < 2:
        return q.copy(), s.copy()
    out_q, out_s = [q[:1]], [s[:1]]
    for k in range(1, len(q)):
        n = max(1, int(np.ceil(np.max(np.abs(q[k] - q[k - 1])) / max_step)))
        t = np.arange(1, n + 1) / n
        out_q.append(q[k - 1] + t[:, None] * (q[k] - q[k - 1]))
        out_s.append(s[k - 1] + t * (s[k] - s[k - 1]))
    return np.concatenate(out_q), np.concatenate(out_s)


def first_invalid(world, q: np.ndarray, s: np.ndarray, allow_grasp_contact: bool) -> int:
    """Index of the first sample of ``q (n, dof)`` at task joint values ``s (n,)`` that is out of the robot's
    limits or in collision; -1 when all are valid."""
    for k in range(len(q)):
        if not world.within_limits(q[k]) or world.in_collision(q[k], s[k], allow_grasp_contact):
            return k
    return -1


@dataclass(frozen=True)
class TrackResult:
    """``success``; dense ``q (m, dof)``, ``s (m,)`` up to the last valid sample; ``reason``; the index of
    the failing target (-1 when none)."""

    success: bool
    q: np.ndarray
    s: np.ndarray
    reason: str
    failed_at: int


def track_poses(kin, world, T_targets: np.ndarray, s_values: np.ndarray, q_start: np.ndarray,
                active: np.ndarray, weights: np.ndarray, cfg: PlannerConfig,
                allow_grasp_contact: bool) -> TrackResult:
    """Follow the tool poses ``T_targets (n, 4, 4)`` (task joint at ``s_values (n,)``) from ``q_start (dof,)``.

    ``q_start`` must already be at ``T_targets[0]``. Each target is solved by IK seeded with the previous
    solution (moving only ``active`` columns, weighted by ``weights``); a target that is not reached within
    ``cfg.track_pos_tol``/``cfg.track_rot_tol``, a jump larger than 0.5 rad/m in one step, or a collision
    anywhere on the interpolated path stops the tracking.
    """
    qs = [np.asarray(q_start, float)]
    for k in range(1, len(T_targets)):
        r = solve_ik(kin.tool_pose_jacobian, T_targets[k], qs[-1], world.robot.lower, world.robot.upper,
                     active, weights, pos_tol=cfg.track_pos_tol * 0.3, rot_tol=cfg.track_rot_tol * 0.3,
                     max_iter=60, max_step=0.2)
        if r.pos_error > cfg.track_pos_tol or r.rot_error > cfg.track_rot_tol:
            return _partial(qs, s_values, world, cfg, allow_grasp_contact,
                            f"IK lost the tool path at sample {k}/{len(T_targets) - 1} "
                            f"(error {r.pos_error * 1000:.1f} mm, {np.degrees(r.rot_error):.1f} deg)", k)
        if np.max(np.abs(r.q - qs[-1])) > 0.5:
            return _partial(qs, s_values, world, cfg, allow_grasp_contact,
                            f"IK jumped {np.max(np.abs(r.q - qs[-1])):.2f} rad at sample {k}", k)
        qs.append(r.q)
    q_dense, s_dense = densify(np.array(qs), np.asarray(s_values)[:len(qs)], cfg.max_joint_step)
    bad = first_invalid(world, q_dense, s_dense, allow_grasp_contact)
    if bad >= 0:
        return TrackResult(False, q_dense[:bad], s_dense[:bad],
                           f"collision at task joint value {s_dense[bad]:.3f}", bad)
    return TrackResult(True, q_dense, s_dense, "ok", -1)


def _partial(qs, s_values, world, cfg, allow, reason, k) -> TrackResult:
    q_dense, s_dense = densify(np.array(qs), np.asarray(s_values)[:len(qs)], cfg.max_joint_step)
    return TrackResult(False, q_dense, s_dense, reason, k)
