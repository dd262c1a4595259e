"""Normals for a scan that has none (a plain point cloud): estimated per part and oriented outward.

A normal estimated from a point's neighbours (a local plane) has an arbitrary sign, but recon reads the
side a panel was seen from in its points' normals (:func:`recon.fitting._seen_side`: a door front's
board lies behind its seen face; :func:`recon.fitting.body_behind_face`). A scanner sees a furniture
object from outside: the seen side of its surfaces faces away from the object's inside. Each estimated
normal is therefore turned to point away from the centre of its object's points. The neighbourhood is
``ScanConfig.normal_neighbours`` points of the same part (the measurement behind its value:
docs/decisions.md, "recon: normals for a scan without").
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from recon.scan import ObjectPoints, PartPoints, Scan

__all__ = ["outward_normals", "with_estimated_normals"]


def outward_normals(points: np.ndarray, centre: np.ndarray, neighbours: int) -> np.ndarray:
    """(n, 3) unit normals (world) of ``points`` (n, 3, world, m) from their ``neighbours`` nearest
    points, each signed to point away from ``centre`` (3,) (a normal across the direction to the centre
    keeps open3d's sign)."""
    from recon.open3d_engine import estimate_normals

    n = estimate_normals(points, min(neighbours, len(points)))
    flip = np.einsum("ij,ij->i", points - centre, n) < 0.0
    n[flip] *= -1.0
    return n


def _with_normals(part: PartPoints, centre: np.ndarray, neighbours: int) -> PartPoints:
    if part.normals is not None and len(part.normals) == len(part.points):
        return part
    if len(part.points) < 3:
        return part
    return replace(part, normals=outward_normals(part.points, centre, neighbours))


def with_estimated_normals(scan: Scan, neighbours: int) -> Scan:
    """The scan with every labelled part that has no normals given outward normals (:func:`outward_normals`,
    away from the centre of its object's points). Parts with normals are kept as they are; the scan's
    unlabelled points are left without."""
    objects = []
    for obj in scan.objects:
        pts = [p.points for p in obj.parts] or [p.points for p in obj.skipped]
        if not pts or all(p.normals is not None for p in (*obj.parts, *obj.skipped)):
            objects.append(obj)
            continue
        centre = np.concatenate(pts).mean(axis=0)
        objects.append(replace(obj, parts=tuple(_with_normals(p, centre, neighbours) for p in obj.parts),
                               skipped=tuple(_with_normals(p, centre, neighbours) for p in obj.skipped)))
    return replace(scan, objects=tuple(objects))
