"""``plan_open_task``: validate the task, find the handle and a stand pose, plan approach, grasp, opening,
release and retreat. Expected failures come back as a :class:`PlanResult` with a status and a reason.

Opening method (``PlannerConfig.open_method``): IK tracking of the estimated handle path (a straight pull
along the prismatic axis, an arc about the revolute hinge) with the whole body, densely interpolated and
collision-checked at every sample (:mod:`planners.motion`); OMPL constrained planning over robot joints +
object joint (:mod:`planners.opening`); or "auto": tracking first, constrained planning when it fails.
"""

from __future__ import annotations

import dataclasses
import functools
import logging
import math
import time

import numpy as np

from planners.config import PlannerConfig, default_amount
from planners.end_reach import END_SAMPLES, end_reach
from planners.errors import HandleStaysPutError, PlannerInputError, TaskJointError
from planners.handle import find_handle, grasp_path
from planners.ik import solve_ik
from planners.motion import TrackResult, densify, first_invalid, ik_weights, track_poses
from planners.opening import plan_opening_constrained
from planners.ompl_adapter import plan_joint_path
from planners.pin_world import LIMIT_TOLERANCE, PlanningWorld, RobotKinematics
from planners.robot import RobotSpec
from planners.scene_urdf import read_floor, read_scene_urdf
from planners.stand import StandPose, find_stand_poses
from planners.task import OpenTask, PlanResult, PlanStatus, Segment, check_amount, check_task
from scenes.description import LEVEL_FLOOR, SceneFloor, SceneModel

__all__ = ["plan_open_task", "robot_kinematics", "closed_value", "close_start_value"]

log = logging.getLogger(__name__)


def robot_kinematics(spec: RobotSpec, floor: SceneFloor = LEVEL_FLOOR) -> RobotKinematics:
    """The (cached) pinocchio model of ``spec`` standing on ``floor`` (loading and convexifying its meshes is
    done once per spec; :meth:`RobotKinematics.standing_on` once per floor)."""
    return _standing(_kinematics(spec), floor)


@functools.lru_cache(maxsize=4)
def _kinematics(spec: RobotSpec) -> RobotKinematics:
    return RobotKinematics(spec)


@functools.lru_cache(maxsize=8)
def _standing(kin: RobotKinematics, floor: SceneFloor) -> RobotKinematics:
    return kin.standing_on(floor)


def closed_value(lower: float, upper: float) -> float:
    """The value (m or rad) at which a joint with limits ``[lower, upper]`` is closed: 0, the state a scan saw,
    moved into the limits (a continuous joint: 0)."""
    return float(min(max(0.0, lower), upper))


#: a close task's joint farther than this (m or rad) from its closed value is already open: it is shut from
#: where it is
_ALREADY_OPEN = 1e-3


def close_start_value(scene: SceneModel, task: OpenTask, s_now: float, cfg: PlannerConfig) -> float:
    """The task joint's value (m or rad) when the close task ``task`` starts, the joint being at ``s_now``: where
    it is when already open, else its closed value plus ``task.amount`` or, without one, the opening an open
    task would request. Raises :class:`planners.errors.TaskJointError` as an opening would."""
    j = check_task(task, scene.joints, scene.path)
    closed = closed_value(j.lower, j.upper)
    if abs(s_now - closed) > _ALREADY_OPEN:
        return float(s_now)
    return closed + _validate(scene, dataclasses.replace(task, close=False), closed, cfg)


