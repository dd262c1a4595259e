"""Walls fitted to the background: vertical RANSAC planes -> boxes behind them, in scene.urdf and graph.json."""

import dataclasses

import numpy as np
import pytest

from recon.config import ReconConfig
from recon.output import write_reconstruction
from recon.walls import walls_from_background

CFG = ReconConfig()


def _room(seed=0, noise=0.01):
    """Floor, a wall at x = 3 (room on -x) and one at y = -2 (room on +y), noisy, plus a cluttered box."""
    rng = np.random.default_rng(seed)
    floor = np.c_[rng.uniform(-3, 3, 4000), rng.uniform(-2, 2, 4000), rng.normal(0, noise, 4000)]
    east = np.c_[3 + rng.normal(0, noise, 5000), rng.uniform(-2, 1.5, 5000), rng.uniform(0, 2.5, 5000)]
    south = np.c_[rng.uniform(-2.5, 3, 5000), -2 + rng.normal(0, noise, 5000), rng.uniform(0, 2.4, 5000)]
    clutter = rng.uniform([-1, -1, 0], [-0.5, -0.5, 0.4], (300, 3))
    return np.vstack([floor, east, south, clutter])


def test_two_walls_are_found_behind_their_planes_facing_the_room():
    walls = walls_from_background(_room(), np.zeros(3), CFG.walls, seed=0)
    assert [w.name for w in walls] == ["wall0", "wall1"]
    by_normal = {tuple(np.round(w.T_world_wall[:3, 0]).astype(int)): w for w in walls}
    east, south = by_normal[(-1, 0, 0)], by_normal[(0, 1, 0)]
    inner = lambda w: w.T_world_wall[:3, 3] + w.T_world_wall[:3, 0] * w.size[0] / 2
    assert inner(east)[0] == pytest.approx(3.0, abs=0.01)
    assert inner(south)[1] == pytest.approx(-2.0, abs=0.01)
    # 1st..99th percentiles trim 2% of the length; the corner strip goes to whichever plane RANSAC found first
    assert east.size[1] == pytest.approx(3.5, rel=0.06) and east.T_world_wall[1, 3] == pytest.approx(-0.25, abs=0.1)
    assert east.size[2] == pytest.approx(2.5, abs=0.05) and east.T_world_wall[2, 3] == pytest.approx(1.25, abs=0.03)
    for w in walls:
        R = w.T_world_wall[:3, :3]
        assert np.allclose(R.T @ R, np.eye(3), atol=1e-9) and np.linalg.det(R) == pytest.approx(1.0)


def test_no_walls_in_a_background_of_floor_only_or_too_few_points():
    rng = np.random.default_rng(1)
    floor = np.c_[rng.uniform(-3, 3, 5000), rng.uniform(-2, 2, 5000), rng.normal(0, 0.005, 5000)]
    assert walls_from_background(floor, np.zeros(3), CFG.walls) == ()
    assert walls_from_background(_room()[:50], np.zeros(3), CFG.walls) == ()


def test_walls_are_fixed_boxes_on_world_in_the_urdf_and_round_trip_through_graph_json(kitchen_rec, tmp_path):
    pb = pytest.importorskip("pybullet")
    from recon.graph_json import read_graph_json

    walls = walls_from_background(_room(), np.zeros(3), CFG.walls, seed=0)
    rec = dataclasses.replace(kitchen_rec, walls=walls)
    write_reconstruction(rec, tmp_path)
    back = read_graph_json(tmp_path / "graph.json")
    assert len(back.walls) == 2 and all(a.isclose(b) for a, b in zip(back.walls, walls))
    import pinocchio
    import yourdfpy

    urdf = yourdfpy.URDF.load(str(tmp_path / "scene.urdf"))
    # scene.urdf rounds lengths and angles to 1e-6
    assert urdf.validate() and np.allclose(urdf.get_transform("wall1", "world"), walls[1].T_world_wall, rtol=0, atol=2e-6)
    model = pinocchio.buildModelFromUrdf(str(tmp_path / "scene.urdf"))
    assert model.existFrame("wall0") and model.existFrame("wall1")
    cid = pb.connect(pb.DIRECT)
    try:
        uid = pb.loadURDF(str(tmp_path / "scene.urdf"), useFixedBase=True, physicsClientId=cid)
        info = {pb.getJointInfo(uid, i, physicsClientId=cid)[12].decode(): pb.getJointInfo(uid, i, physicsClientId=cid)
                for i in range(pb.getNumJoints(uid, physicsClientId=cid))}
        assert info["wall0"][2] == pb.JOINT_FIXED and info["wall0"][16] == -1      # child of world
        i = info["wall0"][0]
        pos = pb.getLinkState(uid, i, physicsClientId=cid)[4]
        assert np.allclose(pos, walls[0].T_world_wall[:3, 3], atol=1e-6)
    finally:
        pb.disconnect(cid)
