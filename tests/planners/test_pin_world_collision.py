"""Planning-time collision checks (pinocchio + coal) against PyBullet, and the gripper-handle allowance."""

from __future__ import annotations

import numpy as np
import pytest
import pybullet as pb

from planners import OpenTask, PlannerConfig
from planners.handle import find_handle
from planners.ik import solve_ik
from planners.pin_world import PlanningWorld
from planners.plan import robot_kinematics
from planners.scene_urdf import read_scene_urdf

DRAWER = "cabinet1_drawer12_joint"


def _world(robot, urdf, joint=DRAWER, kind="drawer", clearance=0.0):
    kin = robot_kinematics(robot)
    scene = read_scene_urdf(urdf)
    handle = find_handle(scene, OpenTask(kind, joint), {}, PlannerConfig())
    return kin, PlanningWorld(kin, scene, joint, set(handle.handle_geoms), {}, clearance), handle, scene


def test_robot_scene_collisions_agree_with_pybullet(robot, fixture_urdf):
    kin, world, _, _ = _world(robot, fixture_urdf)
    rng = np.random.default_rng(7)
    n = 400
    qs = rng.uniform(kin.lower, kin.upper, size=(n, robot.dof))
    qs[:, 0] = rng.uniform(0.3, 1.3, n)
    qs[:, 1] = rng.uniform(-0.8, 0.8, n)
    qs[:, 2] = rng.uniform(-np.pi, np.pi, n)
    s = rng.uniform(0.0, 0.35, n)
    ours = [any("scene::" in a + b for a, b in world.colliding_pairs(q, sk)) for q, sk in zip(qs, s)]
    cid = pb.connect(pb.DIRECT)
    try:
        rid = pb.loadURDF(str(robot.urdf), useFixedBase=True, physicsClientId=cid)
        sid = pb.loadURDF(str(fixture_urdf), useFixedBase=True, physicsClientId=cid)
        rj = {pb.getJointInfo(rid, i, physicsClientId=cid)[1].decode(): i
              for i in range(pb.getNumJoints(rid, physicsClientId=cid))}
        sj = {pb.getJointInfo(sid, i, physicsClientId=cid)[1].decode(): i
              for i in range(pb.getNumJoints(sid, physicsClientId=cid))}
        for f in robot.finger_joints:
            pb.resetJointState(rid, rj[f], robot.finger_open, physicsClientId=cid)
        theirs = []
        for q, sk in zip(qs, s):
            for name, v in zip(robot.joint_names, q):
                pb.resetJointState(rid, rj[name], float(v), physicsClientId=cid)
            pb.resetJointState(sid, sj[DRAWER], float(sk), physicsClientId=cid)
            pb.performCollisionDetection(physicsClientId=cid)
            theirs.append(any(c[8] < -1e-3 for c in pb.getContactPoints(rid, sid, physicsClientId=cid)))
    finally:
        pb.disconnect(cid)
    ours, theirs = np.array(ours), np.array(theirs)
    assert 0.1 < theirs.mean() < 0.9                 # the sample has both outcomes
    assert np.mean(ours == theirs) >= 0.97
    # Convex hulls are conservative: PyBullet rarely sees a penetration we call free. Measured: 1 of 400
    # (Bullet reports panda_link6 3.5 cm inside the drawer front where coal's hull of the same mesh is 4.6 cm
    # away); plans keep PlannerConfig.clearance and simcheck re-checks every plan in PyBullet anyway.
    assert np.mean(theirs & ~ours) <= 0.005


