"""A thin board (a chair seat, a table top) seen from above through ScanNet-style depth noise (sigma 1.5 cm on
its top, about the board's 4 cm thickness): its top is the median of its top's points and its thickness twice the
mean depth of its edges' points behind it (recon.fitting._rimmed_slab). Session 15's scannet chair seats were
fitted 5-15 cm thick, their tops up to 2.6 cm low (the 0.2 / 99.8 percentiles pulled in by 2.9 sigma of a noise
spread widened by the edges' points)."""

from __future__ import annotations

import numpy as np
import pytest

from recon.config import ReconConfig
from recon.fitting import _rimmed_slab, denoised_box
from recon.primitive import Primitive, PrimitiveKind

CFG = ReconConfig().fitting
TOP, THICK, SIDE = 0.446, 0.04, 0.45


def seat(seed: int, sigma: float = 0.015):
    """A 0.45 x 0.45 x 0.04 m board (top at z 0.446) seen on its top (400 points, depth noise ``sigma`` along z,
    normals +z) and on two of its edges (140 points spread evenly over the thickness, 0.5 sigma of noise
    across the edge, normals horizontal); its points' axis-aligned box, as the candidates are built."""
    rng = np.random.default_rng(seed)
    h = SIDE / 2
    top = np.c_[rng.uniform(-h, h, (400, 2)), TOP + np.clip(rng.normal(0, sigma, 400), -2.5 * sigma, 2.5 * sigma)]
    n_top = np.tile([0.0, 0.0, 1.0], (400, 1))
    z = rng.uniform(TOP - THICK, TOP, 140)
    along = rng.uniform(-h, h, 140)
    off = rng.normal(0, sigma / 2, 140)
    edge = np.r_[np.c_[along[:70], h + off[:70], z[:70]], np.c_[h + off[70:], along[70:], z[70:]]]
    n_edge = np.r_[np.tile([0.0, 1.0, 0.0], (70, 1)), np.tile([1.0, 0.0, 0.0], (70, 1))]
    pts, nrm = np.r_[top, edge], np.r_[n_top, n_edge]
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    T = np.eye(4)
    T[:3, 3] = (lo + hi) / 2
    return pts, nrm, Primitive(PrimitiveKind.BOX, hi - lo, T)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_thin_board_in_wide_noise_keeps_its_top_and_thickness(seed):
    pts, nrm, box = seat(seed)
    out = denoised_box(box, pts, CFG, nrm)
    z = out.corners()[:, 2]
    assert abs(z.max() - TOP) < 0.006, z.max()
    assert abs((z.max() - z.min()) - THICK) < 0.01, z.max() - z.min()


def test_a_box_that_is_no_slab_is_left_to_the_other_rules():
    pts, nrm, box = seat(0)
    cube = Primitive(PrimitiveKind.BOX, np.array([0.45, 0.45, 0.2]), box.T_world_part)
    q = cube.to_part(pts)
    assert _rimmed_slab(q, 2, nrm, np.eye(3), cube.size, False, CFG) is None
    # and a board without normals (nothing tells its face from its edges)
    assert _rimmed_slab(box.to_part(pts), 2, None, np.eye(3), box.size, False, CFG) is None
