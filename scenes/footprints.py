"""2D floor footprints (shapely, world xy, metres) used by the composer and the camera path.

* ``footprint``: the closed object's bounding rectangle;
* ``sweep``: the convex hulls of every movable part (and the parts it carries) sampled across
  [lower, upper] -- the floor a fully opening drawer/door needs;
* ``clearance``: for an articulated object, a rectangle ``front_clearance`` deep in front of the
  object (beyond its closed front) as wide as the object -- where a mobile robot stands.
"""

from __future__ import annotations

import numpy as np
from shapely.geometry import MultiPoint, Polygon, box
from shapely.ops import unary_union

from .model import ArticulatedObject
from .poses import transform_points

__all__ = ["footprint", "sweep", "clearance", "keepout", "subtree_parts"]

_SWEEP_SAMPLES = 9


def _world_xy(obj: ArticulatedObject, pts_object: np.ndarray) -> np.ndarray:
    return transform_points(obj.T_world_object, pts_object)[:, :2]


def footprint(obj: ArticulatedObject) -> Polygon:
    """The closed object's bounding rectangle on the floor (world xy)."""
    lo, hi = obj.bounds()
    rect = np.array([[lo[0], lo[1], 0], [hi[0], lo[1], 0], [hi[0], hi[1], 0], [lo[0], hi[1], 0]])
    return Polygon(_world_xy(obj, rect))


def subtree_parts(obj: ArticulatedObject, part_id: int) -> list[int]:
    """``part_id`` and every part below it in the part tree."""
    out, stack = [], [part_id]
    while stack:
        p = stack.pop()
        out.append(p)
        stack += [j.child for j in obj.joints if j.parent == p]
    return out


def sweep(obj: ArticulatedObject, samples: int = _SWEEP_SAMPLES) -> Polygon:
    """Union over movable joints of the xy convex hull of the moving subtree across its range."""
    hulls = []
    for j in obj.joints:
        if not j.movable:
            continue
        pts = []
        for q in np.linspace(j.lower, j.upper, samples):
            for pid in subtree_parts(obj, j.child):
                T = obj.T_object_part_at(pid, {j.child: q})
                for s in obj.part(pid).shapes:
                    pts.append(transform_points(T, s.corners()))
        hulls.append(MultiPoint(_world_xy(obj, np.vstack(pts))).convex_hull)
    return unary_union(hulls) if hulls else Polygon()


def clearance(obj: ArticulatedObject, depth: float) -> Polygon:
    """Free-floor rectangle ``depth`` deep in front of an articulated object (empty if none moves)."""
    if not any(j.movable for j in obj.joints):
        return Polygon()
    lo, hi = obj.bounds()
    rect = np.array([[hi[0], lo[1], 0], [hi[0] + depth, lo[1], 0], [hi[0] + depth, hi[1], 0], [hi[0], hi[1], 0]])
    return Polygon(_world_xy(obj, rect))


def keepout(obj: ArticulatedObject, depth: float) -> Polygon:
    """Footprint, sweep and clearance together: the floor no other object may occupy."""
    return unary_union([footprint(obj), sweep(obj), clearance(obj, depth)])


def room_polygon(room_size) -> Polygon:
    """The inner floor of a room centred on the origin."""
    lx, ly = room_size
    return box(-lx / 2, -ly / 2, lx / 2, ly / 2)
