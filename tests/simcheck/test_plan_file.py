"""simcheck/plan_file.py: partscene.plan/1 documents read, checked (every malformed field named, exit 2 from the
CLI), written and read back; the numpy adapter; binding a plan to the robot's joints."""

import json
import math

import numpy as np
import pytest

from planners.robot import default_robot
from planners.task import Expectation
from simcheck.cli import main
from simcheck.errors import PlanFileError
from simcheck.given_plan import bind_plan
from simcheck.plan_file import PLAN_FORMAT, join_plans, plan_from_arrays, plan_from_dict, plan_to_dict, read_plan, write_plan

NAMES = ["base_x", "base_y", "base_yaw", "torso_lift"] + [f"panda_joint{i}" for i in range(1, 8)]
HOME = [1.2, 0.0, math.pi, 0.0, 0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]


def _doc():
    q = np.array([HOME, HOME, HOME], dtype=float)
    q[:, 0] -= [0.0, 0.01, 0.02]
    return {"format": PLAN_FORMAT, "robot": "default", "joint_names": list(NAMES),
            "segments": [{"name": "approach", "t": [0.0, 0.1, 0.2], "waypoints": q.tolist(), "gripper": "open"},
                         {"name": "open", "dt": 0.05, "waypoints": q[::-1].tolist(), "gripper": "hold",
                          "expect": {"joint": "cabinet1_drawer2_joint", "from": 0.0, "to": 0.3}}]}


def test_a_document_round_trips_through_a_file(tmp_path):
    plan = plan_from_dict(_doc(), "doc")
    assert [s.command for s in plan.segments] == ["open", "hold"]
    assert np.allclose(plan.segments[1].t, [0.0, 0.05, 0.1])
    assert plan.expectations == ((1, Expectation("cabinet1_drawer2_joint", 0.0, 0.3)),)
    path = write_plan(plan, tmp_path / "p.plan.json")
    assert json.loads(path.read_text())["format"] == PLAN_FORMAT
    assert read_plan(path).isclose(plan, atol=0.0)


def test_gripper_state_while_moving_follows_the_commands():
    doc = _doc()
    doc["segments"][0]["gripper"] = "close"           # closes at the end of the approach
    plan = plan_from_dict(doc, "doc")
    assert [s.gripper for s in plan.segments] == ["open", "closed"]


@pytest.mark.parametrize("edit, field", [
    (lambda d: d.update(format="partscene.plan/2"), "field 'format'"),
    (lambda d: d["segments"][0]["waypoints"][1].__setitem__(4, float("nan")), "'segments[0].waypoints[1][4]' (panda_joint1)"),
    (lambda d: d["segments"][1]["waypoints"][2].pop(), "'segments[1].waypoints[2]' has 10 values"),
    (lambda d: d["segments"][0].update(t=[0.0, 0.2, 0.1]), "'segments[0].t[2]'"),
    (lambda d: d["segments"][0].update(t=[0.1, 0.2, 0.3]), "'segments[0].t[0]' must be 0"),
    (lambda d: d["segments"][0].update(dt=0.1), "'segments[0]' ('approach') needs exactly one of 't'"),
    (lambda d: d["segments"][1].pop("dt"), "'segments[1]' ('open') needs exactly one of 't'"),
    (lambda d: d["segments"][1].update(dt=-0.1), "'segments[1].dt'"),
    (lambda d: d["segments"][1].update(gripper="grab"), "'segments[1].gripper'"),
    (lambda d: d["segments"][1].update(name="approach"), "two segments are called 'approach'"),
    (lambda d: d["segments"][1]["expect"].update(to=0.0), "'segments[1].expect'"),
    (lambda d: d["segments"][1].update(expct={}), "unknown field 'expct' (did you mean 'expect'?)"),
    (lambda d: d.pop("joint_names"), "'joint_names' is missing"),
])
def test_a_malformed_document_names_the_field(edit, field):
    doc = _doc()
    edit(doc)
    with pytest.raises(PlanFileError, match="plan doc: .*" + __import__("re").escape(field)):
        plan_from_dict(doc, "doc")


def test_binding_names_a_joint_the_robot_lacks_or_the_plan_lacks():
    robot = default_robot()
    doc = _doc()
    doc["joint_names"][4] = "panda_joint22"
    with pytest.raises(PlanFileError, match="'joint_names': 'panda_joint22' is not a joint of robot"):
        bind_plan(plan_from_dict(doc, "doc"), robot, {}, "scene.urdf")
    doc = _doc()
    del doc["joint_names"][6]
    for s in doc["segments"]:
        for row in s["waypoints"]:
            del row[6]
    with pytest.raises(PlanFileError, match="'joint_names' lacks robot joint 'panda_joint3'"):
        bind_plan(plan_from_dict(doc, "doc"), robot, {}, "scene.urdf")
    doc = _doc()
    doc["segments"][0]["expect"] = {"joint": "cabinet1_door4_joint", "from": 0.0, "to": 1.0}
    with pytest.raises(PlanFileError, match=r"no segment between segments\[0\] \('approach'\) and segments\[1\] "
                                            r"\('open'\), which both have an 'expect', opens the gripper"):
        bind_plan(plan_from_dict(doc, "doc"), robot, {}, "scene.urdf")
    doc["segments"][0]["expect"]["joint"] = "cabinet1_drawer2_joint"      # one joint moved in two parts: one task,
    with pytest.raises(PlanFileError, match=r"no segment between segments\[0\] .* opens the gripper"):  # let go between
        bind_plan(plan_from_dict(doc, "doc"), robot, {}, "scene.urdf")
    a, b = doc["segments"]                                # drawer, door, drawer again: two tasks of one joint
    doc["segments"] = [dict(a, gripper="hold", expect={"joint": "cabinet1_drawer2_joint", "from": 0.0, "to": 0.3}),
                       dict(b, gripper="open", expect={"joint": "cabinet1_door4_joint", "from": 0.0, "to": 1.0}),
                       dict(b, name="again", expect={"joint": "cabinet1_drawer2_joint", "from": 0.3, "to": 0.4})]
    with pytest.raises(PlanFileError, match=r"segments\[0\], segments\[2\] expect scene joint "
                                            r"'cabinet1_drawer2_joint' with another joint's move between them"):
        bind_plan(plan_from_dict(doc, "doc"), robot, {}, "scene.urdf")
    with pytest.raises(PlanFileError, match=r"'segments\[1\].expect.joint': scene joint 'cabinet1_drawer2_joint' of "
                                            r"scene.urdf does not exist"):
        bind_plan(plan_from_dict(_doc(), "doc"), robot, {}, "scene.urdf")


