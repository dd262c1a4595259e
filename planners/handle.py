"""Handle discovery and grasp frames for the part a joint moves (pure numpy over the parsed URDF).

Where the handle is looked for, in order:

1. ``OpenTask.grasp_link`` / ``OpenTask.grasp_point`` when given;
2. a link fixed (directly or through fixed joints) below the moving link whose name contains "handle";
3. the only link fixed below the moving link;
4. collision geometry of the moving link whose ``name`` attribute contains "handle";
5. geometry of the moving link (or links fixed below it) that stands out of its front: beyond the outer
   face of its largest geometry (the panel), along the way the part opens, and small beside it (a knob,
   a handle exported as unnamed mesh geometry of the door);
6. when the part has mesh geometry and nothing of 5: the surface that stands out of its front face (a
   door exported as one mesh, panel and handle together; :mod:`planners.handle_surface`);
7. nothing of the above: the front panel's edges, pinched across the panel (:mod:`planners.edge_grasp`).

A panel too thick for the gripper raises :class:`planners.errors.HandleNotFoundError` naming the file and
the joint; whether a finger fits behind an edge is for the stand-pose search to find out.

Grasp frame (the robot's tool frame at grasp): origin at the handle bar's centre, z (approach) against
the part's outward direction (the direction the grasp point moves when the joint opens), x along the
bar, so the fingers (closing along y) close across the bar's thin dimension. Horizontal bars get a
downward approach tilt (:attr:`PlannerConfig.grasp_tilt`). Several candidates are returned (tilted or
level, at the bar centre or backed off further out, each also turned half a turn about the approach axis
because either finger may come from above); base placement takes the first that works.

The backed-off candidate (for a bar or knob cap whose estimated mount face leaves the fingertips no room
at its centre) is held ``grasp_backoff`` further out, but never more than ``grasp_backoff_share`` of the
grasped shape's depth along the approach: the tool frame then stays inside the bar, and the fingertips,
which reach past the tool frame, still close on it (why, with the measurements:
``docs/decisions.md``, "Grasp back-off").
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

from planners.config import PlannerConfig
from planners.errors import HandleNotFoundError, HandleStaysPutError
from scenes.description import R_about, SceneModel, Shape, ShapeKind
from planners.task import OpenTask

__all__ = ["HandleGrasp", "find_handle", "grasp_path", "handle_link", "outward_direction"]

log = logging.getLogger(__name__)

PROTRUDING_SHARE = 0.5
#: a prismatic part whose largest face's normal is within this cosine of perpendicular to its motion slides
#: across its front (a sliding door): its handle stands out of that face and is approached along its normal
SLIDING_ALIGNMENT = float(np.cos(np.radians(75.0)))
#: ... and no geometry of it shows more than this share of that face's area along the motion (a drawer's front)
SLIDING_EDGE_SHARE = 0.25
"""An unnamed geometry counts as a handle only if the area it shows along the outward direction is under this
share of the panel's (a handle or knob, not a second panel)."""


@dataclass(frozen=True)
class HandleGrasp:
    """Where and how to grasp the part moved by a joint.

    Attributes:
        moving_link: link moved by the joint.
        grasp_link: link that carries the grasped bar (the handle link, or the moving link itself).
        handle_geoms: frozenset of (link, collision index) the gripper may touch.
        T_link_grasps: tuple of (4, 4) candidate grasp frames in the moving link's frame.
        bar_width: float, metres, extent of the bar across the finger closing direction (0 if unknown).
        source: how the handle was found ("grasp_link", "grasp_point", "handle link", "fixed child",
            "named geometry", "protruding geometry", "protruding surface", "panel edge": no handle, the
            front panel pinched at an edge).
        facing: (3,) world unit direction the robot should stand along from the grasp (the front's outward
            normal) when the approach does not say it (a pinch approaches in the panel's plane); None:
            opposite the approach.
        turn_share: share of the part's turn the tool follows while opening (1: rigidly). Below 1 only for a
            round bar (a cylinder longer than its diameter) along a hinge that swings the approach up or
            down: the bar rolls about its own axis between the flat pads by the rest (:func:`grasp_path`).
    """

    moving_link: str
    grasp_link: str
    handle_geoms: frozenset
    T_link_grasps: tuple
    bar_width: float
    source: str
    facing: np.ndarray | None = None
    turn_share: float = 1.0


