"""``metrics.json`` (format :data:`METRICS_FORMAT`): a reconstruction's metrics against its truth.json,
as written into a demo directory and shown by the report (``simcheck.report``).

``summary``: the scene means (Chamfer distance and voxel IoU in each true object's unit box, kinematic mAP
over objects), the number of missing objects and the pooled :class:`~recon.metrics.JointSummary`;
``objects``: one row per true object; ``joints``: one row per true movable joint (errors in degrees and
metres). JSON has no NaN: an undefined metric is written as ``null``.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np

from recon.metrics.evaluation import JointSummary, MetricsConfig, SceneMetrics, evaluate_scene, joint_summary
from recon.metrics.kinematic_ap import mean_average_precision
from recon.metrics.objects import estimate_from_reconstruction
from recon.metrics.truth import TruthScene
from scenes.description import write_text_atomic

__all__ = ["METRICS_FORMAT", "metrics_doc", "reconstruction_metrics_doc", "write_metrics_json"]

METRICS_FORMAT = "partscene.metrics/1"


def _finite_or_none(x: float | None) -> float | None:
    """JSON has no NaN: an undefined metric is written as null (shown as "–")."""
    return float(x) if x is not None and np.isfinite(x) else None


def metrics_doc(scene_metrics: SceneMetrics, summary: JointSummary) -> dict:
    """The ``metrics.json`` document of ``scene_metrics`` and its pooled joint ``summary`` (module docstring)."""
    objs = scene_metrics.objects
    doc = {"format": METRICS_FORMAT, "scene": scene_metrics.scene,
           "summary": {"chamfer": _finite_or_none(scene_metrics.chamfer), "iou": _finite_or_none(scene_metrics.iou),
                       "kinematic_map": _finite_or_none(mean_average_precision(o.ap for o in objs)),
                       "missing_objects": int(scene_metrics.missing)},
           "objects": [], "joints": []}
    for field_name, value in dataclasses.asdict(summary).items():
        doc["summary"][field_name] = value if isinstance(value, int) else _finite_or_none(value)
    for o in objs:
        doc["objects"].append({"name": o.name, "category": o.category, "status": o.status.value,
                               "chamfer": _finite_or_none(o.chamfer), "iou": _finite_or_none(o.iou),
                               "ap": _finite_or_none(o.ap)})
        for j in o.joints:
            if j.true_type == "fixed":
                continue
            doc["joints"].append({"name": j.name, "true_type": j.true_type, "est_type": j.est_type,
                                  "match": j.match.value, "axis_error_deg": _finite_or_none(j.axis_error_deg),
                                  "hinge_distance_m": _finite_or_none(j.hinge_distance_m),
                                  "upper_error": _finite_or_none(j.upper_error)})
    return doc


def reconstruction_metrics_doc(truth: TruthScene, rec, config: MetricsConfig) -> dict:
    """The ``metrics.json`` document of reconstruction ``rec`` (a :class:`recon.Reconstruction`) against
    ``truth`` (:func:`recon.metrics.read_truth`)."""
    estimates = [estimate_from_reconstruction(o, rec.config) for o in rec.objects]
    scene_metrics = evaluate_scene(truth, estimates, config)
    return metrics_doc(scene_metrics, joint_summary([c for o in scene_metrics.objects for c in o.joints]))


def write_metrics_json(doc: dict, path: str | Path) -> Path:
    """Write ``doc`` to ``path`` atomically (two-space indented, no NaN); returns the path."""
    return write_text_atomic(path, json.dumps(doc, indent=2, allow_nan=False) + "\n")
