"""The one door through which open3d enters recon: ICP, normals, RANSAC planes.

Arrays in, arrays out (float64, world frame, metres); no open3d type leaks out of this module.

Each call runs open3d on one thread: from 0.20 it parallelises with oneTBB, which ignores
``OMP_NUM_THREADS`` and sums its reductions (ICP, normals) in an order that depends on the machine's
load, so a recon decision on a borderline value would differ between an idle and a busy run of the
same scan and seed. The limit is lifted after the call (the scanner's ray casting keeps its threads).
"""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np
import open3d as o3d

__all__ = ["estimate_normals", "icp_point_to_plane", "segment_planes"]

o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)


@contextmanager
def _one_thread():
    """open3d limited to one thread inside the block (open3d >= 0.20; older ones follow OMP_NUM_THREADS);
    the limit in force before (a caller's own, else the hardware's) is put back after it."""
    limit = getattr(o3d.utility, "set_max_threads", None)
    if limit is None:
        yield
        return
    before = o3d.utility.get_max_threads()
    limit(1)
    try:
        yield
    finally:
        limit(before)


def _cloud(points: np.ndarray, normals: np.ndarray | None = None) -> "o3d.geometry.PointCloud":
    pc = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(np.ascontiguousarray(points, dtype=np.float64)))
    if normals is not None:
        pc.normals = o3d.utility.Vector3dVector(np.ascontiguousarray(normals, dtype=np.float64))
    return pc


def estimate_normals(points: np.ndarray, k: int = 16) -> np.ndarray:
    """(n, 3) unit normals of ``points`` (n, 3) from their k nearest neighbours (sign arbitrary)."""
    pc = _cloud(points)
    with _one_thread():
        pc.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(knn=k))
    return np.asarray(pc.normals).copy()


def icp_point_to_plane(source: np.ndarray, target: np.ndarray, target_normals: np.ndarray, *,
                       max_distance: float, iterations: int) -> tuple[np.ndarray, float]:
    """Rigid ``T_target_source`` (4, 4) aligning ``source`` (n, 3) onto ``target`` (m, 3) by
    point-to-plane ICP from the identity; also returns the inlier RMSE (m)."""
    with _one_thread():
        res = o3d.pipelines.registration.registration_icp(
            _cloud(source), _cloud(target, target_normals), max_distance, np.eye(4),
            o3d.pipelines.registration.TransformationEstimationPointToPlane(),
            o3d.pipelines.registration.ICPConvergenceCriteria(max_iteration=iterations))
    return np.asarray(res.transformation).copy(), float(res.inlier_rmse)


def segment_planes(points: np.ndarray, *, distance: float, count: int, seed: int,
                   min_inliers: int = 50) -> list[tuple[np.ndarray, np.ndarray]]:
    """Up to ``count`` planes found by iterated RANSAC, largest first.

    Returns ``[(plane (4,) [a, b, c, d] with unit normal, inlier indices (k,) into points), ...]``.
    """
    o3d.utility.random.seed(int(seed))
    remaining = np.arange(len(points))
    out = []
    for _ in range(count):
        if len(remaining) < max(min_inliers, 3):
            break
        with _one_thread():
            plane, inliers = _cloud(points[remaining]).segment_plane(distance, 3, 200)
        inliers = np.asarray(inliers, dtype=np.int64)
        if len(inliers) < min_inliers:
            break
        plane = np.asarray(plane, dtype=np.float64)
        plane /= np.linalg.norm(plane[:3])
        out.append((plane, remaining[inliers]))
        remaining = np.delete(remaining, inliers)
    return out