def _fixed_descendants(scene: SceneModel, link: str) -> list[str]:
    out, stack = [], [link]
    while stack:
        cur = stack.pop()
        for j in scene.child_joints(cur):
            if j.type == "fixed":
                out.append(j.child)
                stack.append(j.child)
    return out


def handle_link(scene: SceneModel, joint: str, preferred: str | None = None) -> str:
    """The link to grasp to move ``joint``, by the link rules of :func:`find_handle`: ``preferred`` when the
    scene has it; else the first link fixed below the moving link whose name contains "handle"; else the
    only link fixed below it; else the moving link itself (whose collision geometry named "*handle*"
    :func:`find_handle` then grasps). KeyError naming the joint when the scene has no such joint."""
    if preferred and preferred in scene.links:
        return preferred
    if joint not in scene.joints:
        raise KeyError(f"{scene.path}: no joint {joint!r}")
    moving = scene.joints[joint].child
    fixed_below = _fixed_descendants(scene, moving)
    named = [ln for ln in fixed_below if "handle" in ln.lower()]
    if named:
        return named[0]
    return fixed_below[0] if len(fixed_below) == 1 else moving


def outward_direction(scene: SceneModel, joint: str, point_world: np.ndarray, values: dict,
                      delta: float = 1e-4) -> np.ndarray:
    """``(3,)`` unnormalised velocity (world, per unit joint value) of a point rigidly attached to the joint's
    child, at the joint values ``values``; zero when the point lies on a hinge axis."""
    j = scene.joints[joint]
    s = float(values.get(joint, 0.0))
    T0 = scene.T_world_link(j.child, values)
    p_link = np.linalg.solve(T0, np.append(point_world, 1.0))
    ahead, behind = dict(values), dict(values)
    ahead[joint], behind[joint] = s + delta, s - delta
    p1 = scene.T_world_link(j.child, ahead) @ p_link
    p0 = scene.T_world_link(j.child, behind) @ p_link
    return (p1 - p0)[:3] / (2 * delta)   # central difference: exact to O(delta^2)


def _bar(geom: Shape) -> tuple[np.ndarray | None, np.ndarray, float]:
    """(long axis in geom frame or None, (3,) centre in geom frame, thickness) of a handle geometry."""
    if geom.kind == "box":
        size = np.asarray(geom.size)
        i = int(np.argmax(size))
        axis = np.eye(3)[i] if size[i] > 1.5 * np.sort(size)[1] else None
        return axis, np.zeros(3), float(np.sort(size)[1] if axis is not None else np.min(size))
    if geom.kind == "cylinder":
        r, ln = geom.radius, geom.length
        return (np.array([0.0, 0.0, 1.0]) if ln > 2 * r else None), np.zeros(3), 2 * r
    if geom.kind == "sphere":
        return None, np.zeros(3), float(geom.size[0])
    try:   # mesh: its bounding box
        import trimesh
        mesh = trimesh.load(geom.mesh, force="mesh")
        lo, hi = mesh.bounds * np.asarray(geom.size)
    except Exception:   # unreadable mesh: grasp its origin
        log.warning("handle mesh %s could not be read; grasping the geometry origin", geom.mesh)
        return None, np.zeros(3), 0.0
    size = hi - lo
    i = int(np.argmax(size))
    axis = np.eye(3)[i] if size[i] > 1.5 * np.sort(size)[1] else None
    return axis, (lo + hi) / 2, float(np.sort(size)[1])


def _outermost(scene, joint, cands, T_world_moving, values, direction=1.0):
    """The candidate geometry furthest out along the part's opening direction (a knob's cap rather than its
    stem, a bar rather than its posts); ties go to the larger geometry."""
    centres = [(T_world_moving @ c[2] @ np.append(_bar(c[1])[1], 1.0))[:3] for c in cands]
    v = direction * outward_direction(scene, joint, np.mean(centres, axis=0), values)
    n = v / max(float(np.linalg.norm(v)), 1e-12)
    return max(zip(cands, centres), key=lambda cc: (round(float(cc[1] @ n), 3), _extent(cc[0][1])))[0]


