"""Joints of the part tree from the articulated templates: type, axis, origin and limits (world frame).

Drawer (prismatic): the axis is the outward normal of the parent's face the drawer sits in — among the
parent's non-horizontal faces, those with the drawer's handle outside them (when it has one), the face
the drawer reaches most closely. Travel = ``drawer_travel_fraction`` × the parent's depth along the axis,
shortened if pulling the drawer out would run into other scan points.

Door (revolute): same face; the hinge is the door's edge opposite its handle — a vertical hinge when
the handle sits off to one side, a horizontal one at the bottom (fold-down) or top (fold-up) when it
sits near the top or bottom edge. The hinge line lies at the edge, on the door's back face (the side
facing its body) -- for a door thicker than a front's board, at the carcass's front on which it rests,
or on its front face when a face beside the hinge edge leaves it no other pivot (hinge_depth.py). The
axis sign makes a
positive angle swing the door outward. The limit is the largest angle (up to ``door_max_angle``, or
``door_drop_angle`` for a door that opens downward: :func:`door_stop`) the door and its handle sweep
without containing other scan points (its body's, a neighbour's, a wall's).

Everything else is fixed (templates.py). lower = 0 is the scanned state.
"""

from __future__ import annotations

import logging
from typing import NamedTuple

import numpy as np

from recon.config import ContactConfig, FittingConfig, JointConfig
from recon.depth_noise import seen_face
from recon.hinge_depth import HingeDepth, SeenPoints, hinge_depth
from recon.model import JointEstimate, JointType
from recon.part_tree import PartTree
from recon.primitive import Primitive, volume_weighted_centre
from recon.templates import template_for
from scenes.description import T_about

__all__ = ["Hinge", "SeenPoints", "door_stop", "estimate_joints", "movable_joint", "movable_joint_detail",
           "opening_face", "hinge", "hinge_line", "seen_points", "sweep_limit"]

log = logging.getLogger(__name__)

_UP = np.array([0.0, 0.0, 1.0])


def opening_face(parent: Primitive, child: Primitive, handles: list[Primitive],
                 contacts: ContactConfig, fitting: FittingConfig,
                 interior: np.ndarray | None = None) -> tuple[np.ndarray, float]:
    """The parent's face a drawer/door sits in: (outward unit normal (3,), d) of that plane.

    Among the parent's faces with a horizontal normal: those its handles stand outside of (when it has
    handles); then those facing away from ``interior`` (3,) world, the centre of the object's other
    parts, when given (a drawer in a thin rail, a table's apron, opens away from the table, not toward
    it); then, for a panel-like child (a closed drawer or a door is seen as its front panel), the
    face most parallel to the panel; then the face the child reaches most closely.
    """
    planes = parent.planes(contacts.cylinder_side_faces)
    side = [p for p in planes if abs(p.normal[2]) < 0.5] or list(planes)
    corners = child.corners()
    ext = np.sort(child.size)
    R = child.T_world_part[:3, :3]
    thin = R[:, int(np.argmin(child.size))] if ext[0] < fitting.panel_ratio * ext[1] else None
    cand = []
    for pl in side:
        gap = float(np.max(corners @ pl.normal + pl.d))            # child's outermost reach past the plane
        outside = all(float(h.center @ pl.normal + pl.d) > -contacts.theta_d for h in handles)
        skew = 0.0 if thin is None else round(1.0 - abs(float(pl.normal @ thin)), 2)
        inward = interior is not None and float(interior @ pl.normal + pl.d) > 0.0
        cand.append((0 if outside else 1, int(inward), skew, abs(gap), pl))
    cand.sort(key=lambda t: t[:4])
    best = cand[0][4]
    return best.normal.copy(), float(best.d)


def _extent(prim: Primitive, direction: np.ndarray) -> tuple[float, float]:
    s = prim.corners() @ direction
    return float(s.min()), float(s.max())


