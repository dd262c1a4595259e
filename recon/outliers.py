"""Statistical outlier removal (flying pixels, stray returns) on a part's points.

A point is an outlier when the mean distance to its ``neighbors`` nearest neighbours exceeds the
cloud's mean of that statistic by ``std_ratio`` standard deviations (the classic PCL / open3d test,
here on scipy's KD-tree).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from scipy.spatial import cKDTree

from recon.scan import Scan

__all__ = ["statistical_inliers", "scan_without_outliers"]


def statistical_inliers(points: np.ndarray, *, neighbors: int, std_ratio: float) -> np.ndarray:
    """(n,) bool mask of the inliers of ``points`` (n, 3)."""
    n = len(points)
    if n <= neighbors + 1:
        return np.ones(n, dtype=bool)
    d, _ = cKDTree(points).query(points, k=neighbors + 1)
    mean = d[:, 1:].mean(axis=1)
    return mean <= mean.mean() + std_ratio * mean.std()


def scan_without_outliers(scan: Scan, *, neighbors: int, std_ratio: float) -> tuple[Scan, int]:
    """(the scan without statistical outliers, how many points were removed), judged part by part (a
    part whose points carry another object id in the scan's arrays is judged on its own points)."""
    keep = np.ones(len(scan.points), dtype=bool)
    for pid in np.unique(scan.part_id[scan.part_id >= 0]):
        idx = np.flatnonzero(scan.part_id == pid)
        keep[idx] = statistical_inliers(scan.points[idx], neighbors=neighbors, std_ratio=std_ratio)
    objects = []
    for o in scan.objects:
        parts = []
        for p in o.parts:
            m = keep[scan.part_id == p.part_id]
            if len(m) != len(p.points):
                m = statistical_inliers(p.points, neighbors=neighbors, std_ratio=std_ratio)
            parts.append(replace(p, points=p.points[m], normals=None if p.normals is None else p.normals[m]))
        objects.append(replace(o, parts=tuple(parts)))
    cleaned = replace(scan, points=scan.points[keep], object_id=scan.object_id[keep], part_id=scan.part_id[keep],
                      normals=None if scan.normals is None else scan.normals[keep],
                      colors=None if scan.colors is None else scan.colors[keep], objects=tuple(objects))
    return cleaned, int((~keep).sum())
