"""Shared planners test helpers: the cabinet fixture and its variants, the robot, an independent PyBullet
re-check of plans (the planner itself never imports pybullet)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pybullet as pb
import pytest

FIXTURE = Path(__file__).parent / "data" / "cabinet_fixture.urdf"
DRAWER = "cabinet1_drawer12_joint"
DOOR = "cabinet1_door14_joint"
DRAWER_HANDLE = "cabinet1_handle13"
DOOR_HANDLE = "cabinet1_handle15"


def _cut(text: str, tag: str, name: str) -> str:
    """Remove the ``<tag name="name">...</tag>`` element."""
    return re.sub(rf'\s*<{tag} name="{name}"[^>]*>.*?</{tag}>', "", text, count=1, flags=re.S)


def without_drawer_handle(tmp: Path) -> Path:
    t = FIXTURE.read_text()
    t = _cut(_cut(t, "link", DRAWER_HANDLE), "joint", DRAWER_HANDLE + "_joint")
    out = tmp / "no_handle.urdf"
    out.write_text(t)
    return out


def drawer_handle_as_named_geometry(tmp: Path) -> Path:
    """The drawer handle bar as a collision named "handle_bar" inside the drawer link (no handle link)."""
    t = FIXTURE.read_text()
    t = _cut(_cut(t, "link", DRAWER_HANDLE), "joint", DRAWER_HANDLE + "_joint")
    bar = ('    <collision name="handle_bar"><origin xyz="0.285 0 0.615"/><geometry><box size="0.02 0.30 0.02"/>'
           '</geometry></collision>\n  </link>')
    t = re.sub(r'(<link name="cabinet1_drawer12">.*?)\n  </link>', lambda m: m.group(1) + "\n" + bar, t, count=1,
               flags=re.S)
    out = tmp / "named_geometry.urdf"
    out.write_text(t)
    return out


def with_wall(tmp: Path, x: float = 1.02) -> Path:
    """A wall (fixed to the world) between the robot's side of the room and the cabinet front at x = 1.25."""
    t = FIXTURE.read_text()
    wall = (f'  <link name="room0_wall1"><collision><origin xyz="{x - 0.05} 0 1.0"/><geometry><box size="0.1 4 2"/>'
            '</geometry></collision></link>\n'
            '  <joint name="room0_wall1_joint" type="fixed"><parent link="world"/><child link="room0_wall1"/>'
            '</joint>\n</robot>')
    t = t.replace("</robot>", wall)
    out = tmp / "walled.urdf"
    out.write_text(t)
    return out


def write(tmp: Path, name: str, text: str) -> Path:
    out = tmp / name
    out.write_text(text)
    return out

def pybullet_contacts(robot, scene_urdf, plan, handle_links, tol=0.002, allow_segments=("grasp", "open")):
    """List of (segment, sample, robot link, scene link, depth) where robot and scene penetrate deeper than
    ``tol`` metres; gripper-handle contacts are allowed in ``allow_segments``. Also the floor (z < -tol)."""
    cid = pb.connect(pb.DIRECT)
    try:
        rid = pb.loadURDF(str(robot.urdf), useFixedBase=True, physicsClientId=cid)
        sid = pb.loadURDF(str(scene_urdf), useFixedBase=True, physicsClientId=cid)
        rj = {pb.getJointInfo(rid, i, physicsClientId=cid)[1].decode(): i
              for i in range(pb.getNumJoints(rid, physicsClientId=cid))}
        rlink = {i: pb.getJointInfo(rid, i, physicsClientId=cid)[12].decode()
                 for i in range(pb.getNumJoints(rid, physicsClientId=cid))}
        sj = {pb.getJointInfo(sid, i, physicsClientId=cid)[1].decode(): i
              for i in range(pb.getNumJoints(sid, physicsClientId=cid))}
        slink = {i: pb.getJointInfo(sid, i, physicsClientId=cid)[12].decode()
                 for i in range(pb.getNumJoints(sid, physicsClientId=cid))}
        slink[-1] = "world"
        cols = [rj[n] for n in plan.joint_names]
        for f in robot.finger_joints:
            pb.resetJointState(rid, rj[f], robot.finger_open, physicsClientId=cid)
        tj = sj[plan.task.joint]
        bad = []
        for seg in plan.segments:
            for k in range(len(seg.q)):
                for c, v in zip(cols, seg.q[k]):
                    pb.resetJointState(rid, c, float(v), physicsClientId=cid)
                pb.resetJointState(sid, tj, float(seg.object_q[k]), physicsClientId=cid)
                pb.performCollisionDetection(physicsClientId=cid)
                for cp in pb.getContactPoints(rid, sid, physicsClientId=cid):
                    if cp[8] >= -tol:
                        continue
                    rl, sl = rlink[cp[3]], slink[cp[4]]
                    if seg.name in allow_segments and rl in robot.gripper_links and sl in handle_links:
                        continue
                    bad.append((seg.name, k, rl, sl, cp[8]))
                for i in rlink:
                    lo = pb.getAABB(rid, i, physicsClientId=cid)[0]
                    if lo[2] < -tol and rlink[i] not in ("base_x_link", "base_y_link"):
                        bad.append((seg.name, k, rlink[i], "floor", lo[2]))
        return bad
    finally:
        pb.disconnect(cid)


@pytest.fixture(scope="session")
def robot():
    from planners import default_robot
    return default_robot()


@pytest.fixture(scope="session")
def fixture_urdf() -> Path:
    return FIXTURE


@pytest.fixture(scope="session")
def pb_contacts():
    """``pb_contacts(robot, scene_urdf, plan, handle_links) -> [(segment, k, robot link, scene link, depth)]``."""
    return pybullet_contacts


@pytest.fixture
def variants(tmp_path):
    """Builders of fixture variants in ``tmp_path``: no_handle(), named_geometry(), walled(x), write(name, text)."""
    from types import SimpleNamespace
    return SimpleNamespace(no_handle=lambda: without_drawer_handle(tmp_path),
                           named_geometry=lambda: drawer_handle_as_named_geometry(tmp_path),
                           walled=lambda x=1.02: with_wall(tmp_path, x),
                           knob=lambda: knob_close_to_the_face(tmp_path),
                           write=lambda name, text: write(tmp_path, name, text),
                           text=FIXTURE.read_text())


def knob_close_to_the_face(tmp: Path) -> Path:
    """The drawer handle replaced by a short knob (r 16 mm, 36 mm long, lying along the face) 21 mm proud of
    the drawer front, as recon reconstructs small knobs."""
    t = FIXTURE.read_text()
    knob = ('<link name="cabinet1_handle13">\n    <inertial><origin xyz="0 0 0"/><mass value="0.02"/>'
            '<inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial>\n'
            '    <collision><origin xyz="0 0 0" rpy="1.5707963 0 0"/><geometry><cylinder radius="0.016" '
            'length="0.036"/></geometry></collision>\n  </link>')
    t = re.sub(r'<link name="cabinet1_handle13">.*?</link>', knob, t, count=1, flags=re.S)
    t = t.replace('<origin xyz="0.285 0 0.615" rpy="0 0 0.000000"/>', '<origin xyz="0.271 0 0.615" rpy="0 0 0"/>')
    assert '0.271 0 0.615' in t
    out = tmp / "knob.urdf"
    out.write_text(t)
    return out
