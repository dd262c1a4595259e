"""Reconstruction metrics of the paper (Sec. IV) and of articulated-object estimation, against truth.json.

Geometry (both in the true object's *unit box*, :mod:`recon.metrics.unit_box`):
    object_chamfer   symmetric mean point-to-surface distance of 10k surface samples per side
    object_iou       IoU of solid occupancy on the truth's 32^3 voxel lattice
Kinematic structure:
    contact_edge_ap  average precision of estimated contact edges (ranked by Eq. 1 score) against the
                     true undirected contact edges; mean_average_precision = the per-category mAP
Joints (matched by child part id; a part recon split off a labelled part takes the id of the true part
holding its centre, split_parts.py):
    compare_joints   type, sign-aware axis angle (deg) and unsigned, hinge-line distance near the part (m),
                     limit errors
Scene:
    read_truth("truth.json") -> TruthScene
    estimate_from_reconstruction(obj, rec.config) -> ObjectEstimate     (the baseline builds ObjectEstimate too)
    evaluate_scene(truth, estimates, MetricsConfig()) -> SceneMetrics (per object; .chamfer, .iou means)
    joint_summary(comparisons) -> JointSummary (type / parent accuracy, median axis / hinge / limit errors)
    reconstruction_metrics_doc(truth, rec, MetricsConfig()) -> the metrics.json document (write_metrics_json)
Diagnostics (not in the paper):
    evaluate_parts(truth_object, estimate) -> PartMetrics per true part (Chamfer, IoU, centre error)

Pure numpy / scipy / trimesh (manifold3d for unions); no simulator.
"""

from recon.metrics.chamfer import (DEFAULT_CHAMFER_SAMPLES, chamfer_distance, distance_to_union_surface,
                                   object_chamfer, surface_samples)
from recon.metrics.errors import EstimateError, MetricsError, TruthFormatError
from recon.metrics.evaluation import (JointSummary, MetricsConfig, ObjectMetrics, ObjectStatus, SceneMetrics,
                                      evaluate_object, evaluate_scene, joint_summary)
from recon.metrics.joint_errors import (JointComparison, JointMatch, axis_angle_deg, compare_joints,
                                        line_distance_near, unsigned_axis_angle_deg)
from recon.metrics.metrics_json import METRICS_FORMAT, metrics_doc, reconstruction_metrics_doc, write_metrics_json
from recon.metrics.kinematic_ap import (average_precision, contact_edge_ap, mean_average_precision,
                                        undirected_scores)
from recon.metrics.objects import ObjectEstimate, estimate_from_reconstruction
from recon.metrics.part_errors import PartMetrics, PartStatus, evaluate_parts
from recon.metrics.solids import bounds_in_frame, grown, union_mesh
from recon.metrics.truth import TRUTH_FORMAT, TruthObject, TruthPart, TruthScene, read_truth, truth_from_dict
from recon.metrics.unit_box import UnitBox, unit_box_from_truth
from recon.metrics.voxel_iou import DEFAULT_VOXEL_RESOLUTION, object_iou, occupied_voxels, voxel_iou

__all__ = [
    "DEFAULT_CHAMFER_SAMPLES", "chamfer_distance", "distance_to_union_surface", "object_chamfer", "surface_samples",
    "MetricsError", "TruthFormatError", "EstimateError",
    "MetricsConfig", "ObjectStatus", "ObjectMetrics", "SceneMetrics", "JointSummary", "evaluate_object",
    "evaluate_scene", "joint_summary",
    "JointComparison", "JointMatch", "axis_angle_deg", "unsigned_axis_angle_deg", "line_distance_near",
    "compare_joints",
    "average_precision", "contact_edge_ap", "mean_average_precision", "undirected_scores",
    "ObjectEstimate", "estimate_from_reconstruction",
    "METRICS_FORMAT", "metrics_doc", "reconstruction_metrics_doc", "write_metrics_json",
    "PartMetrics", "PartStatus", "evaluate_parts",
    "union_mesh", "bounds_in_frame", "grown",
    "TRUTH_FORMAT", "TruthScene", "TruthObject", "TruthPart", "read_truth", "truth_from_dict",
    "UnitBox", "unit_box_from_truth",
    "DEFAULT_VOXEL_RESOLUTION", "occupied_voxels", "voxel_iou", "object_iou",
]
