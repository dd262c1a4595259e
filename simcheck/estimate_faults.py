"""Faulty estimates for testing certification: WRONG scene URDFs built from a correct one by editing its XML
(the input file is never modified). simcheck's tests and benchmark use them to show that a wrong
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

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

__all__ = ["rotate_axis", "flip_hinge", "shift_hinge", "tilt_hinge", "move_handle", "revolute_as_prismatic",
           "widen_limits", "add_box", "blocker_in_swing"]


def _load(src):
    return ET.parse(src)


def _joint(root, name):
    for j in root.findall("joint"):
        if j.get("name") == name:
            return j
    raise KeyError(name)


def _vec(el, attr, default="0 0 0"):
    return np.array([float(v) for v in (el.get(attr) if el is not None and el.get(attr) else default).split()])


def _fmt(v):
    return " ".join(f"{x:.6g}" for x in v)


def _save(tree, out) -> Path:
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    tree.write(out, encoding="unicode")
    return out


def rotate_axis(src, joint: str, deg: float, out, about: str = "z") -> Path:
    """The joint axis rotated by ``deg`` about the joint frame's ``about`` axis ("z": sideways for an
    upright object; "y": tilted up/down for a drawer sliding along x)."""
    tree = _load(src)
    j = _joint(tree.getroot(), joint)
    axis = j.find("axis")
    a = _vec(axis, "xyz", "1 0 0")
    axis.set("xyz", _fmt(Rotation.from_euler(about, deg, degrees=True).apply(a)))
    return _save(tree, out)


def _child_link(root, j):
    name = j.find("child").get("link")
    return next(l for l in root.findall("link") if l.get("name") == name)


def _far_edge(root, j) -> np.ndarray:  # noqa: D401
    """Child-frame vector from the joint origin to the farthest geometry edge, perpendicular to the axis."""
    a = _vec(j.find("axis"), "xyz", "1 0 0")
    a = a / np.linalg.norm(a)
    best, best_d = None, -1.0
    link = _child_link(root, j)
    for col in link.findall("collision"):
        box = col.find("geometry/box")
        if box is None:
            continue
        c = _vec(col.find("origin"), "xyz")
        s = _vec(box, "size") / 2
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


def _front_normal(root, j) -> np.ndarray:
    """Unit vector, in the child (joint) frame, out of the front of ``j``'s part: a drawer's axis; for a
    door, the direction its free edge first moves in (axis x hinge-to-free-edge), since positive opens."""
    a = _vec(j.find("axis"), "xyz", "1 0 0")
    a = a / np.linalg.norm(a)
    if j.get("type") == "prismatic":
        return a
    n = np.cross(a, _far_edge(root, j))
    return n / np.linalg.norm(n)


def _move_joint_keep_geometry(root, j, shift: np.ndarray) -> None:
    """Move joint ``j``'s origin by ``shift`` (3,) metres, child frame, while the child's geometry, inertia
    and child joints stay where they are in the world (the closed state is unchanged)."""
    origin = j.find("origin")
    if origin is None:
        origin = ET.SubElement(j, "origin")
    xyz, rpy = _vec(origin, "xyz"), _vec(origin, "rpy")
    origin.set("xyz", _fmt(xyz + Rotation.from_euler("xyz", rpy).apply(shift)))
    child = _child_link(root, j)
    for tag in ("visual", "collision", "inertial"):
        for el in child.findall(tag):
            o = el.find("origin")
            if o is None:
                o = ET.SubElement(el, "origin")
            o.set("xyz", _fmt(_vec(o, "xyz") - shift))
    for other in root.findall("joint"):
        if other.find("parent").get("link") == child.get("name"):
            o = other.find("origin")
            if o is None:
                o = ET.SubElement(other, "origin")
            o.set("xyz", _fmt(_vec(o, "xyz") - shift))


def flip_hinge(src, joint: str, out) -> Path:
    """Door ``joint`` hinged on its other vertical edge: the hinge moves across the door's width, the
    axis is reversed (so positive still opens outward) and the door's geometry stays where it was."""
    tree = _load(src)
    root = tree.getroot()
    j = _joint(root, joint)
    _move_joint_keep_geometry(root, j, _far_edge(root, j))
    axis = j.find("axis")
    axis.set("xyz", _fmt(-_vec(axis, "xyz")))
    return _save(tree, out)


def shift_hinge(src, joint: str, out, sideways: float = 0.0, normal: float = 0.0) -> Path:
    """Door ``joint``'s hinge line moved ``sideways`` metres along the door's width (positive: toward
    its free edge) and ``normal`` metres along its front normal (positive: out of the front); the door's
    geometry stays where it was, so only the estimated articulation is wrong."""
    tree = _load(src)
    root = tree.getroot()
    j = _joint(root, joint)
    edge = _far_edge(root, j)
    shift = sideways * edge / np.linalg.norm(edge) + normal * _front_normal(root, j)
    _move_joint_keep_geometry(root, j, shift)
    return _save(tree, out)


