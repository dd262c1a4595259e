"""The plan simcheck executes: robot joint trajectories per segment, read from a ``planners.PlanResult``.

simcheck depends on the planners <-> simcheck contract only through :func:`planned_task_from_plan`, so
tests can hand-make a :class:`PlannedTask` (no planner needed) and another planner can be plugged in.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["PlannedSegment", "PlannedTask", "planned_task_from_plan", "GRASP", "OPEN", "RELEASE"]

GRASP, OPEN, RELEASE = "grasp", "open", "release"


@dataclass(frozen=True)
class PlannedSegment:
    """One segment of a plan.

    Attributes:
        name: "approach", "grasp", "open", "release", "retreat" (or any other name).
        q: (n, dof) float robot joint positions, columns in ``PlannedTask.joint_names`` order.
        gripper: "open" or "closed" during this segment.
        object_q: (n,) float planned value of the task joint (rad or m), or None.
        T_world_tool: (n, 4, 4) float planned tool pose (= the grasped handle point while grasped), or None.
    """

    name: str
    q: np.ndarray
    gripper: str = "open"
    object_q: np.ndarray | None = None
    T_world_tool: np.ndarray | None = None

    def __post_init__(self) -> None:
        q = np.atleast_2d(np.asarray(self.q, dtype=float))
        object.__setattr__(self, "q", q)
        if self.object_q is not None:
            object.__setattr__(self, "object_q", np.asarray(self.object_q, dtype=float).reshape(len(q)))
        if self.T_world_tool is not None:
            object.__setattr__(self, "T_world_tool", np.asarray(self.T_world_tool, dtype=float).reshape(len(q), 4, 4))
        if self.gripper not in ("open", "closed"):
            raise ValueError(f"segment {self.name!r}: gripper must be 'open' or 'closed', got {self.gripper!r}")


@dataclass(frozen=True)
class PlannedTask:
    """A plan for one opening task, as simcheck executes it.

    Attributes:
        joint: the task's scene joint (URDF name).
        amount: the requested opening, rad or m (the plan's ``amount``).
        joint_names: (dof,) robot joints, the column order of every segment's ``q``.
        segments: the segments in execution order.
        grasp_link: the scene link the plan grasps (None: found from the joint's moving part).
        collision_checks: how many collision checks the planner made (for the benchmark).
        timings: planner timings, seconds, by name.
    """

    joint: str
    amount: float
    joint_names: tuple[str, ...]
    segments: tuple[PlannedSegment, ...]
    grasp_link: str | None = None
    collision_checks: int = 0
    timings: dict = field(default_factory=dict)

    def segment(self, name: str) -> PlannedSegment | None:
        """The first segment called ``name``, or None."""
        return next((s for s in self.segments if s.name == name), None)


def planned_task_from_plan(plan, joint: str) -> PlannedTask:
    """A :class:`PlannedTask` from a ``planners.PlanResult`` with status OK (duck-typed on the contract:
    ``segments`` with ``name, q, object_q, T_world_tool, gripper``; ``joint_names``; ``amount``)."""
    segments = tuple(PlannedSegment(name=str(s.name), q=np.asarray(s.q, dtype=float), gripper=str(getattr(s, "gripper", "open")),
                                    object_q=getattr(s, "object_q", None), T_world_tool=getattr(s, "T_world_tool", None))
                     for s in plan.segments)
    grasp_link = getattr(plan, "grasp_link", None)
    return PlannedTask(joint=joint, amount=float(plan.amount), joint_names=tuple(plan.joint_names), segments=segments,
                       grasp_link=grasp_link, collision_checks=int(getattr(plan, "collision_checks", 0) or 0),
                       timings=dict(getattr(plan, "timings", {}) or {}))
