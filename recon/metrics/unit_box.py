"""The normalised "unit box" of a true object, in which Chamfer distance and voxel IoU are measured.

The paper (Sec. IV) normalises objects to a unit box. Here *both* the truth and the estimate of one
object are expressed in the same frame, fixed by the truth alone:

- axes: the true object's frame (x = front normal, z up), so voxels are aligned with the object;
- origin: the centre of the axis-aligned bounds of the true object's shapes in that frame;
- scale: the largest extent of those bounds (metres), so the truth fits in ``[-0.5, 0.5]^3`` and
  touches both faces along its longest axis.

A distance of 0.05 in the unit box is therefore 5% of the true object's largest dimension.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from recon.metrics.errors import EstimateError
from recon.metrics.solids import bounds_in_frame
from recon.primitive import Primitive

__all__ = ["UnitBox", "unit_box_from_truth"]


@dataclass(frozen=True)
class UnitBox:
    """Normalisation frame of one object.

    T_world_box : (4, 4) float — box frame (origin at the truth's bounds centre, axes of the object)
    scale : float, metres — the truth's largest extent; unit coordinates are ``metres / scale``
    """

    T_world_box: np.ndarray
    scale: float

    def __post_init__(self) -> None:
        T = np.array(self.T_world_box, dtype=np.float64)
        if T.shape != (4, 4) or not np.all(np.isfinite(T)):
            raise EstimateError(f"UnitBox: T_world_box must be a finite (4, 4) pose, got shape {T.shape}")
        if not (np.isfinite(self.scale) and self.scale > 0):
            raise EstimateError(f"UnitBox: scale must be > 0 metres, got {self.scale}")
        T.setflags(write=False)
        object.__setattr__(self, "T_world_box", T)
        object.__setattr__(self, "scale", float(self.scale))

    def to_unit(self, points_world: np.ndarray) -> np.ndarray:
        """(n, 3) world points (metres) -> (n, 3) unit-box coordinates (dimensionless)."""
        p = np.asarray(points_world, dtype=np.float64).reshape(-1, 3)
        return (p - self.T_world_box[:3, 3]) @ self.T_world_box[:3, :3] / self.scale

    def to_world(self, points_unit: np.ndarray) -> np.ndarray:
        """(n, 3) unit-box coordinates -> (n, 3) world points (metres)."""
        q = np.asarray(points_unit, dtype=np.float64).reshape(-1, 3)
        return q * self.scale @ self.T_world_box[:3, :3].T + self.T_world_box[:3, 3]


def unit_box_from_truth(truth: Sequence[Primitive], T_world_object: np.ndarray) -> UnitBox:
    """The unit box of a true object from its shapes and its frame.

    truth : the true object's primitives (world frame)
    T_world_object : (4, 4) float — the true object frame (only its rotation is used)
    """
    T_obj = np.asarray(T_world_object, dtype=np.float64)
    lo, hi = bounds_in_frame(truth, T_obj)
    T = T_obj.copy()
    T[:3, 3] = T_obj[:3, :3] @ ((lo + hi) / 2.0) + T_obj[:3, 3]
    return UnitBox(T, float(np.max(hi - lo)))
