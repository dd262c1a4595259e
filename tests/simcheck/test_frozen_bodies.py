"""Moving scene parts nothing of the task can reach are left out of the rollout (simcheck.frozen_bodies): a far
part is frozen, a near one is not, and a robot straying from its path loads the frozen parts again."""

import re

import numpy as np
import pybullet as pb
import pytest

from simcheck.config import DEFAULT_PHYSICS
from simcheck.execute import execute_task
from simcheck.frozen_bodies import FreezeGuard, far_parts, path_samples
from simcheck.world import World

from simcheck_fixture_plans import CABINET, DOOR, DRAWER, ROBOT, drawer_plan

FAR_DRAWER, FAR_DOOR = "cabinet9_drawer2_joint", "cabinet9_door4_joint"


@pytest.fixture(scope="module")
def two_cabinets(tmp_path_factory):
    """The fixture cabinet and a copy of it 3 m away along y (links and joints renamed cabinet9_*)."""
    text = CABINET.read_text()
    body = text[text.index('  <link name="cabinet1_body1"'):text.index("</robot>")]
    copy = body.replace("cabinet1_", "cabinet9_")
    copy = re.sub(r'(<joint name="cabinet9_body1_joint".*?<origin xyz=")0 0 0', r"\g<1>0 3 0", copy, flags=re.S)
    path = tmp_path_factory.mktemp("frozen") / "two_cabinets.urdf"
    path.write_text(text.replace("</robot>", copy + "</robot>"))
    return path


def test_far_cabinet_is_frozen_near_door_is_not(two_cabinets):
    with World(two_cabinets, ROBOT, visuals=False) as w:
        plan = drawer_plan()
        w.reset_robot(plan.segments[0].q[0])
        far, _ = far_parts(w, plan, DEFAULT_PHYSICS.freeze_margin)
        frozen = {n for b in far for n in w.part_joints(b)}
        assert frozen == {FAR_DRAWER, FAR_DOOR}            # the task's own cabinet door is kept (near)
        assert w.part_of_joint(DOOR) not in far and w.part_of_joint(DRAWER) not in far


def test_a_moving_far_part_is_not_frozen_nor_what_it_can_sweep_into(two_cabinets):
    with World(two_cabinets, ROBOT, visuals=False) as w:
        plan = drawer_plan()
        w.reset_robot(plan.segments[0].q[0])
        body = w.part_of_joint(FAR_DRAWER)
        pb.resetJointState(body, w.scene_joint(FAR_DRAWER).index, 0.1, 0.05, physicsClientId=w.client)
        far, _ = far_parts(w, plan, DEFAULT_PHYSICS.freeze_margin)
        assert far == ()             # the far drawer moves; its cabinet's door lies within its sweep


def test_rollout_with_far_parts_frozen_keeps_their_state_and_the_verdict_inputs(two_cabinets):
    plan = drawer_plan()
    rollouts = []
    for freeze in (False, True):
        with World(two_cabinets, ROBOT, visuals=False) as w:
            w.reset_scene_joint(FAR_DRAWER, 0.05)
            rollouts.append(execute_task(w, plan, freeze_far=freeze))
            if freeze:
                assert set(w.frozen_joints) >= {FAR_DRAWER, FAR_DOOR}
                assert w.scene_joint_state(FAR_DRAWER) == (pytest.approx(0.05), 0.0)
                drawer_link = w.scene_joint(FAR_DRAWER).child_link
                assert w.scene_link_pose(drawer_link)[1, 3] == pytest.approx(3.0, abs=0.3)
    full, frozen = rollouts
    assert frozen.object_q[-1] == pytest.approx(full.object_q[-1], abs=1e-3)     # the same pull, float-level apart
    assert frozen.n == full.n


