"""Completion of supporting parts whose ends the camera missed.

A scanner rarely sees the top few centimetres of a table leg (under the top's overhang) or its foot
(occluded by the floor's grazing angle), so a fitted leg stops short of what it holds and Eq. 1 finds
no contact. For parts whose template says they span vertically (legs), the primitive is extended
along its vertical axis down to the nearest upward-facing surface below (another part, or the floor
z = 0) and up to the nearest downward-facing surface above whose outline covers the leg, when these
are within ``completion_reach``.

Handles and knobs lose their thin stems the same way (a knob's stem is a few points at most), so a
mounted part is extended backwards, along its axis nearest the plane's normal, onto the face of a
drawer/door (else any part) that it stands in front of, when that face is within ``completion_reach``
(a bar handle lying along the face becomes the box enveloping it and its hidden posts).
Nothing else is changed.
"""

from __future__ import annotations

import numpy as np
import shapely

from recon.config import ReconConfig
from recon.primitive import Primitive, PrimitiveKind

__all__ = ["VERTICAL_SPAN_LABELS", "MOUNTED_LABELS", "complete_vertical_parts", "complete_mounted_parts"]

VERTICAL_SPAN_LABELS = frozenset({"leg"})
MOUNTED_LABELS = frozenset({"handle", "knob"})
_MOUNTS = frozenset({"drawer", "door"})


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


def complete_mounted_parts(prims: dict[int, Primitive], labels: dict[int, str],
                           config: ReconConfig) -> tuple[dict[int, Primitive], dict[int, float]]:
    """Extend handles/knobs back onto the face they are mounted on: (new prims, {part_id: metres})."""
    out, changes = dict(prims), {}
    for i, prim in prims.items():
        if labels[i] not in MOUNTED_LABELS or prim.kind is PrimitiveKind.SPHERE:
            continue
        c = prim.corners()
        best = None
        for j, other in prims.items():
            if j == i or labels[j] in MOUNTED_LABELS:
                continue
            for pl in other.planes(config.cylinder_side_faces):
                gap = float(np.min(c @ pl.normal + pl.d))          # handle's nearest point above the face
                if not (-config.theta_d <= gap <= config.completion_reach):
                    continue
                B = np.linalg.svd(np.eye(3) - np.outer(pl.normal, pl.normal))[0][:, :2]
                poly = shapely.Polygon(pl.polygon @ B)
                if not poly.contains(shapely.Point(*(prim.center @ B))):
                    continue
                key = (labels[j] not in _MOUNTS, gap)
                if best is None or key < best[0]:
                    best = (key, pl.normal, gap)
        if best is None or best[2] <= config.theta_d / 2:
            continue
        n, gap = best[1], best[2]
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
                            config: ReconConfig) -> tuple[dict[int, Primitive], dict[int, tuple[float, float]]]:
    """Extend legs to what supports / is supported by them.

    Returns (new {part_id: primitive}, {part_id: (metres added below, metres added above)}).
    """
    out, changes = dict(prims), {}
    planes = {i: p.planes(config.cylinder_side_faces) for i, p in prims.items()}
    for i, prim in prims.items():
        if labels[i] not in VERTICAL_SPAN_LABELS:
            continue
        k = _vertical_axis(prim)
        if k is None:
            continue
        c = prim.corners()
        bottom, top = float(c[:, 2].min()), float(c[:, 2].max())
        xy = shapely.Point(*prim.center[:2])
        below, above = [0.0], []
        for j, pls in planes.items():
            if j == i:
                continue
            for pl in pls:
                if abs(pl.normal[2]) < 0.97:
                    continue
                z = float(pl.polygon[:, 2].mean())
                if not shapely.Polygon(pl.polygon[:, :2]).buffer(1e-6).contains(xy):
                    continue
                if pl.normal[2] > 0 and bottom - config.completion_reach <= z <= bottom + config.theta_d:
                    below.append(z)
                elif pl.normal[2] < 0 and top - config.theta_d <= z <= top + config.completion_reach:
                    above.append(z)
        below = [z for z in below if bottom - config.completion_reach <= z <= bottom + config.theta_d]
        new_bottom = max(below) if below else bottom
        new_top = min(above) if above else top
        if new_bottom >= bottom - 1e-9 and new_top <= top + 1e-9:
            continue
        new_bottom, new_top = min(new_bottom, bottom), max(new_top, top)
        R = prim.T_world_part[:3, :3]
        axis = R[:, k] * np.sign(R[2, k])
        size = prim.size.copy()
        length = (new_top - new_bottom) / abs(R[2, k])
        shift = ((new_top + new_bottom) / 2 - (top + bottom) / 2) / abs(R[2, k])
        size[k] = length
        T = prim.T_world_part.copy()
        T[:3, 3] = prim.center + shift * axis
        out[i] = Primitive(prim.kind, size, T)
        changes[i] = (bottom - new_bottom, new_top - top)
    return out, changes