def _depth_along(geom: Shape, d: np.ndarray) -> float:
    """Extent (m) of a handle geometry along the unit direction ``d`` (3,) given in the geometry's frame
    (a mesh: its bounding box; unreadable: infinite, so the depth limits nothing)."""
    d = np.abs(np.asarray(d, dtype=float))
    if geom.kind == "box":
        return float(d @ np.asarray(geom.size))
    if geom.kind == "cylinder":   # along local z: length there, diameter across
        return float(geom.length * d[2] + 2 * geom.radius * np.hypot(d[0], d[1]))
    if geom.kind == "sphere":
        return float(geom.size[0])
    try:
        import trimesh
        lo, hi = trimesh.load(geom.mesh, force="mesh").bounds * np.asarray(geom.size)
    except Exception:
        return float("inf")
    return float(d @ (hi - lo))


def _extent(geom: Shape) -> float:
    """Size (m) that ranks candidate geometries: a box's longest edge, the larger of a cylinder's radius and
    length, a sphere's radius; 1 for a mesh."""
    if geom.kind is ShapeKind.CYLINDER:
        return max(geom.radius, geom.length)
    if geom.kind is ShapeKind.SPHERE:
        return geom.radius
    return float(max(geom.size)) if geom.kind is ShapeKind.BOX else 1.0


def _protruding(scene, joint, cands, T_world_moving, values, direction, outward=None) -> list:
    """The candidate geometries that stand out of the front: their centre lies beyond the outer face of the
    panel (the geometry showing the largest area along the part's outward direction), and they are small beside it (the area
    they show along that direction under ``PROTRUDING_SHARE`` of the panel's). A knob (stem and cap), a handle given as
    unnamed mesh geometry of the moving link. Empty when nothing stands out (a front without a handle).
    ``outward`` (3,) world: the side to look on instead of the part's motion (:func:`sliding_front`)."""
    if len(cands) < 2:
        return []
    sizes = [_box_extent(c[1]) for c in cands]
    centre = np.mean([(T_world_moving @ c[2] @ np.append(_bar(c[1])[1], 1.0))[:3] for c in cands], axis=0)
    v = direction * outward_direction(scene, joint, centre, values) if outward is None else np.asarray(outward)
    if np.linalg.norm(v) < 1e-9:
        return []
    n_link = T_world_moving[:3, :3].T @ (v / np.linalg.norm(v))      # outward, moving-link frame

    def facing_area(c, e):        # area the geometry shows along the outward direction, m^2
        m = np.abs(c[2][:3, :3].T @ n_link)
        return float(e[0] * e[1] * m[2] + e[1] * e[2] * m[0] + e[0] * e[2] * m[1])

    k = int(np.argmax([facing_area(c, e) for c, e in zip(cands, sizes)]))
    panel, panel_size = cands[k], sizes[k]
    R = panel[2][:3, :3]
    face = int(np.argmax(np.abs(R.T @ n_link)))          # the panel's face the outward direction is nearest
    n_link = R[:, face] * np.sign(R[:, face] @ n_link)
    outer = float(panel[2][:3, 3] @ n_link + 0.5 * np.abs(R.T @ n_link) @ panel_size)
    out = []
    for c, size in zip(cands, sizes):
        if c is panel:
            continue
        p = (c[2] @ np.append(_bar(c[1])[1], 1.0))[:3]
        if p @ n_link > outer - 1e-4 and facing_area(c, size) < PROTRUDING_SHARE * facing_area(panel, panel_size):
            out.append(c)
    return out


