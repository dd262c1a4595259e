"""Triangle meshes of a scene's shapes (world frame), each tagged with its object and part id.

Cylinders are faceted finely enough that a facet is within ``FACET_TOLERANCE`` of the true surface,
so a scanned point lies on its primitive within that tolerance.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import trimesh

from ..description import Shape, ShapeKind
from ..model import Scene

__all__ = ["FACET_TOLERANCE", "TaggedMesh", "scene_meshes", "shape_mesh"]

FACET_TOLERANCE = 1e-4  # m, max distance between a cylinder facet and the true cylinder


@dataclass(frozen=True, eq=False)
class TaggedMesh:
    """``vertices`` (v, 3) float64 world metres, ``faces`` (f, 3) int; ``object_id``/``part_id`` (-1 =
    background: floor or wall); ``name``: the URDF link name."""

    vertices: np.ndarray
    faces: np.ndarray
    object_id: int
    part_id: int
    name: str


def _sections(radius: float) -> int:
    return int(max(16, np.ceil(np.pi / np.arccos(max(1.0 - FACET_TOLERANCE / max(radius, 1e-6), -1.0)))))


def shape_mesh(shape: Shape, T_world_part: np.ndarray) -> trimesh.Trimesh:
    """The world-frame mesh of ``shape`` on a part at ``T_world_part`` (4, 4)."""
    T = T_world_part @ shape.T_link_shape
    if shape.kind is ShapeKind.BOX:
        return trimesh.creation.box(extents=shape.size, transform=T)
    return trimesh.creation.cylinder(radius=shape.radius, height=shape.length,
                                     sections=_sections(shape.radius), transform=T)


def scene_meshes(scene: Scene, q: dict[str, float] | None = None, floor: bool = True) -> list[TaggedMesh]:
    """One mesh per part (its shapes concatenated), plus walls and the floor when ``floor``.

    ``q``: optional joint values by URDF joint name (default closed).
    """
    out = []
    for obj in scene.objects:
        qo = {}
        for j in obj.joints:
            if q and obj.joint_name(j) in q:
                qo[j.child] = float(q[obj.joint_name(j)])
        for part in obj.parts:
            T = obj.T_world_object @ obj.T_object_part_at(part.id, qo)
            m = trimesh.util.concatenate([shape_mesh(s, T) for s in part.shapes])
            out.append(TaggedMesh(np.asarray(m.vertices), np.asarray(m.faces), obj.id, part.id, obj.link(part)))
    if floor:
        for w in scene.walls:
            m = trimesh.creation.box(extents=w.size, transform=w.T_world_wall)
            out.append(TaggedMesh(np.asarray(m.vertices), np.asarray(m.faces), -1, -1, w.name))
        lx, ly = scene.room_size / 2 + 0.2
        v = np.array([[-lx, -ly, 0], [lx, -ly, 0], [lx, ly, 0], [-lx, ly, 0]], float)
        out.append(TaggedMesh(v, np.array([[0, 1, 2], [0, 2, 3]]), -1, -1, "floor"))
    return out
