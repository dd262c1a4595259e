"""The ``simcheck`` CLI: exit codes 0 / 1 / 2 and messages that say why (some runs in a subprocess)."""

import hashlib
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from simcheck.cli import main
from simcheck.errors import ScenarioError
from simcheck.rollout import Rollout
from simcheck.scenario import load_scenario
from simcheck.scene_joints import read_scene_joints

import simcheck.estimate_faults as wrong
from simcheck_fixture_plans import DATA

CAB = DATA / "panda_cabinet.urdf"
DRAWER, DOOR, HANDLE = "cabinet1_drawer12_joint", "cabinet1_door14_joint", "cabinet1_handle13_joint"


def _cli(*args, cwd):
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    return subprocess.run([sys.executable, "-m", "simcheck", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, env=env, timeout=120)


@pytest.mark.parametrize("task, message", [
    (f"open-drawer:nope_joint", "panda_cabinet.urdf: joint 'nope_joint' does not exist"),
    (f"open-drawer:{HANDLE}", f"panda_cabinet.urdf: joint '{HANDLE}' is fixed"),
    (f"open-drawer:{DOOR}", "is revolute, but a drawer needs a prismatic joint"),
])
def test_bad_task_exits_2_with_a_message_in_a_subprocess(task, message, tmp_path):
    p = _cli("certify", CAB, "--task", task, "--out", tmp_path / "out", cwd=tmp_path)
    assert p.returncode == 2, p.stderr
    import re
    assert re.search(message, p.stderr), p.stderr
    assert not (tmp_path / "out" / "certificate.json").exists()


def test_broken_urdf_exits_2_in_a_subprocess(tmp_path):
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='x'><link name='a'>")
    p = _cli("certify", broken, "--task", "open-drawer:j", cwd=tmp_path)
    assert p.returncode == 2 and "broken.urdf: not valid XML" in p.stderr, p.stderr


@pytest.mark.parametrize("argv, message", [
    (["certify", "missing.urdf", "--task", f"open-drawer:{DRAWER}"], "missing.urdf does not exist"),
    (["certify", str(CAB)], "no task given"),
    (["certify", str(CAB), "--task", f"shut-drawer:{DRAWER}"], "kind must be one of"),
    (["certify", str(CAB), "--task", f"open-drawer:{DRAWER}", "--amount", "0.1", "--amount", "0.2"], "2 amounts for 1 tasks"),
    (["certify", str(CAB), "--task", f"open-drawer:{DRAWER}", "--robot", "nope.yaml"], "robot spec nope.yaml does not exist"),
    (["certify", str(CAB), "--task", f"open-drawer:{DRAWER}", "--gui"], "needs a display"),
    (["certify", str(CAB), "--task", f"open-drawer:{DRAWER}", "--against", "gone.urdf"], "gone.urdf does not exist"),
    (["run", "nothing.yaml"], "scenario nothing.yaml does not exist"),
])
def test_unusable_input_exits_2_and_says_why(argv, message, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    assert main(argv + ["--out", str(tmp_path / "o")]) == 2
    assert message in capsys.readouterr().err


def _out_of_reach(tmp_path):
    """The fixture cabinet lifted 2.6 m: no stand pose reaches its drawer (planning fails fast, nothing runs)."""
    high = tmp_path / "high.urdf"
    high.write_text(CAB.read_text().replace('<origin xyz="1.5 0 0" rpy="0 0 3.141593"/>',
                                            '<origin xyz="1.5 0 2.6" rpy="0 0 3.141593"/>'))
    return high


def test_unreachable_object_exits_1_and_says_unreachable(tmp_path, capsys):
    high = _out_of_reach(tmp_path)
    assert main(["certify", str(high), "--task", f"open-drawer:{DRAWER}", "--out", str(tmp_path / "o"), "--no-images"]) == 1
    out = capsys.readouterr().out
    assert "unreachable" in out and DRAWER in out
    doc = json.loads((tmp_path / "o" / "certificate.json").read_text())
    assert doc["tasks"][0]["status"] == "unreachable" and doc["tasks"][0]["plan_status"] == "NO_STAND_POSE"
    assert doc["robot_joint_stiffness"]["panda_joint6"] == 2000.0 and doc["robot_joint_stiffness"]["torso_lift"] is None


def test_the_certificate_records_the_arm_stiffness_it_simulated(tmp_path):
    """--robot default and compliant share one URDF: the certificate tells them apart by the joint impedance."""
    high = _out_of_reach(tmp_path)
    assert main(["certify", str(high), "--task", f"open-drawer:{DRAWER}", "--out", str(tmp_path / "o"), "--no-images",
                 "--robot", "compliant"]) == 1
    doc = json.loads((tmp_path / "o" / "certificate.json").read_text(), parse_constant=pytest.fail)
    assert doc["robot_joint_stiffness"]["panda_joint6"] == 150.0


def test_certified_drawer_exits_0_and_writes_the_certificate(tmp_path, capsys):
    assert main(["certify", str(CAB), "--task", f"open-drawer:{DRAWER}", "--out", str(tmp_path), "--seed", "3"]) == 0
    doc = json.loads((tmp_path / "certificate.json").read_text())
    assert doc["ok"] and doc["seeds"] == {"seed": 3} and doc["tasks"][0]["status"] == "certified"
    assert (tmp_path / doc["tasks"][0]["rollout"]).is_file()
    assert all((tmp_path / p).is_file() for p in doc["tasks"][0]["images"])
    assert "certified" in capsys.readouterr().out
    assert doc["files"]["scene"]["sha256"] == hashlib.sha256(CAB.read_bytes()).hexdigest()
    # another run into the same folder: refused by name, unless --overwrite; then no stale image is left
    argv = ["certify", str(CAB), "--task", f"open-drawer:{DRAWER}", "--out", str(tmp_path), "--seed", "3", "--no-images"]
    assert main(argv) == 2
    assert "it holds a run with images = True (this run: False)" in capsys.readouterr().err
    assert main(argv + ["--overwrite"]) == 0
    assert not (tmp_path / "images").exists() and json.loads((tmp_path / "certificate.json").read_text())["ok"]


def test_wrong_estimate_against_the_truth_exits_1(tmp_path):
    est = wrong.widen_limits(CAB, DRAWER, 1.5, tmp_path / "wide.urdf")
    before = CAB.read_bytes()
    assert main(["certify", str(est), "--task", f"open-drawer:{DRAWER}", "--against", str(CAB),
                 "--out", str(tmp_path / "o"), "--no-images"]) == 1
    assert CAB.read_bytes() == before                      # inputs are never modified
    doc = json.loads((tmp_path / "o" / "certificate.json").read_text())
    assert doc["against"] == str(CAB) and doc["tasks"][0]["status"] == "failed"


def test_scenario_runs_tasks_in_sequence_with_the_world_state_carried(tmp_path):
    (tmp_path / "scene.urdf").write_bytes(CAB.read_bytes())
    sc = tmp_path / "scenario.yaml"
    sc.write_text(f"scene: scene.urdf\nseed: 1\ntasks:\n  - {{kind: open-door, joint: {DOOR}, amount: 1.2}}\n"
                  f"  - open-drawer:{DRAWER}\n")
    code = main(["run", str(sc), "--out", str(tmp_path / "o"), "--no-images"])
    doc = json.loads((tmp_path / "o" / "certificate.json").read_text())
    assert code == 0, [t["reason"] for t in doc["tasks"]]
    assert doc["files"]["scenario"]["sha256"] == hashlib.sha256(sc.read_bytes()).hexdigest()
    first, second = doc["tasks"]
    assert first["start_state"][DOOR] == pytest.approx(0.0, abs=1e-3)
    # the door opened by the first task is still open when the second starts
    assert second["start_state"][DOOR] == pytest.approx(1.2, abs=0.05)
    assert first["amount"] == pytest.approx(1.2) and doc["seeds"] == {"seed": 1}
    # the second task starts exactly where the first ended: the door's value and the robot's configuration
    end = Rollout.load(tmp_path / "o" / first["rollout"])
    assert second["start_state"][DOOR] == pytest.approx(end.object_q[-1], abs=1e-9)
    assert list(second["start_robot_q"]) == list(end.robot_joint_names)
    np.testing.assert_allclose(list(second["start_robot_q"].values()), end.robot_q[-1], atol=1e-9)


def test_scenario_errors_name_the_file_and_field(tmp_path):
    sc = tmp_path / "bad.yaml"
    sc.write_text("scene: x.urdf\n")
    with pytest.raises(ScenarioError, match=r"bad.yaml: field 'tasks' is missing"):
        load_scenario(sc)
    sc.write_text("scene: x.urdf\ntasks: [{joint: j}]\n")
    with pytest.raises(ScenarioError, match=r"bad.yaml: tasks\[0\] needs 'kind' and 'joint'"):
        load_scenario(sc)
    sc.write_text("tasks: [open-drawer:j]\n")
    with pytest.raises(ScenarioError, match="field 'scene' is missing"):
        load_scenario(sc)


def test_scene_joints_in_world_frame():
    joints = read_scene_joints(CAB)
    assert joints[DOOR].axis_world == pytest.approx([0, 0, -1]) and joints[DOOR].origin_world == pytest.approx([1.25, 0.38, 0])


def test_a_drawer_without_any_handle_is_a_verdict_naming_what_blocks_its_edges(tmp_path):
    import xml.etree.ElementTree as ET
    tree = ET.parse(CAB)
    root = tree.getroot()
    root.remove(next(l for l in root.findall("link") if l.get("name") == "cabinet1_handle13"))
    root.remove(next(j for j in root.findall("joint") if j.get("name") == HANDLE))
    tree.write(tmp_path / "no_handle.urdf")
    assert main(["certify", str(tmp_path / "no_handle.urdf"), "--task", f"open-drawer:{DRAWER}",
                 "--out", str(tmp_path / "o"), "--no-images"]) == 1
    t = json.loads((tmp_path / "o" / "certificate.json").read_text())["tasks"][0]
    # no handle: the panel's edges are pinched, but the closed drawer's front has the carcass behind every edge
    assert t["status"] == "unreachable" and "front panel can be pinched" in t["reason"], t["reason"]
    assert "scene::cabinet1_body10" in t["reason"]


def test_robot_spec_file_round_trips_the_default_robot(tmp_path):
    import yaml

    import planners
    from simcheck.robot_binding import sim_robot_from_spec
    from simcheck.robot_spec_file import load_robot_spec

    spec = planners.default_robot()
    doc = {"urdf": str(spec.urdf), "base_joints": list(spec.base_joints), "arm_joints": list(spec.arm_joints),
           "finger_joints": list(spec.finger_joints), "tool_frame": spec.tool_frame, "base_link": spec.base_link,
           "gripper_links": list(spec.gripper_links), "home": list(spec.home),
           "ignore_pairs": [list(p) for p in spec.ignore_pairs]}
    (tmp_path / "robot.yaml").write_text(yaml.safe_dump(doc))
    loaded = load_robot_spec(str(tmp_path / "robot.yaml"))
    assert loaded.joint_names == spec.joint_names and loaded.tool_frame == spec.tool_frame
    sim = sim_robot_from_spec(loaded)
    assert sim.finger_links == ("panda_leftfinger", "panda_rightfinger") and sim.base_links == ("base_link",)
    assert sim.finger_open == (0.04, 0.04) and sim.finger_closed == (0.0, 0.0)
    (tmp_path / "bad.yaml").write_text("urdf: robot.urdf\nbase_joints: [a]\n")
    from simcheck.errors import RobotBindingError
    with pytest.raises(RobotBindingError, match="bad.yaml"):
        load_robot_spec(str(tmp_path / "bad.yaml"))


def test_all_movable_certifies_every_drawer_and_door_and_lists_joints_without_a_range(tmp_path, capsys, caplog):
    scene = tmp_path / "scene.urdf"
    scene.write_text(CAB.read_text().replace('lower="0.0" upper="1.9"', 'lower="0.0" upper="0.0"'))
    code = main(["certify", str(scene), "--all-movable", "--json", "--no-images", "--out", str(tmp_path / "o")])
    out = capsys.readouterr().out
    summary = json.loads(out)                                # stdout is the JSON summary alone
    assert code == summary["exit_code"] == 0 and summary["ok"]
    assert [(t["kind"], t["joint"], t["status"]) for t in summary["tasks"]] == [("open-drawer", DRAWER, "certified")]
    assert list(summary["untested"]) == [DOOR] and "no opening range" in summary["untested"][DOOR]
    assert any(DOOR in r.getMessage() and "not tested" in r.getMessage() for r in caplog.records)
    doc = json.loads((tmp_path / "o" / "certificate.json").read_text())
    assert doc["untested"] == summary["untested"] and summary["certificate"] == str(tmp_path / "o" / "certificate.json")


def test_all_movable_tasks_are_one_per_prismatic_and_revolute_joint():
    from planners.task import movable_joint_tasks

    tasks, untested = movable_joint_tasks(read_scene_joints(CAB), CAB)
    assert [str(t) for t in tasks] == [f"open-drawer:{DRAWER}", f"open-door:{DOOR}"] and untested == {}


@pytest.mark.parametrize("argv, message", [
    (["--all-movable", "--task", f"open-drawer:{DRAWER}"], "give --task or --all-movable, not both"),
])
def test_all_movable_misuse_exits_2(argv, message, tmp_path, capsys):
    assert main(["certify", str(CAB), *argv, "--out", str(tmp_path)]) == 2
    assert message in capsys.readouterr().err


def test_all_movable_without_any_drawer_or_door_exits_2(tmp_path, capsys):
    scene = tmp_path / "scene.urdf"
    scene.write_text(CAB.read_text().replace('upper="1.9"', 'upper="0.0"').replace('upper="0.35"', 'upper="0.0"'))
    assert main(["certify", str(scene), "--all-movable", "--out", str(tmp_path / "o")]) == 2
    assert "no drawer or door with an opening range" in capsys.readouterr().err


def test_the_summary_lists_untested_joints_and_round_trips(tmp_path):
    from simcheck.certificate import Certificate

    cert = Certificate(tasks=(), scene="s.urdf", against=None, robot="r.urdf", criteria={}, seeds={"seed": 0},
                       versions={}, untested={"j": "s.urdf: revolute joint has no opening range"})
    assert cert.summary() == "untested     j  s.urdf: revolute joint has no opening range"
    assert Certificate.load(cert.write(tmp_path)).untested == cert.untested
    assert json.loads(json.dumps(cert.summary_dict()))["untested"] == cert.untested