def _validate(scene: SceneModel, task: OpenTask, s0: float, cfg: PlannerConfig) -> float:
    """Check the task against the scene (:func:`planners.task.check_task`); return the amount to move from
    ``s0`` (m or rad; negative: toward the lower limit). Without an amount the joint opens toward the limit
    farther from ``s0`` (ties: the upper one, our scenes' positive-opens convention); a joint without
    finite limits (``continuous``) opens by ``+cfg.door_max``. A close task moves to :func:`closed_value`."""
    j = check_task(task, scene.joints, scene.path)
    where = f"{scene.path}: joint {task.joint!r}"
    if task.close:
        amount = closed_value(j.lower, j.upper) - s0
        if not abs(amount) > 1e-9:
            raise TaskJointError(f"{where}: already closed (at {s0:.4g}): nothing to close; start it open "
                                 f"(simcheck opens it by what an opening would request, or by --from)")
        check_amount(task, amount, scene.path)
        return amount
    lower, upper = j.lower, j.upper
    if not math.isfinite(upper) or not math.isfinite(lower):
        lower, upper = s0 - (cfg.door_max / cfg.door_fraction), s0 + (cfg.door_max / cfg.door_fraction)
    up, down = upper - s0, s0 - lower
    if task.amount is None:
        amount = default_amount(task.kind, lower, upper, cfg)
        amount = min(amount, up) if up >= down else -min(amount, down)
    else:
        amount = float(task.amount)
    if not abs(amount) > 1e-9:
        raise TaskJointError(f"{where}: nothing to open (current value {s0:.4g}, limits [{lower:.4g}, "
                             f"{upper:.4g}])")
    if s0 + amount > upper + 1e-9 or s0 + amount < lower - 1e-9:
        raise TaskJointError(f"{where}: amount {amount:.4g} from {s0:.4g} leaves the limits [{lower:.4g}, "
                             f"{upper:.4g}]")
    check_amount(task, amount, scene.path)
    return amount


def _translate_tool(T: np.ndarray, dz: float) -> np.ndarray:
    """``T`` moved by ``dz`` metres along its own z (approach) axis."""
    out = T.copy()
    out[:3, 3] += dz * T[:3, 2]
    return out


def _fk_poses(kin: RobotKinematics, q: np.ndarray) -> np.ndarray:
    return np.array([kin.tool_pose(x) for x in q])