class Hinge(NamedTuple):
    """A door's hinge: ``axis`` (3,) unit, world; ``origin`` (3,) a point on the line, world; ``desc`` how it
    was placed; ``depth`` where it lies across the door (:class:`recon.hinge_depth.HingeDepth`);
    ``side_margin`` (m): without a handle, how much nearer the chosen edge lies to its body's edge than the
    other edge does (None when a handle decides the side)."""

    axis: np.ndarray
    origin: np.ndarray
    desc: str
    depth: HingeDepth
    side_margin: float | None

    def side_undecided(self, margin: float) -> bool:
        """True when nothing decides the side: no handle and the two edges within ``margin`` (m) as near."""
        return self.side_margin is not None and self.side_margin < margin


def hinge(parent: Primitive, door: Primitive, handles: list[Primitive], normal: np.ndarray,
          seen: SeenPoints | None = None, config: JointConfig = JointConfig()
          ) -> tuple[np.ndarray, np.ndarray, str]:
    """(axis (3,), origin (3,), description) of a door's hinge; ``normal`` = the opening's outward normal.
    :func:`hinge_line` without the depth's spread."""
    return hinge_line(parent, door, handles, normal, seen, config)[:3]


def hinge_line(parent: Primitive, door: Primitive, handles: list[Primitive], normal: np.ndarray,
               seen: SeenPoints | None = None, config: JointConfig = JointConfig()
               ) -> Hinge:
    """A door's :class:`Hinge`.

    ``normal`` = the opening's outward normal; ``seen``: the scan points of the door, its parent and the
    rest of its object, which place the line across the door (:func:`recon.hinge_depth.hinge_depth`);
    None: the line on the door box's back face."""
    v = _UP - (_UP @ normal) * normal
    v = v / np.linalg.norm(v) if np.linalg.norm(v) > 1e-6 else np.cross(normal, [1.0, 0.0, 0.0])
    h = np.cross(v, normal)
    c = door.center
    lo_h, hi_h = _extent(door, h)
    lo_v, hi_v = _extent(door, v)
    back, front = _extent(door, normal)
    half_h, half_v = max((hi_h - lo_h) / 2, 1e-6), max((hi_v - lo_v) / 2, 1e-6)
    mid_h, mid_v = (hi_h + lo_h) / 2, (hi_v + lo_v) / 2
    if handles:
        hc = np.mean([p.center for p in handles], axis=0)
        a_h, a_v = (hc @ h - mid_h) / half_h, (hc @ v - mid_v) / half_v
        desc, side_margin = "opposite its handle", None
    else:                       # no handle: hinge on the side nearer the parent face's edge
        plo, phi = _extent(parent, h)
        a_h = 1.0 if abs(lo_h - plo) <= abs(phi - hi_h) else -1.0
        a_v = 0.0
        desc, side_margin = "at the body's nearer edge (no handle)", abs(abs(lo_h - plo) - abs(phi - hi_h))
    if abs(a_v) > abs(a_h):     # handle near the top/bottom edge: horizontal hinge at the other edge
        edge_v = lo_v if a_v > 0 else hi_v
        out, edge, axis, span = (-v if a_v > 0 else v), (-edge_v if a_v > 0 else edge_v), h.copy(), (lo_h, hi_h)
        origin = c + (edge_v - c @ v) * v
        desc = ("horizontal hinge at the bottom, " if a_v > 0 else "horizontal hinge at the top, ") + desc
    else:
        edge_h = lo_h if a_h > 0 else hi_h
        out, edge, axis, span = (-h if a_h > 0 else h), (-edge_h if a_h > 0 else edge_h), v.copy(), (lo_v, hi_v)
        origin = c + (edge_h - c @ h) * h
        desc = "vertical hinge " + desc
    noise = 0.0
    if seen is not None and seen.door is not None and len(seen.door):
        nrm = None if seen.door_normals is None else seen.door_normals @ door.T_world_part[:3, :3]
        noise = seen_face(door.to_part(seen.door), door.size, config.hinge_edge_min_points, nrm).sigma
    edges = ((-h, -lo_h, v, (lo_v, hi_v)), (h, hi_h, v, (lo_v, hi_v)), (-v, -lo_v, h, (lo_h, hi_h)),
             (v, hi_v, h, (lo_h, hi_h)))     # the door's four edges: (out of the door, where, along, span)
    depth = hinge_depth(front, front - back, normal, out, edge, axis, span, seen, config, noise, edges)
    origin = origin + (front - depth.depth - c @ normal) * normal
    if depth.how != "board":
        desc += f", {depth.depth * 1000:.0f} mm behind its front ({depth.how})"
    if np.cross(axis, c - origin) @ normal < 0:   # positive angle must swing the door outward
        axis = -axis
    return Hinge(axis, origin, desc, depth, side_margin)


