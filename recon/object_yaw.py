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
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from recon.config import FittingConfig
from recon.primitive import Primitive, PrimitiveKind
from scenes.description import R_onto_up

__all__ = ["FaceYaw", "face_yaws", "measured_yaw", "yaw_of", "yaw_difference", "turned_about"]


@dataclass(frozen=True)
class FaceYaw:
    """The yaw of one fitted face plane.

    yaw : rad, of the plane's normal about ``up`` (see :func:`yaw_of`), modulo nothing
    se : rad, its standard error
    n_points : the points the plane was fitted to
    part_id : the part whose face it is
    """

    yaw: float
    se: float
    n_points: int
    part_id: int = -1


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
                                3 * config.min_face_points)
            if fitted is not None:
                out.append(dataclasses.replace(fitted[0], part_id=part_id))
                pool = pool & ~fitted[1]
    return out


def _plane_fit(points: np.ndarray, pool: np.ndarray, near: np.ndarray, n0: np.ndarray, up: np.ndarray,
               band: float, min_points: int) -> tuple[FaceYaw, np.ndarray] | None:
    """The plane through ``points[pool & near]``, refitted on the pool's points within a band about it
    that halves from ``band`` (m) each time down to 3 robust sigma of the points about it (a band of 3
    sigma at once can lock onto a plane turned by the stray points of the first fit), then twice at
    3 sigma: (its yaw, the (n,) mask of its points); None with fewer than ``min_points`` points or a
    plane not across ``up``."""
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
    across = np.cross(up, n)
    if np.linalg.norm(across) < 1e-6:
        return None
    X = points[mask]
    u = (X - X.mean(axis=0)) @ (across / np.linalg.norm(across))
    spread = float(np.sqrt((u**2).sum()))
    if spread <= 0.0:
        return None
    yaw = yaw_of(n, up)
    # a plane's halves (either side of its middle across up) lie in it: when they do not (two strips
    # at different depths, a warped face), its yaw is no better than their disagreement
    halves = [_normal(X[side], n) for side in (u < 0, u >= 0)]
    if any(h is None for h in halves):
        return None
    ya, yb = (yaw_of(h, up) for h in halves)
    se = max(max(sigma, 1e-6) / spread, abs(yaw_difference(ya, yb)) / 2,
             abs(yaw_difference(yaw, ya + yaw_difference(yb, ya) / 2)))
    return FaceYaw(yaw, se, int(mask.sum())), mask


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
