"""simcheck.demo: task choice, the stage runner's honesty about what did not run, and its exit codes."""

from __future__ import annotations

import json

import pytest

from simcheck import demo
from simcheck.demo import DemoConfig, StageStatus, choose_tasks, run_demo


def _openings():
    from scenes.openings import Opening

    return (Opening("drawer", "cabinet3_drawer31_joint", "cabinet3", "cabinet"),
            Opening("drawer", "cabinet3_drawer32_joint", "cabinet3", "cabinet"),
            Opening("door", "cabinet3_door33_joint", "cabinet3", "cabinet"),
            Opening("door", "cabinet3_door34_joint", "cabinet3", "cabinet"),
            Opening("drawer", "cabinet3_drawer35_joint", "cabinet3", "cabinet"),
            Opening("door", "refrigerator4_door41_joint", "refrigerator4", "refrigerator"),
            Opening("drawer", "refrigerator4_drawer42_joint", "refrigerator4", "refrigerator"),
            Opening("door", "microwave5_door51_joint", "microwave5", "microwave"),
            Opening("door", "microwave5_door52_joint", "microwave5", "microwave"))


def test_choose_tasks_takes_cabinet_drawers_first_and_doors_round_robin():
    choice = choose_tasks(_openings(), max_drawers=2, max_doors=3)
    assert choice.tasks == (("open-drawer", "cabinet3_drawer31_joint"), ("open-drawer", "cabinet3_drawer32_joint"),
                            ("open-door", "cabinet3_door33_joint"), ("open-door", "microwave5_door51_joint"),
                            ("open-door", "refrigerator4_door41_joint"))
    assert choice.reason == ""


def test_choose_tasks_fills_up_from_other_objects_and_keeps_the_reason():
    choice = choose_tasks(_openings(), max_drawers=5, max_doors=5, reason="x (rejected: fixed)")
    assert [j for k, j in choice.tasks if k == "open-drawer"] == [
        "cabinet3_drawer31_joint", "cabinet3_drawer32_joint", "cabinet3_drawer35_joint", "refrigerator4_drawer42_joint"]
    assert [j for k, j in choice.tasks if k == "open-door"] == [
        "cabinet3_door33_joint", "microwave5_door51_joint", "refrigerator4_door41_joint", "cabinet3_door34_joint",
        "microwave5_door52_joint"]
    assert choice.reason == "x (rejected: fixed)"


def test_a_failing_stage_is_recorded_and_later_stages_are_skipped(tmp_path, monkeypatch):
    from scenes.errors import SceneSpecError

    def bad_input(cfg, lay, state):
        raise SceneSpecError("truth.json: object cabinet3 part 12: bad size (test)")

    stages = list(demo.STAGES)
    stages[0] = ("scene", bad_input, ())
    monkeypatch.setattr(demo, "STAGES", tuple(stages))
    result = run_demo(tmp_path / "out", DemoConfig())
    status = {s.name: s.status for s in result.stages}
    assert status["scene"] is StageStatus.FAILED
    assert status["reconstruct"] is StageStatus.SKIPPED and status["certify"] is StageStatus.SKIPPED
    assert status["report"] is StageStatus.OK
    assert not result.complete and result.certificate is None and result.exit_code == 2
    log = json.loads((tmp_path / "out" / "demo.json").read_text())
    assert log["stages"][0]["message"] == "SceneSpecError: truth.json: object cabinet3 part 12: bad size (test)"
    html = (tmp_path / "out" / "report.html").read_text()
    assert "Not available: the certificate" in html and "Not available: the scan" in html
    assert not (tmp_path / "out" / "certificate.json").exists()


def test_a_stage_failing_on_a_bug_is_reported_with_its_error_and_the_cli_exits_3(tmp_path, monkeypatch, capsys):
    def broken(cfg, lay, state):
        raise ValueError("truth.json: object cabinet3 part 12: bad size (test)")

    stages = list(demo.STAGES)
    stages[0] = ("scene", broken, ())
    monkeypatch.setattr(demo, "STAGES", tuple(stages))
    code = demo.main(["--out", str(tmp_path / "out"), "-q"])
    out = capsys.readouterr().out
    assert code == 3          # not a partscene error: an internal error
    assert "stage scene: failed: ValueError: truth.json: object cabinet3 part 12: bad size (test)" in out
    assert f"report: {(tmp_path / 'out' / 'report.html').resolve()}" in out


