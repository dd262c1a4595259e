"""What is asked (:class:`OpenTask`) and what comes back (:class:`PlanResult` of :class:`Segment`\\ s).

The one task type of partscene: the planner plans it, simcheck certifies it, the command lines and
scenario files write it as ``"open-drawer:JOINT[=AMOUNT][@X,Y,Z]"`` or ``"close-door:JOINT[=FROM]"``
(:func:`parse_task`), and :func:`check_task` checks it against a scene's joints. Engine-free.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from planners.errors import TaskJointError, TaskSpecError

__all__ = ["OpenTask", "PlanStatus", "Segment", "Expectation", "GRIPPER_COMMANDS", "PlanResult", "SEGMENT_NAMES",
           "PUSH_SEGMENT_NAMES",
           "KINDS", "parse_task", "parse_tasks", "check_task", "ALL_MOVABLE", "OPENING_KINDS", "movable_joint_tasks",
           "ACTIONS"]

#: Segment names in execution order.
SEGMENT_NAMES = ("approach", "grasp", "open", "release", "retreat")
#: the segments a plan that finishes an opening by pushing adds after ``retreat`` (:mod:`planners.push_finish`):
#: the free move to the door's inner face, the push (the only segment in which the hand may touch the part
#: without a grasp) and the withdrawal, at whose end the part must be at rest
PUSH_SEGMENT_NAMES = ("reposition", "push", "withdraw")

#: task kind -> the joint type it opens (a door also opens a continuous joint)
KINDS = {"drawer": "prismatic", "door": "revolute"}
#: joint type -> the kind of task that opens it (:func:`movable_joint_tasks`)
OPENING_KINDS = {"prismatic": "drawer", "revolute": "door", "continuous": "door"}
#: every task as the command line writes it: open or close a drawer or a door
ACTIONS = tuple(f"{verb}-{kind}" for verb in ("open", "close") for kind in KINDS)


@dataclass(frozen=True)
class OpenTask:
    """Open (or, with ``close``, shut) the part moved by ``joint`` (its URDF name).

    Attributes:
        kind ("drawer" | "door"): A drawer needs a prismatic joint, a door a revolute one.
        joint (str): URDF name of the joint to open.
        amount (float or None): Target opening (metres / radians, non-zero, counted from the joint's current value;
            negative opens toward the lower limit, for joints whose files open toward negative values). ``None``:
            drawers 90% of the joint's range, doors ``min(90% of range, 85 deg)`` (:class:`planners.PlannerConfig`),
            toward the limit farther from the current value (a joint closed at 0 with limits ``[-1.57, 0]`` opens
            toward -1.57); a ``continuous`` joint opens by ``+door_max`` (85 deg).
        grasp_point ((3,) float or None): Explicit grasp point (world frame, metres, joint closed) on the moving
            part.
        grasp_link (str or None): Explicit handle link (or the moving link itself) to grasp.
        close (bool): Shut the part instead: it starts open and the robot pushes or pulls it to its closed value
            (the joint's 0, the state a scan saw, clipped to its limits). ``amount`` is then how far open it
            starts, counted from closed and signed like an opening (``None``: the amount an opening would
            request); a part that is already open (a scenario's earlier task) is shut from where it is.

    Raises :class:`planners.errors.TaskSpecError` (an input error) naming the task when a field is invalid.
    ``str(task)`` is its command-line form, ``"open-drawer:JOINT"`` or ``"close-door:JOINT"``.
    """

    kind: str
    joint: str
    amount: float | None = None
    grasp_point: tuple[float, float, float] | None = None
    grasp_link: str | None = None
    close: bool = False

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise TaskSpecError(f"task {self.kind}:{self.joint}: kind must be one of {sorted(KINDS)} "
                                f"(written {', '.join(ACTIONS[:-1])} or {ACTIONS[-1]}, then :JOINT)")
        if not self.joint:
            raise TaskSpecError(f"task {self.action}: names no joint (write {self.action}:JOINT)")
        if self.amount is not None:
            try:
                amount = float(self.amount)
            except (TypeError, ValueError):
                amount = math.nan
            if not (amount != 0 and math.isfinite(amount)):
                what = "the opening to close from" if self.close else "amount"
                raise TaskSpecError(f"task {self}: {what} must be a non-zero number (m or rad; negative opens "
                                    f"toward the lower limit), got {self.amount!r}")
            object.__setattr__(self, "amount", amount)
        if self.grasp_point is not None:
            try:
                gp = tuple(float(v) for v in np.asarray(self.grasp_point, dtype=float).reshape(-1))
            except (TypeError, ValueError):
                gp = ()
            if len(gp) != 3 or not all(math.isfinite(v) for v in gp):
                raise TaskSpecError(f"task {self}: grasp_point must be 3 numbers X,Y,Z in metres, "
                                    f"got {self.grasp_point!r}")
            object.__setattr__(self, "grasp_point", gp)

    @property
    def action(self) -> str:
        """``"open-drawer"``, ``"open-door"``, ``"close-drawer"`` or ``"close-door"``: the task as the command
        line and certificates write it."""
        return f"{'close' if self.close else 'open'}-{self.kind}"

    def __str__(self) -> str:
        return f"{self.action}:{self.joint}"


def parse_task(text: str | OpenTask, amount: float | None = None) -> OpenTask:
    """``"open-KIND:JOINT[=AMOUNT][@X,Y,Z]"`` -> :class:`OpenTask`, e.g. ``"open-drawer:cabinet3_drawer12_joint"``,
    ``"open-door:fridge_door=1.2"`` (rad), ``"open-drawer:d1@1.2,0.3,0.8"`` (explicit grasp point, world
    frame, m); ``"close-KIND:JOINT[=FROM]"`` shuts it, from ``FROM`` open (``OpenTask.close``). ``amount``
    fills an amount the text does not give; an :class:`OpenTask` is returned as is.

    Raises :class:`planners.errors.TaskSpecError` naming the text and what is wrong.
    """
    if isinstance(text, OpenTask):
        return text
    action, sep, rest = str(text).partition(":")
    action, kinds = action.strip(), list(ACTIONS)
    if not sep:
        raise TaskSpecError(f"task {text!r}: expected KIND:JOINT with KIND in {kinds}")
    if action not in kinds:
        raise TaskSpecError(f"task {text!r}: kind must be one of {kinds}")
    verb, _, kind = action.partition("-")
    rest, at, point = rest.partition("@")
    grasp_point = None
    if at:
        try:
            grasp_point = tuple(float(v) for v in point.split(","))
        except ValueError:
            grasp_point = ()
        if len(grasp_point) != 3:
            raise TaskSpecError(f"task {text!r}: grasp point {point!r} must be X,Y,Z in metres")
    joint, eq, value = rest.partition("=")
    if eq:
        try:
            amount = float(value)
        except ValueError:
            raise TaskSpecError(f"task {text!r}: amount {value!r} is not a number") from None
    return OpenTask(kind=kind, joint=joint.strip(), amount=amount, grasp_point=grasp_point, close=verb == "close")


def parse_tasks(tasks: Iterable[str | OpenTask], amounts: Iterable[float] | None = None,
                froms: Iterable[float] | None = None) -> tuple[OpenTask, ...]:
    """Parse task strings (or keep :class:`OpenTask`\\ s); ``amounts`` (one for all tasks, or one per task,
    m or rad) fill the amounts the opening tasks do not give, ``froms`` (the same way) how far open the
    closing tasks start.

    Raises :class:`planners.errors.TaskSpecError`: no task, a malformed task, or a wrong number of amounts.
    """
    tasks = list(tasks)
    if not tasks:
        raise TaskSpecError("no task given (use --task open-drawer:JOINT or --task open-door:JOINT)")
    lists = []
    for values, what in ((amounts, "amounts"), (froms, "--from values")):
        values = list(values or [])
        if len(values) == 1:
            values = values * len(tasks)
        if values and len(values) != len(tasks):
            raise TaskSpecError(f"{len(values)} {what} for {len(tasks)} tasks: give one, or one per task")
        lists.append(values)
    amounts, froms = lists
    out = []
    for i, t in enumerate(tasks):
        task = parse_task(t)
        fill = froms if task.close else amounts
        if task.amount is None and fill:
            task = OpenTask(task.kind, task.joint, fill[i], task.grasp_point, task.grasp_link, task.close)
        out.append(task)
    return tuple(out)


#: the largest opening the planners accept: a drawer's travel (m) and a door's swing (rad). A joint range or
#: an amount beyond these is an input error (a 1e6 m drawer would plan ~1e8 waypoints)
MAX_DRAWER_TRAVEL = 3.0
MAX_DOOR_SWING = 2 * math.pi


def check_amount(task: "OpenTask", amount: float, source: object) -> None:
    """Refuse an opening ``amount`` (m for a drawer, rad for a door; either sign) whose size is beyond :data:`MAX_DRAWER_TRAVEL` /
    :data:`MAX_DOOR_SWING`; raises :class:`planners.errors.TaskJointError` naming ``source`` and the joint."""
    bound, unit = (MAX_DRAWER_TRAVEL, "m") if task.kind == "drawer" else (MAX_DOOR_SWING, "rad")
    if abs(amount) > bound:
        raise TaskJointError(f"{task}: {source}: joint {task.joint!r}: opening by {amount:.4g} {unit} is beyond "
                             f"the physical bound {bound:.4g} {unit}; fix the joint's limit or give a smaller amount")


class _JointLike(Protocol):
    type: str        # "prismatic", "revolute", "continuous", "fixed", ... (or a str enum of those)
    lower: float     # m or rad
    upper: float

    @property
    def movable(self) -> bool: ...


def check_task(task: OpenTask, joints: Mapping[str, _JointLike], source: object) -> _JointLike:
    """The joint of ``joints`` (name -> joint with ``type``, ``lower``, ``upper``, ``movable``) that ``task``
    opens, after checking it exists, moves, has the type the task needs and a range (``upper > lower``).

    Raises :class:`planners.errors.TaskJointError` naming ``source`` (the scene file) and the joint.
    """
    where = f"{task}: {source}: joint {task.joint!r}"
    if task.joint not in joints:
        movable = sorted(n for n, j in joints.items() if j.movable)
        raise TaskJointError(f"{where} does not exist (movable joints: {', '.join(movable[:12]) or 'none'})")
    j = joints[task.joint]
    need, jtype = KINDS[task.kind], str(getattr(j.type, "value", j.type))   # an enum or the URDF string
    if jtype == "fixed":
        raise TaskJointError(f"{where} is fixed: nothing to open as a {task.kind}")
    if jtype != need and not (need == "revolute" and jtype == "continuous"):
        raise TaskJointError(f"{where} is {jtype}, but a {task.kind} needs a {need} joint")
    if jtype != "continuous" and not j.upper > j.lower:
        raise TaskJointError(f"{where} has no opening range (lower {j.lower}, upper {j.upper})")
    return j


#: the task list that means "open every drawer and door of the scene" (``--all-movable``)
ALL_MOVABLE = "all-movable"


def movable_joint_tasks(joints: Mapping[str, _JointLike], source: object) -> tuple[tuple[OpenTask, ...], dict[str, str]]:
    """A task for every drawer and door of ``joints`` (name -> joint, in file order): prismatic ->
    ``open-drawer``, revolute or continuous -> ``open-door`` (:data:`OPENING_KINDS`); and the movable joints
    left out, by name, with why (no opening range: ``upper <= lower``; their task would be
    ``OpenTask(OPENING_KINDS[type], name)``). Fixed and other joint types are not tasks.

    >>> from types import SimpleNamespace as J
    >>> tasks, skipped = movable_joint_tasks({"d": J(type="prismatic", lower=0.0, upper=0.3),
    ...                                       "h": J(type="revolute", lower=0.0, upper=0.0),
    ...                                       "f": J(type="fixed", lower=0.0, upper=0.0)}, "s.urdf")
    >>> [str(t) for t in tasks], skipped
    (['open-drawer:d'], {'h': 's.urdf: revolute joint has no opening range (lower 0.0, upper 0.0)'})
    """
    tasks, skipped = [], {}
    for name, j in joints.items():
        jtype = str(getattr(j.type, "value", j.type))
        if jtype not in OPENING_KINDS:
            continue
        if jtype != "continuous" and not j.upper > j.lower:
            skipped[name] = f"{source}: {jtype} joint has no opening range (lower {j.lower}, upper {j.upper})"
            continue
        tasks.append(OpenTask(OPENING_KINDS[jtype], name))
    return tuple(tasks), skipped


class PlanStatus(enum.Enum):
    """Outcome of :func:`planners.plan_open_task`."""

    OK = "ok"
    NO_STAND_POSE = "no_stand_pose"
    IK_FAILED = "ik_failed"
    NO_PATH = "no_path"
    START_IN_COLLISION = "start_in_collision"
    GOAL_IN_COLLISION = "goal_in_collision"
    OPENING_FAILED = "opening_failed"


#: a given plan's gripper commands (``partscene.plan/1``, :mod:`planners.plan_file`): ``open`` opens the fingers
#: at the segment's start (letting go of a grasp) and keeps them open; ``close`` closes them at the segment's
#: end, after its motion (a grasp forms where a handle is between the pads); ``hold`` keeps them as they are
GRIPPER_COMMANDS = ("open", "close", "hold")


@dataclass(frozen=True)
class Expectation:
    """What a segment of a given plan is meant to do to the world: move scene joint ``joint`` from
    ``start`` to ``end`` (m or rad, the joint's values; written ``from`` / ``to`` in a plan file)."""

    joint: str
    start: float
    end: float

    @property
    def amount(self) -> float:
        """The requested opening, ``end - start`` (m or rad; negative: toward the lower limit)."""
        return self.end - self.start


@dataclass(frozen=True)
class Segment:
    """One piece of the plan, sampled densely enough to execute by interpolation.

    Attributes:
        name (str): One of :data:`SEGMENT_NAMES` or :data:`PUSH_SEGMENT_NAMES` (a given plan's: its own).
        q ((n, dof) float): Robot joint positions, columns in ``PlanResult.joint_names`` order (m, rad).
        object_q ((n,) float): Planned value of the task joint at each sample (m or rad).
        T_world_tool ((n, 4, 4) float): Planned tool pose; during ``open`` this is where the handle grasp frame is
            planned to be.
        gripper ("open" | "closed"): Gripper command held during the segment.
        t ((n,) float or None): Seconds from the segment's start at which each waypoint is reached (0 first,
            increasing): the timing of a given plan, executed as it is. None: the executor times the segment itself.
        command ("open" | "close" | "hold" or None): A given plan's gripper command (:data:`GRIPPER_COMMANDS`);
            None: a planner's segment, whose gripper actions follow from its ``name`` and ``gripper``.
        expect (Expectation or None): What the segment is meant to do to a scene joint (given plans).
    """

    name: str
    q: np.ndarray
    object_q: np.ndarray
    T_world_tool: np.ndarray
    gripper: str
    t: np.ndarray | None = None
    command: str | None = None
    expect: Expectation | None = None

    def __post_init__(self) -> None:
        q = np.atleast_2d(np.asarray(self.q, dtype=float))
        n = len(q)
        object_q = np.asarray(self.object_q, dtype=float)
        T = np.asarray(self.T_world_tool, dtype=float)
        if object_q.shape != (n,) or T.shape != (n, 4, 4):
            raise ValueError(f"Segment {self.name!r}: inconsistent shapes q{q.shape} "
                             f"object_q{object_q.shape} T_world_tool{T.shape}")
        if self.gripper not in ("open", "closed"):
            raise ValueError(f"Segment {self.name!r}: gripper must be 'open' or 'closed', got {self.gripper!r}")
        if self.command is not None and self.command not in GRIPPER_COMMANDS:
            raise ValueError(f"Segment {self.name!r}: command must be one of {GRIPPER_COMMANDS}, got {self.command!r}")
        if self.t is not None:
            t = np.asarray(self.t, dtype=float).reshape(-1)
            if t.shape != (n,) or (n and t[0] != 0.0) or np.any(np.diff(t) <= 0):
                raise ValueError(f"Segment {self.name!r}: t must be {n} increasing times from 0, got {t}")
            object.__setattr__(self, "t", t)
        object.__setattr__(self, "q", q)
        object.__setattr__(self, "object_q", object_q)
        object.__setattr__(self, "T_world_tool", T)

    def isclose(self, other: "Segment", atol: float = 1e-9) -> bool:
        return (self.name == other.name and self.gripper == other.gripper and self.q.shape == other.q.shape
                and np.allclose(self.q, other.q, atol=atol) and np.allclose(self.object_q, other.object_q, atol=atol)
                and np.allclose(self.T_world_tool, other.T_world_tool, atol=atol))


@dataclass(frozen=True)
class PlanResult:
    """A plan for an :class:`OpenTask`, or why there is none (``status`` != OK, ``segments`` empty or partial).

    Attributes:
        status, reason: the outcome; ``reason`` names the joint and what failed.
        task: the task planned for.
        joint_names: robot joints, the columns of every ``Segment.q``.
        segments: in execution order (approach, grasp, open, release, retreat) when OK.
        T_world_base_stand: (4, 4) base pose at grasp time (identity when none was found).
        amount: requested opening (m or rad), from ``start_object_q``.
        start_object_q: value of the task joint when the plan starts.
        T_link_grasp: (4, 4) grasp frame in the moving link's frame (rigid during the opening).
        moving_link: the link moved by the task joint.
        grasp_link: the link whose bar is grasped (the handle link, or the moving link for a named geometry or
            an explicit grasp point); simcheck attaches the gripper to it.
        method: how the opening was planned ("constrained" or "ik_tracking"; "" when not planned).
        timings: seconds per stage; collision_checks : count; seed : the seed used.
        nearest_miss: with ``NO_STAND_POSE``, the smallest distance (m) between the tool and the grasp point
            that the arm reached from the sampled base poses (collisions ignored; 0 when the handle is within
            reach but every grasp collides); None otherwise.
    """

    status: PlanStatus
    reason: str
    task: OpenTask
    joint_names: tuple[str, ...]
    segments: tuple[Segment, ...] = ()
    T_world_base_stand: np.ndarray = field(default_factory=lambda: np.eye(4))
    amount: float = 0.0
    start_object_q: float = 0.0
    T_link_grasp: np.ndarray = field(default_factory=lambda: np.eye(4))
    moving_link: str = ""
    grasp_link: str = ""
    method: str = ""
    timings: dict = field(default_factory=dict)
    collision_checks: int = 0
    seed: int = 0
    nearest_miss: float | None = None

    @property
    def ok(self) -> bool:
        return self.status is PlanStatus.OK

    @property
    def opening_segment(self) -> str:
        """The name of the segment that opens the task joint: ``"open"`` for a planner's plan; for a given
        plan the segment whose expectation names the task joint."""
        for s in self.segments:
            if s.expect is not None and s.expect.joint == self.task.joint:
                return s.name
        return "open"

    @property
    def release_segment(self) -> str:
        """The name of the segment at whose end the opened part must be at rest: ``"release"`` for a
        planner's plan (``"withdraw"`` for one that finishes by pushing); for a given plan the first segment that
        opens the gripper after the last segment whose expectation names the task joint (that segment itself when
        none does)."""
        names = [s.name for s in self.segments]
        if self.opening_segment not in names or all(s.command is None for s in self.segments):
            return PUSH_SEGMENT_NAMES[2] if PUSH_SEGMENT_NAMES[1] in names else "release"
        i = max((k for k, s in enumerate(self.segments) if s.expect is not None and s.expect.joint == self.task.joint),
                default=names.index(self.opening_segment))
        return next((s.name for s in self.segments[i + 1:] if s.command == "open"), self.segments[i].name)

    def segment(self, name: str) -> Segment:
        """The segment called ``name`` (KeyError if absent)."""
        for s in self.segments:
            if s.name == name:
                return s
        raise KeyError(f"plan for {self.task.joint!r} has no segment {name!r}")

    def trajectory(self) -> tuple[np.ndarray, np.ndarray]:
        """All segments concatenated: ``q (N, dof)``, ``object_q (N,)``."""
        if not self.segments:
            return np.zeros((0, len(self.joint_names))), np.zeros(0)
        return (np.concatenate([s.q for s in self.segments]), np.concatenate([s.object_q for s in self.segments]))
