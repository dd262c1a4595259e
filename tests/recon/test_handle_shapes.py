"""Handles written as the shapes a gripper meets (recon/handle_shapes.py): a bar on two posts, a knob's
cap on its stem, measured from synthetic handle clouds in front of a face x = 0 (outward normal +x).

The truth follows scenes/generators/handles.py: a 14 mm square bar, 213 mm long along y, 35 mm off the
face (outer face at 49 mm) on two 6 mm-radius posts 15 mm in from its ends; a knob's 18 mm-radius,
20 mm-deep cap on a 7 mm-radius stem (outer face at 45 mm).
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from recon.config import ReconConfig
from recon.handle_shapes import (HandleStyle, facing_plane, handle_shapes, mounted_handle_shapes,
                                 posed_handle_shapes)
from recon.primitive import Primitive, PrimitiveKind, SurfacePlane

CFG = ReconConfig()
BAR_OUT, BAR_T, BAR_L, POST_R, STANDOFF = 0.049, 0.014, 0.213, 0.006, 0.035
FACE = SurfacePlane(np.array([1.0, 0.0, 0.0]), 0.0, np.array([[0, -0.3, -0.2], [0, 0.3, -0.2], [0, 0.3, 0.2],
                                                             [0, -0.3, 0.2]], float))


def _box_envelope(x0: float, x1: float, half_y: float, half_z: float) -> Primitive:
    T = np.eye(4)
    T[:3, 3] = [(x0 + x1) / 2, 0.0, 0.0]
    return Primitive(PrimitiveKind.BOX, [x1 - x0, 2 * half_y, 2 * half_z], T)


def _bar_cloud(rng: np.random.Generator, noise: float = 0.0, bleed: int = 0) -> np.ndarray:
    """Points a camera in front of (+x) and above the handle sees: the bar's front, top and bottom,
    the posts' visible sides; plus ``bleed`` front-face points around the bar labelled handle."""
    x_in = BAR_OUT - BAR_T
    front = np.c_[np.full(150, BAR_OUT), rng.uniform(-BAR_L / 2, BAR_L / 2, 150),
                  rng.uniform(-BAR_T / 2, BAR_T / 2, 150)]
    tb = np.c_[rng.uniform(x_in, BAR_OUT, 60), rng.uniform(-BAR_L / 2, BAR_L / 2, 60),
               rng.choice([-BAR_T / 2, BAR_T / 2], 60)]
    posts = []
    for yc in (-(BAR_L / 2 - 0.015), BAR_L / 2 - 0.015):
        a = rng.uniform(-np.pi / 2, np.pi / 2, 20)          # the half facing the camera
        posts.append(np.c_[rng.uniform(0.0, x_in, 20), yc + POST_R * np.sin(a), POST_R * np.cos(a)])
    pts = np.vstack([front, tb, *posts])
    if bleed:
        out = np.c_[np.zeros(bleed), rng.uniform(-BAR_L / 2 - 0.015, BAR_L / 2 + 0.015, bleed),
                    rng.choice([-1, 1], bleed) * rng.uniform(BAR_T / 2, BAR_T / 2 + 0.015, bleed)]
        pts = np.vstack([pts, out])
    if noise:
        pts[:, 0] += rng.normal(0.0, noise, len(pts))          # depth noise along the camera's rays
    return pts


def _outer_face(prim: Primitive) -> float:
    return float(np.max(prim.corners()[:, 0]))


def _check_bar(hs, tol_out: float):
    assert hs.style is HandleStyle.BAR, hs.reason
    bar, *posts = hs.shapes
    assert bar.kind is PrimitiveKind.BOX and len(posts) == 2
    assert abs(_outer_face(bar) - BAR_OUT) < tol_out, (_outer_face(bar), hs.reason)
    c = bar.corners()
    assert np.ptp(c[:, 0]) < 0.02 and np.ptp(c[:, 2]) < 0.02          # thickness out and across < 2 cm
    assert abs(np.ptp(c[:, 1]) - BAR_L) < 0.012                        # length along the bar
    # the planner grasps the outermost shape: the bar, not a post
    assert all(bar.center[0] > p.center[0] + 0.01 for p in posts)
    for p in posts:      # posts stand on the face and reach the bar's inner face
        assert p.kind is PrimitiveKind.CYLINDER and abs(abs(p.T_world_part[0, 2]) - 1) < 1e-9
        assert abs(np.min(p.corners()[:, 0])) < 1e-9
        assert abs(np.max(p.corners()[:, 0]) - np.min(c[:, 0])) < 1e-9
        assert abs(abs(p.center[1] - bar.center[1]) - (np.ptp(c[:, 1]) / 2 - CFG.handles.handle_post_inset)) < 1e-9
    env = hs.envelope.corners()
    assert np.min(env[:, 0]) == pytest.approx(0.0, abs=1e-9) and np.max(env[:, 0]) == pytest.approx(_outer_face(bar))


