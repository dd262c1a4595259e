"""Clearance: no two links of the reconstructed scene interpenetrate at q = 0.

Fitted primitives of neighbouring parts overlap by a few millimetres on a noisy scan (a door's back
face inside its carcass, a cabinet's back inside the fitted wall, a chair leg reaching into its seat).
Inside one rigid body that is harmless, but an engine that loads ``scene.urdf`` pushes overlapping
links apart at once (a door swings open, a drawer slides out). This stage cuts the shapes so that
every pair of links is at least separated (touching is allowed): the URDF writer then shrinks the
collision shapes of moving parts by ``UrdfConfig.collision_clearance``, so a moving part starts that
far from everything around it.

Who yields, for each overlapping pair of shapes on two links:
    a fitted wall        moves back (away from the room) until it clears the other shape;
    moving vs static     when the moving shape is a board (a front), the static shape by at most two
                         of the board's thicknesses (a carcass front fitted proud, cut back behind an
                         overlay front, which keeps its whole fitted board; a deeper overlap is a misfit
                         of the carcass, not an edge hidden behind a front); else the moving part's
                         shape through its thickness only (thinned from behind: the faces the camera
                         saw stay where they were measured); only then the moving shape along any
                         axis, and last the static one by any depth;
    same rigid group     the tree child (a leg under its seat, a handle on its front), else the smaller;
    two moving groups    the one hanging from the other, else the smaller.
A shape yields by moving one face inward along one of its own axes: the side and axis that need the
smallest cut, never leaving less than ``min_keep_fraction`` of that extent. When the yielding shape
cannot, the other one is tried; a pair neither can clear is reported with a warning naming both links.

Overlap is judged by the separating-axis test on the shapes' boxes (a cylinder or sphere by its
bounding box in its own frame, so the test is conservative for them): :func:`separation` is a lower
bound of the true distance (negative = penetration depth along the best of the 15 axes).

Frames: every shape is a :class:`recon.primitive.Primitive` in the world frame (z up, metres); a wall
is a :class:`recon.walls.Wall` (x = normal into the room).
"""

from __future__ import annotations

import dataclasses
import logging
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from recon.config import ClearanceConfig
from recon.model import JointType, ObjectReconstruction
from recon.primitive import Primitive, PrimitiveKind
from recon.walls import Wall

__all__ = ["separation", "cleared_scene", "links_in_contact", "scene_shapes", "SceneShape"]

log = logging.getLogger(__name__)


def _frame(p: Primitive) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(R (3, 3) world axes as columns, centre (3,), half extents (3,)) of the shape's box."""
    return p.T_world_part[:3, :3], p.T_world_part[:3, 3], np.asarray(p.size, float) / 2.0


def _radius(R: np.ndarray, h: np.ndarray, n: np.ndarray) -> float:
    """Half the extent of the box (R, h) projected on the unit axis ``n`` (3,)."""
    return float(np.abs(R.T @ n) @ h)


def separation(a: Primitive, b: Primitive) -> float:
    """Separating-axis distance (m) between the boxes of ``a`` and ``b``: the largest gap between their
    projections over the 15 axes (faces of both, cross products of their edges). Positive: a lower bound
    of their distance; negative: minus their penetration depth."""
    Ra, ca, ha = _frame(a)
    Rb, cb, hb = _frame(b)
    axes = [Ra[:, i] for i in range(3)] + [Rb[:, i] for i in range(3)]
    for i in range(3):
        for k in range(3):
            n = np.cross(Ra[:, i], Rb[:, k])
            s = np.linalg.norm(n)
            if s > 1e-9:
                axes.append(n / s)
    d = cb - ca
    return max(abs(float(d @ n)) - _radius(Ra, ha, n) - _radius(Rb, hb, n) for n in axes)


def _aabbs(prims: list[Primitive]) -> np.ndarray:
    """(n, 2, 3) world axis-aligned bounds of the shapes' boxes."""
    out = np.empty((len(prims), 2, 3))
    for i, p in enumerate(prims):
        R, c, h = _frame(p)
        r = np.abs(R) @ h
        out[i, 0], out[i, 1] = c - r, c + r
    return out


