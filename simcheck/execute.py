"""Execution with physics: drive the robot through a plan in a :class:`World` and record a :class:`Rollout`.

How the robot is driven: every segment's waypoints are time-parametrised so that no joint exceeds
``speed_scale`` x its URDF velocity limit (capped at ``max_joint_speed``; the opening segment is slower
by ``open_speed_scale``, the approach to the pre-grasp faster by ``approach_speed_scale``:
:func:`segment_timing`); at every physics step (160 Hz) the robot's joints get a position target and a
feed-forward velocity (PyBullet position control with the joints' URDF effort limits). The scene's joints
are never set during a task: the object moves only because the robot pushes or pulls it.

How the grasp is made -- what the robot's gripper can do, not a weld. After the grasp segment the fingers
close; a grasp forms only where a real two-finger gripper holds (:func:`simcheck.grasp.grasp_formation`
on PyBullet's contact points): both finger pads touch the handle from opposite sides, against their
closing directions, and the fingers were stopped by the handle, not fully closed. Then the grasped point
of the handle is held to the tool frame's origin by a spring (forces applied every physics step,
:meth:`World.attach`): the compliance of the real arm following the plan under its joint impedance -- the
tool's Cartesian stiffness ``(J C_q J^T)^-1`` at the current configuration from the robot's
``joint_stiffness`` (else an isotropic ``grasp_stiffness``), damped by ``grasp_damping`` (a rigid grasp on
the stiff position-controlled simulated arm presses forces through the handle that no compliant real arm
produces; docs/decisions.md). The spring force is capped at
what pad friction holds: the robot spec's ``GripperModel`` gives ``F = 2 * mu * grip force``; above it the
handle slides in the fingers. The force the spring needed (before the cap) is recorded every step
(``grasp_force``: its 50 ms running mean); the grasp transmits no torque (a two-pad grip resists about
1 N*m): the handle turns in the fingers, and the grasp is lost when it has turned more than
``grasp_max_turn`` or the grasped point drifts more than ``grasp_break_distance`` from the tool. A round bar
held across its axis (a cylinder of the handle link longer than its diameter, both pads on its round side:
:func:`simcheck.grasp.round_bar_axis`) is held at its axis, and its roll about that axis is not counted as a
turn: flat pads let a cylinder roll, resisting it only by friction over its radius (at most
``2 * pad_friction * grip_force * radius``; the spring on the axis transmits none, so the door turns under
its own weight and the pull alone). A turn of that axis against the pads still counts, as every turn of a
rectangular bar, a knob or a mesh handle does.

Why a modelled grasp and not finger friction: in PyBullet a pure friction grasp of a thin handle pulled a
drawer when the base moved but slipped when the arm pulled, unless handle friction, finger force and
finger coupling were tuned per object; the modelled grasp holds exactly what the gripper
holds on any handle.
"""

from __future__ import annotations

import logging
import time
from collections import defaultdict

import numpy as np

from planners.handle import handle_link
from planners.scene_urdf import read_scene_urdf
from planners.task import PUSH_SEGMENT_NAMES, SEGMENT_NAMES, PlanResult, Segment
from scenes.small_linalg import norm as vector_norm
from simcheck.config import DEFAULT_PHYSICS, PhysicsConfig
from simcheck.frozen_bodies import FreezeGuard, far_parts
from simcheck.grasp import grasp_formation, round_bar_axis
from simcheck.rollout import Rollout
from simcheck.world import World

__all__ = ["execute_task", "handle_link_for", "moving_link_for", "timed_waypoints", "waypoint_timing", "speed_limits",
           "segment_timing", "command_trajectory"]

log = logging.getLogger(__name__)

APPROACH, GRASP, OPEN, RELEASE, _ = SEGMENT_NAMES
_, PUSH, _ = PUSH_SEGMENT_NAMES


def moving_link_for(world: World, joint: str) -> str:
    """The child link of scene joint ``joint``."""
    return world.scene_joint(joint).child_link


def handle_link_for(world: World, joint: str, preferred: str | None = None) -> str:
    """The scene link to grasp to move ``joint`` of ``world``'s scene: ``preferred`` (the plan's grasp link)
    when the scene has it, else the planner's rule (:func:`planners.handle.handle_link`) on the world's URDF."""
    if preferred and world.has_scene_link(preferred):
        return preferred
    return handle_link(read_scene_urdf(world.scene_urdf), joint)


def timed_waypoints(q: np.ndarray, vmax: np.ndarray, min_dt: float, ramp: float = 0.0,
                    tool: np.ndarray | None = None, control_dt: float = 0.0) -> np.ndarray:
    """(n,) times, seconds, at which to reach the (n, dof) waypoints ``q`` so that joint j never
    exceeds ``vmax[j]`` (rad/s or m/s) on the straight segments between waypoints; starts at 0.

    With ``ramp`` > 0 s the speed along the path also changes at most as fast as the executor's ramp at a
    segment's ends changes it (from rest to full speed in ``ramp`` seconds; :func:`_ramped`), and it is
    slowed before a waypoint where the velocity must change at once (see :func:`waypoint_timing`, which
    also gives how the executor accelerates inside each piece)."""
    return waypoint_timing(q, vmax, min_dt, ramp, tool, control_dt)[0]