def sliding_front(scene: SceneModel, joint: str, geoms: list, T_world_moving: np.ndarray, values: dict,
                  direction: float = 1.0) -> np.ndarray | None:
    """The outward unit normal (3,) world of a part that slides across its own front -- a sliding door or
    sash: a prismatic joint moving within ``SLIDING_ALIGNMENT`` of the plane of the part's largest upright
    face, no geometry of the part showing ``SLIDING_EDGE_SHARE`` of that face's area along the motion --
    on the side away from the parent link's geometry (the carcass behind it); None for anything else (a
    drawer moves along its front's normal). ``geoms``: the part's ``(link, geometry, T_moving_geom, index)``."""
    j = scene.joints[joint]
    if j.type != "prismatic" or not geoms:
        return None
    motion = direction * outward_direction(scene, joint, T_world_moving[:3, 3], values)
    if np.linalg.norm(motion) < 1e-9:
        return None
    motion = motion / np.linalg.norm(motion)
    best, normal, along = 0.0, None, 0.0
    for c in geoms:
        e, R = _box_extent(c[1]), T_world_moving[:3, :3] @ c[2][:3, :3]
        m = np.abs(R.T @ motion)
        along = max(along, float(e[0] * e[1] * m[2] + e[1] * e[2] * m[0] + e[0] * e[2] * m[1]))
        for k in range(3):
            area = float(np.prod(np.delete(e, k)))
            if area > best and abs(R[2, k]) < 0.5:       # an upright face (a drawer's bottom is not a front)
                best, normal = area, R[:, k]
    if normal is None or abs(float(normal @ motion)) > SLIDING_ALIGNMENT or along > SLIDING_EDGE_SHARE * best:
        return None
    centre = np.mean([(T_world_moving @ c[2])[:3, 3] for c in geoms], axis=0)
    T_parent = scene.T_world_link(j.parent, values)
    behind = [(T_parent @ g.T_link_shape)[:3, 3] for g in scene.links[j.parent].collisions]
    if not behind:
        return None
    return normal * (1.0 if float((centre - np.mean(behind, axis=0)) @ normal) >= 0 else -1.0)


def _box_extent(geom: Shape) -> np.ndarray:
    """(3,) extents (m) of a geometry in its own frame: box size, cylinder (2r, 2r, length), sphere (2r)^3,
    a mesh's bounding box (unreadable: zeros)."""
    if geom.kind is ShapeKind.BOX:
        return np.asarray(geom.size, dtype=float)
    if geom.kind is ShapeKind.CYLINDER:
        return np.array([2 * geom.radius, 2 * geom.radius, geom.length])
    if geom.kind is ShapeKind.SPHERE:
        return np.full(3, 2 * geom.radius)
    try:
        import trimesh
        lo, hi = trimesh.load(geom.mesh, force="mesh").bounds * np.asarray(geom.size)
    except Exception:
        return np.zeros(3)
    return hi - lo


def _name(cand) -> str:
    """Lower-case name of a candidate ``(link, geometry, T_moving_geom, index)`` (``link_index`` if unnamed)."""
    return (cand[1].name or f"{cand[0]}_{cand[3]}").lower()


