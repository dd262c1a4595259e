"""Articulated-template shapes of a part: a hollow carcass for a body with fronts, an open box for a drawer.

A closed drawer is seen only as its front panel and a cabinet only as its outside, so the fitted
primitives are a front plate and a solid box. The articulated template of the paper says more: a drawer
is a front with a box behind it, reaching back into its body as deep as the body's inside allows (the
joint stage already uses that depth for the travel), and a body that holds drawers or doors is a
carcass of panels, open where its fronts are. A simulator needs that too: a front plate holds nothing,
and a drawer box can only slide inside a hollow body.

Frames: every shape is a :class:`recon.primitive.Primitive` in the world frame (z up, metres), aligned
with the body's axes. Coordinates ``q = R_world_body.T @ p`` are used internally.
"""

from __future__ import annotations

import numpy as np

from recon.config import ShapeConfig
from recon.model import JointEstimate, JointType
from recon.primitive import Primitive, PrimitiveKind

__all__ = ["carcass_shapes", "drawer_shapes", "opening_axis", "template_shapes"]

_OPEN_ALIGN = 0.9
"""A body face is an opening when its outward normal is within ~25° of a front's opening normal."""


def _slab(R: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> Primitive:
    """The box spanning body-aligned coordinates ``lo``..``hi`` (3,) (q = R.T @ p), world frame."""
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = R @ ((lo + hi) / 2.0)
    return Primitive(PrimitiveKind.BOX, hi - lo, T)


def _end_slab(R: np.ndarray, lo: np.ndarray, hi: np.ndarray, axis: int, at_low: bool, w: float) -> Primitive:
    """The ``w``-thick slab of the box ``lo``..``hi`` (body coordinates) at its low (``at_low``) or high end
    along body axis ``axis``, world frame."""
    slo, shi = lo.copy(), hi.copy()
    if at_low:
        shi[axis] = lo[axis] + w
    else:
        slo[axis] = hi[axis] - w
    return _slab(R, slo, shi)


def opening_axis(body: Primitive, normal: np.ndarray) -> tuple[int, float] | None:
    """(body axis index, sign) of the body face whose outward normal is ``normal`` (3,), or None when
    no face is within ``_OPEN_ALIGN`` of it."""
    c = body.T_world_part[:3, :3].T @ np.asarray(normal, float)
    a = int(np.argmax(np.abs(c)))
    return (a, float(np.sign(c[a]))) if abs(c[a]) >= _OPEN_ALIGN else None


def _box_bounds(prim: Primitive, R: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    q = prim.corners() @ R
    return q.min(axis=0), q.max(axis=0)


def _uncovered_cells(lo: np.ndarray, hi: np.ndarray, holes: list[tuple[np.ndarray, np.ndarray]]
                     ) -> list[tuple[np.ndarray, np.ndarray]]:
    """The rectangle ``lo``..``hi`` (2,) minus the ``holes`` (each (lo, hi) (2,)), as rectangles: a grid on
    every hole edge, cells whose centre lies in no hole, merged along the first coordinate per row."""
    us = np.unique(np.clip([lo[0], hi[0]] + [x for h in holes for x in (h[0][0], h[1][0])], lo[0], hi[0]))
    ws = np.unique(np.clip([lo[1], hi[1]] + [x for h in holes for x in (h[0][1], h[1][1])], lo[1], hi[1]))
    out = []
    for w0, w1 in zip(ws[:-1], ws[1:]):
        run = None
        for u0, u1 in zip(us[:-1], us[1:]):
            c = np.array([(u0 + u1) / 2, (w0 + w1) / 2])
            free = (u1 - u0) > 1e-4 and (w1 - w0) > 1e-4 and not any(
                np.all(c > h[0]) and np.all(c < h[1]) for h in holes)
            if free:
                run = [u0, u1] if run is None else [run[0], u1]
            elif run is not None:
                out.append((np.array([run[0], w0]), np.array([run[1], w1])))
                run = None
        if run is not None:
            out.append((np.array([run[0], w0]), np.array([run[1], w1])))
    return out


def carcass_shapes(body: Primitive, fronts: list[tuple[np.ndarray, Primitive]],
                   config: ShapeConfig) -> tuple[Primitive, ...]:
    """The body as panels of ``carcass_wall`` (m). ``fronts`` are (outward normal (3,) world, front
    primitive) of its drawers and doors: the face with that normal gets openings where the fronts'
    outlines are, the rest of it stays a panel (a microwave's control panel, the stiles between doors).
    A front whose outer face lies deeper than ``front_depth_tolerance`` inside the body opens nothing:
    the opening would stay open around it.
    ``(body,)`` unchanged when it is no box, no face is open, or it is too thin to be hollow."""
    if body.kind is not PrimitiveKind.BOX or min(body.size) < 4 * config.carcass_wall:
        return (body,)
    R = body.T_world_part[:3, :3]
    lo, hi = _box_bounds(body, R)
    holes: dict[tuple[int, float], list] = {}
    for n, prim in fronts:
        face = opening_axis(body, n)
        if face is None:
            continue
        a, s = face
        flo, fhi = _box_bounds(prim, R)
        inset = (hi[a] - fhi[a]) if s > 0 else (flo[a] - lo[a])     # how far the front's outside lies inside the body
        if inset > config.front_depth_tolerance:
            continue        # a front sunk into its body (a misfit): an opening there would not be closed
        holes.setdefault(face, []).append((flo, fhi))
    if not holes:
        return (body,)
    panels = []
    for a in range(3):
        for s in (-1.0, 1.0):
            plo, phi = lo.copy(), hi.copy()
            if s > 0:
                plo[a] = hi[a] - config.carcass_wall
            else:
                phi[a] = lo[a] + config.carcass_wall
            if (a, s) not in holes:
                panels.append(_slab(R, plo, phi))
                continue
            uw = [k for k in range(3) if k != a]
            for clo, chi in _uncovered_cells(lo[uw], hi[uw], [(f[0][uw], f[1][uw]) for f in holes[(a, s)]]):
                qlo, qhi = plo.copy(), phi.copy()
                qlo[uw], qhi[uw] = clo, chi
                panels.append(_slab(R, qlo, qhi))
    return tuple(panels)


def drawer_shapes(front: Primitive, axis: np.ndarray, body: Primitive, config: ShapeConfig,
                  back_clearance: float) -> tuple[Primitive, ...]:
    """A drawer: its front panel and, behind it, an open-topped box (bottom, two sides, back) of
    ``drawer_wall`` (m) inside the body's carcass, ``drawer_gap`` (m) clear of every carcass panel, as deep
    as the body allows (back panel + ``drawer_back_clearance``) and ``drawer_box_height`` of the front's
    height. ``axis`` (3,) is the drawer's opening direction. ``(front,)`` when the body is no box or
    leaves no room."""
    face = opening_axis(body, axis)
    if body.kind is not PrimitiveKind.BOX or front.kind is not PrimitiveKind.BOX or face is None:
        return (front,)
    a, s = face
    R = body.T_world_part[:3, :3]
    blo, bhi = _box_bounds(body, R)
    flo, fhi = _box_bounds(front, R)
    inner_lo = blo + config.carcass_wall + config.drawer_gap
    inner_hi = bhi - config.carcass_wall - config.drawer_gap
    lo = np.maximum(flo + config.drawer_gap, inner_lo)
    hi = np.minimum(fhi - config.drawer_gap, inner_hi)
    if s > 0:
        hi[a] = flo[a]
        lo[a] = blo[a] + back_clearance
    else:
        lo[a] = fhi[a]
        hi[a] = bhi[a] - back_clearance
    up = [k for k in range(3) if k != a]
    v = max(up, key=lambda k: abs(R[2, k]))         # the body axis nearest vertical
    u = next(k for k in up if k != v)
    sv = float(np.sign(R[2, v])) or 1.0
    height = config.drawer_box_height * (hi[v] - lo[v])
    if sv > 0:
        hi[v] = lo[v] + height
    else:
        lo[v] = hi[v] - height
    w = config.drawer_wall
    if np.any(hi - lo < 3 * w):
        return (front,)
    return (front, _end_slab(R, lo, hi, v, sv > 0, w),                       # bottom
            _end_slab(R, lo, hi, u, True, w), _end_slab(R, lo, hi, u, False, w),  # sides
            _end_slab(R, lo, hi, a, s > 0, w))                                    # back


def template_shapes(joints: tuple[JointEstimate, ...], prims: dict[int, Primitive], labels: dict[int, str],
                    config: ShapeConfig, back_clearance: float) -> dict[int, tuple[Primitive, ...]]:
    """{part_id: template shapes, world frame} of an object's drawers (front + box) and of the parents
    of its drawers/doors (a carcass open at their fronts); parts not listed keep their primitive."""
    opens: dict[int, list[tuple[np.ndarray, Primitive]]] = {}
    out: dict[int, tuple[Primitive, ...]] = {}
    for j in joints:
        if j.type is JointType.FIXED or j.parent_part_id is None:
            continue
        if j.type is JointType.PRISMATIC:
            normal = j.axis
            if labels[j.child_part_id] == "drawer":
                out[j.child_part_id] = drawer_shapes(prims[j.child_part_id], j.axis, prims[j.parent_part_id], config,
                                                     back_clearance)
        else:
            n = np.cross(j.axis, prims[j.child_part_id].center - j.origin)
            if np.linalg.norm(n) < 1e-9:
                continue
            normal = n / np.linalg.norm(n)
        opens.setdefault(j.parent_part_id, []).append((normal, prims[j.child_part_id]))
    for i, fronts in opens.items():
        if labels[i] in ("body", "frame", "base"):
            out[i] = carcass_shapes(prims[i], fronts, config)
    return {i: s for i, s in out.items() if len(s) > 1}
