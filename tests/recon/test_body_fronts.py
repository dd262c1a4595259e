"""A body does not reach past the fronts closing it (recon.body_fronts): on ScanNet-style scans the fronts'
points that a segmentation gave the body, spread by 2-4 cm of depth noise, made room10's cabinet4 body stand
5-7 cm proud of its drawers; no opening was cut for them, the clearance stage cut the body to pieces around
their drawer boxes (object IoU 0.50)."""

from __future__ import annotations

import numpy as np

from recon.body_fronts import body_within_fronts
from recon.config import ReconConfig
from recon.pipeline import _Run, fit_primitives
from recon.scan import ObjectPoints, PartPoints
from recon_boxes import box, carcass_points

CFG = ReconConfig()
RATIO = CFG.fitting.panel_ratio


def _x_span(prim) -> tuple[float, float]:
    x = prim.corners()[:, 0]
    return float(x.min()), float(x.max())


def test_a_body_proud_of_its_fronts_is_cut_back_to_the_outermost_front():
    body = box([0.0, -0.25, 0.0], [0.57, 0.25, 0.8])
    fronts = [box([0.5, -0.24, 0.05], [0.518, 0.24, 0.39]), box([0.505, -0.24, 0.41], [0.523, 0.24, 0.75])]
    cut = body_within_fronts(body, fronts, RATIO)
    assert np.allclose(_x_span(cut), (0.0, 0.523))
    assert np.allclose(cut.size[1:], body.size[1:])


def test_a_body_behind_its_fronts_or_without_boards_is_unchanged():
    body = box([0.0, -0.25, 0.0], [0.5, 0.25, 0.8])
    overlay = box([0.5, -0.24, 0.05], [0.518, 0.24, 0.39])
    assert body_within_fronts(body, [overlay], RATIO) is body
    # a drawer fitted as a solid box (no board) says nothing about the face
    assert body_within_fronts(box([0.0, -0.25, 0.0], [0.6, 0.25, 0.8]), [box([0.3, -0.24, 0.05], [0.55, 0.24, 0.39])],
                              RATIO).size[0] == 0.6


def test_a_body_fitted_apart_behind_its_fronts_is_moved_out_to_their_backs():
    # seen only at its stiles' edges and through the gaps, the body's face came out 5 cm behind its fronts
    body = box([0.0, -0.25, 0.0], [0.45, 0.25, 0.8])
    fronts = [box([0.5, -0.24, 0.05], [0.518, 0.24, 0.39]), box([0.498, -0.24, 0.41], [0.516, 0.24, 0.75])]
    assert np.allclose(_x_span(body_within_fronts(body, fronts, RATIO)), (0.0, 0.5))
    # a door standing a few millimetres off its carcass (hinge play) is a closed front as it is
    assert body_within_fronts(box([0.0, -0.25, 0.0], [0.497, 0.25, 0.8]), fronts[:1], RATIO).size[0] == 0.497
    # a front farther out than MAX_FRONT_GAP is no closed front (a drawer pulled out): the face is kept
    pulled = [box([0.62, -0.24, 0.05], [0.638, 0.24, 0.39])]
    assert body_within_fronts(body, pulled, RATIO) is body


def test_a_door_opened_beside_the_body_or_lying_across_it_cuts_nothing():
    body = box([0.0, -0.25, 0.0], [0.57, 0.25, 0.8])
    # opened 90 deg about a hinge at the body's +y front corner: the board stands in front of the body, facing y
    opened = box([0.57, 0.25, 0.05], [1.05, 0.268, 0.75])
    assert body_within_fronts(body, [opened], RATIO) is body
    # a board through the body's middle (a misfit shelf-like front) is not at a face
    middle = box([0.3, -0.24, 0.05], [0.318, 0.24, 0.75])
    assert body_within_fronts(body, [middle], RATIO) is body


def test_the_pipeline_cuts_a_body_fitted_past_its_drawer_front():
    rng = np.random.default_rng(5)
    # the carcass: its sides and top from x = 0 to its front at x = 0.5; an overlay drawer front at 0.5-0.518
    carcass, carcass_n = carcass_points(rng)
    k = 800
    front = np.c_[0.518 + rng.normal(0.0, 0.01, k), rng.uniform(-0.24, 0.24, k), rng.uniform(0.05, 0.75, k)]
    front_n = np.tile([1.0, 0.0, 0.0], (k, 1))
    # the front's points a segmentation labelled as the body (its rim), spread by the depth noise
    b = 200
    bleed = np.c_[0.518 + rng.normal(0.0, 0.03, b), rng.uniform(-0.25, 0.25, b), rng.uniform(0.02, 0.78, b)]
    bleed_n = np.tile([1.0, 0.0, 0.0], (b, 1))
    body = PartPoints(1, 10, "body", np.concatenate([carcass, bleed]), np.concatenate([carcass_n, bleed_n]))
    drawer = PartPoints(1, 11, "drawer", front, front_n)
    state = fit_primitives(ObjectPoints(1, "cabinet", (body, drawer)), _Run(CFG, 0, []))
    outer = _x_span(state.prims[11])[1]
    assert abs(outer - 0.518) < 0.01, state.prims[11]
    assert _x_span(state.prims[10])[1] < outer + 0.01, state.prims[10]
    assert _x_span(state.prims[10])[0] < 0.01
