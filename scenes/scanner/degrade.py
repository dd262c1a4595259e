"""Sensor degradations, pure numpy/scipy: each takes arrays and a ``numpy.random.Generator``.

Shapes: ``points`` (n, 3) world metres; ``ranges`` (n,) metres; ``dirs`` (n, 3) unit ray
directions; ``normals`` (n, 3) unit; ids (n,) int.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

__all__ = ["depth_sigma", "keep_returns", "add_depth_noise", "add_outliers", "flip_boundary_labels",
           "voxel_keep"]


def depth_sigma(ranges: np.ndarray, base: float, quadratic: float) -> np.ndarray:
    """(n,) standard deviation of depth noise, metres: ``base + quadratic * r**2``."""
    return base + quadratic * np.asarray(ranges) ** 2


def keep_returns(dirs: np.ndarray, normals: np.ndarray, missing_rate: float, grazing_limit_deg: float,
                 rng: np.random.Generator) -> np.ndarray:
    """(n,) bool: returns kept after random dropout and the grazing-angle limit."""
    cos_inc = np.abs(np.einsum("ij,ij->i", dirs, normals))
    keep = cos_inc >= np.cos(np.radians(grazing_limit_deg)) - 1e-12
    if missing_rate > 0:
        keep &= rng.random(len(dirs)) >= missing_rate
    return keep


def add_depth_noise(ranges: np.ndarray, base: float, quadratic: float, rng: np.random.Generator) -> np.ndarray:
    """(n,) noisy ranges: r + N(0, depth_sigma(r))."""
    sigma = depth_sigma(ranges, base, quadratic)
    if not np.any(sigma > 0):
        return np.asarray(ranges, float).copy()
    return ranges + rng.normal(0.0, 1.0, len(ranges)) * sigma


def add_outliers(ranges: np.ndarray, rate: float, spread: float, rng: np.random.Generator,
                 floor: float = 0.05) -> tuple[np.ndarray, np.ndarray]:
    """Move a ``rate`` fraction of ranges by U(-spread, spread), not below ``floor`` metres;
    returns (ranges, (n,) bool is_outlier)."""
    out = np.zeros(len(ranges), bool)
    if rate <= 0 or spread <= 0:
        return np.asarray(ranges, float).copy(), out
    out = rng.random(len(ranges)) < rate
    r = np.asarray(ranges, float).copy()
    r[out] = np.maximum(r[out] + rng.uniform(-spread, spread, out.sum()), floor)
    return r, out


def flip_boundary_labels(points: np.ndarray, object_id: np.ndarray, part_id: np.ndarray, width: float,
                         prob: float, rng: np.random.Generator, k: int = 8) -> np.ndarray:
    """(n,) part ids where each point within ``width`` m of a point of another part of the same object
    takes that (nearest such) part's id with probability ``prob``."""
    new = part_id.copy()
    if width <= 0 or prob <= 0:
        return new
    for oid in np.unique(object_id[object_id >= 0]):
        idx = np.flatnonzero(object_id == oid)
        if len(idx) < 2:
            continue
        tree = cKDTree(points[idx])
        d, nn = tree.query(points[idx], k=min(k, len(idx)), distance_upper_bound=width)
        valid = np.isfinite(d)
        nn_part = np.where(valid, part_id[idx][np.minimum(nn, len(idx) - 1)], part_id[idx][:, None])
        other = valid & (nn_part != part_id[idx][:, None])
        has = other.any(axis=1)
        first = np.argmax(other, axis=1)
        flip = has & (rng.random(len(idx)) < prob)
        new[idx[flip]] = nn_part[flip, first[flip]]
    return new


def voxel_keep(points: np.ndarray, voxel: float, rng: np.random.Generator) -> np.ndarray:
    """(m,) indices of kept points: one randomly chosen real point per occupied ``voxel`` cube (all if 0).

    Keeping a real return (not a centroid) keeps every point on its surface up to the sensor noise.
    """
    n = len(points)
    if voxel <= 0 or n == 0:
        return np.arange(n)
    order = rng.permutation(n)
    k = np.floor(points[order] / voxel).astype(np.int64) + (1 << 20)   # +-1e6 voxels per axis
    keys = (k[:, 0] << 42) | (k[:, 1] << 21) | k[:, 2]
    _, first = np.unique(keys, return_index=True)
    return np.sort(order[first])
