"""How an estimated joint differs from the reference's joint of the same name (pure numpy).

Used with ``--against`` to make a failed certificate's reason point at the fault: the certificate's
status comes from the physics criteria alone; this only explains it. Differences beyond the tolerances
below are named always (:func:`joint_differences`); when a force criterion failed, the measured
differences within them are named too, with how far they take the planned handle path off the
reference's (:func:`measured_differences`): a few millimetres of hinge offset are what a stiff grasp
and arm feel over a long arc.
"""

from __future__ import annotations

import numpy as np

from simcheck.scene_joints import SceneJoint, axis_angle_deg

__all__ = ["joint_differences", "measured_differences", "path_mismatch", "joint_mapping", "AXIS_TOLERANCE_DEG",
           "ORIGIN_TOLERANCE", "LIMIT_TOLERANCE"]

#: axes closer than this (degrees) are "the same axis"
AXIS_TOLERANCE_DEG = 2.0
#: hinge lines closer than this (metres) are "the same hinge" (a hinge 1.6 cm off bends a 50 cm door's
#: handle path by ~2 cm over 90 deg: enough to make a stiff grasp slip)
ORIGIN_TOLERANCE = 0.01
#: upper limits closer than this (fraction of the reference range) are "the same limits"
LIMIT_TOLERANCE = 0.05


def joint_differences(est: SceneJoint, ref: SceneJoint | None) -> list[str]:
    """Human-readable differences of ``est`` (the estimate) from ``ref`` (the reference), worst first."""
    if ref is None:
        return [f"the reference has no joint {est.name!r}"]
    out = []
    kind = {"continuous": "revolute"}            # a continuous hinge is a revolute one without limits
    if kind.get(str(est.type), str(est.type)) != kind.get(str(ref.type), str(ref.type)):
        out.append(f"joint {est.name} is {est.type} in the estimate but {ref.type} in the reference")
        return out
    # compared as they open: a file whose joint opens toward negative values (axis flipped, range negative)
    # describes the same motion as one that opens toward positive values
    s_est, s_ref = _opens(est), _opens(ref)
    angle = axis_angle_deg(s_est * est.axis_world, s_ref * ref.axis_world)
    if angle > AXIS_TOLERANCE_DEG:
        out.append(f"the estimated axis of {est.name} is {angle:.0f} deg off the reference axis")
    if est.type != "prismatic":
        d = float(np.linalg.norm(np.cross(ref.origin_world - est.origin_world, ref.axis_world)))
        if d > ORIGIN_TOLERANCE:
            out.append(f"the estimated hinge of {est.name} is {d:.3f} m from the reference hinge"
                       + (" (hinged on the wrong side)" if angle > 90 or d > 0.2 else ""))
    ref_range = max(ref.upper - ref.lower, 1e-9)
    if str(ref.type) == "continuous" or str(est.type) == "continuous":
        return out                               # no stop to compare with
    if s_est > 0 and s_ref > 0:
        if est.upper - ref.upper > LIMIT_TOLERANCE * ref_range:
            out.append(f"the estimated upper limit of {est.name} ({est.upper:.3f} {est.unit}) exceeds the "
                       f"reference's ({ref.upper:.3f} {ref.unit})")
    else:
        e, r = (est.upper if s_est > 0 else -est.lower), (ref.upper if s_ref > 0 else -ref.lower)
        if e - r > LIMIT_TOLERANCE * ref_range:
            out.append(f"the estimated opening range of {est.name} ({e:.3f} {est.unit}) exceeds the "
                       f"reference's ({r:.3f} {ref.unit})")
    return out


def _opening_axis(j: SceneJoint) -> np.ndarray:
    """(3,) world axis along (prismatic) or about (revolute) which ``j`` opens: its axis, reversed when it
    opens toward its lower limit."""
    return _opens(j) * np.asarray(j.axis_world, dtype=float)