def test_clean_bar_on_posts():
    rng = np.random.default_rng(0)
    hs = handle_shapes(_bar_cloud(rng), _box_envelope(0.0, BAR_OUT, 0.11, 0.01), FACE, CFG.handles, CFG.fitting)
    _check_bar(hs, tol_out=0.004)


def test_noisy_bar_with_label_bleed_on_the_front():
    rng = np.random.default_rng(1)
    pts = _bar_cloud(rng, noise=0.003, bleed=120)
    # the envelope a noisy fit gives: from behind the face (bleed noise) far out (noise)
    hs = handle_shapes(pts, _box_envelope(-0.01, 0.06, 0.13, 0.03), FACE, CFG.handles, CFG.fitting)
    _check_bar(hs, tol_out=0.006)


def test_bar_found_when_its_envelope_is_a_cylinder_along_the_bar():
    rng = np.random.default_rng(2)
    T = np.eye(4)
    T[:3, :3] = np.array([[0, 0, 1], [1, 0, 0], [0, 1, 0]], float)   # local z along world y
    T[:3, 3] = [0.03, 0.0, 0.0]
    env = Primitive(PrimitiveKind.CYLINDER, [0.04, 0.04, 0.22], T)
    _check_bar(handle_shapes(_bar_cloud(rng, noise=0.002), env, FACE, CFG.handles, CFG.fitting), tol_out=0.005)


def _knob_cloud(rng: np.random.Generator, r_cap: float, r_stem: float, out: float) -> np.ndarray:
    """A knob's cap (front disc and the half of its side facing the camera) on its stem, about y = z = 0."""
    a = rng.uniform(0, 2 * np.pi, 200)
    rad = r_cap * np.sqrt(rng.uniform(0, 1, 200))
    cap_front = np.c_[np.full(200, out), rad * np.cos(a), rad * np.sin(a)]
    b = rng.uniform(-np.pi / 2, np.pi / 2, 80)
    cap_side = np.c_[rng.uniform(out - 0.02, out, 80), r_cap * np.sin(b), r_cap * np.cos(b)]
    stem = np.c_[rng.uniform(0, out - 0.02, 15), r_stem * np.sin(b[:15]), r_stem * np.cos(b[:15])]
    pts = np.vstack([cap_front, cap_side, stem])
    pts[:, 0] += rng.normal(0, 0.002, len(pts))
    return pts


def test_knob_is_a_cap_on_a_stem():
    r_cap, r_stem, out = 0.018, 0.007, 0.045
    pts = _knob_cloud(np.random.default_rng(3), r_cap, r_stem, out)
    hs = handle_shapes(pts, _box_envelope(0.0, out, r_cap, r_cap), FACE, CFG.handles, CFG.fitting)
    assert hs.style is HandleStyle.KNOB, hs.reason
    cap, stem_shape = hs.shapes
    assert cap.kind is PrimitiveKind.CYLINDER and stem_shape.kind is PrimitiveKind.CYLINDER
    assert abs(_outer_face(cap) - out) < 0.006
    assert 0.025 < cap.size[0] <= CFG.handles.handle_knob_max_diameter and cap.size[2] <= CFG.handles.handle_max_thickness
    assert abs(np.min(stem_shape.corners()[:, 0])) < 1e-9
    assert np.linalg.norm(cap.center[1:] - stem_shape.center[1:]) < 1e-9 and cap.center[0] > stem_shape.center[0]


def test_degenerate_handle_on_the_front_plane_keeps_its_envelope():
    env = _box_envelope(0.0, 0.01, 0.02, 0.02)
    pts = np.array([[0.0, 0.0, 0.0], [0.0005, 0.01, 0.0], [-0.0005, 0.0, 0.01]])
    hs = handle_shapes(pts, env, FACE, CFG.handles, CFG.fitting)
    assert hs.style is HandleStyle.ENVELOPE and hs.shapes == () and hs.envelope is env
    assert "0 of 3 points" in hs.reason


