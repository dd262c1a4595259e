"""Individual part alignment (Eq. 3): the best primitive for one part's points.

Candidates M^c come from the part's oriented bounding box (box, a cylinder along each box axis,
sphere). Each is aligned to the points by point-to-plane ICP (open3d) and scored; the lowest score wins.

Score. Eq. 3 is the mean distance from points sampled on the primitive's surface h(M) to the part's
points P. A scan only covers the faces a camera saw: the back of a cabinet against a wall, the
underside of a table top, the inside of a leg pair are missing, and Eq. 3 then charges the true
primitive for faces that are really there. We therefore (a) leave out the primitive's faces whose
samples are mostly farther than ``coverage_distance`` from any point (unobserved faces) and (b) add
the mean distance from the points to the primitive's surface, so that dropping faces can never make a
wrong primitive look good.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree
from scipy.spatial.transform import Rotation

from recon.bounding import oriented_box
from recon.config import CoverageConfig, FittingConfig
from recon.coverage import coverage, coverage_problems
from recon.depth_noise import mad_sigma, seen_face
from recon.label_fragments import point_spacing
from recon.primitive import Primitive, PrimitiveKind

__all__ = ["FitScore", "candidate_primitives", "normals_frame", "score_primitive", "denoised_box", "dominant_yaw", "fit_part",
           "CoveredFit", "fit_part_covering", "body_behind_face"]

# rotations making a box axis the local z of a cylinder: columns = (new x, new y, new z) in box axes
_AXIS_PERM = {
    "cylinder_x": np.array([[0, 0, 1], [1, 0, 0], [0, 1, 0]], float),
    "cylinder_y": np.array([[0, 1, 0], [0, 0, 1], [1, 0, 0]], float),
    "cylinder_z": np.eye(3),
}


@dataclass(frozen=True)
class FitScore:
    """The score of one posed candidate.

    eq3 : plain Eq. 3, mean distance (m) of all surface samples to the points
    observed : Eq. 3 restricted to the observed faces (m)
    points_to_surface : mean distance (m) from the points to the primitive's surface
    total : observed + weight * points_to_surface (what is minimised)
    observed_faces : (k,) indices of the faces counted as observed
    """

    eq3: float
    observed: float
    points_to_surface: float
    total: float
    observed_faces: tuple[int, ...]


def _box_in_frame(points: np.ndarray, R: np.ndarray, min_thickness: float) -> tuple[np.ndarray, np.ndarray]:
    q = points @ R
    lo, hi = q.min(axis=0), q.max(axis=0)
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, R @ ((lo + hi) / 2)
    return T, np.maximum(hi - lo, min_thickness)


def dominant_yaw(normals: np.ndarray) -> float | None:
    """Yaw (rad, modulo 90°) of the vertical faces of ``normals`` (n, 3): the circular mean of 4·yaw
    of the near-horizontal normals, re-taken over those within 10° of it. None without such normals."""
    h = normals[np.abs(normals[:, 2]) < 0.5]
    if len(h) < 10:
        return None
    a4 = 4.0 * np.arctan2(h[:, 1], h[:, 0])
    mean = np.arctan2(np.sin(a4).sum(), np.cos(a4).sum())
    near = np.abs(np.angle(np.exp(1j * (a4 - mean)))) < np.radians(40.0)
    if near.sum() >= 10:
        mean = np.arctan2(np.sin(a4[near]).sum(), np.cos(a4[near]).sum())
    return float(mean / 4.0)


def normals_frame(normals: np.ndarray, config: FittingConfig) -> np.ndarray | None:
    """(3, 3) a right-handed frame whose first axis is the direction (sign-free) that most of the unit
    ``normals`` (n, 3) lie within ``normals_frame_cone`` of, the second the same among the normals
    across it, the third their cross product; None with fewer than ``min_face_points`` normals on the
    first two directions. Candidate directions are the normals themselves (a seeded subsample)."""
    n = np.asarray(normals, dtype=np.float64)
    if len(n) < 2 * config.min_face_points:
        return None
    cands = n[np.random.default_rng(0).choice(len(n), min(len(n), 200), replace=False)]
    cos = np.cos(config.normals_frame_cone)

    def strongest(c, pool):
        votes = (np.abs(pool @ c.T) > cos).sum(axis=0)
        i = int(np.argmax(votes))
        if votes[i] < config.min_face_points:
            return None
        member = pool[np.abs(pool @ c[i]) > cos]
        member = member * np.sign(member @ c[i])[:, None]
        d = member.mean(axis=0)
        return d / np.linalg.norm(d)

    d1 = strongest(cands, n)
    if d1 is None:
        return None
    across = np.abs(n @ d1) < np.sin(config.normals_frame_cone)
    c2 = cands[np.abs(cands @ d1) < np.sin(config.normals_frame_cone)]
    if len(c2) == 0 or across.sum() < config.min_face_points:
        return None
    d2 = strongest(c2, n[across])
    if d2 is None:
        return None
    d2 = d2 - (d2 @ d1) * d1
    d2 /= np.linalg.norm(d2)
    return np.stack([d1, d2, np.cross(d1, d2)], axis=1)


def _frame_angle(Ra: np.ndarray, Rb: np.ndarray) -> float:
    """The smallest rotation angle (rad) between two box frames (3, 3), over the box's 24 symmetries."""
    M = np.abs(Ra.T @ Rb)
    # each axis of Ra matched to its most parallel axis of Rb: the worst of those angles
    return float(np.arccos(np.clip(M.max(axis=1).min(), -1.0, 1.0)))


