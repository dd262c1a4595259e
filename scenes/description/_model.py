"""The scene model: links (inertial, visuals, collisions) and joints (type, axis, limits, dynamics) of one
URDF tree, with forward kinematics. Frozen; editing returns a new model.

Frames: ``T_parent_joint`` (4, 4) is the joint frame in the parent link frame (the URDF ``<origin>``);
the child link frame is the joint frame moved by the joint value (``joint_motion``); ``axis`` (3,) is unit,
in the joint frame. Values are metres (prismatic) or radians (revolute, continuous).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path
from typing import Mapping

import numpy as np

from ._errors import DescriptionError
from ._poses import R_about
from ._shape import Material, Shape

__all__ = ["JointType", "Limit", "Dynamics", "Inertial", "Link", "Joint", "SceneModel", "joint_motion"]


class JointType(StrEnum):
    """A joint's type; the value (also its ``str``) is the URDF ``type`` attribute."""

    FIXED = "fixed"
    PRISMATIC = "prismatic"
    REVOLUTE = "revolute"
    CONTINUOUS = "continuous"


@dataclass(frozen=True)
class Limit:
    """``lower``/``upper`` m or rad; ``effort`` N or N m; ``velocity`` m/s or rad/s."""

    lower: float = 0.0
    upper: float = 0.0
    effort: float = 0.0
    velocity: float = 0.0


@dataclass(frozen=True)
class Dynamics:
    """``damping`` N s/m or N m s/rad; ``friction`` (Coulomb) N or N m."""

    damping: float = 0.0
    friction: float = 0.0


@dataclass(frozen=True, eq=False)
class Inertial:
    """``mass`` kg; ``T_link_com`` (4, 4) pose of the inertia frame in the link; ``inertia`` (3, 3) kg m^2
    about the centre of mass in that frame's axes."""

    mass: float
    T_link_com: np.ndarray = field(default_factory=lambda: np.eye(4))
    inertia: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))

    def isclose(self, other: "Inertial", atol: float = 1e-9) -> bool:
        return (abs(self.mass - other.mass) <= atol and np.allclose(self.T_link_com, other.T_link_com, atol=atol)
                and np.allclose(self.inertia, other.inertia, atol=atol))


@dataclass(frozen=True, eq=False)
class Link:
    """A link: optional ``inertial``, its ``visuals`` and ``collisions`` (shapes in the link frame), and
    ``lateral_friction``: PyBullet's ``<contact><lateral_friction value>`` sliding friction coefficient of
    its surfaces (``None``: the engine's default)."""

    name: str
    inertial: Inertial | None = None
    visuals: tuple[Shape, ...] = ()
    collisions: tuple[Shape, ...] = ()
    lateral_friction: float | None = None

    def isclose(self, other: "Link", atol: float = 1e-9) -> bool:
        same_inertial = (self.inertial is None) == (other.inertial is None) and (
            self.inertial is None or self.inertial.isclose(other.inertial, atol))
        return (self.name == other.name and same_inertial and self.lateral_friction == other.lateral_friction
                and len(self.visuals) == len(other.visuals) and len(self.collisions) == len(other.collisions)
                and all(a.isclose(b, atol) and a.material == b.material for a, b in zip(self.visuals, other.visuals))
                and all(a.isclose(b, atol) for a, b in zip(self.collisions, other.collisions)))


@dataclass(frozen=True, eq=False)
class Joint:
    """A joint from link ``parent`` to link ``child`` (see the module docstring for frames and units)."""

    name: str
    type: JointType
    parent: str
    child: str
    T_parent_joint: np.ndarray = field(default_factory=lambda: np.eye(4))
    axis: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0]))
    limit: Limit | None = None
    dynamics: Dynamics | None = None

    def __post_init__(self):
        object.__setattr__(self, "type", JointType(self.type))
        object.__setattr__(self, "T_parent_joint", np.array(self.T_parent_joint, dtype=np.float64))
        object.__setattr__(self, "axis", np.array(self.axis, dtype=np.float64))

    @property
    def movable(self) -> bool:
        return self.type is not JointType.FIXED

    @property
    def lower(self) -> float:
        """Lower limit (m or rad); ``-inf`` for a continuous joint, 0 for a fixed one."""
        if self.type is JointType.CONTINUOUS:
            return -np.inf
        return float(self.limit.lower) if self.limit is not None and self.movable else 0.0

    @property
    def upper(self) -> float:
        """Upper limit (m or rad); ``inf`` for a continuous joint, 0 for a fixed one."""
        if self.type is JointType.CONTINUOUS:
            return np.inf
        return float(self.limit.upper) if self.limit is not None and self.movable else 0.0

    def motion(self, value: float) -> np.ndarray:
        """(4, 4) pose of the child link frame in the joint frame at ``value`` (m or rad)."""
        return joint_motion(self, value)

    def isclose(self, other: "Joint", atol: float = 1e-9) -> bool:
        return ((self.name, self.type, self.parent, self.child, self.limit is None, self.dynamics is None)
                == (other.name, other.type, other.parent, other.child, other.limit is None, other.dynamics is None)
                and np.allclose(self.T_parent_joint, other.T_parent_joint, atol=atol)
                and (not self.movable or np.allclose(self.axis, other.axis, atol=atol))
                and (self.limit is None or np.allclose(dataclasses.astuple(self.limit),
                                                       dataclasses.astuple(other.limit), atol=atol))
                and (self.dynamics is None or np.allclose(dataclasses.astuple(self.dynamics),
                                                          dataclasses.astuple(other.dynamics), atol=atol)))


