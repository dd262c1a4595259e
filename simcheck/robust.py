"""Robust certification (``simcheck certify ... --robust N``): plan once on the estimate, then execute that
plan in N sampled worlds consistent with the scan, each with a fresh PyBullet world in a worker process or
a Ray task (:mod:`simcheck.robust_engine`), and certify only when the one-sided 95 % Clopper–Pearson lower bound on the success rate reaches
``min_success``.

* The nominal run is :func:`simcheck.certification.certify` itself (plan, independent re-check, execution
  on the estimate or on ``against``); its planner is wrapped to keep the plan.
* The spreads: recon's per-joint uncertainty (graph.json), the physics ranges and robot errors of
  ``spreads`` (defaults, or a ``--spreads FILE``: :mod:`simcheck.spreads_file`).
* Sample i is :func:`simcheck.perturbations.sample_perturbation` (seed, i) written as a URDF by
  :mod:`simcheck.perturbed_scene` (from the estimate; with ``against``, from the reference, physics ranges
  only), executed with the plan (the arm's position gain scaled by the sample's tracking factor; with the
  guarded approach, the rest of the plan corrected after the approach for the robot's base error and the
  handle's offset as re-perceived: :mod:`simcheck.robust_correction`) and judged by the same rollout criteria. A sample
  succeeds when every criterion passes.
* The task is certified when the nominal run is and the bound reaches ``min_success``; its certificate
  gets the ``"robust"`` block (:func:`simcheck.robust_verdict.robust_block`).
* ``replay_sample=i`` executes sample i alone, in this process (images, video and rollout as usual).
"""

from __future__ import annotations

import dataclasses
import logging
import tempfile
import time
from pathlib import Path

import numpy as np

from planners.task import SEGMENT_NAMES, parse_tasks
from scenes.description import file_stem, read_scene_floor
from scenes.outcome import Outcome
from simcheck.certification import SIDE_CAVEAT
from simcheck.perturbations import Perturbation, front_normal, in_front_plane, sample_perturbation
from simcheck.perturbed_scene import base_error_inverse, write_perturbed_scene
from simcheck.robust_correction import guarded_plan
from simcheck.robust_engine import choose_engine, run_samples
from simcheck.robust_spreads import JointSpreads, check_robust_args, joint_spreads_for, spreads_dict
from simcheck.spreads_file import load_spreads
from simcheck.robust_verdict import CONFIDENCE, SampleResult, robust_block, robust_outcome
from simcheck.scene_joints import read_scene_joints

__all__ = ["certify_robustly", "run_sample", "sample_plan"]

log = logging.getLogger(__name__)


class _PlanKeeper:
    """A planner that remembers the plan it returned for each task joint."""

    def __init__(self, planner):
        self.planner, self.plans = planner, {}
        self.robot_spec = getattr(planner, "robot_spec", None)

    def __call__(self, scene, task, seed, start=None, state=None):
        plan = self.planner(scene, task, seed, start, state)
        self.plans[task.joint] = plan if plan.ok else None
        return plan


def _pivot_xy(plan) -> tuple[float, float]:
    """Where the robot stands while it opens: base (x, y) -- the plan's first two joints -- at the start of
    its opening segment (``plan.opening_segment``; else of its first segment)."""
    seg = next((s for s in plan.segments if s.name == plan.opening_segment), plan.segments[0])
    q = np.asarray(seg.q, dtype=float)
    return float(q[0, 0]), float(q[0, 1])


def _handle_point(plan) -> np.ndarray:
    """(3,) world, where the plan grasps: the grasp segment's last tool position (else its last segment's)."""
    seg = next((s for s in plan.segments if s.name == SEGMENT_NAMES[1]), plan.segments[-1])
    return np.asarray(seg.T_world_tool[-1][:3, 3], dtype=float)


