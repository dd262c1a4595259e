"""How sure the reconstruction is of each movable joint: a seeded bootstrap of the joint's local fit.

For a drawer or door joint, K replicates each resample (with replacement) the scan points of the
moving part and of its parent, refit both boxes the way Eq. 3 builds its box candidate (extents of
the points in the box's frame, then the depth-noise / front-panel correction of
:func:`recon.fitting.denoised_box`, with the yaw re-read from the resampled normals as
:func:`recon.fitting.dominant_yaw` does), and re-estimate the joint with the same code as the pipeline
(:func:`recon.joints.movable_joint`: opening face, hinge, swept limit). The axis also follows the
moving panel's face plane re-fitted to the resampled points (its smallest principal direction): the
hinge / slide lies in / across that plane. The same procedure on all points (no resampling) is the
reference; the spreads are RMS deviations from it:

    axis_deg  RMS angle (deg) between a replicate's axis and the reference axis
    origin_m  RMS distance (m) of a replicate's axis point from the reference axis line, perpendicular
              to the axis (the replicates hinge a door on its box's back face), combined in quadrature
              with what the scan leaves undecided across a door thicker than a front's board: its pivot
              may lie anywhere over that thickness (:mod:`recon.hinge_depth`; RMS of a uniform spread,
              undecided / sqrt(3)), and with the clearance it leaves unresolved behind the door: the pivot may lie
              that much deeper or in from the hinge edge (a right triangle of that leg: RMS clearance / sqrt(3))
    upper     RMS deviation of the upper limit (m or rad), combined in quadrature with the template's
              prior on what the scan cannot show: a drawer's travel (its box is hidden:
              ``drawer_travel_prior``) and the stop of a door whose swing no obstacle limits
              (``door_stop_prior``)

What the bootstrap measures is the sampling variability of the fit: few points, noisy points and
uneven coverage widen it. It does not see systematic errors the fit shares across replicates (a part
occluded the same way in every replicate, label bleed); the certifier adds documented physics and
robot spreads on top (simcheck/perturbations.py). A door whose hinge side the scan does not decide
(no handle, both edges as near its body's edges) is flagged ``side_undecided``: the certifier samples both,
and a replicate's hinge is measured from the nearer of the two lines (the side is not a spread across the door).
The replicates are computed in the scan's frame (before the pipeline's support / upright moves of whole
objects, which move every replicate alike). ICP and the candidate search are not re-run (cost).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from recon.config import FittingConfig, ReconConfig
from recon.fitting import denoised_box, dominant_yaw
from recon.hinge_depth import HingeDepth
from recon.joints import door_stop, movable_joint_detail
from recon.model import JointEstimate, JointType, JointUncertainty
from recon.primitive import Primitive, PrimitiveKind
from scenes.hinge_mirror import other_edge_origin

__all__ = ["METHOD", "with_joint_uncertainty", "joint_uncertainty"]

METHOD = "bootstrap+template-prior"
"""The ``method`` recorded in graph.json: the bootstrap, plus the template's prior on what no scan shows
(a drawer's hidden travel, a free door's stop) in the upper limit's spread and a thick door's undecided
pivot depth and the clearance behind a door the scan does not resolve in the origin's."""


@dataclass(frozen=True)
class _PartData:
    """A part's fitted primitive with its scan points (n, 3) and normals (n, 3) or None, world."""

    prim: Primitive
    points: np.ndarray
    normals: np.ndarray | None


def with_joint_uncertainty(joints: tuple[JointEstimate, ...], parts, prims: dict[int, Primitive],
                           obstacles_for, config: ReconConfig, seed: int) -> tuple[JointEstimate, ...]:
    """``joints`` with :class:`JointUncertainty` on every movable one (fixed joints unchanged).

    parts : the object's :class:`recon.scan.PartPoints` (part_id, points, normals)
    prims : {part_id: final primitive}; obstacles_for(part_ids) -> (n, 3) points the moving parts
    must not sweep into (as for :func:`recon.joints.estimate_joints`).
    config : the whole config: each replicate re-runs the end of Eq. 3 fitting (``fitting``) and the
    joint stage (``joints``, ``contacts``); the bootstrap's own group is ``joint_uncertainty``.
    Deterministic for a given ``seed``. ``config.joint_uncertainty.samples == 0`` returns ``joints``.
    """
    ucfg = config.joint_uncertainty
    if ucfg.samples <= 0:
        return joints
    by_id = {p.part_id: p for p in parts}
    children: dict[int, list[int]] = {}
    for j in joints:
        if j.parent_part_id is not None:
            children.setdefault(j.parent_part_id, []).append(j.child_part_id)
    out = []
    for j in joints:
        if j.type is JointType.FIXED or j.parent_part_id not in by_id or j.child_part_id not in by_id:
            out.append(j)
            continue
        sub = _subtree(children, j.child_part_id)
        handles = [prims[k] for k in children.get(j.child_part_id, ())
                   if k in by_id and by_id[k].label in ("handle", "knob")]
        others = [prims[k] for k in sub if k != j.child_part_id]
        p, c = by_id[j.parent_part_id], by_id[j.child_part_id]
        u = joint_uncertainty(j.type, _PartData(prims[j.parent_part_id], p.points, p.normals),
                              _PartData(prims[j.child_part_id], c.points, c.normals), handles, others,
                              obstacles_for(sub), config, seed=(int(seed) * 7919 + j.child_part_id) % 2**31,
                              hinge_depth=j.hinge_depth, side_undecided=j.hinge_side_undecided)
        out.append(replace(j, uncertainty=u))
    return tuple(out)


