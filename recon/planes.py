"""Surface planes Π of a part, two ways (``ContactConfig.planes``):

    "exact"  the faces of the fitted primitive (``Primitive.planes``): complete, even where the camera
             saw nothing, and consistent with the geometry that goes into the URDF;
    "ransac" as in the paper's Sec. III-B: planes found in the part's points by iterated RANSAC
             (open3d), each outlined by the convex hull of its inliers — only what was observed.

``bench/recon_core_ablation.py`` measures which serves the Eq. 1 contact test better.
"""

from __future__ import annotations

import numpy as np
import shapely

from recon.config import ContactConfig
from recon.contacts import plane_basis
from recon.primitive import Primitive, SurfacePlane

__all__ = ["part_planes", "ransac_planes"]


def ransac_planes(points: np.ndarray, config: ContactConfig, seed: int = 0) -> tuple[SurfacePlane, ...]:
    """Planes of ``points`` (n, 3) by iterated RANSAC; normals point away from the points' centroid."""
    from recon.open3d_engine import segment_planes

    centroid = points.mean(axis=0)
    found = segment_planes(points, distance=config.ransac_distance, count=config.ransac_planes, seed=seed,
                           min_inliers=max(12, int(config.ransac_min_fraction * len(points))))
    out = []
    for plane, idx in found:
        n, d = plane[:3], float(plane[3])
        if n @ centroid + d > 0:           # the part's body lies behind its faces
            n, d = -n, -d
        B = plane_basis(n)
        origin = -d * n
        hull = shapely.MultiPoint((points[idx] - origin) @ B.T).convex_hull
        if not isinstance(hull, shapely.Polygon) or hull.area <= 0:
            continue
        ring = np.asarray(hull.exterior.coords)[:-1]
        out.append(SurfacePlane(n.copy(), d, origin + ring @ B))
    return tuple(out)


def part_planes(prim: Primitive, points: np.ndarray, config: ContactConfig, seed: int = 0
                ) -> tuple[SurfacePlane, ...]:
    """The planes Π used by the contact test, per ``config.planes``."""
    if config.planes == "exact":
        return prim.planes(config.cylinder_side_faces)
    if config.planes == "ransac":
        return ransac_planes(points, config, seed)
    raise ValueError(f"ContactConfig.planes must be 'exact' or 'ransac', got {config.planes!r}")