def test_gripper_may_touch_the_handle_only_when_allowed(robot, fixture_urdf):
    kin, world, handle, scene = _world(robot, fixture_urdf)
    T = scene.T_world_link(handle.moving_link) @ handle.T_link_grasps[0]
    q0 = robot.q_with_base(robot.home_q, 0.55, 0.0, 0.0)
    r = solve_ik(kin.tool_pose_jacobian, T, q0, kin.lower, kin.upper, restarts=8,
                 rng=np.random.default_rng(0), accept=lambda q: not world.in_collision(q, 0.0, False))
    assert r.success   # open fingers around the bar: free even without the allowance
    world.q[kin.idx_finger] = robot.finger_closed   # fingers shut through the 2 cm bar
    assert world.in_collision(r.q, 0.0, allow_grasp_contact=False)
    assert not world.in_collision(r.q, 0.0, allow_grasp_contact=True)
    pairs = world.colliding_pairs(r.q, 0.0)
    assert pairs and all("finger" in a or "hand" in a for a, _ in pairs)
    assert all(b.startswith("scene::cabinet1_handle13") for _, b in pairs)


def test_the_task_joint_value_moves_the_drawer_geometry(robot, fixture_urdf):
    kin, world, handle, scene = _world(robot, fixture_urdf)
    # The base just in front of the closed drawer is free; with the drawer pulled out 0.35 m it is hit.
    q = robot.q_with_base(robot.home_q, 1.5 - 0.25 - 0.36, 0.0, 0.0)
    assert not world.in_collision(q, 0.0)
    assert world.in_collision(q, 0.35)
    assert world.checks == 2


def test_clearance_keeps_the_base_away_from_the_scene(robot, fixture_urdf):
    # Base front (0.30 m ahead of its centre) 5 mm short of the cabinet front at x = 1.25.
    q = robot.q_with_base(robot.home_q, 1.25 - 0.30 - 0.005, 0.0, 0.0)
    assert not _world(robot, fixture_urdf)[1].in_collision(q)
    assert _world(robot, fixture_urdf, clearance=0.01)[1].in_collision(q)
    assert not _world(robot, fixture_urdf, clearance=0.004)[1].in_collision(q)
    assert _world(robot, fixture_urdf)[1].clearance(q) == pytest.approx(0.005, abs=1e-4)


def test_on_the_approach_the_gripper_keeps_the_clearance_from_a_neighbour_but_not_from_its_own_part(robot, tmp_path):
    """``kitchen_unit_double_door``: the doors touch. A tool pointing into the right door (the sibling of the task's
    left door) 5 mm further out than the nearest it may come without the clearance: free, but in collision while
    keep_gripper_clear is on; the same in front of the left door (the task's own part) is free either way."""
    import thirdparty
    o = thirdparty.build_object(thirdparty.spec_named("kitchen_unit_double_door"), tmp_path)
    kin = robot_kinematics(robot)
    scene = read_scene_urdf(o.urdf)
    left, right = o.fronts[0], o.fronts[1]
    h = find_handle(scene, OpenTask("door", left.joint), {}, PlannerConfig())
    world = PlanningWorld(kin, scene, left.joint, set(h.handle_geoms), {}, 0.01)
    yaw = np.deg2rad(o.spec.place[2])
    out = np.array([np.sin(yaw), -np.cos(yaw), 0.0])            # the fronts' outward normal

    def closest_free(front) -> np.ndarray:
        """A configuration with the tool pointing into ``front``'s panel 5 mm out of the nearest free one."""
        link = scene.T_world_link(front.moving_link, {})
        panel = scene.links[front.moving_link].collisions[0]
        p = (link @ panel.T_link_shape)[:3, 3] + np.array([0, 0, 0.15])   # above the handle, on the panel
        T = np.eye(4)
        T[:3, 0], T[:3, 2] = [0, 0, 1], -out
        T[:3, 1] = np.cross(T[:3, 2], T[:3, 0])
        base = p[:2] + 0.7 * out[:2]
        q = robot.q_with_base(robot.home_q, base[0], base[1], np.arctan2(-out[1], -out[0]))
        arm = np.zeros(robot.dof, bool)
        arm[3:] = True

        def at(d, q):
            T[:3, 3] = p + d * out
            r = solve_ik(kin.tool_pose_jacobian, T, q, kin.lower, kin.upper, arm, restarts=6,
                         rng=np.random.default_rng(0), accept=lambda x: not kin.self_collision(x))
            assert r.success
            return r.q

        lo, hi = 0.0, 0.2                                          # tool distances (m): in collision / free
        for _ in range(12):
            d = (lo + hi) / 2
            q = at(d, q)
            lo, hi = (lo, d) if not world.in_collision(q, 0.0) else (d, hi)
        return at(hi + 0.005, q)

    q_right = closest_free(right)
    assert not world.in_collision(q_right, 0.0), world.colliding_pairs(q_right, 0.0)
    world.keep_gripper_clear(True)
    assert world.in_collision(q_right, 0.0)
    pairs = world.colliding_pairs(q_right, 0.0)
    assert pairs and all(("finger" in a or "hand" in a) and b.startswith(f"scene::{right.moving_link}") for a, b in pairs)
    world.keep_gripper_clear(False)
    assert not world.in_collision(q_right, 0.0)
    q_left = closest_free(left)
    world.keep_gripper_clear(True)
    assert not world.in_collision(q_left, 0.0)
    # the approach's own clearance (PlannerConfig.approach_clearance): 3 mm lets the gripper come 5 mm from the neighbour
    near = PlanningWorld(kin, scene, left.joint, set(h.handle_geoms), {}, 0.01, approach_clearance=0.003)
    near.keep_gripper_clear(True)
    assert not near.in_collision(q_right, 0.0)
    far = PlanningWorld(kin, scene, left.joint, set(h.handle_geoms), {}, 0.01, approach_clearance=0.03)
    far.keep_gripper_clear(True)
    assert far.in_collision(q_right, 0.0)
    far.keep_gripper_clear(False)
    assert not far.in_collision(q_right, 0.0)


