"""The depth noise of a part's points: their robust spread across the face of a box that holds most of them.

A depth camera's noise runs along its rays, i.e. across the faces it sees. Given a box around a part's
points (its fitted box, or the points' own oriented box), every point is assigned to a box face: a face
across the axis its normal lies along when the normals are given (of either sign), else across the axis
of the face it is nearest; of that axis's two faces, the one on the point's side of the centre. The face
holding the most points is the face the camera saw best, and the robust standard deviation (1.4826 x
median absolute deviation) of those points' coordinates across it is the noise sigma. When the opposite
face holds the other half of one noisy slab (a thin panel whose box the noise inflated), both halves are
judged as one cloud; but by nearest face, a slab whose noise is as thick as its face is wide gives many
of its points to the side faces: normals, where there are any, do not.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["SeenFace", "mad_sigma", "seen_face"]


def mad_sigma(r: np.ndarray) -> float:
    """Robust standard deviation (1.4826 x median absolute deviation) of (n,) values; 0 if empty."""
    return 1.4826 * float(np.median(np.abs(r - np.median(r)))) if len(r) else 0.0


@dataclass(frozen=True, eq=False)
class SeenFace:
    """The face of a box that holds most of the points and the noise across it.

    face : index 2 * axis + (1 for the + side), of the face holding the most points
    axis : the box axis across that face (0, 1, 2)
    sigma : m, the points' robust spread across it (both halves of one noisy slab together)
    across : (m,) the coordinates along ``axis`` (box frame, m) of the points sigma was measured on
    mask : (n,) bool, those points
    """

    face: int
    axis: int
    sigma: float
    across: np.ndarray
    mask: np.ndarray


def seen_face(q: np.ndarray, size: np.ndarray, min_face_points: int,
              normals: np.ndarray | None = None) -> SeenFace:
    """The face of the box of edge lengths ``size`` (3,) m that holds the most of the points ``q`` (n, 3)
    (box frame: centred on the box, its axes), with the depth noise across it.

    normals : (n, 3) unit, box frame, optional, either orientation: a point belongs to a face across the
        box axis its normal is most parallel to, else across the axis of the face it is nearest; of that
        axis's two faces, to the one on its side of the centre. The opposite face's points join when there
        are at least ``min_face_points`` of them and a fifth as many and their median lies within 6 sigma:
        the two halves of one noisy slab.
    """
    q = np.asarray(q, dtype=np.float64).reshape(-1, 3)
    if normals is not None and len(normals) == len(q):
        axis = np.argmax(np.abs(np.asarray(normals, dtype=np.float64).reshape(-1, 3)), axis=1)
    else:
        axis = np.argmin(np.abs(np.abs(q) - np.asarray(size, dtype=np.float64) / 2.0), axis=1)
    face = axis * 2 + (q[np.arange(len(q)), axis] > 0)
    f = int(np.argmax(np.bincount(face, minlength=6)))
    k = f // 2
    mask = face == f
    r = q[mask, k]
    sigma = mad_sigma(r)
    other = q[face == (f ^ 1), k]
    if len(other) >= max(min_face_points, len(r) // 5):
        if abs(float(np.median(r) - np.median(other))) <= 6.0 * max(sigma, mad_sigma(other)):
            mask = mask | (face == (f ^ 1))
            r = q[mask, k]
            sigma = mad_sigma(r)
    return SeenFace(f, k, sigma, r, mask)
