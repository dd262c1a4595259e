"""Tasks to certify: ``open-drawer:JOINT`` / ``open-door:JOINT``, parsed and checked against a scene.

A drawer task needs a prismatic joint, a door task a revolute one; a missing joint, a fixed joint or
the wrong type is an input error that names the file and the joint (exit code 2 in the CLI).
Default amount (DESIGN.md): drawers 90% of the joint's range; doors the smaller of 90% of the range
and 90 degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import planners
from simcheck.errors import TaskSpecError
from simcheck.scene_joints import SceneJoint, read_scene_joints

__all__ = ["Task", "parse_task", "parse_tasks", "check_task", "default_amount", "KINDS"]

#: task kind -> (planner kind, joint type it needs)
KINDS = {"open-drawer": ("drawer", "prismatic"), "open-door": ("door", "revolute")}


@dataclass(frozen=True)
class Task:
    """One task: open the part moved by ``joint``.

    Attributes:
        kind: "open-drawer" or "open-door".
        joint: the URDF joint name.
        amount: opening asked for, m or rad, counted from the joint's current value (None: default).
        grasp_point: (3,) world point to grasp (metres, closed state), or None to find the handle.
        grasp_link: the link to grasp, or None to find the handle.
    """

    kind: str
    joint: str
    amount: float | None = None
    grasp_point: tuple[float, float, float] | None = None
    grasp_link: str | None = None

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise TaskSpecError(f"task {self.kind}:{self.joint}: kind must be one of {sorted(KINDS)}")
        if not self.joint:
            raise TaskSpecError(f"task {self.kind}: names no joint (write {self.kind}:JOINT)")
        if self.amount is not None and not (self.amount > 0 and math.isfinite(self.amount)):
            raise TaskSpecError(f"task {self.kind}:{self.joint}: amount must be a positive number, got {self.amount}")

    @property
    def planner_kind(self) -> str:
        return KINDS[self.kind][0]

    def __str__(self) -> str:
        return f"{self.kind}:{self.joint}"


def parse_task(text: str | Task, amount: float | None = None) -> Task:
    """``"KIND:JOINT[=AMOUNT][@X,Y,Z]"`` -> :class:`Task`, e.g. ``"open-drawer:cabinet3_drawer12_joint"``,
    ``"open-door:fridge_door=1.2"``, ``"open-drawer:d1@1.2,0.3,0.8"`` (explicit grasp point, world frame, m)."""
    if isinstance(text, Task):
        return text
    kind, sep, joint = str(text).partition(":")
    if not sep:
        raise TaskSpecError(f"task {text!r}: expected KIND:JOINT with KIND in {sorted(KINDS)}")
    joint, at, point = joint.partition("@")
    grasp_point = None
    if at:
        try:
            grasp_point = tuple(float(v) for v in point.split(","))
        except ValueError:
            grasp_point = ()
        if len(grasp_point) != 3:
            raise TaskSpecError(f"task {text!r}: grasp point {point!r} must be X,Y,Z in metres")
    joint, eq, value = joint.partition("=")
    if eq:
        try:
            amount = float(value)
        except ValueError:
            raise TaskSpecError(f"task {text!r}: amount {value!r} is not a number") from None
    return Task(kind=kind.strip(), joint=joint.strip(), amount=amount, grasp_point=grasp_point)


def parse_tasks(tasks, amounts=None) -> tuple[Task, ...]:
    """Parse a list of task strings/Tasks; ``amounts`` (one per task, or one for all) fill unset amounts."""
    tasks = list(tasks)
    if not tasks:
        raise TaskSpecError("no task given (use --task open-drawer:JOINT or --task open-door:JOINT)")
    amounts = list(amounts or [])
    if len(amounts) == 1:
        amounts = amounts * len(tasks)
    if amounts and len(amounts) != len(tasks):
        raise TaskSpecError(f"{len(amounts)} amounts for {len(tasks)} tasks: give one, or one per task")
    out = []
    for i, t in enumerate(tasks):
        task = parse_task(t)
        if task.amount is None and amounts:
            task = Task(task.kind, task.joint, amounts[i], task.grasp_point, task.grasp_link)
        out.append(task)
    return tuple(out)


def default_amount(kind: str, joint: SceneJoint, start: float = 0.0) -> float:
    """Default opening of ``joint`` from ``start``: 90% of the remaining range, doors at most 90 deg
    (the planner's rule, :func:`planners.default_amount` with the default :class:`planners.PlannerConfig`)."""
    return planners.default_amount(KINDS[kind][0], max(start, joint.lower), joint.upper, planners.PlannerConfig())


def check_task(task: Task, scene_urdf: str | Path, joints: dict[str, SceneJoint] | None = None) -> SceneJoint:
    """The scene joint ``task`` opens, after checking it exists, moves and has the type the task needs.

    Raises:
        TaskSpecError: names the file and the joint and says what is wrong.
        SceneLoadError: the URDF cannot be read.
    """
    joints = read_scene_joints(scene_urdf) if joints is None else joints
    if task.joint not in joints:
        movable = sorted(n for n, j in joints.items() if j.movable)
        raise TaskSpecError(f"{task}: scene {scene_urdf} has no joint {task.joint!r} (movable joints: {movable})")
    j = joints[task.joint]
    need = KINDS[task.kind][1]
    if j.type == "fixed":
        raise TaskSpecError(f"{task}: joint {task.joint!r} of {scene_urdf} is fixed: nothing to open")
    if j.type != need and not (need == "revolute" and j.type == "continuous"):
        raise TaskSpecError(f"{task}: joint {task.joint!r} of {scene_urdf} is {j.type}, a {task.kind} task "
                            f"needs a {need} joint")
    if not j.upper > j.lower:
        raise TaskSpecError(f"{task}: joint {task.joint!r} of {scene_urdf} has no opening range "
                            f"(lower {j.lower}, upper {j.upper})")
    return j