def test_the_broad_phase_answers_as_every_pair_checked_one_by_one(robot, fixture_urdf):
    """``in_collision`` (through the broad phase) is true exactly when some active pair is closer than its security
    margin: the same answer as checking every pair (no broad phase) and as coal's dynamic AABB tree, with the
    grasp allowance and the gripper's approach clearance switched on and off, near the cabinet."""
    import pinocchio as pin

    kin, world, _, _ = _world(robot, fixture_urdf, clearance=0.01)
    rng = np.random.default_rng(3)
    n = 150
    qs = rng.uniform(kin.lower, kin.upper, size=(n, robot.dof))
    qs[:, 0] = rng.uniform(0.4, 1.1, n)
    qs[:, 1] = rng.uniform(-0.6, 0.6, n)
    qs[:, 2] = rng.uniform(-0.6, 0.6, n)
    s = rng.uniform(0.0, 0.35, n)
    tree = pin.BroadPhaseManager_DynamicAABBTreeCollisionManager(world.model, world.geom, world.gdata)
    answers = []
    for k, (q, sk) in enumerate(zip(qs, s)):
        allow, clear = bool(k % 2), bool(k // 2 % 2)
        world.keep_gripper_clear(clear)
        ours = world.in_collision(q, sk, allow)
        pairs = bool(pin.computeCollisions(world.model, world.data, world.geom, world.gdata, world.q, False))
        assert ours == pairs == bool(pin.computeCollisions(world.model, world.data, tree, world.q, True)), k
        answers.append(ours)
    assert 0.2 < np.mean(answers) < 0.8               # both outcomes


def test_worlds_of_one_scene_file_share_its_models_until_the_file_changes(robot, fixture_urdf, tmp_path):
    kin, world, _, _ = _world(robot, fixture_urdf)
    again = _world(robot, fixture_urdf)[1]
    assert again.geom is world.geom and again.gdata is not world.gdata   # per-world state stays per world
    copy = tmp_path / "scene.urdf"
    copy.write_text(fixture_urdf.read_text())
    first = _world(robot, copy)[1]
    copy.write_text(fixture_urdf.read_text().replace("<robot name=", "<robot name=\"changed\" x="))
    assert _world(robot, copy)[1].geom is not first.geom
