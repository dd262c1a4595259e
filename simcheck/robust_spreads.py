"""What a robust certificate perturbs, and by how much: every spread a documented constant.

Three sources (issue 14):

* :class:`JointSpreads` -- how sure the reconstruction is of the task's joint: RMS angle of its axis
  (deg), RMS distance of its axis line across the axis (m), RMS error of its upper limit (m or rad). Read
  from the ``uncertainty`` block recon writes per joint in ``graph.json`` beside the scene URDF
  (:func:`joint_spreads_for`); without one (a third-party model) :data:`DEFAULT_JOINT_SPREADS`.
* :class:`PhysicsRanges` -- what a scan cannot see: joint friction and damping, the moving part's mass,
  the handle's friction. Uniform ranges.
* :class:`RobotErrors` -- the robot's own errors: its base pose (localisation), the handle's position as
  it perceives it, its controller's tracking (position gain).

Units: metres, radians unless a name says ``_deg``; friction N (prismatic) or N·m (revolute); damping
N·s/m or N·m·s/rad.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import asdict, dataclass
from pathlib import Path

from simcheck.errors import SimcheckInputError

__all__ = ["JointSpreads", "PhysicsRanges", "RobotErrors", "RobustSpreads", "DEFAULT_JOINT_SPREADS",
           "DEFAULT_PHYSICS_RANGES", "DEFAULT_ROBOT_ERRORS", "DEFAULT_SPREADS", "JointCentre", "joint_spreads_for", "check_robust_args", "spreads_dict"]


@dataclass(frozen=True)
class JointSpreads:
    """RMS spreads of the task's joint (recon's bootstrap, or defaults).

    axis_deg : RMS angle (deg) of the axis; origin_m : RMS distance (m) of the axis line, across the
    axis; upper : RMS error of the upper limit (m prismatic, rad revolute); source : where they came from
    ("graph.json" or "default").
    """

    axis_deg: float
    origin_m: float
    upper: float
    source: str


DEFAULT_JOINT_SPREADS = {
    "prismatic": JointSpreads(axis_deg=1.0, origin_m=0.005, upper=0.02, source="default"),
    "revolute": JointSpreads(axis_deg=1.0, origin_m=0.01, upper=0.05, source="default"),
}
"""Spreads used without recon's uncertainty (a third-party model): a drawer's axis within ~1 deg and its
travel within ~2 cm, a door's hinge line within ~1 cm and its stop within ~3 deg; about the realistic
reconstructions' p90 joint errors (docs/decisions.md)."""


@dataclass(frozen=True)
class PhysicsRanges:
    """Uniform ranges (lo, hi) of what a scan cannot see.

    joint_friction : Coulomb friction of the task's joint (N or N·m); simcheck emulates it with a
        velocity motor and never uses less than ``PhysicsConfig.min_joint_friction``.
    joint_damping : viscous damping of the task's joint (N·s/m or N·m·s/rad).
    mass_scale : factor on the moving part's mass and inertia (particle board to solid wood).
    handle_friction : lateral friction coefficient of the handle links.
    """

    joint_friction: tuple[float, float] = (0.5, 2.5)
    joint_damping: tuple[float, float] = (0.5, 3.0)
    mass_scale: tuple[float, float] = (0.7, 1.5)
    handle_friction: tuple[float, float] = (0.5, 1.0)


DEFAULT_PHYSICS_RANGES = PhysicsRanges()


@dataclass(frozen=True)
class RobotErrors:
    """Standard deviations / ranges of the robot's own errors.

    base_xy_m : σ (m) of the base's position error along x and along y (where it is vs where it thinks);
        0.014 per axis is an RMS distance of 2 cm
    base_yaw_deg : σ (deg) of its heading error
    handle_m : σ (m) per axis of the handle position as perceived (kept in the plane of the part's front)
    tracking_gain : uniform range of the factor on the arm's position-control gain (controller tracking)
    guarded_approach : the robot re-perceives the handle once it stands at its stand pose and corrects the
        rest of its path for its own base error (:mod:`simcheck.robust_correction`); False: the plan is
        replayed open loop, the base error uncorrected
    reperception_m : σ (m) per axis (x, y and vertical) of that re-perception's error (where the robot then
        thinks the handle is, relative to itself, minus where it is); the vertical offset it finds is taken up
        by the arm
    reperception_yaw_deg : σ (deg) of the heading error of that re-perception (the front's face normal)
    """

    base_xy_m: float = 0.014
    base_yaw_deg: float = 1.0
    handle_m: float = 0.005
    tracking_gain: tuple[float, float] = (0.7, 1.3)
    guarded_approach: bool = True
    reperception_m: float = 0.003
    reperception_yaw_deg: float = 0.5


DEFAULT_ROBOT_ERRORS = RobotErrors()


@dataclass(frozen=True)
class RobustSpreads:
    """Everything a robust certificate samples from besides recon's per-joint uncertainty.

    physics, robot : the ranges and errors above; joint_defaults : the task joint's spreads without a
    graph.json, per "prismatic" / "revolute"; source : "default" or the spreads file they were read from
    (``--spreads FILE``, :mod:`simcheck.spreads_file`).
    """

    physics: PhysicsRanges
    robot: RobotErrors
    joint_defaults: dict
    source: str = "default"


