"""Poses: (4, 4) float64 homogeneous transforms ``T_a_b`` (pose of frame b in frame a), metres, radians.

``p_a = T_a_b @ p_b`` and ``T_a_c = T_a_b @ T_b_c``. URDF ``xyz``/``rpy`` appear only at the XML boundary
(:func:`T_from_xyz_rpy`, :func:`xyz_rpy_from_T`); rotations about an axis go through
``scipy.spatial.transform.Rotation``.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

__all__ = ["pose", "rot_x", "rot_y", "rot_z", "R_about", "T_about", "T_inverse", "T_translation",
           "T_from_xyz_rpy", "xyz_rpy_from_T", "transform_points", "check_pose", "check_rotation",
           "ROTATION_ATOL"]

ROTATION_ATOL = 1e-6
"""Largest entry of ``R.T @ R - I`` (and deviation of det R from 1) a checked rotation may have."""


def rot_x(theta: float) -> np.ndarray:
    """(3, 3) rotation about x by ``theta`` radians."""
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(theta: float) -> np.ndarray:
    """(3, 3) rotation about y by ``theta`` radians."""
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(theta: float) -> np.ndarray:
    """(3, 3) rotation about z by ``theta`` radians."""
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def R_about(axis, angle: float) -> np.ndarray:
    """(3, 3) rotation by ``angle`` radians about ``axis`` (3,) (normalised here; axis-angle / Rodrigues)."""
    a = np.asarray(axis, dtype=float)
    n = float(np.linalg.norm(a))
    if n == 0.0:
        raise ValueError("rotation axis is zero")
    return Rotation.from_rotvec(a * (float(angle) / n)).as_matrix()


def T_about(axis, point, angle: float) -> np.ndarray:
    """(4, 4) rotation by ``angle`` radians about the line through ``point`` (3,) along ``axis`` (3,)."""
    R = R_about(axis, angle)
    p = np.asarray(point, dtype=float)
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p - R @ p
    return T


def pose(xyz=(0.0, 0.0, 0.0), R: np.ndarray | None = None, yaw: float | None = None) -> np.ndarray:
    """(4, 4) transform with translation ``xyz`` (metres) and rotation ``R`` (3, 3) or ``yaw`` about z."""
    T = np.eye(4)
    if R is not None:
        T[:3, :3] = R
    elif yaw is not None:
        T[:3, :3] = rot_z(yaw)
    T[:3, 3] = np.asarray(xyz, dtype=float)
    return T


def T_translation(xyz) -> np.ndarray:
    """(4, 4) pure translation by ``xyz`` (3,), metres."""
    return pose(xyz)


def T_inverse(T_a_b: np.ndarray) -> np.ndarray:
    """``T_b_a`` of a rigid ``T_a_b`` (4, 4) (transpose of the rotation, no general matrix inverse)."""
    T_a_b = np.asarray(T_a_b, dtype=float)
    T = np.eye(4)
    T[:3, :3] = T_a_b[:3, :3].T
    T[:3, 3] = -T[:3, :3] @ T_a_b[:3, 3]
    return T


def T_from_xyz_rpy(xyz, rpy) -> np.ndarray:
    """(4, 4) transform of a URDF ``<origin xyz rpy>`` (fixed-axis roll, pitch, yaw: R = Rz(y) Ry(p) Rx(r))."""
    T = np.eye(4)
    T[:3, :3] = Rotation.from_euler("xyz", np.asarray(rpy, dtype=float)).as_matrix()
    T[:3, 3] = np.asarray(xyz, dtype=float)
    return T


def xyz_rpy_from_T(T: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """URDF ``xyz`` (3,) and fixed-axis ``rpy`` (3,) of a (4, 4) transform (R = Rz(y) Ry(p) Rx(r))."""
    R = np.asarray(T)[:3, :3]
    pitch = np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0]))
    if np.isclose(np.cos(pitch), 0.0, atol=1e-9):
        roll = 0.0
        yaw = np.arctan2(-R[0, 1], R[1, 1])
    else:
        roll = np.arctan2(R[2, 1], R[2, 2])
        yaw = np.arctan2(R[1, 0], R[0, 0])
    return np.array(T)[:3, 3].copy(), np.array([roll, pitch, yaw])


def transform_points(T_a_b: np.ndarray, p_b: np.ndarray) -> np.ndarray:
    """Map (n, 3) points from frame b to frame a."""
    p_b = np.asarray(p_b, dtype=float).reshape(-1, 3)
    return p_b @ T_a_b[:3, :3].T + T_a_b[:3, 3]


def _finite_array(a, shape: tuple, what: str, kind: str) -> np.ndarray:
    a = np.asarray(a, dtype=np.float64)
    if a.shape != shape:
        raise ValueError(f"{what} must be a {shape} {kind}, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{what} has non-finite entries")
    return a


def check_rotation(R, what: str = "rotation", atol: float = ROTATION_ATOL) -> np.ndarray:
    """``R`` as a (3, 3) float64 array; ``ValueError`` naming ``what`` unless it is a proper rotation."""
    R = _finite_array(R, (3, 3), what, "rotation")
    err = float(np.abs(R.T @ R - np.eye(3)).max())
    if err > atol or abs(float(np.linalg.det(R)) - 1.0) > atol:
        raise ValueError(f"{what} is not a rotation (|R^T R - I| = {err:.2g}, det = {np.linalg.det(R):.6g})")
    return R


def check_pose(T, what: str = "pose", atol: float = ROTATION_ATOL) -> np.ndarray:
    """``T`` as a (4, 4) float64 rigid transform; ``ValueError`` naming ``what`` when it is not one."""
    T = _finite_array(T, (4, 4), what, "pose")
    if not np.allclose(T[3], [0.0, 0.0, 0.0, 1.0], atol=atol):
        raise ValueError(f"{what}: last row must be (0, 0, 0, 1), got {T[3]}")
    check_rotation(T[:3, :3], what, atol)
    return T
