"""Certify a user's own plan (``simcheck certify-plan``): a plan file or arrays, replayed in physics on the scene.

    cert = simcheck.certify_plan("scene.urdf", "drawer.plan.json", against="truth.urdf", out="out/")

How a given plan is judged: the robot is placed at the plan's first waypoint (the only jump, at t = 0), then
the plan is executed as given -- its times, its gripper commands, tracked by the robot's controllers, no
replanning (:func:`simcheck.execute.execute_task` on its timed segments) -- re-checked densely for
collisions (:func:`simcheck.plan_recheck.recheck_plan`) and judged by the criteria of
a planned task (the expectation's segment playing the opening, the next segment that opens the gripper the
release) plus: the expectation met by the end of its segment, every other articulation left where it was
(:mod:`simcheck.plan_expectations`), and the plan's timing within the robot's limits
(:mod:`simcheck.plan_timing`). Each expectation is a task of the certificate, judged on its part of the plan
(:func:`expectation_zones`); a plan with several is executed part after part in one world, as a scenario's
tasks are, each part starting where the robot is.

The binding of a plan to the robot and the scene (:func:`bind_plan`) refuses with exit 2, naming the field: a
joint the robot lacks or a robot joint the plan lacks, an expectation naming no movable scene joint, a plan
without expectation, expectations of one joint with another joint's between them (the certificate has one task
per joint) or two without a segment opening the gripper between them, and in a scenario a first waypoint away
from where the robot is. Consecutive expectations of one joint are one task moved in parts (a grasped pull, the
gripper let go, then a push: :mod:`planners.push_finish`): each part's expectation is met by the end of its
segment and the task asks for the whole move, from the first part's ``from`` to the last one's ``to``.
"""

from __future__ import annotations

import dataclasses
import logging
from pathlib import Path

import numpy as np

from planners.task import OPENING_KINDS, OpenTask, PlanResult, PlanStatus, Segment
from simcheck.config import DEFAULT_CRITERIA, DEFAULT_PHYSICS, CriteriaConfig, PhysicsConfig
from simcheck.errors import PlanFileError
from simcheck.plan_file import GivenPlan, read_plan

__all__ = ["certify_plan", "bind_plan", "expectation_zones", "followed_values", "given_planner", "given_from_result", "given_criteria", "plan_path",
           "START_TOLERANCE"]

log = logging.getLogger(__name__)

#: how far, rad or m per joint, a scenario's given plan may start from where the robot is
START_TOLERANCE = 1e-3

def _tool_poses(robot, q: np.ndarray, scene) -> np.ndarray:
    """(n, 4, 4) tool poses T_world_tool of ``robot`` (a planners.RobotSpec) at (n, dof) ``q``, standing on the
    floor of the scene URDF ``scene`` (scene frame)."""
    from planners.plan import robot_kinematics
    from planners.scene_urdf import read_floor

    kin = robot_kinematics(robot, read_floor(scene))
    return np.array([kin.tool_pose(x) for x in q])


def _check_robot_joints(given: GivenPlan, robot) -> tuple[str, ...]:
    """The robot's joint names, after checking ``given`` has one column per robot joint and an expectation."""
    src = given.source
    robot_names = tuple(robot.joint_names)
    unknown = [n for n in given.joint_names if n not in robot_names]
    if unknown:
        raise PlanFileError(f"plan {src}: field 'joint_names': {unknown[0]!r} is not a joint of robot {robot.urdf.name} "
                            f"(its joints: {', '.join(robot_names)})")
    missing = [n for n in robot_names if n not in given.joint_names]
    if missing:
        raise PlanFileError(f"plan {src}: field 'joint_names' lacks robot joint {missing[0]!r} (give one column per "
                            f"joint of robot {robot.urdf.name}: {', '.join(robot_names)})")
    if not given.expectations:
        raise PlanFileError(f"plan {src}: no segment has an 'expect': nothing to certify (say which joint a "
                            "segment should move, e.g. {\"joint\": J, \"from\": 0.0, \"to\": 0.3})")
    runs = [e.joint for k, (_, e) in enumerate(given.expectations)
            if k == 0 or given.expectations[k - 1][1].joint != e.joint]
    twice = next((j for j in runs if runs.count(j) > 1), None)
    if twice is not None:
        where = ", ".join(f"segments[{i}]" for i, e in given.expectations if e.joint == twice)
        raise PlanFileError(f"plan {src}: {where} expect scene joint {twice!r} with another joint's move between "
                            "them: the certificate has one task per joint (move a joint in consecutive parts, or "
                            "give one plan per move and chain them in a scenario)")
    expectation_zones(given)
    return robot_names


