"""recon.post_section: a leg's section from its faces' points. At ScanNet-style depth noise (sigma 2-3 cm
along the rays, one return kept per 3.5 cm voxel) a 4 cm chair leg's points form a blob 10-15 cm across;
Eq. 3 fitted it as a 12-20 cm x 1 cm board (IoU 0.2-0.35 per leg on every chair of the scannet preset)."""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from recon.config import ReconConfig
from recon.pipeline import _Run, fit_primitives
from recon.post_section import post_primitive
from recon.primitive import PrimitiveKind
from recon.scan import ObjectPoints, PartPoints

CFG = ReconConfig()
R_LEVEL = np.eye(3)


def _noisy(p: np.ndarray, n: np.ndarray, sigma: float, rng) -> np.ndarray:
    """Points ``p`` (m, 3) moved along rays that meet their faces (normals ``n``) up to 50 deg off the
    normal, by N(0, sigma) metres: depth noise along the ray, with a part across the face."""
    yaw = rng.uniform(-0.87, 0.87, len(p))
    pitch = rng.uniform(-0.5, 0.2, len(p))
    rays = np.stack([Rotation.from_euler("zy", [a, b]).apply(v) for a, b, v in zip(yaw, pitch, n)])
    return p + rays * rng.normal(0.0, sigma, len(p))[:, None]


def box_leg(centre, width, height, faces, n_face, sigma, seed):
    """Points and outward normals on the given ``faces`` (of "+x", "-x", "+y", "-y") of a vertical box leg."""
    rng = np.random.default_rng(seed)
    pts, nrm = [], []
    for f in faces:
        a = "xy".index(f[1])
        s = 1.0 if f[0] == "+" else -1.0
        q = np.c_[rng.uniform(-width / 2, width / 2, (n_face, 2)), rng.uniform(0.0, height, n_face)]
        q[:, a] = s * width / 2
        n = np.zeros((n_face, 3))
        n[:, a] = s
        pts.append(q + [centre[0], centre[1], 0.0])
        nrm.append(n)
    p, n = np.concatenate(pts), np.concatenate(nrm)
    return _noisy(p, n, sigma, rng), n


def round_leg(centre, radius, height, n, sigma, seed):
    """Points and normals on the half of a vertical cylinder a camera at -y sees."""
    rng = np.random.default_rng(seed)
    t = rng.uniform(np.pi, 2 * np.pi, n)
    nrm = np.c_[np.cos(t), np.sin(t), np.zeros(n)]
    p = np.c_[centre[0] + radius * nrm[:, 0], centre[1] + radius * nrm[:, 1], rng.uniform(0.0, height, n)]
    return _noisy(p, nrm, sigma, rng), nrm


def _fit(p):
    from recon.fitting import fit_part

    return fit_part(p, CFG.fitting, normals=None, R_world_ref=R_LEVEL, align=False)[1]


def _section(prim):
    return np.sort(prim.size)[:2]


def test_a_noisy_square_legs_section_is_its_faces_not_its_points_spread():
    for seed in range(4):
        p, n = box_leg((0.3, -0.2), 0.04, 0.43, ("+x", "-x", "+y", "-y"), 40, 0.02, seed)
        post = post_primitive(p, n, R_LEVEL, _fit(p), CFG.fitting)
        assert post.kind is PrimitiveKind.BOX
        assert np.all(np.abs(_section(post) - 0.04) < 0.012), post.size
        assert np.linalg.norm(post.center[:2] - [0.3, -0.2]) < 0.01


def test_a_leg_seen_on_two_adjacent_faces_takes_its_centre_from_the_faces_across():
    # a chair tucked under a table: only its +x and +y faces seen
    for seed in range(4):
        p, n = box_leg((0.0, 0.0), 0.04, 0.4, ("+x", "+y"), 40, 0.02, seed)
        post = post_primitive(p, n, R_LEVEL, _fit(p), CFG.fitting)
        assert np.all(np.abs(_section(post) - 0.04) < 0.02), post.size
        assert np.linalg.norm(post.center[:2]) < 0.015


def test_a_clean_legs_section_is_exact():
    p, n = box_leg((0.1, 0.1), 0.05, 0.7, ("+x", "-x", "+y", "-y"), 50, 0.0, 0)
    post = post_primitive(p, n, R_LEVEL, _fit(p), CFG.fitting)
    assert np.allclose(_section(post), 0.05, atol=1e-9) and np.allclose(post.center[:2], 0.1, atol=1e-9)


def test_a_round_leg_is_a_cylinder_of_its_radius():
    for seed in range(4):
        p, n = round_leg((0.0, 0.0), 0.02, 0.4, 120, 0.02, seed)
        post = post_primitive(p, n, R_LEVEL, _fit(p), CFG.fitting)
        assert post.kind is PrimitiveKind.CYLINDER
        assert abs(post.size[0] - 0.04) < 0.015 and np.linalg.norm(post.center[:2]) < 0.015


def test_what_shows_no_post_is_refused():
    # a pedestal table's foot disc (labelled leg): wide, not tall
    p, n = round_leg((0.0, 0.0), 0.25, 0.03, 200, 0.0, 1)
    assert post_primitive(p, n, R_LEVEL, _fit(p), CFG.fitting) is None
    # one face only: nothing says where the leg's centre is across it
    p, n = box_leg((0.0, 0.0), 0.04, 0.4, ("+x",), 40, 0.0, 2)
    assert post_primitive(p, n, R_LEVEL, _fit(p), CFG.fitting) is None
    # no normals
    assert post_primitive(p, None, R_LEVEL, _fit(p), CFG.fitting) is None


def test_the_pipeline_fits_noisy_chair_legs_as_posts():
    rng = np.random.default_rng(7)
    m = 900
    top = np.c_[rng.uniform(-0.22, 0.22, (m, 2)), np.full(m, 0.47)]
    seat_n = np.tile([0.0, 0.0, 1.0], (m, 1))
    parts = [PartPoints(1, 10, "seat", _noisy(top, seat_n, 0.004, rng), seat_n)]
    for k, (x, y) in enumerate([(-0.2, -0.2), (-0.2, 0.2), (0.2, -0.2), (0.2, 0.2)]):
        p, n = box_leg((x, y), 0.04, 0.43, ("+x", "-x", "+y", "-y") if k % 2 else ("+x", "+y"), 30, 0.025, k)
        parts.append(PartPoints(1, 11 + k, "leg", p, n))
    state = fit_primitives(ObjectPoints(1, "chair", tuple(parts)), _Run(CFG, 0, []))
    for k in range(4):
        leg = state.prims[11 + k]
        assert np.all(np.sort(leg.size)[:2] < 0.065), leg.size
