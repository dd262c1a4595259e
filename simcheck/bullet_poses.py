"""Poses between PyBullet's (position, quaternion (x, y, z, w)) and ``T`` (4, 4) float64 (pure: no simulator)."""

from __future__ import annotations

import numpy as np

__all__ = ["T_from_pos_quat", "R_rows_from_quat", "quat_xyzw_from_R"]


def R_rows_from_quat(quat_xyzw) -> list[list[float]]:
    """The rotation matrix (3, 3) of a unit quaternion (x, y, z, w) (PyBullet's order), as three rows of
    Python floats (plain arithmetic: called several times per physics step, where numpy's per-call overhead
    would dominate)."""
    x, y, z, w = quat_xyzw
    xx, yy, zz, xy, xz, yz, wx, wy, wz = x * x, y * y, z * z, x * y, x * z, y * z, w * x, w * y, w * z
    return [[1 - 2 * (yy + zz), 2 * (xy - wz), 2 * (xz + wy)],
            [2 * (xy + wz), 1 - 2 * (xx + zz), 2 * (yz - wx)],
            [2 * (xz - wy), 2 * (yz + wx), 1 - 2 * (xx + yy)]]


def T_from_pos_quat(pos, quat_xyzw) -> np.ndarray:
    """(4, 4) transform from a position (3,) and a unit quaternion (x, y, z, w) (PyBullet's order)
    (:func:`R_rows_from_quat`)."""
    r0, r1, r2 = R_rows_from_quat(quat_xyzw)
    return np.array([[*r0, pos[0]], [*r1, pos[1]], [*r2, pos[2]], [0.0, 0.0, 0.0, 1.0]])


def quat_xyzw_from_R(R: np.ndarray) -> tuple[float, float, float, float]:
    """The unit quaternion (x, y, z, w) of rotation ``R`` (3, 3)."""
    from scipy.spatial.transform import Rotation
    x, y, z, w = Rotation.from_matrix(np.asarray(R, dtype=float)).as_quat()
    return float(x), float(y), float(z), float(w)