def waypoint_timing(q: np.ndarray, vmax: np.ndarray, min_dt: float, ramp: float = 0.0,
                    tool: np.ndarray | None = None, control_dt: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """How the executor times a path of (n, dof) waypoints ``q``: ``(times (n,) s, rho (n-1,))``.

    Without ``ramp`` every piece between waypoints is run at constant velocity, as fast as ``vmax`` (dof,)
    allows (at least ``min_dt`` s): ``rho`` is 0.5. With ``ramp`` > 0 s the path speed ``sigma`` (1: the
    limiting joint at its ``vmax``) is continuous inside the path and changes by at most 1 per ``ramp``
    seconds -- the acceleration of the segment's own start (:func:`_ramped`), which a real arm's trajectory
    generator also bounds: a grasped part is not jerked to another speed -- and it is lowered at a waypoint
    where the velocity turns (it changes there within one control step):

    * the tool's velocity (``tool`` (n, 3) planned tool positions, m) changes there by at most the tool's
      full speed per ``ramp`` times ``control_dt`` (what the grasped part feels: a door whose planned arc
      hands over from the base to the arm slows before the hand-over instead of being stopped in one step);
    * each joint's velocity changes by at most its full speed per ``ramp`` times half of the two pieces
      meeting there (a joint that reverses slows down first; the arm's own small zig-zags along a dense path
      are not stopped for).

    Inside piece i the path accelerates uniformly from ``sigma`` at its start to ``sigma`` at its end: its
    fraction covered after a share ``x`` of its duration is ``2 rho x + (1 - 2 rho) x^2``,
    ``rho = sigma_start / (sigma_start + sigma_end)``."""
    q = np.atleast_2d(q)
    if len(q) == 1:
        return np.zeros(1), np.zeros(0)
    w = np.diff(q, axis=0) / vmax[None, :]
    L = np.abs(w).max(axis=1)
    dt = np.maximum(L, min_dt)
    rho = np.full(len(dt), 0.5)
    moving = np.flatnonzero(L > 1e-12)
    if ramp > 0 and len(moving) > 1:
        Lm = L[moving]
        u = w[moving] / Lm[:, None]
        cap2 = np.ones(len(moving) + 1)
        with np.errstate(divide="ignore", invalid="ignore"):
            turn = np.abs(np.diff(u, axis=0)).max(axis=1)
            cap2[1:-1] = np.minimum(1.0, (Lm[:-1] + Lm[1:]) / (2.0 * ramp * turn))
            if tool is not None and control_dt > 0:
                g = np.diff(np.asarray(tool, dtype=float), axis=0)[moving] / Lm[:, None]  # m per s at sigma 1
                top = float(np.linalg.norm(g, axis=1).max())
                jump = np.linalg.norm(np.diff(g, axis=0), axis=1)
                if top > 0:
                    cap2[1:-1] = np.minimum(cap2[1:-1], (top / ramp * control_dt / jump) ** 2)
        s2 = cap2.tolist()
        grow = (2.0 * Lm / ramp).tolist()
        for k in range(1, len(s2)):                 # speeding up: sigma^2 grows by at most 2 L / ramp a piece
            s2[k] = min(s2[k], s2[k - 1] + grow[k - 1])
        for k in range(len(s2) - 2, -1, -1):        # slowing down, backwards
            s2[k] = min(s2[k], s2[k + 1] + grow[k])
        sigma = np.sqrt(np.asarray(s2))
        dt[moving] = np.maximum(2.0 * Lm / (sigma[:-1] + sigma[1:]), min_dt)
        rho[moving] = sigma[:-1] / (sigma[:-1] + sigma[1:])
    return np.concatenate([[0.0], np.cumsum(dt)]), rho


class _Recorder:
    """Accumulates samples; contacts are aggregated (max force/depth per pair) between samples."""

    def __init__(self, world: World, joint: str, moving: str, handle: str, config: PhysicsConfig) -> None:
        self.world, self.joint, self.moving, self.handle, self.config = world, joint, moving, handle, config
        self.rows = defaultdict(list)
        self.contacts: dict = {}
        self.obj_contacts: dict = {}
        self.contact_rows: list = []
        self.obj_rows: list = []
        self.rest_pairs = world.rest_contacts_of(moving)
        self.rest_excess, self.rest_worst, self.rest_worst_excess = 0.0, "", 0.0
        self.t = 0.0
        self.steps = 0
        self.segment = -1
        self.planned_tool = np.full(3, np.nan)
        self.planned_object_q = np.nan
        self.T_handle_grasp: np.ndarray | None = None
        self.roll_axis: np.ndarray | None = None       # a held round bar's axis, grasp-time tool frame
        self.sample_callback = None
        self.holding_force = world.robot_spec.gripper.holding_force
        self.slid = False
        self.window = max(1, int(round(config.grasp_force_window / config.time_step)))
        self.history = np.zeros(self.window)           # per step: |f|, N (a ring buffer)
        self.filled = 0
        self.mean = 0.0                                 # running mean of the history (0 when detached)
        self.peak = 0.0                                 # largest running mean since the last sample
        dof = len(world.robot_spec.joint_names)
        self.effort_history = np.zeros((self.window, dof))  # per step: |motor torque| / effort limit
        self.effort_peak = np.zeros(dof)                 # largest running mean since the last sample
        self.torques: list = []                          # per step since the history was last brought up to date
        self.ring_rows: dict = {}                        # (first slot, steps) -> _ring_rows
        self.tool_link = world.robot_spec.tool_link
        self.sampled_at = -1                              # the step of the last sample
        self.guard = None                                 # a FreezeGuard when parts are frozen

    def grasp_point(self, T_world_handle: np.ndarray | None = None) -> np.ndarray:
        """(3,) world position of the grasped point of the handle (NaN when not attached);
        ``T_world_handle`` (4, 4) when the caller already has it."""
        if self.T_handle_grasp is None or not self.world.attached:
            return np.full(3, np.nan)
        T = self.world.scene_link_pose(self.handle) if T_world_handle is None else T_world_handle
        return T[:3, :3] @ self.T_handle_grasp[:3, 3] + T[:3, 3]

    def turn(self, T_world_handle: np.ndarray | None = None, T_world_tool: np.ndarray | None = None) -> float:
        """Angle, rad, by which the handle has turned in the fingers since the grasp (0 when not attached);
        of a held round bar (``roll_axis``), the angle its axis has turned against the pads (its roll about
        the axis is left out). ``T_world_handle``, ``T_world_tool`` (4, 4): the poses now, when the caller
        already has them."""
        if self.T_handle_grasp is None or not self.world.attached:
            return 0.0
        T = self.world.scene_link_pose(self.handle) if T_world_handle is None else T_world_handle
        R_tool = (self.world.robot_link_pose(self.tool_link) if T_world_tool is None else T_world_tool)[:3, :3]
        R = (T[:3, :3] @ self.T_handle_grasp[:3, :3]).T @ R_tool
        c = self.roll_axis @ R @ self.roll_axis if self.roll_axis is not None else (np.trace(R) - 1.0) / 2.0
        return float(np.arccos(min(max(c, -1.0), 1.0)))

    def slip_and_turn(self) -> tuple[float, float]:
        """(distance, m, from the grasped point of the handle to the tool origin; :meth:`turn`, rad) now: the
        values this step's sample recorded when one was just taken (the same world state), else read."""
        r = self.rows
        if self.sampled_at == self.steps and r["t"]:
            return vector_norm(r["grasp_point"][-1] - r["tool_pos"][-1]), r["grasp_turn"][-1]
        tool = self.world.robot_link_position(self.world.robot_spec.tool_link)
        return vector_norm(self.grasp_point() - tool), self.turn()

    def held_round_bar(self, pads: np.ndarray | None, closing: np.ndarray) -> np.ndarray | None:
        """(3,) world point on the axis of the round bar the pads hold across its axis, else None; sets
        ``roll_axis`` (the axis in the tool frame now). ``pads`` (2, 3) the pads' contact points, ``closing``
        (3,) a finger's closing direction, world frame."""
        self.roll_axis = None
        if pads is None:
            return None
        model = read_scene_urdf(self.world.scene_urdf)
        if self.handle not in model.links:
            return None
        cylinders = [(s.T_link_shape, s.radius, s.length) for s in model.links[self.handle].collisions
                     if s is not None and s.kind == "cylinder"]
        T = self.world.scene_link_pose(self.handle)
        R, p = T[:3, :3], T[:3, 3]
        bar = round_bar_axis((np.asarray(pads) - p) @ R, R.T @ np.asarray(closing, dtype=float), cylinders,
                             tolerance=self.config.grasp_roll_tolerance, max_angle=self.config.grasp_roll_angle)
        if bar is None:
            return None
        R_tool = self.world.robot_link_pose(self.world.robot_spec.tool_link)[:3, :3]
        self.roll_axis = R_tool.T @ (R @ bar[0])
        return R @ bar[1] + p

    def track_force(self) -> None:
        """Read the grasp's force of this step into the running mean (reset when detached)."""
        if not self.world.attached:
            if self.filled:
                self.history[:] = 0.0
                self.filled = 0
                self.mean = 0.0
            return
        self.history[self.filled % self.window] = self.world.grasp_force()
        self.filled += 1
        self.mean = float(self.history.sum()) / self.window     # steps before the grasp count as 0
        self.peak = max(self.peak, self.mean)

    def track_effort(self) -> None:
        """Read the robot motors' torques of this step (:meth:`update_effort` takes them into the running means)."""
        self.torques.append(self.world.robot_torques())

    def update_effort(self) -> None:
        """Take the torques of the steps since the last update (:meth:`track_effort`) into the motors' running
        means of |torque| / effort limit over the force window (``effort_history``, a ring buffer with a
        row per step) and their peak since the last sample (``effort_peak``): the same numbers as one update
        per step (the window's rows are summed in the same order), with numpy called once for them all."""
        if not self.torques:
            return
        m, window = len(self.torques), self.window
        share = np.abs(np.array(self.torques, dtype=float)) / self.world.robot_effort_limits     # (m, dof)
        self.torques = []
        key = ((self.steps - m + 1) % window, m)
        if key not in self.ring_rows:
            self.ring_rows[key] = _ring_rows(*key, window)
        rings = np.concatenate((self.effort_history, share))[self.ring_rows[key]]    # (m, window, dof)
        # the largest mean is the largest sum over the window (the division by it is monotonic)
        np.maximum(self.effort_peak, rings.sum(axis=1).max(axis=0) / window, out=self.effort_peak)
        self.effort_history = rings[-1]

    def after_step(self) -> None:
        w = self.world
        self.t += self.config.time_step
        self.steps += 1
        self.track_force()
        self.track_effort()
        if self.steps % self.config.contact_every == 0:
            for c in w.robot_contacts(self.config.contact_tolerance):
                key = (c.link_a, c.link_b)
                f, d = self.contacts.get(key, (0.0, 0.0))
                self.contacts[key] = (max(f, c.force), max(d, -c.distance))
            for c in w.scene_link_contacts(self.moving, self.config.contact_tolerance):
                self.obj_contacts[c.link_b] = max(self.obj_contacts.get(c.link_b, 0.0), c.force)
            if self.rest_pairs:
                e, other = w.rest_contact_excess(self.rest_pairs)
                self.rest_excess = max(self.rest_excess, e)
                if e > self.rest_worst_excess:
                    self.rest_worst, self.rest_worst_excess = other, e
        if self.steps % self.config.record_every == 0:
            self.sample()

    def sample(self) -> None:
        self.update_effort()
        w, r = self.world, self.rows
        k = len(r["t"])
        self.sampled_at = self.steps
        q, qd = w.scene_joint_state(self.joint)
        v, om = w.scene_link_velocity(self.moving)
        r["t"].append(self.t)
        r["segment"].append(self.segment)
        r["robot_q"].append(w.robot_q())
        r["robot_q_target"].append(w.robot_q_target())
        if self.guard is not None:
            self.guard.check(r["robot_q"][-1], r["robot_q_target"][-1], self.t)
        r["object_q"].append(q)
        r["object_qd"].append(qd)
        T_handle = w.scene_link_pose(self.handle)
        T_tool = w.robot_link_pose(self.tool_link)
        r["T_world_handle"].append(T_handle)
        r["tool_pos"].append(T_tool[:3, 3].copy())
        r["grasp_point"].append(self.grasp_point(T_handle))
        r["grasp_slide"].append(w.grasp_slide())
        r["grasp_turn"].append(self.turn(T_handle, T_tool))
        r["planned_tool_pos"].append(np.array(self.planned_tool, dtype=float))
        r["planned_object_q"].append(self.planned_object_q)
        r["link_speed"].append(vector_norm(v))
        r["link_angular_speed"].append(vector_norm(om))
        r["grasp_active"].append(w.attached)
        r["grasp_force"].append(self.peak)
        self.peak = self.mean
        r["robot_effort"].append(self.effort_peak.copy())
        self.effort_peak = self.effort_history.sum(axis=0) / self.window
        r["finger_q"].append(w.finger_q())
        r["finger_contacts"].append(w.finger_contact_count(self.handle))
        r["rest_contact_excess"].append(self.rest_excess)
        self.rest_excess = 0.0
        for (a, b), (f, d) in self.contacts.items():
            self.contact_rows.append((k, a, b, f, d))
        for b, f in self.obj_contacts.items():
            self.obj_rows.append((k, b, f))
        self.contacts.clear()
        self.obj_contacts.clear()
        if self.sample_callback is not None:
            self.sample_callback()


def _ring_rows(first: int, m: int, window: int) -> np.ndarray:
    """(m, window) int: row i holds, for each slot of a ring buffer of ``window`` rows, the row of
    ``concatenate((ring, new))`` that slot holds after the (i + 1)-th of ``m`` new rows was written, the k-th
    new row into slot ``(first + k) % window``: ``window + k`` of the latest k <= i written there, else the slot's
    old row."""
    out = np.tile(np.arange(window), (m, 1))
    for k in range(m):
        out[k:, (first + k) % window] = window + k
    return out


def _step(world: World, rec: _Recorder, n: int, on_step=None) -> None:
    for _ in range(n):
        world.step()
        rec.after_step()
        if on_step is not None:
            on_step()


def execute_task(world: World, plan: PlanResult, config: PhysicsConfig = DEFAULT_PHYSICS, *,
                 requested_amount: float | None = None, reset_robot: bool = True,
                 frame_callback=None, sample_callback=None, opening_type: str = "",
                 opening_axis: np.ndarray | None = None, closing: bool = False,
                 joint_range: float = float("nan"), freeze_far: bool = False) -> Rollout:
    """Execute ``plan`` in ``world`` with physics and return the recorded :class:`Rollout`.

    Args:
        world: a world holding the scene the plan is executed on (the estimate, or the reference with
            ``--against``) and the robot. Its scene joints are never reset here.
        plan: the planner's plan (status OK). ``plan.joint_names`` must be the world robot's ``joint_names``.
        requested_amount: the opening asked for, m or rad (default ``plan.amount``).
        opening_type, opening_axis: the planned joint's type ("prismatic"/"revolute") and (3,) world axis
            toward which it opens: the opening is measured along it (see ``Rollout.opening_axis``).
        closing, joint_range: a close task (the plan shuts the part; ``requested_amount`` is how far it is
            open, ``opening_axis`` points the way it closes) and the executed joint's range, recorded for
            the criteria (``Rollout.closing``, ``Rollout.joint_range``).
        reset_robot: place the robot at the plan's first configuration first (the robot's start state;
            the scene is left as it is, so a scenario carries the world state from task to task).
        frame_callback: called as ``frame_callback(label)`` at key frames ("start", "grasped",
            "opened", "end") to take pictures.
        sample_callback: called with no argument after every recorded sample (e.g. video frames).
        freeze_far: leave the moving scene parts nothing of the task can reach out of the simulation
            (:mod:`simcheck.frozen_bodies`, ``config.freeze_margin``; pictures still show them:
            :meth:`simcheck.world.World.render`). They stay out when this returns (``world.frozen_joints``;
            ``world.thaw_parts()`` loads them again): for a world that is closed after the task.
    """
    t0 = time.perf_counter()
    robot = world.robot_spec
    joint = plan.task.joint
    if tuple(plan.joint_names) != tuple(robot.joint_names):
        raise ValueError(f"plan for joint {joint!r} has robot joints {plan.joint_names}, the world's robot "
                         f"has {robot.joint_names}")
    moving = moving_link_for(world, joint)
    handle = handle_link_for(world, joint, plan.grasp_link)
    rec = _Recorder(world, joint, moving, handle, config)
    rec.sample_callback = sample_callback
    q0_obj = world.scene_joint_state(joint)[0]
    vmax = speed_limits(world.robot_max_velocity(), config)
    notes: list[str] = []
    if reset_robot:
        world.reset_robot(plan.segments[0].q[0], fingers_open=True)
    if freeze_far and config.freeze_margin > 0:
        far, weights = far_parts(world, plan, config.freeze_margin)
        if far:
            frozen = world.freeze_parts(far)
            rec.guard = FreezeGuard(world, weights, config.freeze_margin)
            log.debug("%s: %d scene joints frozen for the rollout: %s", joint, len(frozen), ", ".join(frozen))
    fingers_open = True
    snap = frame_callback or (lambda label: None)
    snap("start")
    rec.sample()

    def lose_grasp(why: str) -> None:
        world.detach()
        rec.track_force()
        notes.append(why)

    def check_slip() -> None:
        if world.attached and world.grasp_slid and not rec.slid:
            rec.slid = True
            notes.append(f"the handle slid in the fingers from t={rec.t:.2f} s: the grasp had to transmit more than "
                         f"the gripper holds ({rec.holding_force:.0f} N)")
        if rec.steps % config.record_every == 0 and world.attached and rec.T_handle_grasp is not None:
            slip, turn = rec.slip_and_turn()
            if slip > config.grasp_break_distance:
                lose_grasp(f"grasp torn off at t={rec.t:.2f} s: the handle lagged the tool by {slip:.3f} m")
            elif turn > config.grasp_max_turn:
                what = "its round bar's axis" if rec.roll_axis is not None else "it"
                lose_grasp(f"handle turned out of the fingers at t={rec.t:.2f} s: {what} turned "
                           f"{np.degrees(turn):.0f} deg in the grasp (at most {np.degrees(config.grasp_max_turn):.0f})")

    def set_fingers(open_: bool, seconds: float, hold_q: np.ndarray) -> None:
        nonlocal fingers_open
        if open_:
            world.detach()
        world.command_fingers(open_)
        world.command_robot(hold_q, np.zeros_like(hold_q))
        _step(world, rec, max(1, int(round(seconds / config.time_step))), check_slip)
        fingers_open = open_

    def close_and_grasp(hold_q: np.ndarray) -> None:
        set_fingers(False, config.gripper_close_time, hold_q)
        formed = grasp_formation(world.finger_contacts(handle), handle,
                                 contact_distance=config.grasp_contact_distance,
                                 normal_angle=config.grasp_normal_angle, min_travel=config.grasp_min_travel,
                                 min_width=config.grasp_min_width)
        if formed.ok:
            stiffness = dict(robot.joint_stiffness) if robot.joint_stiffness else config.grasp_stiffness
            held = rec.held_round_bar(formed.pads, world.finger_contacts(handle)[0].closing)
            world.attach(handle, rec.holding_force, stiffness, config.grasp_damping, held_point=held)
            rec.slid = False
            T_w_tool = world.robot_link_pose(robot.tool_link)
            rec.T_handle_grasp = np.linalg.inv(world.scene_link_pose(handle)) @ T_w_tool
            snap("grasped")
        else:
            where = plan.segments[rec.segment].name if 0 <= rec.segment < len(plan.segments) else "?"
            notes.append(f"no grasp: {formed.reason} (the fingers closed in segment {where!r})")

    hold = plan.segments[0].q[0]
    opening = plan.opening_segment
    for i, seg in enumerate(plan.segments):
        rec.segment = i
        if seg.command is not None:              # a given plan: its gripper command (planners.task.GRIPPER_COMMANDS)
            open_first, close_first, close_after = seg.command == "open", False, seg.command == "close"
        else:                                    # a planner's plan: its segment names say what to do
            want_open = seg.gripper == "open"
            open_first = want_open or seg.name == RELEASE
            close_first, close_after = not want_open and seg.name != GRASP, seg.name == GRASP
        if open_first and not fingers_open:
            set_fingers(True, config.gripper_open_time, hold)
        if close_first and fingers_open:
            close_and_grasp(hold)
        hold = _follow(world, rec, seg, *segment_timing(seg.name, vmax, config), check_slip)
        if seg.name == opening:
            snap("opened")
        if close_after and fingers_open:
            close_and_grasp(hold)
        rec.planned_tool = np.full(3, np.nan)
        rec.planned_object_q = np.nan
    rec.segment = -1
    world.command_robot(hold, np.zeros_like(hold))
    _step(world, rec, max(1, int(round(config.final_settle_time / config.time_step))), check_slip)
    rec.sample()
    snap("end")
    lo, hi = world.robot_limits()
    info = world.scene_joint(joint)
    object_limits = np.array([info.lower, info.upper] if info.lower <= info.upper else [np.nan, np.nan], dtype=float)
    rows = rec.rows
    cr = rec.contact_rows
    orows = rec.obj_rows
    return Rollout(
        joint=joint, moving_link=moving, handle_link=handle, robot_joint_names=tuple(robot.joint_names),
        robot_joint_units=tuple("m" if world.robot_joint(n).type == "prismatic" else "rad" for n in robot.joint_names),
        segment_names=tuple(s.name for s in plan.segments),
        gripper_links=tuple(dict.fromkeys(robot.gripper_links + robot.finger_links + (robot.tool_link,))),
        requested_amount=float(plan.amount if requested_amount is None else requested_amount),
        object_q0=float(q0_obj), grasp_note="; ".join(notes), time_step=config.time_step,
        t=np.asarray(rows["t"]), segment=np.asarray(rows["segment"], dtype=int),
        robot_q=np.asarray(rows["robot_q"]), robot_lower=lo, robot_upper=hi,
        object_q=np.asarray(rows["object_q"]), object_qd=np.asarray(rows["object_qd"]),
        T_world_handle=np.asarray(rows["T_world_handle"]), tool_pos=np.asarray(rows["tool_pos"]),
        grasp_point=np.asarray(rows["grasp_point"]), planned_tool_pos=np.asarray(rows["planned_tool_pos"]),
        planned_object_q=np.asarray(rows["planned_object_q"], dtype=float),
        link_speed=np.asarray(rows["link_speed"]), link_angular_speed=np.asarray(rows["link_angular_speed"]),
        grasp_active=np.asarray(rows["grasp_active"], dtype=bool), grasp_force=np.asarray(rows["grasp_force"]),
        grasp_turn=np.asarray(rows["grasp_turn"]), opening_type=opening_type,
        robot_q_target=np.asarray(rows["robot_q_target"]), finger_links=tuple(robot.finger_links),
        opening_axis=None if opening_axis is None else np.asarray(opening_axis, dtype=float).reshape(3),
        holding_force=float(rec.holding_force), opening_segment=opening, release_segment=plan.release_segment,
        closing=bool(closing), joint_range=float(joint_range),
        push_segment=PUSH if any(s.name == PUSH for s in plan.segments) else "",
        object_limits=object_limits, robot_effort=np.asarray(rows["robot_effort"], dtype=float),
        grasp_slide=np.asarray(rows["grasp_slide"], dtype=float),
        finger_q=np.asarray(rows["finger_q"]).reshape(len(rows["t"]), -1),
        finger_contacts=np.asarray(rows["finger_contacts"], dtype=int),
        contact_sample=np.asarray([c[0] for c in cr], dtype=int),
        contact_robot_link=np.asarray([c[1] for c in cr], dtype=str),
        contact_scene_link=np.asarray([c[2] for c in cr], dtype=str),
        contact_force=np.asarray([c[3] for c in cr], dtype=float),
        contact_depth=np.asarray([c[4] for c in cr], dtype=float),
        object_contact_sample=np.asarray([c[0] for c in orows], dtype=int),
        object_contact_link=np.asarray([c[1] for c in orows], dtype=str),
        object_contact_force=np.asarray([c[2] for c in orows], dtype=float),
        rest_contact_links=tuple(dict.fromkeys(p[1] for p in rec.rest_pairs)),
        rest_contact_excess=np.asarray(rows["rest_contact_excess"], dtype=float), rest_contact_worst=rec.rest_worst,
        wall_time=time.perf_counter() - t0)


def speed_limits(vmax_urdf: np.ndarray, config: PhysicsConfig = DEFAULT_PHYSICS) -> np.ndarray:
    """(dof,) the joint speeds, rad/s or m/s, at which the executor times a planner's segment: ``speed_scale``
    x the URDF limits ``vmax_urdf`` (dof,), capped at ``max_joint_speed`` (which also stands for unset, 0, limits)."""
    vmax_urdf = np.asarray(vmax_urdf, dtype=float)
    return np.where(vmax_urdf > 0, np.minimum(vmax_urdf * config.speed_scale, config.max_joint_speed),
                    config.max_joint_speed)


def segment_timing(name: str, vmax: np.ndarray, config: PhysicsConfig = DEFAULT_PHYSICS
                   ) -> tuple[np.ndarray, PhysicsConfig]:
    """How the executor times a planner's segment named ``name``: ``(joint speeds (dof,) rad/s or m/s, the physics
    settings with its ramp)``, from ``vmax`` (dof,) of :func:`speed_limits`. The opening (``open``, ``push``) is
    slower by ``open_speed_scale``. The approach (gripper open, away from the part) is faster by
    ``approach_speed_scale`` with its ``ramp_time`` longer by as much: its accelerations -- on the ramps and where
    the timing slows for a turn (:func:`waypoint_timing`) -- are those of every other segment, only its top speed
    is higher. Every other segment runs at ``vmax``."""
    if name in (OPEN, PUSH):
        return vmax * config.open_speed_scale, config
    if name == APPROACH and config.approach_speed_scale != 1.0:
        k = config.approach_speed_scale
        return vmax * k, config.replace(ramp_time=config.ramp_time * k)
    return vmax, config


def command_trajectory(seg: Segment, vmax: np.ndarray, config: PhysicsConfig = DEFAULT_PHYSICS
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """The timing the executor gives ``seg`` (a planner's segment; ``vmax`` (dof,) and ``config`` as
    :func:`segment_timing` gives them for it), as explicit waypoints:
    ``(t (m,) s from the segment's start, q (m, dof), tool positions (m, 3) or None)``: the position targets
    of every control step, without the ones that lie on the straight line between their neighbours.
    Executed with these times (``Segment.t``) the robot gets the same position targets at every control step."""
    k, q, _, tool_k, _, _ = _targets(seg, vmax, config)
    t = np.concatenate([[0.0], k * config.time_step])
    q = np.concatenate([seg.q[:1], q])
    tool = seg.T_world_tool[:, :3, 3] if seg.T_world_tool is not None else None
    tool = np.concatenate([tool[:1], tool_k]) if tool is not None and tool_k is not None else None
    if len(t) < 2:
        return t, q, tool
    y = q if tool is None else np.concatenate([q, tool], axis=1)
    w = ((t[1:-1] - t[:-2]) / (t[2:] - t[:-2]))[:, None]
    between = (1 - w) * y[:-2] + w * y[2:]
    keep = np.concatenate([[True], np.abs(y[1:-1] - between).max(axis=1) > 1e-12, [True]])
    return t[keep], q[keep], tool[keep] if tool is not None else None


def _ramped(t: np.ndarray, duration: float, ramp: float) -> tuple[np.ndarray, np.ndarray]:
    """Trapezoidal time scaling: (path time u(t), rate du/dt), both (m,), for real times ``t`` in
    [0, duration + ramp], seconds. The rate rises linearly from 0 to 1 over ``ramp`` seconds, stays 1, and
    falls back to 0 at ``duration + ramp``, where u = ``duration``: every segment starts and ends at rest."""
    if ramp <= 0:
        return np.minimum(t, duration), np.ones_like(t)
    end = duration + ramp
    up, down = t < ramp, t > duration
    u = np.where(up, t ** 2 / (2 * ramp), t - ramp / 2)
    u = np.where(down, duration - (end - t) ** 2 / (2 * ramp), u)
    rate = np.where(up, t / ramp, np.where(down, (end - t) / ramp, 1.0))
    return u, rate


def _targets(seg: Segment, vmax: np.ndarray, config: PhysicsConfig):
    """Every control step's robot target along ``seg``: (step numbers k (m,), q (m, dof), qd (m, dof),
    planned tool position (m, 3) or None, planned object q (m,) or None), and the step count.

    A segment with its own times (``seg.t``, a given plan) is interpolated at them as they are (feed-forward
    velocity: the slope of the straight piece, at a waypoint's own time the slope between its neighbours, 0
    at the last waypoint). Otherwise
    the segment is time-parametrised by :func:`timed_waypoints`, then ramped (:func:`_ramped`, over
    ``ramp_time``: a real arm's acceleration is bounded, and a part grasped and jerked to speed in one step
    would take an impulse no gripper transmits); targets are linear interpolations between waypoints at
    the ramped path time of t = k * time_step for the steps k that send a command (every
    ``control_every``-th, from 1).
    """
    if seg.t is not None:                     # a given plan's own timing, executed as it is
        times, ramp = seg.t, 0.0
        rho = np.full(max(len(times) - 1, 0), 0.5)
        n_steps = int(np.ceil(times[-1] / config.time_step - 1e-9))
    else:
        tool_path = seg.T_world_tool[:, :3, 3] if seg.T_world_tool is not None else None
        times, rho = waypoint_timing(seg.q, vmax, config.time_step, config.ramp_time, tool_path,
                                     config.time_step * config.control_every)
        ramp = min(config.ramp_time, times[-1])
        n_steps = int(np.ceil((times[-1] + ramp) / config.time_step))
    k = np.arange(1, n_steps + 1, config.control_every)
    tool = seg.T_world_tool[:, :3, 3] if seg.T_world_tool is not None else None
    if len(times) == 1:
        q = np.repeat(seg.q[:1], len(k), axis=0)
        qd = np.zeros_like(q)
        return k, q, qd, None, None, n_steps
    tk, rate = _ramped(np.minimum(k * config.time_step, times[-1] + ramp), times[-1], ramp)
    j = np.clip(np.searchsorted(times, tk, side="right") - 1, 0, len(times) - 2)
    span = times[j + 1] - times[j]
    x = np.clip((tk - times[j]) / span, 0.0, 1.0)
    r = rho[j]
    a = (2.0 * r * x + (1.0 - 2.0 * r) * x ** 2)[:, None]       # uniform acceleration inside the piece
    q = (1 - a) * seg.q[j] + a * seg.q[j + 1]
    qd = (seg.q[j + 1] - seg.q[j]) / span[:, None] * ((2.0 * r + 2.0 * (1.0 - 2.0 * r) * x) * rate)[:, None]
    if seg.t is not None:
        # a given plan: at a waypoint's own time the velocity is the slope between its neighbours (exact for a
        # path sampled from a smooth one), at the last waypoint 0 (the robot stops there)
        at = np.isclose(tk, times[j], rtol=0.0, atol=1e-12) & (j > 0)
        jj = j[at]
        qd[at] = (seg.q[jj + 1] - seg.q[jj - 1]) / (times[jj + 1] - times[jj - 1])[:, None]
        qd[tk >= times[-1] - 1e-12] = 0.0
    tool_k = (1 - a) * tool[j] + a * tool[j + 1] if tool is not None else None
    obj_k = ((1 - a[:, 0]) * seg.object_q[j] + a[:, 0] * seg.object_q[j + 1]) if seg.object_q is not None else None
    return k, q, qd, tool_k, obj_k, n_steps


def _follow(world: World, rec: _Recorder, seg: Segment, vmax: np.ndarray, config: PhysicsConfig,
            on_step) -> np.ndarray:
    """Drive the robot along ``seg`` (time-parametrised), then hold ``settle_time``; returns the last q."""
    ks, q, qd, tool_k, obj_k, n_steps = _targets(seg, vmax, config)
    tool = seg.T_world_tool[:, :3, 3] if seg.T_world_tool is not None else None
    i = 0
    for k in range(1, n_steps + 1):
        if i < len(ks) and ks[i] == k:
            if tool_k is not None:
                rec.planned_tool = tool_k[i]
            if obj_k is not None:
                rec.planned_object_q = float(obj_k[i])
            world.command_robot(q[i], qd[i])
            i += 1
        world.step()
        rec.after_step()
        on_step()
    last = seg.q[-1]
    if tool is not None:
        rec.planned_tool = tool[-1]
    if seg.object_q is not None:
        rec.planned_object_q = float(seg.object_q[-1])
    world.command_robot(last, np.zeros_like(last))
    _step(world, rec, max(1, int(round(config.settle_time / config.time_step))), on_step)
    return last
