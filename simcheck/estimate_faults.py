"""Faulty estimates for testing certification: WRONG scene URDFs built from a correct one by editing its
scene model (:func:`scenes.description.read_urdf`, then :func:`~scenes.description.write_urdf`; the input
file is never modified). simcheck's tests and benchmark use them to show that a wrong
estimate is never certified; users can do the same with their own scenes.

Each function reads ``src``, changes one joint the way a bad reconstruction would, and writes ``out``:

* :func:`rotate_axis`          -- a drawer axis ``deg`` degrees off (rotated about the joint frame's z);
* :func:`flip_hinge`           -- a door hinged on the wrong side (same geometry, hinge on the other edge);
* :func:`revolute_as_prismatic`-- a door estimated as a drawer sliding out along the door's initial motion;
* :func:`shift_hinge`          -- a door's hinge line moved sideways and/or along the front normal;
* :func:`tilt_hinge`           -- a door's hinge axis tilted ``deg`` degrees in the door's plane;
* :func:`move_handle`          -- the handle (bar and standoffs) moved out of or into the front;
* :func:`widen_limits`         -- joint limits ``factor`` times wider than the real ones;
* :func:`add_box`              -- (for the reference) a neighbour the estimate does not have;
* :func:`blocker_in_swing`     -- such a box placed in the swing of a door.

Assumes upright objects (joint frames whose z is the world z), as ``scenes`` and ``recon`` write them.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Callable

import numpy as np
from scipy.spatial.transform import Rotation

from scenes.description import (Inertial, Joint, JointType, Link, SceneModel, Shape, ShapeKind, T_translation,
                                read_urdf, write_urdf)

__all__ = ["rotate_axis", "flip_hinge", "shift_hinge", "tilt_hinge", "move_handle", "revolute_as_prismatic",
           "widen_limits", "add_box", "blocker_in_swing"]


def _edit(src, out, change: Callable[[SceneModel], list]) -> Path:
    """Read ``src``, put the links/joints ``change(model)`` returns in place of theirs, write ``out``."""
    model = read_urdf(src)
    return write_urdf(model.replaced(*change(model)), out)


def _joint(model: SceneModel, name: str) -> Joint:
    if name not in model.joints:
        raise KeyError(name)
    return model.joints[name]


def _shifted(T: np.ndarray, d: np.ndarray) -> np.ndarray:
    """A copy of the (4, 4) ``T`` with ``d`` (3,) added to its translation."""
    T = np.array(T, dtype=float)
    T[:3, 3] += d
    return T


def rotate_axis(src, joint: str, deg: float, out, about: str = "z") -> Path:
    """The joint axis rotated by ``deg`` about the joint frame's ``about`` axis ("z": sideways for an
    upright object; "y": tilted up/down for a drawer sliding along x)."""
    def change(m):
        j = _joint(m, joint)
        return [dataclasses.replace(j, axis=Rotation.from_euler(about, deg, degrees=True).apply(j.axis))]
    return _edit(src, out, change)


def _far_edge(model: SceneModel, j: Joint) -> np.ndarray:
    """Child-frame vector from the joint origin to the farthest box edge, perpendicular to the axis (boxes
    taken as aligned with the child frame)."""
    a = j.axis / np.linalg.norm(j.axis)
    best, best_d = None, -1.0
    for col in model.links[j.child].collisions:
        if col.kind is not ShapeKind.BOX:
            continue
        c, s = col.T_link_shape[:3, 3], col.size / 2
        for sign in (-1, 1):
            for k in range(3):
                u = np.zeros(3)
                u[k] = sign
                if abs(np.dot(u, a)) > 0.5:
                    continue
                d = np.dot(c, u) + s[k]
                if d > best_d:
                    best, best_d = u, d
    return best * best_d


def _front_normal(model: SceneModel, j: Joint) -> np.ndarray:
    """Unit vector, in the child (joint) frame, out of the front of ``j``'s part: a drawer's axis; for a
    door, the direction its free edge first moves in (axis x hinge-to-free-edge), since positive opens."""
    a = j.axis / np.linalg.norm(j.axis)
    if j.type is JointType.PRISMATIC:
        return a
    n = np.cross(a, _far_edge(model, j))
    return n / np.linalg.norm(n)


def _move_joint_keep_geometry(model: SceneModel, j: Joint, shift: np.ndarray, **joint_changes) -> list:
    """Joint ``j`` with its origin moved by ``shift`` (3,) metres, child frame (and ``joint_changes``), its
    child link and the child's joints moved back by ``shift``: the geometry, inertia and child joints stay
    where they are in the world (the closed state is unchanged)."""
    child = model.links[j.child]
    moved = [dataclasses.replace(j, T_parent_joint=_shifted(j.T_parent_joint, j.T_parent_joint[:3, :3] @ shift),
                                 **joint_changes)]
    back = -np.asarray(shift, dtype=float)
    inertial = None if child.inertial is None else \
        dataclasses.replace(child.inertial, T_link_com=_shifted(child.inertial.T_link_com, back))
    moved.append(dataclasses.replace(
        child, inertial=inertial,
        visuals=tuple(dataclasses.replace(v, T_link_shape=_shifted(v.T_link_shape, back)) for v in child.visuals),
        collisions=tuple(dataclasses.replace(c, T_link_shape=_shifted(c.T_link_shape, back))
                         for c in child.collisions)))
    moved += [dataclasses.replace(o, T_parent_joint=_shifted(o.T_parent_joint, back))
              for o in model.child_joints(j.child)]
    return moved


def flip_hinge(src, joint: str, out) -> Path:
    """Door ``joint`` hinged on its other vertical edge: the hinge moves across the door's width, the
    axis is reversed (so positive still opens outward) and the door's geometry stays where it was."""
    def change(m):
        j = _joint(m, joint)
        return _move_joint_keep_geometry(m, j, _far_edge(m, j), axis=-j.axis)
    return _edit(src, out, change)


