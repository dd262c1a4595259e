"""Certify opening tasks: plan on the scene (the estimate), re-check the plan independently, execute it
with physics on the scene or on a reference (``against``), judge the rollout, write the certificate.

    cert = simcheck.certify("scene.urdf", ["open-drawer:cabinet3_drawer12_joint"], against="truth.urdf",
                            seed=0, out="out/")
    assert cert.ok, cert.summary()

Planning is pluggable: ``planner(scene_urdf, task, seed, start, scene_state) -> planners.PlanResult``
(``task`` a ``planners.OpenTask``); the default calls ``planners.plan_open_task``. The plan is executed
as the planner returned it.
"""

from __future__ import annotations

import dataclasses
import functools
import logging
import math
import time
from pathlib import Path
from typing import Callable

import numpy as np

from planners.config import PlannerConfig
from planners.errors import TaskSpecError
from planners.task import ALL_MOVABLE, OpenTask, PlanResult, PlanStatus, check_task, movable_joint_tasks, parse_tasks
from scenes.description import file_stem
from scenes.outcome import Outcome
from simcheck.certificate import Certificate, TaskCertificate, software_versions
from simcheck.config import DEFAULT_CRITERIA, DEFAULT_PHYSICS, CriteriaConfig, PhysicsConfig
from simcheck.criteria import CriterionResult, plan_collision_free, plan_found, rollout_criteria
from simcheck.errors import RobotBindingError, SimcheckInputError
from simcheck.estimate_diff import joint_differences, joint_mapping, measured_differences
from simcheck.execute import execute_task, handle_link_for
from simcheck.keyframes import KeyFrameCamera
from simcheck.plan_recheck import recheck_plan
from simcheck.robot_binding import SimRobot, sim_robot_from_spec
from simcheck.rollout import Rollout
from simcheck.scene_joints import read_scene_joints, read_scene_joints_and_links
from simcheck.world import World

__all__ = ["certify", "planners_planner", "Session", "outcome_of_unplanned"]

log = logging.getLogger(__name__)



def outcome_of_unplanned(status: PlanStatus) -> Outcome:
    """The task outcome when the planner returned ``status`` (not OK): ``unreachable`` when no base pose
    reaches the handle, ``not_planned`` for every other planning failure."""
    return Outcome.UNREACHABLE if status is PlanStatus.NO_STAND_POSE else Outcome.NOT_PLANNED


def planners_planner(robot_spec, config: PlannerConfig) -> Callable:
    """A planner function backed by ``planners.plan_open_task`` with ``robot_spec`` and ``config``; a start
    configuration in collision is replaced by the planner's own start."""
    from planners.plan import plan_open_task

    def plan(scene_urdf, task: OpenTask, seed: int, start=None, scene_state=None) -> PlanResult:
        result = plan_open_task(robot_spec, str(scene_urdf), task, seed=seed, start=start,
                                scene_state=scene_state, config=config)
        if start is not None and result.status is PlanStatus.START_IN_COLLISION:
            result = plan_open_task(robot_spec, str(scene_urdf), task, seed=seed, start=None,
                                    scene_state=scene_state, config=config)
        return result

    plan.robot_spec = robot_spec
    plan.config = config
    return plan


