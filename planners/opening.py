"""The opening motion planned with OMPL constrained planning (ProjectedStateSpace).

Ambient space: the robot's planned joints plus the task joint, ``x = (q (dof,), s)``. Constraint (6
equations): the tool pose equals the grasp pose on the moving part at joint value ``s``,

    F(x) = [ p_tool(q) - p_grasp(s) ;  log(R_tool(q) R_grasp(s)^T) ] = 0,
    dF/dx ~= [ J_tool(q) | -V_grasp(s) ],

with ``V_grasp`` the grasp frame's world twist per unit ``s`` (central differences of the scene's forward
kinematics: a straight line for a prismatic joint, an arc about the hinge for a revolute one). The manifold
has ``dof + 1 - 6`` dimensions; RRTConnect searches it from the grasp configuration to an IK goal at the
final opening. Every returned sample is checked again: limits, collisions (gripper-handle allowed) and the
tool's distance to the grasp pose at that ``s``.
"""

from __future__ import annotations

import numpy as np

from planners.config import PlannerConfig
from planners.ik import pose_error, rotvec_from_matrix, solve_ik
from planners.motion import TrackResult, densify, ik_weights
from planners.ompl_adapter import plan_constrained_path

__all__ = ["plan_opening_constrained"]


def plan_opening_constrained(kin, world, T_link_grasp: np.ndarray, s0: float, s1: float, q_start: np.ndarray,
                             cfg: PlannerConfig, seed: int, rng: np.random.Generator) -> TrackResult:
    """Plan the opening from ``q_start (dof,)`` (grasping at ``s0``) to joint value ``s1`` on the constraint
    manifold. Returns a :class:`planners.motion.TrackResult` (``q (n, dof)``, ``s (n,)``)."""
    dof = len(q_start)
    h = 1e-4

    def T_grasp(s: float) -> np.ndarray:
        return world.moving_link_pose(s) @ T_link_grasp

    def twist(s: float) -> np.ndarray:
        Ta, Tb = T_grasp(s + h), T_grasp(s - h)
        return np.r_[(Ta[:3, 3] - Tb[:3, 3]) / (2 * h), rotvec_from_matrix(Ta[:3, :3] @ Tb[:3, :3].T) / (2 * h)]

    def function(x: np.ndarray) -> np.ndarray:
        T = kin.tool_pose(x[:dof])
        Tg = T_grasp(float(x[dof]))
        return -pose_error(T, Tg)   # tool minus grasp (position; rotation vector of R_tool R_grasp^T)

    def jacobian(x: np.ndarray) -> np.ndarray:
        _, J = kin.tool_pose_jacobian(x[:dof])
        return np.column_stack([J, -twist(float(x[dof]))])

    # Start and goal must lie on the manifold (OMPL rejects states off it): refine the start tightly.
    start_ik = solve_ik(kin.tool_pose_jacobian, T_grasp(s0), q_start, world.robot.lower, world.robot.upper,
                        None, ik_weights(kin, cfg), pos_tol=2e-5, rot_tol=2e-4, max_iter=50)
    if start_ik.success and not world.in_collision(start_ik.q, s0, True):
        q_start = start_ik.q
    goal_ik = solve_ik(kin.tool_pose_jacobian, T_grasp(s1), q_start, world.robot.lower, world.robot.upper,
                       None, ik_weights(kin, cfg), pos_tol=2e-5, rot_tol=2e-4,
                       restarts=cfg.ik_restarts, rng=rng, restart_span=np.r_[np.full(3, 0.6), np.full(dof - 3, 1.0)],
                       accept=lambda q: not world.in_collision(q, s1, True))
    if not goal_ik.success:
        return TrackResult(False, q_start[None], np.array([s0]), "no collision-free IK goal at the final opening",
                           0)
    # Sample near the start and goal: Newton projection from far-away samples of a redundant arm rarely
    # converges, and a failed projection is a wasted sample.
    margin = np.r_[0.3, 0.3, 0.5, np.full(dof - 3, 0.8)]
    lo = np.r_[np.maximum(world.robot.lower, np.minimum(q_start, goal_ik.q) - margin), min(s0, s1) - 1e-3]
    hi = np.r_[np.minimum(world.robot.upper, np.maximum(q_start, goal_ik.q) + margin), max(s0, s1) + 1e-3]

    def valid(x: np.ndarray) -> bool:
        q = x[:dof]
        return world.within_limits(q) and not world.in_collision(q, float(x[dof]), True)

    res = plan_constrained_path(np.r_[q_start, s0], np.r_[goal_ik.q, s1], lo, hi, function, jacobian, 6, valid,
                                time_limit=cfg.constrained_time, seed=seed, max_step=cfg.max_joint_step,
                                tolerance=1e-3)
    if not res.success:
        return TrackResult(False, q_start[None], np.array([s0]), res.reason, 0)
    q, s = densify(res.path[:, :dof], res.path[:, dof], cfg.max_joint_step)
    for k in range(len(q)):
        dev = np.linalg.norm(kin.tool_pose(q[k])[:3, 3] - T_grasp(s[k])[:3, 3])
        if dev > cfg.track_pos_tol:
            return TrackResult(False, q[:k], s[:k], f"constrained path leaves the handle path by "
                               f"{dev * 1000:.1f} mm at sample {k}", k)
        if not world.within_limits(q[k]) or world.in_collision(q[k], s[k], True):
            return TrackResult(False, q[:k], s[:k], f"constrained path invalid at sample {k} when re-checked", k)
    return TrackResult(True, q, s, "ok", -1)
