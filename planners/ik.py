"""Inverse kinematics by damped least squares with selectable columns and seeded restarts (pure numpy).

The kinematics enter as a callable ``pose_jacobian(q) -> (T_world_tool (4, 4), J (6, dof))`` with ``J``
world-aligned at the tool origin (rows: linear velocity, angular velocity), e.g.
:meth:`planners.pin_world.RobotKinematics.tool_pose_jacobian`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from scenes.small_linalg import solve

__all__ = ["IKResult", "pose_error", "rotvec_from_matrix", "solve_ik"]


@dataclass(frozen=True)
class IKResult:
    """``success``; ``q (dof,)`` the best configuration found; its errors (m, rad); iterations used."""

    success: bool
    q: np.ndarray
    pos_error: float
    rot_error: float
    iterations: int


def pose_error(T: np.ndarray, T_target: np.ndarray) -> np.ndarray:
    """``(6,)`` error (world frame): target minus current position, then the rotation vector of R_t R^T."""
    e = np.empty(6)
    e[:3] = T_target[:3, 3] - T[:3, 3]
    e[3:] = _rotvec(T_target[:3, :3] @ T[:3, :3].T)
    return e


def rotvec_from_matrix(R: np.ndarray) -> np.ndarray:
    """``(3,)`` rotation vector (axis * angle, rad) of the rotation matrix ``R (3, 3)`` (the SO(3) log).

    Written out because scipy's ``Rotation.from_matrix`` costs ~100 us a call, more than an IK iteration.
    """
    return np.array(_rotvec(R), dtype=float)


def _rotvec(R: np.ndarray):
    """:func:`rotvec_from_matrix` as a tuple of 3 floats (an array near a half turn), the IK's inner loop: the
    entries are read once as Python floats (each the same IEEE operation as on numpy scalars, so the result is
    the same to the bit, at a third of the cost)."""
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = R.tolist()
    wx, wy, wz = r21 - r12, r02 - r20, r10 - r01
    c = min(1.0, max(-1.0, (r00 + r11 + r22 - 1.0) / 2.0))
    angle = float(np.arccos(c))
    if angle < 1e-6:
        return 0.5 * wx, 0.5 * wy, 0.5 * wz
    if angle < np.pi - 1e-3:
        f = angle / (2.0 * np.sin(angle))
        return f * wx, f * wy, f * wz
    # Near a half turn: the axis is the dominant column of (R + I) / 2 (its sign from w).
    w = np.array([wx, wy, wz])
    B = (R + np.eye(3)) / 2.0
    k = int(np.argmax(np.diag(B)))
    axis = B[:, k] / np.sqrt(max(B[k, k], 1e-12))
    axis /= np.linalg.norm(axis)
    if axis @ w < 0:
        axis = -axis
    return angle * axis


def solve_ik(pose_jacobian, T_target: np.ndarray, q_seed: np.ndarray, lower: np.ndarray, upper: np.ndarray,
             active: np.ndarray | None = None, weights: np.ndarray | None = None, *, pos_tol: float = 1e-3,
             rot_tol: float = 1e-2, damping: float = 0.05, max_iter: int = 80, max_step: float = 0.3,
             restarts: int = 0, rng: np.random.Generator | None = None, restart_span: np.ndarray | None = None,
             accept=None, position_only: bool = False) -> IKResult:
    """Move the tool to ``T_target (4, 4)`` starting from ``q_seed (dof,)``.

    Args:
        active ((dof,) bool): Columns that may move (default all); inactive joints keep their seed value.
        weights ((dof,) float): Per-joint motion weights (larger moves more; e.g. small on the base to prefer arm
            motion).
        restarts (int): Extra attempts from seeds drawn uniformly within the limits (active columns only; with
            ``restart_span`` (dof,) the draw is ``q_seed +- span`` clipped to the limits instead).
        accept (callable ``q -> bool`` or None): Extra test a converged solution must pass (e.g. collision-free);
            otherwise the next restart runs.
        position_only (bool): Move the tool origin to the target's position, whatever the orientation
            (``rot_error`` is still reported); out of reach, the result is the nearest position the iteration got to.
    """
    dof = len(q_seed)
    act = np.ones(dof, bool) if active is None else np.asarray(active, bool)
    w = np.ones(dof) if weights is None else np.asarray(weights, float)
    w = np.where(act, w, 0.0)
    best = None
    for attempt in range(restarts + 1):
        if attempt == 0:
            q = np.array(q_seed, dtype=float)
        else:
            if rng is None:
                rng = np.random.default_rng(0)
            if restart_span is None:
                draw = rng.uniform(lower, upper)
            else:
                draw = np.clip(q_seed + rng.uniform(-1, 1, dof) * restart_span, lower, upper)
            q = np.where(act, draw, q_seed)
        res = _dls(pose_jacobian, T_target, q, lower, upper, w, pos_tol, rot_tol, damping, max_iter, max_step,
                   position_only)
        if res.success and (accept is None or accept(res.q)):
            return res
        if best is None or res.pos_error + 0.1 * res.rot_error < best.pos_error + 0.1 * best.rot_error:
            best = IKResult(False, res.q, res.pos_error, res.rot_error, res.iterations)
    return best


_clip = getattr(getattr(np, "_core", None), "umath", np).clip     # the ufunc np.clip and ndarray.clip call


def _norm(v: np.ndarray) -> float:
    """``np.linalg.norm(v)`` of a 1-D float array (the same ``sqrt(v . v)``) without its argument checks,
    which cost more than the arithmetic in the IK loop."""
    return math.sqrt(v.dot(v))


def _dls_step(J: np.ndarray, e: np.ndarray, W: np.ndarray, damp: np.ndarray) -> np.ndarray:
    """Damped least-squares joint step ``(dof,)`` for the task error ``e`` with the columns of ``J`` scaled by
    ``W`` (the square roots of the joint weights)."""
    Jw = J * W
    return W * (Jw.T @ solve(Jw @ Jw.T + damp, e))


def _dls(pose_jacobian, T_target, q, lower, upper, w, pos_tol, rot_tol, damping, max_iter, max_step,
         position_only=False) -> IKResult:
    W = np.sqrt(w)
    lo, hi = (np.broadcast_to(np.asarray(b, dtype=float), np.shape(q)).tolist() for b in (lower, upper))
    rows = 3 if position_only else 6
    damp = damping ** 2 * np.eye(rows)
    if position_only:
        rot_tol = np.inf
    history = []
    for it in range(1, max_iter + 1):
        T, J = pose_jacobian(q)
        e = pose_error(T, T_target)
        pe, re = _norm(e[:3]), _norm(e[3:])
        if pe < pos_tol and re < rot_tol:
            return IKResult(True, q, pe, re, it)
        history.append(pe + (0.0 if position_only else 0.1 * re))
        if it > 20 and history[-1] > 0.97 * history[-11]:   # stalled (a limit or out of reach): give up early
            return IKResult(False, q, pe, re, it)
        if position_only:
            J, e = J[:3], e[:3]
        dq = _dls_step(J, e, W, damp)
        # a joint at a limit that the step pushes further out takes no part in the step (otherwise clipping
        # it bends the step away from the target and the iteration stalls); the test on Python floats
        qs = q.tolist()
        if any(v <= b for v, b in zip(qs, lo)) or any(v >= b for v, b in zip(qs, hi)):
            pinned = ((q <= lower) & (dq < 0)) | ((q >= upper) & (dq > 0))
            if pinned.any():
                dq = _dls_step(J, e, np.where(pinned, 0.0, W), damp)
        n = float(np.abs(dq).max())
        if n > max_step:
            dq *= max_step / n
        q = _clip(q + dq, lower, upper)     # np.clip's ufunc, without the method's dispatch overhead
    T, _ = pose_jacobian(q)
    e = pose_error(T, T_target)
    pe, re = float(np.linalg.norm(e[:3])), float(np.linalg.norm(e[3:]))
    return IKResult(pe < pos_tol and re < rot_tol, q, pe, re, max_iter)