class Session:
    """Worlds for one certification run: the planning scene and (with ``against``) the reference.

    ``certify`` opens one Session per task, so each task is judged in freshly loaded worlds (its
    certificate does not depend on the tasks before it); a scenario runs all its tasks in one Session,
    the executed scene keeping its state from task to task. ``last_rollout`` is the rollout of the last
    task executed (None if it was not executed); ``load_seconds`` the wall time its worlds took to load.
    Without ``visuals`` the worlds have no visual shapes (faster to load; nothing can be rendered).
    """

    def __init__(self, scene: Path, against: Path | None, robot: SimRobot, physics: PhysicsConfig,
                 gui: bool = False, visuals: bool = True) -> None:
        t0 = time.perf_counter()
        self.scene, self.against, self.robot, self.physics = scene, against, robot, physics
        self.plan_world = World(scene, robot, physics, gui=gui and against is None, visuals=visuals)
        try:
            self.exec_world = (World(against, robot, physics, gui=gui, visuals=visuals) if against is not None
                               else self.plan_world)
        except Exception:
            self.plan_world.close()
            raise
        self.scene_joints, links = read_scene_joints_and_links(scene)
        self.ref_joints = read_scene_joints(against) if against is not None else self.scene_joints
        self.scene_links = set(links)
        self.last_rollout: Rollout | None = None
        self.save_plan, self.robot_label = False, "default"    # certify(save_plan=...): write out/plans/<joint>.plan.json
        self.freeze_far = False         # execute with the parts nothing can reach frozen (worlds closed after the task)
        self.load_seconds = time.perf_counter() - t0

    def close(self) -> None:
        self.plan_world.close()
        if self.exec_world is not self.plan_world:
            self.exec_world.close()

    def __enter__(self) -> "Session":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def exec_state(self) -> dict[str, float]:
        """Current values of the executed scene's movable joints that the planning scene also has."""
        out = {}
        for info in self.exec_world.scene_joints():
            if info.type in ("prismatic", "revolute") and info.name in self.scene_joints:
                out[info.name] = self.exec_world.scene_joint_state(info.name)[0]
        return out

    def sync_plan_world(self, state: dict[str, float]) -> None:
        """Set the planning scene's joints to ``state`` (kinematically; it is never executed on)."""
        if self.plan_world is not self.exec_world:
            for name, value in state.items():
                self.plan_world.reset_scene_joint(name, value)

    def open_for_close(self, task: OpenTask, config: PlannerConfig) -> None:
        """A close task starts with its part open: unless the executed scene has it open already, set its joint
        (kinematically, before the task) to where ``planners.close_start_value`` says the task starts, in the
        executed world (with ``--against``, the same opening along the reference joint's direction)."""
        if not task.close:
            return
        from planners.plan import close_start_value, closed_value
        from planners.scene_urdf import read_scene_urdf

        est, ref = self.scene_joints[task.joint], self.ref_joints.get(task.joint)
        if ref is None or ref.type not in ("prismatic", "revolute", "continuous"):
            return                                          # judged without execution (run_task)
        now = self.exec_world.scene_joint_state(task.joint)[0]
        start = close_start_value(read_scene_urdf(self.scene), task, now, config)
        if abs(start - now) > 1e-9:
            direction = joint_mapping(est, ref)["direction"] if self.against is not None else 1
            opening = start - closed_value(est.lower, est.upper)
            self.exec_world.reset_scene_joint(task.joint, closed_value(ref.lower, ref.upper) + direction * opening)

    def run_task(self, task: OpenTask, planner: Callable, seed: int, criteria: CriteriaConfig, out: Path | None,
                 images: bool, video: bool, start=None) -> TaskCertificate:
        """Plan, re-check, execute and judge one task (the worlds are left in their end state)."""
        t_all = time.perf_counter()
        self.last_rollout = None
        est = self.scene_joints[task.joint]
        state = self.exec_state()
        self.sync_plan_world(state)
        t = time.perf_counter()
        plan = planner(self.scene, task, seed, start, state)
        timings = {"plan": time.perf_counter() - t, "plan_collision_checks": plan.collision_checks}
        timings.update({f"planner_{k}": float(v) for k, v in plan.timings.items()})
        unit = est.unit
        if not plan.ok:
            timings["total"] = time.perf_counter() - t_all
            reason = f"not planned ({plan.status.name}): {plan.reason}"
            hints = joint_differences(est, self.ref_joints.get(task.joint)) if self.against is not None else []
            if hints:
                reason += " -- estimate vs reference: " + "; ".join(hints)
            return TaskCertificate(task.action, task.joint, outcome_of_unplanned(plan.status), reason,
                                   float(plan.amount), unit, (plan_found(False, plan.reason),), seed, timings,
                                   plan_status=plan.status.name, nearest_miss=plan.nearest_miss)
        if out is not None and self.save_plan and plan.method != "given":
            from simcheck.given_plan import given_from_result, plan_path
            from simcheck.plan_file import write_plan
            write_plan(given_from_result(plan, self.plan_world.robot_max_velocity(), self.physics, self.robot_label),
                       plan_path(out, file_stem(task.joint)))
        t = time.perf_counter()
        check = recheck_plan(self.plan_world, plan, criteria)
        timings["recheck"] = time.perf_counter() - t
        timings["recheck_states"] = check.n_states
        crit: list[CriterionResult] = [plan_found(True, plan.reason),
                                       plan_collision_free(check.max_depth, check.detail, criteria)]
        ref = self.ref_joints.get(task.joint)
        if ref is None or ref.type not in ("prismatic", "revolute", "continuous"):
            # the reference cannot move this part: nothing to execute; the estimate is wrong
            timings["total"] = time.perf_counter() - t_all
            what = "has no joint" if ref is None else f"has a {ref.type} joint"
            crit.append(CriterionResult("opened_fraction", 0.0, criteria.opened_fraction, ">=", "", False,
                                        -criteria.opened_fraction, "joint opening reached / requested",
                                        f"the reference {self.against} {what} {task.joint!r}: the part cannot open"))
            return self._judged(task, plan, crit, timings, seed, unit, None, [], est, ref)
        # the estimate's request, measured along its opening direction in the world: the joint axis, reversed
        # for a negative amount (a joint that opens toward its lower limit)
        sign = 1.0 if plan.amount >= 0 else -1.0
        requested = abs(float(plan.amount))
        camera = None
        w = self.exec_world
        if out is not None and (images or video):
            handle = handle_link_for(w, task.joint, plan.grasp_link)
            opening = [s for s in plan.segments if s.name == plan.opening_segment]
            path = np.concatenate([s.T_world_tool[:, :3, 3] for s in opening]) if opening else np.zeros((1, 3))
            camera = KeyFrameCamera(w, w.scene_link_pose(handle)[:3, 3], self._robot_side(plan), out / "images",
                                    file_stem(task.joint), video=video, part_size=float(np.ptp(path, axis=0).max()))
        counter = {"n": 0}
        given = plan.method == "given"
        traced = tuple(i.name for i in w.scene_joints() if i.type in ("prismatic", "revolute", "continuous")) if given else ()
        trace_rows: list[list[float]] = []

        def on_sample():
            counter["n"] += 1
            if camera is not None and video and counter["n"] % 15 == 0:
                camera.frame()
            if given:
                trace_rows.append([w.scene_joint_state(n)[0] for n in traced])

        t, c0 = time.perf_counter(), time.process_time()
        rollout = execute_task(w, plan, self.physics, requested_amount=requested,
                               opening_type="revolute" if est.type == "continuous" else est.type.value,
                               opening_axis=sign * np.asarray(est.axis_world, dtype=float),
                               closing=task.close, joint_range=float(ref.upper - ref.lower),
                               frame_callback=camera.snap if camera else None,
                               sample_callback=on_sample if given or camera is not None and video else None,
                               freeze_far=self.freeze_far)
        self.last_rollout = rollout
        timings["execute"] = time.perf_counter() - t
        timings["execute_cpu"] = time.process_time() - c0
        timings["simulated"] = rollout.duration
        crit.extend(rollout_criteria(rollout, criteria))
        if given:
            from simcheck.given_plan import given_criteria
            from simcheck.plan_expectations import ArticulationTrace
            trace = ArticulationTrace(traced, np.asarray(trace_rows, dtype=float).reshape(rollout.n, len(traced)),
                                      rollout.t, rollout.segment, rollout.segment_names,
                                      tuple("m" if w.scene_joint(n).type == "prismatic" else "rad" for n in traced))
            crit.extend(given_criteria(plan, trace, w.robot_max_velocity(), self.robot.max_acceleration, criteria,
                                       dict(zip(rollout.robot_joint_names, rollout.robot_joint_units))))
        rel_rollout, rel_images = "", []
        if out is not None:
            path = rollout.save(out / "rollouts" / f"{file_stem(task.joint)}.npz")
            rel_rollout = str(path.relative_to(out))
            if camera is not None:
                gif = camera.save_video() if video else None
                rel_images = [str(p.relative_to(out)) for p in camera.paths + ([gif] if gif else [])]
        timings["total"] = time.perf_counter() - t_all
        blockers = sorted(set(rollout.object_contact_link[rollout.object_contact_force > criteria.contact_force_tolerance])
                          - {rollout.handle_link})
        return self._judged(task, plan, crit, timings, seed, unit, rel_rollout, rel_images, est, ref, blockers)

    def _robot_side(self, plan: PlanResult) -> np.ndarray:
        """Where the robot starts (its first tool position): the camera looks from that side."""
        return plan.segments[0].T_world_tool[0][:3, 3]

    def _judged(self, task, plan, crit, timings, seed, unit, rollout, images, est, ref, blockers=()) -> TaskCertificate:
        failed = [c for c in crit if not c.passed]
        if not failed:
            graded = [c for c in crit if c.name != "plan_found"]
            worst = min(graded, key=lambda c: c.margin / abs(c.threshold) if c.threshold else c.margin)
            reason = (f"{len(crit)} criteria passed; smallest relative margin: {worst.name} "
                      f"({worst.value:.3g} vs {worst.comparison} {worst.threshold:.3g})")
            status = Outcome.CERTIFIED
        else:
            status = Outcome.FAILED
            evidence = "; ".join(f"{c.name}: {c.detail}" for c in failed)
            hints = []
            if self.against is not None:
                hints = joint_differences(est, ref)
                if self.last_rollout is not None and any(c.name in FORCE_CRITERIA for c in failed):
                    measured = measured_differences(est, ref, _grasped_point(self.last_rollout), plan.amount)
                    hints += [measured] if measured else []
                hints += [f"reference link {b} (absent from the estimate) blocked {task.joint}"
                          for b in blockers if b not in self.scene_links]
            hints += [f"scene link {b} blocked {task.joint}" for b in blockers if b in self.scene_links]
            reason = (f"{'; '.join(hints)} -- evidence: {evidence}" if hints else evidence)
        if plan.method == "given":                # say whose plan was judged: "given plan FILE, segment 'open'"
            reason = f"{plan.reason}: {reason}"
        return TaskCertificate(task.action, task.joint, status, reason, float(plan.amount), unit, tuple(crit), seed,
                               timings, rollout or "", tuple(images), plan_status="OK")


