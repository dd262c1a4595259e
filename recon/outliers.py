"""Statistical outlier removal (flying pixels, stray returns) on a part's points.

A point is an outlier when the mean distance to its ``neighbors`` nearest neighbours exceeds the
cloud's mean of that statistic by ``std_ratio`` standard deviations (the classic PCL / open3d test,
here on scipy's KD-tree, which is several times faster than open3d's on these cloud sizes).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

__all__ = ["statistical_inliers"]


def statistical_inliers(points: np.ndarray, *, neighbors: int, std_ratio: float) -> np.ndarray:
    """(n,) bool mask of the inliers of ``points`` (n, 3)."""
    n = len(points)
    if n <= neighbors + 1:
        return np.ones(n, dtype=bool)
    d, _ = cKDTree(points).query(points, k=neighbors + 1)
    mean = d[:, 1:].mean(axis=1)
    return mean <= mean.mean() + std_ratio * mean.std()