def _subtree(children: dict[int, list[int]], root: int) -> list[int]:
    out, stack = [], [root]
    while stack:
        k = stack.pop()
        out.append(k)
        stack.extend(children.get(k, ()))
    return out


def joint_uncertainty(jtype: JointType, parent: _PartData, child: _PartData, handles: list[Primitive],
                      others: list[Primitive], obstacles: np.ndarray, config: ReconConfig, seed: int,
                      hinge_depth: HingeDepth | None = None, side_undecided: bool = False) -> JointUncertainty:
    """The bootstrap spreads of one movable joint (see the module docstring).

    handles : the child's handle primitives (they decide the hinge side); others : the rest of the
    child's subtree, swept with it; obstacles : (n, 3) world points for the limit sweep; hinge_depth : where
    a door's hinge lies across it (how much of its thickness leaves the pivot undecided) and side_undecided :
    whether its side is a guess, as :func:`recon.joints.estimate_joints` found them from all the points.
    """
    ucfg = config.joint_uncertainty
    rng = np.random.default_rng(seed)
    par = _capped(parent, ucfg.max_points, rng)
    chi = _capped(child, ucfg.max_points, rng)
    obstacles = _near(obstacles, [parent.prim, child.prim, *others], ucfg.obstacle_margin)
    ref = _replicate(jtype, par, chi, None, None, handles, others, obstacles, config, sweep=True)
    # a door hinged at whichever edge: its hinge side is a guess (flagged, sampled apart by the certifier),
    # so a replicate's line is measured from the nearer of the two lines, not across the door
    revolute = jtype is JointType.REVOLUTE
    undecided = float(hinge_depth.undecided) if revolute and hinge_depth is not None else 0.0
    side = revolute and side_undecided
    lines = [ref[1]] + ([other_edge_origin(ref[1], ref[0], child.prim.T_world_part, child.prim.size)] if side else [])
    ang, off, dup = [], [], []
    for k in range(ucfg.samples):
        ip = rng.integers(len(par.points), size=len(par.points))
        ic = rng.integers(len(chi.points), size=len(chi.points))
        sweep = k < ucfg.limit_samples
        axis, origin, upper = _replicate(jtype, par, chi, ip, ic, handles, others, obstacles, config, sweep)
        ang.append(np.degrees(np.arccos(np.clip(abs(float(axis @ ref[0])), -1.0, 1.0))))
        d = [origin - o for o in lines]
        off.append(min(float(np.linalg.norm(x - (x @ ref[0]) * ref[0])) for x in d))
        if sweep:
            dup.append(upper - ref[2])
    rms = lambda x: float(np.sqrt(np.mean(np.square(x))))   # noqa: E731
    upper = rms(dup) if dup else 0.0
    if jtype is JointType.PRISMATIC:
        prior = ucfg.drawer_travel_prior
    else:
        free = ref[2] >= door_stop(config.joints, ref[0], ref[1], child.prim) - 1e-9     # no obstacle stopped it
        prior = ucfg.door_stop_prior if free else 0.0
    # a thick door's pivot lies anywhere across the thickness the scan leaves undecided (uniform over it,
    # the estimate at its back end: RMS undecided / sqrt(3)); behind it, in the clearance the scan does not
    # resolve, anywhere in the right triangle of that leg (deeper, or in from the edge), the estimate at its
    # corner: RMS clearance / sqrt(3)
    clearance = float(hinge_depth.clearance) if revolute and hinge_depth is not None else 0.0
    return JointUncertainty(rms(ang), float(np.sqrt(rms(off) ** 2 + (undecided ** 2 + clearance ** 2) / 3.0)),
                            float(np.hypot(upper, prior)), int(ucfg.samples), METHOD, side)