#: criteria that fail when the robot had to push or pull harder than it may: with ``--against``, their failure
#: names the estimate's measured differences from the reference even within estimate_diff's tolerances
FORCE_CRITERIA = ("grasp_force", "interaction_force", "robot_joint_effort")


def _grasped_point(r: Rollout) -> np.ndarray:
    """(3,) world, m: the grasped point of the handle when the opening started (the handle link's origin at the
    first sample when no grasp was made)."""
    held = np.flatnonzero(r.in_segment(r.opening_segment) & np.all(np.isfinite(r.grasp_point), axis=1))
    return r.grasp_point[held[0]] if len(held) else r.T_world_handle[0, :3, 3]


def _robot_label(save_plan: bool | str) -> str:
    """The robot a saved plan names: ``save_plan`` when it is a robot spec path, else "default"."""
    return save_plan if isinstance(save_plan, str) and save_plan else "default"


def _recorded_path(path, out_dir: Path | None) -> str:
    """``path`` as the certificate records it: relative to the certificate's folder when it lies inside it
    (the folder may be renamed into place: ``scenes.output_folder``), else as given."""
    if out_dir is not None:
        try:
            return str(Path(path).resolve().relative_to(Path(out_dir).resolve()))
        except ValueError:
            pass
    return str(path)


