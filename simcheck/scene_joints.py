"""Joints of a scene URDF (read by :func:`planners.scene_urdf.read_scene_urdf`, no simulator): type, limits,
and the axis and origin in the world frame at the closed (all-zero) state. Used to validate tasks, compute
default amounts and to say how an estimate differs from its reference.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from planners.scene_urdf import read_scene_urdf
from scenes.description import JointType, SceneModel
from planners.errors import SceneURDFError
from simcheck.errors import SceneLoadError

__all__ = ["SceneJoint", "read_scene_joints", "read_scene_joints_and_links", "scene_link_names"]


@dataclass(frozen=True)
class SceneJoint:
    """One URDF joint: its :class:`~scenes.description.JointType` (a URDF type string is converted), limits
    (m or rad), ``axis_world`` (3,) unit and ``origin_world`` (3,) metres at the all-zero state."""

    name: str
    type: JointType
    parent: str
    child: str
    lower: float
    upper: float
    axis_world: np.ndarray
    origin_world: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "type", JointType(self.type))

    @property
    def movable(self) -> bool:
        """True for a prismatic, revolute or continuous joint."""
        return self.type is not JointType.FIXED

    @property
    def unit(self) -> str:
        """The unit of its position: "m" (prismatic) or "rad"."""
        return "m" if self.type is JointType.PRISMATIC else "rad"


def _read(path: str | Path) -> SceneModel:
    if not Path(path).is_file():
        what = "is a folder, not a URDF file" if Path(path).is_dir() else "does not exist"
        raise SceneLoadError(f"scene URDF {path} {what}")
    try:
        return read_scene_urdf(path)
    except SceneURDFError as exc:
        raise SceneLoadError(str(exc)) from exc


def scene_link_names(path: str | Path) -> tuple[str, ...]:
    """Names of every ``<link>`` of the URDF at ``path``."""
    return tuple(_read(path).links)


def read_scene_joints(path: str | Path) -> dict[str, SceneJoint]:
    """Every joint of the scene URDF at ``path``, by name, with its axis and origin in the world frame.

    Raises:
        SceneLoadError: missing file, invalid XML, a joint without parent/child/name, a link with two
            parents, or no single root (names the file and the joint).
    """
    return read_scene_joints_and_links(path)[0]


def read_scene_joints_and_links(path: str | Path) -> tuple[dict[str, SceneJoint], tuple[str, ...]]:
    """(:func:`read_scene_joints`, :func:`scene_link_names`) of the scene URDF at ``path``, read once."""
    scene = _read(path)
    out = {}
    for name, j in scene.joints.items():
        T_world_joint = scene.T_world_link(j.parent) @ j.T_parent_joint
        out[name] = SceneJoint(name, j.type, j.parent, j.child,
                               j.lower if np.isfinite(j.lower) else 0.0, j.upper if np.isfinite(j.upper) else 0.0,
                               T_world_joint[:3, :3] @ j.axis, T_world_joint[:3, 3].copy())
    return out, tuple(scene.links)


def axis_angle_deg(a: np.ndarray, b: np.ndarray) -> float:
    """Angle between two unit axes, degrees (direction matters: 180 = opposite)."""
    return math.degrees(math.acos(float(np.clip(np.dot(a, b), -1.0, 1.0))))