def run_sample(src: str, p: Perturbation, plan, requested: float, robot, physics, criteria, pivot,
               workdir: str | None = None, out: str | None = None, images: bool = False, video: bool = False,
               opening_type: str = "", opening_axis=None) -> SampleResult:
    """Execute ``plan`` in the world of perturbation ``p`` (built from scene ``src``) and judge it (``plan``
    as the robot runs it in that world: with the guarded approach's correction, :func:`sample_plan`).

    Runs in a worker process (the world is created and closed here). ``workdir``: where the sampled world's
    URDF is written (None: a temporary folder of this process, removed after). ``out``: a folder for the rollout /
    images of a replayed sample. ``opening_type``, ``opening_axis`` (3,): the planned joint's type and world
    axis toward which it opens (the estimate's, as plain ``certify`` measures the opening; turned with the
    sampled world's scene by its base error); None: the joint's own signed change. Returns the sample's
    outcome, reason and criterion margins.
    """
    from simcheck.criteria import rollout_criteria
    from simcheck.execute import execute_task
    from simcheck.world import World

    if workdir is None:
        with tempfile.TemporaryDirectory(prefix="partscene_sample_") as tmp:
            return run_sample(src, p, plan, requested, robot, physics, criteria, pivot, tmp, out, images, video,
                              opening_type, opening_axis)
    urdf = write_perturbed_scene(src, p, Path(workdir) / f"sample{p.index}.urdf", pivot)
    if opening_axis is not None:
        opening_axis = base_error_inverse(p.base_error, pivot)[:3, :3] @ np.asarray(opening_axis, dtype=float)
    phys = dataclasses.replace(physics, robot_position_gain=physics.robot_position_gain * p.tracking_gain)
    try:
        with World(urdf, robot, phys, floor=read_scene_floor(src)) as world:      # the sample on the room's floor
            camera = None
            if out is not None and (images or video):
                from simcheck.execute import handle_link_for
                from simcheck.keyframes import KeyFrameCamera

                handle = handle_link_for(world, plan.task.joint, plan.grasp_link)
                camera = KeyFrameCamera(world, world.scene_link_pose(handle)[:3, 3], np.array([*pivot, 1.0]),
                                        Path(out) / "images", f"sample{p.index}", video=video)
            rollout = execute_task(world, plan, phys, requested_amount=requested, opening_type=opening_type,
                                   opening_axis=opening_axis, frame_callback=camera.snap if camera else None,
                                   freeze_far=True)
            if out is not None:
                rollout.save(Path(out) / "rollouts" / f"{file_stem(plan.task.joint)}_sample{p.index}.npz")
                if camera is not None and video:
                    camera.save_video()
    except Exception as exc:       # a world that cannot be built or run is a failed sample, said why
        log.warning("sample %d: %s", p.index, exc)
        return SampleResult(p, Outcome.ERROR, f"sample {p.index} could not be executed: {exc}", {})
    crit = rollout_criteria(rollout, criteria)
    failed = [c for c in crit if not c.passed]
    reason = "; ".join(f"{c.name}: {c.detail}" for c in failed) if failed else "every criterion passed"
    return SampleResult(p, Outcome.FAILED if failed else Outcome.CERTIFIED, reason, {c.name: c.margin for c in crit})


def sample_plan(plan, p: Perturbation, pivot, kinematics=None):
    """``plan`` as the robot runs it in the world of ``p``: with the guarded approach's correction when ``p``
    has a re-perception (:func:`simcheck.robust_correction.guarded_plan`; ``kinematics``: the robot's
    :class:`planners.pin_world.RobotKinematics` on the scene's floor, which takes up the handle's vertical
    offset with the arm; None: not), else as planned."""
    if p.reperception is None:
        return plan
    return guarded_plan(plan, p.base_error, p.reperception, pivot, p.handle_shift, kinematics)


def _kinematics(robot, floor):
    """The planning robot's kinematics on ``floor`` (cached by the planner), or None for a robot that is not a
    :class:`planners.robot.RobotSpec` (a given plan's robot: its vertical offsets stay uncorrected)."""
    from planners.plan import robot_kinematics
    from planners.robot import RobotSpec

    return robot_kinematics(robot, floor) if isinstance(robot, RobotSpec) else None