def test_straying_robot_loads_the_frozen_parts_again_as_they_were(two_cabinets):
    with World(two_cabinets, ROBOT, visuals=False) as w:
        plan = drawer_plan()
        w.reset_scene_joint(FAR_DRAWER, 0.05)
        w.reset_robot(plan.segments[0].q[0])
        far, weights = far_parts(w, plan, DEFAULT_PHYSICS.freeze_margin)
        w.freeze_parts(far)
        guard = FreezeGuard(w, weights, DEFAULT_PHYSICS.freeze_margin)
        q = w.robot_q()
        guard.check(q, q + 0.01, 0.5)                       # 4 cm off the path: within half the margin
        assert guard.thawed_at is None and FAR_DRAWER in w.frozen_joints
        guard.check(q, q + np.array([0.0, 0.1, 0.0, 0.0]), 1.0)      # 10 cm: thaw
        assert guard.thawed_at == 1.0 and w.frozen_joints == ()
        assert w.scene_joint_state(FAR_DRAWER)[0] == pytest.approx(0.05)
        body = w.part_of_joint(FAR_DRAWER)
        link = w.scene_joint(FAR_DRAWER).child_link
        # loaded again with its friction motor and collisions: a push beyond its friction opens it
        for _ in range(80):
            pos = w.scene_link_pose(link)[:3, 3]
            pb.applyExternalForce(body, w.scene_joint(FAR_DRAWER).index, [60.0, 0, 0], pos.tolist(), pb.WORLD_FRAME,
                                  physicsClientId=w.client)
            w.step()
        assert w.scene_joint_state(FAR_DRAWER)[0] > 0.06
        assert any(name.startswith("cabinet9_drawer2") for name in w.scene_link_names())


def test_path_samples_leave_no_row_farther_than_a_step_from_the_last_measured_one():
    q = np.cumsum(np.random.default_rng(0).uniform(0, 0.02, (200, 2)), axis=0)
    w = np.array([1.0, 2.0])
    kept = path_samples(q, w, 0.1)
    assert (kept[0] == q[0]).all() and (kept[-1] == q[-1]).all() and len(kept) < len(q)
    run = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(q, axis=0)) @ w)])
    rows = [int(np.flatnonzero((q == k).all(axis=1))[0]) for k in kept]
    for i in range(len(q)):
        last = max(r for r in rows if r <= i)
        assert run[i] - run[last] < 0.1 + 1e-12


def test_a_far_part_gravity_could_move_is_not_frozen(two_cabinets):
    with World(two_cabinets, ROBOT, visuals=False) as w:
        plan = drawer_plan()
        w.reset_robot(plan.segments[0].q[0])
        pb.setGravity(3.0, 0.0, -9.81, physicsClientId=w.client)      # 3 m/s^2 along the drawers' axis
        far, _ = far_parts(w, plan, DEFAULT_PHYSICS.freeze_margin)
        assert w.part_of_joint(FAR_DRAWER) not in far


def test_pictures_show_frozen_parts_and_taking_them_changes_no_physics(two_cabinets):
    plan = drawer_plan()
    eye, target = np.array([1.5, 4.5, 1.5]), np.array([0.0, 3.0, 0.4])      # looking at the far cabinet
    runs, pictures = [], []
    for pictured in (False, True):
        with World(two_cabinets, ROBOT) as w:
            w.reset_scene_joint(FAR_DRAWER, 0.2)
            w.reset_robot(plan.segments[0].q[0])
            whole = w.render(target, eye, 64, 48)
            shot = (lambda label: pictures.append((whole, w.render(target, eye, 64, 48)))) if pictured else None
            runs.append(execute_task(w, plan, frame_callback=shot, freeze_far=True))
            assert FAR_DRAWER in w.frozen_joints
    plain, with_pictures = runs
    assert np.array_equal(plain.object_q, with_pictures.object_q)
    assert np.array_equal(plain.robot_q, with_pictures.robot_q)
    assert np.array_equal(plain.grasp_force, with_pictures.grasp_force)
    whole, frozen = pictures[0]                                   # the start frame: nothing has moved yet
    assert np.abs(whole.astype(int) - frozen.astype(int)).mean() < 0.1      # 1.25 without the frozen cabinet
