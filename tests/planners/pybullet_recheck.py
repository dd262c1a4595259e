"""Independent re-check of a plan in PyBullet (test helper; the planner itself never imports pybullet)."""

from __future__ import annotations

import numpy as np
import pybullet as pb


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