def plan_open_task(robot: RobotSpec, scene_urdf, task: OpenTask, seed: int = 0, *, start=None,
                   scene_state: dict | None = None, config: PlannerConfig | None = None) -> PlanResult:
    """Plan opening ``task.joint`` of the scene in ``scene_urdf`` with ``robot``.

    Args:
        robot: the robot description.
        scene_urdf: path of the scene URDF (the estimate to plan on).
        task: what to open; ``amount`` is counted from the joint's current value. A close task (``task.close``)
            shuts the part from where ``scene_state`` has it (open it first: :func:`close_start_value`).
        seed: every random choice (stand sampling, IK restarts, OMPL) derives from it.
        start: (dof,) robot configuration in ``robot.joint_names`` order, or None: the robot starts
            ``config.start_backoff`` behind the chosen stand pose with the arm at home.
        scene_state: {joint name: value} of the scene's joints when the plan starts (default all 0).
        config: planner parameters.

    Raises:
        planners.errors.PlannerInputError (SceneURDFError, TaskJointError, HandleNotFoundError) for input that
        cannot be planned on. Every other outcome is a PlanResult.
    """
    cfg = config or PlannerConfig()
    t_all = time.perf_counter()
    timings: dict[str, float] = {}
    scene = read_scene_urdf(scene_urdf)
    state = dict(scene_state or {})
    s0 = float(state.get(task.joint, 0.0))
    amount = _validate(scene, task, s0, cfg)
    kin = robot_kinematics(robot, read_floor(scene_urdf))    # the robot on the scene's floor
    opens_up = (amount > 0) != task.close          # which way the joint opens: the handle's outward side
    try:
        handle = find_handle(scene, task, state, cfg, 1.0 if opens_up else -1.0, amount, 2 * robot.finger_open)
    except HandleStaysPutError as exc:      # a usable estimate that moves the handle nowhere: nothing to pull
        return PlanResult(PlanStatus.OPENING_FAILED, f"{task.kind} {task.joint!r}: {exc}", task, robot.joint_names,
                          amount=amount, start_object_q=s0, moving_link=scene.joints[task.joint].child, seed=seed,
                          timings={"total": time.perf_counter() - t_all})
    world = PlanningWorld(kin, scene, task.joint, set(handle.handle_geoms), state, cfg.clearance,
                          cfg.approach_clearance)
    rng = np.random.default_rng(seed)
    base = dict(task=task, joint_names=robot.joint_names, amount=amount, start_object_q=s0,
                moving_link=handle.moving_link, grasp_link=handle.grasp_link, seed=seed, timings=timings)

    def result(status, reason, **kw) -> PlanResult:
        timings["total"] = time.perf_counter() - t_all
        log.info("%s %s: %s (%s)", task.kind, task.joint, status.name, reason)
        return PlanResult(status, reason, collision_checks=world.checks, **base, **kw)

    j = scene.joints[task.joint]
    step = cfg.open_step_prismatic if j.type == "prismatic" else cfg.open_step_revolute
    s_path = s0 + amount * np.linspace(0.0, 1.0, max(2, int(math.ceil(abs(amount) / step)) + 1))
    T_moving = np.array([world.moving_link_pose(s) for s in s_path])
    T_paths = [grasp_path(handle, i, T_moving, s_path, j.axis) for i in range(len(handle.T_link_grasps))]

    t = time.perf_counter()
    hinge_xy = None
    if j.type != "prismatic":
        T_world_joint = scene.T_world_link(j.parent, state) @ j.T_parent_joint
        T_root_joint = kin.in_root(T_world_joint)           # floor frame: "vertical" is along the floor's normal
        if abs((T_root_joint[:3, :3] @ j.axis)[2]) > 0.9:   # a vertical hinge: a side-swinging door
            hinge_xy = T_root_joint[:2, 3]
    stands, summary, miss = find_stand_poses(kin, world, T_paths, s_path, cfg, rng, hinge_xy, handle.facing)
    timings["stand"] = time.perf_counter() - t
    if not stands:
        grasp_at = np.round(T_paths[0][0][:3, 3], 3).tolist()
        edge = handle.source == "panel edge"
        what = "the pinch on the front's edge" if edge else "the handle"
        if miss is None:
            missed = "every base pose sampled collides"
        elif miss > cfg.ik_pos_tol:
            missed = f"nearest miss {miss:.3f} m: {what} at {grasp_at} is out of the robot's reach"
        else:
            missed = f"nearest miss {miss:.3f} m: {what} at {grasp_at} is within reach, but no grasp is"
        howto = (f"an edge of its {handle.bar_width * 1000:.0f} mm front panel can be pinched collision-free (it has "
                 f"no handle)" if edge else "the handle can be grasped collision-free")
        return result(PlanStatus.NO_STAND_POSE, f"{task.kind} {task.joint!r}: no stand pose from which {howto} "
                      f"({missed}; {summary})", nearest_miss=miss)
    arm = np.zeros(robot.dof, bool)
    arm[3:] = True
    whole = np.ones(robot.dof, bool)
    weights = ik_weights(kin, cfg, cfg.base_weight)
    failures = []
    for rank, stand in enumerate(stands[:cfg.stand_tries]):
        out = _plan_from_stand(kin, world, task, stand, T_paths[stand.grasp_index], s_path, handle, cfg, rng,
                               arm, whole, weights, start, timings, seed, rank < cfg.constrained_stands)
        if isinstance(out[0], PlanStatus):
            failures.append(out)
            if out[0] in (PlanStatus.START_IN_COLLISION, PlanStatus.NO_PATH):
                break
            continue
        segments, method, note = out
        T_link_grasp = handle.T_link_grasps[stand.grasp_index]
        return result(PlanStatus.OK, f"{task.kind} {task.joint!r}: planned {'closing' if task.close else 'opening'} by {amount:.3f} "
                      f"({'m' if j.type == 'prismatic' else 'rad'}) from stand {np.round(stand.base, 3).tolist()}{note}",
                      segments=tuple(segments), T_world_base_stand=kin.T_world_root @ stand.T_root_base, T_link_grasp=T_link_grasp,
                      method=method)
    status, reason = failures[0] if len(failures) == 1 else failures[-1]
    if all(f[0] is PlanStatus.OPENING_FAILED for f in failures):
        # every grasp was reached but no opening followed: is the end of the opening out of the robot's reach?
        probe = np.random.default_rng(seed)          # its own stream: the plan's is untouched
        ends = [(end_reach(kin, world, T_paths[gi][-1], s_path[-1], cfg, probe), gi)
                for gi in dict.fromkeys(st.grasp_index for st in stands[:len(failures)])]
        if not any(e.reached for e, _ in ends):
            e, gi = min(ends, key=lambda eg: eg[0].miss)
            T_end = T_paths[gi][-1]
            pose = (f"tool at {np.round(T_end[:3, 3], 3).tolist()}, approaching "
                    f"{np.degrees(np.arcsin(np.clip(T_end[2, 2], -1, 1))):+.0f} deg from level")
            why = (f"nearest miss {e.miss:.3f} m" if e.miss > cfg.track_pos_tol else
                   f"within reach, but every such configuration collides ({e.collides_with})")
            return result(PlanStatus.NO_STAND_POSE, f"{task.kind} {task.joint!r}: the end of the opening is out of the "
                          f"robot's reach: none of {END_SAMPLES} base poses sampled around it holds the handle there "
                          f"({pose}; {why}); {reason} ({summary}; tried {len(failures)} stand poses)",
                          nearest_miss=e.miss, T_world_base_stand=kin.T_world_root @ stands[0].T_root_base)
    return result(status, f"{task.kind} {task.joint!r}: {reason} ({summary}; tried {len(failures)} stand poses)",
                  T_world_base_stand=kin.T_world_root @ stands[0].T_root_base)


