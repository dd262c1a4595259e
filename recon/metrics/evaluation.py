"""Scoring a reconstruction (part-level or object-level) of a scene against its truth.json.

Per true object: Chamfer distance and voxel IoU in the truth's unit box, the kinematic AP of the contact
edges, and one :class:`~recon.metrics.joint_errors.JointComparison` per true joint. Per scene: the means
of Chamfer and IoU over its objects (the paper's per-sequence numbers of Tab. I), and the joint summary.
A true object the estimate lacks is reported with status ``MISSING`` (IoU 0, Chamfer and AP undefined);
an estimated object the truth lacks is ignored (its id is listed).
"""

from __future__ import annotations

import enum
import logging
from dataclasses import dataclass
from typing import Iterable, Mapping

import numpy as np

from recon.metrics.chamfer import DEFAULT_CHAMFER_SAMPLES, object_chamfer
from recon.metrics.joint_errors import JointComparison, compare_joints
from recon.metrics.kinematic_ap import contact_edge_ap
from recon.metrics.objects import ObjectEstimate
from recon.metrics.split_parts import renamed_estimate, true_ids_of_new_parts
from recon.metrics.truth import TruthObject, TruthScene
from recon.metrics.unit_box import unit_box_from_truth
from recon.metrics.voxel_iou import DEFAULT_VOXEL_RESOLUTION, object_iou

__all__ = ["MetricsConfig", "ObjectStatus", "ObjectMetrics", "SceneMetrics", "JointSummary", "evaluate_object",
           "evaluate_scene", "joint_summary"]

log = logging.getLogger(__name__)
NAN = float("nan")


@dataclass(frozen=True)
class MetricsConfig:
    """Sampling constants of the metrics (see each metric's module for the exact definition)."""

    chamfer_samples: int = DEFAULT_CHAMFER_SAMPLES
    """Surface points sampled on each side for the Chamfer distance."""
    voxel_resolution: int = DEFAULT_VOXEL_RESOLUTION
    """Voxels along the true object's longest axis (the paper's 32^3)."""
    seed: int = 0
    """Seed of the surface sampling (object k uses ``seed + 2 k`` and ``seed + 2 k + 1``)."""


class ObjectStatus(enum.Enum):
    """Whether a true object could be scored."""

    OK = "ok"
    MISSING = "missing"       # the estimate has no object with this id


@dataclass(frozen=True)
class ObjectMetrics:
    """Metrics of one true object (``nan`` = undefined; see the module docstring)."""

    object_id: int
    name: str
    category: str
    status: ObjectStatus
    chamfer: float
    iou: float
    ap: float
    joints: tuple[JointComparison, ...]
    seconds: float


@dataclass(frozen=True)
class SceneMetrics:
    """Metrics of a whole scene: per object, plus the scene means."""

    scene: str
    objects: tuple[ObjectMetrics, ...]
    extra_object_ids: tuple[int, ...]

    @property
    def chamfer(self) -> float:
        """Mean Chamfer distance over the scored objects (unit box)."""
        v = [o.chamfer for o in self.objects if o.status is ObjectStatus.OK]
        return float(np.mean(v)) if v else NAN

    @property
    def iou(self) -> float:
        """Mean voxel IoU over all true objects (a missing object counts 0)."""
        return float(np.mean([o.iou for o in self.objects])) if self.objects else NAN

    @property
    def missing(self) -> int:
        return sum(o.status is ObjectStatus.MISSING for o in self.objects)


def evaluate_object(truth: TruthObject, estimate: ObjectEstimate, config: MetricsConfig = MetricsConfig(),
                    index: int = 0) -> ObjectMetrics:
    """All metrics of one object (``index`` offsets the sampling seed so objects get different samples).
    Parts the estimate created by splitting a labelled part are scored as the true parts they are
    (:mod:`recon.metrics.split_parts`)."""
    estimate = renamed_estimate(estimate, true_ids_of_new_parts(truth, estimate))
    box = unit_box_from_truth(truth.primitives, truth.T_world_object)
    seed = config.seed + 2 * index
    chamfer = object_chamfer(truth.primitives, estimate.primitives, box, config.chamfer_samples, seed)
    iou = object_iou(truth.primitives, estimate.primitives, box, config.voxel_resolution)
    # the estimate's own parts are known too: an edge of a split part the truth lacks is simply not true
    ap = contact_edge_ap(truth.contacts, estimate.contact_scores,
                         part_ids={p.id for p in truth.parts} | set(estimate.part_ids),
                         where=f"object {truth.id} ({truth.name})")
    centres = {p.id: p.centre for p in truth.parts}
    joints = compare_joints(truth.joints, estimate.joints, centres)
    return ObjectMetrics(truth.id, truth.name, truth.category, ObjectStatus.OK, chamfer, iou, ap, joints,
                         estimate.seconds)


def evaluate_scene(truth: TruthScene, estimates: Iterable[ObjectEstimate],
                   config: MetricsConfig = MetricsConfig()) -> SceneMetrics:
    """Score every true object of ``truth`` against the estimate of the same id."""
    by_id: Mapping[int, ObjectEstimate] = {e.object_id: e for e in estimates}
    rows = []
    for index, obj in enumerate(truth.objects):
        est = by_id.get(obj.id)
        if est is None:
            log.warning("scene %s: object %d (%s) has no estimate", truth.scene, obj.id, obj.name)
            joints = compare_joints(obj.joints, (), {})
            rows.append(ObjectMetrics(obj.id, obj.name, obj.category, ObjectStatus.MISSING, NAN, 0.0,
                                      0.0 if obj.contacts else NAN, joints, NAN))
            continue
        rows.append(evaluate_object(obj, est, config, index))
    true_ids = {o.id for o in truth.objects}
    extra = tuple(sorted(i for i in by_id if i not in true_ids))
    return SceneMetrics(truth.scene, tuple(rows), extra)


@dataclass(frozen=True)
class JointSummary:
    """Joint metrics pooled over many objects (``nan`` when no joint qualifies)."""

    n_joints: int
    type_accuracy: float
    parent_accuracy: float
    n_movable: int
    median_axis_error_deg: float
    median_axis_error_unsigned_deg: float
    n_revolute: int
    median_hinge_distance_m: float
    median_prismatic_upper_error_m: float
    median_revolute_upper_error_rad: float


def _median(values: list[float]) -> float:
    v = [x for x in values if np.isfinite(x)]
    return float(np.median(v)) if v else NAN


def joint_summary(comparisons: Iterable[JointComparison]) -> JointSummary:
    """Pool joint comparisons: type and parent accuracy over all true joints (missing = wrong); axis-error medians
    over true movable joints whose estimate is movable; hinge medians over revolute-revolute pairs."""
    c = list(comparisons)
    movable = [x for x in c if x.true_type != "fixed"]
    revolute = [x for x in c if x.true_type == "revolute"]
    return JointSummary(
        n_joints=len(c),
        type_accuracy=float(np.mean([x.type_correct for x in c])) if c else NAN,
        parent_accuracy=float(np.mean([x.parent_correct for x in c])) if c else NAN,
        n_movable=len(movable),
        median_axis_error_deg=_median([x.axis_error_deg for x in movable]),
        median_axis_error_unsigned_deg=_median([x.axis_error_unsigned_deg for x in movable]),
        n_revolute=len(revolute),
        median_hinge_distance_m=_median([x.hinge_distance_m for x in revolute]),
        median_prismatic_upper_error_m=_median([x.upper_error for x in c if x.true_type == "prismatic"]),
        median_revolute_upper_error_rad=_median([x.upper_error for x in revolute]),
    )
