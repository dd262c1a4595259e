"""Completion of supporting parts whose ends the camera missed.

A scanner rarely sees the top few centimetres of a table leg (under the top's overhang) or its foot
(occluded by the floor's grazing angle), so a fitted leg stops short of what it holds and Eq. 1 finds
no contact. For parts whose template says they span vertically (legs), the primitive is extended
along its vertical axis down to the nearest upward-facing surface below (another part, or the floor
z = 0) and up to the nearest downward-facing surface above whose outline covers the leg, when these
are within ``completion_reach``; an end sunk into another part is cut back to that part's face.

Handles and knobs lose their thin stems the same way (a knob's stem is a few points at most), so a
mounted part is extended backwards, along its axis nearest the plane's normal, onto the face of a
drawer/door (else any part) that it stands in front of, when that face is within ``completion_reach``
(a bar handle lying along the face becomes the box enveloping it and its hidden posts; handle_shapes.py
then writes it as the bar and posts a gripper meets).
A leg the camera hardly saw at all (under a bed frame: fewer than ``min_part_points`` points, maybe
none) is still declared in labels.json; a bed, table or chair stands on four legs at the corners of a
rectangle, so missing legs are placed at the corners the fitted ones leave free, as copies of the
nearest fitted leg (``complete_missing_legs``). A bed frame's head end is hidden under the mattress and
behind the headboard, its far rail under the mattress; the frame is extended to span its mattress and
along its length to the headboard when that lies within ``completion_reach`` beyond it
(``complete_reaching_parts``).
Nothing else is changed.
"""

from __future__ import annotations

import numpy as np
import shapely

from recon.config import CompletionConfig, ContactConfig
from recon.primitive import Primitive, PrimitiveKind, SurfacePlane

__all__ = ["VERTICAL_SPAN_LABELS", "MOUNTED_LABELS", "LEGGED_CATEGORIES", "complete_vertical_parts",
           "complete_mounted_parts", "mount_face", "complete_missing_legs", "complete_reaching_parts"]

VERTICAL_SPAN_LABELS = frozenset({"leg"})
MOUNTED_LABELS = frozenset({"handle", "knob"})
_MOUNTS = frozenset({"drawer", "door"})
LEGGED_CATEGORIES = frozenset({"bed", "table", "chair"})
"""Categories whose template stands on four legs at the corners of a rectangle."""



def _extended(prim: Primitive, k: int, direction: np.ndarray, amount: float) -> Primitive:
    """``prim`` grown by ``amount`` (m) along its local axis ``k`` on the side of ``direction``."""
    R = prim.T_world_part[:3, :3]
    a = R[:, k] * np.sign(R[:, k] @ direction)
    size = prim.size.copy()
    size[k] += amount
    if prim.kind is PrimitiveKind.SPHERE:
        return prim
    T = prim.T_world_part.copy()
    T[:3, 3] = prim.center + a * amount / 2
    return Primitive(prim.kind, size, T)


def mount_face(i: int, prims: dict[int, Primitive], labels: dict[int, str],
               config: CompletionConfig, contacts: ContactConfig) -> tuple[int, SurfacePlane, float] | None:
    """The face that mounted part ``i`` (a handle/knob) stands in front of: (part id of its mount, the
    mount's surface plane (normal out of the mount, world), gap (m) from part ``i``'s nearest corner to
    that plane). A drawer/door face is preferred to any other part's, then the smallest gap; only faces
    within ``[-theta_d, completion_reach]`` of the part whose outline holds the part's centre count.
    None when no face qualifies."""
    prim = prims[i]
    c = prim.corners()
    best = None
    for j, other in prims.items():
        if j == i or labels[j] in MOUNTED_LABELS:
            continue
        for pl in other.planes(contacts.cylinder_side_faces):
            gap = float(np.min(c @ pl.normal + pl.d))          # handle's nearest point above the face
            if not (-contacts.theta_d <= gap <= config.completion_reach):
                continue
            B = np.linalg.svd(np.eye(3) - np.outer(pl.normal, pl.normal))[0][:, :2]
            poly = shapely.Polygon(pl.polygon @ B)
            if not poly.contains(shapely.Point(*(prim.center @ B))):
                continue
            key = (labels[j] not in _MOUNTS, gap)
            if best is None or key < best[0]:
                best = (key, j, pl, gap)
    return None if best is None else best[1:]