def _yaw_frame(yaw: float) -> np.ndarray:
    c, s = np.cos(yaw), np.sin(yaw)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def candidate_primitives(points: np.ndarray, config: FittingConfig,
                         R_world_ref: np.ndarray | None = None,
                         normals: np.ndarray | None = None) -> dict[str, Primitive]:
    """Candidate primitives scaled from the minimum-volume oriented box of ``points`` (n, 3).

    With ``R_world_ref`` (3, 3) — the axes of the object's base part — the templates are built only
    from the box aligned with those axes (names suffixed ``@ref``): small parts (knobs, handles) have
    too few points for a reliable orientation of their own.
    """
    T, ext = oriented_box(points, min_thickness=config.min_thickness,
                          upright_tolerance=config.upright_tolerance)
    if R_world_ref is not None:
        # a small part (knob, handle) has too few points to orient itself: parts of man-made objects
        # are aligned with their base part, so only the base-aligned templates are tried
        Tr, er = _box_in_frame(points, R_world_ref, config.min_thickness)
        return {f"{k}@ref": v for k, v in _templates(points, Tr, er, config).items()}
    out = _templates(points, T, ext, config)
    R_n = None if normals is None or "box" not in config.candidates else normals_frame(normals, config)
    if R_n is not None and _frame_angle(R_n, T[:3, :3]) > config.normals_frame_min_angle:
        # a box seen on two faces: its minimum-volume box may lie along the diagonal of its L-shaped
        # cross-section; the directions of its faces' normals do not
        Tn, en = _box_in_frame(points, R_n, config.min_thickness)
        out["box@normals"] = Primitive(PrimitiveKind.BOX, en, Tn)
    yaw = None if normals is None or "box" not in config.candidates else dominant_yaw(normals)
    if yaw is not None:
        # noise moves a minimum-area rectangle's corners; the faces' normals hold the yaw better
        Ty, ey = _box_in_frame(points, _yaw_frame(yaw), config.min_thickness)
        out["box@yaw"] = Primitive(PrimitiveKind.BOX, ey, Ty)
    return out


def _templates(points, T, ext, config) -> dict[str, Primitive]:
    out = {}
    for name in config.candidates:
        if name == "box":
            out[name] = Primitive(PrimitiveKind.BOX, ext, T)
        elif name in _AXIS_PERM:
            P = _AXIS_PERM[name]
            Tc = T.copy()
            Tc[:3, :3] = T[:3, :3] @ P
            e = P.T @ ext                      # extents along the new local axes
            d = max((e[0] + e[1]) / 2.0, config.min_thickness)
            circle = _circle_fit((points - Tc[:3, 3]) @ Tc[:3, :2])
            if circle is not None and 2 * circle[1] <= 1.5 * max(e[0], e[1]):
                # a half-seen cylinder has a too-small box: its circle is what the points say
                Tc[:3, 3] += Tc[:3, :2] @ circle[0]
                d = max(2 * circle[1], config.min_thickness)
            out[name] = Primitive(PrimitiveKind.CYLINDER, [d, d, e[2]], Tc)
        elif name == "sphere":
            d = float(np.mean(ext))
            out[name] = Primitive(PrimitiveKind.SPHERE, [d, d, d], T)
        else:
            raise ValueError(f"unknown primitive candidate {name!r} in FittingConfig.candidates")
    return out


def _circle_fit(q: np.ndarray) -> tuple[np.ndarray, float] | None:
    """Least-squares (Kasa) circle through (n, 2) points: (centre (2,), radius) or None if ill-posed."""
    if len(q) < 6:
        return None
    A = np.c_[2 * q, np.ones(len(q))]
    b = (q**2).sum(axis=1)
    sol, *_ = np.linalg.lstsq(A, b, rcond=None)
    r2 = sol[2] + sol[0] ** 2 + sol[1] ** 2
    if not np.isfinite(r2) or r2 <= 0:
        return None
    return sol[:2], float(np.sqrt(r2))


def score_primitive(prim: Primitive, points: np.ndarray, tree: cKDTree, config: FittingConfig,
                    rng: np.random.Generator) -> FitScore:
    """Score ``prim`` against ``points`` (n, 3) whose KD-tree is ``tree`` (see the module docstring)."""
    samples, face = prim.sample_surface(config.surface_samples, rng)
    d, _ = tree.query(samples, k=1)
    faces = np.unique(face)
    cover = np.array([np.mean(d[face == f] < config.coverage_distance) for f in faces])
    observed = faces[cover >= config.min_face_coverage]
    if observed.size == 0:
        observed = faces
    keep = np.isin(face, observed)
    obs = float(d[keep].mean())
    p2s = float(prim.surface_distance(points).mean())
    return FitScore(float(d.mean()), obs, p2s, obs + config.point_term_weight * p2s,
                    tuple(int(f) for f in observed))


