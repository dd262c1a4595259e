"""Every threshold of the planners, named once (:class:`PlannerConfig`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["PlannerConfig", "default_amount"]


@dataclass(frozen=True)
class PlannerConfig:
    """Planning parameters. Units: metres, radians, seconds.

    Grasp
        grasp_tilt: downward tilt of the approach for horizontal handle bars (STACK: ~20 deg helps); a level
            grasp is the fallback candidate.
        grasp_backoff: fallback grasp held this much further out than the bar centre (short knobs) ...
        grasp_backoff_share: ... but at most this share of the grasped shape's depth along the approach
            (0.5: the tool frame stays within the bar's outer face; the fingertips reach past it). A 12 mm
            bar is then backed off 6 mm, not 15 mm (which closed the fingers on air, planners.handle).
        pregrasp_distance: tool stand-off before the straight grasp motion, along the approach axis.
        retreat_distance: straight retreat along the approach axis after releasing; when blocked, half
            of it, down to min_retreat_distance, is tried.
        grasp_turn_share: on a door that swings up or down (a horizontal hinge) with a round bar along the
            hinge, the share of the door's turn the tool follows: the bar rolls about its own axis between the
            flat pads by the rest (simcheck does not count that roll as the handle turning out of the fingers),
            so the wrist turns less than the door (a dishwasher's handle ends low facing the floor, a flap's
            high facing up).
        min_handle_lever: a grasp point that moves less than this per unit joint value (m/m or m/rad)
            cannot be pulled (it sits on the hinge axis).
    Push finish (:mod:`planners.push_finish`: a door on a horizontal hinge whose grasped opening ends short)
        push_finish: plan it at all; push_min_share: the grasped opening must reach this share of the request
            first (the inner face must be open to the hand); push_inset: the fingertips push this far in from
            the door's free edge, m; push_lead: m, how far short of the door's inner face the move onto it stops
            and ahead of the fingertips the planning checks put the face (the tips on the face are not a
            collision): about the estimate's hinge-line error (a centimetre), so the free move does not meet a
            door that lies a little nearer than estimated; push_effort_share: a grasped opening that would
            statically load an arm joint beyond this share of its effort limit is handed over to the push there
            (half: the margin the certificate keeps on the gripper's hold, for what statics leaves out -- the
            door's damping and inertia, the compliant grasp's lag); push_tilts: rad, the approach axis tilted from the
            face's normal toward the hinge, tried in turn (the hand beyond the free edge, clear of the opening).
    Default amounts
        drawer_fraction: share of a prismatic joint's range opened by default.
        door_fraction, door_max: a door opens min(door_fraction * range, door_max) by default (85 deg: short
            of the 90 deg stop many files give their doors, which an estimate a little wider than its
            reference would otherwise request exactly).
    Stand pose sampling
        stand_distance: (min, max) horizontal distance from the handle to the base centre along the
            outward normal; stand_lateral: half-width of the lateral offset (drawers); door_lateral: (min,
            max) lateral offset for doors, positive away from the hinge; stand_yaw_noise: half-width of
            the yaw noise about facing the handle; stand_candidates: poses sampled; stand_keep: stop after
            this many poses that reach the whole opening path; stand_tries: ranked poses planned from
            before giving up; stand_path_samples: path points checked
            with the base fixed.
        start_backoff: when no start configuration is given, the robot starts this far behind the stand
            pose with the arm at home (falls back to the stand pose itself if that is in collision).
    Collision
        clearance: distance (m) robot links other than the gripper keep from the scene and the floor.
        approach_clearance: distance (m) the gripper keeps from every scene link but the task's part on the
            free approach to the pre-grasp and at the pre-grasp (near the grasp it may come as close as the
            grasp needs); 0.03: about 2 sigma of the robot's own base position error (1.4 cm per horizontal
            axis, ``simcheck.robust_spreads``), which the free approach is executed with (docs/decisions.md).
    IK
        ik_pos_tol, ik_rot_tol: convergence (m, rad); ik_restarts: random restarts per pose;
        base_weight: relative motion weight of base joints during whole-body tracking (< 1 favours the arm).
        lift_weight: relative motion weight of a torso lift (the prismatic arm joints before the shoulder,
            metres) in every IK: < 1 moves the arm first, so the lift rises or sinks only where the arm alone
            falls short (a metre of lift is a large tool motion next to a radian of arm joint).
    Motion
        approach_time: OMPL time limit for the approach; approach_planner: OMPL geometric planner name;
        approach_check_step: OMPL's edge-checking step (Euclidean norm in joint space, m and rad mixed);
        approach_attempts: plans tried (seed + i, step halved) until one passes the dense re-check;
        max_joint_step: densest joint-space spacing of returned and collision-checked samples (rad or m);
        open_step_prismatic / open_step_revolute: task-joint spacing of opening waypoints;
        track_pos_tol, track_rot_tol: tool pose error allowed at any opening sample;
        open_method: "ik_tracking", "constrained" or "auto" (tracking, then constrained planning if it fails);
        constrained_time: time limit of OMPL constrained planning of the opening (0 disables the fallback);
        constrained_stands: in "auto", the fallback runs only from the best this-many stand poses.
    """

    grasp_tilt: float = math.radians(20.0)
    grasp_backoff: float = 0.015
    grasp_backoff_share: float = 0.5
    pregrasp_distance: float = 0.10
    retreat_distance: float = 0.12
    min_retreat_distance: float = 0.04
    grasp_turn_share: float = 0.5
    min_handle_lever: float = 0.05
    push_finish: bool = True
    push_min_share: float = 0.3
    push_inset: float = 0.04
    push_lead: float = 0.015
    push_tilts: tuple = (0.0, math.radians(30.0), math.radians(60.0))
    push_effort_share: float = 0.5
    drawer_fraction: float = 0.9
    door_fraction: float = 0.9
    door_max: float = math.radians(85.0)
    stand_distance: tuple = (0.55, 0.95)
    stand_lateral: float = 0.35
    door_lateral: tuple = (-0.35, 0.6)
    stand_yaw_noise: float = math.radians(25.0)
    stand_candidates: int = 40
    stand_keep: int = 3
    stand_tries: int = 6
    stand_path_samples: int = 6
    start_backoff: float = 0.35
    clearance: float = 0.01
    approach_clearance: float = 0.03
    ik_pos_tol: float = 1e-3
    ik_rot_tol: float = 1e-2
    ik_restarts: int = 4
    base_weight: float = 0.3
    lift_weight: float = 0.1
    approach_time: float = 3.0
    approach_planner: str = "RRTConnect"
    approach_check_step: float = 0.03
    approach_attempts: int = 3
    max_joint_step: float = 0.02
    open_step_prismatic: float = 0.01
    open_step_revolute: float = math.radians(1.5)
    track_pos_tol: float = 3e-3
    track_rot_tol: float = 2e-2
    open_method: str = "auto"
    constrained_time: float = 3.0
    constrained_stands: int = 2


def default_amount(kind: str, lower: float, upper: float, cfg: PlannerConfig) -> float:
    """Default opening (m or rad) of a joint with range ``[lower, upper]``: drawers ``cfg.drawer_fraction`` of
    the range; doors ``min(cfg.door_fraction`` of it, ``cfg.door_max)``. ``kind``: "drawer" or "door"."""
    span = upper - lower
    return cfg.drawer_fraction * span if kind == "drawer" else min(cfg.door_fraction * span, cfg.door_max)