def sweep_limit(moving: list[Primitive], motion, values: np.ndarray, obstacles: np.ndarray,
                config: JointConfig, reach: float) -> float:
    """The largest of ``values`` (increasing) reachable before the moving primitives — shrunk by
    ``sweep_clearance`` and moved by ``motion(value) -> (4, 4)`` — contain ``sweep_min_points`` of
    ``obstacles`` (n, 3). ``reach`` (m) bounds how far any moving point travels (to crop obstacles).
    Returns 0.0 when the first value already collides."""
    shrunk = [m.shrunk(config.sweep_clearance) for m in moving]
    values = np.asarray(values, dtype=np.float64)
    if len(obstacles):
        # crop to the box swept by the moving corners (sampled finely enough for hinges)
        probe = values[:: max(1, len(values) // 12)].tolist() + [0.0, float(values[-1])]
        c = np.concatenate([m.transformed(motion(v)).corners() for v in probe for m in moving])
        lo, hi = c.min(axis=0) - 0.05, c.max(axis=0) + 0.05
        obstacles = obstacles[np.all((obstacles >= lo) & (obstacles <= hi), axis=1)]
        at_rest = np.min([m.surface_distance(obstacles) + config.sweep_bleed * m.contains(obstacles)
                          for m in moving], axis=0) if len(obstacles) else np.zeros(0)
        inside = np.any([m.contains(obstacles) for m in moving], axis=0) if len(obstacles) else np.zeros(0, bool)
        obstacles = obstacles[(at_rest > config.sweep_bleed) & ~inside]
    def collides(val) -> bool:
        if not len(obstacles):
            return False
        M = motion(val)
        return sum(int(m.transformed(M).contains(obstacles).sum()) for m in shrunk) >= config.sweep_min_points

    # coarse pass over every 4th value, then the fine values just before the first coarse hit
    coarse = list(range(3, len(values), 4))
    if not coarse or coarse[-1] != len(values) - 1:
        coarse.append(len(values) - 1)
    lo_idx = 0
    for idx in coarse:
        if collides(values[idx]):
            for k in range(lo_idx, idx + 1):
                if collides(values[k]):
                    return float(values[k - 1]) if k > 0 else 0.0
        lo_idx = idx + 1
    return float(values[-1])


def _translation(axis: np.ndarray, s: float) -> np.ndarray:
    M = np.eye(4)
    M[:3, 3] = axis * s
    return M


def _drawer_travel(parent: Primitive, axis: np.ndarray, config: JointConfig, body: tuple = ()) -> float:
    """A drawer's travel (m) before collisions: ``drawer_travel_fraction`` of the parent's depth along
    ``axis`` (3,) less ``drawer_back_clearance``. A parent shallower than the object's other parts
    ``body`` (primitives) reach behind its front face (a rail, a table's apron) holds a drawer whose box
    lies behind it: the depth is then that reach, at most ``rail_drawer_depth``."""
    lo, hi = _extent(parent, axis)
    depth = hi - lo
    if body:
        behind = hi - min(_extent(p, axis)[0] for p in body)
        if behind > depth:
            depth = max(depth, min(behind, config.rail_drawer_depth))
    return config.drawer_travel_fraction * max(depth - config.drawer_back_clearance, 0.0)


def door_stop(config: JointConfig, axis: np.ndarray, origin: np.ndarray, door: Primitive) -> float:
    """The stop (rad) a door's swing ends at when nothing in the scan stops it earlier: ``door_drop_angle``
    for a door that opens downward (its axis (3,) within 45 deg of the horizontal, through ``origin`` (3,) m
    below the door's centre), else ``door_max_angle``. World frame, z up."""
    a = np.asarray(axis, dtype=np.float64) / np.linalg.norm(axis)
    r = door.center - np.asarray(origin, dtype=np.float64)
    if abs(float(a @ _UP)) < np.sin(np.radians(45.0)) and float((r - (r @ a) * a) @ _UP) > 0.0:
        return config.door_drop_angle
    return config.door_max_angle


def movable_joint(jtype: JointType, parent: Primitive, child: Primitive, handles: list[Primitive],
                  moving: list[Primitive], obstacles: np.ndarray, config: JointConfig,
                  contacts: ContactConfig, fitting: FittingConfig,
                  body: tuple[Primitive, ...] = (), seen: SeenPoints | None = None
                  ) -> tuple[np.ndarray, np.ndarray, float]:
    """(axis (3,), origin (3,), upper) of a drawer's (PRISMATIC) or door's (REVOLUTE) joint, world frame.

    parent, child : the fitted primitives; handles : the child's handles; moving : every primitive of
    the child's subtree (swept for the limit); obstacles : (n, 3) points it must not sweep into, or
    None to skip the sweep (upper is then NaN); body : the object's other parts (not moving), whose
    volume-weighted centre the opening faces away from and whose reach behind a thin parent gives a
    drawer its depth (optional); seen : the scan points that place a door's hinge across its
    thickness (:func:`hinge_line`; optional).
    upper : metres or radians (0 when the first step already collides).
    """
    return movable_joint_detail(jtype, parent, child, handles, moving, obstacles, config, contacts, fitting,
                                body, seen)[:3]


def movable_joint_detail(jtype: JointType, parent: Primitive, child: Primitive, handles: list[Primitive],
                         moving: list[Primitive], obstacles: np.ndarray, config: JointConfig,
                         contacts: ContactConfig, fitting: FittingConfig,
                         body: tuple[Primitive, ...] = (), seen: SeenPoints | None = None
                         ) -> tuple[np.ndarray, np.ndarray, float, Hinge | None]:
    """:func:`movable_joint` and, for a door, its :class:`Hinge` (None for a drawer)."""
    interior = volume_weighted_centre(body) if body else None
    normal, _ = opening_face(parent, child, handles, contacts, fitting, interior)
    if jtype is JointType.PRISMATIC:
        travel = _drawer_travel(parent, normal, config, body)
        if obstacles is None:
            return normal, child.center, float("nan"), None
        step = max(min(config.swing_step, travel / 4), 1e-3)
        steps = np.append(np.arange(step, travel, step), travel) if travel > 0 else np.zeros(1)
        reach = sweep_limit(moving, lambda s: _translation(normal, s), steps, obstacles, config, reach=travel)
        return normal, child.center, (reach if reach < travel - 1e-9 else travel), None
    line = hinge_line(parent, child, handles, normal, seen, config)
    axis, origin = line.axis, line.origin
    log.debug("hinge %s", line.desc)
    if obstacles is None:
        return axis, origin, float("nan"), line
    stop = door_stop(config, axis, origin, child)
    angles = np.append(np.arange(config.swing_step, stop, config.swing_step), stop)
    radius = max(float(np.max(np.linalg.norm(m.corners() - origin, axis=1))) for m in moving)
    upper = sweep_limit(moving, lambda a: T_about(axis, origin, a), angles, obstacles, config,
                        reach=radius)
    return axis, origin, upper, line


def seen_points(part_points: dict | None, parent: int, child: int, moving) -> SeenPoints | None:
    """The :class:`SeenPoints` of door ``child`` in ``parent`` from {part_id: (points, normals)}; ``moving``:
    the part ids that move with the door (left out of the rest). None without points."""
    if not part_points or parent not in part_points or child not in part_points:
        return None
    rest = [k for k in part_points if k not in set(moving)]
    normals = [part_points[k][1] for k in rest]
    return SeenPoints(part_points[child][0], part_points[parent][0],
                      np.concatenate([part_points[k][0] for k in rest]) if rest else None,
                      np.concatenate(normals) if rest and all(n is not None for n in normals) else None,
                      part_points[child][1])


def estimate_joints(category: str, names: dict[int, str], labels: dict[int, str],
                    prims: dict[int, Primitive], tree: PartTree, obstacles_for, config: JointConfig,
                    contacts: ContactConfig, fitting: FittingConfig, warn,
                    part_points: dict | None = None) -> tuple[JointEstimate, ...]:
    """One joint per part of an object: the root's fixed joint to the world, then the tree's.

    names : {part_id: URDF joint name}; labels : {part_id: label}; prims : refined primitives
    obstacles_for(part_ids) -> (n, 3) scan points not belonging to those parts (for the sweeps)
    warn(msg) : records a warning.
    part_points : {part_id: (points (n, 3), normals (n, 3) or None)} world, the parts' scan points (a
    door's hinge depth); optional.
    """
    root = tree.root
    joints = [JointEstimate(names[root], JointType.FIXED, None, root, _UP, prims[root].center)]
    for c in tree.top_down():
        p = tree.parent[c]
        edge = tree.edges.get(c)
        score = 0.0 if edge is None else edge.score
        tpl = template_for(category, labels[c])
        jtype = JointType.FIXED if tpl is None else tpl.joint
        if jtype is not JointType.FIXED and edge is None and labels[p] not in tpl.parents:
            warn(f"{names[c]}: part {c} ({labels[c]}) touches nothing it could move in; fixed to part "
                 f"{p} ({labels[p]}) instead of a {jtype.value} joint")
            jtype = JointType.FIXED
        handles = [k for k in tree.children(c) if labels[k] in ("handle", "knob")]
        hprims = [prims[k] for k in handles]
        if jtype is JointType.FIXED:
            joints.append(JointEstimate(names[c], JointType.FIXED, p, c, _UP, prims[c].center,
                                        contact_score=score))
            continue
        sub = tree.subtree(c)
        body = tuple(prims[k] for k in prims if k not in sub)
        axis, origin, upper, line = movable_joint_detail(jtype, prims[p], prims[c], hprims, [prims[k] for k in sub],
                                                         obstacles_for(sub), config, contacts, fitting, body,
                                                         seen_points(part_points, p, c, sub))
        side_undecided = line is not None and line.side_undecided(config.hinge_side_margin)
        if side_undecided:
            warn(f"{names[c]}: hinge side undecided: the {labels[c]} has no handle and its two edges lie as near "
                 f"its body's edges (within {line.side_margin * 1000:.0f} mm), so nothing in the scan shows which "
                 f"edge is free; hinged at one, the other is as likely (label its handle, finger pull or edge "
                 f"profile to decide)")
        travel = _drawer_travel(prims[p], axis, config, body)
        if jtype is JointType.PRISMATIC and upper < travel:
            warn(f"{names[c]}: drawer travel limited to {upper:.3f} m (of {travel:.3f} m) by scan points in its way")
        elif jtype is JointType.REVOLUTE and upper < door_stop(config, axis, origin, prims[c]) - 1e-9:
            log.info("%s: door swing stops at %.0f deg (collision)", names[c], np.degrees(upper))
        if upper <= 0.0:
            warn(f"{names[c]}: the {labels[c]} cannot move without collision; upper limit 0")
        joints.append(JointEstimate(names[c], jtype, p, c, axis, origin, 0.0, float(upper), score,
                                    handles[0] if handles else None,
                                    hinge_depth=None if line is None else line.depth,
                                    hinge_side_undecided=side_undecided))
    return tuple(joints)
