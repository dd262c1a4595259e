"""The object-level baseline (the paper's [9]): each scanned object replaced whole by the best-fitting
template of its category, scaled anisotropically to the object's gravity-aligned oriented box.

For one labelled object with points P (all its parts together):

1. the scanned box: yaw from the minimum-area rectangle of P's footprint, extents from robust quantiles,
   bottom on P's lowest points (:func:`recon.baseline.placement.scanned_box`);
2. every template of the category, at each of the 4 yaws of that box (the front is not known from the
   footprint), is scaled onto it and scored by the mean distance from the object's scan points to the
   template's surface (exact point-to-primitive distance, metres):

       score = mean_{p in P} d(p, template surface)

   Only this direction is used: the reverse term (template surface samples to scan, Eq. 3's direction)
   is dominated by the template's drawer insides and back panel that no camera sees;
3. the lowest score wins. No parts are fitted: the object's estimate is the template's primitives.
   For the joint and structure metrics only, the template's parts are put in correspondence with the
   scan's labelled parts (same label, nearest centres, Hungarian), which carries the template's joints
   and contact edges (score 1) over to the scan's part ids; unmatched template parts carry nothing.
"""

from __future__ import annotations

import enum
import logging
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import linear_sum_assignment

from recon.baseline.placement import BOX_QUANTILE, ScannedBox, TemplatePlacement, scanned_box, yaw_candidates
from recon.baseline.templates import Template, TemplateLibrary, library_from_generators
from recon.metrics.chamfer import distance_to_union_surface
from recon.metrics.objects import ObjectEstimate
from recon.scan import ObjectPoints, Scan
from scenes.description import joint_name

