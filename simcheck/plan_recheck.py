"""Independent collision re-check of a plan in PyBullet (not the planner's pinocchio + coal checker).

The plan is densely interpolated (no joint moves more than ``recheck_resolution`` between states);
at each state the robot joints, the fingers (open/closed as the segment says) and the task joint (the
plan's ``object_q``) are set kinematically and PyBullet's contacts are queried. A contact between a
gripper link and the grasped handle link is expected; any other robot-scene or robot-floor contact deeper
than ``plan_penetration_tolerance`` makes the plan colliding -- and a colliding plan is never certified.
The world is restored afterwards.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from planners.task import PlanResult
from simcheck.config import DEFAULT_CRITERIA, CriteriaConfig
from simcheck.execute import handle_link_for
from simcheck.world import World

__all__ = ["PlanCheck", "recheck_plan", "densify"]


@dataclass(frozen=True)
class PlanCheck:
    """Outcome of the re-check.

    Attributes:
        max_depth: deepest unexpected penetration found, m (0 when none).
        detail: the worst collision: segment, state index, robot link, scene link.
        n_states: states checked.
        seconds: wall time of the re-check.
    """

    max_depth: float
    detail: str
    n_states: int
    seconds: float

    @property
    def checks_per_second(self) -> float:
        return self.n_states / self.seconds if self.seconds > 0 else 0.0


def densify(q: np.ndarray, resolution: float, *extra: np.ndarray | None) -> tuple[np.ndarray, ...]:
    """Linearly interpolate waypoints ``q`` (n, dof) so no joint steps more than ``resolution``;
    ``extra`` arrays (n, ...) are interpolated alongside (None stays None). Returns (q_dense, *extra_dense)."""
    q = np.atleast_2d(q)
    if len(q) == 1:
        return (q,) + tuple(extra)
    steps = np.maximum(np.ceil(np.abs(np.diff(q, axis=0)).max(axis=1) / resolution).astype(int), 1)
    s = np.concatenate([[0.0], np.concatenate([i + np.arange(1, n + 1) / n for i, n in enumerate(steps)])])
    base = np.arange(len(q))
    out_q = np.stack([np.interp(s, base, q[:, j]) for j in range(q.shape[1])], axis=1)
    outs = []
    for e in extra:
        if e is None:
            outs.append(None)
        else:
            flat = np.asarray(e, float).reshape(len(q), -1)
            outs.append(np.stack([np.interp(s, base, flat[:, j]) for j in range(flat.shape[1])], axis=1)
                        .reshape((len(s),) + np.shape(e)[1:]))
    return (out_q,) + tuple(outs)


def recheck_plan(world: World, plan: PlanResult, criteria: CriteriaConfig = DEFAULT_CRITERIA) -> PlanCheck:
    """Re-check every densely interpolated state of ``plan`` for robot-scene collisions in ``world``
    (the scene the plan was made for). The world's state is restored afterwards."""
    t0 = time.perf_counter()
    joint = plan.task.joint
    handle = handle_link_for(world, joint, plan.grasp_link)
    q_obj_now = world.scene_joint_state(joint)[0]
    worst, detail, n = 0.0, "", 0
    with world.saved_state():
        for seg in plan.segments:
            q, obj = densify(seg.q, criteria.recheck_resolution, seg.object_q)
            for i in range(len(q)):
                value = float(obj[i]) if obj is not None else q_obj_now
                contacts = world.collisions_at(q[i], seg.gripper == "open", {joint: value},
                                               criteria.plan_penetration_tolerance * 0.0)
                n += 1
                for c in contacts:
                    if c.link_b == handle and world.is_gripper_link(c.link_a):
                        continue
                    depth = -c.distance
                    if depth > worst:
                        worst = depth
                        detail = (f"plan state {i} of segment {seg.name!r}: robot link {c.link_a} penetrates "
                                  f"scene link {c.link_b} by {depth * 1e3:.1f} mm")
    return PlanCheck(max_depth=worst, detail=detail, n_states=n, seconds=time.perf_counter() - t0)
