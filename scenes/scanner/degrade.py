"""Sensor degradations, pure numpy/scipy: each takes arrays and a ``numpy.random.Generator``.

Shapes: ``points`` (n, 3) world metres; ``ranges`` (n,) metres; ``dirs`` (n, 3) unit ray
directions; ``normals`` (n, 3) unit; ids (n,) int.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

__all__ = ["depth_sigma", "keep_returns", "add_depth_noise", "add_outliers", "flip_boundary_labels",
           "voxel_keep", "punch_holes", "bleed_into_background", "label_fragments", "tilt_about"]


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


def punch_holes(points: np.ndarray, holes_per_m2: float, radius: tuple[float, float], spacing: float,
                rng: np.random.Generator) -> np.ndarray:
    """(n,) bool: points kept outside holes. The surface is about ``n * spacing**2`` m^2 (one point per
    ``spacing`` square); ``holes_per_m2`` times that many holes, each a ball of radius U(``radius``) m
    around a random point (unseen or unfused surface: dark, shiny or never in view)."""
    n = len(points)
    keep = np.ones(n, bool)
    k = int(rng.poisson(holes_per_m2 * n * spacing**2)) if holes_per_m2 > 0 and n else 0
    if k == 0:
        return keep
    tree = cKDTree(points)
    for c, r in zip(rng.integers(0, n, k), rng.uniform(radius[0], radius[1], k)):
        keep[tree.query_ball_point(points[c], r)] = False
    return keep


def bleed_into_background(points: np.ndarray, object_id: np.ndarray, part_id: np.ndarray, width: float, prob: float,
                          rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """(object ids, part ids) where each background point within ``width`` m of an object's point takes
    that (nearest) point's object and part with probability ``prob`` (a segmentation mask spilling onto
    the floor or wall it touches)."""
    oid, pid = object_id.copy(), part_id.copy()
    fg, bg = np.flatnonzero(object_id >= 0), np.flatnonzero(object_id < 0)
    if width <= 0 or prob <= 0 or not len(fg) or not len(bg):
        return oid, pid
    d, nn = cKDTree(points[fg]).query(points[bg], distance_upper_bound=width)
    hit = np.isfinite(d) & (rng.random(len(bg)) < prob)
    src = fg[nn[hit]]
    oid[bg[hit]], pid[bg[hit]] = object_id[src], part_id[src]
    return oid, pid


def label_fragments(points: np.ndarray, object_id: np.ndarray, part_id: np.ndarray, per_object: float,
                    radius: tuple[float, float], rng: np.random.Generator) -> np.ndarray:
    """(n,) part ids with small wrong-label fragments: per object Poisson(``per_object``) balls of radius
    U(``radius``) m around random points of it, whose points take another part of the same object."""
    new = part_id.copy()
    if per_object <= 0:
        return new
    for o in np.unique(object_id[object_id >= 0]):
        idx = np.flatnonzero(object_id == o)
        parts = np.unique(part_id[idx])
        k = int(rng.poisson(per_object))
        if len(parts) < 2 or k == 0:
            continue
        tree = cKDTree(points[idx])
        for c, r in zip(rng.integers(0, len(idx), k), rng.uniform(radius[0], radius[1], k)):
            ball = idx[tree.query_ball_point(points[idx[c]], r)]
            others = parts[parts != part_id[idx[c]]]
            new[ball] = others[rng.integers(len(others))]
    return new


def tilt_about(points: np.ndarray, R: np.ndarray, pivot: np.ndarray) -> np.ndarray:
    """(n, 3) ``points`` rotated by ``R`` (3, 3) about ``pivot`` (3,)."""
    return (points - pivot) @ R.T + pivot
