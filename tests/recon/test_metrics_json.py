"""recon.metrics.metrics_json: the metrics.json document of a reconstruction against its truth."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from recon.metrics import MetricsConfig, evaluate_scene, joint_summary, metrics_doc, read_truth

TRUTH_JSON = Path(__file__).parents[1] / "simcheck" / "test_simcheck_report_data" / "truth" / "truth.json"


def _metrics_of(estimates_from):
    truth = read_truth(TRUTH_JSON)
    sm = evaluate_scene(truth, estimates_from(truth), MetricsConfig(seed=0))
    return metrics_doc(sm, joint_summary([c for o in sm.objects for c in o.joints])), truth


def test_metrics_doc_of_a_perfect_estimate_is_perfect_and_strict_json():
    from recon.metrics import ObjectEstimate

    doc, truth = _metrics_of(lambda t: [ObjectEstimate(o.id, o.category, o.primitives, o.joints,
                                                       {e: 1.0 for e in o.contacts}) for o in t.objects])
    json.dumps(doc, allow_nan=False)  # JSON without NaN: a browser or jq can read it
    s = doc["summary"]
    assert doc["format"] == "partscene.metrics/1"
    assert s["chamfer"] == pytest.approx(0.0, abs=1e-4) and s["iou"] == pytest.approx(1.0, abs=1e-6)
    assert s["kinematic_map"] == pytest.approx(1.0) and s["type_accuracy"] == pytest.approx(1.0)
    assert s["missing_objects"] == 0
    assert [o["name"] for o in doc["objects"]] == [o.name for o in truth.objects]
    movable = [j.name for o in truth.objects for j in o.joints if str(getattr(j.type, "value", j.type)) != "fixed"]
    assert [j["name"] for j in doc["joints"]] == movable and movable
    assert all(j["axis_error_deg"] == pytest.approx(0.0, abs=1e-6) for j in doc["joints"])


def test_metrics_doc_writes_undefined_metrics_of_a_missing_object_as_null():
    doc, truth = _metrics_of(lambda t: [])
    json.dumps(doc, allow_nan=False)
    assert doc["summary"]["missing_objects"] == len(truth.objects)
    assert all(o["status"] == "missing" and o["chamfer"] is None for o in doc["objects"])
    assert all(j["est_type"] == "" and j["axis_error_deg"] is None for j in doc["joints"])
