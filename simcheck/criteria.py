"""The certificate's criteria: pure numpy predicates over a recorded :class:`Rollout` (no PyBullet).

Each predicate returns a :class:`CriterionResult` with its value, threshold and margin (positive margin
= passed, by how much; negative = failed, by how much) and, when it fails, a detail that says what
went wrong in terms of the scene (joint, link, time). Thresholds come from :class:`CriteriaConfig`.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from simcheck.config import DEFAULT_CRITERIA, CriteriaConfig
from simcheck.rollout import Rollout

__all__ = ["CriterionResult", "at_release", "at_end_stop", "opened_amount", "opened_fraction", "opened_overshoot", "closed_gap", "closed_tolerance",
           "handle_path_deviation", "settled_linear_speed",
           "settled_angular_speed", "unexpected_contact_force", "unexpected_contact_depth", "rest_contact_penetration", "grasp_held", "grasp_force",
           "interaction_force",
           "robot_joint_limits", "robot_joint_effort", "plan_found", "plan_collision_free", "rollout_criteria", "FLOOR"]

FLOOR = "floor"


@dataclass(frozen=True)
class CriterionResult:
    """One criterion judged on one task.

    Attributes:
        name: criterion name (stable; certificates and reports key on it).
        value: the measured value (``inf`` when it could not be measured, e.g. no grasp was made).
        threshold: the limit from :class:`CriteriaConfig`.
        comparison: ">=" (value must be at least threshold) or "<=" (at most).
        unit: "m", "rad", "m/s", "rad/s", "N", "" (fraction / count).
        passed: value compares correctly with threshold.
        margin: ``value - threshold`` for ">=", ``threshold - value`` for "<=" (negative: failed).
        description: what the criterion measures.
        detail: what happened (names joint/link/time), mainly when it failed.
    """

    name: str
    value: float
    threshold: float
    comparison: str
    unit: str
    passed: bool
    margin: float
    description: str
    detail: str = ""

    def to_dict(self) -> dict:
        """JSON-ready: non-finite numbers become ``None``."""
        d = asdict(self)
        for k in ("value", "margin", "threshold"):
            if not math.isfinite(d[k]):
                d[k] = None
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "CriterionResult":
        d = dict(d)
        for k in ("value", "margin"):
            if d.get(k) is None:
                d[k] = math.inf if k == "value" and d["comparison"] == "<=" else -math.inf
        d["threshold"] = float(d["threshold"]) if d.get("threshold") is not None else math.nan
        return cls(**d)


def _judge(name, value, threshold, comparison, unit, description, detail_fail, detail_pass="") -> CriterionResult:
    value = float(value)
    if math.isnan(value):
        value = math.inf if comparison == "<=" else -math.inf
    margin = value - threshold if comparison == ">=" else threshold - value
    passed = bool(margin >= 0)
    return CriterionResult(name, value, float(threshold), comparison, unit, passed, float(margin), description,
                           detail_pass if passed else detail_fail)


def opened_amount(r: Rollout, end: int | None = None) -> tuple[float, str]:
    """How far the executed part opened, m or rad, from the first sample to the end (to sample ``end``, when
    given), and how it was measured.

    Along the PLANNED opening direction (``r.opening_type``, ``r.opening_axis``): the handle link's
    displacement along the axis (prismatic), or its rotation about the axis summed sample to sample
    (revolute), so a reference whose joint axis or range sign is the opposite of the estimate's is
    judged by how it moved, not by its raw joint value. Without an opening direction: the executed
    joint's value change."""
    last = r.n - 1 if end is None else int(end)
    raw = float(r.object_q[last] - r.object_q0)
    axis = np.asarray(r.opening_axis, dtype=float)
    if r.opening_type not in ("prismatic", "revolute") or not np.isfinite(axis).all() or last < 1:
        return raw, f"joint {r.joint}'s value changed by {raw:.3f}"
    T = r.T_world_handle[:last + 1]
    if r.opening_type == "prismatic":
        opened = float((T[-1, :3, 3] - T[0, :3, 3]) @ axis)
    else:
        R_step = np.einsum("nij,nkj->nik", T[1:, :3, :3], T[:-1, :3, :3])      # R_k+1 R_k^T
        from scipy.spatial.transform import Rotation
        opened = float((Rotation.from_matrix(R_step).as_rotvec() @ axis).sum())
    how = (f"measured along the planned {r.opening_type} axis [{axis[0]:.2f}, {axis[1]:.2f}, {axis[2]:.2f}]: "
           f"{opened:.3f}; executed joint {r.joint} changed by {raw:+.3f}")
    return opened, how


