"""Solid unions of primitives, as the geometric metrics see them: surface mesh, bounds, growth.

Both sides of a comparison are sequences of :class:`recon.primitive.Primitive` in the world frame
(``size`` = box extents | cylinder ``(2r, 2r, length)`` along local z | sphere ``(2r,)*3``): the truth
from ``truth.json`` ``shapes`` and the estimate from a reconstruction (one primitive per part) or the
object-level baseline (a whole scaled template).
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
import trimesh

from recon.metrics.errors import EstimateError
from recon.primitive import Primitive

__all__ = ["union_mesh", "bounds_in_frame", "grown"]


def union_mesh(primitives: Sequence[Primitive]) -> trimesh.Trimesh:
    """Closed mesh (world frame, metres) of the union of ``primitives`` (manifold3d booleans).

    Faces hidden inside another primitive, or shared by two touching ones, are removed, so surface
    samples lie on the outer surface of the solid and on the walls of its cavities (the inside of a
    hollow cabinet), never on internal seams.
    """
    meshes = [p.to_trimesh() for p in primitives]
    if not meshes:
        raise EstimateError("union_mesh: no primitives given")
    if len(meshes) == 1:
        return meshes[0]
    return trimesh.boolean.union(meshes, engine="manifold")


def bounds_in_frame(primitives: Sequence[Primitive], T_world_frame: np.ndarray) -> np.ndarray:
    """Axis-aligned bounds of the primitives' mesh vertices, expressed in a frame.

    T_world_frame : (4, 4) float
    returns : (2, 3) float, metres — ``[min, max]`` corners in that frame
    """
    T = np.asarray(T_world_frame, dtype=np.float64)
    if not primitives:
        raise EstimateError("bounds_in_frame: no primitives given")
    verts = np.concatenate([p.to_trimesh().vertices for p in primitives], axis=0)
    local = (verts - T[:3, 3]) @ T[:3, :3]
    return np.stack([local.min(axis=0), local.max(axis=0)])


def grown(primitive: Primitive, margin: float) -> Primitive:
    """``primitive`` with every face moved outward by ``margin`` metres (box extents + 2 margin,
    cylinder radius and half length + margin, sphere radius + margin)."""
    return Primitive(primitive.kind, primitive.size + 2.0 * float(margin), primitive.T_world_part)

