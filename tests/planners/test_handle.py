"""Handle discovery (own link, named geometry, explicit point) and the grasp frame's geometry."""

from __future__ import annotations

import numpy as np
import pytest

from planners import HandleNotFoundError, OpenTask, PlannerConfig
from planners.handle import find_handle
from planners.scene_urdf import read_scene_urdf

DRAWER = "cabinet1_drawer12_joint"
DOOR = "cabinet1_door14_joint"
CFG = PlannerConfig()


def _world_frames(scene, h):
    T = scene.T_world_link(h.moving_link, {})
    return [T @ G for G in h.T_link_grasps]


def test_drawer_handle_link_found_and_grasp_frame_faces_the_front(fixture_urdf):
    s = read_scene_urdf(fixture_urdf)
    h = find_handle(s, OpenTask("drawer", DRAWER), {}, CFG)
    assert h.source == "handle link" and h.grasp_link == "cabinet1_handle13"
    assert ("cabinet1_handle13", 0) in h.handle_geoms
    frames = _world_frames(s, h)
    assert len(frames) == 8   # (tilted, level) x (centre, backed off) x (two finger orders)
    for T in frames[:2]:
        # Preferred candidates: bar centre: cabinet at x = 1.5 facing -x, handle 0.285 in front of the body origin, 0.615 high.
        assert np.allclose(T[:3, 3], [1.5 - 0.285, 0.0, 0.615], atol=1e-6)
        # Approach into the front (+x world), tilted 20 deg downward about the horizontal bar.
        assert np.degrees(np.arccos(T[:3, 2] @ [1, 0, 0])) == pytest.approx(20.0, abs=1e-6)
        assert T[2, 2] < 0
        assert abs(T[:3, 0] @ [0, 1, 0]) == pytest.approx(1.0)   # x along the bar (world y)
        assert np.allclose(T[:3, :3].T @ T[:3, :3], np.eye(3), atol=1e-12)
    assert h.bar_width == pytest.approx(0.02)
    level, backed = frames[2], frames[4]
    assert np.allclose(level[:3, 2], [1, 0, 0], atol=1e-6)   # the fixture yaw is written to 1e-6
    # Backed off by half the 20 mm bar's depth (grasp_backoff_share), not the full 15 mm grasp_backoff.
    assert np.allclose(backed[:3, 3], frames[0][:3, 3] - 0.010 * frames[0][:3, 2], atol=1e-12)


def test_door_handle_is_vertical_and_approached_against_the_swing(fixture_urdf):
    s = read_scene_urdf(fixture_urdf)
    h = find_handle(s, OpenTask("door", DOOR), {}, CFG)
    T = _world_frames(s, h)[0]
    assert abs(T[:3, 0] @ [0, 0, 1]) == pytest.approx(1.0)   # vertical bar, no tilt
    # Approach along the handle's opening velocity: the door opens toward world -x, and the bar stands
    # 3.5 cm proud of a 0.68 m lever, so the direction leans atan(0.035 / 0.68) = 2.9 deg toward the hinge.
    assert np.degrees(np.arccos(T[:3, 2] @ [1, 0, 0])) == pytest.approx(np.degrees(np.arctan2(0.035, 0.68)), abs=1e-3)


def test_handle_as_named_geometry_of_the_drawer_link(variants):
    s = read_scene_urdf(variants.named_geometry())
    h = find_handle(s, OpenTask("drawer", DRAWER), {}, CFG)
    assert h.source == "named geometry" and h.grasp_link == "cabinet1_drawer12"
    assert np.allclose(_world_frames(s, h)[0][:3, 3], [1.215, 0.0, 0.615], atol=1e-6)


def test_without_a_handle_the_edges_of_the_front_panel_are_the_grasps(variants):
    s = read_scene_urdf(variants.no_handle())
    h = find_handle(s, OpenTask("drawer", DRAWER), {}, CFG)
    assert h.source == "panel edge" and h.grasp_link == h.moving_link == "cabinet1_drawer12"
    assert len(h.T_link_grasps) == 8                # four edges, each pinched with either finger on the outside
    for T in _world_frames(s, h):
        assert abs(T[:3, 1] @ [1, 0, 0]) == pytest.approx(1.0)     # closing across the panel (normal +x)
        assert abs(T[:3, 2] @ [1, 0, 0]) < 1e-5                    # approaching in the panel's plane


def test_no_handle_and_a_panel_too_thick_to_pinch_raises_naming_the_file_and_joint(variants):
    s = read_scene_urdf(variants.no_handle())
    with pytest.raises(HandleNotFoundError, match=r"no_handle.urdf: joint 'cabinet1_drawer12_joint': no handle, and "
                       r"the front panel is \d+ mm thick"):
        find_handle(s, OpenTask("drawer", DRAWER), {}, CFG, grip_width=0.01)


def test_explicit_grasp_point_is_used_when_there_is_no_handle(variants):
    s = read_scene_urdf(variants.no_handle())
    p = (1.5 - 0.25, 0.1, 0.7)   # on the drawer front
    h = find_handle(s, OpenTask("drawer", DRAWER, grasp_point=p), {}, CFG)
    assert h.source == "grasp_point"
    assert np.allclose(_world_frames(s, h)[0][:3, 3], p, atol=1e-6)


def test_grasp_point_on_the_hinge_axis_is_rejected(fixture_urdf):
    s = read_scene_urdf(fixture_urdf)
    on_hinge = (1.5 - 0.25, 0.38, 0.3)   # the door's hinge line (world)
    with pytest.raises(HandleNotFoundError, match="lies on the hinge axis"):
        find_handle(s, OpenTask("door", DOOR, grasp_point=on_hinge), {}, CFG)


def test_grasp_link_not_on_the_moving_part_is_rejected(fixture_urdf):
    s = read_scene_urdf(fixture_urdf)
    with pytest.raises(HandleNotFoundError, match="'cabinet1_handle15' is not rigidly attached"):
        find_handle(s, OpenTask("drawer", DRAWER, grasp_link="cabinet1_handle15"), {}, CFG)
