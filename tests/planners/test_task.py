"""planners.task: the one task type, its command-line syntax and its check against a scene's joints."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from planners.config import PlannerConfig, default_amount
from planners.errors import PlannerInputError, TaskJointError, TaskSpecError
from planners.scene_urdf import read_scene_urdf
from planners.task import OpenTask, PlanResult, PlanStatus, Segment, check_task, parse_task, parse_tasks

FIXTURE = Path(__file__).parent / "data" / "cabinet_fixture.urdf"
DRAWER = "cabinet1_drawer12_joint"
DOOR = "cabinet1_door14_joint"


def test_parse_task_syntax():
    assert parse_task(f"open-drawer:{DRAWER}=0.2") == OpenTask("drawer", DRAWER, 0.2)
    assert parse_task("open-door:d@1,2.5,0.8").grasp_point == (1.0, 2.5, 0.8)
    assert parse_task(" open-door : d ") == OpenTask("door", "d")
    assert parse_task("open-door:d", amount=1.0).amount == 1.0
    assert str(OpenTask("drawer", DRAWER)) == f"open-drawer:{DRAWER}" and OpenTask("door", "d").action == "open-door"
    task = OpenTask("door", "d")
    assert parse_task(task) is task
    assert [t.amount for t in parse_tasks(["open-drawer:a", "open-door:b"], [0.3])] == [0.3, 0.3]
    assert [t.amount for t in parse_tasks(["open-drawer:a=0.1", "open-door:b"], [0.3, 0.4])] == [0.1, 0.4]


@pytest.mark.parametrize("text, message", [
    ("open-door:d@1,2", "grasp point '1,2' must be X,Y,Z"),
    ("open-drawer:a=0", "amount must be a non-zero number"),
    ("open-drawer:a=inf", "amount must be a non-zero number"),
    ("open-drawer:a=x", "amount 'x' is not a number"),
    ("drawer:a", "kind must be one of"),
    ("open-drawer", "expected KIND:JOINT"),
    ("open-window:a", "kind must be one of"),
    ("open-door:", "names no joint"),
])
def test_malformed_tasks_raise_an_input_error_naming_the_task(text, message):
    with pytest.raises(TaskSpecError, match=message):
        parse_task(text)
    assert issubclass(TaskSpecError, PlannerInputError)


def test_task_fields_are_checked_on_construction():
    with pytest.raises(TaskSpecError, match="amount must be a non-zero number"):
        OpenTask("drawer", DRAWER, amount=0.0)
    with pytest.raises(TaskSpecError, match="grasp_point must be 3 numbers"):
        OpenTask("drawer", DRAWER, grasp_point=(1.0, 2.0))
    assert OpenTask("drawer", DRAWER, amount=np.float32(0.25), grasp_point=np.array([1, 2, 3])).grasp_point == (1.0, 2.0, 3.0)
    with pytest.raises(TaskSpecError, match="no task given"):
        parse_tasks([])
    with pytest.raises(TaskSpecError, match="2 amounts for 3 tasks"):
        parse_tasks(["open-drawer:a", "open-drawer:b", "open-drawer:c"], [0.1, 0.2])


def test_check_task_against_the_scene_joints():
    scene = read_scene_urdf(FIXTURE)
    j = check_task(OpenTask("drawer", DRAWER), scene.joints, FIXTURE)
    assert j.type == "prismatic" and default_amount("drawer", j.lower, j.upper, PlannerConfig()) == pytest.approx(
        0.9 * (j.upper - j.lower))
    d = check_task(OpenTask("door", DOOR), scene.joints, FIXTURE)
    assert default_amount("door", d.lower, d.upper, PlannerConfig()) == pytest.approx(min(0.9 * (d.upper - d.lower),
                                                                                       math.radians(85)))
    for task, message in [(OpenTask("drawer", "nope"), "joint 'nope' does not exist"),
                          (OpenTask("door", DRAWER), "is prismatic, but a door needs a revolute joint")]:
        with pytest.raises(TaskJointError, match=message) as e:
            check_task(task, scene.joints, FIXTURE)
        assert "cabinet_fixture.urdf" in str(e.value)


def test_a_hand_made_plan_is_a_plan_result():
    q = np.zeros((3, 4))
    seg = Segment("approach", q, [0.0, 0.0, 0.0], np.repeat(np.eye(4)[None], 3, axis=0), "open")
    plan = PlanResult(PlanStatus.OK, "hand-made", OpenTask("drawer", DRAWER), ("a", "b", "c", "d"), (seg,), amount=0.2)
    assert plan.ok and plan.segment("approach").object_q.dtype == np.float64
    with pytest.raises(ValueError, match="inconsistent shapes"):
        Segment("grasp", q, [0.0], np.repeat(np.eye(4)[None], 3, axis=0), "open")
    with pytest.raises(ValueError, match="gripper must be 'open' or 'closed'"):
        Segment("grasp", q, np.zeros(3), np.repeat(np.eye(4)[None], 3, axis=0), "shut")


def test_close_tasks_parse_with_the_opening_they_start_from():
    task = parse_task(f"close-drawer:{DRAWER}=0.2")
    assert task == OpenTask("drawer", DRAWER, 0.2, close=True)
    assert str(task) == f"close-drawer:{DRAWER}" and task.action == "close-drawer"
    assert parse_task("close-door:d").amount is None and parse_task("close-door:d").close
    tasks = parse_tasks(["open-drawer:a", "close-door:b", "close-drawer:c=0.1"], [0.3], froms=[0.5])
    assert [(t.action, t.amount) for t in tasks] == [("open-drawer", 0.3), ("close-door", 0.5), ("close-drawer", 0.1)]
    with pytest.raises(TaskSpecError, match="the opening to close from must be a non-zero number"):
        parse_task("close-door:d=0")
    with pytest.raises(TaskSpecError, match="2 --from values for 3 tasks"):
        parse_tasks(["close-door:a", "close-door:b", "open-door:c"], froms=[0.1, 0.2])


def test_a_close_task_starts_where_an_opening_would_end_and_moves_to_closed():
    from planners.plan import _validate, close_start_value, closed_value

    scene, cfg = read_scene_urdf(FIXTURE), PlannerConfig()
    j = scene.joints[DOOR]
    close = OpenTask("door", DOOR, close=True)
    start = close_start_value(scene, close, 0.0, cfg)
    assert start == pytest.approx(default_amount("door", j.lower, j.upper, cfg))
    assert close_start_value(scene, OpenTask("door", DOOR, 0.5, close=True), 0.0, cfg) == pytest.approx(0.5)
    assert close_start_value(scene, close, 0.3, cfg) == pytest.approx(0.3)      # already open: shut from there
    assert _validate(scene, close, start, cfg) == pytest.approx(closed_value(j.lower, j.upper) - start)
    with pytest.raises(TaskJointError, match="already closed"):
        _validate(scene, close, 0.0, cfg)
    assert closed_value(-1.57, 0.0) == 0.0 and closed_value(0.2, 1.5) == 0.2
