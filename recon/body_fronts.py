"""A body's face where fronts close it lies at those fronts: not past them, not apart from them.

A drawer or door front closes an opening in its body's face: an overlay front stands on that face, an
inset one is flush with it, so the body's face on that side lies at most at the front's outer face. On a
noisy scan the body's points on that side are a few narrow strips (the stiles and rails between the
fronts) and the fronts' points that a segmentation gave the body's label, spread by the depth noise
across the face; the fitted body box then stands 5-8 cm proud of its fronts (ScanNet-style scans:
room10's cabinet4, microwaves), the fronts sink into a solid box, no opening is cut for them
(:mod:`recon.part_shapes`) and the clearance stage cuts the body to pieces around their drawer boxes.
The opposite also happens: the body's points on that side, seen only at the stiles' edges and through the
gaps, put its face several centimetres behind the fronts' backs, and the carcass's front panels, 18 mm thick,
then lie wholly apart from the true ones. A closed front touches its body (an overlay front's back on the
body's face, an inset front's edges in its opening), so a face behind the fronts' backs is moved out to them.
A front's board is measured from its own face's points and normals (:mod:`recon.fitting`): where the
two disagree, the front is the better measure of that face.

A documented limit: a body with a top overhanging its fronts (a kitchen counter) loses the overhang (it
is one box: its front face cannot be both at the fronts and past them).

Frames: primitives in the world frame (z up, metres); ``q = body.to_part(p)`` are body coordinates.
"""

from __future__ import annotations

import numpy as np

from recon.primitive import Primitive, PrimitiveKind

__all__ = ["body_within_fronts"]

_FACE_ALIGN = 0.9
"""A front closes a body face when its thin axis is within ~25 deg of that face's normal."""

MIN_FRONT_GAP = 0.01
MAX_FRONT_GAP = 0.1
"""A body face more than ``MIN_FRONT_GAP`` (m; a closed front stands a few millimetres off its carcass: hinge
play, bumpers) and at most ``MAX_FRONT_GAP`` behind the back of the fronts closing it is moved out to them; a
wider gap is no closed front (a drawer pulled out), and the face is kept."""


def body_within_fronts(body: Primitive, fronts: list[Primitive], panel_ratio: float) -> Primitive:
    """``body`` (a box) with each face that lies beyond the outer face of a front closing it moved back
    to the outermost such front's outer face, and each face behind that front's back face (by more than
    ``MIN_FRONT_GAP``, at most ``MAX_FRONT_GAP``) moved out to it; ``body`` itself when no face moves.

    A front is a box (world frame) thinner than ``panel_ratio`` x its middle extent, whose thin axis is
    within ``_FACE_ALIGN`` of a body axis, whose centre lies within the body's outline across that axis
    and beyond half of the body's half extent along it (it stands at that face, not across the body: a
    door opened 90 deg stands beside the body, in front of it). Its outer face is its side away from the
    body's centre."""
    if body.kind is not PrimitiveKind.BOX:
        return body
    R = body.T_world_part[:3, :3]
    half = np.asarray(body.size, float) / 2.0
    lo, hi = -half.copy(), half.copy()
    outer: dict[tuple[int, bool], tuple[float, float]] = {}   # (body axis, + side): the outermost front's faces
    for front in fronts:
        if front.kind is not PrimitiveKind.BOX:
            continue
        order = np.argsort(front.size)
        if front.size[order[0]] >= panel_ratio * front.size[order[1]]:
            continue
        c = R.T @ front.T_world_part[:3, order[0]]
        a = int(np.argmax(np.abs(c)))
        if abs(c[a]) < _FACE_ALIGN:
            continue
        centre = body.to_part(front.center[None])[0]
        inside = all(lo[b] < centre[b] < hi[b] for b in range(3) if b != a)
        if not inside or abs(centre[a]) < half[a] / 2.0:
            continue
        q = body.to_part(front.corners())[:, a]
        side = bool(centre[a] > 0)
        faces = (float(q.max()), float(q.min())) if side else (-float(q.min()), -float(q.max()))  # (outer, back)
        outer[(a, side)] = max(outer.get((a, side), (-np.inf, -np.inf)), faces)
    for (a, side), (face, back) in outer.items():
        at = hi[a] if side else -lo[a]                 # the body's face, outwards positive
        if at > face:
            at = face
        elif back - MAX_FRONT_GAP <= at < back - MIN_FRONT_GAP:
            at = back
        if side:
            hi[a] = at
        else:
            lo[a] = -at
    if np.allclose(lo, -half) and np.allclose(hi, half):
        return body
    T = body.T_world_part.copy()
    T[:3, 3] = body.to_world(((lo + hi) / 2.0)[None])[0]
    return Primitive(PrimitiveKind.BOX, hi - lo, T)
