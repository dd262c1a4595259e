"""The robot stands on the scene's floor (graph.json beside the scene URDF): its root at the floor frame's
origin, the floor half-space on the floor; the base joints' (x, y, yaw) are floor-frame coordinates."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

from planners import OpenTask, PlannerConfig
from planners.handle import find_handle
from planners.pin_world import PlanningWorld
from planners.plan import robot_kinematics
from planners.scene_urdf import read_floor, read_scene_urdf
from scenes.description import LEVEL_FLOOR

DRAWER = "cabinet1_drawer12_joint"


def _tilted_copy(fixture_urdf, tmp_path):
    """The fixture scene in a folder whose graph.json puts the floor 5 cm up, tilted 1 deg."""
    urdf = tmp_path / "scene.urdf"
    shutil.copy(fixture_urdf, urdf)
    n = np.array([np.sin(np.radians(1.0)), 0.0, np.cos(np.radians(1.0))])
    (tmp_path / "graph.json").write_text(json.dumps({"floor": {"height_m": 0.05, "tilt_deg": 1.0, "normal": n.tolist(),
                                                               "n_points": 5000}}))
    return urdf


def _floor_hits(kin, urdf, qs, clearance):
    scene = read_scene_urdf(urdf)
    handle = find_handle(scene, OpenTask("drawer", DRAWER), {}, PlannerConfig())
    world = PlanningWorld(kin, scene, DRAWER, set(handle.handle_geoms), {}, clearance)
    return np.array([any("floor" in a + b for a, b in world.colliding_pairs(q)) for q in qs])


def test_the_robot_stands_on_a_tilted_floor_and_keeps_its_clearance_from_it(robot, fixture_urdf, tmp_path):
    urdf = _tilted_copy(fixture_urdf, tmp_path)
    floor = read_floor(urdf)
    assert read_floor(fixture_urdf) == LEVEL_FLOOR and floor.tilt_deg == pytest.approx(1.0)
    level, tilted = robot_kinematics(robot), robot_kinematics(robot, floor)
    assert robot_kinematics(robot, floor) is tilted and robot_kinematics(robot, LEVEL_FLOOR) is level
    rng = np.random.default_rng(3)
    qs = np.tile(robot.home_q, (40, 1))
    qs[:, :2] = rng.uniform(-3.0, 3.0, size=(40, 2))    # 1 deg over 3 m: 5 cm off a level floor
    qs[:, 2] = rng.uniform(-np.pi, np.pi, 40)
    qs = qs[np.hypot(qs[:, 0] - 0.8, qs[:, 1]) > 1.5]   # away from the fixture's cabinet
    for q in qs:                                         # poses in the scene's frame, on the floor
        assert np.allclose(tilted.tool_pose(q), floor.T_scene_floor @ level.tool_pose(q), atol=1e-12)
        base = tilted.frame_pose(q, robot.base_link)
        assert floor.height_of(base[:3, 3])[0] == pytest.approx(0.0, abs=1e-12)
        assert base[:3, 2] @ np.asarray(floor.normal) == pytest.approx(1.0)
    # the base box's bottom is BASE_CLEARANCE (3 cm) above the floor wherever it stands: the floor half-space
    # is on the floor the robot stands on
    assert not _floor_hits(tilted, urdf, qs, 0.029).any()
    assert _floor_hits(tilted, urdf, qs, 0.031).all()