def test_a_flat_plate_with_no_standoff_keeps_its_envelope():
    rng = np.random.default_rng(4)
    pts = np.c_[rng.uniform(0.009, 0.012, 200), rng.uniform(-0.1, 0.1, 200), rng.uniform(-0.01, 0.01, 200)]
    hs = handle_shapes(pts, _box_envelope(0.0, 0.012, 0.1, 0.01), FACE, CFG.handles, CFG.fitting)
    assert hs.style is HandleStyle.ENVELOPE and "room for its posts" in hs.reason


def test_bar_measured_from_the_face_its_mount_points_show():
    """A refined mount 1 cm behind its points: the bar stays where its points are, the posts reach
    back to the mount."""
    rng = np.random.default_rng(5)
    pts = _bar_cloud(rng, noise=0.002, bleed=100)
    face = SurfacePlane(np.array([1.0, 0.0, 0.0]), 0.01, FACE.polygon - [0.01, 0, 0])   # plane x = -0.01
    mount = np.c_[rng.normal(0.0, 0.002, 800), rng.uniform(-0.3, 0.3, 800), rng.uniform(-0.2, 0.2, 800)]
    hs = handle_shapes(pts, _box_envelope(-0.01, BAR_OUT, 0.11, 0.01), face, CFG.handles, CFG.fitting, mount)
    assert hs.style is HandleStyle.BAR
    assert abs(_outer_face(hs.shapes[0]) - BAR_OUT) < 0.006
    for p in hs.shapes[1:]:
        assert np.min(p.corners()[:, 0]) == pytest.approx(-0.01, abs=1e-9)
    assert re.search(r"seen at \+(9\.\d|10\.\d) mm", hs.reason), hs.reason


def test_mounted_handles_follow_their_part_and_switch_off():
    rng = np.random.default_rng(6)
    front = Primitive(PrimitiveKind.BOX, [0.02, 0.6, 0.4], np.diag([1.0, 1, 1, 1]) @ _shift([-0.01, 0, 0]))
    prims = {1: front, 2: _box_envelope(0.0, BAR_OUT, 0.11, 0.01)}
    labels = {1: "drawer", 2: "handle"}
    points = {2: _bar_cloud(rng), 1: np.c_[np.zeros(300), rng.uniform(-0.3, 0.3, 300), rng.uniform(-0.2, 0.2, 300)]}
    out, shapes = mounted_handle_shapes(prims, labels, points, CFG.handles, CFG.contacts, CFG.fitting,
                                        CFG.completion, "cabinet1")
    assert set(shapes) == {2} and out[1] is front and out[2] is shapes[2].envelope
    M = _shift([0.1, -0.2, 0.05])
    moved = posed_handle_shapes(shapes, {2: out[2].transformed(M)})[2]
    for a, b in zip(moved, shapes[2].shapes):
        assert a.isclose(b.transformed(M), atol=1e-12)
    from dataclasses import replace
    off, none = mounted_handle_shapes(prims, labels, points, replace(CFG.handles, handle_shapes=False),
                                      CFG.contacts, CFG.fitting, CFG.completion)
    assert none == {} and off[2] is prims[2]


def _shift(t) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = t
    return T


def test_a_mount_fitted_in_front_of_its_bar_leaves_the_envelope():
    """A noise-thickened front fitted 4 cm proud of its points would bury the bar's posts."""
    rng = np.random.default_rng(7)
    face = SurfacePlane(np.array([1.0, 0.0, 0.0]), -0.04, FACE.polygon + [0.04, 0, 0])   # plane x = +0.04
    mount = np.c_[rng.normal(0.0, 0.002, 800), rng.uniform(-0.3, 0.3, 800), rng.uniform(-0.2, 0.2, 800)]
    env = _box_envelope(0.04, 0.06, 0.11, 0.01)
    hs = handle_shapes(_bar_cloud(rng, noise=0.002), env, face, CFG.handles, CFG.fitting, mount)
    assert hs.style is HandleStyle.ENVELOPE and hs.envelope is env and "room for its posts" in hs.reason


