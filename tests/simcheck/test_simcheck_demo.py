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
