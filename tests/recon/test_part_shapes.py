"""Articulated-template shapes: hollow carcass open at its fronts, drawer boxes inside it, and the
URDF they make (a drawer box slides over its whole range without touching its carcass or anything
else)."""

import numpy as np
import pytest

from recon.config import ReconConfig
from recon.output import write_reconstruction
from recon.part_shapes import carcass_shapes, drawer_shapes
from recon.primitive import Primitive

CFG = ReconConfig()


def box(lo, hi):
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    T = np.eye(4)
    T[:3, 3] = (lo + hi) / 2
    return Primitive("box", hi - lo, T)


BODY = box([0, -0.4, 0], [0.5, 0.4, 0.8])                       # faces +x
DRAWER = box([0.5, -0.375, 0.425], [0.52, 0.375, 0.775])         # overlay front, upper half
DOOR = box([0.5, -0.375, 0.025], [0.52, 0.375, 0.395])
X = np.array([1.0, 0, 0])


def _grid(prim, n=9):
    lo, hi = prim.corners().min(axis=0), prim.corners().max(axis=0)
    g = np.stack(np.meshgrid(*[np.linspace(a, b, n) for a, b in zip(lo, hi)], indexing="ij"), -1)
    return g.reshape(-1, 3)


def test_carcass_is_open_only_where_its_fronts_are():
    panels = carcass_shapes(BODY, [(X, DRAWER)], CFG.shapes)
    assert len(panels) > 5
    inside = lambda p: np.any([q.contains(np.atleast_2d(p)) for q in panels], axis=0)
    assert not inside([0.49, 0.0, 0.6])[0]                     # behind the drawer: open
    assert inside([0.49, 0.0, 0.2])[0]                         # behind where no front is: a panel
    assert inside([0.01, 0.0, 0.4])[0] and inside([0.25, 0.0, 0.79])[0]   # back and top panels
    assert not inside([0.25, 0.0, 0.4])[0]                     # hollow
    both = carcass_shapes(BODY, [(X, DRAWER), (X, DOOR)], CFG.shapes)
    assert not any(q.contains(np.array([[0.49, 0.0, 0.2]]))[0] for q in both)


def test_no_front_or_a_cylinder_body_keeps_the_solid_primitive():
    assert carcass_shapes(BODY, [], CFG.shapes) == (BODY,)
    side = np.array([0.0, 1.0, 0.0])
    assert carcass_shapes(BODY, [(np.array([0.7, 0.7, 0.1]) / np.linalg.norm([0.7, 0.7, 0.1]), DRAWER)],
                          CFG.shapes) == (BODY,)
    cyl = Primitive("cylinder", [0.5, 0.5, 0.8], BODY.T_world_part)
    assert carcass_shapes(cyl, [(side, DRAWER)], CFG.shapes) == (cyl,)


def test_drawer_box_reaches_back_inside_the_carcass_without_touching_it():
    shapes = drawer_shapes(DRAWER, X, BODY, CFG.shapes, CFG.joints.drawer_back_clearance)
    assert shapes[0] is DRAWER and len(shapes) == 5
    box_pts = np.concatenate([_grid(s.shrunk(1e-4)) for s in shapes[1:]])
    assert box_pts[:, 0].min() == pytest.approx(CFG.joints.drawer_back_clearance, abs=1e-3)   # back clearance
    assert box_pts[:, 0].max() <= 0.5 + 1e-9                                            # behind the front
    panels = carcass_shapes(BODY, [(X, DRAWER), (X, DOOR)], CFG.shapes)
    for s in np.linspace(0.0, 0.4, 5):                                                  # slid out by s
        assert not any(q.contains(box_pts + s * X).any() for q in panels), s


def test_no_room_behind_the_front_leaves_the_front_alone():
    thin_body = box([0.45, -0.4, 0], [0.5, 0.4, 0.8])
    assert drawer_shapes(DRAWER, X, thin_body, CFG.shapes, CFG.joints.drawer_back_clearance) == (DRAWER,)
    assert drawer_shapes(DRAWER, np.array([0.0, 0.0, 1.0]), BODY, CFG.shapes, CFG.joints.drawer_back_clearance) == (DRAWER,)


def test_reconstructed_drawer_box_slides_free_in_its_carcass_in_pybullet(kitchen_rec, tmp_path):
    pb = pytest.importorskip("pybullet")
    cab = next(o for o in kitchen_rec.objects if o.category == "cabinet")
    drawer = next(p for p in cab.parts if p.label == "drawer")
    body = cab.part(cab.root_part_id)
    assert len(drawer.solids) == 5 and len(body.solids) > 5      # the templates are in the URDF
    write_reconstruction(kitchen_rec, tmp_path)
    cid = pb.connect(pb.DIRECT)
    try:
        uid = pb.loadURDF(str(tmp_path / "scene.urdf"), useFixedBase=True, physicsClientId=cid)
        idx = {pb.getJointInfo(uid, i, physicsClientId=cid)[12].decode(): i
               for i in range(pb.getNumJoints(uid, physicsClientId=cid))}
        assert len(pb.getCollisionShapeData(uid, idx[drawer.link], physicsClientId=cid)) == 5
        parent_of = {j.child_part_id: j.parent_part_id for j in cab.joints}
        moved = 0
        for j in cab.joints:
            if j.type.value != "prismatic":
                continue
            sub = {j.child_part_id} | {c for c, p in parent_of.items() if p == j.child_part_id}
            moving = {idx[cab.part(k).link] for k in sub}
            others = [i for i in idx.values() if i not in moving]
            li = idx[cab.part(j.child_part_id).link]
            for q in np.linspace(0.0, j.upper, 6):
                pb.resetJointState(uid, li, q, physicsClientId=cid)
                for a in moving:
                    for b in others:
                        pts = pb.getClosestPoints(uid, uid, 0.005, a, b, physicsClientId=cid)
                        d = min((p[8] for p in pts), default=np.inf)
                        assert d > -1e-3, (j.name, q, b, d)
            pb.resetJointState(uid, li, 0.0, physicsClientId=cid)
            moved += 1
        assert moved == 1
    finally:
        pb.disconnect(cid)


def test_a_front_sunk_deep_into_its_body_opens_no_hole():
    sunk = box([0.42, -0.375, 0.425], [0.43, 0.375, 0.775])     # 7-8 cm inside the +x face
    panels = carcass_shapes(BODY, [(X, sunk)], CFG.shapes)
    assert any(q.contains(np.array([[0.49, 0.0, 0.6]]))[0] for q in panels)   # the face stays closed
    inset = box([0.48, -0.375, 0.425], [0.5, 0.375, 0.775])     # flush inset front: opens
    assert not any(q.contains(np.array([[0.49, 0.0, 0.6]]))[0] for q in carcass_shapes(BODY, [(X, inset)], CFG.shapes))