def test_the_mount_face_is_the_one_the_handle_stands_in_front_of():
    """A door 2 cm thick with a bar near its edge: the front face, not the side face next to the bar."""
    door = Primitive(PrimitiveKind.BOX, [0.02, 0.6, 0.8], _shift([-0.01, 0.0, 0.0]))
    pts = _bar_cloud(np.random.default_rng(8)) + [0.0, 0.27, 0.0]       # bar 3 cm in from the door's edge
    face = facing_plane(door, pts, CFG.handles, CFG.contacts)
    assert face is not None and np.allclose(face.normal, [1, 0, 0]) and abs(face.d) < 1e-12
    back = facing_plane(door, pts * [-1, 1, 1] - [0.02, 0, 0], CFG.handles, CFG.contacts)      # the same bar behind the door
    assert back is not None and np.allclose(back.normal, [-1, 0, 0])
    assert facing_plane(door, pts * [0, 1, 1] - [0.01, 0, 0], CFG.handles, CFG.contacts) is None   # points inside the door: no face


def test_reconstructed_cabinet_handles_are_bars_on_posts_in_scene_urdf(kitchen_rec, kitchen_scan):
    """The synthetic cabinet's handles (solid 30 mm boxes in front of the fronts at x = 0.5 m): each is
    written as a bar whose outer face is where the handle's front is, on two posts standing on the
    front, and scene.urdf gives the handle link one collision per shape."""
    from recon.scene_urdf import urdf_string

    cab = next(o for o in kitchen_rec.objects if o.category == "cabinet")
    text = urdf_string(kitchen_rec)
    for pid in (103, 105):
        part = cab.part(pid)
        bar, *posts = part.solids
        assert len(posts) == 2 and bar.kind is PrimitiveKind.BOX
        assert abs(float(np.max(bar.corners()[:, 0])) - 0.53) < 0.005
        assert max(np.sort(np.ptp(bar.corners(), axis=0))[:2]) <= CFG.handles.handle_max_thickness + 1e-9
        for p in posts:
            assert abs(float(np.min(p.corners()[:, 0])) - 0.5) < 0.006
        assert text.count(f'<collision name="{part.link}_collision') == 3


def test_a_horizontal_bar_seen_from_above_is_centred_between_its_edges():
    """A camera above a horizontal bar sees its top face as well as its front (as many points again along
    the upper edge): the bar's middle across it stays between its edges, not up where the median went."""
    rng = np.random.default_rng(3)
    pts = _bar_cloud(rng, noise=0.003)
    top = np.c_[rng.uniform(BAR_OUT - BAR_T, BAR_OUT, 150), rng.uniform(-BAR_L / 2, BAR_L / 2, 150),
                BAR_T / 2 + rng.normal(0.0, 0.001, 150)]
    cloud = np.vstack([pts, top])
    assert np.median(cloud[cloud[:, 0] > 0.01, 2]) > 0.003          # the median alone would be 3+ mm up
    hs = handle_shapes(cloud, _box_envelope(0.0, 0.06, 0.12, 0.03), FACE, CFG.handles, CFG.fitting)
    assert hs.style is HandleStyle.BAR, hs.reason
    assert abs(hs.shapes[0].center[2]) < 0.002, hs.shapes[0].center


def test_a_vertical_bar_whose_points_trail_off_one_edge_is_centred_on_the_bar():
    """Depth noise along a passing camera's oblique rays trails a vertical bar's points up to 3 cm off one
    edge (a quarter of them): the bar's middle across it (horizontal) is where most of its points are,
    not halfway between percentiles the trail has moved."""
    rng = np.random.default_rng(2)
    pts = _bar_cloud(rng, noise=0.003)
    n = len(pts) // 4
    trail = np.c_[rng.uniform(BAR_OUT - BAR_T, BAR_OUT, n), rng.uniform(-BAR_L / 2, BAR_L / 2, n),
                  BAR_T / 2 + rng.exponential(0.01, n).clip(max=0.03)]
    upright = np.vstack([pts, trail])[:, [0, 2, 1]]                  # the bar along z, across y
    across = upright[upright[:, 0] > 0.01, 1]
    assert np.mean(np.percentile(across, [10, 90])) > 0.004         # the percentile pair would be 4+ mm off
    hs = handle_shapes(upright, _box_envelope(0.0, 0.06, 0.03, 0.12), FACE, CFG.handles, CFG.fitting)
    assert hs.style is HandleStyle.BAR, hs.reason
    bar = hs.shapes[0]
    assert abs(bar.T_world_part[2, 0]) > 0.99                        # along z
    assert abs(bar.center[1]) < 0.003, bar.center