def certify_robustly(certify, scene, tasks, *, robust: int, min_success: float, replay_sample: int | None,
                     against, seed: int, out, robot, planner, amounts, criteria, physics, planner_config,
                     images: bool, video: bool, gui: bool, workers: int | None = None, spreads=None,
                     engine: str = "auto", address: str | None = None):
    """:func:`simcheck.certification.certify` with ``robust`` sampled worlds per task (module docstring).

    certify : the plain certify function (called once, for the nominal run). spreads : the physics, robot
    and default joint spreads (None: the defaults; a YAML/JSON file or a ``RobustSpreads``:
    :func:`simcheck.spreads_file.load_spreads`). engine, workers, address : where the samples run
    (:mod:`simcheck.robust_engine`). Raises SimcheckInputError naming ``robust`` / ``min_success`` /
    ``replay_sample`` / ``engine``, a spreads file's field or a graph.json uncertainty field.
    """
    check_robust_args(robust, min_success)
    spreads_cfg = load_spreads(spreads)
    engine = choose_engine(engine, address)
    if replay_sample is not None and not (isinstance(replay_sample, int) and 0 <= replay_sample < robust):
        from simcheck.errors import SimcheckInputError
        raise SimcheckInputError(f"replay_sample: must be an integer in [0, {robust}), got {replay_sample!r}")
    t0 = time.perf_counter()
    scene = Path(scene)
    source = Path(against) if against is not None else scene
    joints = read_scene_joints(source)
    spreads = {}
    for task in parse_tasks(tasks, amounts):             # validate graph.json before any simulation
        sj = read_scene_joints(scene).get(task.joint)
        if sj is not None and sj.type in ("prismatic", "revolute") and against is None:
            spreads[task.joint] = joint_spreads_for(scene, task.joint, sj.type, spreads_cfg.joint_defaults)
    if planner is None:
        from simcheck.certification import planners_planner
        if robot is None:
            from planners.robot import default_robot
            robot = default_robot()
        planner = planners_planner(robot, planner_config)
    keeper = _PlanKeeper(planner)
    nominal = certify(scene, tasks, against=against, seed=seed, out=out, robot=robot, planner=keeper,
                      amounts=amounts, criteria=criteria, physics=physics, images=images and replay_sample is None,
                      video=video and replay_sample is None, gui=gui)
    from simcheck.robot_binding import sim_robot_from_spec
    sim_robot = sim_robot_from_spec(robot)
    out_tasks = []
    for tc in nominal.tasks:
        plan = keeper.plans.get(tc.joint)
        ref = joints.get(tc.joint)
        if plan is None or ref is None or ref.type not in ("prismatic", "revolute", "continuous"):
            out_tasks.append(tc)            # not planned / nothing to move: the nominal verdict stands
            continue
        mode = "physics" if against is not None else "scan"
        jspreads, centre = spreads.get(tc.joint, (JointSpreads(0.0, 0.0, 0.0, "reference (physics only)"), None))
        indices = [replay_sample] if replay_sample is not None else list(range(robust))
        perts = [sample_perturbation(i, seed, tc.joint, ref.type, ref.axis_world, ref.origin_world, ref.upper, centre,
                                     jspreads, spreads_cfg.physics, spreads_cfg.robot, mode) for i in indices]
        normal = front_normal(ref.type, ref.axis_world, ref.origin_world, _handle_point(plan))
        perts = [dataclasses.replace(p, handle_shift=in_front_plane(p.handle_shift, normal)) for p in perts]
        # measured as plain certify does (with --against too): the estimate's request along its opening
        # direction in the world, its axis reversed for a negative amount (a reference of the other sign
        # convention is matched by direction, not by the sign of its joint value)
        est = read_scene_joints(scene)[tc.joint]
        requested = abs(float(plan.amount))
        opening_type = "revolute" if est.type == "continuous" else est.type.value
        opening_axis = (1.0 if plan.amount >= 0 else -1.0) * np.asarray(est.axis_world, dtype=float)
        pivot = _pivot_xy(plan)
        t1 = time.perf_counter()
        kin = _kinematics(robot, read_scene_floor(source)) if any(p.reperception for p in perts) else None
        with tempfile.TemporaryDirectory(prefix="partscene_robust_") as tmp:
            args = [(str(source), p, sample_plan(plan, p, pivot, kin), requested, sim_robot, physics, criteria, pivot,
                     tmp, None, False, False, opening_type, opening_axis) for p in perts]
            if replay_sample is not None:
                results = [run_sample(*args[0][:9], out=None if out is None else str(out), images=images,
                                      video=video, opening_type=opening_type, opening_axis=opening_axis)]
            else:
                if engine == "ray":        # a Ray task writes its world in a folder of its own node
                    args = [(*a[:8], None, *a[9:]) for a in args]
                results = run_samples(run_sample, args, engine, workers, address)
        extra = {"min_success": min_success, "mode": mode, "engine": engine,
                 "spreads": spreads_dict(jspreads, spreads_cfg.physics, spreads_cfg.robot, spreads_cfg.source),
                 "seconds": time.perf_counter() - t1}
        if replay_sample is not None:
            extra["replayed_sample"] = replay_sample
        block = robust_block(results, CONFIDENCE, extra)
        ok = robust_outcome(block, min_success) is Outcome.CERTIFIED and tc.status is Outcome.CERTIFIED
        if replay_sample is not None:
            status, reason = results[0].outcome, f"replayed sample {replay_sample}: {results[0].reason}"
        else:
            status = Outcome.CERTIFIED if ok else Outcome.FAILED
            reason = (f"robust: {block['successes']} of {block['samples']} sampled worlds opened it; with "
                      f"{CONFIDENCE:.0%} confidence at least {block['success_lower_bound']:.3f} of such worlds do "
                      f"({'>=' if block['success_lower_bound'] >= min_success else '<'} {min_success:g}); "
                      f"nominal: {tc.status.value} -- {tc.reason.removesuffix(f'; {SIDE_CAVEAT}')}")
            if block["failures"]:
                f = block["failures"][0]
                reason += f"; first failing sample {f['sample']}: {f['reason']}"
        out_tasks.append(dataclasses.replace(tc, status=status, reason=reason, robust=block))
    cert = dataclasses.replace(nominal, tasks=tuple(out_tasks), path=None,
                               timings={**nominal.timings, "total": time.perf_counter() - t0},
                               seeds={**nominal.seeds, "robust_samples": robust})
    if out is not None:
        path = cert.write(out)
        cert = dataclasses.replace(cert, path=path)
    return cert