@dataclass(frozen=True)
class SceneShape:
    """One shape of one link: ``link`` (URDF name), ``index`` into the link's shapes, ``prim`` (world),
    ``group`` (the movable part it moves with: (object index, part id), or None = static), ``parent``
    (the link's tree parent link, None for a root or a wall), ``wall`` (a fitted wall)."""

    link: str
    index: int
    prim: Primitive
    group: tuple | None
    parent: str | None
    wall: bool = False


def scene_shapes(objects, walls) -> list[SceneShape]:
    """Every shape of the scene's links in URDF order (objects' parts, then walls)."""
    out = []
    for k, obj in enumerate(objects):
        parent = {j.child_part_id: j.parent_part_id for j in obj.joints}
        movable = {j.child_part_id for j in obj.joints if j.type is not JointType.FIXED}

        def group(pid):
            while pid is not None:
                if pid in movable:
                    return (k, pid)
                pid = parent.get(pid)
            return None

        for part in obj.parts:
            pp = parent.get(part.part_id)
            plink = obj.part(pp).link if pp is not None else None
            for i, s in enumerate(part.solids):
                out.append(SceneShape(part.link, i, s, group(part.part_id), plink))
    for w in walls:
        out.append(SceneShape(w.name, 0, Primitive(PrimitiveKind.BOX, w.size, w.T_world_wall), None, None, True))
    return out


def _yielders(a: SceneShape, b: SceneShape, groups_parent: dict) -> list[tuple[SceneShape, SceneShape]]:
    """[(yielding, other), ...] in the order to try (see the module docstring)."""
    if a.wall != b.wall:
        return [(a, b) if a.wall else (b, a)]
    if a.group != b.group:
        if a.group is None or b.group is None:
            first = a if b.group is None else b
        elif _hangs_from(a.group, b.group, groups_parent):
            first = a
        elif _hangs_from(b.group, a.group, groups_parent):
            first = b
        else:
            first = a if (a.prim.volume, a.link) < (b.prim.volume, b.link) else b
    elif a.parent == b.link:
        first = a
    elif b.parent == a.link:
        first = b
    else:
        first = a if (a.prim.volume, a.link) < (b.prim.volume, b.link) else b
    second = b if first is a else a
    return [(first, second)] if second.wall else [(first, second), (second, first)]


BOARD_ASPECT = 0.25
"""A shape whose thinnest extent is at most this fraction of its middle one is a board (a door or drawer
front), for :func:`_attempts`."""


def _attempts(order: list[tuple[SceneShape, SceneShape]]) -> list[tuple[SceneShape, SceneShape, tuple[int, ...], float]]:
    """[(yielding, other, axes it may be cut along, deepest cut m), ...]: a moving shape against a static one:
    when the moving shape is a board (a front), first the static shape is cut by at most two of the board's
    thicknesses (a carcass front fitted from noisy points, reaching behind the front: the front keeps its whole
    fitted board, whose back the robot may pass once it is open); then the moving shape is thinned through its
    thickness (from behind: its seen faces stay where they were measured), then cut along any axis, and last
    the static one by any depth."""
    every, inf = (0, 1, 2), float("inf")
    if len(order) == 2 and order[0][0].group is not None and order[0][1].group is None:
        y, o = order[0]
        size = np.sort(np.asarray(y.prim.size, float))
        thin = int(np.argmin(y.prim.size))
        behind_board = 2.0 * size[0] if size[0] <= BOARD_ASPECT * size[1] else 0.0
        return [(o, y, every, behind_board), (y, o, (thin,), inf), (y, o, every, inf), (o, y, every, inf)]
    return [(y, o, every, inf) for y, o in order]


def _hangs_from(g: tuple, h: tuple, groups_parent: dict) -> bool:
    """Whether movable group ``g`` hangs (directly or not) from movable group ``h``."""
    g = groups_parent.get(g)
    while g is not None:
        if g == h:
            return True
        g = groups_parent.get(g)
    return False


