"""2D floor footprints (shapely, world xy, metres) used by the composer and the camera path.

* ``footprint``: the closed object's bounding rectangle;
* ``sweep``: the convex hulls of every movable part (and the parts it carries) sampled across
  [lower, upper] -- the floor a fully opening drawer/door needs;
* ``clearance``: for an articulated object, a rectangle ``front_clearance`` deep in front of the
  object (beyond its closed front) as wide as the object -- where a mobile robot stands;
* ``handle_reach``: the path of every handle across its joint range, grown by ``robot_reach`` and
  kept in front of the object -- where a robot holding the handle while it opens may be.
"""

from __future__ import annotations

import numpy as np
from shapely.affinity import affine_transform
from shapely.geometry import MultiPoint, Polygon, box
from shapely.ops import unary_union

from .model import ArticulatedObject
from .description import transform_points

__all__ = ["footprint", "sweep", "clearance", "handle_reach", "keepout", "subtree_parts", "room_polygon"]

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


def handle_reach(obj: ArticulatedObject, reach: float, samples: int = _SWEEP_SAMPLES) -> Polygon:
    """Floor within ``reach`` m of any handle's path over its joint's range, in front of the object."""
    if reach <= 0:
        return Polygon()
    lo, hi = obj.bounds()
    zones = []
    for j in obj.joints:
        if not j.movable or j.handle is None:
            continue
        pts = np.array([obj.T_object_part_at(j.handle, {j.child: q})[:3, 3]
                        for q in np.linspace(j.lower, j.upper, samples)])
        zone = MultiPoint(pts[:, :2]).convex_hull.buffer(reach)
        front = box(hi[0], lo[1] - 2 * reach, hi[0] + 2 * reach + 2.0, hi[1] + 2 * reach)
        local = zone.intersection(front)
        if not local.is_empty:
            T = obj.T_world_object
            zones.append(affine_transform(local, [T[0, 0], T[0, 1], T[1, 0], T[1, 1], T[0, 3], T[1, 3]]))
    return unary_union(zones) if zones else Polygon()


def keepout(obj: ArticulatedObject, depth: float, reach: float = 0.0) -> Polygon:
    """Footprint, sweep, clearance and handle reach together: the floor no other object may occupy."""
    return unary_union([footprint(obj), sweep(obj), clearance(obj, depth), handle_reach(obj, reach)])


def room_polygon(room_size) -> Polygon:
    """The inner floor of a room centred on the origin."""
    lx, ly = room_size
    return box(-lx / 2, -ly / 2, lx / 2, ly / 2)
