"""Contact relations between two parts (Eq. 1) on their surface planes Π.

For a parent plane (π_p^i, U_p^i) and a child plane (π_c^j, U_c^j):

    Align = |n_p^i · n_c^j|                                   >= theta_a
    Dist  = mean over u in U_c^j of |n_p^i · u + d_p^i|         <= theta_d   (m)
    Cont  = A(U_p^i ∩ proj_{p,i}(U_c^j)) / A(proj_{p,i}(U_c^j))  >= theta_c

Dist takes the absolute value per vertex (the paper's signed mean lets a tilted polygon that crosses
the plane look close). Cont divides by the projected child area (equal to A(U_c^j) once aligned, and
keeps Cont in [0, 1]). Polygons are intersected with shapely, vectorised over the candidate pairs.
The best pair of a part pair maximises Cont, then minimises Dist.
"""

from __future__ import annotations

import numpy as np
import shapely

from recon.config import ContactConfig
from recon.model import ContactEdge
from recon.primitive import SurfacePlane

__all__ = ["plane_basis", "contact_pairs", "contact_edge", "contact_edges"]


def plane_basis(normal: np.ndarray) -> np.ndarray:
    """(2, 3) orthonormal in-plane axes (rows) of a plane with unit ``normal`` (3,)."""
    a = np.array([1.0, 0.0, 0.0]) if abs(normal[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(normal, a)
    u /= np.linalg.norm(u)
    return np.stack([u, np.cross(normal, u)])


def contact_pairs(parent_planes: tuple[SurfacePlane, ...], child_planes: tuple[SurfacePlane, ...],
                  config: ContactConfig) -> list[tuple[int, int, float, float, float]]:
    """Every plane pair satisfying Eq. 1: [(parent plane i, child plane j, Cont, Align, Dist), ...]."""
    if not parent_planes or not child_planes:
        return []
    Np = np.stack([p.normal for p in parent_planes])                 # (P, 3)
    dp = np.array([p.d for p in parent_planes])                      # (P,)
    align = np.abs(Np @ np.stack([c.normal for c in child_planes]).T)  # (P, C)
    dist = np.stack([np.abs(c.polygon @ Np.T + dp).mean(axis=0) for c in child_planes], axis=1)
    ii, jj = np.nonzero((align >= config.theta_a) & (dist <= config.theta_d))
    if ii.size == 0:
        return []
    polys_p, polys_c = [], []
    for i, j in zip(ii, jj):
        pp = parent_planes[i]
        B = plane_basis(pp.normal)
        origin = pp.polygon[0]
        polys_p.append(shapely.Polygon((pp.polygon - origin) @ B.T))
        polys_c.append(shapely.Polygon((child_planes[j].polygon - origin) @ B.T))
    polys_p = shapely.make_valid(np.array(polys_p, dtype=object))
    polys_c = shapely.make_valid(np.array(polys_c, dtype=object))
    area_c = shapely.area(polys_c)
    inter = shapely.area(shapely.intersection(polys_p, polys_c))
    cont = np.where(area_c > 1e-12, inter / np.maximum(area_c, 1e-12), 0.0)
    return [(int(i), int(j), float(c), float(align[i, j]), float(dist[i, j]))
            for i, j, c in zip(ii, jj, cont) if c >= config.theta_c]


def contact_edge(parent_id: int, parent_planes: tuple[SurfacePlane, ...], child_id: int,
                 child_planes: tuple[SurfacePlane, ...], config: ContactConfig) -> ContactEdge | None:
    """The directed contact parent -> child of Eq. 1 (best pair: max Cont, then min Dist), or None
    when no plane pair satisfies it (an ordinary outcome while building the graph, not a failure)."""
    pairs = contact_pairs(parent_planes, child_planes, config)
    if not pairs:
        return None
    i, j, cont, align, dist = min(pairs, key=lambda t: (-round(t[2], 3), t[4]))
    return ContactEdge(int(parent_id), int(child_id), cont, align, dist, i, j)


def _bounds(planes: tuple[SurfacePlane, ...]) -> np.ndarray:
    v = np.concatenate([p.polygon for p in planes])
    return np.stack([v.min(axis=0), v.max(axis=0)])


def contact_edges(planes_by_part: dict[int, tuple[SurfacePlane, ...]],
                  config: ContactConfig) -> tuple[ContactEdge, ...]:
    """Every directed edge p -> c (p != c) satisfying Eq. 1 among the parts of one object.

    ``planes_by_part`` : {part_id: its planes Π}. Pairs whose bounding boxes are farther apart than
    theta_d are skipped without testing planes.
    """
    ids = sorted(planes_by_part)
    bounds = {i: _bounds(planes_by_part[i]) for i in ids if planes_by_part[i]}
    out = []
    for p in ids:
        for c in ids:
            if p == c or p not in bounds or c not in bounds:
                continue
            gap = np.maximum(bounds[p][0] - bounds[c][1], bounds[c][0] - bounds[p][1])
            if np.any(gap > config.theta_d):
                continue
            e = contact_edge(p, planes_by_part[p], c, planes_by_part[c], config)
            if e is not None:
                out.append(e)
    return tuple(out)