def denoised_box(prim: Primitive, points: np.ndarray, config: FittingConfig,
                 normals: np.ndarray | None = None, front: bool = False) -> Primitive:
    """The box with its extents corrected for depth noise (see :func:`_denoised`)."""
    return _denoised(prim, points, config, normals, front)[0]


def _denoised(prim: Primitive, points: np.ndarray, config: FittingConfig,
              normals: np.ndarray | None = None, front: bool = False) -> tuple[Primitive, bool]:
    """The box with its extents corrected for depth noise.

    The noise σ is the robust spread (1.4826 × MAD) of the points about the box face that holds the
    most points (the face the camera saw best; depth noise runs across it). Min/max extents of a
    noisy scan overshoot by about 3σ along that face's normal, so the faces on that axis are placed at
    the 0.2 / 99.8 percentiles pulled in by 2.9σ (a Gaussian's 0.2 % quantile); the other axes take
    the 0.2 / 99.8 percentiles. When the opposite face holds the other half of one noisy slab (an
    inflated panel), σ is taken over both; a slab that collapses is ``min_thickness`` thick about the
    median of its points.

    normals : (n, 3) unit, world, optional. An end of that axis whose outermost points
    (``edge_tail_fraction``) mostly face sideways (|n · axis| < 0.5) is the rim of side faces the
    camera saw edge-on — a table top's underside is hidden, its lowest points are its edges — not a
    noise tail of the seen face, so it is not pulled in. Only for boxes at least ``rim_min_extent`` across the
    axis: the front of a 12 mm handle bar is no rim, its noise is.

    A front — a vertical panel (thinner than ``panel_ratio`` × its other extents) whose face points'
    oriented normals show it was seen from one side only (a door, a drawer front; not a chair back) —
    is measured from the points of its face (normals along its thin axis): its in-plane edges where
    their density falls to ``front_edge_density`` of the face's (label bleed and the edges' own noise
    lie beyond; moved in from the outermost points by at most ``front_edge_max_trim`` or, for a front by
    its label (``front``), ``front_edge_trim_spacings`` times the face points' spacing, whichever is more: a
    coarse scan blurs an edge farther), its seen face at their median, and a ``front_thickness`` board
    behind it. A front on a clean scan thinner than that board (only its face was seen) gets the board
    behind its face.

    A slab (a board, a table top) seen on one face and its edges gets its thickness from its edges
    (:func:`_slab_box`); a box seen on two or three faces has each seen face pulled in like the best one.

    front : the part is a front by its label (a drawer, a door: a panel seen from before it). The face the
    camera saw best is then the one most of its points' ``normals`` point out of, not the box face most
    points lie nearest: a front's noise slab as deep as the front is tall (3.5 cm voxels, sigma 2-3 cm)
    gives most of its points to the box's top and bottom faces, and the noise correction across those
    collapsed the front into a horizontal film (then refused by the coverage check and refitted as a
    cylinder).

    Returns (box, whether the front rule placed it).
    """
    if prim.kind is not PrimitiveKind.BOX:
        return prim, False
    q = prim.to_part(points)
    # the face the camera saw best and the depth noise across it (both halves of an inflated slab)
    by_normals = front and normals is not None and len(normals) == len(q)
    best = seen_face(q, prim.size, config.min_face_points,
                     normals @ prim.T_world_part[:3, :3] if by_normals else None)
    f, k, sigma, r, seen_mask = best.face, best.axis, best.sigma, best.across, best.mask
    if sigma < config.noise_floor:
        # a clean scan: nothing to correct, but a front seen only by its face is a board, not a film; a
        # panel already a board's thickness (within the noise floor) is such a front too, so a second pass
        # (after ICP) keeps the board behind its face instead of re-measuring it as a slab
        side = _seen_side(normals, _facing(normals, seen_mask, prim.T_world_part[:3, k], config),
                          prim.T_world_part[:3, k])
        lo, hi = -prim.size / 2, prim.size / 2
        if side is None or prim.size[k] > config.front_thickness + config.noise_floor or not _vertical_panel(
                lo, hi, k, prim.T_world_part[:3, :3], config):
            # a slab whose edges show it notably thinner than its box (noise just under the floor): its
            # thickness is measured; an untilted box keeps its orientation and in-plane extents
            slab = _slab_box(prim, q, k, bool(f % 2), config)
            if slab is None or slab.size[k] > prim.size[k] - config.noise_floor:
                return prim, False
            if _frame_angle(slab.T_world_part[:3, :3], prim.T_world_part[:3, :3]) > config.slab_min_turn:
                return slab, False          # a box tilted off the slab's face by the noise: turned onto it
            across = prim.to_part(slab.corners())[:, k]
            lo, hi = lo.copy(), hi.copy()
            lo[k], hi[k] = float(across.min()), float(across.max())
            return _box_between(prim, lo, hi), False
        # (a face-only cloud got min_thickness about the face: the face is the median of its points)
        seen = float(np.median(q[_facing(normals, seen_mask, prim.T_world_part[:3, k], config), k]))
        lo, hi = lo.copy(), hi.copy()
        _board_behind(lo, hi, k, seen, side, config.front_thickness)
        return _box_between(prim, lo, hi), True
    lo = np.percentile(q, 0.2, axis=0)
    hi = np.percentile(q, 99.8, axis=0)
    wide = all(prim.size[a] >= config.rim_min_extent for a in range(3) if a != k)
    rim_lo, rim_hi = _rim_ends(q[:, k], normals, prim.T_world_part[:3, k], config) if wide else (False, False)
    face_lo, face_hi = _seen_faces(q, k, normals, prim.T_world_part[:3, :3], lo[k], hi[k], config)
    if _curved(q, seen_mask, k, normals, prim.T_world_part[:3, :3], config):
        # a curved surface (a cylinder's side) spreads about its best face by its shape, not by noise
        rim_lo = rim_hi = True
    if not rim_lo:
        # depth noise runs along the rays, i.e. across the seen face: its median, or 2.9σ in
        lo[k] = face_lo if face_lo != lo[k] else lo[k] + 2.9 * sigma
    if not rim_hi:
        hi[k] = face_hi if face_hi != hi[k] else hi[k] - 2.9 * sigma
    if hi[k] - lo[k] < config.min_thickness:
        # a panel: its plane is the median of its points (noise is symmetric about the surface)
        seen = float(np.median(r))
        lo[k], hi[k] = seen - config.min_thickness / 2, seen + config.min_thickness / 2
    face_mask = _facing(normals, seen_mask, prim.T_world_part[:3, k], config)
    side = _seen_side(normals, face_mask, prim.T_world_part[:3, k])
    # a front by its label is judged by its outline, not by its noise slab's depth (sigma 4-5 cm at 3-4 m: the
    # 2.9 sigma correction leaves a slab 20 cm deep when one end's tail passes for a face)
    lo_k, hi_k = (lo[k], hi[k]) if not by_normals else (-config.front_thickness / 2, config.front_thickness / 2)
    is_front = side is not None and _vertical_panel(np.where(np.arange(3) == k, lo_k, lo),
                                                    np.where(np.arange(3) == k, hi_k, hi), k,
                                                    prim.T_world_part[:3, :3], config)
    if is_front:
        # a front (door, drawer front) seen from one side: its in-plane edges at the half-density of its
        # face, its seen face at the median of that face's points, the board's thickness behind it
        trim = config.front_edge_max_trim
        if front:
            trim = max(trim, config.front_edge_trim_spacings * point_spacing(q[face_mask]))
        for a in range(3):
            if a != k:
                edges = _half_density_edges(q[face_mask, a], config)
                if edges is not None:
                    # scattered points past the face (flying pixels, bleed from far) are no extent to trim from
                    dense = _half_density_edges(q[face_mask, a], config, config.front_edge_tail_density)
                    start = (max(lo[a], dense[0]), min(hi[a], dense[1])) if dense else (lo[a], hi[a])
                    lo[a] = max(lo[a], min(edges[0], start[0] + trim))
                    hi[a] = min(hi[a], max(edges[1], start[1] - trim))
        _board_behind(lo, hi, k, float(np.median(q[face_mask, k])), side, config.front_thickness)
    else:
        slab = _slab_box(prim, q, k, bool(f % 2), config)
        if slab is not None:
            return slab, False
        if rim_lo != rim_hi:
            thin = _rimmed_slab(q, k, normals, prim.T_world_part[:3, :3], prim.size, rim_hi, config)
            if thin is not None:
                lo[k], hi[k] = thin
        # a box seen on two or three faces: each other seen face at the median of its points
        for a in range(3):
            if a != k:
                lo[a], hi[a] = _seen_faces(q, a, normals, prim.T_world_part[:3, :3], lo[a], hi[a], config, True)
    for a in range(3):
        if hi[a] - lo[a] < config.min_thickness:
            mid = (hi[a] + lo[a]) / 2
            lo[a], hi[a] = mid - config.min_thickness / 2, mid + config.min_thickness / 2
    return _box_between(prim, lo, hi), is_front