def test_cli_rejects_bad_arguments(capsys):
    with pytest.raises(SystemExit) as exc:
        demo.main(["--seed", "zero"])
    assert exc.value.code == 2


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


def test_usable_openings_rejects_a_joint_without_range_of_the_wrong_type_or_missing_naming_it(tmp_path):
    from scenes.openings import Opening

    urdf = tmp_path / "scene.urdf"
    urdf.write_text(ZERO_RANGE_URDF)
    kept, reason = demo.usable_openings((Opening("drawer", "cabinet3_drawer12_joint", "cabinet3", "cabinet"),
                                         Opening("door", "cabinet3_door13_joint", "cabinet3", "cabinet"),
                                         Opening("drawer", "cabinet3_drawer14_joint", "cabinet3", "cabinet"),
                                         Opening("drawer", "cabinet3_drawer15_joint", "cabinet3", "cabinet")), urdf)
    assert [o.joint for o in kept] == ["cabinet3_drawer14_joint"]
    assert "cabinet3_drawer12_joint (rejected: " in reason and "no opening range" in reason
    assert "cabinet3_door13_joint (rejected: " in reason and "prismatic" in reason
    assert "cabinet3_drawer15_joint (rejected: " in reason and "does not exist" in reason


def test_cli_rejects_an_unknown_scene_naming_the_built_in_ones(capsys):
    with pytest.raises(SystemExit) as exc:
        demo.main(["--scene", "nosuchroom", "--out", "unused"])
    assert exc.value.code == 2
    assert "unknown scene 'nosuchroom'; built-in scenes: kitchen" in capsys.readouterr().err


def test_demo_runs_as_a_module_in_a_subprocess(tmp_path):
    """End to end in a subprocess through the CLI's ``main``: a stage that fails (here a scan that cannot be made:
    zero views) is named on stdout with its error, the report is still written, and the exit code is 2 (a
    partscene error: unusable input)."""
    import subprocess
    import sys

    code = ("import sys, scenes, simcheck.demo as d\n"
            "orig = scenes.make_scene\n"
            "scenes.make_scene = lambda *a, **k: orig(*a, **{**k, 'n_frames': 0})\n"
            "sys.exit(d.main(sys.argv[1:]))\n")
    res = subprocess.run([sys.executable, "-c", code, "--out", str(tmp_path / "o"), "-q"], capture_output=True,
                         text=True, timeout=120)
    assert res.returncode == 2, res.stderr[-3000:]
    assert f"report: {(tmp_path / 'o' / 'report.html').resolve()}" in res.stdout
    assert "stage scene: failed: ScanError: scan parameter n_frames=0 is out of range" in res.stdout
    assert "Traceback" not in res.stderr  # a project error explains itself
    assert (tmp_path / "o" / "report.html").stat().st_size > 1000


def test_the_joints_the_demo_did_not_certify_are_named_with_why(tmp_path, monkeypatch):
    import importlib

    from scenes.openings import Opening

    urdf = tmp_path / "scene.urdf"
    urdf.write_text(ZERO_RANGE_URDF)
    truth = (Opening("door", "cabinet3_door13_joint", "cabinet3", "cabinet"),
             Opening("drawer", "cabinet3_drawer14_joint", "cabinet3", "cabinet"),
             Opening("drawer", "cabinet3_drawer16_joint", "cabinet3", "cabinet"))
    monkeypatch.setattr(importlib.import_module("scenes.openings"), "openings", lambda scene: truth)
    choice = demo.TaskChoice((("open-drawer", "cabinet3_drawer14_joint"),), "")
    untested = demo.untested_joints(None, urdf, choice, DemoConfig(max_drawers=1))
    assert untested["cabinet3_door13_joint"].startswith("rejected: ") and "prismatic" in untested["cabinet3_door13_joint"]
    assert "does not exist" in untested["cabinet3_drawer16_joint"]
    assert untested["cabinet3_drawer12_joint"] == ("movable in the reconstruction, but no drawer or door of the truth "
                                                   "has this name")
    assert "cabinet3_drawer14_joint" not in untested
