"""simcheck.demo: task choice, metrics.json, and the stage runner's honesty about what did not run."""

from __future__ import annotations

import json

import numpy as np
import pytest

from simcheck import demo
from simcheck.demo import DemoConfig, StageStatus, choose_tasks, run_demo


def _eye(x=0.0):
    T = np.eye(4)
    T[0, 3] = x
    return T.tolist()


def _object(oid, category, joints):
    """A truth/graph object with a body part and one part per ``(label, part_id, joint type)``."""
    parts = [{"id": oid * 10, "label": "body", "link": f"{category}{oid}_body{oid * 10}", "T_world_part": _eye()}]
    js = []
    for label, pid, jtype in joints:
        parts.append({"id": pid, "label": label, "link": f"{category}{oid}_{label}{pid}", "T_world_part": _eye()})
        js.append({"name": f"{category}{oid}_{label}{pid}_joint", "type": jtype, "parent_part_id": oid * 10,
                   "child_part_id": pid})
    return {"id": oid, "name": f"{category}{oid}", "category": category, "parts": parts, "joints": js}


TRUTH = {"objects": [
    _object(3, "cabinet", [("drawer", 31, "prismatic"), ("drawer", 32, "prismatic"), ("door", 33, "revolute"),
                           ("door", 34, "revolute"), ("drawer", 35, "prismatic"), ("handle", 36, "fixed")]),
    _object(4, "microwave", [("door", 41, "revolute")]),
    _object(5, "refrigerator", [("door", 51, "revolute"), ("door", 52, "revolute")]),
    _object(6, "table", [("leg", 61, "fixed")]),
]}


def test_choose_tasks_takes_cabinet_drawers_and_doors_round_robin():
    choice = choose_tasks(TRUTH, TRUTH, max_drawers=2, max_doors=3)
    assert choice.tasks == (("open-drawer", "cabinet3_drawer31_joint"), ("open-drawer", "cabinet3_drawer32_joint"),
                            ("open-door", "cabinet3_door33_joint"), ("open-door", "microwave4_door41_joint"),
                            ("open-door", "refrigerator5_door51_joint"))
    assert choice.reason == ""


def test_choose_tasks_leaves_out_joints_the_reconstruction_did_not_make_movable():
    graph = json.loads(json.dumps(TRUTH))
    for j in graph["objects"][1]["joints"]:
        j["type"] = "fixed"  # the microwave door was estimated rigid
    choice = choose_tasks(TRUTH, graph, max_drawers=1, max_doors=5)
    assert ("open-door", "microwave4_door41_joint") not in choice.tasks
    assert "microwave4_door41_joint (not movable in the reconstruction)" in choice.reason
    assert [t for t in choice.tasks if t[0] == "open-drawer"] == [("open-drawer", "cabinet3_drawer31_joint")]
    assert len([t for t in choice.tasks if t[0] == "open-door"]) == 4


def test_choose_tasks_never_picks_fixed_or_mislabelled_joints():
    truth = {"objects": [_object(7, "cabinet", [("shelf", 71, "prismatic"), ("handle", 72, "fixed")])]}
    assert choose_tasks(truth, truth, 5, 5).tasks == ()


def test_unavailable_stage_is_recorded_and_later_stages_are_skipped(tmp_path, monkeypatch):
    def unavailable(cfg, lay, state):
        raise demo.StageUnavailable("scenes.make_scene is not available yet (test)")

    stages = list(demo.STAGES)
    stages[0] = ("scene", unavailable, ())
    monkeypatch.setattr(demo, "STAGES", tuple(stages))
    result = run_demo(tmp_path / "out", DemoConfig())
    status = {s.name: s.status for s in result.stages}
    assert status["scene"] is StageStatus.UNAVAILABLE
    assert status["reconstruct"] is StageStatus.SKIPPED and status["certify"] is StageStatus.SKIPPED
    assert status["report"] is StageStatus.OK
    assert not result.complete
    log = json.loads((tmp_path / "out" / "demo.json").read_text())
    assert log["stages"][0]["message"] == "scenes.make_scene is not available yet (test)"
    html = (tmp_path / "out" / "report.html").read_text()
    assert "Not available: the certificate" in html and "Not available: the scan" in html
    assert not (tmp_path / "out" / "certificate.json").exists()


def test_failing_stage_is_reported_with_its_error_and_the_cli_exits_1(tmp_path, monkeypatch, capsys):
    def broken(cfg, lay, state):
        raise ValueError("truth.json: object cabinet3 part 12: bad size (test)")

    stages = list(demo.STAGES)
    stages[0] = ("scene", broken, ())
    monkeypatch.setattr(demo, "STAGES", tuple(stages))
    code = demo.main(["--out", str(tmp_path / "out"), "-q"])
    out = capsys.readouterr().out
    assert code == 1
    assert "stage scene: failed: ValueError: truth.json: object cabinet3 part 12: bad size (test)" in out
    assert f"report: {(tmp_path / 'out' / 'report.html').resolve()}" in out