def _box_between(prim: Primitive, lo: np.ndarray, hi: np.ndarray) -> Primitive:
    """The box spanning [lo, hi] (3,) each, in ``prim``'s part frame, with ``prim``'s orientation."""
    T = prim.T_world_part.copy()
    T[:3, 3] = prim.to_world(((lo + hi) / 2)[None])[0]
    return Primitive(PrimitiveKind.BOX, hi - lo, T)


def _board_behind(lo: np.ndarray, hi: np.ndarray, k: int, seen: float, side: bool, thickness: float) -> None:
    """Set (in place) extent ``k`` of [lo, hi] to a ``thickness`` board whose seen face is at ``seen``:
    below it when the +k face was seen (``side``), above it otherwise."""
    lo[k], hi[k] = (seen - thickness, seen) if side else (seen, seen + thickness)


def _vertical_panel(lo: np.ndarray, hi: np.ndarray, k: int, R: np.ndarray, config: FittingConfig) -> bool:
    """Is the box [lo, hi] (part frame, (3,) each; axes the columns of ``R`` (3, 3) world) a vertical panel
    seen across its thin axis ``k`` (horizontal; one of its other axes within ``front_max_tilt`` of the
    vertical, as a door or drawer front stands), thinner than ``panel_ratio`` × its other extents?"""
    size = hi - lo
    others = [a for a in range(3) if a != k]
    upright = max(abs(R[2, a]) for a in others) >= np.cos(config.front_max_tilt)
    return bool(abs(R[2, k]) < 0.5 and upright and size[k] < config.panel_ratio * min(size[a] for a in others))


