"""Per-part diagnostics: how well each true part is reproduced by the estimate's primitives of that part.

Not a paper metric: it tells *which* parts (labels) spoil an object's Chamfer or IoU, so a benchmark can
point at the stage to fix (a part whose own geometry is off points at fitting; parts that are right alone
but wrong together point at refinement or support). For each true part with an estimate (matched by part
id, :attr:`ObjectEstimate.part_ids`):

- ``chamfer`` and ``iou``: as :func:`object_chamfer` / :func:`object_iou` but restricted to the part, in
  the *object's* unit box and lattice (so numbers are comparable with the object's);
- ``centre_error_m``: distance between the volume-weighted centres of truth and estimate, metres;
- ``size_ratio``: estimated / true total volume of the part.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np

from recon.metrics.chamfer import object_chamfer
from recon.metrics.objects import ObjectEstimate
from recon.metrics.truth import TruthObject
from recon.metrics.unit_box import unit_box_from_truth
from recon.metrics.voxel_iou import DEFAULT_VOXEL_RESOLUTION, object_iou
from recon.primitive import volume_weighted_centre

__all__ = ["PartStatus", "PartMetrics", "evaluate_parts"]

NAN = float("nan")


class PartStatus(enum.Enum):
    OK = "ok"
    MISSING = "missing"        # no estimated primitive carries this part id


@dataclass(frozen=True)
class PartMetrics:
    """Diagnostics of one true part (``nan`` when missing)."""

    part_id: int
    label: str
    status: PartStatus
    chamfer: float
    iou: float
    centre_error_m: float
    size_ratio: float


def evaluate_parts(truth: TruthObject, estimate: ObjectEstimate, chamfer_samples: int = 2000,
                   resolution: int = DEFAULT_VOXEL_RESOLUTION, seed: int = 0) -> tuple[PartMetrics, ...]:
    """Per-part diagnostics of one object (see the module docstring); empty when the estimate has no
    part ids (an object-level method)."""
    if not estimate.part_ids:
        return ()
    box = unit_box_from_truth(truth.primitives, truth.T_world_object)
    rows = []
    for k, part in enumerate(truth.parts):
        est = [p for p, i in zip(estimate.primitives, estimate.part_ids) if i == part.id]
        if not est:
            rows.append(PartMetrics(part.id, part.label, PartStatus.MISSING, NAN, NAN, NAN, NAN))
            continue
        rows.append(PartMetrics(
            part.id, part.label, PartStatus.OK,
            object_chamfer(part.primitives, est, box, chamfer_samples, seed + 2 * k),
            object_iou(part.primitives, est, box, resolution),
            float(np.linalg.norm(volume_weighted_centre(est) - volume_weighted_centre(part.primitives))),
            float(sum(p.volume for p in est) / sum(p.volume for p in part.primitives))))
    return tuple(rows)
