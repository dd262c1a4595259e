"""Handles of every kind on third-party fronts (planners.handle): an own link, unnamed mesh geometry of the
moving link, a knob (stem and cap), none. Pure: no simulator."""

from __future__ import annotations

import numpy as np
import pytest

import thirdparty
from planners import HandleNotFoundError, OpenTask, PlannerConfig
from planners.handle import find_handle
from planners.scene_urdf import read_scene_urdf

CFG = PlannerConfig()


@pytest.mark.parametrize("obj, k, source, shape", [
    ("base_cabinet_door_drawer", 0, "handle link", "cylinder"),
    ("kitchen_unit_double_door", 0, "protruding geometry", "mesh"),
    ("kitchen_unit_double_door", 1, "protruding geometry", "mesh"),     # opens toward negative values
    ("drawer_stack_knobs", 1, "protruding geometry", "sphere"),         # the knob's cap, not its stem
    ("nightstand", 0, "fixed child", "sphere"),
    ("safe_box", 0, "protruding geometry", "sphere"),                   # a 5 cm thick door
])
def test_the_handle_is_found_whatever_its_kind(obj, k, source, shape, tmp_path):
    o = thirdparty.build_object(thirdparty.spec_named(obj), tmp_path)
    f = o.fronts[k]
    s = read_scene_urdf(o.urdf)
    j = s.joints[f.joint]
    direction = 1.0 if j.upper >= -j.lower else -1.0
    h = find_handle(s, OpenTask("drawer" if f.kind == "drawer" else "door", f.joint), {}, CFG, direction)
    assert h.source == source
    geoms = {(ln, i): s.links[ln].collisions[i] for ln, i in h.handle_geoms}
    assert shape in {g.kind.value for g in geoms.values()}
    # the preferred grasp is at the centre of the outermost handle shape (a knob's cap, not its stem), and
    # approaches into the front (which faces the world's -y turned by the placement yaw)
    T = s.T_world_link(h.moving_link, {}) @ h.T_link_grasps[0]
    yaw = np.deg2rad(o.spec.place[2])
    out = np.array([np.sin(yaw), -np.cos(yaw), 0.0])
    assert T[:3, 2] @ out < -0.8
    if shape == "sphere":
        (ln, i), = [key for key, g in geoms.items() if g.kind.value == "sphere"]
        centre = (s.T_world_link(ln, {}) @ s.links[ln].collisions[i].T_link_shape)[:3, 3]
        assert np.linalg.norm(T[:3, 3] - centre) < 1e-6


def test_a_front_without_a_handle_is_pinched_on_the_edges_of_its_panel(tmp_path):
    """``sink_base_no_handles``: no handle of any kind, so the candidates pinch the 20 mm panel across its thickness,
    the free edge (x = 0.4485 m in the object frame) first, 15 mm in from it, approached in the panel's plane."""
    o = thirdparty.build_object(thirdparty.spec_named("sink_base_no_handles"), tmp_path)
    s = read_scene_urdf(o.urdf)
    j = o.fronts[0].joint
    h = find_handle(s, OpenTask("door", j), {}, CFG)
    assert h.source == "panel edge" and h.bar_width == pytest.approx(0.02)
    assert h.handle_geoms == {(h.moving_link, 0)}
    T = s.T_world_link(h.moving_link, {}) @ h.T_link_grasps[0]
    place = np.array(o.spec.place[:2])             # yaw 0: object x, y = world x, y minus the placement
    assert T[0, 3] - place[0] == pytest.approx(0.45 - 0.0015 - 0.015, abs=1e-6)     # 15 mm inside the free edge
    assert np.allclose(T[:3, 2], [-1, 0, 0], atol=1e-9)      # approaching from beyond the edge, toward the hinge
    assert abs(T[:3, 1] @ [0, 1, 0]) == pytest.approx(1.0)   # the fingers close across the panel
    assert np.allclose(h.facing, [0, -1, 0], atol=1e-9)      # the robot stands in front of the cabinet


def test_a_panel_thicker_than_the_gripper_opens_is_refused_naming_its_thickness(tmp_path):
    o = thirdparty.build_object(thirdparty.spec_named("sink_base_no_handles"), tmp_path)
    s = read_scene_urdf(o.urdf)
    with pytest.raises(HandleNotFoundError, match=r"no handle, and the front panel is 20 mm thick: more than the "
                       r"gripper opens \(25 mm\)"):
        find_handle(s, OpenTask("door", o.fronts[0].joint), {}, CFG, grip_width=0.025)


@pytest.mark.parametrize("k, bar", [(0, [1, 0, 0]), (1, [0, 0, 1])])
def test_a_handle_exported_in_one_mesh_with_its_panel_is_found_on_the_surface(k, bar, tmp_path):
    """``one_mesh_fronts``: each front is one OBJ (panel + U bar): the grasp is at the bar's centre, 3.5 cm
    out of the front, approaching into it, x along the bar (horizontal on the drawer, vertical on the door)."""
    o = thirdparty.build_object(thirdparty.spec_named("one_mesh_fronts"), tmp_path)
    f = o.fronts[k]
    s = read_scene_urdf(o.urdf)
    j = s.joints[f.joint]
    direction = 1.0 if j.upper >= -j.lower else -1.0
    h = find_handle(s, OpenTask("drawer" if f.kind == "drawer" else "door", f.joint), {}, CFG, direction)
    assert h.source == "protruding surface"
    body = next(link for link, label in o.labels.items() if label == "body")
    T_body = s.T_world_link(body, {})               # the carcass frame: the object's axes, at its top-back corner
    out = T_body[:3, :3] @ [0.0, -1.0, 0.0]
    frames = [s.T_world_link(h.moving_link, {}) @ G for G in h.T_link_grasps]
    T = min(frames[:4], key=lambda F: float(F[:3, 2] @ out))       # the level grasp at the bar (not backed off)
    assert T[:3, 2] @ out < -0.99
    assert abs(T[:3, 0] @ (T_body[:3, :3] @ bar)) > 0.95
    p_obj = np.linalg.solve(T_body, np.append(T[:3, 3], 1.0))[:3]
    assert p_obj[1] + 0.5 == pytest.approx(-0.02 - 0.035, abs=0.004)  # 3.5 cm out of the 2 cm panel (depth 0.5)


def test_a_knob_held_at_its_cap_s_outer_face_is_held_level(tmp_path):
    """A drawer knob: the centred grasps come tilted 20 deg down, then level; the backed-off ones (at the cap's
    outer face) only level: tilted there, the lower fingertip lands on the cap's front rim (kitchen 3's
    ``cabinet1_drawer2`` with plan seeds 3 and 4)."""
    o = thirdparty.build_object(thirdparty.spec_named("drawer_stack_knobs"), tmp_path)
    s = read_scene_urdf(o.urdf)
    h = find_handle(s, OpenTask("drawer", o.fronts[1].joint), {}, CFG)
    frames = [s.T_world_link(h.moving_link, {}) @ T for T in h.T_link_grasps]
    tilt = [np.degrees(np.arcsin(-T[2, 2])) for T in frames]
    assert np.allclose(tilt, [20, 20, 0, 0, 0, 0], atol=1e-6)
    out = [T[:3, 3] @ -T[:3, 2] for T in frames]           # along the approach, backwards
    assert out[4] > out[2] + 0.005                         # the last two are backed off
