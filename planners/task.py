"""What is asked (:class:`OpenTask`) and what comes back (:class:`PlanResult` of :class:`Segment`\\ s)."""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

import numpy as np

__all__ = ["OpenTask", "PlanStatus", "Segment", "PlanResult", "SEGMENT_NAMES"]

#: Segment names in execution order.
SEGMENT_NAMES = ("approach", "grasp", "open", "release", "retreat")


@dataclass(frozen=True)
class OpenTask:
    """Open the part moved by ``joint`` (its URDF name).

    Attributes
    ----------
    kind : "drawer" | "door"
        A drawer needs a prismatic joint, a door a revolute one.
    joint : str
        URDF name of the joint to open.
    amount : float or None
        Target joint value (metres / radians, from the joint's current value). ``None``: drawers 90% of
        the joint's range; doors ``min(90% of range, 90 deg)``.
    grasp_point : (3,) float or None
        Explicit grasp point (world frame, metres, joint closed) on the moving part.
    grasp_link : str or None
        Explicit handle link (or the moving link itself) to grasp.
    """

    kind: str
    joint: str
    amount: float | None = None
    grasp_point: tuple[float, float, float] | None = None
    grasp_link: str | None = None

    def __post_init__(self) -> None:
        if self.kind not in ("drawer", "door"):
            raise ValueError(f"OpenTask({self.joint!r}): kind must be 'drawer' or 'door', got {self.kind!r}")
        if self.grasp_point is not None:
            gp = tuple(float(v) for v in np.asarray(self.grasp_point, dtype=float).reshape(-1))
            if len(gp) != 3:
                raise ValueError(f"OpenTask({self.joint!r}): grasp_point must be 3 numbers, got {self.grasp_point}")
            object.__setattr__(self, "grasp_point", gp)


class PlanStatus(enum.Enum):
    """Outcome of :func:`planners.plan_open_task`."""

    OK = "ok"
    NO_HANDLE = "no_handle"   # kept for the contract; a missing handle raises HandleNotFoundError instead
    NO_STAND_POSE = "no_stand_pose"
    IK_FAILED = "ik_failed"
    NO_PATH = "no_path"
    START_IN_COLLISION = "start_in_collision"
    GOAL_IN_COLLISION = "goal_in_collision"
    OPENING_FAILED = "opening_failed"


@dataclass(frozen=True)
class Segment:
    """One piece of the plan, sampled densely enough to execute by interpolation.

    Attributes
    ----------
    name : str
        One of :data:`SEGMENT_NAMES`.
    q : (n, dof) float
        Robot joint positions, columns in ``PlanResult.joint_names`` order (m, rad).
    object_q : (n,) float
        Planned value of the task joint at each sample (m or rad).
    T_world_tool : (n, 4, 4) float
        Planned tool pose; during ``open`` this is where the handle grasp frame is planned to be.
    gripper : "open" | "closed"
        Gripper command held during the segment.
    """

    name: str
    q: np.ndarray
    object_q: np.ndarray
    T_world_tool: np.ndarray
    gripper: str

    def __post_init__(self) -> None:
        n = len(self.q)
        if self.object_q.shape != (n,) or self.T_world_tool.shape != (n, 4, 4):
            raise ValueError(f"Segment {self.name!r}: inconsistent shapes q{self.q.shape} "
                             f"object_q{self.object_q.shape} T_world_tool{self.T_world_tool.shape}")

    def isclose(self, other: "Segment", atol: float = 1e-9) -> bool:
        return (self.name == other.name and self.gripper == other.gripper and self.q.shape == other.q.shape
                and np.allclose(self.q, other.q, atol=atol) and np.allclose(self.object_q, other.object_q, atol=atol)
                and np.allclose(self.T_world_tool, other.T_world_tool, atol=atol))


@dataclass(frozen=True)
class PlanResult:
    """A plan for an :class:`OpenTask`, or why there is none (``status`` != OK, ``segments`` empty or partial).

    Attributes
    ----------
    status, reason : the outcome; ``reason`` names the joint and what failed.
    task : the task planned for.
    joint_names : robot joints, the columns of every ``Segment.q``.
    segments : in execution order (approach, grasp, open, release, retreat) when OK.
    T_world_base_stand : (4, 4) base pose at grasp time (identity when none was found).
    amount : requested opening (m or rad), from ``start_object_q``.
    start_object_q : value of the task joint when the plan starts.
    T_link_grasp : (4, 4) grasp frame in the moving link's frame (rigid during the opening).
    moving_link : the link moved by the task joint.
    grasp_link : the link whose bar is grasped (the handle link, or the moving link for a named geometry or
        an explicit grasp point); simcheck attaches the gripper to it.
    method : how the opening was planned ("constrained" or "ik_tracking"; "" when not planned).
    timings : seconds per stage; collision_checks : count; seed : the seed used.
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

    @property
    def ok(self) -> bool:
        return self.status is PlanStatus.OK

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