def find_handle(scene: SceneModel, task: OpenTask, values: dict, cfg: PlannerConfig,
                direction: float = 1.0, amount: float = 0.0, grip_width: float = 0.08) -> HandleGrasp:
    """Find the handle of the part moved by ``task.joint`` with the scene at joint ``values``; ``direction``
    +1 / -1: the joint opens toward increasing / decreasing values (the outward side is where the handle
    moves when it opens). ``amount`` (rad, signed; 0: unknown): how far a revolute joint will turn; on a
    door that swings up or down (a horizontal hinge) the approach turns with it, and the first grasp
    candidates are tilted so that the approach is tilted by ``cfg.grasp_tilt`` half-way through the swing.
    When the bar held there is round and lies along the hinge, the tool follows only ``cfg.grasp_turn_share`` of
    the turn (``HandleGrasp.turn_share``; the bar rolls between the pads by the rest; paths: :func:`grasp_path`).
    A part without a handle is pinched on an edge of its front panel (:mod:`planners.edge_grasp`; source
    "panel edge") when the panel is thinner than ``grip_width`` (m, the gripper's largest opening) allows."""
    j = scene.joints[task.joint]
    moving = j.child
    where = f"{scene.path}: joint {task.joint!r}"
    fixed_below = _fixed_descendants(scene, moving)
    T_world_moving = scene.T_world_link(moving, values)

    def geoms_of(link):
        T = np.linalg.solve(T_world_moving, scene.T_world_link(link, values))
        return [(link, g, T @ g.T_link_shape, k) for k, g in enumerate(scene.links[link].collisions)]

    cands, source, front = [], "", None
    if task.grasp_link is not None:
        if task.grasp_link not in scene.links:
            raise HandleNotFoundError(f"{where}: grasp_link {task.grasp_link!r} is not a link of the scene")
        if task.grasp_link != moving and task.grasp_link not in fixed_below:
            raise HandleNotFoundError(f"{where}: grasp_link {task.grasp_link!r} is not rigidly attached to "
                                      f"the moving link {moving!r}")
        cands, source = geoms_of(task.grasp_link), "grasp_link"
        named = [c for c in cands if "handle" in _name(c)]
        cands = named or cands
    else:
        link = handle_link(scene, task.joint)
        if link != moving:
            cands, source = geoms_of(link), "handle link" if "handle" in link.lower() else "fixed child"
        else:
            every = [c for ln in [moving] + fixed_below for c in geoms_of(ln)]
            cands = [c for c in every if "handle" in _name(c)]
            source = "named geometry"
            front = sliding_front(scene, task.joint, every, T_world_moving, values, direction)
            if not cands and task.grasp_point is None:
                cands = _protruding(scene, task.joint, every, T_world_moving, values, direction, front)
                source = "protruding geometry"
    cands = [c for c in cands if c[1] is not None]
    if task.grasp_point is not None:
        p_world = np.asarray(task.grasp_point, dtype=float)
        p_link = np.linalg.solve(T_world_moving, np.append(p_world, 1.0))[:3]
        if not cands:   # the geometries the point is on or near may be touched
            near = []
            for ln in [moving] + fixed_below:
                for c in geoms_of(ln):
                    d = np.linalg.norm(c[2][:3, 3] - p_link) - 0.5 * _extent(c[1]) * np.sqrt(3)
                    if d < 0.05:
                        near.append(c)
            cands = near
        axis, width, grasp_link, depth_geom, held = None, 0.0, moving, None, None
        if cands:
            best = _outermost(scene, task.joint, cands, T_world_moving, values, direction)
            grasp_link, held = best[0], best
            a, _, width = _bar(best[1])
            axis = None if a is None else best[2][:3, :3] @ a
        source = "grasp_point"
    else:
        surface = None
        if not cands and source == "protruding geometry" and any(c[1].kind is ShapeKind.MESH for c in every):
            from planners.handle_surface import protruding_surface
            centre = np.mean([(T_world_moving @ c[2] @ np.append(_bar(c[1])[1], 1.0))[:3] for c in every], axis=0)
            v = direction * outward_direction(scene, task.joint, centre, values)
            if np.linalg.norm(v) > 1e-9:
                surface = protruding_surface(every, T_world_moving[:3, :3].T @ v, j.type == "prismatic")
        if surface is not None:
            cands = [c for c in every if (c[0], c[3]) in set(surface.geoms)]
            source = "protruding surface"
        if not cands:
            return _edge_grasp(scene, task, every, T_world_moving, values, direction, cfg, grip_width, where)
        held = None
        if surface is not None:      # a handle that is part of the front's own mesh
            grasp_link, depth_geom = cands[0][0], None
            p_link, axis, width = surface.p, surface.axis, surface.width
        else:
            best = _outermost(scene, task.joint, cands, T_world_moving, values, direction)
            grasp_link, depth_geom, held = best[0], best, best
            a, centre, width = _bar(best[1])
            p_link = (best[2] @ np.append(centre, 1.0))[:3]
            axis = None if a is None else best[2][:3, :3] @ a
    p_world = (T_world_moving @ np.append(p_link, 1.0))[:3]
    v = direction * outward_direction(scene, task.joint, p_world, values)
    if np.linalg.norm(v) < cfg.min_handle_lever * (1.0 if j.type == "prismatic" else 1.0):
        raise HandleStaysPutError(f"{where}: the handle at {np.round(p_world, 3).tolist()} does not move when "
                                  f"the joint opens (it lies on the hinge axis)")
    n = v / np.linalg.norm(v) if front is None else front      # a sliding front: approached along its normal
    axis_world = None if axis is None else T_world_moving[:3, :3] @ axis
    backoff = cfg.grasp_backoff
    if depth_geom is not None:
        n_geom = depth_geom[2][:3, :3].T @ (T_world_moving[:3, :3].T @ n)   # the outward direction, geometry frame
        backoff = min(backoff, cfg.grasp_backoff_share * _depth_along(depth_geom[1], n_geom))
    swing, share = 0.0, 1.0
    if j.type != "prismatic" and amount:
        T_end = scene.T_world_link(moving, {**values, task.joint: float(values.get(task.joint, 0.0)) + amount})
        z_end = T_end[:3, :3] @ (T_world_moving[:3, :3].T @ -n)
        swing = float(np.arcsin(np.clip(z_end[2], -1, 1)) - np.arcsin(np.clip(-n[2], -1, 1)))
        hinge = scene.T_world_link(j.parent, values)[:3, :3] @ j.T_parent_joint[:3, :3] @ j.axis
        if abs(swing) > _SWING_CENTRED and held is not None and _round_bar(held[1]) and axis_world is not None \
                and abs(axis_world @ hinge) > _ALONG_HINGE * np.linalg.norm(axis_world) * np.linalg.norm(hinge):
            share = cfg.grasp_turn_share
    frames = _grasp_frames(p_world, n, axis_world, task.kind, cfg.grasp_tilt, backoff, swing, share)
    T_link = tuple(np.linalg.solve(T_world_moving, T) for T in frames)
    geoms = frozenset((c[0], c[3]) for c in cands)
    log.debug("%s: handle via %s at %s, outward %s", where, source, p_world.round(3), n.round(3))
    return HandleGrasp(moving, grasp_link, geoms, T_link, width, source, turn_share=share)


