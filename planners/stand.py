"""Base placement: where the mobile base should stand to grasp the handle and follow the whole opening.

Stand poses are sampled (seeded) in front of the handle: at a distance along the part's outward normal,
with a lateral offset and the base turned roughly toward the handle. A pose is kept when arm-only IK
reaches the grasp collision-free; it is *complete* when arm-only IK (base fixed) also reaches the handle
at ``cfg.stand_path_samples`` points spread along the whole opening path (for a door, the arc).
Ranking: complete poses first, then the share of the path reached, then the reach margin (the smallest
normalised distance of a revolute arm joint to its limit along the path; a torso lift at the end of its
travel is no strain) plus the clearance between the arm/base
and the scene at the grasp (metres, capped at 0.1).

When no pose reaches the grasp, the search reports the nearest miss: the smallest distance (m) between the
tool and the grasp point that position-only IK (collisions ignored) gets to from the sampled base poses
(0 when the handle is within reach but every grasp collides or needs an orientation the arm cannot take),
and the summary names what the grasp configurations collide with (e.g. on
realistic reconstructions: the fingers inside a noise-inflated front or body box in front of the handle,
``panda_leftfinger_0 / scene::microwave2_body8_0``), from a few seeds re-solved without collision checks.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from planners.config import PlannerConfig
from planners.ik import solve_ik
from planners.motion import ik_weights

__all__ = ["StandPose", "StandSearch", "find_stand_poses"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class StandPose:
    """A ranked stand pose.

    Attributes:
        base: (3,) float, base (x m, y m, yaw rad), in the robot's root frame (the floor frame: the base joints'
            values).
        q_grasp: (dof,) float, configuration at the grasp (task joint at its start value).
        grasp_index: which grasp candidate (index into ``HandleGrasp.T_link_grasps``).
        path_share: share of the path samples reached with the base fixed (1.0 = complete).
        reach_margin: smallest normalised arm joint-limit margin along the reached samples (0..0.5).
        clearance: metres between the non-gripper robot links and the scene at the grasp.
    """

    base: np.ndarray
    q_grasp: np.ndarray
    grasp_index: int
    path_share: float
    reach_margin: float
    clearance: float = 0.0

    @property
    def T_root_base(self) -> np.ndarray:
        """(4, 4) the base in the robot's root frame (the floor frame; the world's when the floor is z = 0)."""
        c, s = math.cos(self.base[2]), math.sin(self.base[2])
        T = np.eye(4)
        T[:2, :2] = [[c, -s], [s, c]]
        T[:2, 3] = self.base[:2]
        return T

    def rank_key(self) -> tuple:
        """Sort key, best first: path share, then reach margin + clearance (capped at 0.1 m)."""
        return (-self.path_share, -(self.reach_margin + min(self.clearance, 0.1)))


class StandSearch(NamedTuple):
    """What :func:`find_stand_poses` found: ``poses`` best first; ``summary``, how many were tried and why
    they failed; ``nearest_miss`` (m) when no pose reaches the grasp (None otherwise, or when no base pose
    was collision-free to measure it from)."""

    poses: list
    summary: str
    nearest_miss: float | None = None


def _margin(q: np.ndarray, lower: np.ndarray, upper: np.ndarray, cols: np.ndarray) -> float:
    """Smallest normalised distance (0..0.5) of ``q[cols]`` to the joint limits."""
    span = np.maximum(upper[cols] - lower[cols], 1e-9)
    return float(np.min(np.minimum(q[cols] - lower[cols], upper[cols] - q[cols]) / span))


def find_stand_poses(kin, world, T_paths: list, s_samples: np.ndarray, cfg: PlannerConfig,
                     rng: np.random.Generator, hinge_xy: np.ndarray | None = None,
                     facing: np.ndarray | None = None) -> StandSearch:
    """Sample and rank stand poses for grasp paths ``T_paths`` (one ``(m, 4, 4)`` array per grasp candidate)
    at task joint values ``s_samples (m,)``.

    ``hinge_xy (2,)``: for a door, a point of its (vertical) hinge line, floor frame (``kin.in_root``); the
    lateral offsets are then biased away from the hinge (``cfg.door_lateral``), so the base stands clear of the
    swinging panel. ``facing (3,)``: the world direction to stand along from the grasp (default: opposite the
    approach; a pinch on a front's edge approaches in the front's plane, so it gives the front's outward normal).
    Base poses are sampled in the robot's root frame (the floor frame, :meth:`RobotKinematics.in_root`).

    Returns a :class:`StandSearch`.
    """
    spec = kin.spec
    lower, upper = world.robot.lower, world.robot.upper
    T0 = kin.in_root(T_paths[0][0])            # the grasp in the floor frame, where the base poses are sampled
    p0 = T0[:3, 3]
    approach = T0[:3, 2]
    n = -approach[:2] if facing is None else (kin.in_root(np.eye(4))[:3, :3] @ np.asarray(facing, float))[:2]
    if np.linalg.norm(n) < 1e-6:
        n = np.array([1.0, 0.0])
    n = n / np.linalg.norm(n)
    perp = np.array([-n[1], n[0]])
    lat_range = (-cfg.stand_lateral, cfg.stand_lateral)
    if hinge_xy is not None:
        if perp @ (p0[:2] - hinge_xy) < 0:
            perp = -perp   # +perp points from the hinge toward the handle (the free edge)
        lat_range = cfg.door_lateral
    arm = np.zeros(spec.dof, bool)
    arm[3:] = True
    strained = arm & ~kin.prismatic   # the columns of the reach margin
    weights = ik_weights(kin, cfg)
    m = len(s_samples)
    idx = np.unique(np.linspace(0, m - 1, max(2, cfg.stand_path_samples)).round().astype(int))
    kept: list[StandPose] = []
    n_ik = n_complete = 0
    missed: list[np.ndarray] = []   # base-feasible seeds from which no grasp was reached (for the reason)
    far: list[tuple[float, np.ndarray]] = []   # base-feasible seeds rejected as out of reach (for the miss)
    for trial in range(cfg.stand_candidates):
        d = rng.uniform(*cfg.stand_distance)
        lat = rng.uniform(*lat_range)
        xy = p0[:2] + n * d + perp * lat
        to_handle = p0[:2] - xy
        yaw = math.atan2(to_handle[1], to_handle[0]) + rng.uniform(-cfg.stand_yaw_noise, cfg.stand_yaw_noise)
        q_seed = spec.q_with_base(spec.home_q, xy[0], xy[1], yaw)
        if world.in_collision(q_seed, s_samples[0], True):   # base (arm at home) collides: cheap rejection
            continue
        dist = kin.shoulder_distance(q_seed, T_paths[0][0][:3, 3])
        if dist > kin.reach:   # grasp out of the arm's reach
            far.append((dist, q_seed))
            continue
        best, successes = None, 0
        for gi, T_path in enumerate(T_paths):
            # Full restarts for the two preferred grasps, one for the fallbacks (they rarely decide).
            r = solve_ik(kin.tool_pose_jacobian, T_path[0], q_seed, lower, upper, arm, weights,
                         pos_tol=cfg.ik_pos_tol, rot_tol=cfg.ik_rot_tol,
                         restarts=cfg.ik_restarts if gi < 2 else 1, rng=rng,
                         accept=lambda q: not world.in_collision(q, s_samples[0], True))
            if not r.success:
                continue
            n_ik += 1
            successes += 1
            q, reached, margin = r.q, 1, _margin(r.q, lower, upper, strained)
            for k in idx[1:]:
                rk = solve_ik(kin.tool_pose_jacobian, T_path[k], q, lower, upper, arm, weights,
                              pos_tol=cfg.track_pos_tol, rot_tol=cfg.track_rot_tol, restarts=1, rng=rng,
                              restart_span=np.full(spec.dof, 0.3),
                              accept=lambda q, s=s_samples[k]: not world.in_collision(q, s, True))
                if not rk.success:
                    break
                q, reached, margin = rk.q, reached + 1, min(margin, _margin(rk.q, lower, upper, strained))
            cand = StandPose(np.array([xy[0], xy[1], yaw]), r.q, gi, reached / len(idx), margin)
            if best is None or cand.rank_key() < best.rank_key():
                best = cand
            if cand.path_share == 1.0 or successes == 2:   # candidates are in order of preference
                break
        if best is None and len(missed) < _DIAGNOSED_SEEDS:
            missed.append(q_seed)
        if best is not None:
            best = replace(best, clearance=world.clearance(best.q_grasp, s_samples[0]))
            kept.append(best)
            n_complete += best.path_share == 1.0
            if n_complete >= cfg.stand_keep:
                break
            # Doors rarely have complete poses: enough partial ones after half the budget will do.
            if len(kept) >= 2 * cfg.stand_keep and trial + 1 >= cfg.stand_candidates // 2:
                break
    kept.sort(key=StandPose.rank_key)
    summary = (f"{trial + 1} stand poses sampled, IK reached the grasp from {n_ik}, the whole opening path "
               f"(base fixed) from {n_complete}")
    if kept:
        return StandSearch(kept, summary)
    if missed:
        summary += _grasp_blockers(kin, world, T_paths, s_samples[0], missed, cfg)
    seeds = missed + [q for _, q in sorted(far, key=lambda dq: dq[0])[:_DIAGNOSED_SEEDS]]
    miss = _nearest_miss(kin, world, T_paths[0][0], seeds) if seeds else None
    return StandSearch(kept, summary, miss)


def _nearest_miss(kin, world, T_grasp: np.ndarray, seeds: list) -> float:
    """Smallest distance (m) from the tool origin to the grasp point ``T_grasp[:3, 3]`` that position-only
    IK of the arm joints (collisions ignored) reaches from the base poses of ``seeds`` ((dof,) each)."""
    arm = np.zeros(kin.spec.dof, bool)
    arm[3:] = True
    return min(solve_ik(kin.tool_pose_jacobian, T_grasp, q, world.robot.lower, world.robot.upper, arm, None,
                        pos_tol=1e-3, max_iter=200, position_only=True).pos_error for q in seeds)


_DIAGNOSED_SEEDS = 3
"""When no stand pose reaches the grasp, this many of the sampled seeds are re-solved without collision
checks to name what the grasp configurations collide with (only then: successful searches pay nothing)."""


def _grasp_blockers(kin, world, T_paths: list, s0: float, seeds: list, cfg: PlannerConfig) -> str:
    """``"; the grasp collides with: A / B (k of n), ..."``: the scene geometries that the collision-free
    IK rejected, from grasp IK solved without collision checks (its own seeded generator, so the stand
    search's random stream is untouched); ``""`` when IK misses the grasp even without them."""
    spec = kin.spec
    arm = np.zeros(spec.dof, bool)
    arm[3:] = True
    rng = np.random.default_rng(0)
    counts: dict[tuple[str, str], int] = {}
    n = 0
    for q_seed in seeds:
        for T_path in T_paths[:2]:   # the preferred candidates
            r = solve_ik(kin.tool_pose_jacobian, T_path[0], q_seed, world.robot.lower, world.robot.upper, arm,
                         None, pos_tol=cfg.ik_pos_tol, rot_tol=cfg.ik_rot_tol, restarts=1, rng=rng)
            if not r.success:
                continue
            n += 1
            for pair in dict.fromkeys(world.colliding_pairs(r.q, s0, True)):
                counts[pair] = counts.get(pair, 0) + 1
    if not counts:
        return ""
    top = sorted(counts.items(), key=lambda kv: -kv[1])[:3]
    return "; the grasp collides with: " + ", ".join(f"{a} / {b} ({k} of {n})" for (a, b), k in top)

