"""Sampling the worlds of a robust certificate: one :class:`Perturbation` per sampled world (pure numpy).

Sample ``i`` of seed ``s`` draws from ``numpy.random.default_rng([s, i])``: it does not depend on how many
samples are drawn, so ``--replay-sample i`` rebuilds exactly that world.

The task's joint (world frame, at q = 0):

* centred on the value the scan supports (:class:`simcheck.robust_spreads.JointCentre`: recon's estimate
  in graph.json), else on the certified URDF's own joint;
* axis: turned by a rotation vector perpendicular to it, each of its two components N(0, σ²) with
  σ = axis_deg / √2, so that the RMS angle is ``axis_deg``;
* hinge line (revolute only; a prismatic joint's axis position does not change its motion): moved across
  the axis by a vector whose two components are N(0, σ²), σ = origin_m / √2 (RMS distance origin_m);
* upper limit: a drawer's + N(0, upper²); a door's + uniform in ±√3·upper (the same RMS, bounded: a
  hinge's stop lies in a range -- furniture hinges stop at 92-110 deg, recon's ``door_stop_prior`` is that
  range's RMS about its 100 deg estimate -- it has no tails below it); kept at least a tenth of the centre's.

Physics: uniform in :class:`PhysicsRanges`. Robot: base position error N(0, base_xy_m²) along x and y,
heading N(0, base_yaw_deg²), perceived handle position N(0, handle_m²) per axis (then kept in the plane of
the part's front, :func:`in_front_plane`: a depth camera's error moves the perceived front with the handle, so
it does not change the bar's standoff from the front -- recon's handle geometry), position gain factor
uniform in ``tracking_gain``; the re-perception error of the guarded approach N(0, reperception_m²) along x
and y and N(0, reperception_yaw_deg²) in heading (none without ``guarded_approach``). Then the hinge side:
a door whose side recon left undecided (:attr:`JointCentre.other_origin`) is hinged at its other edge with
probability 1/2, the perturbations above applied about that hinge (``hinge_side`` "other"). Last, the
re-perception's vertical error N(0, reperception_m²). The draws after the joint's come in a fixed order, each
of a sample independent of the later ones. ``mode="physics"`` (robust ``--against`` a reference) leaves the joint and
the robot as they are and samples the physics ranges only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from simcheck.robust_spreads import JointCentre, JointSpreads, PhysicsRanges, RobotErrors

__all__ = ["Perturbation", "sample_perturbation", "sample_perturbations", "front_normal", "in_front_plane", "MODES"]

MODES = ("scan", "physics")


@dataclass(frozen=True)
class Perturbation:
    """One sampled world, relative to the certified scene.

    joint : the task's joint name; axis (3,) unit and origin (3,) m: its world axis / axis point at q = 0;
    upper : its upper limit (m or rad); axis_off_deg / origin_off_m : how far those are from the
    certified URDF's joint (angle; distance of the axis lines across the axis); joint_friction,
    joint_damping : its dynamics; mass_scale : factor on the moving part's mass and inertia;
    handle_friction : the handles' lateral friction coefficient; base_error : (dx m, dy m, dyaw rad) of
    the robot's base (where it is minus where it thinks); handle_shift : (3,) m, world, the handle's true
    position minus the perceived one; tracking_gain : factor on the arm's position gain; reperception :
    (dx m, dy m, dyaw rad, dz m), world, the error of the robot's pose relative to the handle left after the
    guarded approach's correction (:mod:`simcheck.robust_correction`), or None: no correction (the plan is
    replayed open loop); hinge_side : "estimated", or "other" when the door is hinged at its other edge
    (its side undecided by the scan).
    """

    index: int
    joint: str
    axis: tuple[float, float, float]
    origin: tuple[float, float, float]
    upper: float
    axis_off_deg: float
    origin_off_m: float
    joint_friction: float
    joint_damping: float
    mass_scale: float
    handle_friction: float
    base_error: tuple[float, float, float]
    handle_shift: tuple[float, float, float]
    tracking_gain: float
    reperception: tuple[float, float, float, float] | None = None
    hinge_side: str = "estimated"

    def to_dict(self) -> dict:
        return {"sample": self.index, "joint": self.joint, "axis": list(self.axis), "origin": list(self.origin),
                "upper": self.upper, "axis_off_deg": self.axis_off_deg, "origin_off_m": self.origin_off_m,
                "joint_friction": self.joint_friction, "joint_damping": self.joint_damping,
                "mass_scale": self.mass_scale, "handle_friction": self.handle_friction,
                "base_error": list(self.base_error), "handle_shift": list(self.handle_shift),
                "tracking_gain": self.tracking_gain,
                "reperception": None if self.reperception is None else list(self.reperception),
                "hinge_side": self.hinge_side}


def _perpendicular_basis(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors (3,) perpendicular to the unit ``a`` (3,) and to each other."""
    helper = np.array([0.0, 0.0, 1.0]) if abs(a[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    u = np.cross(a, helper)
    u /= np.linalg.norm(u)
    return u, np.cross(a, u)


def _rotated(v: np.ndarray, rotvec: np.ndarray) -> np.ndarray:
    angle = float(np.linalg.norm(rotvec))
    if angle < 1e-15:
        return v.copy()
    k = rotvec / angle
    return v * np.cos(angle) + np.cross(k, v) * np.sin(angle) + k * (k @ v) * (1 - np.cos(angle))


def sample_perturbation(index: int, seed: int, joint: str, joint_type: str, urdf_axis, urdf_origin, urdf_upper: float,
                        centre: JointCentre | None, spreads: JointSpreads, physics: PhysicsRanges,
                        robot: RobotErrors, mode: str = "scan") -> Perturbation:
    """Sample world ``index`` (see the module docstring).

    urdf_axis (3,), urdf_origin (3,), urdf_upper : the certified URDF's joint, world frame at q = 0.
    centre : the scan-supported joint (None: the URDF's). joint_type : "prismatic" or "revolute".
    """
    if mode not in MODES:
        raise ValueError(f"mode must be one of {MODES}, got {mode!r}")
    rng = np.random.default_rng([int(seed), int(index)])
    a_urdf = np.asarray(urdf_axis, dtype=np.float64)
    a_urdf = a_urdf / np.linalg.norm(a_urdf)
    o_urdf = np.asarray(urdf_origin, dtype=np.float64)
    # every draw happens in every mode, in this order: the physics of sample i is the same in both modes
    z_axis, z_origin, z_upper = rng.standard_normal(2), rng.standard_normal(2), rng.standard_normal()
    friction = rng.uniform(*physics.joint_friction)
    damping = rng.uniform(*physics.joint_damping)
    mass = rng.uniform(*physics.mass_scale)
    handle_friction = rng.uniform(*physics.handle_friction)
    base = rng.standard_normal(3) * [robot.base_xy_m, robot.base_xy_m, np.radians(robot.base_yaw_deg)]
    handle = rng.standard_normal(3) * robot.handle_m
    gain = rng.uniform(*robot.tracking_gain)
    reperceive = rng.standard_normal(3) * [robot.reperception_m, robot.reperception_m,
                                           np.radians(robot.reperception_yaw_deg)]
    other_side = rng.random() < 0.5 and centre is not None and centre.other_origin is not None
    reperceive_z = rng.standard_normal() * robot.reperception_m
    if mode == "physics":
        return Perturbation(int(index), joint, tuple(a_urdf), tuple(o_urdf), float(urdf_upper), 0.0, 0.0,
                            float(friction), float(damping), float(mass), float(handle_friction), (0.0, 0.0, 0.0),
                            (0.0, 0.0, 0.0), 1.0)
    if centre is None:
        a_c, o_c, u_c = a_urdf, o_urdf, float(urdf_upper)
    else:
        a_c = np.asarray(centre.axis, dtype=np.float64)
        a_c = a_c / np.linalg.norm(a_c)
        if a_c @ a_urdf < 0:
            a_c = -a_c
        o_c, u_c = np.asarray(centre.origin, dtype=np.float64), float(centre.upper)
        if other_side:               # the same line at the other edge, reversed: a positive angle still opens
            a_c, o_c = -a_c, np.asarray(centre.other_origin, dtype=np.float64)
    u1, u2 = _perpendicular_basis(a_c)
    s_axis = np.radians(spreads.axis_deg) / np.sqrt(2.0)
    axis = _rotated(a_c, s_axis * (z_axis[0] * u1 + z_axis[1] * u2))
    if joint_type == "revolute":
        origin = o_c + spreads.origin_m / np.sqrt(2.0) * (z_origin[0] * u1 + z_origin[1] * u2)
    else:
        origin = o_urdf.copy()
    if joint_type == "revolute":                   # the same draw, mapped to uniform(-√3, √3)
        z_upper = np.sqrt(3.0) * math.erf(z_upper / np.sqrt(2.0))
    upper = max(u_c + spreads.upper * z_upper, 0.1 * u_c)
    d = origin - o_urdf
    off = float(np.linalg.norm(d - (d @ a_urdf) * a_urdf))
    ang = float(np.degrees(np.arccos(np.clip(axis @ a_urdf, -1.0, 1.0))))
    return Perturbation(int(index), joint, tuple(map(float, axis)), tuple(map(float, origin)), float(upper), ang, off,
                        float(friction), float(damping), float(mass), float(handle_friction),
                        tuple(map(float, base)), tuple(map(float, handle)), float(gain),
                        (*map(float, reperceive), float(reperceive_z)) if robot.guarded_approach else None,
                        "other" if other_side else "estimated")


def sample_perturbations(n: int, seed: int, *args, **kwargs) -> tuple[Perturbation, ...]:
    """Samples 0 .. n - 1 of :func:`sample_perturbation` (same further arguments)."""
    return tuple(sample_perturbation(i, seed, *args, **kwargs) for i in range(int(n)))


def front_normal(joint_type: str, axis, origin, handle) -> np.ndarray | None:
    """(3,) unit normal, world, of the moving part's front at q = 0 where its handle stands: a drawer's axis;
    a door's direction perpendicular to its hinge axis and to the hinge-to-handle lever. ``axis`` (3,),
    ``origin`` (3,) m: the joint's world axis and a point on it; ``handle`` (3,) m: the handle as planned.
    None when it is undefined (a handle on the hinge line, a zero axis)."""
    a = np.asarray(axis, dtype=np.float64)
    if np.linalg.norm(a) < 1e-12:
        return None
    a = a / np.linalg.norm(a)
    if joint_type == "prismatic":
        return a
    lever = np.asarray(handle, dtype=np.float64) - np.asarray(origin, dtype=np.float64)
    n = np.cross(a, lever - (lever @ a) * a)
    return None if np.linalg.norm(n) < 1e-9 else n / np.linalg.norm(n)


def in_front_plane(shift, normal) -> tuple[float, float, float]:
    """``shift`` (3,) m with its component along the unit ``normal`` (3,) removed (``normal`` None: as is)."""
    s = np.asarray(shift, dtype=np.float64)
    if normal is not None:
        s = s - (s @ normal) * np.asarray(normal, dtype=np.float64)
    return tuple(map(float, s))