def test_cli_rejects_bad_arguments(capsys):
    with pytest.raises(SystemExit) as exc:
        demo.main(["--seed", "zero"])
    assert exc.value.code == 2


# ------------------------------------------------------------------------------------------ metrics.json
TRUTH_JSON = __import__("pathlib").Path(__file__).with_name("test_simcheck_report_data") / "truth" / "truth.json"


def _metrics_of(estimates_from):
    from recon.metrics import MetricsConfig, evaluate_scene, joint_summary, read_truth

    truth = read_truth(TRUTH_JSON)
    sm = evaluate_scene(truth, estimates_from(truth), MetricsConfig(seed=0))
    return demo.metrics_doc(sm, joint_summary([c for o in sm.objects for c in o.joints])), truth


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


# ------------------------------------------------------------------------------------------ usable tasks
ZERO_RANGE_URDF = """<?xml version="1.0"?>
<robot name="s"><link name="world"/>
<link name="cabinet3_body11"><visual><geometry><box size="0.5 0.8 0.8"/></geometry></visual></link>
<joint name="cabinet3_body11_joint" type="fixed"><parent link="world"/><child link="cabinet3_body11"/></joint>
<link name="cabinet3_drawer12"><visual><geometry><box size="0.02 0.7 0.3"/></geometry></visual></link>
<joint name="cabinet3_drawer12_joint" type="prismatic"><parent link="cabinet3_body11"/><child link="cabinet3_drawer12"/>
<axis xyz="1 0 0"/><limit lower="0" upper="0" effort="100" velocity="1"/></joint>
<link name="cabinet3_door13"><visual><geometry><box size="0.02 0.7 0.3"/></geometry></visual></link>
<joint name="cabinet3_door13_joint" type="prismatic"><parent link="cabinet3_body11"/><child link="cabinet3_door13"/>
<axis xyz="1 0 0"/><limit lower="0" upper="0.3" effort="100" velocity="1"/></joint>
<link name="cabinet3_drawer14"><visual><geometry><box size="0.02 0.7 0.3"/></geometry></visual></link>
<joint name="cabinet3_drawer14_joint" type="prismatic"><parent link="cabinet3_body11"/><child link="cabinet3_drawer14"/>
<axis xyz="1 0 0"/><limit lower="0" upper="0.3" effort="100" velocity="1"/></joint>
</robot>
"""


def test_usable_tasks_rejects_a_joint_without_range_or_of_the_wrong_type_naming_it(tmp_path):
    urdf = tmp_path / "scene.urdf"
    urdf.write_text(ZERO_RANGE_URDF)
    choice = demo.usable_tasks(demo.TaskChoice((("open-drawer", "cabinet3_drawer12_joint"),
                                                ("open-door", "cabinet3_door13_joint"),
                                                ("open-drawer", "cabinet3_drawer14_joint")), ""), urdf)
    assert choice.tasks == (("open-drawer", "cabinet3_drawer14_joint"),)
    assert "cabinet3_drawer12_joint (rejected: " in choice.reason and "no opening range" in choice.reason
    assert "cabinet3_door13_joint (rejected: " in choice.reason and "prismatic" in choice.reason


def test_cli_rejects_an_unknown_scene_naming_the_built_in_ones(capsys):
    with pytest.raises(SystemExit) as exc:
        demo.main(["--scene", "nosuchroom", "--out", "unused"])
    assert exc.value.code == 2
    assert "unknown scene 'nosuchroom'; built-in scenes: kitchen" in capsys.readouterr().err


def test_demo_runs_as_a_module_in_a_subprocess(tmp_path):
    """End to end in a subprocess through the CLI's ``main``: a stage that fails (here a scan that cannot be made:
    zero views) is named on stdout with its error, the report is still written, and the exit code is 1."""
    import subprocess
    import sys

    code = ("import sys, scenes, simcheck.demo as d\n"
            "orig = scenes.make_scene\n"
            "scenes.make_scene = lambda *a, **k: orig(*a, **{**k, 'n_frames': 0})\n"
            "sys.exit(d.main(sys.argv[1:]))\n")
    res = subprocess.run([sys.executable, "-c", code, "--out", str(tmp_path / "o"), "-q"], capture_output=True,
                         text=True, timeout=120)
    assert res.returncode == 1, res.stderr[-3000:]
    assert f"report: {(tmp_path / 'o' / 'report.html').resolve()}" in res.stdout
    assert "stage scene: failed: ScanError: scan parameter n_frames=0 is out of range" in res.stdout
    assert "Traceback" not in res.stderr  # a project error explains itself
    assert (tmp_path / "o" / "report.html").stat().st_size > 1000
