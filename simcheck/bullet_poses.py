"""Poses between PyBullet's (position, quaternion (x, y, z, w)) and ``T`` (4, 4) float64 (pure: no simulator)."""

from __future__ import annotations

import numpy as np

__all__ = ["T_from_pos_quat", "quat_xyzw_from_R"]


def T_from_pos_quat(pos, quat_xyzw) -> np.ndarray:
    """(4, 4) transform from a position (3,) and a unit quaternion (x, y, z, w) (PyBullet's order).

    Plain Python arithmetic: called several times per physics step, where numpy's per-call overhead
    would dominate a 3x3 product."""
    x, y, z, w = quat_xyzw
    xx, yy, zz, xy, xz, yz, wx, wy, wz = x * x, y * y, z * z, x * y, x * z, y * z, w * x, w * y, w * z
    return np.array([[1 - 2 * (yy + zz), 2 * (xy - wz), 2 * (xz + wy), pos[0]],
                     [2 * (xy + wz), 1 - 2 * (xx + zz), 2 * (yz - wx), pos[1]],
                     [2 * (xz - wy), 2 * (yz + wx), 1 - 2 * (xx + yy), pos[2]],
                     [0.0, 0.0, 0.0, 1.0]])


def quat_xyzw_from_R(R: np.ndarray) -> tuple[float, float, float, float]:
    """The unit quaternion (x, y, z, w) of rotation ``R`` (3, 3)."""
    from scipy.spatial.transform import Rotation
    x, y, z, w = Rotation.from_matrix(np.asarray(R, dtype=float)).as_quat()
    return float(x), float(y), float(z), float(w)