def expectation_zones(given: GivenPlan) -> list[tuple[int, int]]:
    """(first, last) segment indices, inclusive, of the part of ``given`` each expectation is judged on, in plan
    order: an expectation's part ends with the first segment after it that opens the gripper (its release)
    and the next part starts right after; the first part starts with the plan, the last ends with it.

    Raises:
        PlanFileError: no segment opens the gripper between two expectations (the gripper must let go of one
            part before it grasps the next).
    """
    idx = [i for i, _ in given.expectations]
    zones, first = [], 0
    for m, i in enumerate(idx[:-1]):
        nxt = idx[m + 1]
        release = next((k for k in range(i + 1, nxt) if given.segments[k].command == "open"), None)
        if release is None:
            raise PlanFileError(f"plan {given.source}: field 'segments[{i + 1}:{nxt}]': no segment between "
                                f"segments[{i}] ({given.segments[i].name!r}) and segments[{nxt}] "
                                f"({given.segments[nxt].name!r}), which both have an 'expect', opens the gripper: "
                                "let go of one part (\"gripper\": \"open\") before grasping the next")
        zones.append((first, release))
        first = release + 1
    if idx:
        zones.append((first, len(given.segments) - 1))
    return zones


def bind_plan(given: GivenPlan, robot, scene_joints: dict, scene) -> list[PlanResult]:
    """One :class:`planners.PlanResult` per expectation of ``given`` for ``robot`` (a planners.RobotSpec) on a
    scene whose joints are ``scene_joints`` (name -> joint with ``type``, from
    :func:`simcheck.scene_joints.read_scene_joints` of ``scene``): columns in the robot's joint order, tool
    poses by forward kinematics (``tool_positions`` of the file kept), the expected joint's planned value
    following the tool over its segment (:func:`followed_values`; ``e.start`` before, its last value after).

    Raises:
        PlanFileError: naming the plan file and the field (see the module docstring).
    """
    src = given.source
    robot_names = _check_robot_joints(given, robot)
    for i, e in given.expectations:
        j = scene_joints.get(e.joint)
        if j is None or str(getattr(j.type, "value", j.type)) not in OPENING_KINDS:
            movable = sorted(n for n, x in scene_joints.items() if str(getattr(x.type, "value", x.type)) in OPENING_KINDS)
            what = "does not exist" if j is None else f"is {getattr(j.type, 'value', j.type)}"
            raise PlanFileError(f"plan {src}: field 'segments[{i}].expect.joint': scene joint {e.joint!r} of {scene} "
                                f"{what} (movable joints: {', '.join(movable[:12]) or 'none'})")
    order = [given.joint_names.index(n) for n in robot_names]
    segments = []
    for s in given.segments:
        q = s.q[:, order]
        T = _tool_poses(robot, q, scene)
        given_tool = np.isfinite(s.T_world_tool[:, :3, 3]).all(axis=1)
        T[given_tool, :3, 3] = s.T_world_tool[given_tool, :3, 3]
        segments.append(dataclasses.replace(s, q=q, T_world_tool=T))
    parts: list[list] = []                 # consecutive expectations of one joint: one task
    for (i, e), zone in zip(given.expectations, expectation_zones(given)):
        if parts and parts[-1][-1][1].joint == e.joint:
            parts[-1].append((i, e, zone))
        else:
            parts.append([(i, e, zone)])
    plans = []
    for part in parts:
        first, last = part[0][1], part[-1][1]
        moved = {i: followed_values(segments[i].T_world_tool[:, :3, 3], scene_joints[e.joint], e) for i, e, _ in part}
        value, segs = first.start, []
        for k in range(part[0][2][0], part[-1][2][1] + 1):
            s = segments[k]
            obj = moved[k] if k in moved else np.full(len(s.t), value)
            value = float(obj[-1])
            segs.append(dataclasses.replace(s, object_q=obj))
        amount = last.end - first.start
        kind = OPENING_KINDS[str(getattr(scene_joints[first.joint].type, "value", scene_joints[first.joint].type))]
        task = OpenTask(kind, first.joint, amount)
        names = ", ".join(repr(given.segments[i].name) for i, _, _ in part)
        plans.append(PlanResult(PlanStatus.OK, f"given plan {src}, segment{'s' if len(part) > 1 else ''} {names}",
                                task, robot_names, tuple(segs), amount=amount, start_object_q=first.start,
                                method="given"))
    return plans