def _round_bar(geom: Shape) -> bool:
    """A cylinder longer than its diameter: held across its axis, it rolls between flat pads."""
    return geom.kind == "cylinder" and geom.length > 2.0 * geom.radius


#: a grasped bar within this angle of the hinge axis (cos 15 deg) rolls in the fingers as the part turns
_ALONG_HINGE = float(np.cos(np.radians(15.0)))


def grasp_path(handle: HandleGrasp, index: int, T_moving: np.ndarray, s: np.ndarray, axis_link: np.ndarray
               ) -> np.ndarray:
    """``(m, 4, 4)`` world tool poses holding grasp candidate ``index`` of ``handle`` while the moving link is at
    ``T_moving (m, 4, 4)`` (task joint values ``s (m,)``, the first the grasp's; ``axis_link (3,)`` the joint
    axis, in the moving link's frame). A rigid grasp turns with the link; with ``handle.turn_share`` < 1 the tool
    turns back about its own x axis (along the bar, along the hinge) so that it follows only that share of the
    turn, the round bar rolling between the pads by the rest; its origin, on the bar, moves with the link."""
    T_lg = handle.T_link_grasps[index]
    out = T_moving @ T_lg
    if handle.turn_share >= 1.0:
        return out
    sigma = float(np.sign(T_lg[:3, 0] @ np.asarray(axis_link, dtype=float)))
    back = -sigma * (1.0 - handle.turn_share) * (np.asarray(s, dtype=float) - float(s[0]))
    c, sn = np.cos(back), np.sin(back)
    R = np.zeros((len(back), 3, 3))
    R[:, 0, 0] = 1.0
    R[:, 1, 1], R[:, 1, 2], R[:, 2, 1], R[:, 2, 2] = c, -sn, sn, c
    out[:, :3, :3] = out[:, :3, :3] @ R
    return out