def certified_files(files: dict, out_dir: Path | None) -> dict:
    """``{role: {"path": recorded path, "sha256": hex}}`` of the existing files in ``files`` (role -> path or None)."""
    from scenes.output_folder import file_sha256

    return {role: {"path": _recorded_path(p, out_dir), "sha256": file_sha256(p)}
            for role, p in files.items() if p is not None and Path(p).is_file()}


SIDE_CAVEAT = ("the scan leaves this door's hinge side undecided (graph.json: side_undecided): it was certified "
               "hinged at the estimated edge only; a robust certificate (--robust N) hinges half of its worlds at "
               "the other edge, or certify --against a reference")
"""Appended to the reason of a door certified on an estimate whose hinge side recon left undecided."""


def _with_side_caveat(scene: Path, cert: TaskCertificate) -> TaskCertificate:
    """``cert`` with :data:`SIDE_CAVEAT` after its reason when it certifies a door of ``scene`` (an estimate,
    no reference) whose hinge side graph.json beside it flags undecided (:mod:`simcheck.hinge_side`)."""
    if cert.status is not Outcome.CERTIFIED or not cert.kind.endswith("door"):
        return cert
    from simcheck.robust_spreads import joint_spreads_for

    _, centre = joint_spreads_for(scene, cert.joint, "revolute")
    if centre is None or centre.other_origin is None:
        return cert
    log.warning("%s: %s", cert.joint, SIDE_CAVEAT)
    return dataclasses.replace(cert, reason=f"{cert.reason}; {SIDE_CAVEAT}")