def _facing(normals: np.ndarray | None, mask: np.ndarray, axis_k: np.ndarray, config: FittingConfig) -> np.ndarray:
    """(n,) bool: the points whose ``normals`` (n, 3) lie along ``axis_k`` (3,) (|cos| > 0.5), i.e. the
    panel's face, not its edges: an edge seen from the side has its depth noise across the face's edge.
    By normals, not by the nearest face of the noise-inflated box, which gives the face's points near
    its edges to the side faces. ``mask`` (the points nearest the seen face) without normals or with fewer than
    ``front_edge_min_points`` such points."""
    if normals is None or len(normals) != len(mask):
        return mask
    m = np.abs(normals @ axis_k) > 0.5
    return m if m.sum() >= config.front_edge_min_points else mask


def _seen_side(normals: np.ndarray | None, mask: np.ndarray, axis_k: np.ndarray) -> bool | None:
    """Is a panel seen from its +k side (True) or its -k side (False) only? By the mean of its face
    points' (``mask``) oriented ``normals`` (n, 3) along ``axis_k`` (3,): |mean| > 0.5 when one side
    was seen. None when both sides were seen (a chair back) or without oriented normals (estimated
    normals have an arbitrary sign): such a panel keeps the noise-corrected extents."""
    if normals is None or len(normals) != len(mask) or not mask.any():
        return None
    m = float(np.mean(normals[mask] @ axis_k))
    return (m > 0) if abs(m) > 0.5 else None


def _half_density_edges(x: np.ndarray, config: FittingConfig,
                        fraction: float | None = None) -> tuple[float, float] | None:
    """(low, high) edges of the coordinates ``x`` (n,) of a face's points along one in-plane axis: where
    the density of points, from each end inwards, first reaches ``fraction`` (default
    ``front_edge_density``) × the density of the central half (linear between bin centres). None with
    too few points or a degenerate spread."""
    if len(x) < config.front_edge_min_points:
        return None
    q25, q75 = np.percentile(x, [25.0, 75.0])
    if q75 - q25 <= 1e-6:
        return None
    level = 0.5 * len(x) / (q75 - q25)                    # points per metre in the central half
    b = max(config.front_edge_min_bin, config.front_edge_bin_points / level)
    lo, hi = float(x.min()), float(x.max())
    nb = int(np.ceil((hi - lo) / b)) + 2
    if nb < 5:
        return None
    counts, edges = np.histogram(x, bins=nb, range=(lo - b, lo - b + nb * b))
    dens = counts / b
    centre = (edges[:-1] + edges[1:]) / 2
    thresh = (config.front_edge_density if fraction is None else fraction) * level
    full = np.flatnonzero(dens >= thresh)
    if len(full) == 0:
        return None

    def crossing(i: int, j: int) -> float:     # between centre j (below thresh) and centre i (above)
        t = (thresh - dens[j]) / max(dens[i] - dens[j], 1e-12)
        return float(centre[j] + t * (centre[i] - centre[j]))

    i_lo, i_hi = int(full[0]), int(full[-1])
    low = crossing(i_lo, i_lo - 1) if i_lo > 0 else float(centre[0])
    high = crossing(i_hi, i_hi + 1) if i_hi < nb - 1 else float(centre[-1])
    return low, high


def _rim_ends(x: np.ndarray, normals: np.ndarray | None, axis: np.ndarray,
              config: FittingConfig) -> tuple[bool, bool]:
    """(low end, high end) of the coordinates ``x`` (n,) along ``axis`` (3,) world: is that end made of
    points whose normals (n, 3) mostly lie across the axis (side faces seen edge-on)? (False, False)
    without normals."""
    if normals is None or len(normals) != len(x) or len(x) < 20:
        return False, False
    m = max(5, int(config.edge_tail_fraction * len(x)))
    order = np.argsort(x)
    across = np.abs(normals @ axis) < 0.5
    return bool(across[order[:m]].mean() > 0.5), bool(across[order[-m:]].mean() > 0.5)