def _cut(prim: Primitive, other: Primitive, gap: float, cfg: ClearanceConfig,
         axes: tuple[int, ...] = (0, 1, 2), max_depth: float = float("inf")) -> tuple[Primitive, float, str] | None:
    """``prim`` with one face moved inward along one of its axes so that its projection on that axis
    clears ``other``'s by ``gap``: the smallest such cut that keeps ``min_keep_fraction`` of the extent.
    A cylinder cut across its axis (a sphere cut along any axis) loses that much diameter and moves
    its centre half of it away from ``other``.
    ``axes``: the shape's axes a cut may move a face along; ``max_depth`` (m): the deepest cut allowed.
    Returns (cut shape, cut depth m, "+x" / "-y" ...: the face moved), or None."""
    R, c, h = _frame(prim)
    Ro, co, ho = _frame(other)
    best = None
    for k in axes:
        u = R[:, k]
        r_o = _radius(Ro, ho, u)
        lo_o, hi_o = float(co @ u) - r_o, float(co @ u) + r_o
        lo, hi = float(c @ u) - h[k], float(c @ u) + h[k]
        for sign, amount in ((+1, hi - (lo_o - gap)), (-1, (hi_o + gap) - lo)):
            if amount <= 0 or amount > max_depth or 2 * h[k] - amount < cfg.min_keep_fraction * 2 * h[k]:
                continue
            if best is None or amount < best[0]:
                best = (amount, k, sign)
    if best is None:
        return None
    amount, k, sign = best
    size = np.asarray(prim.size, float).copy()
    if prim.kind is PrimitiveKind.BOX:
        size[k] -= amount
    elif prim.kind is PrimitiveKind.CYLINDER and k == 2:
        size[2] -= amount
    elif prim.kind is PrimitiveKind.CYLINDER:
        size[:2] -= amount
    else:
        size[:] -= amount
    T = prim.T_world_part.copy()
    T[:3, 3] -= sign * R[:, k] * amount / 2.0
    return Primitive(prim.kind, size, T), float(amount), ("+" if sign > 0 else "-") + "xyz"[k]


def _moved_back(wall: Primitive, other: Primitive, gap: float, cfg: ClearanceConfig) -> tuple[Primitive, float, str] | None:
    """The wall box moved along its -x (out of the room) until its room side clears ``other`` by ``gap``,
    or None when that is more than ``wall_max_shift``."""
    R, c, h = _frame(wall)
    Ro, co, ho = _frame(other)
    u = R[:, 0]
    amount = (float(c @ u) + h[0]) - (float(co @ u) - _radius(Ro, ho, u) - gap)
    if amount <= 0 or amount > cfg.wall_max_shift:
        return None
    T = wall.T_world_part.copy()
    T[:3, 3] -= u * amount
    return Primitive(wall.kind, wall.size, T), float(amount), "moved back"


