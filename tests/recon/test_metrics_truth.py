"""truth.json reading (each malformed case named) and whole-scene evaluation on a hand-built truth."""

from __future__ import annotations

import copy
import json

import numpy as np
import pytest

from recon.metrics import (MetricsConfig, ObjectEstimate, ObjectStatus, TruthFormatError, evaluate_scene,
                           joint_summary, read_truth, truth_from_dict)
from recon.model import JointEstimate, JointType
from recon.primitive import Primitive


def T(xyz=(0.0, 0.0, 0.0)):
    M = np.eye(4)
    M[:3, 3] = xyz
    return M.tolist()


def cabinet_truth() -> dict:
    """A 0.6 x 0.8 x 0.8 m cabinet at x=1: hollow body (5 panels), one drawer, its handle; a 1-part stool."""
    t = 0.02
    panels = [  # (size, centre) in the body frame (origin on the floor at the footprint centre)
        ([0.6, 0.8, t], (0, 0, t / 2)), ([0.6, 0.8, t], (0, 0, 0.8 - t / 2)),
        ([0.6, t, 0.8], (0, -0.4 + t / 2, 0.4)), ([0.6, t, 0.8], (0, 0.4 - t / 2, 0.4)),
        ([t, 0.8, 0.8], (-0.3 + t / 2, 0, 0.4)),
    ]
    body = {"id": 11, "label": "body", "link": "cabinet3_body11", "T_world_part": T((1.0, 0.0, 0.0)),
            "shapes": [{"type": "box", "size": s, "T_part_shape": T(c)} for s, c in panels]}
    drawer = {"id": 12, "label": "drawer", "link": "cabinet3_drawer12", "T_world_part": T((1.29, 0.0, 0.4)),
              "shapes": [{"type": "box", "size": [t, 0.75, 0.7], "T_part_shape": T()}]}
    handle = {"id": 13, "label": "handle", "link": "cabinet3_handle13", "T_world_part": T((1.32, 0.0, 0.6)),
              "shapes": [{"type": "cylinder", "radius": 0.01, "length": 0.3,
                          "T_part_shape": [[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]]}]}
    stool = {"id": 21, "label": "seat", "link": "stool4_seat21", "T_world_part": T((-1.0, 0.0, 0.25)),
             "shapes": [{"type": "cylinder", "radius": 0.2, "length": 0.5, "T_part_shape": T()}]}
    return {
        "format": "partscene.truth/1", "scene": "unit", "seed": 0, "floor": {"z": 0.0}, "walls": [],
        "objects": [
            {"id": 3, "name": "cabinet3", "category": "cabinet", "T_world_object": T((1.0, 0.0, 0.0)),
             "size": [0.64, 0.8, 0.8], "supported_by": None, "parts": [body, drawer, handle],
             "joints": [{"name": "cabinet3_body11_joint", "type": "fixed", "parent_part_id": None,
                         "child_part_id": 11, "axis": [0, 0, 0], "origin": [1.0, 0, 0]},
                        {"name": "cabinet3_drawer12_joint", "type": "prismatic", "parent_part_id": 11,
                         "child_part_id": 12, "axis": [1, 0, 0], "origin": [1.29, 0, 0.4], "lower": 0.0,
                         "upper": 0.45, "handle_part_id": 13},
                        {"name": "cabinet3_handle13_joint", "type": "fixed", "parent_part_id": 12,
                         "child_part_id": 13, "axis": [0, 0, 0], "origin": [1.32, 0, 0.6], "lower": 0.0,
                         "upper": 0.0, "handle_part_id": None}],
             "contacts": [[11, 12], [12, 13]]},
            {"id": 4, "name": "stool4", "category": "chair", "T_world_object": T((-1.0, 0.0, 0.0)),
             "size": [0.4, 0.4, 0.5], "supported_by": None, "parts": [stool], "joints": [], "contacts": []},
        ],
    }


def perfect_estimate(obj) -> ObjectEstimate:
    """An estimate that copies the truth: its shapes, joints and contact edges (score 0.8)."""
    return ObjectEstimate(obj.id, obj.category, obj.primitives, obj.joints, {e: 0.8 for e in obj.contacts})


def test_read_truth_builds_world_shapes(tmp_path):
    path = tmp_path / "truth.json"
    path.write_text(json.dumps(cabinet_truth()))
    scene = read_truth(path)
    cab = scene.object(3)
    assert [p.id for p in cab.parts] == [11, 12, 13] and len(cab.primitives) == 7
    top = cab.part(11).primitives[1]
    np.testing.assert_allclose(top.T_world_part[:3, 3], [1.0, 0.0, 0.79])
    handle = cab.part(13).primitives[0]
    np.testing.assert_allclose(handle.size, [0.02, 0.02, 0.3])
    assert cab.joints[0].parent_part_id is None           # the root's world joint is read ...
    assert cab.joints[1].type is JointType.PRISMATIC and cab.joints[1].upper == 0.45
    assert cab.contacts == ((11, 12), (12, 13))


def _broken(mutate):
    d = cabinet_truth()
    mutate(d)
    return d