@pytest.mark.parametrize("edit, field", [
    (lambda d: d["segments"][0]["waypoints"][0].__setitem__(0, float("nan")), "segments[0].waypoints[0][0]"),
    (lambda d: d["joint_names"].pop(), "segments[0].waypoints[0]' has 11 values, 'joint_names' has 10"),
    (lambda d: d.update(format="partscene.plan/7"), "field 'format'"),
    (lambda d: d["joint_names"].__setitem__(9, "wrist"), "'wrist' is not a joint of robot"),
    (lambda d: [d["joint_names"].pop(6)] + [row.pop(6) for s in d["segments"] for row in s["waypoints"]],
     "'joint_names' lacks robot joint 'panda_joint3'"),
])
def test_cli_exits_2_naming_the_field(tmp_path, capsys, edit, field):
    doc = _doc()
    edit(doc)
    path = tmp_path / "bad.plan.json"
    path.write_text(json.dumps(doc))           # NaN written as the JSON extension NaN, as numpy users produce it
    code = main(["certify-plan", str(tmp_path / "missing.urdf"), str(path), "--out", str(tmp_path / "out"), "-q"])
    assert code == 2
    err = capsys.readouterr().err
    assert "bad.plan.json" in err and field in err


def test_arrays_adapter_and_join():
    q = np.tile(np.array(HOME), (4, 1))
    a = plan_from_arrays(q, NAMES, t=[0.0, 0.1, 0.2, 0.3], gripper="open", name="reach")
    b = plan_from_arrays(q[::-1], NAMES, dt=0.1, gripper="hold", name="pull",
                         expect={"joint": "d", "from": 0.0, "to": 0.2})
    plan = join_plans(a, b)
    assert [s.name for s in plan.segments] == ["reach", "pull"] and plan.expectations[0][0] == 1
    assert plan_from_dict(plan_to_dict(plan)).isclose(plan)
    with pytest.raises(PlanFileError, match=r"waypoints\[0\]' has 3 values"):
        plan_from_arrays(np.zeros((2, 3)), NAMES, dt=0.1)


_OMPL_PATH = """
import numpy as np
from ompl import base as ob, geometric as og
space = ob.CompoundStateSpace()
se2 = ob.SE2StateSpace()
b = ob.RealVectorBounds(2); b.setLow(-5); b.setHigh(5); se2.setBounds(b)
arm = ob.RealVectorStateSpace(7)
a = ob.RealVectorBounds(7); a.setLow(-3); a.setHigh(3); arm.setBounds(a)
space.addSubspace(se2, 1.0); space.addSubspace(arm, 1.0)
si = ob.SpaceInformation(space); si.setStateValidityChecker(lambda s: True); si.setup()
path = og.PathGeometric(si)
for k in range(3):
    s = space.allocState()
    s[0].setX(1.2 - 0.1 * k); s[0].setY(0.05 * k); s[0].setYaw(3.0)
    for j in range(7):
        s[1][j] = 0.1 * j + 0.01 * k
    path.append(s)
path.printAsMatrix()
"""


def test_ompl_print_as_matrix_converts_to_a_plan():
    """OMPL's own printAsMatrix output (an SE2 base + a 7-joint arm) -> a plan with those columns."""
    import subprocess
    import sys

    from simcheck.plan_adapters import plan_from_ompl_matrix

    out = subprocess.run([sys.executable, "-c", _OMPL_PATH], capture_output=True, text=True, timeout=60, check=True)
    names = [n for n in NAMES if n != "torso_lift"]      # the SE2 base and the 7 arm joints OMPL planned
    plan = plan_from_ompl_matrix(out.stdout, names, dt=0.2, gripper="open", name="approach")
    q = plan.segments[0].q
    assert q.shape == (3, 10)
    assert np.allclose(q[:, 0], [1.2, 1.1, 1.0]) and np.allclose(q[:, 2], 3.0)
    assert np.allclose(q[2, 3:], 0.1 * np.arange(7) + 0.02)
    with pytest.raises(PlanFileError, match="line 2 has 2 numbers"):
        plan_from_ompl_matrix("1 2 3\n1 2\n", names, dt=0.1)