def _capped(part: _PartData, n: int, rng: np.random.Generator) -> _PartData:
    """At most ``n`` of the part's points (a seeded subsample, as Eq. 3 fitting caps its input)."""
    if len(part.points) <= n:
        return part
    idx = np.sort(rng.choice(len(part.points), n, replace=False))
    return _PartData(part.prim, part.points[idx], None if part.normals is None else part.normals[idx])


def _near(points: np.ndarray, prims: list[Primitive], margin: float) -> np.ndarray:
    """The ``points`` (n, 3) within ``margin`` (m) plus the moving parts' reach of the parts' corners' box
    (a crop that keeps every point a replicate's sweep can meet)."""
    if not len(points):
        return points
    c = np.concatenate([p.corners() for p in prims])
    reach = float(np.max(np.ptp(c, axis=0)))
    lo, hi = c.min(axis=0) - reach - margin, c.max(axis=0) + reach + margin
    return points[np.all((points >= lo) & (points <= hi), axis=1)]


def _replicate(jtype, par: _PartData, chi: _PartData, ip, ic, handles, others, obstacles,
               config: ReconConfig, sweep: bool):
    """(axis, origin, upper) re-estimated from the points indexed by ``ip`` / ``ic`` (None = all); upper is
    NaN unless ``sweep`` (the limit's collision sweep is the costly part). A door's hinge is on its box's
    back face here: the depth across a thick door is not resampled (``hinge_depth``, from all the points)."""
    p_box = _refit(par, ip, config.fitting)
    c_box = _refit(chi, ic, config.fitting)
    axis, origin, upper, _ = movable_joint_detail(jtype, p_box, c_box, handles, [c_box, *others],
                                                  obstacles if sweep else None, config.joints, config.contacts,
                                                  config.fitting)
    R = _plane_tilt(chi, ic, config.fitting)
    return R @ axis, origin, float(upper)


def _refit(part: _PartData, idx, config: FittingConfig) -> Primitive:
    """The part's box refitted to its (resampled) points, its frame turned by the change in the normals'
    dominant yaw. On a noisy scan, the depth-noise / front correction of the fitted box (the last step
    of Eq. 3 fitting) re-run on these points; on a clean one (the correction keeps the box), the
    extents of the points in the box's frame (the Eq. 3 candidate box), then the front rule."""
    if part.prim.kind is not PrimitiveKind.BOX:
        return part.prim
    pts = part.points if idx is None else part.points[idx]
    nrm = None if part.normals is None else (part.normals if idx is None else part.normals[idx])
    T = part.prim.T_world_part.copy()
    if idx is not None and part.normals is not None:
        y0, y1 = dominant_yaw(part.normals), dominant_yaw(nrm)
        if y0 is not None and y1 is not None:
            d = (y1 - y0 + np.pi / 4) % (np.pi / 2) - np.pi / 4
            c, s = np.cos(d), np.sin(d)
            T[:3, :3] = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]) @ T[:3, :3]
    box = Primitive(PrimitiveKind.BOX, part.prim.size, T)
    out = denoised_box(box, pts, config, nrm)
    if out is not box:
        return out
    R = T[:3, :3]
    q = pts @ R
    lo, hi = q.min(axis=0), q.max(axis=0)
    T[:3, 3] = R @ ((lo + hi) / 2)
    return denoised_box(Primitive(PrimitiveKind.BOX, np.maximum(hi - lo, config.min_thickness), T), pts, config,
                        nrm)


def _plane_tilt(part: _PartData, idx, config: FittingConfig) -> np.ndarray:
    """(3, 3) the smallest rotation from a panel's face normal (smallest principal direction of all its
    points) to that of the resampled points; identity for a non-panel part or ``idx`` None."""
    size = np.sort(part.prim.size)
    if idx is None or size[0] >= config.panel_ratio * size[1]:
        return np.eye(3)
    n0 = _normal(part.points)
    n1 = _normal(part.points[idx])
    if n1 @ n0 < 0:
        n1 = -n1
    v = np.cross(n0, n1)
    s, c = float(np.linalg.norm(v)), float(n0 @ n1)
    if s < 1e-12:
        return np.eye(3)
    K = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]]) / s
    a = np.arctan2(s, c)
    return np.eye(3) + np.sin(a) * K + (1 - np.cos(a)) * (K @ K)


def _normal(points: np.ndarray) -> np.ndarray:
    c = points - points.mean(axis=0)
    return np.linalg.svd(c, full_matrices=False)[2][2]