def _edge_grasp(scene, task, every, T_world_moving, values, direction, cfg, grip_width, where) -> HandleGrasp:
    """Pinch grasps on the front panel's edges of a part without a handle (:func:`planners.edge_grasp.edge_grasps`)."""
    from planners.edge_grasp import edge_grasps
    moving = scene.joints[task.joint].child
    if not every:
        raise HandleNotFoundError(f"{where}: no handle found on moving link {moving!r} and no geometry to pinch; "
                                  f"give OpenTask.grasp_point or grasp_link")

    def speed(p_link):
        return direction * outward_direction(scene, task.joint, (T_world_moving @ np.append(p_link, 1.0))[:3], values)

    centre = np.mean([(c[2] @ np.append(_bar(c[1])[1], 1.0))[:3] for c in every], axis=0)
    outward = T_world_moving[:3, :3].T @ speed(centre)
    if np.linalg.norm(outward) < 1e-9:      # the centre on the axis (a door turning about its middle)
        outward = T_world_moving[:3, :3].T @ speed(centre + np.array([0.1, 0.1, 0.1]))
    edges = edge_grasps(every, speed, outward, grip_width, where)
    lever = max(float(np.linalg.norm(speed(T[:3, 3]))) for T in edges.frames) if edges.frames else 0.0
    if lever < cfg.min_handle_lever:
        raise HandleStaysPutError(f"{where}: the front's edges do not move when the joint opens (its panel lies "
                                  f"on the hinge axis)")
    facing = T_world_moving[:3, :3] @ edges.facing
    log.debug("%s: no handle; pinching the front panel's edge (%.0f mm thick)", where, edges.thickness * 1000)
    return HandleGrasp(moving, edges.geom[0], frozenset([edges.geom]), edges.frames, edges.thickness, "panel edge",
                       facing=facing)


#: a swing that turns the approach up or down by more than this (rad) gets the swing-centred grasp first
_SWING_CENTRED = np.radians(10.0)


def _grasp_frames(p: np.ndarray, n: np.ndarray, bar_axis: np.ndarray | None, kind: str, tilt: float,
                  backoff: float, swing: float = 0.0, share: float = 1.0) -> list:
    """Candidate ``(4, 4)`` world grasp frames at ``p`` approaching along ``-n`` with x along the bar.

    In order of preference: tilted (horizontal bars only) then level; at the bar centre, then held
    ``backoff`` metres further out (a short knob close to the part's face leaves no room for the fingertips;
    a knob, ``bar_axis`` None, is held level there); each also turned half a turn about the approach axis. ``swing`` (rad, up positive): how much the
    approach's elevation changes over the opening (a door hinged at the bottom turns it up, a flap hinged
    at the top down); beyond :data:`_SWING_CENTRED` a horizontal bar is first grasped tilted by
    ``tilt + share * swing / 2`` downward, so the approach is tilted by ``tilt`` half-way through the swing
    when the tool follows ``share`` of the part's turn.
    """
    z = -n
    ez = np.array([0.0, 0.0, 1.0])
    x = None
    knob = bar_axis is None
    if bar_axis is not None:
        x = bar_axis - (bar_axis @ z) * z
        if np.linalg.norm(x) < 0.3:
            x = None
    if x is None:   # knob or unknown: vertical fingers for doors, horizontal closing for drawers
        x = ez - (ez @ z) * z if kind == "door" else np.cross(ez, z)
        if np.linalg.norm(x) < 1e-6:
            x = np.cross(np.array([1.0, 0.0, 0.0]), z)
    x = x / np.linalg.norm(x)
    R0 = np.column_stack([x, np.cross(z, x), z])
    rotations = [R0]
    if abs(x @ ez) < 0.5 and tilt > 0:   # horizontal bar: tilt the approach downward about the bar
        down = 1.0 if (R_about(x, tilt) @ z) @ ez <= z @ ez else -1.0
        rotations = [R_about(x, down * tilt) @ R0, R0]
        if abs(swing) > _SWING_CENTRED:
            rotations.insert(0, R_about(x, down * (tilt + share * swing / 2)) @ R0)
    out = []
    for depth in (0.0, backoff):
        # a knob held at its cap's outer face is held level: tilted there, the lower fingertip lands on the cap's
        # front rim instead of its pad (kitchen 3's cabinet1_drawer2 with plan seeds 3 and 4, 49 deg off the pad)
        for R in rotations if depth == 0.0 or not knob else rotations[-1:]:
            for flip in (False, True):
                T = np.eye(4)
                T[:3, :3] = R @ np.diag([-1.0, -1.0, 1.0]) if flip else R
                T[:3, 3] = p - depth * R[:, 2]
                out.append(T)
    return out