def followed_values(p_world_tool: np.ndarray, joint, e) -> np.ndarray:
    """(n,) the values, m or rad, of the expected joint ``joint`` (with ``type``, ``axis_world`` (3,) and
    ``origin_world`` (3,), world frame) if its part follows the tool positions ``p_world_tool`` (n, 3) of the
    expectation's segment from ``e.start``: the tool's displacement along the axis (prismatic) or its turn
    about the axis line (revolute), kept between ``e.start`` and ``e.end``. The planned state of the part the
    collision re-check sets while the robot holds it (a grasped part moves with the hand)."""
    p = np.asarray(p_world_tool, dtype=float)
    axis = np.asarray(joint.axis_world, dtype=float)
    axis = axis / np.linalg.norm(axis)
    if str(getattr(joint.type, "value", joint.type)) == "prismatic":
        delta = (p - p[0]) @ axis
    else:
        v = p - np.asarray(joint.origin_world, dtype=float)
        v = v - np.outer(v @ axis, axis)                                  # in the plane normal to the axis
        step = np.arctan2(np.cross(v[:-1], v[1:]) @ axis, np.einsum("ij,ij->i", v[:-1], v[1:]))
        delta = np.concatenate([[0.0], np.cumsum(step)])
    lo, hi = min(e.start, e.end), max(e.start, e.end)
    return np.clip(e.start + delta, lo, hi)


class _GivenPlanner:
    """A planner (``planner(scene, task, seed, start, scene_state)``) that returns the bound given plans. With a
    ``start`` (the robot's configuration where the previous task left it): the first part of a plan must start
    there (a scenario's carried-over state, else PlanFileError); a later part (the next expectation of the same
    plan) starts from it -- its first waypoint is where the robot is, the previous part's tracking error
    carried over, not a jump."""

    def __init__(self, plans: list[PlanResult], robot, source: str) -> None:
        self.plans, self.robot_spec, self.source = plans, robot, source

    def __call__(self, scene, task, seed, start=None, scene_state=None) -> PlanResult:
        k, plan = next((k, p) for k, p in enumerate(self.plans) if p.task == task)
        if start is not None and k > 0:
            first = plan.segments[0]
            q = first.q.copy()
            q[0] = np.asarray(start, dtype=float)
            return dataclasses.replace(plan, segments=(dataclasses.replace(first, q=q), *plan.segments[1:]))
        if start is not None:
            q0 = plan.segments[0].q[0]
            off = np.abs(np.asarray(start, dtype=float) - q0)
            if off.max() > START_TOLERANCE:
                j = int(np.argmax(off))
                raise PlanFileError(f"plan {self.source}: field 'segments[0].waypoints[0]' starts joint "
                                    f"{plan.joint_names[j]} at {q0[j]:.4f}, but the robot is at {start[j]:.4f} after "
                                    f"the previous task (at most {START_TOLERANCE} apart: the first waypoint must be "
                                    "where the robot is)")
        return plan


def given_planner(plan, robot, scene):
    """The tasks (one :class:`planners.OpenTask` per expectation) and the planner function that returns
    ``plan`` (a :class:`GivenPlan` or a plan file path) bound to ``robot`` and ``scene``."""
    from simcheck.scene_joints import read_scene_joints

    given = plan if isinstance(plan, GivenPlan) else read_plan(plan)
    _check_robot_joints(given, robot)             # the plan's own problems before the scene's
    plans = bind_plan(given, robot, read_scene_joints(scene), scene)
    return [p.task for p in plans], _GivenPlanner(plans, robot, given.source)


def certify_plan(scene, plan, *, against=None, out=None, robot=None, seed: int = 0, robust: int | None = None,
                 min_success: float = 0.9, replay_sample: int | None = None,
                 criteria: CriteriaConfig = DEFAULT_CRITERIA, physics: PhysicsConfig = DEFAULT_PHYSICS,
                 images: bool = True, video: bool = False, gui: bool = False, files=None, spreads=None,
                 robust_engine: str = "auto", address: str | None = None):
    """Certify the given ``plan`` (a plan file path, or a :class:`GivenPlan` from
    :func:`simcheck.plan_file.plan_from_arrays`) on ``scene``; returns the :class:`Certificate`, its task the
    plan's expectation (written to ``out`` if given).

    Args:
        against: a reference URDF to execute on instead of ``scene``.
        robot: a planners.RobotSpec; default: the plan's ``robot`` ("default" or a robot spec file).
        seed, robust, min_success, replay_sample, spreads, robust_engine, address: as for
            :func:`simcheck.certify` (the plan executed in ``robust`` worlds sampled with ``seed``).
        files: more files the run was judged on, by role; the plan file's sha256 is recorded as "plan".

    Raises:
        PlanFileError (and the other SimcheckInputErrors): the plan or the scene cannot be used (exit 2).
    """
    from simcheck.certification import certify

    given = plan if isinstance(plan, GivenPlan) else read_plan(plan)
    if robot is None:
        from simcheck.robot_spec_file import load_robot_spec
        robot = load_robot_spec(given.robot)
    tasks, planner = given_planner(given, robot, scene)
    if len(tasks) > 1 and (robust is not None or replay_sample is not None):
        raise PlanFileError(f"plan {given.source}: --robust certifies a plan with one expectation; this one has "
                            f"{len(tasks)} (give one plan per expectation)")
    return certify(scene, tasks, against=against, out=out, robot=robot, planner=planner, seed=seed, criteria=criteria,
                   carry_state=len(tasks) > 1,
                   physics=physics, images=images, video=video, gui=gui, robust=robust, min_success=min_success,
                   replay_sample=replay_sample, spreads=spreads, robust_engine=robust_engine, address=address,
                   files={"plan": None if isinstance(plan, GivenPlan) else plan, **(files or {})})