def _plan_from_stand(kin, world, task, stand: StandPose, T_path, s_path, handle, cfg, rng, arm, whole, weights,
                     start, timings, seed, constrained_fallback):
    """Segments for one stand pose, or ``(PlanStatus, reason)``."""
    spec = kin.spec
    lower, upper = world.robot.lower, world.robot.upper
    s0, s1 = float(s_path[0]), float(s_path[-1])
    q_grasp = stand.q_grasp
    # Pre-grasp: backed off along the approach axis, gripper open, no contact allowed.
    t = time.perf_counter()
    T_pre = _translate_tool(T_path[0], -cfg.pregrasp_distance)
    world.keep_gripper_clear(True)    # the approach's goal: clear of the neighbours
    try:
        r = solve_ik(kin.tool_pose_jacobian, T_pre, q_grasp, lower, upper, arm, ik_weights(kin, cfg),
                     pos_tol=cfg.ik_pos_tol, rot_tol=cfg.ik_rot_tol, restarts=cfg.ik_restarts, rng=rng,
                     restart_span=np.full(spec.dof, 0.4), accept=lambda q: not world.in_collision(q, s0, False))
    finally:
        world.keep_gripper_clear(False)
    if not r.success:
        return PlanStatus.IK_FAILED, "no collision-free pre-grasp configuration"
    q_pre = r.q
    # Grasp: straight line from the pre-grasp to the grasp.
    n = max(2, int(math.ceil(cfg.pregrasp_distance / 0.01)) + 1)
    T_line = np.array([_translate_tool(T_path[0], -cfg.pregrasp_distance * (1 - u)) for u in np.linspace(0, 1, n)])
    g = track_poses(kin, world, T_line, np.full(n, s0), q_pre, arm, None, cfg, True)
    timings["grasp"] = time.perf_counter() - t
    if not g.success:
        return PlanStatus.IK_FAILED, f"straight grasp motion failed: {g.reason}"
    # Open: follow the estimated handle path with the whole body.
    t = time.perf_counter()
    # A stand pose from which the base-fixed arm reached the whole path is tracked arm-first; otherwise the
    # whole body moves (base down-weighted). track_poses falls back to the other resolutions per step.
    method = "ik_tracking"
    o = None
    if cfg.open_method in ("auto", "ik_tracking"):
        o = track_poses(kin, world, T_path, s_path, g.q[-1], arm if stand.path_share == 1.0 else whole, weights,
                        cfg, True)
    if cfg.open_method == "constrained" or (cfg.open_method == "auto" and not o.success and cfg.constrained_time > 0
                                            and constrained_fallback):
        oc = plan_opening_constrained(kin, world, handle.T_link_grasps[stand.grasp_index], s0, s1, g.q[-1], cfg,
                                      seed, rng)
        if oc.success or o is None:
            o, method = oc, "constrained"
        else:
            o = TrackResult(False, o.q, o.s, f"{o.reason}; constrained planning: {oc.reason}", o.failed_at)
    timings["open"] = time.perf_counter() - t
    # A door on a horizontal hinge whose grasped opening falls short (or would load an arm joint beyond
    # cfg.push_effort_share statically) is handed over to a push (planners.push_finish); a push that cannot be
    # planned leaves a whole grasped opening as it is.
    o_cut, frames, why_not = _grasped_share(kin, world, task, stand, handle, o, s0, s1, cfg)
    if not o.success and not frames:
        return PlanStatus.OPENING_FAILED, (f"opening motion failed at {o.s[-1] if len(o.s) else s0:.3f}: "
                                           f"{o.reason}{why_not}")
    tries = ([(o_cut, frames)] if frames else []) + ([(o, None)] if o.success else [])
    for o_try, frames_try in tries:
        s_rel = float(o_try.s[-1])    # where the fingers let go: the end of the opening, or where a push takes over
        rt, note = _retreat(kin, world, task, o_try, s_rel, whole, weights, cfg, timings)
        pushed = []
        if frames_try:
            pushed = _push_segments(kin, world, frames_try, s_rel, s1, rt.q[-1], cfg, seed, rng, timings)
            if isinstance(pushed, tuple):
                failed = pushed
                continue
            note += f"; opened by the grasp to {s_rel:.3f}, then pushed to {s1:.3f}"
        o = o_try
        break
    else:
        return failed
    # Approach: OMPL from the start configuration to the pre-grasp.
    t = time.perf_counter()
    q_start = _start_configuration(world, spec, stand, start, cfg, s0)
    if isinstance(q_start, tuple):
        return q_start
    world.keep_gripper_clear(True)    # the free approach keeps the gripper clear of the neighbours too
    try:
        if not world.within_limits(q_pre) or world.in_collision(q_pre, s0, False):
            return PlanStatus.GOAL_IN_COLLISION, "pre-grasp configuration in collision"
        qa, bad = _approach(world, q_start, q_pre, s0, cfg, seed, timings, t)
        if isinstance(qa, tuple):
            return qa
        if bad >= 0:
            return PlanStatus.NO_PATH, (f"approach: {cfg.approach_attempts} OMPL paths all collided when re-checked "
                                        f"densely ({_what(world, qa[bad], s0)})")
    finally:
        world.keep_gripper_clear(False)
    sa = np.full(len(qa), s0)
    T_moving = np.array([world.moving_link_pose(s) for s in o.s])
    T_open = T_moving @ handle.T_link_grasps[stand.grasp_index] if method == "constrained" else \
        grasp_path(handle, stand.grasp_index, T_moving, o.s, world.scene.joints[task.joint].axis)
    q_rel = np.repeat(o.q[-1:], 2, axis=0)
    return [
        Segment("approach", qa, sa, _fk_poses(kin, qa), "open"),
        Segment("grasp", g.q, g.s, _fk_poses(kin, g.q), "open"),
        Segment("open", o.q, o.s, T_open, "closed"),
        Segment("release", q_rel, np.full(2, s_rel), _fk_poses(kin, q_rel), "open"),
        Segment("retreat", rt.q, rt.s, _fk_poses(kin, rt.q), "open"),
        *pushed,
    ], method, note