DEFAULT_SPREADS = RobustSpreads(DEFAULT_PHYSICS_RANGES, DEFAULT_ROBOT_ERRORS, DEFAULT_JOINT_SPREADS)


@dataclass(frozen=True)
class JointCentre:
    """Where the worlds' joint is centred (the value the scan supports), world frame at q = 0.

    axis : (3,) unit; origin : (3,) metres, a point on the axis; upper : m or rad; source : "graph.json"
    (recon's estimate from the scan) or "urdf" (the certified URDF's own joint). other_origin : (3,) a point
    on the hinge line at the door's other edge when recon left its side undecided (:mod:`simcheck.hinge_side`;
    half of the worlds are hinged there, about the reversed axis), else None.
    """

    axis: tuple[float, float, float]
    origin: tuple[float, float, float]
    upper: float
    source: str
    other_origin: tuple[float, float, float] | None = None


def check_robust_args(robust: int, min_success: float) -> None:
    """Raise :class:`SimcheckInputError` naming ``robust`` / ``min_success`` when out of range."""
    if isinstance(robust, bool) or not isinstance(robust, int) or robust < 1:
        raise SimcheckInputError(f"robust: the number of sampled worlds must be an integer >= 1, got {robust!r}")
    if not isinstance(min_success, (int, float)) or not (0.0 < float(min_success) <= 1.0):
        raise SimcheckInputError(f"min_success: must be in (0, 1], got {min_success!r}")


def _spread(u: dict, key: str, where: str) -> float:
    if key not in u:
        raise SimcheckInputError(f"{where}: uncertainty.{key} is missing")
    v = u[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(float(v)) or float(v) < 0.0:
        raise SimcheckInputError(f"{where}: uncertainty.{key} is {v!r}; expected a finite number >= 0")
    return float(v)


def joint_spreads_for(scene_urdf: str | Path, joint: str, joint_type: str, defaults: dict = DEFAULT_JOINT_SPREADS
                      ) -> tuple[JointSpreads, JointCentre | None]:
    """The task joint's spreads and scan-supported centre from ``graph.json`` beside ``scene_urdf``.

    Returns (defaults[joint_type], None) (default :data:`DEFAULT_JOINT_SPREADS`) when there is no graph.json
    or it has no such joint or no uncertainty for it. A door whose ``uncertainty.side_undecided`` is true
    gets its other hinge in the centre (:func:`simcheck.hinge_side.other_hinge_origin`). Raises :class:`SimcheckInputError` naming the file, joint and field on an
    unreadable graph.json or an uncertainty block with a missing, NaN or negative spread.
    """
    path = Path(scene_urdf).parent / "graph.json"
    default = defaults["prismatic" if joint_type == "prismatic" else "revolute"]
    if not path.is_file():
        return default, None
    try:
        doc = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as exc:
        raise SimcheckInputError(f"{path}: cannot read it ({exc})") from exc
    for obj in doc.get("objects", []) if isinstance(doc, dict) else []:
        for j in obj.get("joints", []):
            if j.get("name") != joint or "uncertainty" not in j:
                continue
            where = f"{path}: joint {joint!r}"
            u = j["uncertainty"]
            if not isinstance(u, dict):
                raise SimcheckInputError(f"{where}: uncertainty is not an object")
            spreads = JointSpreads(_spread(u, "axis_deg", where), _spread(u, "origin_m", where),
                                   _spread(u, "upper", where), "graph.json")
            try:
                centre = JointCentre(tuple(float(x) for x in j["axis"]), tuple(float(x) for x in j["origin"]),
                                     float(j["upper"]), "graph.json")
            except (KeyError, TypeError, ValueError) as exc:
                raise SimcheckInputError(f"{where}: axis / origin / upper unreadable ({exc})") from exc
            if len(centre.axis) != 3 or len(centre.origin) != 3 or not all(
                    math.isfinite(x) for x in (*centre.axis, *centre.origin, centre.upper)):
                raise SimcheckInputError(f"{where}: axis / origin must be 3 finite numbers, upper finite")
            side = u.get("side_undecided", False)
            if not isinstance(side, bool):
                raise SimcheckInputError(f"{where}: uncertainty.side_undecided is {side!r}; expected true or false")
            if side and joint_type == "revolute":
                from simcheck.hinge_side import other_hinge_origin
                o = other_hinge_origin(scene_urdf, joint, centre.axis, centre.origin)
                centre = dataclasses.replace(centre, other_origin=tuple(map(float, o)))
            return spreads, centre
    return default, None


def spreads_dict(joint: JointSpreads, physics: PhysicsRanges, robot: RobotErrors, source: str = "default") -> dict:
    """The spreads a robust certificate was sampled with, as JSON data (``source``: "default" or the spreads
    file of the physics and robot spreads)."""
    return {"joint": asdict(joint), "physics": asdict(physics), "robot": asdict(robot), "source": source}