def path_mismatch(est: SceneJoint, ref: SceneJoint, point: np.ndarray, amount: float) -> float:
    """Largest distance, m, between where the estimate and the reference take the grasped ``point`` (3,), world,
    m, over an opening of ``0..amount`` (m or rad, along each joint's opening direction): the path the plan
    asks the handle to follow versus the one the real part allows. 0 for joints of different types."""
    from scipy.spatial.transform import Rotation

    s = np.linspace(0.0, abs(float(amount)), 91)
    a_est, a_ref = _opening_axis(est), _opening_axis(ref)
    point = np.asarray(point, dtype=float)
    if est.type == "prismatic" and ref.type == "prismatic":
        return float(s[-1] * np.linalg.norm(a_est - a_ref))
    if "prismatic" in (est.type, ref.type):
        return 0.0
    if str(ref.type) == "continuous" or str(est.type) == "continuous":
        a_ref = a_ref if float(a_ref @ a_est) >= 0 else -a_ref     # a continuous hinge turns either way
    arc = lambda j, a: j.origin_world + Rotation.from_rotvec(s[:, None] * a).apply(point - j.origin_world)
    return float(np.linalg.norm(arc(est, a_est) - arc(ref, a_ref), axis=1).max())


def measured_differences(est: SceneJoint, ref: SceneJoint | None, point: np.ndarray, amount: float) -> str:
    """The estimate's measured differences from the reference, named even within the tolerances (used when a
    force criterion failed): the hinge offset split along the door toward the grasped ``point`` (3,), world, m,
    and along the door's front normal (the way the handle starts to move); the axis angle; the opening
    range; and :func:`path_mismatch` over the requested ``amount`` (m or rad). "" when the types differ
    (:func:`joint_differences` names that)."""
    kind = {"continuous": "revolute"}
    if ref is None or kind.get(str(est.type), str(est.type)) != kind.get(str(ref.type), str(ref.type)):
        return ""
    a_est, a_ref = _opening_axis(est), _opening_axis(ref)
    parts = [f"axis {axis_angle_deg(a_est, a_ref):.1f} deg off"]
    point = np.asarray(point, dtype=float)
    if est.type != "prismatic":
        d = est.origin_world - ref.origin_world
        d = d - (d @ a_ref) * a_ref                            # across the reference hinge line
        along = point - ref.origin_world
        along = along - (along @ a_ref) * a_ref
        along /= max(float(np.linalg.norm(along)), 1e-9)
        normal = np.cross(a_ref, along)                        # where the handle goes when the door opens
        parts.insert(0, f"hinge {np.linalg.norm(d) * 1e3:.0f} mm off ({d @ along * 1e3:+.0f} mm along the door "
                        f"toward the handle, {d @ normal * 1e3:+.0f} mm along its front normal)")
    if "continuous" not in (str(est.type), str(ref.type)):
        e = est.upper if _opens(est) > 0 else -est.lower
        r = ref.upper if _opens(ref) > 0 else -ref.lower
        parts.append(f"opening range {e:.3f} vs {r:.3f} {ref.unit}")
    return (f"measured, estimate vs reference of {est.name}: " + ", ".join(parts)
            + f"; over the requested {abs(float(amount)):.3f} {est.unit} the estimated articulation takes the "
              f"grasped point up to {path_mismatch(est, ref, point, amount) * 1e3:.0f} mm off the reference's path")


def _opens(j: SceneJoint) -> float:
    """+1 when ``j`` opens toward its upper limit (the farther one from 0; ties: upper), else -1."""
    return 1.0 if j.upper >= -j.lower else -1.0


def joint_mapping(est: SceneJoint, ref: SceneJoint | None) -> dict | None:
    """How ``est`` (the estimate's task joint) was matched to the reference's joint: by name; ``direction``
    is +1 when the reference's axis points the estimate's way (world frame), -1 when it is opposite (then the
    estimate's positive opening is the reference's negative one: a file with the other sign convention).
    None when the reference has no joint of that name.

    >>> import numpy as np
    >>> j = lambda ax, lo, up: SceneJoint("d", "revolute", "a", "b", lo, up, np.array(ax, float), np.zeros(3))
    >>> joint_mapping(j([0, 0, 1], 0, 1.57), j([0, 0, -1], -1.57, 0))
    {'name': 'd', 'type': 'revolute', 'direction': -1, 'lower': -1.57, 'upper': 0.0}
    """
    if ref is None:
        return None
    direction = 1 if float(np.dot(est.axis_world, ref.axis_world)) >= 0.0 else -1
    return {"name": ref.name, "type": ref.type.value, "direction": direction,
            "lower": float(ref.lower), "upper": float(ref.upper)}
