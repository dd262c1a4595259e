"""A post's cross-section (a leg's) from the points of its faces, not from the spread of all its points.

Depth noise moves a point along its ray, i.e. across the face it lies on, and is symmetric about that face.
On a post a few centimetres across, seen from several sides at a few metres (a ScanNet-style capture: sigma
2-3 cm), the noise is as large as the post: the points form a blob about twice as wide as the post, whose
extents (the oriented box, its percentiles) measure the noise, and a noise correction across one face of
that box collapses it to a film. The faces themselves are still where their points' median says:

- a box post (normals on the four directions of the base's horizontal axes): each face at the median
  coordinate of the points whose oriented normals point out of it (``|n . a| > 0.8``, signed); along an
  axis seen on one face only, the section's centre is the median of the points on the faces across the
  other axis (the section is twice as wide as from there to the seen face); an axis that shows neither is
  as wide as the other (a documented prior: legs are square);
- a round post (normals spread around): ``p_h = c + r n_h`` for every point with a horizontal normal
  (``n_h`` its unit horizontal part), solved for the axis ``c`` and the radius ``r`` by least squares.

On a clean scan both give the exact section. The post's vertical extent is the Eq. 3 fit's (completion then
extends a leg to what it stands on and holds).
Normals must be oriented (a scanner's, or :mod:`recon.estimated_normals`' outward ones); a part whose
normals do not show two opposite faces on an axis nor a round section is left to Eq. 3.

Frames: world, metres; the post is aligned with the object's base part (``R_world_ref`` (3, 3), columns
its axes).
"""

from __future__ import annotations

import numpy as np

from recon.config import FittingConfig
from recon.primitive import Primitive, PrimitiveKind

__all__ = ["post_primitive"]

_FACE_COS = 0.8
"""A point lies on the face across axis ``a`` when its normal is within ~37 deg of that axis."""
_AXIAL_COS = 0.95
"""A horizontal normal within ~18 deg of a base axis counts toward a box section."""


def post_primitive(points: np.ndarray, normals: np.ndarray | None, R_world_ref: np.ndarray, fit: Primitive,
                   config: FittingConfig) -> Primitive | None:
    """The post (a vertical box or cylinder along ``R_world_ref``'s most vertical axis) whose faces the
    ``points`` (n, 3) and their oriented ``normals`` (n, 3) show (module docstring), as tall as the part's
    Eq. 3 ``fit`` reaches along that axis (its bounding box's corners); None when the normals
    show no section (too few points on faces, an inverted face pair) or the points are not a post (their
    vertical extent under ``post_min_slenderness`` x the section's width: a pedestal table's foot disc)."""
    if normals is None or len(normals) != len(points) or len(points) < 2 * config.post_face_min_points:
        return None
    R = np.asarray(R_world_ref, dtype=np.float64)
    v = int(np.argmax(np.abs(R[2, :])))
    h = [a for a in range(3) if a != v]
    q = np.asarray(points, dtype=np.float64) @ R
    n = np.asarray(normals, dtype=np.float64) @ R
    horizontal = np.abs(n[:, v]) < 0.5
    nh = n[horizontal][:, h]
    nh_len = np.linalg.norm(nh, axis=1)
    if horizontal.sum() < 2 * config.post_face_min_points or not np.all(nh_len > 0):
        return None
    nh = nh / nh_len[:, None]
    axial = float(np.mean(np.abs(nh).max(axis=1) > _AXIAL_COS))
    reach = fit.corners() @ R[:, v]
    lo_v, hi_v = float(reach.min()), float(reach.max())
    if axial >= config.post_axial_share:
        section = _box_section(q, n, h, config)
    else:
        section = _round_section(q[horizontal][:, h], nh)
    if section is None:
        return None
    centre_h, width = section
    width = np.maximum(width, config.min_thickness)
    if hi_v - lo_v < config.post_min_slenderness * float(np.max(width)):
        return None
    centre = np.zeros(3)
    centre[h], centre[v] = centre_h, (lo_v + hi_v) / 2
    T = np.eye(4)
    T[:3, 3] = R @ centre
    if axial >= config.post_axial_share:
        size = np.zeros(3)
        size[h], size[v] = width, max(hi_v - lo_v, config.min_thickness)
        T[:3, :3] = R
        return Primitive(PrimitiveKind.BOX, size, T)
    # a cylinder's local z along the base's vertical axis (a right-handed frame)
    z = R[:, v]
    x = R[:, h[0]]
    T[:3, :3] = np.stack([x, np.cross(z, x), z], axis=1)
    d = float(width[0])
    return Primitive(PrimitiveKind.CYLINDER, [d, d, max(hi_v - lo_v, config.min_thickness)], T)


def _box_section(q: np.ndarray, n: np.ndarray, h: list[int],
                 config: FittingConfig) -> tuple[np.ndarray, np.ndarray] | None:
    """(centre (2,), width (2,)) along the horizontal axes ``h`` (module docstring), or None.

    Along each axis: two opposite faces seen give the section between their medians; one face seen gives
    one end, and the centre is the median coordinate, along that axis, of the points on the faces across
    the other axis (they cover the section's width evenly; depth noise moves them across their own face,
    not along it), so the section is twice as wide as from that centre to the face; an axis that shows
    neither is as wide as the other (a documented prior: legs are square)."""
    m = config.post_face_min_points
    found: list[tuple[float, float] | None] = []
    centres: list[float | None] = []
    ends: list[tuple[float | None, float | None]] = []
    for i, a in enumerate(h):
        b = h[1 - i]
        plus, minus = n[:, a] > _FACE_COS, n[:, a] < -_FACE_COS
        hi = float(np.median(q[plus, a])) if plus.sum() >= m else None
        lo = float(np.median(q[minus, a])) if minus.sum() >= m else None
        across = np.abs(n[:, b]) > _FACE_COS
        c = float(np.median(q[across, a])) if across.sum() >= m else None
        ends.append((lo, hi))
        centres.append(c)
        if lo is not None and hi is not None:
            found.append(((lo + hi) / 2, hi - lo) if hi > lo else None)
        elif hi is not None and c is not None and hi > c:
            found.append((c, 2 * (hi - c)))
        elif lo is not None and c is not None and lo < c:
            found.append((c, 2 * (c - lo)))
        else:
            found.append(None)
    if all(f is None for f in found):
        return None
    centre, width = np.zeros(2), np.zeros(2)
    for i in range(2):
        if found[i] is not None:
            centre[i], width[i] = found[i]
            continue
        w = found[1 - i][1]                         # the other axis's width: the section is square
        lo, hi = ends[i]
        if hi is not None and lo is None:
            centre[i] = hi - w / 2
        elif lo is not None and hi is None:
            centre[i] = lo + w / 2
        elif centres[i] is not None:
            centre[i] = centres[i]
        else:
            return None
        width[i] = w
    return centre, width


def _round_section(p: np.ndarray, nh: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """(centre (2,), diameter twice (2,)) of the circle ``p = c + r nh`` fitted to the horizontal
    coordinates ``p`` (m, 2) and unit horizontal normals ``nh`` (m, 2) by least squares, or None."""
    A = np.zeros((2 * len(p), 3))
    A[0::2, 0], A[1::2, 1] = 1.0, 1.0
    A[0::2, 2], A[1::2, 2] = nh[:, 0], nh[:, 1]
    sol, *_ = np.linalg.lstsq(A, p.reshape(-1), rcond=None)
    if not np.all(np.isfinite(sol)) or sol[2] <= 0.0:
        return None
    return sol[:2], np.array([2.0 * sol[2], 2.0 * sol[2]])