__all__ = ["BaselineConfig", "BaselineStatus", "BaselineObject", "BaselineResult", "fit_object",
           "reconstruct_object_level", "object_level_from_files"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class BaselineConfig:
    """Constants of the object-level baseline."""

    fit_points: int = 1000
    """Scan points per object used to score templates (a seeded subsample; the score is a mean, so
    1000 points estimate it within a few percent)."""
    box_quantile: float = BOX_QUANTILE
    """Points ignored at each end of every axis when measuring the scanned box (fraction)."""
    min_points: int = 30
    """An object with fewer scan points is not replaced (status TOO_FEW_POINTS)."""


class BaselineStatus(enum.Enum):
    OK = "ok"
    NO_TEMPLATE = "no_template"          # the library has no model of the object's category
    TOO_FEW_POINTS = "too_few_points"    # fewer than BaselineConfig.min_points scan points


@dataclass(frozen=True, eq=False)
class BaselineObject:
    """The baseline's result for one labelled object.

    status, reason : OK, or why the object was not replaced (``estimate`` is then None)
    template : name of the winning template ("" if none); score : its fit score (metres)
    box : the winning placement's scanned box (x = the template's front); seconds : time spent
    """

    object_id: int
    category: str
    status: BaselineStatus
    reason: str
    template: str = ""
    score: float = float("nan")
    box: ScannedBox | None = None
    estimate: ObjectEstimate | None = None
    seconds: float = float("nan")


@dataclass(frozen=True, eq=False)
class BaselineResult:
    """The baseline over a whole scan: one :class:`BaselineObject` per labelled object."""

    objects: tuple[BaselineObject, ...]
    seconds: float

    @property
    def estimates(self) -> tuple[ObjectEstimate, ...]:
        """The estimates of the replaced objects (what :func:`recon.metrics.evaluate_scene` takes)."""
        return tuple(o.estimate for o in self.objects if o.status is BaselineStatus.OK)


def _correspondence(obj: ObjectPoints, template: Template, placement: TemplatePlacement) -> dict[int, int]:
    """{template part id: scan part id}: same label, nearest centres (Hungarian per label)."""
    out = {}
    for label in sorted({p.label for p in obj.parts}):
        scan_parts = [p for p in obj.parts if p.label == label]
        tmpl_parts = [p for p in template.parts if p.label == label]
        if not scan_parts or not tmpl_parts:
            continue
        a = np.array([p.points.mean(axis=0) for p in scan_parts])
        b = placement.points(np.array([p.centre for p in tmpl_parts]))
        rows, cols = linear_sum_assignment(np.linalg.norm(a[:, None] - b[None], axis=2))
        for r, c in zip(rows, cols):
            out[tmpl_parts[c].id] = scan_parts[r].part_id
    return out


def _estimate(obj: ObjectPoints, template: Template, placement: TemplatePlacement, seconds: float) -> ObjectEstimate:
    prims = tuple(placement.primitive(p) for p in template.primitives)
    m = _correspondence(obj, template, placement)
    labels = {p.part_id: p.label for p in obj.parts}
    joints = []
    for j in template.joints:
        if j.parent_part_id in m and j.child_part_id in m:
            child = m[j.child_part_id]
            handle = m.get(j.handle_part_id) if j.handle_part_id is not None else None
            joints.append(placement.joint(j, joint_name(obj.category, obj.id, labels[child], child),
                                          m[j.parent_part_id], child, handle))
    contacts = {(m[a], m[b]): 1.0 for a, b in template.contacts if a in m and b in m}
    return ObjectEstimate(obj.id, obj.category, prims, tuple(joints), contacts, seconds)


def fit_object(obj: ObjectPoints, templates: tuple[Template, ...], config: BaselineConfig = BaselineConfig(),
               seed: int = 0) -> BaselineObject:
    """Replace one labelled object by its best template (module docstring)."""
    t0 = time.perf_counter()
    where = f"object {obj.id} ({obj.category})"
    if not templates:
        return BaselineObject(obj.id, obj.category, BaselineStatus.NO_TEMPLATE,
                              f"{where}: the library has no {obj.category!r} template")
    points = np.concatenate([p.points for p in obj.parts], axis=0) if obj.parts else np.zeros((0, 3))
    if len(points) < config.min_points:
        return BaselineObject(obj.id, obj.category, BaselineStatus.TOO_FEW_POINTS,
                              f"{where}: {len(points)} scan points, fewer than {config.min_points}")
    rng = np.random.default_rng(seed)
    fit_pts = points[rng.choice(len(points), config.fit_points, replace=False)] \
        if len(points) > config.fit_points else points
    best = None
    for template in templates:
        for box in yaw_candidates(scanned_box(points, config.box_quantile)):
            placement = TemplatePlacement.onto(template.bounds, box)
            prims = [placement.primitive(p) for p in template.primitives]
            score = float(distance_to_union_surface(fit_pts, prims).mean())
            if best is None or score < best[0]:
                best = (score, template, placement, box)
    score, template, placement, box = best
    seconds = time.perf_counter() - t0
    log.debug("%s: template %s, yaw %.1f deg, score %.4f m", where, template.name, np.degrees(box.yaw), score)
    return BaselineObject(obj.id, obj.category, BaselineStatus.OK, "", template.name, score, box,
                          _estimate(obj, template, placement, seconds), seconds)


def reconstruct_object_level(scan: Scan, library: TemplateLibrary | None = None,
                             config: BaselineConfig = BaselineConfig(), seed: int = 0) -> BaselineResult:
    """Run the baseline on every labelled object of ``scan`` (default library:
    :func:`recon.baseline.templates.library_from_generators`)."""
    t0 = time.perf_counter()
    library = library_from_generators() if library is None else library
    rows = []
    for k, obj in enumerate(scan.objects):
        row = fit_object(obj, tuple(library.get(obj.category, ())), config, seed + k)
        if row.status is not BaselineStatus.OK:
            log.warning("%s", row.reason)
        rows.append(row)
    return BaselineResult(tuple(rows), time.perf_counter() - t0)


def object_level_from_files(scan_path: str | Path, labels_path: str | Path, library: TemplateLibrary | None = None,
                            config: BaselineConfig = BaselineConfig(), seed: int = 0) -> BaselineResult:
    """Read ``scan.ply``/``scan.npz`` + ``labels.json`` (:func:`recon.scan.read_scan`) and run the baseline."""
    from recon.scan import read_scan

    return reconstruct_object_level(read_scan(scan_path, labels_path), library, config, seed)
