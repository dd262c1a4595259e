"""The scene-level contact graph: object support (floor or another object), proximity, upright poses.

Support: an object whose lowest point is within ``support_distance`` of the floor (z = 0) stands on
the floor; otherwise on the object whose top is nearest below its bottom with overlapping footprints.
Pose refinement by support: an object tilted by less than ``max_upright_tilt`` is rotated upright about
its bottom centre, then moved vertically to rest exactly on its supporter. Proximal: footprints closer
than ``proximal_distance``.
"""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial.transform import Rotation

from recon.config import SceneConfig
from recon.model import JointEstimate, JointType
from recon.primitive import Primitive

__all__ = ["footprint", "upright_correction", "support_relations", "proximal_relations", "resting_on",
           "object_frame", "object_front"]

_UP = np.array([0.0, 0.0, 1.0])


def _corners(prims: list[Primitive]) -> np.ndarray:
    return np.concatenate([p.corners() for p in prims])


def footprint(prims: list[Primitive]) -> shapely.Geometry:
    """The convex hull of the object's primitives' corners projected on the floor (shapely)."""
    return shapely.MultiPoint(_corners(prims)[:, :2]).convex_hull


def upright_correction(root: Primitive, config: SceneConfig) -> np.ndarray:
    """(3, 3) rotation taking the root part's most vertical axis onto ±z (identity if tilt is 0 or
    larger than ``max_upright_tilt``, which is then taken as intended)."""
    R = root.T_world_part[:3, :3]
    k = int(np.argmax(np.abs(R[2, :])))
    a = R[:, k] * np.sign(R[2, k])
    tilt = float(np.arccos(np.clip(a @ _UP, -1.0, 1.0)))
    if tilt < 1e-9 or tilt > config.max_upright_tilt:
        return np.eye(3)
    rot, _ = Rotation.align_vectors([_UP], [a])
    return rot.as_matrix()


def support_relations(objects: dict[int, list[Primitive]], config: SceneConfig
                      ) -> dict[int, tuple[int | None, float]]:
    """{object id: (supporter id or None = floor, the supporting height z (m))}."""
    bottoms = {i: float(_corners(p)[:, 2].min()) for i, p in objects.items()}
    tops = {i: float(_corners(p)[:, 2].max()) for i, p in objects.items()}
    prints = {i: footprint(p) for i, p in objects.items()}
    out = {}
    for i in objects:
        if bottoms[i] <= config.support_distance:
            out[i] = (None, 0.0)
            continue
        best = None
        for j in objects:
            if j == i or abs(bottoms[i] - tops[j]) > config.support_distance:
                continue
            overlap = prints[i].intersection(prints[j]).area
            if overlap > 0 and (best is None or overlap > best[1]):
                best = (j, overlap)
        out[i] = (best[0], tops[best[0]]) if best else (None, 0.0)
    return out


def proximal_relations(objects: dict[int, list[Primitive]], config: SceneConfig) -> tuple[tuple[int, int], ...]:
    """Pairs (a, b), a < b, of objects whose footprints are closer than ``proximal_distance``."""
    ids = sorted(objects)
    prints = [footprint(objects[i]) for i in ids]
    out = []
    for a in range(len(ids)):
        for b in range(a + 1, len(ids)):
            if prints[a].distance(prints[b]) < config.proximal_distance:
                out.append((ids[a], ids[b]))
    return tuple(out)


def object_frame(prims: list[Primitive], front: np.ndarray | None) -> tuple[np.ndarray, np.ndarray]:
    """(T_world_object (4, 4), size (3,)): origin at the bottom centre, x = ``front`` (horizontal
    unit (3,); the root part's x when None), z up; size = extent in that frame."""
    c = _corners(prims)
    if front is None or np.linalg.norm(front[:2]) < 1e-6:
        front = prims[0].T_world_part[:3, 0]
    x = np.array([front[0], front[1], 0.0])
    x /= max(np.linalg.norm(x), 1e-12)
    R = np.stack([x, np.cross(_UP, x), _UP], axis=1)
    q = c @ R
    lo, hi = q.min(axis=0), q.max(axis=0)
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = R @ np.array([(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, lo[2]])
    return T, hi - lo


def resting_on(prims: dict[int, Primitive], top: float, base: int | None = None,
               base_tolerance: float = 0.0, moved: list | None = None) -> dict[int, Primitive]:
    """An object's parts ``prims`` (world frame) resting at height ``top`` (m): parts sunk below it
    (noise below the floor / a top surface) are cut there instead of lifting the whole object (which
    would move its fitted drawers and doors). An object above ``top`` whose ``base`` part (its body)
    reaches its lowest point (within ``base_tolerance`` m) and stands upright has that part extended
    down to ``top`` (it stands on something the scan does not show: feet, a plinth, its hidden bottom
    edge), for the same reason; otherwise the object moves vertically so its bottom is ``top``. ``moved``
    (a list), when given, gets that whole-object motion appended as a (4, 4) transform (none when no part moved
    or parts were only cut or extended)."""
    bottom = min(float(p.corners()[:, 2].min()) for p in prims.values())
    if bottom < top:
        prims = {k: _bottom_at(p, top) if p.corners()[:, 2].min() < top else p for k, p in prims.items()}
        bottom = min(float(p.corners()[:, 2].min()) for p in prims.values())
    elif bottom > top and base in prims and float(prims[base].corners()[:, 2].min()) <= bottom + base_tolerance:
        extended = _bottom_at(prims[base], top)
        if extended is not prims[base]:
            return {**prims, base: extended}
    if abs(top - bottom) > 1e-9:
        M = np.eye(4)
        M[2, 3] = top - bottom
        prims = {k: p.transformed(M) for k, p in prims.items()}
        if moved is not None:
            moved.append(M)
    return prims


def _bottom_at(prim: Primitive, z: float) -> Primitive:
    """``prim`` with its bottom at height ``z`` (the part below cut off, or extended down to it), when it
    stands upright (an axis within ~3° of vertical) and its top is above ``z``; otherwise unchanged."""
    R = prim.T_world_part[:3, :3]
    k = int(np.argmax(np.abs(R[2, :])))
    c = prim.corners()
    lo, hi = float(c[:, 2].min()), float(c[:, 2].max())
    if lo == z or hi <= z or abs(R[2, k]) < 0.998 or prim.kind.value == "sphere":
        return prim
    if prim.kind.value == "cylinder" and k != 2:
        return prim
    size = prim.size.copy()
    size[k] = (hi - z) / abs(R[2, k])
    T = prim.T_world_part.copy()
    T[2, 3] += (z - lo) / 2
    return Primitive(prim.kind, size, T)


def object_front(joints: tuple[JointEstimate, ...], prims: dict[int, Primitive]) -> np.ndarray | None:
    """The object's front, (3,) unit, world: a drawer's axis, else the outward normal of a door (the
    direction its centre moves as it opens), else None."""
    for j in joints:
        if j.type is JointType.PRISMATIC:
            return j.axis
    for j in joints:
        if j.type is JointType.REVOLUTE:
            n = np.cross(j.axis, prims[j.child_part_id].center - j.origin)
            if np.linalg.norm(n) > 1e-9:
                return n / np.linalg.norm(n)
    return None
