"""``--spreads FILE``: the printed defaults read back as the defaults, a partial file overrides only its keys,
and every bad value exits 2 naming the file and the field."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from simcheck.errors import SimcheckInputError
from simcheck.robust_spreads import DEFAULT_SPREADS, joint_spreads_for
from simcheck.spreads_file import load_spreads, spreads_yaml

DATA = Path(__file__).parent / "data"


def test_the_printed_defaults_read_back_as_the_defaults(tmp_path):
    f = tmp_path / "spreads.yaml"
    f.write_text(spreads_yaml())
    got = load_spreads(f)
    assert (got.physics, got.robot, got.joint_defaults) == (DEFAULT_SPREADS.physics, DEFAULT_SPREADS.robot,
                                                            DEFAULT_SPREADS.joint_defaults)
    assert got.source == str(f) and load_spreads(None) is DEFAULT_SPREADS


def test_a_partial_file_overrides_only_its_keys(tmp_path):
    f = tmp_path / "s.yaml"
    f.write_text("robot: {base_xy_m: 0.005, guarded_approach: false}\njoint_defaults: {revolute: {origin_m: 0.02}}\n")
    got = load_spreads(f)
    assert got.robot.base_xy_m == 0.005 and got.robot.guarded_approach is False
    assert got.robot.base_yaw_deg == DEFAULT_SPREADS.robot.base_yaw_deg and got.physics == DEFAULT_SPREADS.physics
    assert got.joint_defaults["revolute"].origin_m == 0.02
    assert got.joint_defaults["revolute"].axis_deg == DEFAULT_SPREADS.joint_defaults["revolute"].axis_deg
    # the task joint's defaults without graph.json come from the file
    spreads, centre = joint_spreads_for(DATA / "cabinet.urdf", "cabinet1_door4_joint", "revolute", got.joint_defaults)
    assert centre is None and spreads.origin_m == 0.02


@pytest.mark.parametrize("text, field", [
    ("robot: {base_xy_m: .nan}", "robot.base_xy_m"),
    ("robot: {handle_m: -0.001}", "robot.handle_m"),
    ("physics: {joint_friction: [2.0, 1.0]}", "physics.joint_friction"),
    ("physics: {mass_scale: [0.0, 1.0]}", "physics.mass_scale"),
    ("physics: {joint_damping: [0.5]}", "physics.joint_damping"),
    ("robot: {base_xy: 0.01}", "base_xy"),
    ("robot: {base_yaw_deg: fast}", "robot.base_yaw_deg"),
    ("joint_defaults: {revolute: {upper: .inf}}", "joint_defaults.revolute.upper"),
])
def test_bad_spreads_name_the_field(tmp_path, text, field):
    f = tmp_path / "s.yaml"
    f.write_text(text + "\n")
    with pytest.raises(SimcheckInputError, match=f"spreads {f}") as e:
        load_spreads(f)
    assert field in str(e.value)


def test_a_negative_graph_uncertainty_names_the_field(tmp_path):
    (tmp_path / "scene.urdf").write_text((DATA / "cabinet.urdf").read_text())
    joint = {"name": "J", "type": "revolute", "axis": [0, 0, 1], "origin": [0, 0, 0], "upper": 1.5,
             "uncertainty": {"axis_deg": 0.5, "origin_m": -0.01, "upper": 0.1, "samples": 10, "method": "bootstrap"}}
    (tmp_path / "graph.json").write_text(json.dumps({"objects": [{"joints": [joint]}]}))
    with pytest.raises(SimcheckInputError, match="uncertainty.origin_m is -0.01"):
        joint_spreads_for(tmp_path / "scene.urdf", "J", "revolute")


def test_cli_prints_the_defaults_and_refuses_a_bad_file(tmp_path):
    r = subprocess.run([sys.executable, "-m", "simcheck", "spreads"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "base_xy_m: 0.014" in r.stdout and "guarded_approach: true" in r.stdout
    bad = tmp_path / "bad.yaml"
    bad.write_text("physics: {handle_friction: [-1, 1]}\n")
    r = subprocess.run([sys.executable, "-m", "simcheck", "certify", str(DATA / "cabinet.urdf"), "--task",
                        "open-door:cabinet1_door4_joint", "--out", str(tmp_path / "out"), "--robust", "3",
                        "--spreads", str(bad)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    assert "physics.handle_friction" in r.stderr and str(bad) in r.stderr
    r = subprocess.run([sys.executable, "-m", "simcheck", "certify", str(DATA / "cabinet.urdf"), "--task",
                        "open-door:cabinet1_door4_joint", "--out", str(tmp_path / "out2"), "--spreads", str(bad)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and "give --robust N too" in r.stderr
