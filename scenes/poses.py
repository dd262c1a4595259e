"""Small pose helpers: (4, 4) float64 homogeneous transforms ``T_a_b`` (pose of b in a), metres, radians."""

from __future__ import annotations

import numpy as np

__all__ = ["pose", "rot_z", "rot_x", "rot_y", "xyz_rpy_from_T", "transform_points"]


def rot_z(theta: float) -> np.ndarray:
    """(3, 3) rotation about z by ``theta`` radians."""
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rot_x(theta: float) -> np.ndarray:
    """(3, 3) rotation about x by ``theta`` radians."""
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(theta: float) -> np.ndarray:
    """(3, 3) rotation about y by ``theta`` radians."""
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def pose(xyz=(0.0, 0.0, 0.0), R: np.ndarray | None = None, yaw: float | None = None) -> np.ndarray:
    """(4, 4) transform with translation ``xyz`` (metres) and rotation ``R`` (3, 3) or ``yaw`` about z."""
    T = np.eye(4)
    if R is not None:
        T[:3, :3] = R
    elif yaw is not None:
        T[:3, :3] = rot_z(yaw)
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
