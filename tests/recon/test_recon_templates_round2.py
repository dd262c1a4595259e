"""Second-round template priors: designed neighbour contacts (bed), hidden fourth legs, slab rims."""

import numpy as np
import pytest

from recon.completion import complete_missing_legs
from recon.config import ReconConfig
from recon.fitting import denoised_box
from recon.model import ContactEdge, JointEstimate, JointType, ObjectReconstruction, PartFit
from recon.part_tree import contact_scores
from recon.primitive import Primitive
from recon.scan import PartPoints
from recon.templates import expected_contact

CFG = ReconConfig()


def at(x, y, z):
    T = np.eye(4)
    T[:3, 3] = [x, y, z]
    return T


def test_bed_headboard_mattress_is_a_designed_contact_and_leg_headboard_is_not():
    assert expected_contact("bed", "headboard", "mattress")
    assert expected_contact("bed", "mattress", "headboard")
    assert not expected_contact("bed", "leg", "headboard")
    assert not expected_contact("cabinet", "drawer", "drawer")
    assert expected_contact("bed", "frame", "leg")


def _bed(contacts):
    labels = {1: "frame", 2: "leg", 6: "headboard", 7: "mattress"}
    box = Primitive("box", [0.1, 0.1, 0.1], at(0, 0, 0))
    parts = tuple(PartFit(i, lab, f"bed1_{lab}{i}", box, 0.0, {}, 100, ()) for i, lab in labels.items())
    joints = (JointEstimate("bed1_frame1_joint", JointType.FIXED, None, 1, [0, 0, 1], [0, 0, 0]),) + tuple(
        JointEstimate(f"bed1_{lab}{i}_joint", JointType.FIXED, 1, i, [0, 0, 1], [0, 0, 0], contact_score=1.0)
        for i, lab in labels.items() if i != 1)
    edges = tuple(ContactEdge(p, c, s, 1.0, 0.0, 0, 0) for p, c, s in contacts)
    return ObjectReconstruction(1, "bed", "bed1", 1, parts, edges, joints, (), np.eye(4), np.ones(3))


def test_bed_mattress_against_headboard_outranks_a_leg_touching_the_headboard():
    # measured on bedroom seed 0 (clean): both raw Cont ~1.0; the true edge must not tie the false one
    bed = _bed([(1, 2, 1.0), (1, 6, 1.0), (1, 7, 1.0), (6, 7, 1.0), (6, 2, 0.996)])
    s = contact_scores(bed, CFG.tree)
    assert s[(6, 7)] == pytest.approx(1.0)
    assert s[(2, 6)] == pytest.approx(0.996 * CFG.tree.foreign_parent_penalty)
    assert s[(6, 7)] > s[(2, 6)]


def _legs(skip):
    corners = {2: (0.0, 0.0), 3: (1.8, 0.0), 4: (1.8, 1.2), 5: (0.0, 1.2)}
    prims = {i: Primitive("box", [0.06, 0.06, 0.15], at(x, y, 0.075)) for i, (x, y) in corners.items() if i != skip}
    prims[1] = Primitive("box", [1.9, 1.3, 0.1], at(0.9, 0.6, 0.2))
    labels = {i: ("frame" if i == 1 else "leg") for i in prims}
    return prims, labels, corners[skip]


def test_a_hidden_fourth_leg_is_placed_at_the_missing_corner():
    prims, labels, (x, y) = _legs(skip=4)
    out, placed = complete_missing_legs("bed", prims, labels, (PartPoints(1, 4, "leg", np.zeros((0, 3))),), CFG.completion)
    assert set(placed) == {4}
    assert np.allclose(out[4].center, [x, y, 0.075])
    assert np.allclose(out[4].size, [0.06, 0.06, 0.15])
    assert set(out) == set(prims) | {4}


def test_a_hidden_leg_whose_few_points_lie_elsewhere_is_not_placed():
    prims, labels, (x, y) = _legs(skip=4)
    far = np.array([[x - 0.9, y - 0.6, 0.05]] * 5)              # 1 m from the missing corner
    out, placed = complete_missing_legs("bed", prims, labels, (PartPoints(1, 4, "leg", far),), CFG.completion)
    assert placed == {} and set(out) == set(prims)
    near = np.array([[x + 0.01, y - 0.02, 0.05]] * 5)
    _, placed = complete_missing_legs("bed", prims, labels, (PartPoints(1, 4, "leg", near),), CFG.completion)
    assert set(placed) == {4}


def test_no_leg_is_placed_for_a_cabinet_or_legs_that_span_no_right_angle():
    prims, labels, _ = _legs(skip=4)
    skipped = (PartPoints(1, 4, "leg", np.zeros((0, 3))),)
    assert complete_missing_legs("cabinet", prims, labels, skipped, CFG.completion)[1] == {}
    prims[5] = Primitive("box", [0.06, 0.06, 0.15], at(0.9, 0.6, 0.075))   # collinear-ish, not a corner
    assert complete_missing_legs("bed", prims, labels, skipped, CFG.completion)[1] == {}


