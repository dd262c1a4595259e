"""Handles and legs without the label fragments a segmentation scatters: each is one piece, its points one cluster.

A segmentation network labels small blobs of one part with another part's label (a few points of a door
labelled "handle" half a metre from the handle). A handle or knob has a few dozen points at most, so two
such points pull its fitted bar across the front and its hinge side with it. The points of a handle part
are linked when closer than ``fragment_link_spacings`` times the point spacing (the median distance from
each point to its nearest neighbour: the scan's density, whatever the scanner) of its object or, when
sparser, of the handle's own points (a handle seen by a few points); the largest linked cluster is the handle, and so is any other cluster holding at least
``fragment_min_share`` of its points (a bar seen in two pieces). The other clusters are fragments: they
leave the handle part (they stay in the scan, as obstacles). A leg is one small piece too: a fragment of
leg-labelled points on a bed's mattress, 1.4 m from the leg, made its box 1.2 m wide; it is reduced
the same way.
"""

from __future__ import annotations

import logging
from dataclasses import replace

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from recon.config import ScanConfig
from recon.scan import Scan

__all__ = ["FRAGMENT_LABELS", "point_spacing", "handle_cluster", "without_label_fragments"]

log = logging.getLogger(__name__)

FRAGMENT_LABELS = frozenset({"handle", "knob", "leg"})
"""Labels of the parts that are one small piece: their points are stripped of label fragments."""


def point_spacing(points: np.ndarray) -> float:
    """The median distance (m) from each of ``points`` (n, 3) to its nearest other point; 0 below 2 points."""
    if len(points) < 2:
        return 0.0
    d, _ = cKDTree(points).query(points, k=2)
    return float(np.median(d[:, 1]))


def handle_cluster(points: np.ndarray, link: float, min_share: float) -> np.ndarray:
    """(n,) bool: the points of ``points`` (n, 3) in their largest cluster (points closer than ``link`` m
    linked) or in a cluster holding at least ``min_share`` of them."""
    n = len(points)
    if n < 3 or link <= 0:
        return np.ones(n, bool)
    pairs = cKDTree(points).query_pairs(link, output_type="ndarray")
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    sizes = np.bincount(label)
    keep = (sizes == sizes.max()) | (sizes >= min_share * n)
    if (sizes == sizes.max()).sum() > 1:
        keep = sizes >= min_share * n          # two largest of equal size: no piece stands out
    return keep[label]


def without_label_fragments(scan: Scan, config: ScanConfig) -> tuple[Scan, int]:
    """(the scan with every handle/knob/leg part (``FRAGMENT_LABELS``) reduced to its cluster
    (:func:`handle_cluster`), how many points left those parts). Other parts and the scan's point arrays
    are unchanged."""
    objects, removed = [], 0
    for o in scan.objects:
        handles = {p.part_id for p in o.parts if p.label in FRAGMENT_LABELS and len(p.points) >= 3}
        if not handles:
            objects.append(o)
            continue
        spacing = point_spacing(np.concatenate([p.points for p in o.parts]))
        parts = []
        for p in o.parts:
            link = config.fragment_link_spacings * max(spacing, point_spacing(p.points))
            keep = handle_cluster(p.points, link, config.fragment_min_share) if p.part_id in handles else None
            if keep is None or keep.all():
                parts.append(p)
                continue
            log.info("object %d part %d (%s): %d of its %d points lie apart from the rest (more than %.3f m); "
                     "dropped as label fragments", o.id, p.part_id, p.label, int((~keep).sum()), len(keep), link)
            removed += int((~keep).sum())
            parts.append(replace(p, points=p.points[keep], normals=None if p.normals is None else p.normals[keep]))
        objects.append(replace(o, parts=tuple(parts)))
    return replace(scan, objects=tuple(objects)), removed
