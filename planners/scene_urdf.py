"""A pure reading of an articulated scene URDF: links, their collision geometry, joints, and forward kinematics.

Only the standard library XML parser and numpy are used, so task validation and handle discovery work
(and are testable) without any engine. Every problem raises :class:`planners.errors.SceneURDFError`
naming the file and the element.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from planners.errors import SceneURDFError

__all__ = ["Geometry", "LinkInfo", "JointInfo", "SceneDescription", "read_scene_urdf", "transform_from_xyz_rpy",
           "joint_motion"]


def transform_from_xyz_rpy(xyz, rpy) -> np.ndarray:
    """``(4, 4)`` transform of a URDF ``<origin xyz rpy>`` (fixed-axis roll, pitch, yaw: R = Rz Ry Rx)."""
    r, p, y = (float(v) for v in rpy)
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    T = np.eye(4)
    T[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                 [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                 [-sp, cp * sr, cp * cr]]
    T[:3, 3] = [float(v) for v in xyz]
    return T


def _rotation_about(axis: np.ndarray, angle: float) -> np.ndarray:
    """``(3, 3)`` rotation by ``angle`` (rad) about the unit ``axis`` (Rodrigues)."""
    k = np.asarray(axis, dtype=float)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


@dataclass(frozen=True)
class Geometry:
    """One ``<collision>`` element of a link.

    ``kind`` is ``box`` (``size`` = full extents), ``cylinder`` (``size`` = (radius, radius, length), along
    local z), ``sphere`` (``size`` = (r, r, r)) or ``mesh`` (``size`` = scale, ``mesh`` = resolved path).
    ``T_link_geom`` is ``(4, 4)``; ``index`` is the element's position among the link's collisions.
    """

    name: str
    kind: str
    size: tuple[float, float, float]
    T_link_geom: np.ndarray
    index: int
    mesh: str | None = None


@dataclass(frozen=True)
class LinkInfo:
    """A URDF link: its ``<collision>`` ``geometries`` (what planning checks) and its ``<visual>`` ones."""

    name: str
    geometries: tuple[Geometry, ...]
    visuals: tuple[Geometry, ...] = ()


@dataclass(frozen=True)
class JointInfo:
    """A URDF joint. ``axis`` is unit, in the joint frame; ``T_parent_joint`` is ``(4, 4)``."""

    name: str
    type: str
    parent: str
    child: str
    T_parent_joint: np.ndarray
    axis: np.ndarray
    lower: float
    upper: float

    @property
    def movable(self) -> bool:
        return self.type in ("prismatic", "revolute", "continuous")


@dataclass(frozen=True)
class SceneDescription:
    """The parsed scene: ``links`` and ``joints`` by name, ``root`` link, ``path`` of the file."""

    path: Path
    links: dict
    joints: dict
    root: str

    def parent_joint(self, link: str) -> JointInfo | None:
        """The joint whose child is ``link`` (``None`` for the root)."""
        for j in self.joints.values():
            if j.child == link:
                return j
        return None

    def child_joints(self, link: str) -> list[JointInfo]:
        """Joints whose parent is ``link``, in file order."""
        return [j for j in self.joints.values() if j.parent == link]

    def subtree_links(self, link: str) -> list[str]:
        """``link`` and every link below it."""
        out, stack = [], [link]
        while stack:
            cur = stack.pop()
            out.append(cur)
            stack.extend(j.child for j in self.child_joints(cur))
        return out

    def T_world_link(self, link: str, joint_values: dict | None = None) -> np.ndarray:
        """``(4, 4)`` pose of ``link`` in the root frame; unlisted movable joints are at 0."""
        values = joint_values or {}
        T = np.eye(4)
        cur = link
        while cur != self.root:
            j = self.parent_joint(cur)
            T = j.T_parent_joint @ joint_motion(j, float(values.get(j.name, 0.0))) @ T
            cur = j.parent
        return T


def joint_motion(joint: JointInfo, value: float) -> np.ndarray:
    """``(4, 4)`` transform of the joint's child frame in the joint frame at ``value`` (m or rad)."""
    M = np.eye(4)
    if joint.type == "prismatic":
        M[:3, 3] = joint.axis * value
    elif joint.type in ("revolute", "continuous"):
        M[:3, :3] = _rotation_about(joint.axis, value)
    return M


def _floats(text: str | None, n: int, default, where: str) -> tuple[float, ...]:
    if text is None:
        return tuple(default)
    try:
        vals = tuple(float(v) for v in text.split())
    except ValueError as e:
        raise SceneURDFError(f"{where}: cannot read numbers from {text!r}") from e
    if len(vals) != n or not all(math.isfinite(v) for v in vals):
        raise SceneURDFError(f"{where}: expected {n} finite numbers, got {text!r}")
    return vals


def _origin(el, where: str) -> np.ndarray:
    o = el.find("origin")
    if o is None:
        return np.eye(4)
    return transform_from_xyz_rpy(_floats(o.get("xyz"), 3, (0, 0, 0), where),
                                  _floats(o.get("rpy"), 3, (0, 0, 0), where))


