"""Individual part alignment (Eq. 3): the best primitive for one part's points.

Candidates M^c come from the part's oriented bounding box (box, a cylinder along each box axis,
sphere). Each is aligned to the points by point-to-plane ICP (open3d) and scored; the lowest score wins.

Score. Eq. 3 is the mean distance from points sampled on the primitive's surface h(M) to the part's
points P. A scan only covers the faces a camera saw: the back of a cabinet against a wall, the
underside of a table top, the inside of a leg pair are missing, and Eq. 3 then charges the true
primitive for faces that are really there. We therefore (a) leave out the primitive's faces whose
samples are mostly farther than ``coverage_distance`` from any point (unobserved faces) and (b) add
the mean distance from the points to the primitive's surface, so that dropping faces can never make a
wrong primitive look good. ``bench/recon_fit_score.py`` (if present) measures both scores.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from recon.bounding import oriented_box
from recon.config import ReconConfig
from recon.primitive import Primitive, PrimitiveKind

__all__ = ["FitScore", "candidate_primitives", "score_primitive", "fit_part"]

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


def candidate_primitives(points: np.ndarray, config: ReconConfig) -> dict[str, Primitive]:
    """Candidate primitives scaled from the minimum-volume oriented box of ``points`` (n, 3)."""
    T, ext = oriented_box(points, min_thickness=config.min_thickness,
                          upright_tolerance=config.upright_tolerance)
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
            raise ValueError(f"unknown primitive candidate {name!r} in ReconConfig.candidates")
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


def score_primitive(prim: Primitive, points: np.ndarray, tree: cKDTree, config: ReconConfig,
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


def _icp_refined(prim: Primitive, score: FitScore, points: np.ndarray, normals: np.ndarray,
                 config: ReconConfig, rng: np.random.Generator) -> Primitive:
    from recon.open3d_engine import icp_point_to_plane

    samples, face = prim.sample_surface(config.surface_samples, rng)
    src = samples[np.isin(face, score.observed_faces)]
    if len(src) < 10:
        return prim
    T, _ = icp_point_to_plane(src, points, normals, max_distance=config.icp_max_distance,
                              iterations=config.icp_iterations)
    return prim.transformed(T)


def fit_part(points: np.ndarray, config: ReconConfig = ReconConfig(), *, seed: int = 0,
             normals: np.ndarray | None = None) -> tuple[str, Primitive, FitScore, dict[str, float]]:
    """Eq. 3 for one part: ``points`` (n, 3) world -> (winner name, primitive, its score, {name: total}).

    Deterministic for a given ``seed``. ``normals`` (n, 3) are estimated when not given.
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
    initial = {name: (prim, score_primitive(prim, points, tree, config, np.random.default_rng(seed)))
               for name, prim in candidate_primitives(points, config).items()}
    cutoff = config.icp_candidate_ratio * min(s.total for _, s in initial.values())
    for name, (prim, s0) in initial.items():
        if s0.total > cutoff:          # hopeless before alignment: ICP will not rescue it
            table[name] = s0.total
            continue
        moved = _icp_refined(prim, s0, points, normals, config, np.random.default_rng(seed + 1))
        s1 = score_primitive(moved, points, tree, config, np.random.default_rng(seed))
        prim, s = (moved, s1) if s1.total < s0.total else (prim, s0)
        table[name] = s.total
        if best is None or s.total < best[2].total - 1e-12:
            best = (name, prim, s)
    return best[0], best[1], best[2], table
