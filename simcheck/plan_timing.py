"""Is a given plan's timing one the robot can follow? Pure numpy criteria over a plan's timed segments
(``Segment.t``, seconds from each segment's start): the user's interpolation and timing are judged, never
fixed.

* :func:`waypoint_gap` -- the largest joint step between consecutive waypoints (also from one segment's last
  waypoint to the next one's first): beyond ``CriteriaConfig.max_waypoint_gap`` the path between them is the
  controller's interpolation, not the plan's.
* :func:`joint_speed` -- the largest joint speed between waypoints as a fraction of the robot's velocity
  limit (URDF ``velocity``); a jump between segments is infinitely fast.
* :func:`joint_acceleration` -- the largest joint acceleration as a fraction of the robot spec's limit
  (``RobotSpec.max_acceleration``): the second difference of the piecewise-linear position over
  ``CriteriaConfig.acceleration_window`` seconds, the robot at rest before and after each segment (the
  executor holds still between segments), so a segment that starts at full speed is a jump in velocity
  spread over one window.

Each failure names the segment and the time (seconds from the segment's start) and the joint.
"""

from __future__ import annotations

import numpy as np

from simcheck.config import DEFAULT_CRITERIA, CriteriaConfig
from simcheck.criteria import CriterionResult, _judge

__all__ = ["waypoint_gap", "joint_speed", "joint_acceleration", "timing_criteria"]


def waypoint_gap(segments, names, c: CriteriaConfig = DEFAULT_CRITERIA, units=None) -> CriterionResult:
    """Largest joint step between consecutive waypoints of ``segments`` (each ``q`` (n, dof), columns
    ``names``), across segment boundaries too; at most ``c.max_waypoint_gap``. The unit is the worst joint's
    (``units``: joint name -> "m" or "rad"; "rad" when unknown)."""
    worst, where, unit = 0.0, "", "rad"
    prev = None
    for seg in segments:
        q = seg.q if prev is None else np.concatenate([prev[None], seg.q])
        if len(q) > 1:
            step = np.abs(np.diff(q, axis=0))
            k, j = np.unravel_index(np.argmax(step), step.shape)
            if step[k, j] > worst:
                i = k if prev is None else k - 1          # the waypoint the step leads to
                worst = float(step[k, j])
                unit = (units or {}).get(names[j], "rad")
                where = (f"segment {seg.name!r}: joint {names[j]} steps {worst:.3f} {unit} between waypoints "
                         + (f"{i} and {i + 1}, t={seg.t[i]:.3f}-{seg.t[i + 1]:.3f} s" if i >= 0 else
                            "(from the previous segment's last waypoint to this one's first, at t=0)"))
        prev = seg.q[-1]
    return _judge("waypoint_gap", worst, c.max_waypoint_gap, "<=", unit,
                  "largest joint step between consecutive waypoints (the controller interpolates the rest)",
                  f"{where}: waypoints too far apart for the controller (at most {c.max_waypoint_gap:g}); give denser "
                  f"waypoints", where)


def joint_speed(segments, names, vmax: np.ndarray, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Largest joint speed between waypoints / the joint's velocity limit ``vmax`` (dof,) (rad/s or m/s; 0 or
    non-finite: unlimited); at most 1. A segment whose first waypoint is not where the previous one ended
    asks for a jump (infinite speed)."""
    vmax = np.asarray(vmax, dtype=float)
    limit = np.where((vmax > 0) & np.isfinite(vmax), vmax, np.inf)
    worst, where = 0.0, ""
    prev = None
    for seg in segments:
        if prev is not None:
            jump = np.abs(seg.q[0] - prev)
            if jump.max() > 1e-9:
                j = int(np.argmax(jump))
                worst, where = np.inf, (f"segment {seg.name!r} starts {jump[j]:.3f} away from where the previous "
                                        f"one ended (joint {names[j]}): a jump at t=0")
                break
        prev = seg.q[-1]
        if len(seg.q) < 2:
            continue
        ratio = np.abs(np.diff(seg.q, axis=0)) / np.diff(seg.t)[:, None] / limit[None]
        k, j = np.unravel_index(np.argmax(ratio), ratio.shape)
        if ratio[k, j] > worst:
            worst = float(ratio[k, j])
            where = (f"segment {seg.name!r}: joint {names[j]} at {worst * limit[j]:.3f} between t={seg.t[k]:.3f} "
                     f"and {seg.t[k + 1]:.3f} s, limit {limit[j]:.3g}")
    return _judge("joint_speed", worst, 1.0, "<=", "", "largest joint speed / the robot's velocity limit",
                  f"{where}: faster than the robot can move", where)


def _accelerations(seg, window: float) -> tuple[np.ndarray, np.ndarray]:
    """(times (m,), accelerations (m, dof)) of ``seg``'s piecewise-linear path, at rest before and after:
    ``(q(t + w) - 2 q(t) + q(t - w)) / w**2`` on a grid of ``w / 4`` plus the waypoint times."""
    t_end = float(seg.t[-1])
    grid = np.union1d(np.arange(-window, t_end + window + 1e-12, window / 4), seg.t)

    def q_at(x):
        return np.stack([np.interp(x, seg.t, seg.q[:, j]) for j in range(seg.q.shape[1])], axis=1)

    a = (q_at(grid + window) - 2 * q_at(grid) + q_at(grid - window)) / window ** 2
    return grid, a


def joint_acceleration(segments, names, amax, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Largest joint acceleration (:func:`_accelerations`, over ``c.acceleration_window``) / the robot spec's
    limit ``amax`` (dof,) rad/s^2 or m/s^2 (empty: the robot gives none, the value is 0); at most 1."""
    desc = "largest joint acceleration / the robot spec's acceleration limit"
    if amax is None or not len(amax):
        return _judge("joint_acceleration", 0.0, 1.0, "<=", "", desc, "", "the robot spec gives no acceleration limits")
    limit = np.where(np.asarray(amax, dtype=float) > 0, np.asarray(amax, dtype=float), np.inf)
    worst, where = 0.0, ""
    for seg in segments:
        if len(seg.q) < 2:
            continue
        t, a = _accelerations(seg, c.acceleration_window)
        ratio = np.abs(a) / limit[None]
        k, j = np.unravel_index(np.argmax(ratio), ratio.shape)
        if ratio[k, j] > worst:
            worst = float(ratio[k, j])
            when = min(max(t[k], 0.0), float(seg.t[-1]))
            where = (f"segment {seg.name!r}: joint {names[j]} accelerates at {abs(a[k, j]):.2f} near "
                     f"t={when:.2f} s, limit {limit[j]:.3g}")
    return _judge("joint_acceleration", worst, 1.0, "<=", "", desc,
                  f"{where}: beyond what the robot can do (the robot is at rest at each segment's ends)", where)


def timing_criteria(segments, names, vmax, amax, c: CriteriaConfig = DEFAULT_CRITERIA,
                    units=None) -> tuple[CriterionResult, ...]:
    """:func:`waypoint_gap`, :func:`joint_speed` and :func:`joint_acceleration` of timed ``segments``
    (``units``: joint name -> "m" or "rad")."""
    return (waypoint_gap(segments, names, c, units), joint_speed(segments, names, vmax, c),
            joint_acceleration(segments, names, amax, c))