def _slab_box(prim: Primitive, q: np.ndarray, k: int, plus: bool, config: FittingConfig) -> Primitive | None:
    """The box of a slab (a board, a table top) seen on its ``+k`` face (``plus``) or its ``-k`` face and
    on some of its edges, from its points ``q`` (n, 3) in the frame of ``prim`` (a box about them); None
    when the points do not show that.

    The seen face is the plane of the interior points (farther than ``slab_edge_band`` in-plane from the
    box's outline: only the face has points there): the box is turned so that axis ``k`` is that plane's
    normal (a minimum-volume box of a noisy board is tilted by the noise), the face is at the median of
    those points and the noise σ is their robust spread. The edges' points lie within the band and spread
    evenly across the thickness; those deeper than 2.5σ behind the seen face (no face noise reaches
    there) are spread evenly from that depth to the hidden face, which is therefore at twice their mean
    depth less 2.5σ. The in-plane extents are the 0.2 / 99.8 percentiles. Requires ``min_face_points``
    such edge points, interior points deeper than 2.5σ fewer than ``slab_hidden_fraction`` of the
    interior ones (the hidden face was not seen) and a box thinner than ``panel_ratio`` × its other extents.
    """
    inplane = [a for a in range(3) if a != k]
    if prim.size[k] >= config.panel_ratio * min(prim.size[a] for a in inplane):
        return None

    def interior_of(qq):
        lo, hi = np.percentile(qq, 0.2, axis=0), np.percentile(qq, 99.8, axis=0)
        band = np.zeros(len(qq), bool)
        for a in inplane:
            band |= (qq[:, a] - lo[a] < config.slab_edge_band) | (hi[a] - qq[:, a] < config.slab_edge_band)
        return band, lo, hi

    band, _, _ = interior_of(q)
    if (~band).sum() < max(config.min_face_points, 3):
        return None
    c = q[~band] - q[~band].mean(axis=0)
    normal = np.linalg.svd(c, full_matrices=False)[2][2]
    normal = normal if normal[k] > 0 else -normal
    e = np.zeros(3)
    e[k] = 1.0
    axis = np.cross(e, normal)
    angle = np.arctan2(np.linalg.norm(axis), normal[k])
    if angle > config.slab_max_tilt:
        return None
    R = Rotation.from_rotvec(axis / max(np.linalg.norm(axis), 1e-12) * angle).as_matrix() if angle > 1e-9 else np.eye(3)
    q = q @ R                              # coordinates in the turned frame (its axis k = the normal)
    band, lo, hi = interior_of(q)
    interior = q[~band, k]
    seen = float(np.median(interior))
    sigma = mad_sigma(interior)
    inward = -1.0 if plus else 1.0
    depth = (q[:, k] - seen) * inward
    cut = max(2.5 * sigma, config.slab_min_cut)
    if np.mean(depth[~band] > cut) >= config.slab_hidden_fraction:
        return None
    rim = depth[band & (depth > cut)]
    if len(rim) < config.min_face_points:
        return None
    far = seen + inward * max(2.0 * float(rim.mean()) - cut, config.min_thickness)
    lo[k], hi[k] = min(seen, far), max(seen, far)
    T = prim.T_world_part.copy()
    T[:3, :3] = T[:3, :3] @ R
    return _box_between(Primitive(PrimitiveKind.BOX, prim.size, T), lo, hi)


def _rimmed_slab(q: np.ndarray, k: int, normals: np.ndarray | None, R: np.ndarray, size: np.ndarray,
                 rim_high: bool, config: FittingConfig) -> tuple[float, float] | None:
    """(low, high) along axis ``k`` of a slab (a seat, a table top: thinner than ``panel_ratio`` x its other
    extents ``size`` (3,)) seen on one face, whose other end along ``k`` is the rim of its edges seen edge-on
    (``rim_high``: the high end), in depth noise too wide for :func:`_slab_box` (no edge point lies deeper than
    the face's noise reaches). ``q`` (n, 3) its points in the box's frame, whose axes are the columns of ``R``
    (3, 3) world; ``normals`` (n, 3) world, sign-free.

    The seen face is the median of the points whose normals lie along ``k`` (|cos| > 0.8): depth noise moves
    them symmetrically about it. The edges' points (normals across ``k``, |cos| < 0.5) spread evenly over the
    thickness and noise moves them symmetrically too, so their mean depth behind the seen face is half the
    thickness (their mean: the centroid of an even spread). None without normals, on a box no slab, or with
    fewer than ``min_face_points`` face or edge points."""
    if normals is None or len(normals) != len(q):
        return None
    if size[k] >= config.panel_ratio * min(size[a] for a in range(3) if a != k):
        return None
    along = np.abs(normals @ R[:, k])
    face, edge = along > 0.8, along < 0.5
    if face.sum() < config.min_face_points or edge.sum() < config.min_face_points:
        return None
    seen = float(np.median(q[face, k]))
    inward = 1.0 if rim_high else -1.0
    depth = float(np.mean((q[edge, k] - seen) * inward))
    thickness = max(2.0 * depth, config.min_thickness)
    return (seen, seen + thickness) if rim_high else (seen - thickness, seen)


def _turn(q: np.ndarray, n: np.ndarray, a: int) -> float:
    """How far the normals ``n`` (m, 3) of points ``q`` (m, 3) (both in a box's frame) on a face across
    axis ``a`` turn over it: the largest change, fitted linearly, of an in-plane normal component
    across the points' spread (0 on a plane, about 1 across a cylinder's visible side)."""
    turn = 0.0
    for b in range(3):
        if b != a and len(q) >= 3 and np.ptp(q[:, b]) > 0:
            slope = np.polyfit(q[:, b], n[:, b], 1)[0]
            turn = max(turn, abs(slope) * float(np.ptp(q[:, b])))
    return turn


def _curved(q: np.ndarray, mask: np.ndarray, k: int, normals: np.ndarray | None, R: np.ndarray,
            config: FittingConfig) -> bool:
    """Is the best-seen face of a box (its points ``mask`` (n,) of ``q`` (n, 3) in the box's frame, across
    axis ``k``; axes the columns of ``R`` (3, 3) world) a curved surface: do the ``normals`` (n, 3, world)
    of those of its points facing along ``k`` turn by more than ``seen_face_max_turn`` across it?"""
    if normals is None or len(normals) != len(q):
        return False
    n_part = normals @ R
    face = mask & (np.abs(n_part[:, k]) > 0.8)
    return face.sum() >= config.min_face_points and _turn(q[face], n_part[face], k) > config.seen_face_max_turn