def _retreat(kin, world, task, o: TrackResult, s_rel: float, whole, weights, cfg: PlannerConfig, timings: dict):
    """Retreat after the release at the end of ``o`` (task joint at ``s_rel``): back off along the approach axis
    with the gripper open, the whole body with the base weighted down further (it stays near where the opening
    left it, clear of the opened part); ``(TrackResult, note)``."""
    t = time.perf_counter()
    T_end = kin.tool_pose(o.q[-1])
    dist = cfg.retreat_distance
    w_back = weights.copy()
    w_back[:3] *= _RETREAT_BASE
    while True:
        n = max(2, int(math.ceil(dist / 0.01)) + 1)
        T_back = np.array([_translate_tool(T_end, -dist * u) for u in np.linspace(0, 1, n)])
        rt = track_poses(kin, world, T_back, np.full(n, s_rel), o.q[-1], whole, w_back, cfg, False)
        if rt.success or dist / 2 < cfg.min_retreat_distance - 1e-9:
            break
        dist /= 2
    timings["retreat"] = time.perf_counter() - t
    note = ""
    if not rt.success:
        # The opening is done once the gripper is open; a robot boxed in by the opened part and a wall stays
        # where it released (a two-sample, zero-length retreat) rather than failing the task.
        log.warning("%s: retreat blocked (%s); the robot stays where it released", task.joint, rt.reason)
        note = f"; retreat blocked ({rt.reason}), the robot stays at the release pose"
        rt = TrackResult(True, np.repeat(o.q[-1:], 2, axis=0), np.full(2, s_rel), "blocked", -1)
    return rt, note


