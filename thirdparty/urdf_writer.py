"""URDF text of a corpus object, written the way other people's exporters write it (not with
:mod:`scenes.description`): plain XML strings, ``rpy`` origins on joints, a root link that is not ``world``,
optional missing ``<inertial>`` elements, mesh files referenced by relative paths.

Geometry comes in as closed-state poses in the object frame; the writer re-expresses each shape in the
frame of the link that carries it (the joint frame of its front), so a joint frame rotated or placed
away from the panel moves nothing in the world.
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy.spatial.transform import Rotation

__all__ = ["Geom", "LinkOut", "JointOut", "robot_xml", "rpy_xyz", "mass_com", "DENSITY"]

#: density of every corpus part, kg/m^3 (wood-based board)
DENSITY = 500.0


def _f(x: float) -> str:
    return f"{float(x):.6g}"


def rpy_xyz(T: np.ndarray) -> str:
    """``xyz=... rpy=...`` attributes of a (4, 4) pose (URDF fixed-axis roll, pitch, yaw)."""
    with warnings.catch_warnings():          # gimbal lock (pitch +-90 deg) still gives a valid rpy
        warnings.simplefilter("ignore", UserWarning)
        rpy = Rotation.from_matrix(T[:3, :3]).as_euler("xyz")
    rpy = np.where(np.abs(rpy) < 1e-12, 0.0, rpy)
    return f'xyz="{" ".join(map(_f, T[:3, 3]))}" rpy="{" ".join(map(_f, rpy))}"'


class Geom:
    """A shape at ``T`` (4, 4), in the frame of the link that carries it once written. ``kind`` "box" (size
    (3,) m), "cylinder" (radius, length; axis local z), "sphere" (radius) or "mesh" (relative file name)."""

    def __init__(self, kind: str, T: np.ndarray, size=None, mesh: str | None = None, name: str | None = None,
                 solid=None):
        self.kind, self.T, self.size, self.mesh, self.name = kind, np.asarray(T, float), size, mesh, name
        self.solid = solid          # a mesh's (centre (3,) in its frame, volume m^3), for the inertial

    def moved(self, T_new_old: np.ndarray) -> "Geom":
        return Geom(self.kind, T_new_old @ self.T, self.size, self.mesh, self.name, self.solid)

    def xml(self, tag: str) -> str:
        s = self.size
        if self.kind == "box":
            g = f'<box size="{" ".join(map(_f, s))}"/>'
        elif self.kind == "cylinder":
            g = f'<cylinder radius="{_f(s[0])}" length="{_f(s[1])}"/>'
        elif self.kind == "sphere":
            g = f'<sphere radius="{_f(s[0])}"/>'
        else:
            g = f'<mesh filename="{self.mesh}"/>'
        name = f' name="{self.name}"' if self.name and tag == "collision" else ""
        return f'    <{tag}{name}><origin {rpy_xyz(self.T)}/><geometry>{g}</geometry></{tag}>\n'

    def volume_box(self) -> tuple[np.ndarray, float]:
        """(centre (3,), volume m^3) of the shape, a mesh counted as ``solid`` or a 2 cm cube at its origin (for
        inertials only)."""
        s = self.size
        if self.kind == "mesh" and self.solid is not None:
            return (self.T @ np.append(self.solid[0], 1.0))[:3], float(self.solid[1])
        vol = {"box": lambda: float(np.prod(s)), "cylinder": lambda: float(np.pi * s[0] ** 2 * s[1]),
               "sphere": lambda: float(4 / 3 * np.pi * s[0] ** 3)}.get(self.kind, lambda: 8e-6)()
        return self.T[:3, 3], vol


def mass_com(geoms: list[Geom]) -> tuple[float, np.ndarray]:
    """(mass kg, centre of mass (3,) in the geometries' frame) of a link made of ``geoms`` at :data:`DENSITY`
    (at least 0.2 kg)."""
    cs, vs = zip(*(g.volume_box() for g in geoms))
    vs = np.asarray(vs)
    return max(0.2, DENSITY * float(vs.sum())), (np.asarray(cs) * vs[:, None]).sum(0) / vs.sum()


class LinkOut:
    """A link: its geometries (link frame) and whether to write an ``<inertial>`` (density :data:`DENSITY`)."""

    def __init__(self, name: str, geoms: list[Geom], inertial: bool = True):
        self.name, self.geoms, self.inertial = name, geoms, inertial

    def xml(self) -> str:
        out = f'  <link name="{self.name}">\n'
        if self.inertial and self.geoms:
            cs = [g.volume_box()[0] for g in self.geoms]
            mass, com = mass_com(self.geoms)
            spread = np.ptp(np.asarray(cs), axis=0) + 0.1
            inertia = mass / 12.0 * (np.sum(spread ** 2) - spread ** 2)
            out += (f'    <inertial><origin xyz="{" ".join(map(_f, com))}" rpy="0 0 0"/><mass value="{_f(mass)}"/>'
                    f'<inertia ixx="{_f(inertia[0])}" ixy="0" ixz="0" iyy="{_f(inertia[1])}" iyz="0" '
                    f'izz="{_f(inertia[2])}"/></inertial>\n')
        for g in self.geoms:
            out += g.xml("visual") + g.xml("collision")
        return out + "  </link>\n"


class JointOut:
    """A joint with its origin ``T_parent_joint`` (4, 4), axis (3,) in the joint frame and limits."""

    def __init__(self, name: str, type_: str, parent: str, child: str, T_parent_joint: np.ndarray,
                 axis=(0.0, 0.0, 1.0), lower: float = 0.0, upper: float = 0.0, damping: float = 0.5,
                 friction: float = 0.1):
        self.name, self.type, self.parent, self.child = name, type_, parent, child
        self.T, self.axis, self.lower, self.upper = np.asarray(T_parent_joint, float), np.asarray(axis, float), lower, upper
        self.damping, self.friction = damping, friction

    def xml(self) -> str:
        out = (f'  <joint name="{self.name}" type="{self.type}">\n    <parent link="{self.parent}"/>'
               f'<child link="{self.child}"/>\n    <origin {rpy_xyz(self.T)}/>\n')
        if self.type != "fixed":
            axis = np.where(np.abs(self.axis) < 1e-12, 0.0, self.axis)
            out += f'    <axis xyz="{" ".join(map(_f, axis))}"/>\n'
            if self.type != "continuous":
                out += (f'    <limit lower="{_f(self.lower)}" upper="{_f(self.upper)}" effort="100" '
                        f'velocity="1"/>\n')
            out += f'    <dynamics damping="{_f(self.damping)}" friction="{_f(self.friction)}"/>\n'
        return out + "  </joint>\n"


def robot_xml(name: str, links: list[LinkOut], joints: list[JointOut]) -> str:
    """The whole URDF document."""
    body = "".join(link.xml() for link in links) + "".join(j.xml() for j in joints)
    return f'<?xml version="1.0"?>\n<robot name="{name}">\n{body}</robot>\n'