def tilt_hinge(src, joint: str, deg: float, out) -> Path:
    """Door ``joint``'s hinge axis tilted by ``deg`` degrees about the door's front normal (it leans in
    the door's plane) through the joint origin; the geometry stays where it was."""
    tree = _load(src)
    root = tree.getroot()
    j = _joint(root, joint)
    n = _front_normal(root, j)
    axis = j.find("axis")
    axis.set("xyz", _fmt(Rotation.from_rotvec(np.deg2rad(deg) * n).apply(_vec(axis, "xyz", "1 0 0"))))
    return _save(tree, out)


def move_handle(src, joint: str, outward: float, out) -> Path:
    """Every handle link fixed to ``joint``'s moving part (a fixed child joint whose child link's name
    contains "handle") moved ``outward`` metres along the part's front normal: positive, the estimate's
    bar stands farther out of the front than the source's (the source's bar sits deeper than
    estimated); negative, nearer the front.

    Raises:
        KeyError: ``joint`` has no such handle link (naming the joint).
    """
    tree = _load(src)
    root = tree.getroot()
    j = _joint(root, joint)
    n = _front_normal(root, j)
    part = j.find("child").get("link")
    handles = [h for h in root.findall("joint") if h.find("parent").get("link") == part
               and h.get("type") == "fixed" and "handle" in h.find("child").get("link").lower()]
    if not handles:
        raise KeyError(f"joint {joint!r}: no handle link fixed to its part {part!r}")
    for h in handles:
        o = h.find("origin")
        if o is None:
            o = ET.SubElement(h, "origin")
        o.set("xyz", _fmt(_vec(o, "xyz") + outward * n))
    return _save(tree, out)


def revolute_as_prismatic(src, joint: str, out, travel: float = 0.3) -> Path:
    """Revolute ``joint`` estimated as a prismatic one sliding ``travel`` metres along the direction the
    door's free edge first moves in."""
    tree = _load(src)
    root = tree.getroot()
    j = _joint(root, joint)
    a = _vec(j.find("axis"), "xyz")
    u = _far_edge(root, j)
    d = np.cross(a, u)
    j.set("type", "prismatic")
    j.find("axis").set("xyz", _fmt(d / np.linalg.norm(d)))
    lim = j.find("limit")
    lim.set("lower", "0")
    lim.set("upper", f"{travel:g}")
    return _save(tree, out)


def widen_limits(src, joint: str, factor: float, out) -> Path:
    """``joint``'s upper limit multiplied by ``factor`` (> 1: wider than the real one)."""
    tree = _load(src)
    lim = _joint(tree.getroot(), joint).find("limit")
    lim.set("upper", f"{float(lim.get('upper')) * factor:.6g}")
    return _save(tree, out)


def add_box(src, out, name: str, xyz, size) -> Path:
    """Add a fixed box link ``name`` at world position ``xyz`` (3,) with ``size`` (3,), metres."""
    tree = _load(src)
    root = tree.getroot()
    link = ET.SubElement(root, "link", name=name)
    inertial = ET.SubElement(link, "inertial")
    ET.SubElement(inertial, "mass", value="5.0")
    ET.SubElement(inertial, "inertia", ixx="0.1", iyy="0.1", izz="0.1", ixy="0", ixz="0", iyz="0")
    for tag in ("visual", "collision"):
        el = ET.SubElement(link, tag)
        ET.SubElement(el, "origin", xyz="0 0 0")
        g = ET.SubElement(el, "geometry")
        ET.SubElement(g, "box", size=_fmt(size))
    jt = ET.SubElement(root, "joint", name=f"{name}_joint", type="fixed")
    ET.SubElement(jt, "parent", link="world")
    ET.SubElement(jt, "child", link=name)
    ET.SubElement(jt, "origin", xyz=_fmt(xyz), rpy="0 0 0")
    return _save(tree, out)


def blocker_in_swing(src, joint: str, out, angle_deg: float = 40.0, radius_fraction: float = 0.5,
                     size=(0.12, 0.12, 0.15), name: str = "blocker99_box99") -> Path:
    """The reference with a box a neighbour could be: in the swing of door ``joint``, ``angle_deg`` open,
    at ``radius_fraction`` of the door's width from the hinge, level with the door's bottom edge
    (below the handle, so it blocks the door rather than the robot)."""
    from simcheck.scene_joints import read_scene_joints
    from simcheck.world import World

    tree = _load(src)
    root = tree.getroot()
    j = _joint(root, joint)
    sj = read_scene_joints(src)[joint]
    with World(src) as w:                                        # the door frame's world pose, closed
        R_world_door = w.scene_link_pose(sj.child)[:3, :3]
    edge_world = R_world_door @ _far_edge(root, j)               # hinge -> far edge, world frame
    bottom = np.inf                                              # lowest door point (door frame z = world z)
    for col in _child_link(root, j).findall("collision"):
        box = col.find("geometry/box")
        if box is not None:
            bottom = min(bottom, _vec(col.find("origin"), "xyz")[2] - _vec(box, "size")[2] / 2)
    swing = Rotation.from_rotvec(np.deg2rad(angle_deg) * sj.axis_world).apply(edge_world) * radius_fraction
    centre = sj.origin_world + swing
    centre[2] = sj.origin_world[2] + bottom + size[2] / 2
    return add_box(src, out, name, centre, size)
