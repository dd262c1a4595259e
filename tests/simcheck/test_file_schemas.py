"""Scenario and robot spec files are checked against their schemas (simcheck.file_schemas): one test per
malformed case, each error naming the file, the field and, for an unknown key, the closest valid key."""

from __future__ import annotations

import dataclasses

import pytest
import yaml

from simcheck.errors import RobotBindingError, ScenarioError
from simcheck.file_schemas import ROBOT_SPEC_SCHEMA, SCENARIO_SCHEMA, schema_problems
from simcheck.robot_spec_file import load_robot_spec
from simcheck.scenario import load_scenario

GOOD_SCENARIO = "scene: scene.urdf\nagainst: truth.urdf\nseed: 2\ntasks:\n  - open-drawer:d\n  - {kind: open-door, joint: h, amount: 1.2}\n"


@pytest.mark.parametrize("text, message", [
    ("scene: s.urdf\nagaints: truth.urdf\ntasks: [open-drawer:d]\n",
     r"scenario .*bad.yaml: unknown field 'againts' \(did you mean 'against'\?\)"),
    ("scene: s.urdf\ntask: [open-drawer:d]\n",
     r"bad.yaml: field 'tasks' is missing; unknown field 'task' \(did you mean 'tasks'\?\)"),
    ("scene: s.urdf\ntasks: [open-drawer:d]\nzzz: 1\n",
     r"bad.yaml: unknown field 'zzz' \(valid fields: against, robot, scene, seed, tasks\)"),
    ("scene: s.urdf\ntasks: [{kind: open-door, joint: h, amout: 1.2}]\n",
     r"bad.yaml: tasks\[0\]: unknown field 'amout' \(did you mean 'amount'\?\)"),
    ("scene: s.urdf\ntasks: [{kind: open-door, joint: h, amount: 0}]\n",
     r"bad.yaml: field 'tasks\[0\].amount' must be a non-zero opening, m \(drawer\) or rad \(door\); negative opens toward the lower limit, got 0"),
    ("scene: s.urdf\ntasks: [{kind: open-window, joint: h}]\n",
     r"field 'tasks\[0\].kind' must be 'open-drawer', 'open-door', 'close-drawer' or 'close-door', got 'open-window'"),
    ("scene: s.urdf\ntasks: []\n", r"bad.yaml: field 'tasks' must be a non-empty list, got \[\]"),
    ("scene: s.urdf\nseed: one\ntasks: [open-drawer:d]\n", r"field 'seed' must be an integer, got 'one'"),
    ("tasks: [open-drawer:d]\n", r"bad.yaml: field 'scene' is missing"),
    ("- open-drawer:d\n", r"bad.yaml: the document must be a mapping with 'scene' and 'tasks'"),
    ("scene: s.urdf\ntasks: [{joint: j}]\n", r"bad.yaml: tasks\[0\] needs 'kind' and 'joint'"),
])
def test_a_malformed_scenario_is_an_error_naming_file_and_field(text, message, tmp_path):
    (tmp_path / "bad.yaml").write_text(text)
    with pytest.raises(ScenarioError, match=message):
        load_scenario(tmp_path / "bad.yaml")


def test_a_well_formed_scenario_loads(tmp_path):
    (tmp_path / "ok.yaml").write_text(GOOD_SCENARIO)
    sc = load_scenario(tmp_path / "ok.yaml")
    assert sc.against == tmp_path / "truth.urdf" and sc.seed == 2
    assert [str(t) for t in sc.tasks] == ["open-drawer:d", "open-door:h"] and sc.tasks[1].amount == 1.2


def _robot_doc() -> dict:
    import planners

    spec = planners.default_robot()
    return {"urdf": str(spec.urdf), "base_joints": list(spec.base_joints), "arm_joints": list(spec.arm_joints),
            "finger_joints": list(spec.finger_joints), "tool_frame": spec.tool_frame, "base_link": spec.base_link,
            "gripper_links": list(spec.gripper_links), "home": list(spec.home)}