def _seen_faces(q: np.ndarray, a: int, normals: np.ndarray | None, R: np.ndarray, lo: float, hi: float,
                config: FittingConfig, wide: bool = False) -> tuple[float, float]:
    """(low, high) ends along axis ``a`` of a box whose points ``q`` (n, 3) in its frame (axes the columns
    of ``R`` (3, 3) world) extend over [``lo``, ``hi``] along it (percentiles, overshooting by the noise).

    An end is a face seen across its plane when most of its outermost points (``edge_tail_fraction``, at
    least ``min_face_points``) have normals (n, 3, world) along the axis (|cos| > 0.8): it is moved to the
    median coordinate of the points with such normals within ``seen_face_band`` of it (depth noise is
    symmetric about the surface), if that median is within half the band of it (a median deeper in is an
    inner face seen beside the end: a cabinet's bottom panel) and those points are flat (their normals do
    not turn with their position across the face by more than ``seen_face_max_turn`` over it, as on a
    cylinder's side). An end made of other faces' edges is kept. Unchanged without normals.
    """
    x = q[:, a]
    m = max(config.min_face_points, int(config.edge_tail_fraction * len(x)))
    if normals is None or len(normals) != len(x) or len(x) < 4 * m:
        return lo, hi
    n_part = normals @ R                                   # normals in the box's frame
    order = np.argsort(x)
    along = np.abs(n_part[:, a]) > 0.8
    out = [lo, hi]
    for end, tail in ((0, order[:m]), (1, order[-m:])):
        if along[tail].mean() <= 0.5:
            continue
        if wide:
            face, near = _face_from_end(x, along, out[end], config)
            if face is None:
                continue
        else:
            near = along & (np.abs(x - out[end]) < config.seen_face_band)
            if near.sum() < config.min_face_points:
                continue
            face = float(np.median(x[near]))
            if abs(face - out[end]) > config.seen_face_band / 2:
                continue
        if _turn(q[near], n_part[near], a) <= config.seen_face_max_turn:
            out[end] = face
    return (out[0], out[1]) if out[1] - out[0] >= config.min_thickness else (lo, hi)


def _face_from_end(x: np.ndarray, along: np.ndarray, end: float, config: FittingConfig
                   ) -> tuple[float | None, np.ndarray]:
    """(the face, its points (n,) bool) of a box end at ``end`` whose face points (``along``: normals across
    the face) spread wider than ``seen_face_band`` by depth noise, from their coordinates ``x`` (n,): the
    median of the along-points in a window from ``end`` to as far past the median as ``end`` lies before it
    (plus the band), re-taken until it settles -- noise is symmetric about the surface, so the window's median
    is the face once the window is centred on it. None when it does not settle, or settles farther in than
    3 of the window's robust sigmas + half the band (an inner face seen beside the end)."""
    sign = 1.0 if end <= float(np.median(x)) else -1.0       # inwards
    d = (x - end) * sign                                      # depth behind the end
    face = float(config.seen_face_band / 2)
    near = along & (d < config.seen_face_band)
    for _ in range(20):
        near = along & (d > -config.seen_face_band) & (d < 2.0 * face + config.seen_face_band)
        if near.sum() < config.min_face_points:
            return None, near
        new = float(np.median(d[near]))
        if abs(new - face) < 1e-4:
            break
        face = new
    else:
        return None, near
    sigma = mad_sigma(d[near])
    if face > 3.0 * sigma + config.seen_face_band / 2:
        return None, near
    return end + sign * face, near


def _icp_refined(prim: Primitive, score: FitScore, points: np.ndarray, normals: np.ndarray,
                 config: FittingConfig, rng: np.random.Generator) -> Primitive:
    from recon.open3d_engine import icp_point_to_plane

    samples, face = prim.sample_surface(config.surface_samples, rng)
    src = samples[np.isin(face, score.observed_faces)]
    if len(src) < 10:
        return prim
    T, _ = icp_point_to_plane(src, points, normals, max_distance=config.icp_max_distance,
                              iterations=config.icp_iterations)
    return prim.transformed(T)