@pytest.mark.parametrize("mutate, message", [
    (lambda d: d.update(format="partscene.truth/0"), r"truth.json: format is 'partscene.truth/0'"),
    (lambda d: d["objects"][0].pop("parts"), r"object 3 \(cabinet3\): missing field 'parts'"),
    (lambda d: d["objects"][0]["parts"][1].update(shapes=[]), r"object 3 \(cabinet3\) part 12: has no shapes"),
    (lambda d: d["objects"][0]["parts"][1]["shapes"][0].update(type="cone"),
     r"part 12 shape 0: unknown shape type 'cone'"),
    (lambda d: d["objects"][0]["parts"][1]["shapes"][0].update(size=[0.02, -0.7, 0.7]),
     r"part 12 shape 0: bad box shape"),
    (lambda d: d["objects"][0]["parts"][0].update(T_world_part=[[1, 0], [0, 1]]),
     r"part 11.T_world_part: expected a finite 4x4 pose"),
    (lambda d: d["objects"][0]["joints"][1].update(child_part_id=99),
     r"object 3 \(cabinet3\) joint cabinet3_drawer12_joint: names unknown part 99"),
    (lambda d: d["objects"][0]["joints"][1].update(axis=[2, 0, 0]),
     r"joint cabinet3_drawer12_joint: prismatic axis \[2.0, 0.0, 0.0\] is not a unit vector"),
    (lambda d: d["objects"][0]["joints"][1].update(type="ball"),
     r"joint cabinet3_drawer12_joint: unknown joint type 'ball'"),
    (lambda d: d["objects"][0]["contacts"].append([12, 12]),
     r"object 3 \(cabinet3\): contact edge \[12, 12\] must join two distinct parts"),
    (lambda d: d["objects"][1].update(id=3), r"truth.json: duplicate object ids"),
])
def test_malformed_truth_is_rejected_naming_the_culprit(mutate, message):
    with pytest.raises(TruthFormatError, match=message):
        truth_from_dict(_broken(mutate))


def test_unreadable_truth_file_names_the_path(tmp_path):
    bad = tmp_path / "truth.json"
    bad.write_text("{not json")
    with pytest.raises(TruthFormatError, match=r"truth.json: not valid JSON"):
        read_truth(bad)
    with pytest.raises(TruthFormatError, match=r"missing.json: cannot read"):
        read_truth(tmp_path / "missing.json")


def test_perfect_estimate_scores_perfectly_and_a_missing_object_is_reported():
    scene = truth_from_dict(cabinet_truth())
    cfg = MetricsConfig(chamfer_samples=4000)
    m = evaluate_scene(scene, [perfect_estimate(o) for o in scene.objects], cfg)
    cab = m.objects[0]
    assert cab.status is ObjectStatus.OK and cab.iou == 1.0 and cab.ap == 1.0
    assert cab.chamfer < 1e-6                    # exact point-to-surface distances: no floor
    assert np.isnan(m.objects[1].ap)             # a one-part object has no true edge
    s = joint_summary(j for o in m.objects for j in o.joints)
    assert s.type_accuracy == 1.0 and s.median_axis_error_deg == 0.0
    assert s.n_joints == 2                       # ... but not scored: only part-to-part joints

    only_stool = evaluate_scene(scene, [perfect_estimate(scene.object(4))], cfg)
    assert only_stool.objects[0].status is ObjectStatus.MISSING and only_stool.missing == 1
    assert only_stool.iou == pytest.approx(0.5)  # the missing cabinet counts 0, the stool 1
    assert joint_summary(only_stool.objects[0].joints).type_accuracy == 0.0


def test_solid_box_for_a_hollow_cabinet_is_penalised_and_a_wrong_joint_is_caught():
    scene = truth_from_dict(cabinet_truth())
    cab = scene.object(3)
    solid = Primitive("box", np.array([0.64, 0.8, 0.8]), np.array(T((1.02, 0.0, 0.4))))
    wrong_joint = JointEstimate("cabinet3_drawer12_joint", JointType.REVOLUTE, 11, 12, np.array([0, 0, 1.0]),
                                np.array([1.3, 0.4, 0.4]), 0.0, 1.5)
    est = ObjectEstimate(3, "cabinet", (solid,), (wrong_joint,), {(11, 13): 0.9, (11, 12): 0.5})
    m = evaluate_scene(scene, [est, perfect_estimate(scene.object(4))], MetricsConfig(chamfer_samples=4000))
    row = m.objects[0]
    assert 0.2 < row.iou < 0.75                 # 4 cm gaps above and below the drawer: the cavity is open, not filled
    assert row.ap == pytest.approx((0 + 1 / 2) / 2)   # false edge first, one true edge never found
    drawer = [j for j in row.joints if j.child_part_id == 12][0]
    assert not drawer.type_correct and drawer.axis_error_deg == pytest.approx(90.0)


def test_part_diagnostics_point_at_the_part_that_is_off():
    from recon.metrics import PartStatus, evaluate_parts

    cab = truth_from_dict(cabinet_truth()).object(3)
    prims, ids = [], []
    for part in cab.parts:
        if part.id == 13:
            continue                                               # the handle is not estimated
        for p in part.primitives:
            shift = np.eye(4)
            if part.id == 12:
                shift[:3, 3] = [0.05, 0.0, 0.0]                    # the drawer sticks out 5 cm
            prims.append(p.transformed(shift))
            ids.append(part.id)
    est = ObjectEstimate(3, "cabinet", tuple(prims), part_ids=tuple(ids))
    rows = {r.part_id: r for r in evaluate_parts(cab, est)}
    assert rows[11].status is PartStatus.OK and rows[11].iou == 1.0 and rows[11].centre_error_m < 1e-12
    assert rows[12].iou < 0.5 and rows[12].centre_error_m == pytest.approx(0.05)
    assert rows[12].chamfer > 0.01 and rows[12].size_ratio == pytest.approx(1.0)
    assert rows[13].status is PartStatus.MISSING and np.isnan(rows[13].iou)
    assert evaluate_parts(cab, ObjectEstimate(3, "cabinet", tuple(prims))) == ()     # no part ids: no rows
