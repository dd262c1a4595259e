"""End to end on a real ``scenes`` kitchen: its truth.json is read by the metrics, and the object-level
baseline runs on its scan.ply + labels.json and is scored by the same metrics (seeded, headless)."""

from __future__ import annotations

import numpy as np
import pytest

from recon.baseline import BaselineStatus, object_level_from_files
from recon.metrics import ObjectEstimate, evaluate_scene, joint_summary, read_truth

#: A lighter scan than the clean preset's (fewer, smaller frames): same scene, same truth, faster test.
LIGHT_SCAN = dict(n_frames=16, width=200, height=150)


@pytest.fixture(scope="module")
def kitchen(tmp_path_factory):
    from scenes import make_scene

    out = tmp_path_factory.mktemp("kitchen")
    make_scene("kitchen", seed=0, preset="clean", out=out, previews=False, **LIGHT_SCAN)
    return out


def test_scenes_truth_json_is_read_and_scores_itself_perfectly(kitchen):
    truth = read_truth(kitchen / "truth.json")
    assert len(truth.objects) >= 5
    assert {"cabinet", "microwave", "refrigerator", "table", "chair"} <= {o.category for o in truth.objects}
    perfect = [ObjectEstimate(o.id, o.category, o.primitives, o.joints, {e: 1.0 for e in o.contacts})
               for o in truth.objects]
    m = evaluate_scene(truth, perfect)
    assert [o.iou for o in m.objects] == [1.0] * len(truth.objects)
    assert m.chamfer < 1e-3
    assert all(o.ap == 1.0 for o in m.objects if np.isfinite(o.ap))
    assert joint_summary(j for o in m.objects for j in o.joints).type_accuracy == 1.0


def test_baseline_replaces_every_kitchen_object_facing_the_right_way(kitchen):
    truth = read_truth(kitchen / "truth.json")
    result = object_level_from_files(kitchen / "scan.ply", kitchen / "labels.json", seed=0)
    assert [o.status for o in result.objects] == [BaselineStatus.OK] * len(result.objects)
    for row in result.objects:
        T = truth.object(row.object_id).T_world_object
        true_yaw = np.arctan2(T[1, 0], T[0, 0])
        if row.category in ("cabinet", "microwave", "refrigerator"):      # articulated: the front matters
            err = (row.box.yaw - true_yaw + np.pi) % (2 * np.pi) - np.pi
            assert abs(err) < np.radians(3.0), (row.object_id, row.category, np.degrees(err))
    m = evaluate_scene(truth, result.estimates)
    assert m.missing == 0 and m.iou > 0.7 and m.chamfer < 0.05
    s = joint_summary(j for o in m.objects for j in o.joints)
    assert s.median_axis_error_deg < 5.0