def complete_mounted_parts(prims: dict[int, Primitive], labels: dict[int, str],
                           config: CompletionConfig, contacts: ContactConfig) -> tuple[dict[int, Primitive], dict[int, float]]:
    """Extend handles/knobs back onto the face they are mounted on: (new prims, {part_id: metres})."""
    out, changes = dict(prims), {}
    for i, prim in prims.items():
        if labels[i] not in MOUNTED_LABELS or prim.kind is PrimitiveKind.SPHERE:
            continue
        found = mount_face(i, prims, labels, config, contacts)
        if found is None or found[2] <= contacts.theta_d / 2:
            continue
        n, gap = found[1].normal, found[2]
        k = int(np.argmax(np.abs(prim.T_world_part[:3, :3].T @ n)))
        if prim.kind is PrimitiveKind.CYLINDER and k != 2:
            # a bar lying along the face on hidden posts: its envelope down to the face is a box
            prim = Primitive(PrimitiveKind.BOX, prim.size, prim.T_world_part)
        out[i] = _extended(prim, k, -n, gap)
        changes[i] = gap
    return out, changes


def _vertical_axis(prim: Primitive) -> int | None:
    R = prim.T_world_part[:3, :3]
    k = int(np.argmax(np.abs(R[2, :])))
    if abs(R[2, k]) < 0.97 or (prim.kind is PrimitiveKind.CYLINDER and k != 2):
        return None
    return k if prim.kind is not PrimitiveKind.SPHERE else None


def complete_vertical_parts(prims: dict[int, Primitive], labels: dict[int, str],
                            config: CompletionConfig, contacts: ContactConfig) -> tuple[dict[int, Primitive], dict[int, tuple[float, float]]]:
    """Extend legs to what supports / is supported by them.

    A leg end sunk more than ``theta_d`` into another part (its end's centre inside that part's solid,
    whose face covers the leg) is cut back to that part's face instead: a leg meets what it holds at
    its face, never passes through it to the next surface beyond (a bed leg whose top is inside a
    frame fitted low is not extended through the frame to the mattress).

    Returns (new {part_id: primitive}, {part_id: (metres added below, metres added above)}; negative:
    cut back).
    """
    out, changes = dict(prims), {}
    planes = {i: p.planes(contacts.cylinder_side_faces) for i, p in prims.items()}
    for i, prim in prims.items():
        if labels[i] not in VERTICAL_SPAN_LABELS:
            continue
        k = _vertical_axis(prim)
        if k is None:
            continue
        c = prim.corners()
        bottom, top = float(c[:, 2].min()), float(c[:, 2].max())
        R = prim.T_world_part[:3, :3]
        axis = R[:, k] * np.sign(R[2, k])
        ends = prim.center + np.outer([-1.0, 1.0], axis * prim.size[k] / 2)     # (2, 3) bottom, top
        xy = shapely.Point(*prim.center[:2])
        below, above, sunk_below, sunk_above = [0.0], [], [], []
        for j, pls in planes.items():
            if j == i:
                continue
            holds_bottom, holds_top = prims[j].contains(ends)
            for pl in pls:
                if abs(pl.normal[2]) < 0.97:
                    continue
                z = float(pl.polygon[:, 2].mean())
                if not shapely.Polygon(pl.polygon[:, :2]).buffer(1e-6).contains(xy):
                    continue
                inner = bottom + contacts.theta_d < z < top - contacts.theta_d
                if pl.normal[2] > 0 and bottom - config.completion_reach <= z <= bottom + contacts.theta_d:
                    below.append(z)
                elif pl.normal[2] < 0 and top - contacts.theta_d <= z <= top + config.completion_reach:
                    above.append(z)
                elif pl.normal[2] > 0 and holds_bottom and inner:
                    sunk_below.append(z)
                elif pl.normal[2] < 0 and holds_top and inner:
                    sunk_above.append(z)
        below = [z for z in below if bottom - config.completion_reach <= z <= bottom + contacts.theta_d]
        new_bottom = max(below) if below else bottom
        new_top = min(above) if above else top
        new_bottom, new_top = min(new_bottom, bottom), max(new_top, top)
        # an end sunk deeper than theta_d into another part meets that part's face (never passes it)
        if sunk_below:
            new_bottom = max(sunk_below)
        if sunk_above:
            new_top = min(sunk_above)
        if abs(new_bottom - bottom) <= 1e-9 and abs(new_top - top) <= 1e-9:
            continue
        size = prim.size.copy()
        length = (new_top - new_bottom) / abs(R[2, k])
        shift = ((new_top + new_bottom) / 2 - (top + bottom) / 2) / abs(R[2, k])
        size[k] = length
        T = prim.T_world_part.copy()
        T[:3, 3] = prim.center + shift * axis
        out[i] = Primitive(prim.kind, size, T)
        changes[i] = (bottom - new_bottom, new_top - top)
    return out, changes


