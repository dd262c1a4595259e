"""The robot stands on the scene's floor (issue 12, item 5): recon keeps a ScanNet-style scan in its own frame,
its floor 5 cm up and tilted 1 deg (graph.json "floor"); the planner and the PyBullet world put the robot's
base, the ground plane and gravity on that floor, and plans stay in the scene's frame.

The scene: the generated kitchen (seed 0, a light clean scan) moved rigidly as a tilted scanner would see it,
reconstructed WITHOUT level_floor. Real physics, seeded planning."""

import dataclasses
import json

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import scenes
from planners.plan import robot_kinematics
from planners.robot import BASE_CLEARANCE, BASE_SIZE, default_robot
from recon.output import write_reconstruction
from recon.pipeline import reconstruct_scan
from recon.scan import read_scan
from scenes.description import read_scene_floor
from simcheck.certification import certify
from simcheck.config import DEFAULT_PHYSICS
from simcheck.given_plan import certify_plan
from simcheck.robot_binding import sim_robot_from_spec
from simcheck.rollout import Rollout
from simcheck.world import World

DRAWER = "cabinet1_drawer4_joint"
DOOR = "refrigerator3_door14_joint"
FRIDGE_DOORS = ("refrigerator3_door14_joint", "refrigerator3_door16_joint")
DRAWERS = ("cabinet1_drawer4_joint", "cabinet1_drawer6_joint", "cabinet1_drawer8_joint")
TILT_DEG, HEIGHT = 1.0, 0.05


def _T_scan_world() -> np.ndarray:
    """A scanner frame whose floor is HEIGHT m up along its normal, tilted TILT_DEG about a horizontal axis."""
    a = np.array([1.0, 0.3, 0.0]) / np.hypot(1.0, 0.3)        # the cabinet's drawers slide along the slope
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec(np.radians(TILT_DEG) * a).as_matrix()
    T[:3, 3] = HEIGHT * T[:3, 2]
    return T


@pytest.fixture(scope="module")
def tilted(tmp_path_factory):
    """Folder with scene.urdf + graph.json of the tilted kitchen scan, in the scan's frame."""
    out = tmp_path_factory.mktemp("tilted_kitchen")
    scenes.make_scene("kitchen", seed=0, preset="clean", out=out / "truth", previews=False,
                      n_frames=16, width=200, height=150)
    scan = read_scan(out / "truth" / "scan.ply", out / "truth" / "labels.json").transformed(_T_scan_world())
    write_reconstruction(reconstruct_scan(scan, seed=0), out / "est")
    floor = json.loads((out / "est" / "graph.json").read_text())["floor"]
    assert floor["height_m"] == pytest.approx(HEIGHT, abs=0.003) and floor["tilt_deg"] == pytest.approx(TILT_DEG, abs=0.1)
    return out / "est"


def _base_bottom_heights(T_world_base: np.ndarray, floor) -> np.ndarray:
    """(4,) heights (m) of the base box's bottom corners above ``floor``, along its normal."""
    sx, sy, _ = BASE_SIZE
    corners = np.array([T_world_base @ [x, y, BASE_CLEARANCE, 1.0] for x in (-sx / 2, sx / 2) for y in (-sy / 2, sy / 2)])
    return floor.height_of(corners[:, :3])


def test_the_robot_stands_on_the_estimated_floor_and_gravity_pulls_along_its_normal(tilted):
    """Fails with the robot at z = 0 and gravity along -z: its base 2.5-3.8 cm inside the scene's floor, tilted
    1 deg off it, and frictionless drawers sliding out (0.41 m in 2 s) and fridge doors swinging shut (0.6 rad in
    4 s)."""
    floor = read_scene_floor(tilted / "scene.urdf")
    assert not floor.level and floor.tilt_deg == pytest.approx(TILT_DEG, abs=0.1)
    spec = default_robot()
    frictionless = dataclasses.replace(DEFAULT_PHYSICS, min_joint_friction=0.0)
    with World(tilted / "scene.urdf", sim_robot_from_spec(spec), frictionless, visuals=False) as w:
        assert w.scene_floor == floor
        q = spec.home_q.copy()
        q[:3] = (-1.0, 0.4, 1.0)
        for name in FRIDGE_DOORS:
            w.reset_scene_joint(name, 0.6)
        w.reset_robot(q)
        w.step(480)                                       # 2 s: nothing touches the scene
        T_base = w.robot_link_pose(spec.base_link)
        assert np.abs(_base_bottom_heights(T_base, floor) - BASE_CLEARANCE).max() < 1e-6   # no sinking, no floating
        assert T_base[:3, 2] @ np.asarray(floor.normal) > np.cos(np.radians(0.01))
        for name in DRAWERS:
            assert abs(w.scene_joint_state(name)[0]) < 1e-4, name
        for name in FRIDGE_DOORS:
            assert abs(w.scene_joint_state(name)[0] - 0.6) < 1e-4, name


def test_a_drawer_and_a_door_are_certified_with_the_robot_on_the_floor_and_their_plans_replay(tilted):
    """Fails with gravity along -z: the drawer slides open down the slope (0.41 m in 3 s, despite its joint
    friction) before the robot comes, and its grasp closes on nothing."""
    cert = certify(tilted / "scene.urdf", [f"open-drawer:{DRAWER}", f"open-door:{DOOR}"], out=tilted / "cert",
                   images=False, seed=0, save_plan=True)
    assert cert.ok, cert.summary()
    floor = read_scene_floor(tilted / "scene.urdf")
    kin = robot_kinematics(default_robot(), floor)
    for t in cert.tasks:
        r = Rollout.load(tilted / "cert" / t.rollout)
        approach = r.in_segment("approach")                # the robot drives up; nothing touches the part
        assert approach.sum() > 10 and np.abs(r.object_q[approach] - r.object_q0).max() < 1e-5
        for q in r.robot_q[:: max(1, len(r.robot_q) // 20)]:
            heights = _base_bottom_heights(kin.frame_pose(q, "base_link"), floor)
            assert np.abs(heights - BASE_CLEARANCE).max() < 1e-6
        assert "floor" not in set(r.contact_scene_link.tolist())
    # the saved plan (joint values; tool positions in the scene's frame) replays on the same floor
    given = certify_plan(tilted / "scene.urdf", tilted / "cert" / "plans" / f"{DRAWER}.plan.json", images=False)
    assert given.ok, given.summary()
    for name in ("handle_path_deviation", "opened_fraction"):
        assert given.tasks[0].criterion(name).value == pytest.approx(cert[DRAWER].criterion(name).value, abs=2e-4)