def test_a_knob_whose_points_trail_off_one_side_is_centred_on_its_cap():
    """A knob's points trailing up to 3 cm off one side (horizontally, as a passing camera leaves them; a sixth
    of them): its cap stays near where most of its points are, not halfway between its extremes."""
    rng = np.random.default_rng(4)
    r_cap, out = 0.017, 0.045
    pts = _knob_cloud(rng, r_cap, 0.007, out)
    n = len(pts) // 6
    trail = np.c_[rng.uniform(out - 0.02, out, n), r_cap + rng.exponential(0.01, n).clip(max=0.03),
                  rng.uniform(-r_cap, r_cap, n)]
    cloud = np.vstack([pts, trail])
    assert np.mean(np.percentile(cloud[cloud[:, 0] > 0.01, 1], [2, 98])) > 0.01     # the extremes' middle: 1 cm off
    hs = handle_shapes(cloud, _box_envelope(0.0, out, 0.03, r_cap), FACE, CFG.handles, CFG.fitting)
    assert hs.style is HandleStyle.KNOB, hs.reason
    assert np.linalg.norm(hs.shapes[0].center[1:]) < 0.005, hs.shapes[0].center


def test_a_knob_with_label_fragments_behind_its_door_is_not_a_box_through_the_door():
    """ScanNet-style nightstand (third-party corpus, seed 1): 10 points of a knob 2-4 cm in front of its door
    and 6 points of the body's back 45 cm behind it, all labelled handle; too few for a knob's cap, so the
    handle keeps its envelope -- which Eq. 3 fitted round all 16 points: a 48 cm deep box through the door.
    A handle stands in front of its mount: the envelope is the box of its points in front of the face."""
    rng = np.random.default_rng(9)
    knob = np.c_[rng.uniform(0.02, 0.04, 10), rng.uniform(-0.02, 0.02, 10), rng.uniform(-0.02, 0.02, 10)]
    back = np.c_[rng.uniform(-0.46, -0.44, 6), rng.uniform(0.02, 0.05, 6), rng.uniform(0.14, 0.2, 6)]
    env = _box_envelope(-0.46, 0.04, 0.05, 0.11)
    hs = handle_shapes(np.r_[knob, back], env, FACE, CFG.handles, CFG.fitting)
    assert hs.style is HandleStyle.ENVELOPE and hs.shapes == ()
    c = hs.envelope.corners()
    assert c[:, 0].min() == pytest.approx(0.0, abs=1e-9) and c[:, 0].max() == pytest.approx(knob[:, 0].max())
    assert np.all(c[:, 1:].min(axis=0) >= knob[:, 1:].min(axis=0) - 1e-9)
    assert np.all(c[:, 1:].max(axis=0) <= knob[:, 1:].max(axis=0) + 1e-9)
    # and through the caller: the part's primitive is the repaired box
    door = Primitive(PrimitiveKind.BOX, [0.02, 0.6, 0.4], _shift([-0.01, 0, 0]))
    out, shapes = mounted_handle_shapes({1: door, 2: env}, {1: "door", 2: "handle"}, {2: np.r_[knob, back]},
                                        CFG.handles, CFG.contacts, CFG.fitting, CFG.completion, "cabinet1", {2: 1})
    assert shapes == {} and out[2].isclose(hs.envelope, atol=1e-12) and out[1] is door


def test_a_handle_whose_points_all_stand_in_front_keeps_its_envelope():
    """Points within the face window behind the face (depth noise, the front's bleed) are the handle's:
    nothing is cut, the envelope is the input."""
    rng = np.random.default_rng(10)
    pts = np.c_[rng.uniform(-0.03, 0.04, 12), rng.uniform(-0.02, 0.02, 12), rng.uniform(-0.02, 0.02, 12)]
    env = _box_envelope(-0.03, 0.04, 0.02, 0.02)
    hs = handle_shapes(pts, env, FACE, CFG.handles, CFG.fitting)
    assert hs.style is HandleStyle.ENVELOPE and hs.envelope is env