def _grasped_share(kin, world, task, stand, handle, o: TrackResult, s0: float, s1: float, cfg: PlannerConfig):
    """Where a push takes over a grasped opening ``o`` of a door on a horizontal hinge: before the first sample at
    which holding the door would load an arm joint beyond ``cfg.push_effort_share`` of its effort statically
    (:func:`planners.push_finish.held_effort`), else where ``o`` failed -- at 75 % of what it reached: the arm
    ends a tracking that fails near its joint limits or a singular posture, where it follows the handle under load
    poorly -- when that is at least ``cfg.push_min_share`` of the request:
    ``(o cut there, [PushFrame, ...], "")``; else ``(o, [], why not, for a failure's reason)``."""
    from planners.push_finish import held_effort, horizontal_hinge, push_frames
    if not cfg.push_finish or task.close or len(o.s) < 2 or not horizontal_hinge(world, task.joint, s0):
        return o, [], ""
    direction = 1.0 if s1 >= s0 else -1.0
    over = np.flatnonzero(held_effort(kin, world, task.joint, o.q, o.s, direction) > cfg.push_effort_share)
    if len(over) and over[0] >= 1:
        reached, share = float(o.s[over[0] - 1]) - s0, 1.0
    elif o.success:
        return o, [], ""
    else:
        reached, share = float(o.s[-1]) - s0, 0.75
    if abs(reached) < cfg.push_min_share * abs(s1 - s0):
        return o, [], (f"; no push finish: the grasp follows only {abs(reached):.3f} of {abs(s1 - s0):.3f} "
                       f"(a push needs {cfg.push_min_share:.0%} open first)")
    frames = push_frames(world, task.joint, handle, stand.grasp_index, direction, cfg)
    if not frames:
        return o, [], "; no push finish: the door has no geometry to push but meshes"
    keep = np.abs(o.s - s0) <= share * abs(reached) + 1e-12
    return TrackResult(True, o.q[keep], o.s[keep], "ok", -1), frames, ""