def _geometry(col, link: str, index: int, base_dir: Path, where: str) -> Geometry | None:
    g = col.find("geometry")
    if g is None or len(g) == 0:
        raise SceneURDFError(f"{where}: link {link!r} collision #{index} has no <geometry>")
    shape = g[0]
    name = col.get("name") or f"{link}_{index}"
    T = _origin(col, f"{where}: link {link!r} collision #{index}")
    if shape.tag == "box":
        size = _floats(shape.get("size"), 3, None, f"{where}: link {link!r} box")
        if min(size) <= 0:
            raise SceneURDFError(f"{where}: link {link!r} box has a non-positive size {size}")
        return Geometry(name, "box", size, T, index)
    if shape.tag == "cylinder":
        r, = _floats(shape.get("radius"), 1, None, f"{where}: link {link!r} cylinder radius")
        ln, = _floats(shape.get("length"), 1, None, f"{where}: link {link!r} cylinder length")
        if r <= 0 or ln <= 0:
            raise SceneURDFError(f"{where}: link {link!r} cylinder has a non-positive radius/length")
        return Geometry(name, "cylinder", (r, r, ln), T, index)
    if shape.tag == "sphere":
        r, = _floats(shape.get("radius"), 1, None, f"{where}: link {link!r} sphere radius")
        if r <= 0:
            raise SceneURDFError(f"{where}: link {link!r} sphere has a non-positive radius")
        return Geometry(name, "sphere", (r, r, r), T, index)
    if shape.tag == "mesh":
        fn = shape.get("filename") or ""
        scale = _floats(shape.get("scale"), 3, (1, 1, 1), f"{where}: link {link!r} mesh scale")
        path = fn[len("file://"):] if fn.startswith("file://") else fn
        if not path.startswith("package://") and not Path(path).is_absolute():
            path = str(base_dir / path)
        if not path.startswith("package://") and not Path(path).is_file():
            raise SceneURDFError(f"{where}: link {link!r} mesh {fn!r} not found (looked at {path})")
        return Geometry(name, "mesh", scale, T, index, mesh=path)
    raise SceneURDFError(f"{where}: link {link!r} has an unknown geometry <{shape.tag}>")


def read_scene_urdf(path) -> SceneDescription:
    """Parse and check a scene URDF (one tree, known parents, finite numbers, limits on movable joints)."""
    path = Path(path)
    where = str(path)
    if not path.is_file():
        raise SceneURDFError(f"{where}: scene URDF not found")
    try:
        root_el = ET.parse(path).getroot()
    except ET.ParseError as e:
        raise SceneURDFError(f"{where}: not valid XML ({e})") from e
    if root_el.tag != "robot":
        raise SceneURDFError(f"{where}: root element is <{root_el.tag}>, expected <robot>")
    links: dict[str, LinkInfo] = {}
    for el in root_el.findall("link"):
        name = el.get("name")
        if not name:
            raise SceneURDFError(f"{where}: a <link> has no name")
        if name in links:
            raise SceneURDFError(f"{where}: link {name!r} is defined twice")
        geoms = tuple(_geometry(c, name, i, path.parent, where) for i, c in enumerate(el.findall("collision")))
        # visuals are validated too: a broken visual breaks every loader
        visuals = tuple(_geometry(v, name, i, path.parent, f"{where} (visual)") for i, v in enumerate(el.findall("visual")))
        links[name] = LinkInfo(name, geoms, visuals)
    joints: dict[str, JointInfo] = {}
    children: set[str] = set()
    for el in root_el.findall("joint"):
        name, typ = el.get("name"), el.get("type")
        if not name:
            raise SceneURDFError(f"{where}: a <joint> has no name")
        if name in joints:
            raise SceneURDFError(f"{where}: joint {name!r} is defined twice")
        if typ not in ("fixed", "prismatic", "revolute", "continuous", "floating", "planar"):
            raise SceneURDFError(f"{where}: joint {name!r} has unknown type {typ!r}")
        p, c = el.find("parent"), el.find("child")
        parent = p.get("link") if p is not None else None
        child = c.get("link") if c is not None else None
        for role, ln in (("parent", parent), ("child", child)):
            if ln not in links:
                raise SceneURDFError(f"{where}: joint {name!r} names {role} link {ln!r}, which does not exist")
        if child in children:
            raise SceneURDFError(f"{where}: link {child!r} is the child of two joints")
        children.add(child)
        ax = el.find("axis")
        axis = np.array(_floats(ax.get("xyz") if ax is not None else None, 3, (1, 0, 0),
                                f"{where}: joint {name!r} axis"))
        lower, upper = -math.inf, math.inf
        if typ in ("prismatic", "revolute"):
            n = float(np.linalg.norm(axis))
            if n < 1e-9:
                raise SceneURDFError(f"{where}: joint {name!r} has a zero axis")
            axis = axis / n
            lim = el.find("limit")
            if lim is None:
                raise SceneURDFError(f"{where}: {typ} joint {name!r} has no <limit>")
            lower, = _floats(lim.get("lower", "0"), 1, None, f"{where}: joint {name!r} lower limit")
            upper, = _floats(lim.get("upper", "0"), 1, None, f"{where}: joint {name!r} upper limit")
            if upper < lower:
                raise SceneURDFError(f"{where}: joint {name!r} has upper limit {upper} < lower {lower}")
        elif typ == "continuous":
            axis = axis / max(float(np.linalg.norm(axis)), 1e-12)
        joints[name] = JointInfo(name, typ, parent, child, _origin(el, f"{where}: joint {name!r}"), axis,
                                 float(lower), float(upper))
    roots = [ln for ln in links if ln not in children]
    if len(roots) != 1:
        raise SceneURDFError(f"{where}: expected one root link, found {roots}")
    scene = SceneDescription(path=path, links=links, joints=joints, root=roots[0])
    cut_off = set(links) - set(scene.subtree_links(roots[0]))
    if cut_off:
        raise SceneURDFError(f"{where}: links {sorted(cut_off)} are not below the root link {roots[0]!r} "
                             f"(their joints form a cycle)")
    return scene
