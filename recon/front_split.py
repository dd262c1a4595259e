"""Fronts labelled as one part but showing several: a drawer/door part split at horizontal gaps.

A segmentation can give one part id to a chest's whole column of drawer fronts. The rails between the
fronts belong to the body, so the part's points show horizontal bands without points (dividers). Along
the vertical (world z, metres) the part's points are binned ``front_split_bin`` wide; a run of bins
holding at most ``front_split_density`` × the median count of the occupied bins, at least
``front_split_min_gap`` tall, with at least ``front_split_min_height`` of front above and below it, is a
gap. The part is cut at the middle of each gap; the lowest piece keeps the part id, the others get new
ids above every id in the scan, with the same label. Each split is reported by a warning naming the
object, the part and the new ids.

A sparse scan may show no gap (a rail narrower than the point spacing). A drawer part without gaps
whose handles stand at several heights is then cut between them (:func:`handle_levels`): a drawer is
pulled by one handle or by handles side by side, so pulls stacked one above another mark one front each.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from recon.config import ScanConfig
from recon.scan import PartPoints, Scan

__all__ = ["FRONT_LABELS", "horizontal_gaps", "handle_heights", "handle_levels", "split_fronts"]

FRONT_LABELS = frozenset({"drawer", "door"})
"""Labels of the parts that are checked for several fronts under one label."""


def horizontal_gaps(z: np.ndarray, config: ScanConfig) -> list[float]:
    """Heights (m) of the middles of the horizontal gaps in the heights ``z`` (n,) of one part's points,
    lowest first (empty when the points show one front)."""
    if len(z) < 2 * config.min_part_points:
        return []
    b = config.front_split_bin
    lo, hi = float(z.min()), float(z.max())
    nb = int(np.ceil((hi - lo) / b))
    if nb < 3:
        return []
    counts, edges = np.histogram(z, bins=nb, range=(lo, lo + nb * b))
    level = config.front_split_density * float(np.median(counts[counts > 0]))
    empty = counts <= level
    gaps, k = [], 0
    while k < nb:
        if not empty[k]:
            k += 1
            continue
        j = k
        while j + 1 < nb and empty[j + 1]:
            j += 1
        bottom, top = float(edges[k]), float(edges[j + 1])
        if (top - bottom >= config.front_split_min_gap and bottom - lo >= config.front_split_min_height
                and hi - top >= config.front_split_min_height):
            gaps.append((bottom + top) / 2)
        k = j + 1
    return gaps


HANDLE_LABELS = frozenset({"handle", "knob"})


def handle_heights(parts: tuple[PartPoints, ...]) -> dict[int, list[float]]:
    """{front part id: the heights (m, lowest first) of the handle/knob centres standing on it} for one
    object's ``parts``: a handle stands on the front part nearest its centre."""
    from scipy.spatial import cKDTree

    fronts = [p for p in parts if p.label in FRONT_LABELS and len(p.points)]
    if not fronts:
        return {}
    trees = [cKDTree(p.points) for p in fronts]
    out: dict[int, list[float]] = {}
    for h in parts:
        if h.label in HANDLE_LABELS and len(h.points):
            c = h.points.mean(axis=0)
            out.setdefault(fronts[int(np.argmin([t.query(c)[0] for t in trees]))].part_id, []).append(float(c[2]))
    return {k: sorted(v) for k, v in out.items()}


def handle_levels(front: PartPoints, zs: list[float], config: ScanConfig) -> list[float]:
    """Cut heights (m, lowest first) between the levels of the handles standing on ``front`` at heights
    ``zs`` (sorted, :func:`handle_heights`).

    Handle centres less than ``front_split_min_height`` apart in height are one level. The front is cut
    midway between consecutive levels at least 2 x ``front_split_min_height`` apart, where that leaves at
    least ``front_split_min_height`` of it above and below; empty when its handles stand at one level.
    """
    levels: list[list[float]] = []
    for z in zs:
        if levels and z - levels[-1][-1] < config.front_split_min_height:
            levels[-1].append(z)
        else:
            levels.append([z])
    if len(levels) < 2:
        return []
    mids = [float(np.mean(v)) for v in levels]
    lo, hi = float(front.points[:, 2].min()), float(front.points[:, 2].max())
    h = config.front_split_min_height
    cuts = [(a + b) / 2 for a, b in zip(mids, mids[1:]) if b - a >= 2 * h]
    return [c for c in cuts if c - lo >= h and hi - c >= h]


def split_fronts(scan: Scan, config: ScanConfig) -> tuple[Scan, list[str]]:
    """(the scan with every drawer/door part that shows horizontal gaps -- or, a drawer, handles stacked
    at several heights -- split into one part per front, the warnings naming each split). Parts of other
    labels and single fronts are unchanged."""
    next_id = int(max(scan.part_id.max(initial=-1), max((p.part_id for o in scan.objects for p in o.parts),
                                                        default=-1))) + 1
    part_id = scan.part_id.copy()
    objects, warnings = [], []
    for obj in scan.objects:
        parts, heights = [], None
        for p in obj.parts:
            gaps = horizontal_gaps(p.points[:, 2], config) if p.label in FRONT_LABELS else []
            cue = "separated by horizontal gaps"
            if not gaps and p.label == "drawer":
                heights = handle_heights(obj.parts) if heights is None else heights
                gaps = handle_levels(p, heights.get(p.part_id, []), config)
                cue = "with handles stacked one above another, cut"
            if not gaps:
                parts.append(p)
                continue
            piece = np.searchsorted(np.asarray(gaps), p.points[:, 2])
            ids = [p.part_id] + list(range(next_id, next_id + len(gaps)))
            next_id += len(gaps)
            for k, pid in enumerate(ids):
                m = piece == k
                parts.append(PartPoints(p.object_id, pid, p.label, p.points[m],
                                        None if p.normals is None else p.normals[m]))
            in_scan = np.flatnonzero(scan.part_id == p.part_id)
            part_id[in_scan] = np.asarray(ids)[np.searchsorted(np.asarray(gaps), scan.points[in_scan, 2])]
            warnings.append(f"object {obj.id} ({obj.category}) part {p.part_id} ({p.label}): its points show "
                            f"{len(ids)} fronts {cue} at z = "
                            f"{', '.join(f'{g:.3f}' for g in gaps)} m; split into parts "
                            f"{', '.join(map(str, ids))}, each a {p.label} (check the labels)")
        objects.append(replace(obj, parts=tuple(parts)))
    if not warnings:
        return scan, []
    return replace(scan, part_id=part_id, objects=tuple(objects)), warnings
