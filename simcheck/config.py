"""Every threshold simcheck uses, named once: physics/execution settings and the certificate criteria.

Two frozen dataclasses:

* :class:`PhysicsConfig` -- how the world is simulated and how the robot is driven (time step, solver
  iterations, damping, emulated joint friction, controller speed limits, when a grasp forms and how its load is averaged; the grasp's force bound
  comes from the robot's gripper model, ``planners.robot.GripperModel``).
* :class:`CriteriaConfig` -- what a certificate demands. It has a ``name`` and a ``version``; a
  certificate records both and every value, so a certificate says which rules it was judged by.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

__all__ = ["PhysicsConfig", "CriteriaConfig", "DEFAULT_PHYSICS", "DEFAULT_CRITERIA"]


@dataclass(frozen=True)
class PhysicsConfig:
    """Simulation and execution settings (SI units).

    Attributes:
        time_step: physics step, seconds (160 Hz; why: docs/decisions.md, "PyBullet step settings").
        solver_iterations: constraint solver iterations per step (fixed, for determinism; 20 instead of
            PyBullet's 50; see docs/decisions.md, "PyBullet step settings").
        contact_breaking_threshold: distance, metres, within which Bullet keeps contact points and grows
            every collider's bounding box for the broad phase (Bullet's default 0.02). 0.01 m is more than
            a robot link moves in one step (<= ~6 mm at 1 m/s and 160 Hz), so no contact starts deeper.
            Bullet keeps this one value per process (a global): every World sets it.
        gravity: gravity along world -z, m/s^2.
        scene_joint_damping: extra linear/angular link damping for scene bodies (PyBullet ``changeDynamics``).
        min_joint_friction: emulated Coulomb friction of a scene joint, N or N*m, used when the URDF's
            ``<dynamics friction>`` is smaller (PyBullet ignores URDF joint friction; we emulate it with a
            zero-velocity motor of this force, which is also what keeps an opened door from drifting).
        overlap_tolerance: two scene links that already interpenetrate deeper than this (metres) in the
            loaded (closed) state never collide with each other (a third-party file's may; logged as a warning).
        rest_contact_gap: two scene links closer than this (metres; touching, or interpenetrating by any
            depth) in the loaded state are "in contact at rest" (sibling fronts, a door in its frame): Bullet
            does not collide them, so the contact neither blocks the opening nor counts as a contact of the
            moving part; how much deeper than at rest they then interpenetrate is recorded instead
            (``CriteriaConfig.rest_contact_slack``; the policy: docs/decisions.md, "Touching at rest").
        speed_scale: fraction of each robot joint's URDF velocity limit used to time-parametrise a plan.
        max_joint_speed: cap on any robot joint speed while executing, rad/s or m/s (the approach's cap is
            ``approach_speed_scale`` times this).
        open_speed_scale: extra slow-down of the opening segment (pulling an object is done gently).
        approach_speed_scale: extra speed-up of the approach to the pre-grasp (gripper open, away from the part,
            every state of the path collision-checked with the planner's clearance), with its ``ramp_time`` longer
            by as much: its accelerations are those of every other segment, only its top speed is higher (1.8: the
            Panda's joints at up to 1.44 rad/s of their 2.175-2.61 spec, the base 0.9 m/s of its URDF 1.0). The
            retreat keeps ``speed_scale`` (why: docs/decisions.md, "CPU per certification").
        ramp_time: seconds over which every segment's speed ramps up from rest and back down to rest
            (a trapezoidal velocity profile, as a real arm's acceleration limits impose; with a step in
            speed the arm jerks a grasped drawer to speed in one physics step).
        settle_time: seconds the robot holds still after each segment before the next one starts.
        final_settle_time: seconds simulated after the last segment before the end state is measured.
        gripper_close_time: seconds allowed for the fingers to close on a handle.
        gripper_open_time: seconds allowed for the fingers to open on release.
        grasp_break_distance: slip (metres) between the tool and the grasped point at which the
            attachment is considered torn off and removed, as a real grasp would let go.
        grasp_force_window: seconds over which the grasp's force is averaged (a running mean at every
            physics step) for the slip test and the recorded ``grasp_force``: a friction grip slips under
            a sustained load, not under a one-step solver impulse.
        grasp_stiffness: stiffness, N/m, of the isotropic spring that holds the grasped point to the tool
            for a robot whose spec gives no joint stiffness (``SimRobot.joint_stiffness``; with one, the
            spring is the tool's Cartesian stiffness under that joint impedance, see ``grasp_stiffness_every``).
        grasp_damping: damping, N*s/m, of that spring.
        grasp_stiffness_every: with a robot's joint stiffness, the tool's Cartesian stiffness is computed again
            (and its stable cap applied) every this many physics steps of the grasp, from the first (5 at 160 Hz
            = 32 Hz: the arm's configuration moves ~0.015 rad at most in between; measured against every step in
            docs/decisions.md, "The grasp spring's stiffness at 32 Hz").
        grasp_max_turn: the grasp is lost when the handle has turned more than this in the fingers, rad
            (the grasp transmits no torque; 20 deg turns a bar out of flat pads). A round bar held across
            its axis rolls between the pads: its roll about its own axis is not counted, only the turn of
            that axis (:func:`simcheck.grasp.round_bar_axis`).
        grasp_roll_tolerance: both pads' contact points within this of a cylinder's radius from its axis,
            metres, are on its round side (PyBullet's contact points lie a fraction of a millimetre off).
        grasp_roll_angle: the fingers close across a bar's axis when their closing direction is within this
            of perpendicular to it, rad (then flat pads touch it along lines parallel to the axis).
        grasp_contact_distance: a finger's contact point with the handle touches when it is at most this
            far, metres (PyBullet keeps contact points up to ``contact_breaking_threshold`` apart).
        grasp_normal_angle: largest angle, rad, between a finger's contact normal and its opening
            direction for the contact to be on the finger's pad (45 deg: a fingertip or finger side
            touching is 90 deg off; a pad on a round or slightly tilted bar is a few deg off, on a box
            bar's edge a few tens of deg).
        grasp_min_travel: a finger nearer than this (m or rad) to fully closed was not stopped by the handle.
        grasp_min_width: the handle between the two pads' contact points must be at least this wide, metres.
        robot_position_gain: PyBullet position-control gain of the robot joints.
        record_every: record one rollout sample, and check the grasp slip against
            ``grasp_break_distance``, every this many physics steps (5 = 32 Hz; checking the slip at every
            step cost ~10% of a door task's execution time and changed no outcome).
        control_every: send new robot joint targets every this many physics steps (1 = 160 Hz; PyBullet's
            motors hold the last target and feed-forward velocity in between).
        contact_every: query contacts every this many physics steps (1 = 160 Hz:
            any contact lasting more than 6.25 ms is seen; the largest force/depth in between is kept).
        contact_tolerance: penetration depth (metres) below which a contact point is ignored when recording.
        freeze_margin: a rollout that may (``execute_task(freeze_far=True)``) leaves out of the simulation every
            moving scene part at rest farther than this, metres, from everything the plan's robot and the parts
            it can move may sweep, and loads them again if the robot strays half of it from its path
            (:mod:`simcheck.frozen_bodies`); 0: the whole scene is always simulated.
    """

    time_step: float = 1.0 / 160.0
    solver_iterations: int = 20
    contact_breaking_threshold: float = 0.01
    gravity: float = 9.81
    scene_joint_damping: float = 0.04
    min_joint_friction: float = 0.5
    overlap_tolerance: float = 0.002
    rest_contact_gap: float = 0.001
    speed_scale: float = 0.5
    max_joint_speed: float = 0.8
    open_speed_scale: float = 0.6
    approach_speed_scale: float = 1.8
    ramp_time: float = 0.25
    settle_time: float = 0.25
    final_settle_time: float = 1.0
    gripper_close_time: float = 0.6
    gripper_open_time: float = 0.4
    grasp_break_distance: float = 0.06
    grasp_force_window: float = 0.05
    grasp_stiffness: float = 7000.0
    grasp_damping: float = 50.0
    grasp_stiffness_every: int = 5
    grasp_max_turn: float = 0.3490658503988659
    grasp_roll_tolerance: float = 0.003
    grasp_roll_angle: float = 0.2617993877991494
    grasp_contact_distance: float = 0.0005
    grasp_normal_angle: float = 0.7853981633974483
    grasp_min_travel: float = 0.001
    grasp_min_width: float = 0.003
    robot_position_gain: float = 0.3
    record_every: int = 5
    control_every: int = 1
    contact_every: int = 1
    contact_tolerance: float = 0.0
    freeze_margin: float = 0.15

    def replace(self, **changes) -> "PhysicsConfig":
        """A copy with ``changes`` applied."""
        return dataclasses.replace(self, **changes)


@dataclass(frozen=True)
class CriteriaConfig:
    """What a task must show to be certified. Versioned: a certificate records ``name``, ``version``
    and every field below.

    Attributes:
        opened_fraction: minimum opened joint value / requested amount at the end (0.9: the issue's
            "joint reaches >= 90% of the requested amount").
        opened_overshoot: maximum opening past the request at the end, as a fraction of the request
            (0.1: a door swung far past the plan, or a drawer pulled out farther, moved where nothing
            was checked for collision).
        settled_linear_speed: maximum speed of the moved link right after the gripper let go (the last
            sample of the release segment, before the retreat and the final hold), m/s (0.05; common
            open-cabinet benchmarks such as ManiSkill's OpenCabinetDrawer/Door use 0.1 at the episode's
            end; a part that rests after release reads ~0, and a front that drops onto its own stop
            after release rests there by then).
        settled_angular_speed: the same for the angular speed, rad/s (0.25; ManiSkill: 1.0 at the end).
        handle_path_tolerance: maximum distance, metres, between the grasped point of the handle and
            the planned tool position, at every recorded instant of the opening segment and at the end
            of it (0.03 m: a few cm of controller lag and grasp compliance is normal; a 30 deg axis
            error over a 0.3 m pull is ~0.15 m).
        contact_force_tolerance: robot-scene contacts other than gripper-handle are unexpected when
            their normal force exceeds this, N (small numerical brushes are tolerated).
        contact_penetration_tolerance: ... or when their penetration is deeper than this, metres.
        grasp_slip_tolerance: maximum slide of the grasped point on the handle in the fingers during the
            opening segment, metres (rollouts recorded before the slide was: the distance between the tool
            frame and the grasped point); the grasp also must exist for the whole segment.
        grasp_safety_factor: the ``grasp_force`` criterion allows at most the gripper's holding force
            divided by this (2: gripper sizing practice for a friction grip, required grip >= load x
            safety factor / (friction x contacts), so that an unknown handle finish, a worn pad or a
            dynamic peak does not slip the handle). The simulated grasp still slips only above the
            holding force itself.
        end_stop_tolerance: a part whose joint is within this (m or rad) of one of its limits rests on its
            end stop; the grasp's pull is not judged there (``grasp_force``, ``interaction_force``): a plan
            asking a few mm past the real stop pulls into the stop after the part is open, and the handle
            slides in the fingers (``grasp_held``). 0.002: PyBullet holds a loaded joint within a fraction
            of a millimetre of its limit.
        joint_limit_tolerance: maximum excursion of a robot joint beyond its URDF limits, rad or m.
        robot_effort_share: largest share of its URDF effort limit a robot joint's motor may apply, averaged
            over ``PhysicsConfig.grasp_force_window`` (0.99: held at its limit -- the simulated motor is capped
            at exactly 1 -- the joint no longer follows the plan; a passing step-long spike averages out).
        plan_penetration_tolerance: penetration depth, metres, above which a state of the densely
            interpolated plan counts as colliding in the independent PyBullet re-check.
        recheck_resolution: maximum joint step, rad or m, between re-checked states of the plan.
        max_waypoint_gap: a given plan's largest joint step between consecutive waypoints, rad or m (a
            trajectory controller interpolates between waypoints itself; farther apart, the path between
            them is the controller's, not the plan's; our own planner's plans stay below it:
            docs/decisions.md, "Given plans").
        acceleration_window: seconds over which a given plan's joint accelerations are measured (the
            second difference of its piecewise-linear path; a corner or a start at speed counts as the
            velocity change spread over this window).
        articulation_tolerance: how far, m or rad, a scene joint may move in a given plan's segment that
            does not expect it to, and how far an expectation's ``from`` may be from the joint's value.
        rest_contact_slack: links in contact at rest (``PhysicsConfig.rest_contact_gap``) may interpenetrate
            at most this much deeper than they did at rest while the part moves, metres (a door whose
            corner sweeps into the sibling it touched has passed through it: physically, it is blocked).
        closed_range_fraction, closed_gap_prismatic, closed_gap_revolute: a close task's part counts as
            closed when it ends within ``closed_range_fraction`` of its joint's range of its closed value,
            or within ``closed_gap_prismatic`` m / ``closed_gap_revolute`` rad if that is larger (the
            issue's "2% of the range, 1 cm / 2 deg, whichever is larger"). A close task is judged by this
            instead of the opened fraction and overshoot.
    """

    name: str = "partscene-default"
    version: str = "2.2"
    opened_fraction: float = 0.9
    opened_overshoot: float = 0.1
    settled_linear_speed: float = 0.05
    settled_angular_speed: float = 0.25
    handle_path_tolerance: float = 0.03
    contact_force_tolerance: float = 5.0
    contact_penetration_tolerance: float = 0.005
    grasp_slip_tolerance: float = 0.02
    grasp_safety_factor: float = 2.0
    end_stop_tolerance: float = 0.002
    joint_limit_tolerance: float = 0.01
    robot_effort_share: float = 0.99
    plan_penetration_tolerance: float = 0.005
    recheck_resolution: float = 0.02
    max_waypoint_gap: float = 0.15
    acceleration_window: float = 0.1
    articulation_tolerance: float = 0.01
    rest_contact_slack: float = 0.003
    closed_range_fraction: float = 0.02
    closed_gap_prismatic: float = 0.01
    closed_gap_revolute: float = math.radians(2.0)

    def replace(self, **changes) -> "CriteriaConfig":
        """A copy with ``changes`` applied."""
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict:
        """Every field, JSON-ready."""
        return dataclasses.asdict(self)


#: The unit of each numeric field of :class:`CriteriaConfig` ("" for a fraction of the request).
CRITERIA_UNITS = {"opened_fraction": "", "opened_overshoot": "", "settled_linear_speed": "m/s",
                  "settled_angular_speed": "rad/s", "handle_path_tolerance": "m", "contact_force_tolerance": "N",
                  "contact_penetration_tolerance": "m", "grasp_slip_tolerance": "m",
                  "joint_limit_tolerance": "rad or m", "plan_penetration_tolerance": "m",
                  "recheck_resolution": "rad or m", "max_waypoint_gap": "rad or m", "acceleration_window": "s",
                  "articulation_tolerance": "m or rad", "rest_contact_slack": "m",
                  "closed_range_fraction": "", "closed_gap_prismatic": "m", "closed_gap_revolute": "rad",
                  "grasp_safety_factor": "", "end_stop_tolerance": "m or rad", "robot_effort_share": ""}

DEFAULT_PHYSICS = PhysicsConfig()
DEFAULT_CRITERIA = CriteriaConfig()