def _run_task(session: Session, task: OpenTask, planner: Callable, seed: int, criteria: CriteriaConfig,
              out_dir: Path | None, images: bool, video: bool, start, load_seconds: float | None) -> TaskCertificate:
    """Certify ``task`` in ``session``'s worlds as they are now; the certificate records the start state
    (the executed scene's joints, the robot's configuration: see :class:`TaskCertificate`) and, when the
    worlds were loaded for it, their loading time (``timings["load_worlds"]``, s)."""
    log.info("certifying %s on %s%s", task, session.scene, f" against {session.against}" if session.against else "")
    session.open_for_close(task, getattr(planner, "config", PlannerConfig()))
    state = session.exec_state()
    q_now = session.exec_world.robot_q()
    cert = session.run_task(task, planner, seed, criteria, out_dir, images, video, start=start)
    q0 = session.last_rollout.robot_q[0] if session.last_rollout is not None else q_now
    timings = cert.timings if load_seconds is None else {**cert.timings, "load_worlds": load_seconds}
    mapping = (joint_mapping(session.scene_joints[task.joint], session.ref_joints.get(task.joint))
               if session.against is not None else None)
    cert = dataclasses.replace(cert, start_state=state, timings=timings, reference_joint=mapping,
                               start_robot_q=dict(zip(session.robot.joint_names, map(float, q0))))
    log.info("%s: %s -- %s", task, cert.status.value, cert.reason)
    return cert