def opened_fraction(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Opening reached at the end / requested amount (see :func:`opened_amount`), at least ``c.opened_fraction``."""
    opened, how = opened_amount(r)
    frac = opened / r.requested_amount if r.requested_amount != 0 else -math.inf
    after = ""
    released = np.flatnonzero(r.in_segment(r.release_segment))
    if frac < c.opened_fraction and released.size and released[0] > 0:
        held, _ = opened_amount(r, int(released[0]) - 1)
        if r.requested_amount != 0 and held / r.requested_amount >= c.opened_fraction:
            after = (f"; it was {held:.3f} open when the fingers let go: it moved back by itself once released "
                     f"(nothing holds it open)")
    return _judge("opened_fraction", frac, c.opened_fraction, ">=", "",
                  "opening reached at the end (along the planned opening direction) / opening requested",
                  f"{r.joint} opened {opened:.3f} of the requested {r.requested_amount:.3f} "
                  f"({frac:.0%}, needs {c.opened_fraction:.0%}{after}; {how})", how)


def opened_overshoot(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """How far past the request the part ended, as a fraction of the request (0 when not past it); at
    most ``c.opened_overshoot``."""
    opened, how = opened_amount(r)
    over = max(opened / r.requested_amount - 1.0, 0.0) if r.requested_amount != 0 else math.inf
    return _judge("opened_overshoot", over, c.opened_overshoot, "<=", "",
                  "opening past the request at the end, as a fraction of the request",
                  f"{r.joint} ended {over:.0%} past the requested {r.requested_amount:.3f} (at most "
                  f"{c.opened_overshoot:.0%}; {how}): the part moved farther than planned", how)


def closed_tolerance(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> float:
    """How near its closed value (m or rad) a closed part must end: ``c.closed_range_fraction`` of the joint's
    range, or ``c.closed_gap_prismatic`` / ``c.closed_gap_revolute`` if larger (the range unknown: those)."""
    floor = c.closed_gap_prismatic if r.opening_type == "prismatic" else c.closed_gap_revolute
    span = r.joint_range if math.isfinite(r.joint_range) else 0.0
    return max(c.closed_range_fraction * span, floor)


def closed_gap(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """A close task's gap at the end: how far (m or rad) the part is from its closed value, i.e. the opening
    it started at (``r.requested_amount``) minus how far it moved the way it closes (:func:`opened_amount`,
    along ``r.opening_axis``); at most :func:`closed_tolerance`."""
    moved, how = opened_amount(r)
    gap = abs(r.requested_amount - moved)
    tol = closed_tolerance(r, c)
    unit = "m" if r.opening_type == "prismatic" else "rad"
    return _judge("closed_gap", gap, tol, "<=", unit,
                  "distance of the part from its closed value at the end (the opening it started at minus "
                  "how far it was shut)",
                  f"{r.joint} ended {gap:.3f} {unit} from closed (it started {r.requested_amount:.3f} open and "
                  f"was shut by {moved:.3f}; at most {tol:.3f}; {how})", how)


def handle_path_deviation(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Max distance, m, between the grasped point of the handle and the planned tool position over the
    opening segment (time-aligned: the plan's pose at the same instant, and its last pose while holding)."""
    mask = r.in_segment(r.opening_segment) & np.all(np.isfinite(r.planned_tool_pos), axis=1)
    desc = "max distance between the grasped handle point and the planned path during the opening"
    if not mask.any():
        return _judge("handle_path_deviation", math.inf, c.handle_path_tolerance, "<=", "m", desc,
                      f"the opening of joint {r.joint} was not executed with a planned tool path")
    d = np.linalg.norm(r.grasp_point[mask] - r.planned_tool_pos[mask], axis=1)
    if not np.isfinite(d).any():
        return _judge("handle_path_deviation", math.inf, c.handle_path_tolerance, "<=", "m", desc,
                      f"handle link {r.handle_link} was never grasped, so it did not follow the planned path "
                      f"during segment {r.opening_segment!r}")
    lost = ~np.isfinite(d)
    worst = int(np.nanargmax(d))
    t = r.t[mask][worst]
    value = math.inf if lost.any() else float(d[worst])
    detail = (f"handle {r.handle_link} left the planned path by {np.nanmax(d):.3f} m at t={t:.2f} s during segment "
              f"{r.opening_segment!r}"
              + (f" and was lost for {lost.mean():.0%} of the opening" if lost.any() else "")
              + f" (the articulation of {r.joint} does not move the handle along the planned path)")
    return _judge("handle_path_deviation", value, c.handle_path_tolerance, "<=", "m", desc, detail)


def at_release(r: Rollout) -> int:
    """Index of the sample at which the moved part must be at rest: the last sample of the release
    segment (the fingers have opened and the robot has held still for its settle time), before the
    retreat and the final hold; the last sample when the plan has no release segment."""
    release = np.flatnonzero(r.in_segment(r.release_segment))
    return int(release[-1]) if len(release) else r.n - 1


def settled_linear_speed(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Linear speed, m/s, of the moved link right after release (:func:`at_release`)."""
    if not r.n:
        return _judge("settled_linear_speed", math.inf, c.settled_linear_speed, "<=", "m/s", "", "no samples")
    k = at_release(r)
    v = float(r.link_speed[k])
    return _judge("settled_linear_speed", v, c.settled_linear_speed, "<=", "m/s",
                  "speed of the moved link right after the gripper let go",
                  f"link {r.moving_link} still moved at {v:.3f} m/s at t={r.t[k]:.2f} s, after the gripper let go")


def settled_angular_speed(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Angular speed, rad/s, of the moved link right after release (:func:`at_release`)."""
    if not r.n:
        return _judge("settled_angular_speed", math.inf, c.settled_angular_speed, "<=", "rad/s", "", "no samples")
    k = at_release(r)
    w = float(r.link_angular_speed[k])
    return _judge("settled_angular_speed", w, c.settled_angular_speed, "<=", "rad/s",
                  "angular speed of the moved link right after the gripper let go",
                  f"link {r.moving_link} still turned at {w:.3f} rad/s at t={r.t[k]:.2f} s, after the gripper let go")


def _pushing(r: Rollout) -> np.ndarray:
    """(m,) bool: robot contacts of a gripper link with the part (moving link or handle) while the plan pushes it
    (``r.push_segment``)."""
    if not r.push_segment:
        return np.zeros(len(r.contact_sample), bool)
    return (r.in_segment(r.push_segment)[r.contact_sample] & np.isin(r.contact_robot_link, list(r.gripper_links))
            & np.isin(r.contact_scene_link, [r.moving_link, r.handle_link]))


def _unexpected(r: Rollout) -> np.ndarray:
    """(m,) bool: robot contacts other than gripper links vs the grasped handle link, and than the gripper pushing
    the part in the push segment."""
    allowed = np.isin(r.contact_robot_link, list(r.gripper_links)) & (r.contact_scene_link == r.handle_link)
    return ~(allowed | _pushing(r))


def _worst_contact(r: Rollout, values: np.ndarray, mask: np.ndarray) -> tuple[float, str]:
    if not mask.any():
        return 0.0, ""
    i = int(np.argmax(np.where(mask, values, -np.inf)))
    k = int(r.contact_sample[i])
    seg = r.segment_names[r.segment[k]] if 0 <= r.segment[k] < len(r.segment_names) else "settle"
    return float(values[i]), (f"robot link {r.contact_robot_link[i]} hit scene link {r.contact_scene_link[i]} "
                              f"at t={r.t[k]:.2f} s during {seg}")


def unexpected_contact_force(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Largest normal force, N, of a robot-scene (or robot-floor) contact other than gripper-handle."""
    value, where = _worst_contact(r, r.contact_force, _unexpected(r))
    return _judge("unexpected_contact_force", value, c.contact_force_tolerance, "<=", "N",
                  "largest force of a robot-scene contact other than gripper-handle",
                  f"{where} with {value:.1f} N")


def unexpected_contact_depth(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Deepest penetration, m, of a robot-scene contact other than gripper-handle."""
    value, where = _worst_contact(r, r.contact_depth, _unexpected(r))
    return _judge("unexpected_contact_depth", value, c.contact_penetration_tolerance, "<=", "m",
                  "deepest penetration of a robot-scene contact other than gripper-handle",
                  f"{where}, {value * 1e3:.1f} mm deep")


def rest_contact_penetration(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """The moving part may not pass into the links it touched at rest (sibling fronts, its frame) deeper than
    it was at rest, beyond ``c.rest_contact_slack``: their contact is not a collision in the simulation (it
    neither blocks the opening nor counts as an unexpected contact), so this is what stops a part going
    through them. 0 when it touched nothing at rest."""
    ex = np.asarray(r.rest_contact_excess, dtype=float)
    value = float(np.max(ex)) if ex.size else 0.0
    return _judge("rest_contact_penetration", value, c.rest_contact_slack, "<=", "m",
                  "extra interpenetration with links touched at rest",
                  f"{r.moving_link} passed {value * 1e3:.1f} mm into {r.rest_contact_worst or 'a link'} it touched "
                  f"at rest: physically it is blocked there",
                  f"touched at rest: {', '.join(r.rest_contact_links) or 'nothing'}")


def grasp_held(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Max slip, m, of the grasped point of the handle in the fingers during the opening segment (``inf`` if
    the grasp did not exist for the whole segment): how far the held point slid on the handle
    (``r.grasp_slide``); the grasp spring's stretch between the tool and the handle is the arm's compliance
    under load, judged by ``handle_path_deviation`` and the force criteria. Rollouts recorded without
    ``grasp_slide`` are judged by the distance between the tool and the grasped point."""
    mask = r.in_segment(r.opening_segment)
    desc = "max slide of the grasped handle point in the fingers while opening (inf: grasp not held)"
    note = f" ({r.grasp_note})" if r.grasp_note else ""
    if not mask.any():
        return _judge("grasp_held", math.inf, c.grasp_slip_tolerance, "<=", "m", desc,
                      f"no opening segment ({r.opening_segment!r}) was executed for joint {r.joint}{note}")
    active = r.grasp_active[mask]
    if not active.any():
        return _judge("grasp_held", math.inf, c.grasp_slip_tolerance, "<=", "m", desc,
                      f"the gripper never held handle {r.handle_link} during segment {r.opening_segment!r}{note}")
    slide = np.asarray(r.grasp_slide, dtype=float)[mask]
    slip = slide if np.isfinite(slide).all() else np.linalg.norm(r.grasp_point[mask] - r.tool_pos[mask], axis=1)
    if not active.all():
        t_lost = r.t[mask][int(np.argmin(active))]
        return _judge("grasp_held", math.inf, c.grasp_slip_tolerance, "<=", "m", desc,
                      f"the grasp of handle {r.handle_link} was lost at t={t_lost:.2f} s during segment "
                      f"{r.opening_segment!r}{note}")
    value = float(np.max(slip))
    return _judge("grasp_held", value, c.grasp_slip_tolerance, "<=", "m", desc,
                  f"handle {r.handle_link} slipped {value:.3f} m in the gripper{note}")


def at_end_stop(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> np.ndarray:
    """(n,) bool: the executed joint is within ``c.end_stop_tolerance`` of (or past) one of its limits and
    has left its starting value: the part rests on its end stop (none when the limits are unknown)."""
    lo, hi = np.asarray(r.object_limits, dtype=float)
    q = np.asarray(r.object_q, dtype=float)
    tol = c.end_stop_tolerance
    moved = np.abs(q - r.object_q0) > tol
    with np.errstate(invalid="ignore"):
        return moved & ((q >= hi - tol) | (q <= lo + tol))


def _grasp_load(r: Rollout, c: CriteriaConfig) -> tuple[np.ndarray, float]:
    """(n,) the grasp's recorded force (50 ms mean), N, where it is judged -- grasped, and the part not on
    its end stop -- else 0; and the peak of what was left out at the end stop (0 when nothing)."""
    held = r.grasp_active | (r.grasp_force > 0)
    stop = at_end_stop(r, c)
    force = np.where(held & ~stop, r.grasp_force, 0.0).astype(float)
    at_stop = np.where(held & stop, r.grasp_force, 0.0)
    return force, float(at_stop.max()) if r.n else 0.0


def grasp_force(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Peak, N, over the grasped phase of the grasp's force averaged over ``grasp_force_window`` (the
    recorded ``grasp_force``); threshold: what the robot's gripper holds (``r.holding_force``, from its
    ``GripperModel``) divided by ``c.grasp_safety_factor``: a pull the gripper holds only without margin
    fails. ``inf`` when no grasp was made.

    Samples with the part on its end stop (:func:`at_end_stop`) are left out: a plan that asks for a few
    millimetres past the real stop pulls into the stop once the part is open, not to open it; the
    handle then slides in the fingers, which ``grasp_held`` judges (at most ``grasp_slip_tolerance``),
    and ``opened_fraction`` judges how far it opened."""
    allowed = r.holding_force / c.grasp_safety_factor
    desc = (f"peak force through the grasp (mean over 50 ms) while opening, the part off its end stop / what the "
            f"gripper holds with a safety factor of {c.grasp_safety_factor:g}")
    held = r.grasp_active | (r.grasp_force > 0)
    if not held.any():
        return _judge("grasp_force", math.inf, allowed, "<=", "N", desc,
                      f"handle {r.handle_link} was never grasped, so no grasp force was measured")
    force, stop_peak = _grasp_load(r, c)
    k = int(np.argmax(force))
    seg = r.segment_names[r.segment[k]] if 0 <= r.segment[k] < len(r.segment_names) else "settle"
    stop = f"; {stop_peak:.0f} N pulling {r.joint} against its end stop, not judged" if stop_peak > allowed else ""
    return _judge("grasp_force", float(force[k]), allowed, "<=", "N", desc,
                  f"pulling {r.joint} took {force[k]:.0f} N through the grasp of {r.handle_link} at t={r.t[k]:.2f} s "
                  f"during {seg}; the gripper holds {r.holding_force:.0f} N, {allowed:.0f} N with a safety factor of "
                  f"{c.grasp_safety_factor:g} (the estimated articulation does not match how the part moves, or the "
                  f"part is blocked)", stop.lstrip("; "))


def robot_joint_limits(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Largest excursion of a robot joint beyond its URDF limits, measured or COMMANDED: the simulated joint
    stops at its limit, a real arm faults when a plan drives a joint past it. The unit is the worst joint's
    (m for a prismatic joint, rad otherwise; the threshold applies in either)."""
    def excursion(q):
        over = np.maximum(q - r.robot_upper[None, :], r.robot_lower[None, :] - q)
        return np.where(np.isfinite(over), over, 0.0)

    desc = "largest excursion of a robot joint beyond its limits (measured or commanded)"
    measured, commanded = excursion(r.robot_q), excursion(np.asarray(r.robot_q_target, dtype=float))
    units = tuple(r.robot_joint_units) or ("rad",) * np.shape(r.robot_q)[-1]
    if not measured.size:
        return _judge("robot_joint_limits", 0.0, c.joint_limit_tolerance, "<=", "rad", desc, "")
    worst = measured if measured.max() >= commanded.max() else commanded
    value = float(max(worst.max(), 0.0))
    k, j = np.unravel_index(np.argmax(worst), worst.shape)
    name = r.robot_joint_names[j] if r.robot_joint_names else "?"
    unit = units[j] if value > 0 else "rad"
    how = "went" if worst is measured else "was commanded"
    return _judge("robot_joint_limits", value, c.joint_limit_tolerance, "<=", unit, desc,
                  f"robot joint {name} {how} {value:.3f} {unit} beyond its limits at t={r.t[k]:.2f} s")


def robot_joint_effort(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Largest share of its effort limit, over the whole task, that a robot joint's motor torque (force)
    reached, averaged over ``PhysicsConfig.grasp_force_window`` (the recorded ``robot_effort``). At its limit
    the motor cannot hold the joint on its target: the arm yields and no longer follows the plan -- a wrist
    joint pushed back by a door whose hinge is not where the plan assumed keeps the grasp's pull just below
    what its torque allows, however wrong the estimate -- and a real arm stops (Franka's joint torque reflex).
    Threshold ``c.robot_effort_share``; 0 with the detail "not recorded" for rollouts recorded without it."""
    desc = "largest motor torque of a robot joint (mean over 50 ms) / its effort limit"
    effort = np.asarray(r.robot_effort, dtype=float)
    if not effort.size or not np.isfinite(effort).any():
        return _judge("robot_joint_effort", 0.0, c.robot_effort_share, "<=", "", desc, "", "not recorded")
    k, j = np.unravel_index(np.nanargmax(effort), effort.shape)
    value = float(effort[k, j])
    name = r.robot_joint_names[j] if r.robot_joint_names else "?"
    seg = r.segment_names[r.segment[k]] if 0 <= r.segment[k] < len(r.segment_names) else "settle"
    return _judge("robot_joint_effort", value, c.robot_effort_share, "<=", "", desc,
                  f"robot joint {name} was held at {value:.0%} of its effort limit at t={r.t[k]:.2f} s during {seg}: "
                  f"the arm could not follow the plan (the estimated articulation does not match how the part "
                  f"moves, or the part is blocked)")


def interaction_force(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Largest force, N, the robot applied to the task's part other than by squeezing it between its
    fingers: per sample, the grasp's force (50 ms mean) plus the contact forces of every robot link that
    is not a finger on the moving link or the handle (while the plan pushes the part, ``r.push_segment``, the
    fingers' contacts too: they push it, nothing is squeezed). Threshold: what the gripper holds
    (``r.holding_force``): the robot's spec bounds what it applies to the object. The grasp's pull is left
    out while the part rests on its end stop, as in :func:`grasp_force`."""
    total, _ = _grasp_load(r, c)
    on_part = np.isin(r.contact_scene_link, [r.moving_link, r.handle_link]) & (
        ~np.isin(r.contact_robot_link, list(r.finger_links)) | _pushing(r))
    pushed = np.zeros(r.n)
    np.add.at(pushed, r.contact_sample[on_part], r.contact_force[on_part])
    total = total + pushed
    k = int(np.argmax(total)) if r.n else 0
    value = float(total[k]) if r.n else 0.0
    links = sorted(set(r.contact_robot_link[on_part & (r.contact_sample == k)]))
    seg = r.segment_names[r.segment[k]] if r.n and 0 <= r.segment[k] < len(r.segment_names) else "settle"
    return _judge("interaction_force", value, r.holding_force, "<=", "N",
                  "largest force the robot applied to the part (grasp plus pushes, fingers' squeeze aside)",
                  f"the robot applied {value:.0f} N to {r.moving_link} at t={r.t[k]:.2f} s during {seg} "
                  f"(grasp {total[k] - pushed[k]:.0f} N" + (f", pushed by {', '.join(links)} {pushed[k]:.0f} N"
                                                            if links else "") + f"); at most {r.holding_force:.0f} N")


def plan_found(found: bool, reason: str = "") -> CriterionResult:
    """1 when the planner returned a plan, else 0 (the planner's reason as detail)."""
    return _judge("plan_found", 1.0 if found else 0.0, 1.0, ">=", "", "the planner found a plan", reason)


def plan_collision_free(max_depth: float, detail: str, c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Deepest robot-scene penetration, m, along the densely interpolated plan, from the independent
    PyBullet re-check (gripper-handle contacts excepted)."""
    return _judge("plan_collision_free", max_depth, c.plan_penetration_tolerance, "<=", "m",
                  "deepest penetration along the plan, re-checked independently in PyBullet", detail)


def rollout_criteria(r: Rollout, c: CriteriaConfig = DEFAULT_CRITERIA) -> tuple[CriterionResult, ...]:
    """Every rollout criterion, in the order a failure reason lists them (most telling first). A close task
    (``r.closing``) is judged by :func:`closed_gap` instead of the opened fraction and overshoot."""
    reached = (closed_gap(r, c),) if r.closing else (opened_fraction(r, c), opened_overshoot(r, c))
    return (grasp_held(r, c), grasp_force(r, c), *reached,
            handle_path_deviation(r, c), unexpected_contact_force(r, c), unexpected_contact_depth(r, c),
            rest_contact_penetration(r, c), interaction_force(r, c), settled_linear_speed(r, c),
            settled_angular_speed(r, c), robot_joint_limits(r, c), robot_joint_effort(r, c))
