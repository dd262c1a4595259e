"""Level a scan that arrives in a camera frame: find the floor plane and make it z = 0, normal up.

RANSAC (open3d) proposes the ``floor_candidates`` largest planes. Walls are large planes too, so the
floor is the plane that the most labelled objects touch from one side (furniture stands on the floor;
only some of it touches a wall); ties go to the larger plane. The normal is oriented toward the
objects. The result is the rigid ``T_level_scan`` that maps the scan into a z-up, floor-at-0 frame.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from recon.config import LevelingConfig, SceneConfig
from recon.errors import ScanError
from recon.scan import Scan

__all__ = ["floor_transform"]


def floor_transform(scan: Scan, config: LevelingConfig, scene: SceneConfig, seed: int = 0) -> tuple[np.ndarray, float]:
    """(T_level_scan (4, 4), tilt of the original up direction from the floor normal in radians)."""
    from recon.open3d_engine import segment_planes

    rng = np.random.default_rng(seed)
    pts = scan.points
    if len(pts) > 60000:
        pts = pts[np.sort(rng.choice(len(pts), 60000, replace=False))]
    planes = segment_planes(pts, distance=config.floor_ransac_distance, count=config.floor_candidates,
                            seed=seed, min_inliers=max(50, len(pts) // 100))
    if not planes:
        raise ScanError(f"{scan.source}: level_floor found no plane large enough to be the floor")
    objects = [np.concatenate([p.points for p in o.parts]) for o in scan.objects]
    best = None
    for rank, (plane, inliers) in enumerate(planes):
        n, d = plane[:3], plane[3]
        side = np.concatenate([o @ n + d for o in objects])
        if np.mean(side) < 0:
            n, d = -n, -d
        touching = 0
        for o in objects:
            s = o @ n + d
            if np.mean(s > -config.floor_ransac_distance) > 0.95 and s.min() < scene.support_distance:
                touching += 1
        key = (touching, -rank)
        if best is None or key > best[0]:
            best = (key, n, d)
    _, n, d = best
    rot, _ = Rotation.align_vectors([[0.0, 0.0, 1.0]], [n])
    T = np.eye(4)
    T[:3, :3] = rot.as_matrix()
    # a point p on the plane satisfies n.p = -d; after rotation its height is n.p = -d: shift by +d
    T[2, 3] = d
    tilt = float(np.arccos(np.clip(n[2], -1.0, 1.0)))
    return T, tilt
