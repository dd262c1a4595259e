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

__all__ = ["densify", "first_invalid", "TrackResult", "track_poses", "ik_weights"]


def ik_weights(kin, cfg: PlannerConfig, base_weight: float = 1.0) -> np.ndarray:
    """``(dof,)`` IK motion weights: ``base_weight`` for the base joints, ``cfg.lift_weight`` for a torso lift
    (``kin.lift_cols``), 1 for the other arm joints."""
    w = np.ones(kin.spec.dof)
    w[:len(kin.spec.base_joints)] = base_weight
    w[kin.lift_cols] = cfg.lift_weight
    return w


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
                active: np.ndarray, weights: np.ndarray | None, cfg: PlannerConfig,
                allow_grasp_contact: bool) -> TrackResult:
    """Follow the tool poses ``T_targets (n, 4, 4)`` (task joint at ``s_values (n,)``) from ``q_start (dof,)``.

    ``q_start`` must already be at ``T_targets[0]``. Target ``k`` is solved by IK seeded with the solution
    for ``k - 1``; the joint-space segment between them is interpolated at ``cfg.max_joint_step`` and every
    sample must be within the limits, collision-free, and keep the tool within ``cfg.track_pos_tol`` of the
    straight line between the two targets. When the preferred redundancy resolution (``active`` columns,
    ``weights``) fails a step, alternatives are tried in a fixed order: arm only, whole body weighted,
    whole body with equal weights, then seeded restarts near the previous solution. The first step no variant can take stops
    the tracking, and the reason names what collided.
    """
    s_values = np.asarray(s_values, float)
    dof = len(q_start)
    arm = np.zeros(dof, bool)
    arm[3:] = True
    whole = np.ones(dof, bool)
    variants, seen = [], set()
    even = ik_weights(kin, cfg)
    weights = even if weights is None else weights
    for act, w in ((np.asarray(active, bool), weights), (arm, even), (whole, weights), (whole, even)):
        key = (act.tobytes(), np.asarray(w).tobytes())
        if key not in seen:
            seen.add(key)
            variants.append((act, w, 0))
    variants += [(np.asarray(active, bool), weights, r) for r in (1, 2, 3)]
    out_q, out_s = [np.asarray(q_start, float)], [float(s_values[0])]
    q = out_q[0]
    for k in range(1, len(T_targets)):
        first_reason = None
        for act, w, restart in variants:
            seed_q = q
            if restart:
                rng = np.random.default_rng(1000 * k + restart)
                seed_q = np.clip(q + np.where(act, rng.uniform(-0.15, 0.15, dof), 0.0), world.robot.lower,
                                 world.robot.upper)
            r = solve_ik(kin.tool_pose_jacobian, T_targets[k], seed_q, world.robot.lower, world.robot.upper,
                         act, w, pos_tol=cfg.track_pos_tol * 0.3, rot_tol=cfg.track_rot_tol * 0.3,
                         max_iter=60, max_step=0.2)
            why = _step_problem(kin, world, q, r, T_targets[k - 1], T_targets[k], s_values[k - 1], s_values[k],
                                cfg, allow_grasp_contact)
            if why is None:
                break
            first_reason = first_reason or why
        else:
            q_d, s_d = np.array(out_q), np.array(out_s)
            return TrackResult(False, q_d, s_d, f"step {k}/{len(T_targets) - 1}: {first_reason}", k)
        seg_q, seg_s = densify(np.array([q, r.q]), s_values[k - 1:k + 1], cfg.max_joint_step)
        out_q.extend(seg_q[1:])
        out_s.extend(seg_s[1:])
        q = r.q
    return TrackResult(True, np.array(out_q), np.array(out_s), "ok", -1)


def _step_problem(kin, world, q_prev, r, T_prev, T_next, s_prev, s_next, cfg, allow) -> str | None:
    """Why the IK step ``q_prev -> r.q`` cannot be taken (None when it can)."""
    if r.pos_error > cfg.track_pos_tol or r.rot_error > cfg.track_rot_tol:
        return (f"IK lost the tool path (error {r.pos_error * 1000:.1f} mm, "
                f"{np.degrees(r.rot_error):.1f} deg)")
    jump = float(np.max(np.abs(r.q - q_prev)))
    if jump > 0.5:
        return f"IK jumped {jump:.2f} rad"
    seg_q, seg_s = densify(np.array([q_prev, r.q]), np.array([s_prev, s_next]), cfg.max_joint_step)
    for i in range(1, len(seg_q)):
        u = i / (len(seg_q) - 1)
        p_line = (1 - u) * T_prev[:3, 3] + u * T_next[:3, 3]
        dev = float(np.linalg.norm(kin.tool_pose(seg_q[i])[:3, 3] - p_line))
        if dev > cfg.track_pos_tol:
            return f"tool leaves the path by {dev * 1000:.1f} mm between samples"
        if not world.within_limits(seg_q[i]) or world.in_collision(seg_q[i], seg_s[i], allow):
            return _what_collides(world, seg_q[i], seg_s[i], allow) + f" at task joint value {seg_s[i]:.3f}"
    return None


def _what_collides(world, q, s, allow) -> str:
    """Short description of why ``(q, s)`` is invalid, e.g. "collision panda_hand / scene::cabinet1_door2_0"."""
    if not world.within_limits(q):
        return "joint limit"
    pairs = world.colliding_pairs(q, s, allow)
    return "collision " + ", ".join(f"{a} / {b}" for a, b in pairs[:3]) if pairs else "collision"
