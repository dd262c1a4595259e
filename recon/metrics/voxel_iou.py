"""Voxel IoU between a true and an estimated object on the truth's 32^3 unit-box lattice (paper Sec. IV).

Lattice: voxels of edge ``1 / resolution`` in the truth's unit box (:mod:`recon.metrics.unit_box`),
aligned so that the true object spans exactly ``resolution`` voxels along its longest axis
(voxel faces at ``-0.5 + k / resolution``). The lattice is not cut at the truth's box: an estimate that
sticks out keeps its outside voxels (they count in the union), up to ``LATTICE_HALF_WIDTH`` unit boxes
from the centre, beyond which anything is so wrong that the IoU is ~0 anyway.

Occupancy is *solid* (filled, not only the surface), in two steps:

1. a voxel is occupied when it overlaps the interior of one of the side's primitives, i.e. its centre
   lies inside the primitive grown by (just under) half a voxel along the primitive's own axes. That is
   exact for boxes aligned with the lattice (a box whose faces lie on voxel faces occupies exactly the
   voxels inside it) and slightly under-generous for rotated ones. Thin parts (cabinet panels, drawer
   walls thinner than a voxel) therefore still occupy a voxel layer instead of vanishing;
2. empty voxels enclosed by occupied ones (not 6-connected to the outside) are filled
   (``scipy.ndimage.binary_fill_holes``), as a solid voxelizer does with a closed mesh: the inside of a
   closed cabinet (doors and drawers shut) is part of its solid, the space under a table is not.

Why step 2: without it a hollow cabinet is a few one-voxel panel layers (18 mm panels, 20-60 mm voxels),
and a sub-voxel shift of a perfect estimate flips whole layers, so IoU would measure voxel aliasing
instead of shape.

    IoU = |occ(truth) & occ(estimate)| / |occ(truth) | occ(estimate)|
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
from scipy import ndimage

from recon.metrics.errors import EstimateError
from recon.metrics.solids import grown
from recon.primitive import Primitive
from recon.metrics.unit_box import UnitBox

__all__ = ["DEFAULT_VOXEL_RESOLUTION", "LATTICE_HALF_WIDTH", "occupied_voxels", "voxel_iou", "object_iou"]

#: Voxels along the truth's longest axis (the paper's 32^3 grid).
DEFAULT_VOXEL_RESOLUTION = 32
#: Half width of the lattice, in unit boxes, beyond which estimate voxels are dropped.
LATTICE_HALF_WIDTH = 4.0
#: Fraction of a voxel edge by which the half-voxel growth is shortened, so that a voxel that only
#: touches a primitive's face (distance exactly half a voxel) is not counted as overlapping it.
_TOUCH_EPS = 1e-6


def occupied_voxels(primitives: Sequence[Primitive], box: UnitBox,
                    resolution: int = DEFAULT_VOXEL_RESOLUTION) -> np.ndarray:
    """Integer indices of the lattice voxels overlapped by the union of ``primitives``.

    Voxel ``(i, j, k)`` has its centre at ``-0.5 + ((i, j, k) + 0.5) / resolution`` in the unit box.
    Enclosed empty voxels are filled (module docstring).
    returns : (m, 3) int64, unique rows, sorted lexicographically
    """
    if resolution < 1:
        raise EstimateError(f"occupied_voxels: resolution must be >= 1, got {resolution}")
    h = 1.0 / resolution
    k_cap = int(np.ceil(LATTICE_HALF_WIDTH * resolution))
    grow_m = (0.5 - _TOUCH_EPS) * h * box.scale
    chunks = []
    for prim in primitives:
        unit_verts = box.to_unit(prim.to_trimesh().vertices)
        lo = unit_verts.min(axis=0) - h
        hi = unit_verts.max(axis=0) + h
        k_lo = np.clip(np.floor((lo + 0.5) / h - 0.5).astype(np.int64), -k_cap, k_cap)
        k_hi = np.clip(np.ceil((hi + 0.5) / h - 0.5).astype(np.int64), -k_cap, k_cap)
        axes = [np.arange(a, b + 1, dtype=np.int64) for a, b in zip(k_lo, k_hi)]
        idx = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
        centres_unit = -0.5 + (idx + 0.5) * h
        inside = grown(prim, grow_m).contains(box.to_world(centres_unit))
        chunks.append(idx[inside])
    if not chunks or not any(len(c) for c in chunks):
        return np.zeros((0, 3), dtype=np.int64)
    return _filled(np.unique(np.concatenate(chunks, axis=0), axis=0))


def _filled(voxels: np.ndarray) -> np.ndarray:
    """Occupied voxels plus the empty voxels they enclose. voxels : (m, 3) int -> (m', 3) int, sorted."""
    lo = voxels.min(axis=0) - 1
    dense = np.zeros(voxels.max(axis=0) - lo + 2, dtype=bool)
    dense[tuple((voxels - lo).T)] = True
    return np.argwhere(ndimage.binary_fill_holes(dense)) + lo


def _keys(voxels: np.ndarray) -> np.ndarray:
    """(m, 3) int voxel indices -> (m,) int64 scalar keys (indices are bounded by the lattice cap)."""
    v = np.asarray(voxels, dtype=np.int64).reshape(-1, 3)
    off = 1 << 20
    return ((v[:, 0] + off) << 42) | ((v[:, 1] + off) << 21) | (v[:, 2] + off)


def voxel_iou(voxels_a: np.ndarray, voxels_b: np.ndarray) -> float:
    """Intersection over union of two sets of voxel indices.

    voxels_a, voxels_b : (m, 3) int — occupied voxels on the same lattice
    returns : float in [0, 1]; 1.0 when both are empty (nothing to disagree on)
    """
    a = np.unique(_keys(voxels_a))
    b = np.unique(_keys(voxels_b))
    union = np.union1d(a, b).size
    if union == 0:
        return 1.0
    return float(np.intersect1d(a, b, assume_unique=True).size / union)


def object_iou(truth: Sequence[Primitive], estimate: Sequence[Primitive], box: UnitBox,
               resolution: int = DEFAULT_VOXEL_RESOLUTION) -> float:
    """Voxel IoU of two objects on the truth's lattice (see the module docstring).

    truth, estimate : primitives in the world frame
    box : the truth's :class:`UnitBox`
    """
    if not estimate:
        raise EstimateError("object_iou: the estimate has no primitives")
    return voxel_iou(occupied_voxels(truth, box, resolution), occupied_voxels(estimate, box, resolution))
