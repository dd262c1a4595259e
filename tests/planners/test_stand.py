"""Base placement: ranked, seeded stand poses from which the grasp is reached collision-free."""

from __future__ import annotations

import numpy as np

from planners import OpenTask, PlannerConfig
from planners.handle import find_handle
from planners.pin_world import PlanningWorld
from planners.plan import robot_kinematics
from planners.scene_urdf import read_scene_urdf
from planners.stand import find_stand_poses

DRAWER = "cabinet1_drawer12_joint"


def _setup(robot, urdf):
    kin = robot_kinematics(robot)
    scene = read_scene_urdf(urdf)
    handle = find_handle(scene, OpenTask("drawer", DRAWER), {}, PlannerConfig())
    world = PlanningWorld(kin, scene, DRAWER, set(handle.handle_geoms), {}, 0.01)
    s = np.linspace(0.0, 0.3, 31)
    T_moving = np.array([world.moving_link_pose(v) for v in s])
    return kin, world, [T_moving @ G for G in handle.T_link_grasps], s


def test_stand_poses_are_ranked_reach_the_grasp_and_are_seeded(robot, fixture_urdf):
    kin, world, T_paths, s = _setup(robot, fixture_urdf)
    poses, summary, _ = find_stand_poses(kin, world, T_paths, s, PlannerConfig(), np.random.default_rng(4))
    assert poses and "stand poses sampled" in summary
    keys = [p.rank_key() for p in poses]
    assert keys == sorted(keys)
    best = poses[0]
    assert best.path_share == 1.0 and best.clearance > 0.0
    T = kin.tool_pose(best.q_grasp)
    assert np.linalg.norm(T[:3, 3] - T_paths[best.grasp_index][0][:3, 3]) < 1e-3
    assert np.allclose(best.q_grasp[:3], best.base)
    assert not world.in_collision(best.q_grasp, 0.0, True)
    # In front of the cabinet (it faces world -x from x = 1.25): the base stands at smaller x.
    assert best.base[0] < 1.25 - 0.3
    again, _, _ = find_stand_poses(kin, world, T_paths, s, PlannerConfig(), np.random.default_rng(4))
    assert np.array_equal(again[0].q_grasp, best.q_grasp)