def test_a_table_top_seen_from_above_keeps_its_rim_thickness():
    """A 27 mm top: a noisy upper face (σ 5 mm along z, normals up) and edge faces seen edge-on
    (normals sideways) down to its hidden underside. Pulling both ends of z in by the upper face's
    noise made it 15 mm thick (realistic random/1 table); only the noise-tail end is pulled."""
    rng = np.random.default_rng(3)
    t, n_top, n_rim = 0.027, 6000, 800
    top = np.c_[rng.uniform(-0.7, 0.7, n_top), rng.uniform(-0.4, 0.4, n_top), t / 2 + rng.normal(0, 0.005, n_top)]
    rim = np.c_[rng.choice([-0.7, 0.7], n_rim) + rng.normal(0, 0.002, n_rim), rng.uniform(-0.4, 0.4, n_rim),
                rng.uniform(-t / 2, t / 2, n_rim)]
    pts = np.vstack([top, rim])
    nrm = np.vstack([np.tile([0, 0, 1.0], (n_top, 1)), np.c_[np.sign(rim[:, 0]), np.zeros(n_rim), np.zeros(n_rim)]])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    raw = Primitive("box", hi - lo, at(*((lo + hi) / 2)))
    fixed = denoised_box(raw, pts, CFG.fitting, nrm)
    c = fixed.corners()[:, 2]
    assert c.min() == pytest.approx(-t / 2, abs=0.003)          # the rim's bottom is kept
    assert c.max() == pytest.approx(t / 2, abs=0.004)           # the noisy face is pulled in
    blind = denoised_box(raw, pts, CFG.fitting)                         # without normals: both ends pulled
    assert blind.size[2] < fixed.size[2] - 0.01


def test_a_handle_bar_is_no_rim_both_ends_of_its_noise_are_pulled_in():
    """A 12 mm bar seen from the front: its front face (normals sideways) is noise, not a rim; keeping
    it made a demo handle 40 mm tall and the grasp missed it."""
    rng = np.random.default_rng(4)
    n_top, n_front = 2000, 1000
    top = np.c_[rng.uniform(-0.1, 0.1, n_top), rng.uniform(-0.006, 0.006, n_top), 0.006 + rng.normal(0, 0.006, n_top)]
    front = np.c_[rng.uniform(-0.1, 0.1, n_front), 0.006 + rng.normal(0, 0.006, n_front),
                  rng.uniform(-0.006, 0.006, n_front)]
    pts = np.vstack([top, front])
    nrm = np.vstack([np.tile([0, 0, 1.0], (n_top, 1)), np.tile([0, 1.0, 0], (n_front, 1))])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    raw = Primitive("box", hi - lo, at(*((lo + hi) / 2)))
    assert denoised_box(raw, pts, CFG.fitting, nrm).isclose(denoised_box(raw, pts, CFG.fitting))
    import dataclasses
    anywhere = dataclasses.replace(CFG.fitting, rim_min_extent=0.0)     # the rule without its size guard
    assert not denoised_box(raw, pts, anywhere, nrm).isclose(denoised_box(raw, pts, anywhere))


def test_two_hidden_legs_are_placed_from_two_seen_ones_and_the_frame():
    corners = {2: (0.0, 0.0), 3: (1.8, 0.0), 4: (1.8, 1.2), 5: (0.0, 1.2)}
    frame = Primitive("box", [1.9, 1.3, 0.1], at(0.9, 0.6, 0.2))
    for seen in ((2, 3), (2, 4)):                       # adjacent (mirrored about the frame) and diagonal
        prims = {i: Primitive("box", [0.06, 0.06, 0.15], at(*corners[i], 0.075)) for i in seen}
        prims[1] = frame
        labels = {i: ("frame" if i == 1 else "leg") for i in prims}
        hidden = [i for i in corners if i not in seen]
        skipped = tuple(PartPoints(1, i, "leg", np.array([[*corners[i], 0.05]] * 3)) for i in hidden)
        out, placed = complete_missing_legs("bed", prims, labels, skipped, CFG.completion, base=1)
        assert set(placed) == set(hidden), seen
        for i in hidden:
            assert np.allclose(out[i].center, [*corners[i], 0.075], atol=1e-9), (seen, i)


def test_a_bed_frame_hidden_at_its_head_end_is_extended_to_its_headboard():
    from recon.completion import complete_reaching_parts

    frame = Primitive("box", [1.48, 1.693, 0.15], at(2.428, 1.325, 0.294))   # random/4 bed15: 26 cm short
    head = Primitive("box", [1.521, 0.05, 1.048], at(2.428, 2.446, 0.527))
    labels = {80: "frame", 85: "headboard"}
    out, changes = complete_reaching_parts({80: frame, 85: head}, labels, CFG.completion, CFG.contacts)
    assert changes[80] == pytest.approx(2.421 - (1.325 + 1.693 / 2))
    assert out[80].corners()[:, 1].max() == pytest.approx(2.421)
    assert out[80].corners()[:, 1].min() == pytest.approx(1.325 - 1.693 / 2)
    far = Primitive("box", [1.521, 0.05, 1.048], at(2.428, 2.446 + 0.5, 0.527))     # beyond the reach
    assert complete_reaching_parts({80: frame, 85: far}, labels, CFG.completion, CFG.contacts)[1] == {}