def cleared_scene(objects, walls, cfg: ClearanceConfig,
                  warn: Callable[[str], None] | None = None) -> tuple[tuple[ObjectReconstruction, ...], tuple[Wall, ...]]:
    """``objects`` (ObjectReconstruction, ...) and ``walls`` (Wall, ...) with their links' shapes cut
    (walls moved) so that no two links overlap (see the module docstring). A part whose shapes change
    gets them as ``PartFit.shapes`` (its fitted ``primitive`` is kept for metrics and graph.json).
    ``warn(message)`` is called for every pair that could not be cleared."""
    objects, walls = tuple(objects), tuple(walls)
    if not cfg.enabled:
        return objects, walls
    shapes = scene_shapes(objects, walls)
    groups_parent = {}
    for k, obj in enumerate(objects):
        parent = {j.child_part_id: j.parent_part_id for j in obj.joints}
        by_part = {s.link: s.group for s in shapes}
        for part in obj.parts:
            g = by_part.get(part.link)
            if g is not None and g[1] == part.part_id and parent.get(part.part_id) is not None:
                groups_parent[g] = by_part.get(obj.part(parent[part.part_id]).link)
    cuts: dict[tuple[str, str], tuple[float, str]] = {}
    for _ in range(cfg.max_passes):
        changed = False
        boxes = _aabbs([s.prim for s in shapes])
        for i, j in _near_pairs(shapes, boxes, cfg.tolerance):
            a, b = shapes[i], shapes[j]
            gap = cfg.moving_gap if a.group != b.group else 0.0
            if separation(a.prim, b.prim) >= gap - cfg.tolerance:
                continue
            index = {id(a): i, id(b): j}
            for y, o, axes, depth in _attempts(_yielders(a, b, groups_parent)):
                res = (_moved_back(y.prim, o.prim, gap, cfg) if y.wall and not o.wall
                       else _cut(y.prim, o.prim, gap, cfg, axes, depth))
                if res is not None:
                    k = index[id(y)]
                    shapes[k] = dataclasses.replace(y, prim=res[0])
                    boxes[k] = _aabbs([res[0]])[0]
                    key = (y.link, o.link)
                    cuts[key] = (max(cuts.get(key, (0.0, ""))[0], res[1]), res[2])
                    changed = True
                    break
        if not changed:
            break
    for (y, o), (amount, face) in sorted(cuts.items()):
        log.info("%s: %s %.1f mm to clear %s", y, "moved back" if face == "moved back" else f"cut its {face} face",
                 amount * 1e3, o)
    remaining: dict[tuple[str, str], float] = {}
    boxes = _aabbs([s.prim for s in shapes])
    for i, j in _near_pairs(shapes, boxes, cfg.tolerance):
        sep = separation(shapes[i].prim, shapes[j].prim)
        if sep < -cfg.report_overlap:
            key = tuple(sorted((shapes[i].link, shapes[j].link)))
            remaining[key] = max(remaining.get(key, 0.0), -sep)
    for (la, lb), depth in sorted(remaining.items()):
        msg = (f"links {la} and {lb} overlap by {depth * 1e3:.1f} mm and no shape of theirs could be cut to clear "
               "it; an engine loading scene.urdf may push them apart")
        if warn is not None:
            warn(msg)
        else:
            log.warning(msg)
    return _rebuilt(objects, walls, shapes)


def _near_pairs(shapes: list[SceneShape], boxes: np.ndarray, tol: float) -> list[tuple[int, int]]:
    """(i, j), i < j, of shapes on different links whose world bounds overlap (grown by ``tol``)."""
    lo, hi = boxes[:, 0], boxes[:, 1]
    touch = np.all((lo[:, None] < hi[None] + tol) & (hi[:, None] > lo[None] - tol), axis=2)
    links = np.array([s.link for s in shapes])
    touch &= links[:, None] != links[None]
    i, j = np.nonzero(np.triu(touch, 1))
    return list(zip(i.tolist(), j.tolist()))


def _rebuilt(objects, walls, shapes: list[SceneShape]):
    by_link: dict[str, list[Primitive]] = {}
    for s in shapes:
        by_link.setdefault(s.link, []).append(s.prim)
    new_objects = []
    for obj in objects:
        parts = []
        for p in obj.parts:
            new = by_link[p.link]
            if all(a is b for a, b in zip(new, p.solids)):
                parts.append(p)
            else:
                parts.append(dataclasses.replace(p, shapes=tuple(new)))
        new_objects.append(dataclasses.replace(obj, parts=tuple(parts)))
    new_walls = tuple(Wall(w.name, by_link[w.name][0].size, by_link[w.name][0].T_world_part, w.n_points)
                      for w in walls)
    return tuple(new_objects), new_walls


def links_in_contact(objects, walls, distance: float) -> tuple[tuple[str, str, float], ...]:
    """((link a, link b, separation m), ...) of every pair of links (a < b by name) whose shapes come
    within ``distance`` of each other at q = 0 (the separating-axis distance of :func:`separation`, a
    lower bound: a pair listed may be a little farther apart, none within ``distance`` is missed);
    sorted by name. A negative separation is a remaining overlap."""
    shapes = scene_shapes(objects, walls)
    boxes = _aabbs([s.prim for s in shapes])
    out: dict[tuple[str, str], float] = {}
    for i, j in _near_pairs(shapes, boxes, distance):
        sep = separation(shapes[i].prim, shapes[j].prim)
        if sep <= distance:
            key = tuple(sorted((shapes[i].link, shapes[j].link)))
            out[key] = min(out.get(key, np.inf), sep)
    return tuple((a, b, float(s)) for (a, b), s in sorted(out.items()))
