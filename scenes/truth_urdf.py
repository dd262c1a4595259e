"""Write a :class:`~scenes.model.Scene` as ``truth.urdf`` (the shape fixed in ``docs/contracts.md``).

Root link ``world``; each object's root part hangs from ``world`` by a fixed joint; every other part
hangs from its parent part; walls are fixed boxes on ``world``. Every link has an inertial (from
its shapes' volume and the part's density), a visual and a collision per shape with native
``box``/``cylinder`` geometry. Every joint has ``<limit>`` and ``<dynamics>``.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from .description import DEFAULT_RGBA, LABEL_RGBA, WORLD_LINK, write_text_atomic, xyz_rpy_from_T
from .inertia import part_mass_properties
from .model import ArticulatedObject, Scene, ShapeType

__all__ = ["urdf_from_scene", "write_truth_urdf", "WALL_DENSITY"]

WALL_DENSITY = 1500.0  # kg/m^3, plaster board/brick-ish; walls are fixed, the mass only keeps loaders quiet


def _f(x: float) -> str:
    return f"{float(x):.9g}"


def _vec(v) -> str:
    return " ".join(_f(x) for x in v)


def _origin(parent: ET.Element, T: np.ndarray) -> None:
    xyz, rpy = xyz_rpy_from_T(T)
    ET.SubElement(parent, "origin", xyz=_vec(xyz), rpy=_vec(rpy))


def _geometry(parent: ET.Element, stype: ShapeType, size: np.ndarray) -> None:
    g = ET.SubElement(parent, "geometry")
    if stype is ShapeType.BOX:
        ET.SubElement(g, "box", size=_vec(size))
    else:
        ET.SubElement(g, "cylinder", radius=_f(size[0] / 2), length=_f(size[2]))


def _inertial(link: ET.Element, mass: float, com: np.ndarray, inertia: np.ndarray) -> None:
    el = ET.SubElement(link, "inertial")
    ET.SubElement(el, "origin", xyz=_vec(com), rpy="0 0 0")
    ET.SubElement(el, "mass", value=_f(mass))
    ET.SubElement(el, "inertia", ixx=_f(inertia[0, 0]), ixy=_f(inertia[0, 1]), ixz=_f(inertia[0, 2]),
                  iyy=_f(inertia[1, 1]), iyz=_f(inertia[1, 2]), izz=_f(inertia[2, 2]))


def _shape_elements(link: ET.Element, name: str, label: str, shapes) -> None:
    for k, s in enumerate(shapes):
        vis = ET.SubElement(link, "visual", name=f"{name}_v{k}")
        _origin(vis, s.T_part_shape)
        _geometry(vis, s.type, s.size)
        mat = ET.SubElement(vis, "material", name=f"mat_{label}")
        ET.SubElement(mat, "color", rgba=_vec(LABEL_RGBA.get(label, DEFAULT_RGBA)))
        col = ET.SubElement(link, "collision", name=f"{name}_c{k}")
        _origin(col, s.T_part_shape)
        _geometry(col, s.type, s.size)


def _joint(robot: ET.Element, name: str, jtype: str, parent: str, child: str, T_parent_child: np.ndarray,
           axis=None, lower=0.0, upper=0.0, effort=0.0, velocity=0.0, damping=0.0, friction=0.0) -> None:
    j = ET.SubElement(robot, "joint", name=name, type=jtype)
    ET.SubElement(j, "parent", link=parent)
    ET.SubElement(j, "child", link=child)
    _origin(j, T_parent_child)
    if jtype != "fixed":
        ET.SubElement(j, "axis", xyz=_vec(axis))
        ET.SubElement(j, "limit", effort=_f(effort), velocity=_f(velocity), lower=_f(lower), upper=_f(upper))
    ET.SubElement(j, "dynamics", damping=_f(damping), friction=_f(friction))


def _add_object(robot: ET.Element, obj: ArticulatedObject) -> None:
    for part in obj.parts:
        link = ET.SubElement(robot, "link", name=obj.link(part))
        m, com, inertia = part_mass_properties(part)
        _inertial(link, m, com, inertia)
        _shape_elements(link, obj.link(part), part.label, part.shapes)
    for j in obj.joints:
        child = obj.part(j.child)
        name = obj.joint_name(j)
        if j.parent is None:
            _joint(robot, name, "fixed", WORLD_LINK, obj.link(child), obj.T_world_object @ child.T_object_part)
            continue
        parent = obj.part(j.parent)
        T_parent_child = np.linalg.inv(parent.T_object_part) @ child.T_object_part
        axis_child = child.T_object_part[:3, :3].T @ j.axis
        _joint(robot, name, j.type.value, obj.link(parent), obj.link(child), T_parent_child,
               axis=axis_child / np.linalg.norm(axis_child), lower=j.lower, upper=j.upper,
               effort=j.effort, velocity=j.velocity, damping=j.damping, friction=j.friction)


def urdf_from_scene(scene: Scene) -> str:
    """The URDF text of ``scene`` (closed state = every joint at 0)."""
    robot = ET.Element("robot", name=f"partscene_{scene.name}")
    world = ET.SubElement(robot, "link", name=WORLD_LINK)
    _inertial(world, 0.0, np.zeros(3), np.zeros((3, 3)))
    for wall in scene.walls:
        link = ET.SubElement(robot, "link", name=wall.name)
        m = float(np.prod(wall.size) * WALL_DENSITY)
        a, b, c = wall.size
        _inertial(link, m, np.zeros(3), m / 12 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b]))
        _shape_elements(link, wall.name, "wall", [_WallShape(wall.size)])
        _joint(robot, f"{wall.name}_joint", "fixed", WORLD_LINK, wall.name, wall.T_world_wall)
    for obj in scene.objects:
        _add_object(robot, obj)
    ET.indent(robot, space="  ")
    return '<?xml version="1.0"?>\n' + ET.tostring(robot, encoding="unicode") + "\n"


class _WallShape:
    """A wall's single box, centred on the wall link frame."""

    type = ShapeType.BOX
    T_part_shape = np.eye(4)

    def __init__(self, size):
        self.size = np.asarray(size, float)


def write_truth_urdf(scene: Scene, path: str | Path) -> Path:
    """Write ``truth.urdf`` atomically; returns the path."""
    return write_text_atomic(path, urdf_from_scene(scene))