def certify(scene, tasks, *, against=None, seed: int = 0, out=None, robot=None, planner: Callable | None = None,
            amounts=None, criteria: CriteriaConfig = DEFAULT_CRITERIA, physics: PhysicsConfig = DEFAULT_PHYSICS,
            planner_config: PlannerConfig = PlannerConfig(), images: bool = True, video: bool = False,
            gui: bool = False, carry_state: bool = False, robust: int | None = None, min_success: float = 0.9,
            replay_sample: int | None = None, save_plan: bool | str = False, files=None, froms=None,
            spreads=None, robust_engine: str = "auto", address: str | None = None) -> Certificate:
    """Certify each task on ``scene``; returns the :class:`Certificate` (written to ``out`` if given).

    Args:
        scene: the scene URDF to plan on (an estimate, or a truth).
        tasks: task strings ("open-drawer:JOINT", "open-door:JOINT", optionally "=AMOUNT", see
            ``planners.parse_task``) or ``planners.OpenTask``; or ``"all-movable"``: every drawer and door of
            ``scene`` (``planners.movable_joint_tasks``), the movable joints without an opening range logged
            and listed in ``Certificate.untested``.
        against: a reference URDF to execute on instead of ``scene`` (joints matched by name).
        seed: planning seed (physics is deterministic).
        out: folder for certificate.json, rollouts/ and images/ (None: nothing written).
        robot: a ``planners.RobotSpec`` (or :class:`SimRobot` together with ``planner``); default robot if None.
        planner: ``planner(scene, task, seed, start, scene_state) -> planners.PlanResult``; default planners'.
        planner_config: the default planner's parameters (unused with ``planner``).
        amounts: one amount for all tasks or one per task (m or rad), for opening tasks without one.
        froms: the same for how far open the close tasks (``close-drawer``, ``close-door``) start (``--from``;
            default: what an opening would request). A close task's part is set open before the task
            (:meth:`Session.open_for_close`) unless it is open already.
        carry_state: run the tasks one after the other in one world, its state carried from task to task
            (a scenario); by default each task is judged in freshly loaded worlds.
        robust: execute each task's plan in this many worlds sampled from the scan's uncertainty, physics
            ranges and robot errors too; certified only if the 95 % lower bound on the success rate reaches
            ``min_success`` (:mod:`simcheck.robust`). ``replay_sample``: run only that sample.
        spreads: with ``robust``, the physics / robot / default joint spreads: a YAML or JSON file
            (:mod:`simcheck.spreads_file`) or a ``RobustSpreads``; None: the defaults.
        robust_engine, address: with ``robust``, where the sampled executions run: "processes", "ray" (the
            Ray at ``address``, else a local one) or "auto" (:mod:`simcheck.robust_engine`).
        save_plan: write each planned task's plan, timed as the executor runs it, to
            ``out/plans/<joint>.plan.json`` (``partscene.plan/1``; replay it with :func:`simcheck.certify_plan`);
            a string is the robot spec recorded in the file (True: "default").
        files: more files the run was judged on, by role ({"scenario": path}, {"robot_spec": path}); the
            certificate records every such file's sha256, with the scene's, the reference's and the robot's.

    Raises:
        SimcheckInputError (SceneLoadError, RobotBindingError) and ``planners.PlannerInputError``
            (TaskSpecError, HandleNotFoundError, ...): unusable input, naming the file and joint.
    """
    if isinstance(tasks, str) and tasks == ALL_MOVABLE:
        tasks, untested = movable_joint_tasks(read_scene_joints(scene), scene)
        for joint, why in untested.items():
            log.warning("%s: not tested: %s", joint, why)
        if not tasks:
            raise TaskSpecError(f"{scene}: no drawer or door with an opening range to certify"
                                f"{f' (untested: {sorted(untested)})' if untested else ''}")
        cert = certify(scene, tasks, against=against, seed=seed, out=out, robot=robot, planner=planner,
                       amounts=amounts, criteria=criteria, physics=physics, planner_config=planner_config,
                       images=images, video=video, gui=gui, carry_state=carry_state, robust=robust,
                       min_success=min_success, replay_sample=replay_sample, save_plan=save_plan,
                       files=files, spreads=spreads, robust_engine=robust_engine, address=address)
        if not untested:
            return cert
        cert = dataclasses.replace(cert, untested=untested)
        return dataclasses.replace(cert, path=cert.write(cert.path.parent)) if cert.path is not None else cert
    if froms:
        tasks = parse_tasks(tasks, None, froms)
    if (spreads is not None or robust_engine != "auto" or address is not None) and robust is None:
        raise SimcheckInputError("spreads / robust_engine / address: they set how --robust samples and runs its "
                                 "worlds; give --robust N too")
    if robust is not None or replay_sample is not None:
        closing = [str(t) for t in parse_tasks(tasks) if t.close]
        if closing:
            raise TaskSpecError(f"--robust certifies opening tasks only; {', '.join(closing)} would start closed "
                                f"in the sampled worlds: certify close tasks without --robust")
        from simcheck.robust import certify_robustly
        return certify_robustly(functools.partial(certify, save_plan=save_plan, files=files), scene, tasks,
                                robust=robust, min_success=min_success,
                                replay_sample=replay_sample, against=against, seed=seed, out=out, robot=robot,
                                planner=planner, amounts=amounts, criteria=criteria, physics=physics,
                                planner_config=planner_config, images=images, video=video, gui=gui,
                                spreads=spreads, engine=robust_engine, address=address)
    t0 = time.perf_counter()
    scene = Path(scene)
    against = Path(against) if against is not None else None
    parsed = parse_tasks(tasks, amounts)
    joints = read_scene_joints(scene)
    for task in parsed:
        check_task(task, joints, scene)
    if against is not None:
        read_scene_joints(against)
    if planner is None:
        if isinstance(robot, SimRobot):
            raise RobotBindingError(f"certify: robot {robot.urdf} is a SimRobot; the default planner needs a "
                                    "planners.RobotSpec (or pass planner=...)")
        if robot is None:
            from planners.robot import default_robot
            robot = default_robot()
        planner = planners_planner(robot, planner_config)
    if robot is None:
        raise ValueError("certify: a custom planner needs its robot (robot=...)")
    sim_robot = sim_robot_from_spec(robot)
    out_dir = Path(out) if out is not None else None
    if out_dir is not None and (out_dir / "certificate.json").is_file():
        # a run that fails from here on must not leave the previous run's verdict in place
        log.info("removing the previous %s", out_dir / "certificate.json")
        (out_dir / "certificate.json").unlink()
    results = []
    visuals = out_dir is not None and (images or video)     # key frames and video are the only renderings
    if carry_state:
        with Session(scene, against, sim_robot, physics, gui=gui, visuals=visuals) as session:
            session.save_plan, session.robot_label = bool(save_plan), _robot_label(save_plan)
            for i, task in enumerate(parsed):
                start = session.exec_world.robot_q() if i else None
                results.append(_run_task(session, task, planner, seed, criteria, out_dir, images, video, start,
                                         None if i else session.load_seconds))
    else:
        for task in parsed:                       # fresh worlds: a task's verdict never depends on the others
            with Session(scene, against, sim_robot, physics, gui=gui, visuals=visuals) as session:
                session.save_plan, session.robot_label = bool(save_plan), _robot_label(save_plan)
                session.freeze_far = not gui
                results.append(_run_task(session, task, planner, seed, criteria, out_dir, images, video, None,
                                         session.load_seconds))
    if against is None:
        results = [_with_side_caveat(scene, c) for c in results]
    certificate = Certificate(tasks=tuple(results), scene=_recorded_path(scene, out_dir),
                              against=_recorded_path(against, out_dir) if against else None,
                              robot=str(sim_robot.urdf), criteria=criteria.to_dict(), seeds={"seed": seed},
                              versions=software_versions(), timings={"total": time.perf_counter() - t0},
                              files=certified_files({"scene": scene, "against": against, "robot": sim_robot.urdf,
                                                     **(files or {})}, out_dir),
                              robot_joint_stiffness={n: float(k) if math.isfinite(k) else None
                                                     for n, k in sim_robot.joint_stiffness})
    if out_dir is not None:
        path = certificate.write(out_dir)
        certificate = Certificate(**{**certificate.__dict__, "path": path})
    return certificate
