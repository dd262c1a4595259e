"""Completion of half-seen legs and knobs, noise-aware box extents, RANSAC planes."""

import numpy as np
import pytest
import trimesh

from recon.completion import complete_mounted_parts, complete_vertical_parts
from recon.config import ReconConfig
from recon.contacts import contact_edge
from recon.fitting import denoised_box, dominant_yaw
from recon.planes import ransac_planes
from recon.primitive import Primitive

CFG = ReconConfig()


def at(x, y, z):
    T = np.eye(4)
    T[:3, 3] = [x, y, z]
    return T


def test_a_short_leg_is_extended_to_the_top_and_the_floor():
    top = Primitive("box", [1.0, 0.8, 0.04], at(0, 0, 0.74))              # underside at z = 0.72
    leg = Primitive("cylinder", [0.05, 0.05, 0.55], at(0.4, 0.3, 0.05 + 0.275))  # 0.05 .. 0.60
    assert contact_edge(1, top.planes(), 2, leg.planes(), CFG.contacts) is None
    out, changes = complete_vertical_parts({1: top, 2: leg}, {1: "top", 2: "leg"}, CFG.completion, CFG.contacts)
    c = out[2].corners()[:, 2]
    assert c.min() == pytest.approx(0.0, abs=1e-9) and c.max() == pytest.approx(0.72, abs=1e-9)
    assert changes[2] == pytest.approx((0.05, 0.12))
    assert out[1] is top
    assert contact_edge(1, top.planes(), 2, out[2].planes(), CFG.contacts) is not None
    # a leg not under the top (outside its outline) is left alone
    far = Primitive("cylinder", [0.05, 0.05, 0.55], at(0.8, 0.3, 0.325))
    out, _ = complete_vertical_parts({1: top, 2: far}, {1: "top", 2: "leg"}, CFG.completion, CFG.contacts)
    assert out[2].corners()[:, 2].max() == pytest.approx(0.6)


def test_a_floating_knob_is_extended_back_onto_its_drawer():
    drawer = Primitive("box", [0.02, 0.6, 0.2], at(0.49, 0, 0.5))          # front face at x = 0.5
    R = np.eye(4)
    R[:3, :3] = [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]                         # cylinder axis along x
    R[:3, 3] = [0.53, 0.0, 0.5]
    knob = Primitive("cylinder", [0.03, 0.03, 0.02], R)                    # 0.52 .. 0.54: 2 cm gap
    out, changes = complete_mounted_parts({1: drawer, 2: knob}, {1: "drawer", 2: "knob"}, CFG.completion, CFG.contacts)
    assert changes[2] == pytest.approx(0.02)
    assert out[2].corners()[:, 0].min() == pytest.approx(0.5)
    assert out[2].corners()[:, 0].max() == pytest.approx(0.54)


def test_denoised_box_undoes_depth_noise_inflation_and_leaves_clean_boxes_alone():
    rng = np.random.default_rng(1)
    n = 4000
    pts = np.c_[rng.normal(0.0, 0.01, n), rng.uniform(-0.3, 0.3, n), rng.uniform(0, 0.8, n)]  # a noisy panel
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    noisy = Primitive("box", hi - lo, at(*((lo + hi) / 2)))
    assert noisy.size[0] > 0.06                                           # min/max: ~7 sigma thick
    fixed = denoised_box(noisy, pts, CFG.fitting)
    assert fixed.size[0] < 0.025 and np.allclose(fixed.size[1:], [0.6, 0.8], atol=0.01)
    clean = np.c_[np.zeros(n), pts[:, 1:]]
    box = Primitive("box", [0.018, 0.6, 0.8], at(-0.009, 0, 0.4))
    assert denoised_box(box, clean, CFG.fitting) is box


def test_dominant_yaw_of_box_normals():
    yaw = 0.3
    c, s = np.cos(yaw), np.sin(yaw)
    n = np.array([[c, s, 0], [-s, c, 0], [-c, -s, 0], [s, -c, 0], [0, 0, 1]] * 20, float)
    n += np.random.default_rng(0).normal(0, 0.02, n.shape)
    assert dominant_yaw(n) == pytest.approx(yaw, abs=0.01)
    assert dominant_yaw(np.tile([0.0, 0.0, 1.0], (50, 1))) is None


def test_ransac_planes_are_the_seen_faces_with_outward_normals():
    mesh = trimesh.creation.box([0.4, 0.6, 0.8], transform=at(1, 0, 0.4))
    pts, _ = trimesh.sample.sample_surface(mesh, 6000, seed=0)
    planes = ransac_planes(pts, CFG.contacts, seed=0)
    assert len(planes) == 6
    for pl in planes:
        assert pl.normal @ np.array([1, 0, 0.4]) + pl.d < 0                # centre behind the face
        k = int(np.argmax(np.abs(pl.normal)))
        assert abs(pl.normal[k]) > 0.999
        assert abs(abs(pl.d + pl.normal[k] * [1, 0, 0.4][k]) - [0.2, 0.3, 0.4][k]) < 0.005
