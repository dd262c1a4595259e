"""The recorded rollout of one executed task: arrays over time, saved to / loaded from ``.npz``.

A :class:`Rollout` is everything the certificate's criteria look at; they are pure functions of it
(:mod:`simcheck.criteria`), so they can be tested on rollouts built by hand, without PyBullet.

Sample ``i`` is taken at time ``t[i]`` (seconds since the task started). World frame, metres, radians.
"""

from __future__ import annotations

import json
from dataclasses import MISSING, dataclass, fields
from pathlib import Path

import numpy as np

from scenes.description import write_with_atomic
from simcheck.errors import RolloutFormatError

__all__ = ["Rollout", "ROLLOUT_FORMAT"]

ROLLOUT_FORMAT = "partscene.rollout/1"

_META = ("joint", "moving_link", "handle_link", "robot_joint_names", "segment_names", "gripper_links",
         "requested_amount", "object_q0", "grasp_note", "time_step", "holding_force", "opening_type",
         "finger_links", "opening_segment", "release_segment", "rest_contact_links", "rest_contact_worst",
         "robot_joint_units", "closing", "joint_range", "push_segment")


@dataclass(frozen=True)
class Rollout:
    """Arrays recorded while executing one task (n samples; m robot contact records; k object contact records).

    Attributes:
        joint: the task joint (URDF name) in the executed world.
        moving_link: the link the task joint moves.
        handle_link: the link that was grasped (the handle, or the moving link itself).
        robot_joint_names: (dof,) robot joint names, the columns of ``robot_q``.
        robot_joint_units: (dof,) "m" (prismatic) or "rad" per robot joint; () in rollouts recorded before.
        segment_names: names of the plan's segments; ``segment`` indexes them.
        gripper_links: robot links allowed to touch ``handle_link``.
        requested_amount: the opening asked for, rad or m (in the executed joint's units); along
            ``opening_axis`` when one is given, else the joint's signed change (negative: toward its lower limit).
        object_q0: the task joint's value when the task started.
        grasp_note: how the grasp went ("" when the grasp was made and kept).
        time_step: physics time step, seconds.
        t: (n,) seconds.
        segment: (n,) int index into ``segment_names``; -1 while settling after the last segment.
        robot_q: (n, dof) robot joint positions.  robot_lower / robot_upper: (dof,) URDF limits (+-inf: none).
        object_q, object_qd: (n,) task joint position / velocity.
        T_world_handle: (n, 4, 4) handle link pose.
        tool_pos: (n, 3) robot tool frame position.
        grasp_point: (n, 3) world position of the grasped point of the handle (NaN before the grasp).
        planned_tool_pos: (n, 3) planned tool position at that instant (NaN where the plan has none).
        planned_object_q: (n,) planned task joint value (NaN where the plan has none).
        link_speed, link_angular_speed: (n,) speed of ``moving_link``, m/s and rad/s.
        grasp_active: (n,) bool, the grasp attachment exists.
        grasp_force: (n,) what the grasp transmitted: the largest running mean (over
            ``PhysicsConfig.grasp_force_window``) of the norm of its force since the previous sample, N;
            0 while not grasped.
        holding_force: the force the robot's gripper holds, N (its ``GripperModel``).
        object_limits: (2,) lower and upper limit of the executed task joint, rad or m (NaN: none, or a
            rollout recorded without them).
        robot_q_target: (n, dof) the robot joint positions commanded at that instant (the plan's targets).
        finger_links: the robot's finger links (a subset of ``gripper_links``).
        grasp_turn: (n,) angle, rad, by which the handle has turned in the fingers since the grasp.
        opening_type, opening_axis: how the opening is measured: "prismatic" (the handle's displacement
            along ``opening_axis``, m) or "revolute" (its rotation about ``opening_axis``, rad), the
            direction in which the PLANNED (estimated) joint opens, world frame, (3,) unit; "" and NaN:
            the executed joint's own value is used.
        finger_q: (n, n_fingers).  finger_contacts: (n,) int finger links touching the handle.
        contact_sample, contact_robot_link, contact_scene_link, contact_force, contact_depth: (m,) robot
            contacts -- per sample and pair, the largest normal force (N) and penetration (m, >= 0) over
            the physics steps since the previous sample; ``contact_scene_link`` is "floor" for the floor.
        object_contact_sample, object_contact_link, object_contact_force: (k,) contacts of the moving
            link with other scene links / the floor (what blocked it), same aggregation.
        wall_time: seconds of wall-clock time the execution took.
        opening_segment, release_segment: the names of the segment that opens the task joint and of the
            segment at whose end the part must rest ("open" and "release" for a planner's plan; a given
            plan's own names, :attr:`planners.PlanResult.opening_segment`).
        push_segment: the name of the segment in which the hand pushes the part without a grasp ("push" when
            the plan has a segment of that name: a planner's plan that finishes an opening by pushing,
            :mod:`planners.push_finish`, or a given plan's; "" when none): its gripper contacts with the part are
            expected, and count toward the force applied to the part.
        rest_contact_links: the scene links the moving part touched at rest (their contact is not a
            collision, :attr:`simcheck.config.PhysicsConfig.rest_contact_gap`).
        rest_contact_excess: (n,) how much deeper than at rest the moving part interpenetrated any of them
            since the previous sample, m (>= 0); rest_contact_worst: the link of the largest excess ("").
        closing: the task shuts the part (a close task): ``requested_amount`` is then how far it was open,
            measured along ``opening_axis`` pointing the way it closes, so the gap left is the request
            minus what it moved.
        joint_range: the executed joint's range (upper - lower, m or rad; NaN: unknown), which sets how
            near its closed value a closed part must be.
        robot_effort: (n, dof) each robot joint's motor torque (force), N*m (N), as a share of its URDF effort
            limit: the largest running mean over ``PhysicsConfig.grasp_force_window`` since the previous
            sample (1: the motor held at its limit, where the simulated joint stops following its target;
            NaN in rollouts recorded before it existed).
        grasp_slide: (n,) how far the held point has slid on the handle since the grasp was made, m (NaN when
            not attached, and in rollouts recorded before it existed): slip in the fingers, not the grasp
            spring's stretch (the arm's compliance).
    """

    joint: str
    moving_link: str
    handle_link: str
    robot_joint_names: tuple[str, ...]
    segment_names: tuple[str, ...]
    gripper_links: tuple[str, ...]
    requested_amount: float
    object_q0: float
    grasp_note: str
    time_step: float
    t: np.ndarray
    segment: np.ndarray
    robot_q: np.ndarray
    robot_lower: np.ndarray
    robot_upper: np.ndarray
    object_q: np.ndarray
    object_qd: np.ndarray
    T_world_handle: np.ndarray
    tool_pos: np.ndarray
    grasp_point: np.ndarray
    planned_tool_pos: np.ndarray
    planned_object_q: np.ndarray
    link_speed: np.ndarray
    link_angular_speed: np.ndarray
    grasp_active: np.ndarray
    grasp_force: np.ndarray
    finger_q: np.ndarray
    finger_contacts: np.ndarray
    contact_sample: np.ndarray
    contact_robot_link: np.ndarray
    contact_scene_link: np.ndarray
    contact_force: np.ndarray
    contact_depth: np.ndarray
    object_contact_sample: np.ndarray
    object_contact_link: np.ndarray
    object_contact_force: np.ndarray
    wall_time: float = 0.0
    grasp_turn: np.ndarray | None = None
    opening_type: str = ""
    robot_q_target: np.ndarray | None = None
    finger_links: tuple[str, ...] = ()
    opening_axis: np.ndarray | None = None
    holding_force: float = float("nan")
    opening_segment: str = "open"
    release_segment: str = "release"
    rest_contact_links: tuple[str, ...] = ()
    rest_contact_excess: np.ndarray | None = None
    rest_contact_worst: str = ""
    robot_joint_units: tuple[str, ...] = ()
    closing: bool = False
    joint_range: float = float("nan")
    object_limits: np.ndarray | None = None
    robot_effort: np.ndarray | None = None
    push_segment: str = ""
    grasp_slide: np.ndarray | None = None

    def __post_init__(self) -> None:
        n = len(self.t)
        for name in ("grasp_turn", "rest_contact_excess"):     # rollouts recorded before these existed
            if getattr(self, name) is None:
                object.__setattr__(self, name, np.zeros(n))
        if self.robot_q_target is None:
            object.__setattr__(self, "robot_q_target", np.full(np.shape(self.robot_q), np.nan))
        if self.opening_axis is None:
            object.__setattr__(self, "opening_axis", np.full(3, np.nan))
        if self.object_limits is None:
            object.__setattr__(self, "object_limits", np.full(2, np.nan))
        if self.robot_effort is None:                              # rollouts recorded before it existed
            object.__setattr__(self, "robot_effort", np.full(np.shape(self.robot_q), np.nan))
        if self.grasp_slide is None:
            object.__setattr__(self, "grasp_slide", np.full(n, np.nan))
        for name in ("segment", "robot_q", "object_q", "object_qd", "T_world_handle", "tool_pos", "grasp_point",
                     "planned_tool_pos", "planned_object_q", "link_speed", "link_angular_speed", "grasp_active",
                     "grasp_force", "grasp_turn", "robot_q_target", "finger_q", "finger_contacts",
                     "rest_contact_excess", "robot_effort", "grasp_slide"):
            if len(getattr(self, name)) != n:
                raise RolloutFormatError(f"rollout of joint {self.joint!r}: {name} has {len(getattr(self, name))} "
                                         f"samples, t has {n}")

    @property
    def n(self) -> int:
        return len(self.t)

    @property
    def duration(self) -> float:
        """Simulated seconds."""
        return float(self.t[-1]) if self.n else 0.0

    def in_segment(self, name: str) -> np.ndarray:
        """(n,) bool mask of the samples recorded during segment(s) called ``name``."""
        ids = [i for i, s in enumerate(self.segment_names) if s == name]
        return np.isin(self.segment, ids)

    # ------------------------------------------------------------------ I/O
    def save(self, path: str | Path) -> Path:
        """Write the rollout to ``path`` (.npz), atomically. Returns the path."""
        path = Path(path)
        arrays = {}
        meta = {"format": ROLLOUT_FORMAT}
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name in _META or f.name == "wall_time":
                meta[f.name] = list(v) if isinstance(v, tuple) else v
            else:
                arrays[f.name] = np.asarray(v)
        arrays["meta"] = np.array(json.dumps(meta))
        return write_with_atomic(path, lambda tmp: np.savez_compressed(tmp, **arrays))  # tmp ends in .npz

    @classmethod
    def load(cls, path: str | Path) -> "Rollout":
        """Read a rollout written by :meth:`save`.

        Raises:
            RolloutFormatError: not a partscene rollout, or an array is missing (names the file).
        """
        path = Path(path)
        try:
            with np.load(path, allow_pickle=False) as data:
                meta = json.loads(str(data["meta"]))
                if meta.get("format") != ROLLOUT_FORMAT:
                    raise RolloutFormatError(f"{path}: format {meta.get('format')!r}, expected {ROLLOUT_FORMAT!r}")
                kwargs = {}
                for f in fields(cls):
                    if f.name in meta:
                        v = meta[f.name]
                        kwargs[f.name] = tuple(v) if isinstance(v, list) else v
                    elif f.name in data:
                        kwargs[f.name] = data[f.name]
                    elif f.default is MISSING:
                        raise RolloutFormatError(f"{path}: array {f.name!r} missing")
        except (OSError, KeyError, ValueError) as exc:
            if isinstance(exc, RolloutFormatError):
                raise
            raise RolloutFormatError(f"{path}: not a readable rollout ({exc})") from exc
        return cls(**kwargs)

    def isclose(self, other: "Rollout", atol: float = 1e-9) -> bool:
        """True when every field of ``other`` equals this one (floats within ``atol``)."""
        for f in fields(self):
            a, b = getattr(self, f.name), getattr(other, f.name)
            if isinstance(a, np.ndarray) and a.dtype.kind == "f":
                if a.shape != np.shape(b) or not np.allclose(a, b, atol=atol, equal_nan=True):
                    return False
            elif isinstance(a, np.ndarray):
                if not np.array_equal(a, np.asarray(b)):
                    return False
            elif isinstance(a, float):
                if abs(a - float(b)) > atol:
                    return False
            elif tuple(a) != tuple(b) if isinstance(a, tuple) else a != b:
                return False
        return True
