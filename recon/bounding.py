"""Minimum-volume oriented bounding boxes of part clouds, robust to flat and collinear parts.

Two boxes are computed: an upright one (z = world up, minimum-area rectangle of the footprint: the
right frame for furniture in a gravity-aligned scan) and a free 3D one (trimesh's minimum-volume box).
The upright box wins unless the free box is clearly smaller. Degenerate inputs (flat, collinear,
duplicate points), on which Qhull fails, fall back to the principal axes of the points.
"""

from __future__ import annotations

import numpy as np
import trimesh
from scipy.spatial import QhullError

__all__ = ["OrientedBox", "oriented_box"]


class OrientedBox(tuple):
    """``(T_world_box (4, 4), extents (3,))``: the box centre frame and its full edge lengths (m)."""

    __slots__ = ()

    def __new__(cls, T_world_box, extents):
        return super().__new__(cls, (np.asarray(T_world_box, float), np.asarray(extents, float)))

    @property
    def T_world_box(self) -> np.ndarray:
        return self[0]

    @property
    def extents(self) -> np.ndarray:
        return self[1]


def _pca_box(points: np.ndarray) -> OrientedBox:
    c = points.mean(axis=0)
    _, _, vt = np.linalg.svd(points - c, full_matrices=False)
    R = vt.T.copy()
    if np.linalg.det(R) < 0:
        R[:, 2] *= -1
    q = (points - c) @ R
    lo, hi = q.min(axis=0), q.max(axis=0)
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, c + R @ ((lo + hi) / 2)
    return OrientedBox(T, hi - lo)


def _upright_box(points: np.ndarray) -> OrientedBox:
    xy = points[:, :2]
    try:
        if np.linalg.matrix_rank(xy - xy.mean(axis=0), tol=1e-6) < 2:
            raise QhullError("flat footprint")
        T2, ext2 = trimesh.bounds.oriented_bounds_2D(xy)
        R2 = np.linalg.inv(T2)[:2, :2]        # columns: rectangle axes in world xy
        c2 = np.linalg.inv(T2)[:2, 2]
    except (QhullError, ValueError):
        d = xy - xy.mean(axis=0)
        _, _, vt = np.linalg.svd(d, full_matrices=False) if len(xy) > 1 else (None, None, np.eye(2))
        R2 = vt.T
        q = d @ R2
        lo, hi = q.min(axis=0), q.max(axis=0)
        ext2, c2 = hi - lo, xy.mean(axis=0) + R2 @ ((lo + hi) / 2)
    ext2 = np.asarray(ext2, dtype=np.float64)
    if np.linalg.det(R2) < 0:
        R2 = R2[:, ::-1]
        ext2 = ext2[::-1]
    # of the four equivalent yaws (quarter turns) keep the one closest to the world axes
    for _ in range(4):
        if R2[0, 0] >= abs(R2[1, 0]) - 1e-12:
            break
        R2 = np.stack([R2[:, 1], -R2[:, 0]], axis=1)
        ext2 = ext2[::-1]
    z0, z1 = points[:, 2].min(), points[:, 2].max()
    T = np.eye(4)
    T[:2, :2] = R2
    T[:2, 3] = c2
    T[2, 3] = (z0 + z1) / 2
    return OrientedBox(T, np.array([ext2[0], ext2[1], z1 - z0]))


def _free_box(points: np.ndarray) -> OrientedBox:
    centred = points - points.mean(axis=0)
    if np.linalg.matrix_rank(centred, tol=1e-6) < 3:
        return _pca_box(points)
    try:
        to_origin, ext = trimesh.bounds.oriented_bounds(points)
    except (QhullError, ValueError):
        return _pca_box(points)
    return OrientedBox(np.linalg.inv(to_origin), ext)


def oriented_box(points: np.ndarray, *, min_thickness: float, upright_tolerance: float) -> OrientedBox:
    """The part's oriented bounding box: ``points`` (n, 3) world -> OrientedBox (extents >= min_thickness).

    The upright box is used when its volume is within ``(1 + upright_tolerance)`` of the free box's
    (volumes measured with extents floored at ``min_thickness``, so flat parts compare sensibly).
    """
    points = np.asarray(points, dtype=np.float64)
    up = _upright_box(points)
    vol = lambda b: float(np.prod(np.maximum(b.extents, min_thickness)))  # noqa: E731
    # against the minimum-volume box, not the principal-axes one: the principal axes of a box seen on
    # two or three faces run along its diagonals, and that box is no tighter than a wrong upright one
    free = _free_box(points)
    best = up if vol(up) <= (1.0 + upright_tolerance) * vol(free) else free
    return OrientedBox(best.T_world_box, np.maximum(best.extents, min_thickness))
