"""Every articulated joint moves through its whole range in PyBullet without its moving parts touching
anything else: its own object's other links, other objects, or walls (closest-point distance check)."""

from __future__ import annotations

import numpy as np
import pybullet as pb
import pytest

from scenes.builtin import build_scene
from scenes.footprints import subtree_parts
from scenes.truth_urdf import write_truth_urdf

PENETRATION_TOL = 1e-3   # m, pybullet closest-point distance below -tol counts as a collision
N_VALUES = 6             # joint values checked across [lower, upper]
QUERY_DISTANCE = 0.005   # m; pybullet returns nothing at all for a query distance of exactly 0


def _collisions(urdf, scene, cid):
    body = pb.loadURDF(str(urdf), useFixedBase=True, physicsClientId=cid)
    idx = {pb.getJointInfo(body, i, physicsClientId=cid)[12].decode(): i
           for i in range(pb.getNumJoints(body, physicsClientId=cid))}
    bad = []
    for o in scene.objects:
        for j in o.joints:
            if not j.movable:
                continue
            li = idx[o.link(o.part(j.child))]
            moving = {idx[o.link(o.part(p))] for p in subtree_parts(o, j.child)}
            others = [i for i in idx.values() if i not in moving]
            for q in np.linspace(j.lower, j.upper, N_VALUES):
                pb.resetJointState(body, li, q, physicsClientId=cid)
                for a in moving:
                    for b in others:
                        pts = pb.getClosestPoints(body, body, QUERY_DISTANCE, a, b, physicsClientId=cid)
                        d = min((p[8] for p in pts), default=np.inf)
                        if d < -PENETRATION_TOL:
                            names = {v: k for k, v in idx.items()}
                            bad.append((o.joint_name(j), round(float(q), 3), names[b], round(d, 4)))
            pb.resetJointState(body, li, 0.0, physicsClientId=cid)
    pb.removeBody(body, physicsClientId=cid)
    return bad


@pytest.mark.parametrize("name, seeds", [("kitchen", (0, 1, 2)), ("office", (0, 1)), ("bedroom", (0,)),
                                         ("random", (0, 1)), ("studio", (0,))])
def test_joints_sweep_their_range_without_collision(tmp_path, name, seeds):
    cid = pb.connect(pb.DIRECT)
    try:
        for seed in seeds:
            scene = build_scene(name, seed)
            urdf = write_truth_urdf(scene, tmp_path / f"{name}{seed}.urdf")
            assert _collisions(urdf, scene, cid) == [], f"{name} seed {seed}"
    finally:
        pb.disconnect(cid)


def test_sweep_check_detects_a_joint_whose_range_is_too_long(tmp_path):
    """A drawer whose positive direction pushes it into its carcass must be reported."""
    import dataclasses

    scene = build_scene("kitchen", 0)
    cab = next(o for o in scene.objects if o.category == "cabinet")
    j = next(j for j in cab.joints if j.movable and cab.part(j.child).label == "drawer")
    # flip the axis: positive values now push the drawer into the carcass
    bad_j = dataclasses.replace(j, axis=-j.axis)
    bad_cab = dataclasses.replace(cab, joints=tuple(bad_j if x is j else x for x in cab.joints))
    scene = dataclasses.replace(scene, objects=tuple(bad_cab if o is cab else o for o in scene.objects))
    urdf = write_truth_urdf(scene, tmp_path / "bad.urdf")
    cid = pb.connect(pb.DIRECT)
    try:
        bad = _collisions(urdf, scene, cid)
    finally:
        pb.disconnect(cid)
    assert any(b[0] == cab.joint_name(j) for b in bad)