def fit_part(points: np.ndarray, config: FittingConfig, *, seed: int = 0,
             normals: np.ndarray | None = None, R_world_ref: np.ndarray | None = None, align: bool = True,
             front: bool = False) -> tuple[str, Primitive, FitScore, dict[str, float]]:
    """Eq. 3 for one part: ``points`` (n, 3) world -> (winner name, primitive, its score, {name: total}).

    Deterministic for a given ``seed``. ``normals`` (n, 3) are estimated when not given.
    ``R_world_ref`` (3, 3): extra candidates aligned with these axes (see candidate_primitives).
    ``align`` False: no ICP, the candidates keep their frames (with ``R_world_ref``: those axes).
    ``front``: the part is a drawer or door front (its noise correction reads the seen face from the
    normals, :func:`_denoised`).
    """
    from recon.open3d_engine import estimate_normals

    points = np.asarray(points, dtype=np.float64)
    rng = np.random.default_rng(seed)
    if len(points) > config.fit_max_points:
        idx = np.sort(rng.choice(len(points), config.fit_max_points, replace=False))
        points = points[idx]
        normals = None if normals is None else normals[idx]
    if normals is None or len(normals) != len(points):
        normals = estimate_normals(points)
    tree = cKDTree(points)
    best = None
    table: dict[str, float] = {}
    cands = candidate_primitives(points, config, R_world_ref, normals)
    cands = {k: denoised_box(v, points, config, normals, front) for k, v in cands.items()}   # no-op on clean scans
    initial = {name: (prim, score_primitive(prim, points, tree, config, np.random.default_rng(seed)))
               for name, prim in cands.items()}
    cutoff = config.icp_candidate_ratio * min(s.total for _, s in initial.values())
    for name, (prim, s0) in initial.items():
        if s0.total > cutoff:          # hopeless before alignment: ICP will not rescue it
            table[name] = s0.total
            continue
        s = s0
        if align:
            moved = _icp_refined(prim, s0, points, normals, config, np.random.default_rng(seed + 1))
            s1 = score_primitive(moved, points, tree, config, np.random.default_rng(seed))
            prim, s = (moved, s1) if s1.total < (1.0 - config.icp_min_improvement) * s0.total else (prim, s0)
        if prim.kind is PrimitiveKind.BOX:
            variant, board = _denoised(prim, points, config, normals, front)
            s2 = score_primitive(variant, points, tree, config, np.random.default_rng(seed))
            # a front's board is not judged by Eq. 3: on a noise slab thicker than the board the score
            # prefers a box centred in the noise (ICP moves it there), half a board too far out
            prim, s = (variant, s2) if board or s2.total < s.total else (prim, s)
        table[name] = s.total
        # Occam prior: a non-box must beat the boxes by ``box_preference`` (furniture is mostly boxes)
        rank = s.total * (1.0 if prim.kind is PrimitiveKind.BOX else 1.0 + config.box_preference)
        if best is None or rank < best[3] - 1e-12:
            best = (name, prim, s, rank)
    return best[0], best[1], best[2], table


@dataclass(frozen=True, eq=False)
class CoveredFit:
    """:func:`fit_part_covering`'s answer: the winner's name, primitive, score and {name: total} table as
    :func:`fit_part` gives them, the kinds refused because their fit did not cover the points (in the
    order refused) and the coverage problems of the fit kept (empty when it covers its points)."""

    name: str
    primitive: Primitive
    score: FitScore
    table: dict
    refused: tuple[str, ...]
    problems: tuple[str, ...]


def fit_part_covering(points: np.ndarray, config: FittingConfig, coverage_config: CoverageConfig, *,
                      seed: int = 0, normals: np.ndarray | None = None,
                      R_world_ref: np.ndarray | None = None, front: bool = False) -> CoveredFit:
    """:func:`fit_part`, then the fit checked against its points (:mod:`recon.coverage`: mean distance,
    share covered, volume against the points' oriented box); a fit outside the bounds is refitted with
    the candidates of the other kinds (box, cylinder, sphere), kind by kind, until one covers the points.
    When none does, the fit with the fewest problems (the first fit on a tie) is kept with its problems.
    ``points`` (n, 3) world; the other arguments as for :func:`fit_part`."""
    def attempt(cfg):
        name, prim, score, table = fit_part(points, cfg, seed=seed, normals=normals, R_world_ref=R_world_ref,
                                            front=front)
        cov = coverage(prim, prim, points, coverage_config, normals)
        return name, prim, score, table, tuple(coverage_problems(cov, coverage_config))

    best = current = attempt(config)
    refused: list[str] = []
    while current[4]:
        refused.append(current[1].kind.value)
        left = tuple(c for c in config.candidates if _candidate_kind(c) not in refused)
        if not left:
            break
        current = attempt(dataclasses.replace(config, candidates=left))
        if len(current[4]) < len(best[4]):
            best = current
    return CoveredFit(*best[:4], tuple(refused), best[4])


def _candidate_kind(name: str) -> str:
    """The primitive kind ("box", "cylinder", "sphere") of a candidate name (``cylinder_x``, ``box@yaw``)."""
    return name.split("@")[0].split("_")[0]


def body_behind_face(prim: Primitive, normals: np.ndarray | None, config: FittingConfig) -> Primitive | None:
    """A body (a cabinet's carcass) whose fitted box is a panel — its points show one face only — as a
    box as deep as its narrower side behind that face (a documented prior: the depth no scan shows); the
    seen side is the one its points' oriented ``normals`` (n, 3, world) point to. None when the box is
    no panel (thinnest extent at least ``panel_ratio`` × the next) or the normals do not tell the side."""
    if prim.kind is not PrimitiveKind.BOX or normals is None or not len(normals):
        return None
    order = np.argsort(prim.size)
    k = int(order[0])
    if prim.size[k] >= config.panel_ratio * prim.size[order[1]]:
        return None
    axis = prim.T_world_part[:3, k]
    m = float(np.mean(normals @ axis))
    if abs(m) <= 0.5:
        return None
    h = prim.size / 2
    lo, hi = -h.copy(), h.copy()
    depth = float(prim.size[order[1]])
    if m > 0:                              # seen from +k: the body lies behind, toward -k
        lo[k] = hi[k] - depth
    else:
        hi[k] = lo[k] + depth
    return _box_between(prim, lo, hi)