def joint_motion(joint: Joint, value: float) -> np.ndarray:
    """(4, 4) pose of ``joint``'s child frame in its joint frame at ``value`` (m or rad)."""
    M = np.eye(4)
    if joint.type is JointType.PRISMATIC:
        M[:3, 3] = joint.axis * value
    elif joint.type in (JointType.REVOLUTE, JointType.CONTINUOUS) and value != 0.0:
        M[:3, :3] = R_about(joint.axis, value)
    return M


@dataclass(frozen=True, eq=False)
class SceneModel:
    """One URDF tree: ``links`` and ``joints`` by name (file order), its ``root`` link, top-level
    ``materials``, and the ``path`` it was read from (``None`` if built in memory).

    Built with a check that the joints form one tree over the links (every named link exists, no link is
    the child of two joints, no cycle, none cut off from the root); a failure raises
    :class:`DescriptionError` naming the joint or link.
    """

    name: str
    links: Mapping[str, Link]
    joints: Mapping[str, Joint]
    materials: tuple[Material, ...] = ()
    path: Path | None = None
    root: str = field(init=False)

    def __post_init__(self):
        links = _by_name(self.links, "link", self.path)
        joints = _by_name(self.joints, "joint", self.path)
        object.__setattr__(self, "links", links)
        object.__setattr__(self, "joints", joints)
        object.__setattr__(self, "materials", tuple(self.materials))
        object.__setattr__(self, "root", _check_tree(links, joints, _where(self.path)))
        object.__setattr__(self, "_parent_of", {j.child: j for j in joints.values()})

    # ----- tree
    def parent_joint(self, link: str) -> Joint | None:
        """The joint whose child is ``link`` (``None`` for the root)."""
        return self._parent_of.get(link)

    def child_joints(self, link: str) -> list[Joint]:
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

    def ancestors(self, link: str) -> list[str]:
        """``link`` and the links above it, up to the root."""
        out = [link]
        while (j := self._parent_of.get(out[-1])) is not None:
            out.append(j.parent)
        return out

    def is_moving(self, link: str) -> bool:
        """True when a movable joint lies between ``link`` and the root."""
        return any(self._parent_of[ln].movable for ln in self.ancestors(link)[:-1])

    # ----- kinematics
    def T_world_link(self, link: str, q: Mapping[str, float] | None = None) -> np.ndarray:
        """(4, 4) pose of ``link`` in the root ("world") frame with joint values ``q`` {joint name: value};
        unlisted joints are at 0."""
        values = q or {}
        T = np.eye(4)
        cur = link
        while (j := self._parent_of.get(cur)) is not None:
            v = float(values.get(j.name, 0.0))
            T = (j.T_parent_joint @ joint_motion(j, v) @ T) if j.movable else (j.T_parent_joint @ T)
            cur = j.parent
        if cur != self.root:
            raise KeyError(f"{_where(self.path)}: no link {link!r}")
        return T

    # ----- edits (new models)
    def replaced(self, *items: Link | Joint) -> "SceneModel":
        """A copy with each link/joint of ``items`` put in place of the one of the same name (or added)."""
        links, joints = dict(self.links), dict(self.joints)
        for it in items:
            (links if isinstance(it, Link) else joints)[it.name] = it
        return SceneModel(self.name, links, joints, self.materials, self.path)

    def isclose(self, other: "SceneModel", atol: float = 1e-9) -> bool:
        """Same links and joints (names, order-independent) within ``atol``."""
        return (set(self.links) == set(other.links) and set(self.joints) == set(other.joints)
                and all(l.isclose(other.links[n], atol) for n, l in self.links.items())
                and all(j.isclose(other.joints[n], atol) for n, j in self.joints.items()))


def _where(path) -> str:
    return str(path) if path is not None else "scene model"


def _by_name(items, what: str, path) -> dict:
    if isinstance(items, Mapping):
        items = items.values()
    out: dict = {}
    for it in items:
        if not it.name:
            raise DescriptionError(f"{_where(path)}: a {what} has no name")
        if it.name in out:
            raise DescriptionError(f"{_where(path)}: {what} {it.name!r} is defined twice")
        out[it.name] = it
    return out


def _check_tree(links: dict, joints: dict, where: str) -> str:
    """The root link name; raises naming the joint/link when the joints do not form one tree."""
    children: set[str] = set()
    for j in joints.values():
        for role, ln in (("parent", j.parent), ("child", j.child)):
            if ln not in links:
                raise DescriptionError(f"{where}: joint {j.name!r} names {role} link {ln!r}, which does not exist")
        if j.child in children:
            raise DescriptionError(f"{where}: link {j.child!r} is the child of two joints")
        children.add(j.child)
    roots = [ln for ln in links if ln not in children]
    if len(roots) != 1:
        raise DescriptionError(f"{where}: expected one root link, found {roots}")
    reached, stack = set(), [roots[0]]
    below: dict[str, list[str]] = {}
    for j in joints.values():
        below.setdefault(j.parent, []).append(j.child)
    while stack:
        cur = stack.pop()
        reached.add(cur)
        stack.extend(below.get(cur, ()))
    cut_off = [ln for ln in links if ln not in reached]
    if cut_off:
        raise DescriptionError(f"{where}: links {sorted(cut_off)} are not below the root link {roots[0]!r} "
                               f"(their joints form a cycle)")
    return roots[0]

