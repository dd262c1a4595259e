"""Eq. 1 contacts against closed-form overlaps, Eq. 4 trees (template prior, isolated parts), and
Alg. 1 refinement reducing interpenetration."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from recon.config import ReconConfig
from recon.contacts import contact_edge, contact_edges
from recon.part_tree import part_tree
from recon.primitive import Primitive
from recon.refinement import interpenetration, refine_parts

CFG = ReconConfig()


def box(lo, hi, rotvec=(0, 0, 0)):
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec(rotvec).as_matrix()
    T[:3, 3] = (lo + hi) / 2
    return Primitive("box", hi - lo, T)


def planes(p):
    return p.planes(CFG.contacts.cylinder_side_faces)


@pytest.mark.parametrize("shift, expected", [(0.0, 1.0), (0.1, 0.5), (0.16, 0.2)])
def test_cont_is_the_overlapping_fraction_of_the_child_face(shift, expected):
    top = box([-0.5, -0.5, 0.7], [0.5, 0.5, 0.74])                    # 1 x 1 slab
    child = box([0.3 + shift, -0.1, 0.74], [0.5 + shift, 0.1, 0.9])    # 0.2 x 0.2 block on it
    e = contact_edge(1, planes(top), 2, planes(child), CFG.contacts)
    assert e is not None and e.score == pytest.approx(expected, abs=1e-9)
    assert e.dist == pytest.approx(0.0, abs=1e-12) and e.align == pytest.approx(1.0)
    # the reverse direction divides by the slab's face: a small ratio
    r = contact_edge(2, planes(child), 1, planes(top), CFG.contacts)
    assert r is None or r.score < 0.05 + 1e-9


def test_no_contact_when_too_far_too_tilted_or_not_overlapping():
    top = box([-0.5, -0.5, 0.7], [0.5, 0.5, 0.74])
    gap = box([-0.1, -0.1, 0.74 + 1.5 * CFG.contacts.theta_d], [0.1, 0.1, 0.9])
    tilted = box([-0.1, -0.1, 0.745], [0.1, 0.1, 0.9], rotvec=(0.4, 0, 0))   # 23 deg
    beside = box([0.6, -0.1, 0.74], [0.8, 0.1, 0.9])
    for child in (gap, tilted, beside):
        assert contact_edge(1, planes(top), 2, planes(child), CFG.contacts) is None
    near = box([-0.1, -0.1, 0.74 + 0.5 * CFG.contacts.theta_d], [0.1, 0.1, 0.9])
    assert contact_edge(1, planes(top), 2, planes(near), CFG.contacts) is not None


def test_leg_cylinder_cap_touches_the_top():
    top = box([-0.5, -0.5, 0.7], [0.5, 0.5, 0.74])
    T = np.eye(4)
    T[:3, 3] = [0.4, 0.4, 0.35]
    leg = Primitive("cylinder", [0.06, 0.06, 0.7], T)
    e = contact_edge(1, planes(top), 2, planes(leg), CFG.contacts)
    assert e is not None and e.score == pytest.approx(1.0, abs=1e-6)


def _cabinet_prims():
    body = box([0, -0.4, 0], [0.5, 0.4, 0.8])
    drawer = box([0.48, -0.375, 0.425], [0.5, 0.375, 0.775])
    handle = box([0.5, -0.08, 0.59], [0.53, 0.08, 0.61])
    return {1: body, 2: drawer, 3: handle}


def test_tree_hangs_the_handle_from_its_drawer_not_the_body():
    prims = _cabinet_prims()
    labels = {1: "body", 2: "drawer", 3: "handle"}
    edges = contact_edges({i: planes(p) for i, p in prims.items()}, CFG.contacts)
    # the handle touches the body's front plane just as well as the drawer's
    pairs = {(e.parent_part_id, e.child_part_id): e.score for e in edges}
    assert pairs[(1, 3)] == pytest.approx(1.0) and pairs[(2, 3)] == pytest.approx(1.0)
    tree = part_tree("cabinet", labels, {i: p.volume for i, p in prims.items()}, edges, CFG.tree, CFG.contacts)
    assert tree.root == 1 and tree.parent == {2: 1, 3: 2} and tree.isolated == ()


def test_parts_that_touch_nothing_are_attached_to_the_root_and_reported():
    prims = _cabinet_prims()
    prims[4] = box([2, 2, 0], [2.2, 2.2, 0.2])       # far away
    labels = {1: "body", 2: "drawer", 3: "handle", 4: "door"}
    edges = contact_edges({i: planes(p) for i, p in prims.items()}, CFG.contacts)
    tree = part_tree("cabinet", labels, {i: p.volume for i, p in prims.items()}, edges, CFG.tree, CFG.contacts)
    assert tree.parent[4] == 1 and tree.isolated == (4,) and tree.edges[4] is None
    assert sorted(tree.top_down()) == [2, 3, 4]


def test_root_is_the_base_label_else_the_largest_part():
    prims = _cabinet_prims()
    edges = contact_edges({i: planes(p) for i, p in prims.items()}, CFG.contacts)
    vol = {i: p.volume for i, p in prims.items()}
    assert part_tree("x", {1: "a", 2: "b", 3: "c"}, vol, edges, CFG.tree, CFG.contacts).root == 1
    assert part_tree("x", {1: "leg", 2: "top", 3: "c"}, vol, edges, CFG.tree, CFG.contacts).root == 2


def test_refinement_removes_tilt_and_interpenetration_of_a_leg():
    top = box([-0.5, -0.5, 0.7], [0.5, 0.5, 0.74])
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec([0.06, -0.04, 0.0]).as_matrix()     # ~4 deg off vertical
    T[:3, 3] = [0.4, 0.4, 0.35 + 0.012]                                  # sunk 12 mm into the top
    leg = Primitive("box", [0.05, 0.05, 0.7], T)
    prims = {1: top, 2: leg}
    edges = contact_edges({i: planes(p) for i, p in prims.items()}, CFG.contacts)
    tree = part_tree("table", {1: "top", 2: "leg"}, {1: top.volume, 2: leg.volume}, edges, CFG.tree, CFG.contacts)
    assert tree.parent == {2: 1}
    before = interpenetration(top, leg)
    out = refine_parts(prims, tree, CFG.refinement, CFG.contacts, CFG.fitting)
    after = interpenetration(out[1], out[2])
    assert before > 1e-5 and after < 0.05 * before
    R = out[2].T_world_part[:3, :3]
    assert np.max(np.abs(np.abs(R) - np.eye(3))) < 1e-6                  # leg axes parallel to the top's
    assert out[2].corners()[:, 2].max() == pytest.approx(0.7, abs=1e-6)  # cap on the underside
    assert out[1].isclose(top)                                           # the root does not move