def given_from_result(plan: PlanResult, vmax_urdf: np.ndarray, physics: PhysicsConfig = DEFAULT_PHYSICS,
                      robot: str = "default") -> GivenPlan:
    """The planner's ``plan`` as a :class:`GivenPlan` with the timing simcheck's executor gives it
    (:func:`simcheck.execute.command_trajectory`; ``vmax_urdf`` (dof,) the robot's URDF velocity limits):
    replayed with :func:`certify_plan` the robot gets the same position targets at every control step.
    Gripper commands: ``grasp`` closes at its end, ``open`` holds, segments with the gripper open open it;
    the ``open`` segment expects the task joint to move from ``start_object_q`` by ``amount`` (in a plan finished
    by a push, ``open`` and ``push`` each expect the move they plan)."""
    from planners.task import Expectation
    from simcheck.execute import command_trajectory, segment_timing, speed_limits

    vmax = speed_limits(vmax_urdf, physics)
    segments = []
    pushed = any(s.name == "push" for s in plan.segments)
    for s in plan.segments:
        t, q, tool = command_trajectory(s, *segment_timing(s.name, vmax, physics))
        T = np.full((len(t), 4, 4), np.nan)
        if tool is not None:
            T[:, :3, 3] = tool
        command = "close" if s.name == "grasp" else ("hold" if s.gripper == "closed" else "open")
        expect = None
        if s.name == "open" and not pushed:
            expect = Expectation(plan.task.joint, plan.start_object_q, plan.start_object_q + plan.amount)
        elif s.name in ("open", "push"):     # a plan finished by a push: each moves the joint its own share
            expect = Expectation(plan.task.joint, float(s.object_q[0]), float(s.object_q[-1]))
        segments.append(Segment(s.name, q, np.full(len(t), np.nan), T, s.gripper, t=t, command=command,
                                expect=expect))
    return GivenPlan(robot=robot, joint_names=tuple(plan.joint_names), segments=tuple(segments),
                     source=f"planned {plan.task}")


def plan_path(out: Path, joint_stem: str) -> Path:
    """Where ``--save-plan`` writes a task's plan: ``out/plans/<stem>.plan.json``."""
    return Path(out) / "plans" / f"{joint_stem}.plan.json"



def given_criteria(plan: PlanResult, trace, vmax_urdf: np.ndarray, amax, criteria: CriteriaConfig = DEFAULT_CRITERIA,
                   units=None):
    """The criteria a given plan adds to a planned task's: its expectation for the task joint met
    (:func:`simcheck.plan_expectations.expectation_met`), every other articulation still
    (:func:`~simcheck.plan_expectations.articulations_still`; ``trace`` an ArticulationTrace of the execution)
    and its timing within ``vmax_urdf`` (dof,) and ``amax`` (dof,) (:func:`simcheck.plan_timing.timing_criteria`;
    ``units``: robot joint name -> "m" or "rad")."""
    from simcheck.plan_expectations import articulations_still, expectation_met
    from simcheck.plan_timing import timing_criteria

    out = []
    expected: dict[int, set[str]] = {}
    for i, s in enumerate(plan.segments):
        if s.expect is not None:
            expected.setdefault(i, set()).add(s.expect.joint)
            if s.expect.joint == plan.task.joint:
                out.append(expectation_met(trace, i, s.expect, criteria))
    out.append(articulations_still(trace, expected, criteria))
    out.extend(timing_criteria(plan.segments, plan.joint_names, vmax_urdf, amax, criteria, units))
    return tuple(out)
