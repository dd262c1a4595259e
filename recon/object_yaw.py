"""The yaw of an object as the planes of its faces show it.

Eq. 3 does not fix a noisy body's yaw: its score barely changes over a few degrees of yaw about the best
box, and the minimum-volume box and ICP end wherever the noise puts them (measured: docs/decisions.md).
Alg. 1 then turns every front onto that body, and a front moves by the angle times its distance from the
body's centre, out of its carcass. The planes of
the object's large vertical faces fix it: a drawer front or a carcass side of thousands of points fits its
plane to a small fraction of a degree, with estimated normals as with exact ones (the normals only pick
the face's points; the plane is fitted to the points).

Each box part's vertical faces are refitted to the points near them (least squares, trimmed at 3 robust
sigma, twice); each gives a yaw (modulo 90 degrees: a box's faces are perpendicular) and its standard
error (the robust spread of the points about the plane over the root sum of squares of their horizontal
in-plane coordinates: a short face resolves yaw worse than a long one). The object's yaw is the weighted
mean of the group of faces agreeing within ``yaw_consensus`` that the most parts show (a rigid object's
parts share its frame; an opened door, a round leg's strip, a box fitted across a leg's corners do not
join), the base part's group on a tie; faces whose error exceeds that window cannot tell which group they
belong to and are left out. Its standard error is inflated by the group's scatter when the faces disagree
more than their own errors say (a second view registered a little off).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from recon.config import FittingConfig
from recon.primitive import Primitive, PrimitiveKind
from scenes.description import R_onto_up

__all__ = ["FaceYaw", "face_yaws", "measured_yaw", "yaw_of", "yaw_difference", "turned_about", "on_face_planes"]


@dataclass(frozen=True)
class FaceYaw:
    """The yaw of one fitted face plane.

    yaw : rad, of the plane's normal about ``up`` (see :func:`yaw_of`), modulo nothing
    se : rad, its standard error
    n_points : the points the plane was fitted to
    part_id : the part whose face it is
    point : (3,) world, m: the centroid of those points (on the plane); None when not known
    normal : (3,) world, unit: the plane's normal, pointing out of the box; None when not known
    sigma : m, the robust spread of those points about the plane
    """

    yaw: float
    se: float
    n_points: int
    part_id: int = -1
    point: np.ndarray | None = field(default=None, compare=False, repr=False)
    normal: np.ndarray | None = field(default=None, compare=False, repr=False)
    sigma: float = 0.0


def yaw_of(direction: np.ndarray, up: np.ndarray) -> float:
    """Yaw (rad) of ``direction`` (3,) about the unit ``up`` (3,): the angle of its component across ``up``
    in the frame that the smallest rotation taking ``up`` onto +z levels (the world's yaw when up is +z)."""
    v = R_onto_up(up) @ np.asarray(direction, dtype=np.float64)
    return float(np.arctan2(v[1], v[0]))


def yaw_difference(a: float, b: float) -> float:
    """a - b (rad) modulo 90 degrees, in [-45, 45) degrees: the turn between two boxes' yaws."""
    q = np.pi / 2
    return float((a - b + q / 2) % q - q / 2)


def face_yaws(prim: Primitive, points: np.ndarray, normals: np.ndarray | None, up: np.ndarray,
              config: FittingConfig, part_id: int = -1) -> list[FaceYaw]:
    """The yaws of the vertical faces of the box ``prim`` as its ``points`` (n, 3, world) show them.

    A point belongs to the faces across the box axis its normal is most nearly parallel to (``normals``
    (n, 3), unit, sign-free; None: to every axis) and lies inside their outline (``seen_face_band``
    margin). Along each vertical face's axis, the face with more such points within ``seen_face_band``
    of it is fitted first, the other one from the points that plane left (a thin board's two faces are
    one plane of noisy points). A face needs ``3 * min_face_points`` points. ``up`` (3,) unit. Empty for
    a non-box. ``part_id`` labels the faces (:attr:`FaceYaw.part_id`).
    """
    if prim.kind is not PrimitiveKind.BOX or len(points) < 3 * config.min_face_points:
        return []
    R, h = prim.T_world_part[:3, :3], prim.size / 2
    points = np.asarray(points, dtype=np.float64)
    q = (points - prim.center) @ R
    along = None if normals is None else np.argmax(np.abs(normals @ R), axis=1)
    out = []
    for k in range(3):
        if abs(R[:, k] @ up) > np.sin(config.normals_frame_cone):
            continue                                    # not a vertical face
        others = [j for j in range(3) if j != k]
        pool = np.all(np.abs(q[:, others]) <= h[others] + config.seen_face_band, axis=1)
        if along is not None:
            pool &= along == k
        near = {s: np.abs(s * q[:, k] - h[k]) < config.seen_face_band for s in (1.0, -1.0)}
        for s in sorted(near, key=lambda s: -int((pool & near[s]).sum())):
            fitted = _plane_fit(points, pool, near[s], s * R[:, k], up, config.seen_face_band,
                                3 * config.min_face_points, config.normals_frame_cone)
            if fitted is not None:
                out.append(dataclasses.replace(fitted[0], part_id=part_id))
                pool = pool & ~fitted[1]
    return out


def _plane_fit(points: np.ndarray, pool: np.ndarray, near: np.ndarray, n0: np.ndarray, up: np.ndarray,
               band: float, min_points: int, max_tilt: float) -> tuple[FaceYaw, np.ndarray] | None:
    """The plane through ``points[pool & near]``, refitted on the pool's points within a band about it
    that halves from ``band`` (m) each time down to 3 robust sigma of the points about it (a band of 3
    sigma at once can lock onto a plane turned by the stray points of the first fit), then twice at
    3 sigma: (its yaw, the (n,) mask of its points); None with fewer than ``min_points`` points or a
    plane tilted more than ``max_tilt`` (rad) off vertical about the unit ``up`` (the points of a strip,
    a table top's edge, fit a plane turned about its length as well as one across it)."""
    mask = pool & near
    n = n0
    sigma, at_sigma = 0.0, 0
    while at_sigma < 3:
        if mask.sum() < min_points:
            return None
        X = points[mask]
        centre = X.mean(axis=0)
        n = _normal(X, n0)
        r = (points - centre) @ n
        sigma = 1.4826 * float(np.median(np.abs(r[mask] - np.median(r[mask]))))
        band /= 2.0
        if band <= 3.0 * sigma:
            band, at_sigma = 3.0 * sigma, at_sigma + 1
        mask = pool & (np.abs(r) <= band)
    if mask.sum() < min_points:
        return None
    if abs(n @ up) > np.sin(max_tilt):
        return None
    across = np.cross(up, n)
    X = points[mask]
    u = (X - X.mean(axis=0)) @ (across / np.linalg.norm(across))
    spread = float(np.sqrt((u**2).sum()))
    if spread <= 0.0:
        return None
    yaw = yaw_of(n, up)
    centre = X.mean(axis=0)
    # a plane's halves (either side of its middle across up) lie in it: when they do not (two strips
    # at different depths, a warped face), its yaw is no better than their disagreement
    halves = [_normal(X[side], n) for side in (u < 0, u >= 0)]
    if any(h is None for h in halves):
        return None
    ya, yb = (yaw_of(h, up) for h in halves)
    se = max(max(sigma, 1e-6) / spread, abs(yaw_difference(ya, yb)) / 2,
             abs(yaw_difference(yaw, ya + yaw_difference(yb, ya) / 2)))
    return FaceYaw(yaw, se, int(mask.sum()), point=centre, normal=n, sigma=sigma), mask


def _normal(X: np.ndarray, n0: np.ndarray) -> np.ndarray | None:
    """(3,) the unit normal (on ``n0``'s side) of the least-squares plane of ``X`` (k, 3); None below 3 points."""
    if len(X) < 3:
        return None
    n = np.linalg.svd(X - X.mean(axis=0), full_matrices=False)[2][2]
    return n * np.sign(n @ n0)


def measured_yaw(faces: list[FaceYaw], consensus: float, base: int | None = None) -> tuple[float, float] | None:
    """(yaw, standard error) (rad; the yaw modulo 90 degrees) of an object as its ``faces`` show it.

    Faces with a standard error above ``consensus`` (rad) are left out. A group is the faces within
    ``consensus`` (modulo 90 degrees) of one of them; the group showing the most parts wins, then the one
    holding a face of part ``base``, then the heaviest (weights 1 / se^2). The yaw is the group's weighted
    mean, its error 1 / sqrt(sum of weights) inflated by sqrt(chi^2 / dof) when that is above 1. None
    without faces.
    """
    faces = [f for f in faces if f.se <= consensus]
    if not faces:
        return None
    y = np.array([f.yaw for f in faces])
    w = 1.0 / np.array([f.se for f in faces]) ** 2
    part = np.array([f.part_id for f in faces])
    d = np.array([[yaw_difference(a, b) for b in y] for a in y])       # d[i, j] = y_i - y_j (mod 90)
    member = np.abs(d) <= consensus

    def rank(j):
        m = member[:, j]
        return len(set(part[m].tolist())), bool(base is not None and (part[m] == base).any()), float(w[m].sum())

    j = max(range(len(faces)), key=rank)
    m = member[:, j]
    offset = float((w[m] * d[m, j]).sum() / w[m].sum())
    se = 1.0 / np.sqrt(w[m].sum())
    if m.sum() > 1:
        chi2 = float((w[m] * (d[m, j] - offset) ** 2).sum()) / (m.sum() - 1)
        se *= np.sqrt(max(chi2, 1.0))
    return float(y[j] + offset), float(se)


def turned_about(R: np.ndarray, up: np.ndarray, angle: float) -> np.ndarray:
    """(3, 3) the frame ``R`` turned by ``angle`` (rad) about the unit ``up`` (3,)."""
    return Rotation.from_rotvec(np.asarray(up) * angle).as_matrix() @ R


def on_face_planes(prim: Primitive, faces: list[FaceYaw], up: np.ndarray, max_turn: float, band: float,
                   min_thickness: float, cover: np.ndarray | None = None) -> Primitive:
    """The box ``prim`` with each face that one of ``faces`` (fitted to its own points, :func:`face_yaws`)
    shows placed on that face's plane: along the box axis most nearly parallel to the plane's normal, on
    the side it points to, at its points' centroid. A least-squares plane trimmed at 3 robust sigma sits
    in the middle of its points' depth noise; the box's own ends (the min/max or percentiles of the points
    along a frame) lie about 3 sigma out, more where the noise grows with range.

    Only the faces of the box's frame count: a yaw about ``up`` (3,) within ``max_turn`` (rad) of the
    box's (a plane whose yaw is uncertain still lies at its points: its offset is known to the noise over
    the square root of its points). A face that other parts cover is kept: more of the ``cover`` points
    (n, 3, world: the object's other parts) than the plane has lie inside its outline and in front of it
    by at most twice ``band`` (m) and 3 of its sigma -- a carcass's front behind its doors and drawers
    shows its panels' edges and what lies between the fronts, not a face. Both faces of an axis are moved
    only when they stay ``min_thickness`` apart. Orientation kept; faces without a plane unchanged
    (``prim`` itself when no face moved)."""
    if prim.kind is not PrimitiveKind.BOX:
        return prim
    R = prim.T_world_part[:3, :3]
    lo, hi = -prim.size / 2, prim.size / 2
    q = np.empty((0, 3)) if cover is None or not len(cover) else (np.asarray(cover) - prim.center) @ R
    new: list[dict[int, float]] = [{}, {}]                   # [low ends, high ends] {axis: coordinate}
    for f in faces:
        if f.point is None or f.normal is None:
            continue
        c = R.T @ f.normal
        k = int(np.argmax(np.abs(c)))
        if abs(yaw_difference(f.yaw, yaw_of(R[:, k], up))) > max_turn:
            continue
        side = 1.0 if c[k] > 0 else -1.0
        offset = float((f.point - prim.center) @ R[:, k])
        others = [j for j in range(3) if j != k]
        ahead = side * (q[:, k] - offset)
        covered = (np.all(np.abs(q[:, others]) <= prim.size[others] / 2, axis=1)
                   & (ahead >= 0.0) & (ahead <= 2.0 * band + 3.0 * f.sigma))
        if covered.sum() > f.n_points:
            continue
        new[int(side > 0)][k] = offset
    lo, hi = lo.copy(), hi.copy()
    moved = False
    for k in range(3):
        a, b = new[0].get(k, lo[k]), new[1].get(k, hi[k])
        if (k in new[0] or k in new[1]) and b - a >= min_thickness:
            lo[k], hi[k], moved = a, b, True
    if not moved:
        return prim
    T = prim.T_world_part.copy()
    T[:3, 3] = prim.to_world(((lo + hi) / 2)[None])[0]
    return Primitive(PrimitiveKind.BOX, hi - lo, T)
