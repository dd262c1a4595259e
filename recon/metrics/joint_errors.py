"""Joint metrics used by articulated-object estimators: type accuracy, axis angle, hinge distance, limits.

Joints are matched by their **child part id** (a part has at most one parent). For every true joint
between two parts (a root's joint to the world, ``parent_part_id is None``, is not scored):

- *type correct*: an estimated joint with the same child exists and has the same type (a missing
  estimate counts as wrong);
- *parent correct*: that estimated joint also has the true parent part (the part tree's edge is right);
- *axis error* (both movable): the angle between the axes, sign-aware, in degrees, in [0, 180]. Under
  the positive-opens convention a flipped axis opens the wrong way, so it counts as 180 deg; the
  *unsigned* angle ``min(a, 180 - a)`` is reported too;
- *hinge distance* (both revolute): the distance from the point of the true hinge line nearest the true
  child part's centre to the estimated hinge line, metres ("distance between the lines near the part";
  exact for parallel lines). For prismatic joints the origin does not change the motion, so no origin
  error is defined (``nan``);
- *limit error* (same movable type): ``|upper_est - upper_true|`` (metres or radians) and the same for
  ``lower``.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from recon.model import JointEstimate, JointType

__all__ = ["JointMatch", "JointComparison", "axis_angle_deg", "unsigned_axis_angle_deg", "line_distance_near",
           "compare_joints"]

NAN = float("nan")


class JointMatch(enum.Enum):
    """How a true joint was matched."""

    MATCHED = "matched"          # an estimated joint has the same child part
    MISSING = "missing"          # no estimated joint moves this child part


def axis_angle_deg(axis_true: np.ndarray, axis_est: np.ndarray) -> float:
    """Sign-aware angle between two axes, degrees in [0, 180] (inputs need not be unit)."""
    a = np.asarray(axis_true, dtype=np.float64)
    b = np.asarray(axis_est, dtype=np.float64)
    c = float(np.dot(a, b) / (np.linalg.norm(a) * np.linalg.norm(b)))
    return float(np.degrees(np.arccos(np.clip(c, -1.0, 1.0))))


def unsigned_axis_angle_deg(axis_true: np.ndarray, axis_est: np.ndarray) -> float:
    """Angle between the two axis *lines*, ignoring direction: degrees in [0, 90]."""
    a = axis_angle_deg(axis_true, axis_est)
    return min(a, 180.0 - a)


def line_distance_near(origin_true: np.ndarray, axis_true: np.ndarray, origin_est: np.ndarray,
                       axis_est: np.ndarray, near: np.ndarray) -> float:
    """Distance from the true line's point nearest ``near`` to the estimated line.

    origin_* : (3,) float, metres, world — a point on each line; axis_* : (3,) direction
    near : (3,) float, metres, world — where the lines are compared (the true child part's centre)
    returns : float, metres
    """
    o_t, o_e, p = (np.asarray(v, dtype=np.float64) for v in (origin_true, origin_est, near))
    u_t = np.asarray(axis_true, dtype=np.float64)
    u_t = u_t / np.linalg.norm(u_t)
    u_e = np.asarray(axis_est, dtype=np.float64)
    u_e = u_e / np.linalg.norm(u_e)
    foot = o_t + np.dot(p - o_t, u_t) * u_t
    d = foot - o_e
    return float(np.linalg.norm(d - np.dot(d, u_e) * u_e))


@dataclass(frozen=True)
class JointComparison:
    """One true joint against its estimate (``nan`` where a quantity is not defined; see module doc)."""

    name: str
    child_part_id: int
    true_type: str
    est_type: str                  # "" when missing
    match: JointMatch
    axis_error_deg: float
    axis_error_unsigned_deg: float
    hinge_distance_m: float
    upper_error: float
    lower_error: float
    parent_correct: bool = False

    @property
    def type_correct(self) -> bool:
        return self.match is JointMatch.MATCHED and self.true_type == self.est_type


def compare_joints(truth: Sequence[JointEstimate], estimate: Sequence[JointEstimate],
                   child_centres: Mapping[int, np.ndarray]) -> tuple[JointComparison, ...]:
    """Compare every true joint with the estimated joint of the same child part.

    truth, estimate : joints of one object
    child_centres : ``{part_id: (3,) world centre}`` of the true parts (where hinge lines are compared)
    returns : one :class:`JointComparison` per true part-to-part joint, in the truth's order
    """
    by_child = {j.child_part_id: j for j in estimate}
    out = []
    for t in truth:
        if t.parent_part_id is None:
            continue
        e = by_child.get(t.child_part_id)
        if e is None:
            out.append(JointComparison(t.name, t.child_part_id, t.type.value, "", JointMatch.MISSING,
                                       NAN, NAN, NAN, NAN, NAN))
            continue
        axis = unsigned = hinge = upper = lower = NAN
        t_movable, e_movable = t.type is not JointType.FIXED, e.type is not JointType.FIXED
        if t_movable and e_movable:
            axis = axis_angle_deg(t.axis, e.axis)
            unsigned = min(axis, 180.0 - axis)
        if t.type is JointType.REVOLUTE and e.type is JointType.REVOLUTE:
            hinge = line_distance_near(t.origin, t.axis, e.origin, e.axis, child_centres[t.child_part_id])
        if t_movable and t.type is e.type:
            upper = abs(e.upper - t.upper)
            lower = abs(e.lower - t.lower)
        out.append(JointComparison(t.name, t.child_part_id, t.type.value, e.type.value, JointMatch.MATCHED,
                                   axis, unsigned, hinge, upper, lower, e.parent_part_id == t.parent_part_id))
    return tuple(out)