def shift_hinge(src, joint: str, out, sideways: float = 0.0, normal: float = 0.0) -> Path:
    """Door ``joint``'s hinge line moved ``sideways`` metres along the door's width (positive: toward
    its free edge) and ``normal`` metres along its front normal (positive: out of the front); the door's
    geometry stays where it was, so only the estimated articulation is wrong."""
    def change(m):
        j = _joint(m, joint)
        edge = _far_edge(m, j)
        return _move_joint_keep_geometry(m, j, sideways * edge / np.linalg.norm(edge) + normal * _front_normal(m, j))
    return _edit(src, out, change)


def tilt_hinge(src, joint: str, deg: float, out) -> Path:
    """Door ``joint``'s hinge axis tilted by ``deg`` degrees about the door's front normal (it leans in
    the door's plane) through the joint origin; the geometry stays where it was."""
    def change(m):
        j = _joint(m, joint)
        n = _front_normal(m, j)
        return [dataclasses.replace(j, axis=Rotation.from_rotvec(np.deg2rad(deg) * n).apply(j.axis))]
    return _edit(src, out, change)


def move_handle(src, joint: str, outward: float, out) -> Path:
    """Every handle link fixed to ``joint``'s moving part (a fixed child joint whose child link's name
    contains "handle") moved ``outward`` metres along the part's front normal: positive, the estimate's
    bar stands farther out of the front than the source's (the source's bar sits deeper than
    estimated); negative, nearer the front.

    Raises:
        KeyError: ``joint`` has no such handle link (naming the joint).
    """
    def change(m):
        j = _joint(m, joint)
        n = _front_normal(m, j)
        handles = [h for h in m.child_joints(j.child) if h.type is JointType.FIXED and "handle" in h.child.lower()]
        if not handles:
            raise KeyError(f"joint {joint!r}: no handle link fixed to its part {j.child!r}")
        return [dataclasses.replace(h, T_parent_joint=_shifted(h.T_parent_joint, outward * n)) for h in handles]
    return _edit(src, out, change)


def revolute_as_prismatic(src, joint: str, out, travel: float = 0.3) -> Path:
    """Revolute ``joint`` estimated as a prismatic one sliding ``travel`` metres along the direction the
    door's free edge first moves in."""
    def change(m):
        j = _joint(m, joint)
        d = np.cross(j.axis, _far_edge(m, j))
        return [dataclasses.replace(j, type=JointType.PRISMATIC, axis=d / np.linalg.norm(d),
                                    limit=dataclasses.replace(j.limit, lower=0.0, upper=float(travel)))]
    return _edit(src, out, change)


def widen_limits(src, joint: str, factor: float, out) -> Path:
    """``joint``'s upper limit multiplied by ``factor`` (> 1: wider than the real one)."""
    def change(m):
        j = _joint(m, joint)
        return [dataclasses.replace(j, limit=dataclasses.replace(j.limit, upper=j.limit.upper * factor))]
    return _edit(src, out, change)


def _box_items(model: SceneModel, name: str, xyz, size) -> list:
    box = Shape.box(size)
    return [Link(name, Inertial(5.0, np.eye(4), np.diag([0.1, 0.1, 0.1])), (box,), (box,)),
            Joint(f"{name}_joint", JointType.FIXED, model.root, name, T_translation(xyz))]


def add_box(src, out, name: str, xyz, size) -> Path:
    """Add a fixed box link ``name`` at world position ``xyz`` (3,) with ``size`` (3,), metres."""
    return _edit(src, out, lambda m: _box_items(m, name, xyz, size))


def blocker_in_swing(src, joint: str, out, angle_deg: float = 40.0, radius_fraction: float = 0.5,
                     size=(0.12, 0.12, 0.15), name: str = "blocker99_box99") -> Path:
    """The reference with a box a neighbour could be: in the swing of door ``joint``, ``angle_deg`` open,
    at ``radius_fraction`` of the door's width from the hinge, level with the door's bottom edge
    (below the handle, so it blocks the door rather than the robot)."""
    def change(m):
        j = _joint(m, joint)
        T_world_joint = m.T_world_link(j.parent) @ j.T_parent_joint      # = the door frame's pose, closed
        axis_world, origin_world = T_world_joint[:3, :3] @ j.axis, T_world_joint[:3, 3]
        edge_world = T_world_joint[:3, :3] @ _far_edge(m, j)              # hinge -> far edge, world frame
        bottom = min((c.T_link_shape[2, 3] - c.size[2] / 2 for c in m.links[j.child].collisions
                      if c.kind is ShapeKind.BOX), default=np.inf)       # lowest door point (door z = world z)
        swing = Rotation.from_rotvec(np.deg2rad(angle_deg) * axis_world).apply(edge_world) * radius_fraction
        centre = origin_world + swing
        centre[2] = origin_world[2] + bottom + size[2] / 2
        return _box_items(m, name, centre, size)
    return _edit(src, out, change)