def _push_segments(kin, world, frames, s_rel: float, s1: float, q_from: np.ndarray, cfg: PlannerConfig, seed: int,
                   rng, timings: dict):
    """The ``reposition``, ``push`` and ``withdraw`` segments (:data:`planners.task.PUSH_SEGMENT_NAMES`) of a push
    from ``s_rel`` to ``s1`` starting at ``q_from`` (the retreat's end) with the first of ``frames`` that works, or
    ``(PlanStatus, reason)``."""
    from planners.push_finish import plan_push
    t = time.perf_counter()
    j = world.scene.joints[world.task_joint]
    limits = (j.lower, j.upper) if math.isfinite(j.lower) and math.isfinite(j.upper) else (-math.inf, math.inf)
    for frame in frames:
        out = plan_push(kin, world, frame, s_rel, s1, q_from, cfg, rng, limits)
        if out[0] is not None:
            break
    else:
        timings["push"] = time.perf_counter() - t
        return PlanStatus.OPENING_FAILED, f"grasped opening to {s_rel:.3f}, then {out[1]}"
    q_pre, line, push, _ = out
    # the free move keeps the gripper clear of the door too (it is not grasped), unless its ends are too near
    for part in (True, False):
        world.keep_gripper_clear(True, part)
        try:
            qa, bad = _approach(world, q_from, q_pre, s_rel, cfg, seed, timings, t)
        finally:
            world.keep_gripper_clear(False)
        if not isinstance(qa, tuple) and bad < 0:
            break
    # (an opening failure: the next stand pose is tried, as after a failed grasped opening)
    if isinstance(qa, tuple):
        return PlanStatus.OPENING_FAILED, f"grasped opening to {s_rel:.3f}, then the move to the door's inner " \
                                          f"face: {qa[1]}"
    if bad >= 0:
        return PlanStatus.OPENING_FAILED, (f"grasped opening to {s_rel:.3f}, then the move to the door's inner face "
                                           f"collided ({_what(world, qa[bad], s_rel)})")
    reposition = np.concatenate([qa, line.q[1:]])
    # withdraw: back off along the approach axis from the face, the door where the push left it
    T_end = kin.tool_pose(push.q[-1])
    n = max(2, int(math.ceil(cfg.retreat_distance / 0.01)) + 1)
    T_back = np.array([_translate_tool(T_end, -cfg.retreat_distance * u) for u in np.linspace(0, 1, n)])
    lead = float(np.clip(s1 + (cfg.push_lead / frame.lever) * np.sign(s1 - s_rel), *limits))
    wd = track_poses(kin, world, T_back, np.full(n, lead), push.q[-1], np.ones(kin.spec.dof, bool),
                     ik_weights(kin, cfg, cfg.base_weight), cfg, False)
    timings["push"] = time.perf_counter() - t
    if not wd.success:
        return PlanStatus.OPENING_FAILED, f"grasped opening to {s_rel:.3f} and push to {s1:.3f}, then the " \
                                          f"withdrawal failed: {wd.reason}"
    return [Segment("reposition", reposition, np.full(len(reposition), s_rel), _fk_poses(kin, reposition), "open"),
            Segment("push", push.q, push.s, _fk_poses(kin, push.q), "open"),
            Segment("withdraw", wd.q, np.full(len(wd.q), s1), _fk_poses(kin, wd.q), "open")]


