"""The object-level baseline on synthetic scans of generator objects with known pose (seeded)."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from recon.baseline import (BaselineStatus, TemplatePlacement, fit_object, library_from_generators,
                            reconstruct_object_level, scanned_box, template_from_object, yaw_candidates)
from recon.metrics import ObjectEstimate, evaluate_scene, joint_summary, truth_from_dict, union_mesh
from recon.primitive import Primitive
from recon.scan import ObjectPoints, PartPoints, Scan
from scenes.generators import GENERATORS
from scenes.description import joint_name, link_name


def pose(yaw: float, xyz) -> np.ndarray:
    T = np.eye(4)
    c, s = np.cos(yaw), np.sin(yaw)
    T[:2, :2] = [[c, -s], [s, c]]
    T[:3, 3] = xyz
    return T


def scan_object(obj, T_world_object, object_id: int, seed: int, per_part: int = 600):
    """Points on each part's surface that a camera in front could see (no back, no bottom faces)."""
    rng = np.random.default_rng(seed)
    tmpl = template_from_object(obj, "truth")
    parts = []
    for k, part in enumerate(tmpl.parts):
        mesh = union_mesh(part.primitives)
        pts, faces = trimesh.sample.sample_surface(mesh, per_part, seed=int(rng.integers(1 << 30)))
        n = mesh.face_normals[faces]
        keep = (n[:, 0] > -0.5) & (n[:, 2] > -0.5)
        world = pts[keep] @ T_world_object[:3, :3].T + T_world_object[:3, 3]
        parts.append(PartPoints(object_id, 100 * object_id + part.id, part.label, world))
    return ObjectPoints(object_id, obj.category, tuple(parts))


def truth_dict(obj, T_world_object, object_id: int) -> dict:
    """A truth.json object entry for ``obj`` placed at ``T_world_object`` with part ids 100*id + local."""
    pid = lambda local: 100 * object_id + local
    parts = [{"id": pid(p.id), "label": p.label, "link": link_name(obj.category, object_id, p.label, pid(p.id)),
              "T_world_part": (T_world_object @ p.T_object_part).tolist(),
              "shapes": [{"type": s.kind.value, "size": s.size.tolist(), "radius": s.size[0] / 2,
                          "length": s.size[2], "T_part_shape": s.T_link_shape.tolist()} for s in p.shapes]}
             for p in obj.parts]
    R, t = T_world_object[:3, :3], T_world_object[:3, 3]
    joints = [{"name": joint_name(obj.category, object_id, obj.part(j.child).label, pid(j.child)),
               "type": j.type.value, "parent_part_id": None if j.parent is None else pid(j.parent),
               "child_part_id": pid(j.child), "axis": (R @ j.axis).tolist(), "origin": (R @ j.origin + t).tolist(),
               "lower": j.lower, "upper": j.upper} for j in obj.joints]
    return {"id": object_id, "name": f"{obj.category}{object_id}", "category": obj.category,
            "T_world_object": T_world_object.tolist(), "size": obj.size.tolist(), "supported_by": None,
            "parts": parts, "joints": joints, "contacts": [[pid(a), pid(b)] for a, b in obj.contacts]}


@pytest.fixture(scope="module")
def library():
    return library_from_generators(variants=2)


def test_scanned_box_recovers_yaw_modulo_90_and_size():
    rng = np.random.default_rng(0)
    box = Primitive("box", np.array([1.2, 0.5, 0.8]), pose(0.4, (2.0, 1.0, 0.4)))
    pts, _ = box.sample_surface(3000, rng)
    sb = scanned_box(pts)
    yaw_err = (sb.yaw - 0.4 + np.pi / 4) % (np.pi / 2) - np.pi / 4
    assert abs(yaw_err) < np.radians(0.5)
    assert sorted(sb.size[:2]) == pytest.approx([0.5, 1.2], abs=0.01) and sb.size[2] == pytest.approx(0.8, abs=0.01)
    np.testing.assert_allclose(sb.T_world_box[:3, 3], [2.0, 1.0, 0.0], atol=0.01)   # bottom centre
    sizes = [c.size for c in yaw_candidates(sb)]
    np.testing.assert_allclose(sizes[1], sizes[0][[1, 0, 2]])


