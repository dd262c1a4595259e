"""Interpenetration volume between shapes, parts and objects (manifold3d booleans, exact for boxes).

Touching shapes have zero overlap; ``OVERLAP_TOLERANCE`` is the volume below which two solids are
said not to overlap (10 mm^3: a 1 mm penetration over 1 cm^2 already exceeds it).
"""

from __future__ import annotations

import numpy as np

from .description import Shape, ShapeKind
from .model import ArticulatedObject
from .scanner.meshes import FACET_TOLERANCE

__all__ = ["OVERLAP_TOLERANCE", "shape_solid", "overlap_volume", "part_overlaps", "object_overlap"]

OVERLAP_TOLERANCE = 1e-8  # m^3


def shape_solid(shape: Shape, T_world_part: np.ndarray):
    """A ``manifold3d.Manifold`` of ``shape`` placed by ``T_world_part`` (4, 4)."""
    import manifold3d as m3d

    T = T_world_part @ shape.T_link_shape
    if shape.kind is ShapeKind.BOX:
        solid = m3d.Manifold.cube(tuple(shape.size), center=True)
    else:
        n = int(max(16, np.ceil(np.pi / np.arccos(1 - FACET_TOLERANCE / shape.radius))))
        solid = m3d.Manifold.cylinder(shape.length, shape.radius, shape.radius, n, center=True)
    return solid.transform(T[:3, :].tolist())


def _aabb(shape: Shape, T: np.ndarray) -> np.ndarray:
    c = shape.corners() @ T[:3, :3].T + T[:3, 3]
    return np.array([c.min(0), c.max(0)])


def overlap_volume(a: Shape, T_a: np.ndarray, b: Shape, T_b: np.ndarray) -> float:
    """Volume (m^3) of the intersection of two placed shapes."""
    ba, bb = _aabb(a, T_a), _aabb(b, T_b)
    if np.any(ba[1] <= bb[0]) or np.any(bb[1] <= ba[0]):
        return 0.0
    return float((shape_solid(a, T_a) ^ shape_solid(b, T_b)).volume())


def part_overlaps(obj: ArticulatedObject, q: dict[int, float] | None = None,
                  tol: float = OVERLAP_TOLERANCE) -> list[tuple[int, int, float]]:
    """[(part a, part b, volume m^3)] of the parts of ``obj`` that interpenetrate at joint values ``q``."""
    placed = [(p.id, s, obj.T_object_part_at(p.id, q)) for p in obj.parts for s in p.shapes]
    out: dict[tuple[int, int], float] = {}
    for i in range(len(placed)):
        for j in range(i + 1, len(placed)):
            (pa, sa, Ta), (pb, sb, Tb) = placed[i], placed[j]
            if pa == pb:
                continue
            v = overlap_volume(sa, Ta, sb, Tb)
            if v > tol:
                key = (min(pa, pb), max(pa, pb))
                out[key] = out.get(key, 0.0) + v
    return [(a, b, v) for (a, b), v in sorted(out.items())]


def _world_boxes(obj: ArticulatedObject) -> list[tuple[Shape, np.ndarray, np.ndarray]]:
    out = []
    for p in obj.parts:
        T = obj.T_world_object @ p.T_object_part
        out += [(s, T, _aabb(s, T)) for s in p.shapes]
    return out


def object_overlap(a: ArticulatedObject, b: ArticulatedObject) -> float:
    """Total intersection volume (m^3) between the closed objects ``a`` and ``b`` in the world."""
    sa_all, sb_all = _world_boxes(a), _world_boxes(b)
    lo_a = np.min([bb[0] for _, _, bb in sa_all], axis=0)
    hi_a = np.max([bb[1] for _, _, bb in sa_all], axis=0)
    total = 0.0
    for sb, Tb, bb in sb_all:
        if np.any(bb[1] <= lo_a) or np.any(hi_a <= bb[0]):
            continue
        for sa, Ta, ba in sa_all:
            if np.any(ba[1] <= bb[0]) or np.any(bb[1] <= ba[0]):
                continue
            total += float((shape_solid(sa, Ta) ^ shape_solid(sb, Tb)).volume())
    return total