def _approach(world, q_start, q_pre, s0, cfg, seed, timings, t):
    """OMPL path from ``q_start`` to ``q_pre`` (task joint at ``s0``) densified at ``cfg.max_joint_step``:
    ``(q (n, dof), index of its first invalid sample or -1)``, or ``((PlanStatus, reason), -1)``."""
    lower, upper = world.robot.lower, world.robot.upper
    lo, hi = lower.copy(), upper.copy()
    span = np.array([1.0, 1.0, 1.0])
    lo[:3] = np.maximum(lower[:3], np.minimum(q_start[:3], q_pre[:3]) - span)
    hi[:3] = np.minimum(upper[:3], np.maximum(q_start[:3], q_pre[:3]) + span)

    def valid(q) -> bool:
        return not world.in_collision(q, s0, False)

    extent = float(np.linalg.norm(hi - lo))
    step = cfg.approach_check_step
    for attempt in range(cfg.approach_attempts):
        # OMPL checks edges at `step` (Euclidean in joint space); the returned path is re-checked at
        # cfg.max_joint_step per joint. A path that fails the dense re-check is planned again, finer.
        mr = plan_joint_path(q_start, q_pre, lo, hi, valid, time_limit=cfg.approach_time, seed=seed + attempt,
                             planner=cfg.approach_planner, resolution=step / extent)
        if not mr.success:
            timings["approach"] = time.perf_counter() - t
            return (PlanStatus.NO_PATH, f"approach: {mr.reason}"), -1
        path = mr.path.copy()
        path[0], path[-1] = q_start, q_pre   # exactly the requested ends (OMPL copies may differ in the last bit)
        qa, sa = densify(path, np.full(len(path), s0), cfg.max_joint_step)
        bad = first_invalid(world, qa, sa, False)
        if bad < 0:
            break
        log.debug("approach path collides at dense sample %d; planning again with half the step", bad)
        step /= 2
    timings["approach"] = time.perf_counter() - t
    return qa, bad


def _what(world, q, s) -> str:
    if not world.within_limits(q):
        return "joint limit"
    pairs = world.colliding_pairs(q, s, False)
    return "collision " + ", ".join(f"{a} / {b}" for a, b in pairs[:3]) if pairs else "collision"


#: how far (m or rad) a given start configuration may lie beyond a joint limit and still be planned from, moved
#: onto the limit: a robot that ended the previous task on a limit reads back a hair beyond it
_START_LIMIT_SLACK = 1e-3


#: the base's motion weight in the retreat relative to the opening's (the base stays near where it opened)
_RETREAT_BASE = 0.3


def _start_configuration(world, spec, stand: StandPose, start, cfg, s0):
    """The robot's start: given, or behind the stand pose with the arm at home."""
    if start is not None:
        q = np.asarray(start, float).reshape(-1)
        if q.shape != (spec.dof,):
            raise PlannerInputError(f"start configuration must have {spec.dof} values ({', '.join(spec.joint_names)}), "
                                    f"got shape {q.shape}")
        lower, upper = world.robot.lower, world.robot.upper
        if np.all(q >= lower - _START_LIMIT_SLACK) and np.all(q <= upper + _START_LIMIT_SLACK):
            q = np.clip(q, lower, upper)   # a measured start (the end of an executed task) sits on a limit
        if not world.within_limits(q):
            out = np.flatnonzero((q < world.robot.lower - LIMIT_TOLERANCE) | (q > world.robot.upper + LIMIT_TOLERANCE))
            i = int(out[0])
            return PlanStatus.START_IN_COLLISION, (
                f"start configuration outside the robot's joint limits: {spec.joint_names[i]} = {q[i]:.6g} not in "
                f"[{world.robot.lower[i]:.6g}, {world.robot.upper[i]:.6g}]")
        # a start resting on a limit up to rounding (physics) is moved onto it: the planner's box holds it
        q = np.clip(q, world.robot.lower, world.robot.upper)
        if world.in_collision(q, s0, False):
            return PlanStatus.START_IN_COLLISION, "start configuration in collision"
        return q
    x, y, yaw = stand.base
    for back in (cfg.start_backoff, cfg.start_backoff / 2, 0.0):
        q = spec.q_with_base(spec.home_q, x - back * math.cos(yaw), y - back * math.sin(yaw), yaw)
        if not world.in_collision(q, s0, False):
            return q
    return PlanStatus.START_IN_COLLISION, "no collision-free start behind the stand pose (arm at home)"