def test_template_placement_scales_a_box_onto_the_scanned_box():
    bounds = np.array([[-0.5, -0.5, 0.0], [0.5, 0.5, 1.0]])
    target = scanned_box(Primitive("box", np.array([2.0, 1.0, 0.5]), pose(0.0, (0, 0, 0.25)))
                         .sample_surface(2000, np.random.default_rng(1))[0])
    pl = TemplatePlacement.onto(bounds, target)
    # a template cube standing on the floor maps onto the whole box; a quarter-height slab keeps its place
    cube = pl.primitive(Primitive("box", np.ones(3), pose(0.0, (0, 0, 0.5))))
    assert sorted(cube.size) == pytest.approx([0.5, 1.0, 2.0], abs=0.02)
    slab = pl.primitive(Primitive("box", np.array([1.0, 1.0, 0.25]), pose(0.0, (0, 0, 0.125))))
    assert slab.T_world_part[2, 3] == pytest.approx(0.0625, abs=0.005)
    cyl = pl.primitive(Primitive("cylinder", np.array([0.2, 0.2, 1.0]), pose(0.0, (0, 0, 0.5))))
    assert cyl.size[0] == cyl.size[1] and cyl.size[2] == pytest.approx(0.5, abs=0.01)


def test_a_library_object_is_found_whole_with_its_front_and_joints(library):
    template_obj = GENERATORS["cabinet"](np.random.default_rng([9001, 0]))   # the library's cabinet/0
    T = pose(2.0, (1.5, -0.7, 0.0))
    obj = scan_object(template_obj, T, 3, seed=1)
    row = fit_object(obj, library["cabinet"], seed=0)
    assert row.status is BaselineStatus.OK and row.template == "cabinet/0"
    assert abs((row.box.yaw - 2.0 + np.pi) % (2 * np.pi) - np.pi) < np.radians(2.0)   # front found
    truth = truth_from_dict({"format": "partscene.truth/1", "objects": [truth_dict(template_obj, T, 3)]})
    m = evaluate_scene(truth, [row.estimate])
    assert m.objects[0].iou > 0.85 and m.objects[0].chamfer < 0.02
    s = joint_summary(m.objects[0].joints)
    assert s.type_accuracy == 1.0 and s.median_axis_error_deg < 2.0
    assert m.objects[0].ap == 1.0              # the template's structure is the truth's here


def test_another_object_of_the_category_is_approximated_and_scored_lower(library):
    other = GENERATORS["table"](np.random.default_rng(5))
    T = pose(-0.6, (0.0, 2.0, 0.0))
    obj = scan_object(other, T, 7, seed=2)
    row = fit_object(obj, library["table"], seed=0)
    assert row.status is BaselineStatus.OK and row.template.startswith("table/")
    np.testing.assert_allclose(sorted(row.box.size[:2]), sorted(other.size[:2]), atol=0.03)
    truth = truth_from_dict({"format": "partscene.truth/1", "objects": [truth_dict(other, T, 7)]})
    m = evaluate_scene(truth, [row.estimate])
    assert 0.1 < m.objects[0].iou < 0.95


def test_objects_that_cannot_be_replaced_are_reported_not_dropped(library):
    rng = np.random.default_rng(3)
    sofa = ObjectPoints(5, "sofa", (PartPoints(5, 51, "seat", rng.uniform(0, 1, (200, 3))),))
    tiny = ObjectPoints(6, "chair", (PartPoints(6, 61, "seat", rng.uniform(0, 1, (10, 3))),))
    pts = np.concatenate([sofa.parts[0].points, tiny.parts[0].points])
    scan = Scan(pts, np.r_[np.full(200, 5), np.full(10, 6)], np.r_[np.full(200, 51), np.full(10, 61)], None, None,
                (sofa, tiny))
    result = reconstruct_object_level(scan, library)
    assert [o.status for o in result.objects] == [BaselineStatus.NO_TEMPLATE, BaselineStatus.TOO_FEW_POINTS]
    assert "object 5 (sofa): the library has no 'sofa' template" in result.objects[0].reason
    assert "object 6 (chair): 10 scan points" in result.objects[1].reason
    assert result.estimates == ()
    assert all(isinstance(e, ObjectEstimate) for e in result.estimates)