def _two_values(x: np.ndarray, mirror_about: float, tol: float) -> list[float] | None:
    """The two distinct values of ``x`` (clustered within ``tol``), or one value and its mirror image
    about ``mirror_about``; None when ``x`` has more than two."""
    vals: list[list[float]] = []
    for v in np.sort(x):
        if vals and v - vals[-1][-1] <= tol:
            vals[-1].append(float(v))
        else:
            vals.append([float(v)])
    means = [float(np.mean(c)) for c in vals]
    if len(means) == 1:
        means.append(2 * mirror_about - means[0])
    return sorted(means) if len(means) == 2 else None


def complete_missing_legs(category: str, prims: dict[int, Primitive], labels: dict[int, str],
                          skipped, config: CompletionConfig, base: int | None = None
                          ) -> tuple[dict[int, Primitive], dict[int, np.ndarray]]:
    """Place the legs of a four-legged object that the camera missed.

    prims : {part_id: fitted primitive}; labels : {part_id: label} of the fitted parts
    skipped : the object's parts with too few points to fit (:attr:`recon.scan.ObjectPoints.skipped`)
    base : the part the legs carry (its horizontal axes and centre frame the leg rectangle; a bed frame
        already extended to span its mattress and reach its headboard, :func:`complete_reaching_parts`)
    Applies when the category stands on four legs, at least two legs are fitted (one when ``base`` is
    fitted: a bed frame may hide three) and the skipped legs make up four. The fitted legs' centres, in the
    base's horizontal axes, give the rectangle's two x and two y values (a value is mirrored about the
    base's centre when the seen legs share it); the
    missing legs go to the free corners — a leg with a few points to the corner nearest them (within
    ``completion_reach``), the others in part-id order — each a copy of the nearest fitted leg.
    Returns (prims with the placed legs added, {part_id: (3,) world centre of each placed leg}).
    """
    legs = [i for i, lab in labels.items() if lab == "leg"]
    missing = sorted((p for p in skipped if p.label == "leg"), key=lambda p: p.part_id)
    frame = prims[base] if base in prims else None
    fewest = 1 if frame is not None else 2            # one leg's mirror images need the base's centre
    if category not in LEGGED_CATEGORIES or len(legs) < fewest or not missing or len(legs) + len(missing) != 4:
        return dict(prims), {}
    if frame is not None:
        R = frame.T_world_part[:3, :3]
        horiz = sorted(range(3), key=lambda k: abs(R[2, k]))[:2]
        axes = np.stack([R[:, k] for k in horiz], axis=1)
        mid = frame.center @ axes
    else:
        axes, mid = np.eye(3)[:, :2], np.mean([prims[i].center[:2] for i in legs], axis=0)
    c = {i: prims[i].center @ axes for i in legs}
    tol = 2 * max(float(np.max(np.sort(prims[i].size)[:2])) for i in legs)
    xs = _two_values(np.array([v[0] for v in c.values()]), float(mid[0]), tol)
    ys = _two_values(np.array([v[1] for v in c.values()]), float(mid[1]), tol)
    if xs is None or ys is None:
        return dict(prims), {}
    corners = [np.array([x, y]) for x in xs for y in ys]
    free = [q for q in corners if min(np.linalg.norm(q - v) for v in c.values()) > tol]
    if len(free) != len(missing) or len(free) + len(legs) != 4:
        return dict(prims), {}
    out, placed = dict(prims), {}
    order = sorted(missing, key=lambda p: len(p.points) == 0)       # legs with points choose first
    for leg in order:
        if len(leg.points):
            q = leg.points.mean(axis=0) @ axes
            k = int(np.argmin([np.linalg.norm(f - q) for f in free]))
            if np.linalg.norm(free[k] - q) > config.completion_reach:
                continue
        else:
            k = 0
        corner = free.pop(k)
        src = min(legs, key=lambda i: float(np.linalg.norm(c[i] - corner)))
        T = prims[src].T_world_part.copy()
        T[:3, 3] = prims[src].center + axes @ (corner - c[src])
        out[leg.part_id] = Primitive(prims[src].kind, prims[src].size, T)
        placed[leg.part_id] = T[:3, 3].copy()
    return out, placed


_REACHES = {("frame", "headboard")}
"""(label, label it reaches): a bed frame starts at its headboard."""

