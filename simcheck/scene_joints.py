"""Movable joints of a scene URDF read with the standard library (no simulator): type, limits, and the
axis and origin in the world frame at the closed (all-zero) state. Used to validate tasks, compute
default amounts and to say how an estimate differs from its reference.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from simcheck.errors import SceneLoadError

__all__ = ["SceneJoint", "read_scene_joints", "scene_link_names"]


@dataclass(frozen=True)
class SceneJoint:
    """One URDF joint. ``axis_world`` (3,) unit and ``origin_world`` (3,) metres at the all-zero state."""

    name: str
    type: str
    parent: str
    child: str
    lower: float
    upper: float
    axis_world: np.ndarray
    origin_world: np.ndarray

    @property
    def movable(self) -> bool:
        return self.type in ("prismatic", "revolute", "continuous")

    @property
    def unit(self) -> str:
        return "m" if self.type == "prismatic" else "rad"


def _floats(text: str | None, n: int, default: float, where: str) -> np.ndarray:
    if text is None:
        return np.full(n, default)
    try:
        v = np.array([float(t) for t in text.split()])
    except ValueError:
        raise SceneLoadError(f"{where}: not numbers: {text!r}") from None
    if v.shape != (n,):
        raise SceneLoadError(f"{where}: expected {n} numbers, got {text!r}")
    return v


def _parse(path: Path) -> ET.Element:
    if not path.is_file():
        raise SceneLoadError(f"scene URDF {path} does not exist")
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        raise SceneLoadError(f"scene URDF {path} is not valid XML: {exc}") from exc
    if root.tag != "robot":
        raise SceneLoadError(f"scene URDF {path}: root element is <{root.tag}>, expected <robot>")
    return root


def scene_link_names(path: str | Path) -> tuple[str, ...]:
    """Names of every ``<link>`` of the URDF at ``path``."""
    return tuple(l.get("name") for l in _parse(Path(path)).findall("link"))


def read_scene_joints(path: str | Path) -> dict[str, SceneJoint]:
    """Every joint of the scene URDF at ``path``, by name.

    Raises:
        SceneLoadError: missing file, invalid XML, a joint without parent/child/name, a link with two
            parents, or a kinematic loop (names the file and the joint).
    """
    path = Path(path)
    root = _parse(path)
    raw = {}
    child_of = {}
    for j in root.findall("joint"):
        name = j.get("name")
        parent, child = j.find("parent"), j.find("child")
        if not name or parent is None or child is None or not parent.get("link") or not child.get("link"):
            raise SceneLoadError(f"scene URDF {path}: joint {name!r} lacks a name, parent link or child link")
        where = f"scene URDF {path}, joint {name!r}"
        o = j.find("origin")
        xyz = _floats(o.get("xyz") if o is not None else None, 3, 0.0, where + " origin xyz")
        rpy = _floats(o.get("rpy") if o is not None else None, 3, 0.0, where + " origin rpy")
        a = j.find("axis")
        axis = _floats(a.get("xyz") if a is not None else None, 3, 0.0, where + " axis") if a is not None else np.array([1.0, 0, 0])
        lim = j.find("limit")
        lower = float(lim.get("lower", 0.0)) if lim is not None else 0.0
        upper = float(lim.get("upper", 0.0)) if lim is not None else 0.0
        jtype = j.get("type", "")
        if jtype in ("prismatic", "revolute") and not np.linalg.norm(axis) > 0:
            raise SceneLoadError(f"{where}: zero axis")
        if child.get("link") in child_of:
            raise SceneLoadError(f"scene URDF {path}: link {child.get('link')!r} has two parent joints "
                                 f"({child_of[child.get('link')]!r} and {name!r})")
        child_of[child.get("link")] = name
        T = np.eye(4)
        T[:3, :3] = Rotation.from_euler("xyz", rpy).as_matrix()
        T[:3, 3] = xyz
        raw[name] = (jtype, parent.get("link"), child.get("link"), lower, upper, axis / max(np.linalg.norm(axis), 1e-12), T)
    cache: dict[str, np.ndarray] = {}

    def T_world(link: str, depth: int = 0) -> np.ndarray:
        if link in cache:
            return cache[link]
        if depth > len(raw) + 1:
            raise SceneLoadError(f"scene URDF {path}: kinematic loop through link {link!r}")
        jn = child_of.get(link)
        T = np.eye(4) if jn is None else T_world(raw[jn][1], depth + 1) @ raw[jn][6]
        cache[link] = T
        return T

    out = {}
    for name, (jtype, parent, child, lower, upper, axis, T_parent_joint) in raw.items():
        T = T_world(parent) @ T_parent_joint
        out[name] = SceneJoint(name, jtype, parent, child, lower, upper, T[:3, :3] @ axis, T[:3, 3].copy())
    return out


def axis_angle_deg(a: np.ndarray, b: np.ndarray) -> float:
    """Angle between two unit axes, degrees (direction matters: 180 = opposite)."""
    return math.degrees(math.acos(float(np.clip(np.dot(a, b), -1.0, 1.0))))
