"""The scene split into bodies (for step speed) keeps every name, pose and collision rule of the URDF."""

import numpy as np
import pybullet as pb
import pytest

from simcheck.world import World

from simcheck_fixture_plans import CABINET, CABINET_BLOCKED, DOOR, DRAWER, ROBOT


def _whole_urdf_poses(urdf, q: dict[str, float]) -> dict[str, np.ndarray]:
    """Link name -> world position (3,) with the URDF loaded whole in a separate client, joints at ``q``."""
    c = pb.connect(pb.DIRECT)
    try:
        body = pb.loadURDF(str(urdf), useFixedBase=True, flags=pb.URDF_USE_INERTIA_FROM_FILE, physicsClientId=c)
        out = {pb.getBodyInfo(body, physicsClientId=c)[0].decode(): np.zeros(3)}
        for j in range(pb.getNumJoints(body, physicsClientId=c)):
            info = pb.getJointInfo(body, j, physicsClientId=c)
            if info[1].decode() in q:
                pb.resetJointState(body, j, q[info[1].decode()], physicsClientId=c)
        for j in range(pb.getNumJoints(body, physicsClientId=c)):
            name = pb.getJointInfo(body, j, physicsClientId=c)[12].decode()
            out[name] = np.asarray(pb.getLinkState(body, j, computeForwardKinematics=1, physicsClientId=c)[4])
        return out
    finally:
        pb.disconnect(c)


@pytest.mark.parametrize("q", [{}, {DRAWER: 0.2, DOOR: 1.0}])
def test_split_scene_has_every_link_at_the_pose_of_the_whole_urdf(q):
    ref = _whole_urdf_poses(CABINET_BLOCKED, q)
    with World(CABINET_BLOCKED, ROBOT) as w:
        for name, value in q.items():
            w.reset_scene_joint(name, value)
        assert set(w.scene_link_names()) == set(ref)
        for name, pos in ref.items():
            assert np.allclose(w.scene_link_pose(name)[:3, 3], pos, atol=1e-9), name
        for name, value in q.items():
            assert w.scene_joint_state(name)[0] == pytest.approx(value)


def test_split_scene_keeps_joint_table_and_static_joints_read_zero():
    with World(CABINET, ROBOT) as w:
        assert [j.name for j in w.scene_joints()][:2] == ["cabinet1_body1_joint", DRAWER]
        drawer = w.scene_joint(DRAWER)
        assert (drawer.type, drawer.parent_link, drawer.child_link) == ("prismatic", "cabinet1_body1", "cabinet1_drawer2")
        assert drawer.upper == pytest.approx(0.35) and drawer.damping == pytest.approx(2.0)
        assert w.scene_joint("cabinet1_body1_joint").index == -1
        assert w.scene_joint_state("cabinet1_body1_joint") == (0.0, 0.0)


def test_a_drawer_collides_with_a_static_neighbour_but_never_with_its_parent():
    """Swung kinematically into the blocker box standing in front of the cabinet, the door must report
    the contact (non-ancestor static link); pushed 10 cm into the cabinet's back panel, the drawer never
    reports the cabinet body it slides in (its parent)."""
    with World(CABINET_BLOCKED, ROBOT) as w:
        w.reset_scene_joint(DRAWER, -0.1)
        pb.performCollisionDetection(physicsClientId=w.client)
        assert not [c for c in w.scene_link_contacts("cabinet1_drawer2") if c.link_b == "cabinet1_body1"]
        w.reset_scene_joint(DOOR, 1.0)                 # the door swings into the blocker
        pb.performCollisionDetection(physicsClientId=w.client)
        hits = {c.link_b for c in w.scene_link_contacts("cabinet1_door4")}
        assert "box9_body9" in hits and "cabinet1_body1" not in hits