_HANGS_DOWN = {"headboard": ("frame", "mattress")}
"""{label: (label, hiding label)}: a headboard reaches down at least to its frame's underside; the part of it the
mattress in front hides (a mattress whose underside lies below the headboard's fitted lower edge) is completed."""

_SPANS = {("frame", "mattress")}
"""(label, label it spans): a bed frame is at least as long and wide as the mattress it carries."""


def _face_reach(prim: Primitive, axis: np.ndarray) -> float:
    """How far (m) along the unit ``axis`` (3,) the centres of the box ``prim``'s faces reach: its extent there
    without the corners a slight turn swings out (1.5 deg across a 2 m mattress: 2.6 cm)."""
    R, h = prim.T_world_part[:3, :3], prim.size / 2
    return float(prim.center @ axis + np.max(np.abs(R.T @ axis) * h))


def _toward(R: np.ndarray, flat: list[int], d: np.ndarray) -> tuple[int, float]:
    """(axis k among ``flat`` of the frame ``R`` (3, 3) nearest the direction ``d`` (3,), the sign along it)."""
    k = max(flat, key=lambda a: abs(float(R[:, a] @ d)))
    return k, float(np.sign(R[:, k] @ d))


def complete_reaching_parts(prims: dict[int, Primitive], labels: dict[int, str], config: CompletionConfig,
                            contacts: ContactConfig, normals: dict[int, np.ndarray | None] | None = None
                            ) -> tuple[dict[int, Primitive], dict[int, float]]:
    """Extend a box (a bed frame) along its horizontal axes, but toward the part it reaches (its headboard), to the
    ends of the part it carries by template (its mattress) where that part reaches past it by more than
    ``theta_d`` and the box's end there was not seen
    (the frame's far rail hides under the mattress; fewer than ``hidden_face_points`` of its points' normals
    point out of that end), then along a horizontal axis to the part it reaches by template (its headboard)
    when that part's near face lies beyond the box's end by more than ``theta_d`` and at most
    ``completion_reach`` (m), facing it. ``normals`` : {part_id: its points' unit normals (n, 3), world,
    oriented out of the part}; a part without them shows no end. Last, a headboard whose fitted lower edge lies
    above its mattress's underside (the mattress in front hides its lower part) is extended down to its frame's
    underside (``_HANGS_DOWN``). Returns (new prims, {part_id: metres added})."""
    out, changes = dict(prims), {}
    for i, prim in prims.items():
        if prim.kind is not PrimitiveKind.BOX:
            continue
        R = prim.T_world_part[:3, :3]
        flat = [a for a in range(3) if abs(R[2, a]) < 0.5]
        reached = [j for j in prims if (labels[i], labels[j]) in _REACHES]
        toward = {_toward(R, flat, prims[j].center - prim.center) for j in reached}
        for j in (j for j in prims if (labels[i], labels[j]) in _SPANS):
            for k in flat:
                for sign in (-1.0, 1.0):
                    if (k, sign) in toward:
                        continue                    # the end at the headboard: reached below, never past it
                    axis = R[:, k] * sign
                    gap = _face_reach(prims[j], axis) - float(np.max(out[i].corners() @ axis))
                    n = (normals or {}).get(i)
                    shown = 0 if n is None else int(np.sum(n @ axis > 0.8))
                    if gap > contacts.theta_d and shown < config.hidden_face_points:
                        out[i] = _extended(out[i], k, axis, gap)
                        changes[i] = changes.get(i, 0.0) + gap
        for j in reached:
            k, sign = _toward(R, flat, prims[j].center - out[i].center)
            axis = R[:, k] * sign
            end = float(np.max(out[i].corners() @ axis))
            near = float(np.min(prims[j].corners() @ axis))
            gap = near - end
            if contacts.theta_d < gap <= config.completion_reach:
                out[i] = _extended(out[i], k, axis, gap)
                changes[i] = changes.get(i, 0.0) + gap
    for i, (base, hider) in ((i, _HANGS_DOWN[labels[i]]) for i in prims if labels[i] in _HANGS_DOWN):
        k = _vertical_axis(out[i])
        bottom = float(out[i].corners()[:, 2].min())
        hidden = any(labels[j] == hider and float(out[j].corners()[:, 2].min()) < bottom for j in out)
        floors = [float(out[j].corners()[:, 2].min()) for j in out if labels[j] == base]
        if k is None or not hidden or not floors:
            continue
        gap = bottom - min(floors)
        if gap > contacts.theta_d:
            out[i] = _extended(out[i], k, np.array([0.0, 0.0, -1.0]), gap)
            changes[i] = changes.get(i, 0.0) + gap
    return out, changes
