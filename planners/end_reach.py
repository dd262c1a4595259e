"""Whether any base pose reaches the tool pose at the end of an opening: a verdict of the robot.

When every stand pose reached the grasp but no opening motion could be followed to its end, the end may lie
outside what the robot can reach at all (a door hinged at its bottom puts its handle under the door near the
floor, facing down; a flap hinged at its top puts it overhead, facing up): then no other stand pose or
redundancy resolution would help, and the task is ``unreachable``, not a failed articulation. Base poses are
sampled (seeded) around the end's tool position, turned toward it; arm-only IK (the torso lift included) to
the full end pose, collision-free, from each.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from planners.config import PlannerConfig
from planners.ik import solve_ik
from planners.motion import ik_weights

__all__ = ["EndReach", "end_reach", "END_SAMPLES"]

END_SAMPLES = 24
"""Base poses tried around the end of the opening."""

_DISTANCE = (0.35, 1.0)     # horizontal base-to-tool distance sampled, m (the arm's reach and a little more)


class EndReach(NamedTuple):
    """``reached``: a sampled base pose reaches the end pose collision-free; ``miss`` (m): the smallest distance
    between the tool and the end position that full-pose IK got to, collisions ignored (0: within reach, but
    every such configuration collides); ``collides_with``: the most frequent colliding pair then, or ""."""

    reached: bool
    miss: float
    collides_with: str


def end_reach(kin, world, T_end: np.ndarray, s_end: float, cfg: PlannerConfig, rng: np.random.Generator) -> EndReach:
    """Can the robot hold the tool at ``T_end (4, 4)`` (world) with the task joint at ``s_end`` from any of
    :data:`END_SAMPLES` base poses around it?"""
    spec = kin.spec
    lower, upper = world.robot.lower, world.robot.upper
    arm = np.zeros(spec.dof, bool)
    arm[3:] = True
    weights = ik_weights(kin, cfg)
    p = kin.in_root(T_end[:3, 3])               # base poses are sampled in the floor frame
    miss, pairs = math.inf, {}
    for _ in range(END_SAMPLES):
        a = rng.uniform(-math.pi, math.pi)
        xy = p[:2] + rng.uniform(*_DISTANCE) * np.array([math.cos(a), math.sin(a)])
        yaw = math.atan2(p[1] - xy[1], p[0] - xy[0]) + rng.uniform(-0.4, 0.4)
        q = spec.q_with_base(spec.home_q, xy[0], xy[1], yaw)
        if world.in_collision(q, s_end, True):
            continue
        r = solve_ik(kin.tool_pose_jacobian, T_end, q, lower, upper, arm, weights, pos_tol=cfg.track_pos_tol,
                     rot_tol=cfg.track_rot_tol, restarts=2, rng=rng)
        miss = min(miss, r.pos_error if not r.success else 0.0)
        if not r.success:
            continue
        found = world.colliding_pairs(r.q, s_end, True)
        if not found:
            return EndReach(True, 0.0, "")
        for pair in found[:1]:
            pairs[pair] = pairs.get(pair, 0) + 1
    top = max(pairs.items(), key=lambda kv: kv[1])[0] if pairs else None
    return EndReach(False, miss, f"{top[0]} / {top[1]}" if top else "")