@pytest.mark.parametrize("change, message", [
    ({"tool_fame": "x"}, r"robot spec .*robot.yaml: unknown field 'tool_fame' \(did you mean 'tool_frame'\?\)"),
    ({"gripper": {"grip_forse": 70}}, r"robot.yaml: gripper: unknown field 'grip_forse' \(did you mean 'grip_force'\?\)"),
    ({"base_joints": ["x", "y"]}, r"robot.yaml: field 'base_joints' must be three names \(x, y, yaw\), got \['x', 'y'\]"),
    ({"home": "zero"}, r"robot.yaml: field 'home' must be one number per base and arm joint \(m, rad\), got 'zero'"),
    ({"tool_frame": None}, r"robot.yaml: field 'tool_frame' is missing"),
    ({"gripper": {"grip_force": 0}}, r"field 'gripper.grip_force' must be a force in newtons, got 0"),
    ({"joint_stiffness": [3000, 3000]}, r"robot.yaml: .*joint_stiffness needs one positive number"),
])
def test_a_malformed_robot_spec_is_an_error_naming_file_and_field(change, message, tmp_path):
    doc = {**_robot_doc(), **change}
    doc = {k: v for k, v in doc.items() if v is not None}
    (tmp_path / "robot.yaml").write_text(yaml.safe_dump(doc))
    with pytest.raises(RobotBindingError, match=message):
        load_robot_spec(str(tmp_path / "robot.yaml"))


def test_a_robot_spec_joint_stiffness_reaches_the_simulated_robot(tmp_path):
    from simcheck.robot_binding import sim_robot_from_spec

    values = [1000.0, 1000.0, 1000.0, 800.0, 800.0, 500.0, 500.0, 400.0][-len(_robot_doc()["arm_joints"]):]
    doc = {**_robot_doc(), "joint_stiffness": values}
    (tmp_path / "robot.yaml").write_text(yaml.safe_dump(doc))
    robot = sim_robot_from_spec(load_robot_spec(str(tmp_path / "robot.yaml")))
    assert robot.joint_stiffness == tuple(zip(doc["arm_joints"], values))
    assert ("panda_joint1", 3000.0) in sim_robot_from_spec(load_robot_spec(None)).joint_stiffness


def test_the_robot_spec_schema_has_exactly_the_robot_spec_fields():
    from planners.robot import GripperModel, RobotSpec

    props = ROBOT_SPEC_SCHEMA["properties"]
    assert set(props) == {f.name for f in dataclasses.fields(RobotSpec)}
    assert set(props["gripper"]["properties"]) == {f.name for f in dataclasses.fields(GripperModel)}
    required = {f.name for f in dataclasses.fields(RobotSpec)
                if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING}
    assert set(ROBOT_SPEC_SCHEMA["required"]) == required


def test_a_conforming_document_has_no_problems():
    assert schema_problems(yaml.safe_load(GOOD_SCENARIO), SCENARIO_SCHEMA) == []
    assert schema_problems(_robot_doc(), ROBOT_SPEC_SCHEMA) == []


def test_the_compliant_robot_is_the_default_robot_under_libfrankas_joint_impedance_example_gains(tmp_path):
    from planners.robot import PANDA_COMPLIANT_JOINT_STIFFNESS
    from simcheck.robot_binding import sim_robot_from_spec

    stiff, soft = load_robot_spec("default"), load_robot_spec("compliant")
    assert soft.joint_stiffness[1:] == PANDA_COMPLIANT_JOINT_STIFFNESS == (600.0, 600.0, 600.0, 600.0, 250.0, 150.0, 50.0)
    assert dataclasses.replace(soft, joint_stiffness=stiff.joint_stiffness) == stiff
    assert ("panda_joint6", 150.0) in sim_robot_from_spec(soft).joint_stiffness
    (tmp_path / "s.yaml").write_text("scene: s.urdf\nrobot: compliant\ntasks: [open-drawer:d]\n")
    assert load_scenario(tmp_path / "s.yaml").robot == "compliant"      # a name, not a file beside the scenario
