"""Ground-truth artifacts: shapes, parts, joints, articulated objects, walls and scenes.

All are frozen dataclasses; arrays are float64. Frames (see ``docs/contracts.md``):

* object frame: origin on the floor (or the supporting surface) at the footprint centre, x = the
  outward front normal, z up;
* part frame ``T_object_part``: pose of a part in its object frame at joint value 0 (closed); for a
  movable part the frame origin lies on the joint axis (on the hinge line for a door);
* shape frame ``Shape.T_link_shape`` (:class:`scenes.description.Shape`; the link is the part): a box is
  centred on its frame, a cylinder is centred with its axis along local z.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from .description import JointType, Shape, T_about, joint_name, link_name, object_name

__all__ = ["JointType", "Part", "Joint", "ArticulatedObject", "Wall", "Scene"]


@dataclass(frozen=True, eq=False)
class Part:
    """A rigid part: semantic ``label`` (DESIGN vocabulary), shapes, closed pose ``T_object_part`` (4, 4)."""

    id: int
    label: str
    T_object_part: np.ndarray
    shapes: tuple[Shape, ...]
    density: float  # kg/m^3, used for the URDF inertial

    def isclose(self, other: "Part", atol: float = 1e-9) -> bool:
        return (self.id == other.id and self.label == other.label
                and np.allclose(self.T_object_part, other.T_object_part, atol=atol)
                and len(self.shapes) == len(other.shapes)
                and all(a.isclose(b, atol) for a, b in zip(self.shapes, other.shapes)))


@dataclass(frozen=True, eq=False)
class Joint:
    """The joint whose child is part ``child``; axis and origin are in the OBJECT frame.

    ``axis`` (3,) unit, positive value opens; ``origin`` (3,) a point on the axis (hinge line for a
    door), metres. ``lower``/``upper`` metres (prismatic) or radians (revolute); 0 = closed.
    ``effort`` N or N m, ``velocity`` m/s or rad/s, ``damping`` N s/m or N m s/rad, ``friction`` N or N m.
    """

    type: JointType
    parent: int | None  # parent part id; None = the world (object root)
    child: int
    axis: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0]))
    origin: np.ndarray = field(default_factory=lambda: np.zeros(3))
    lower: float = 0.0
    upper: float = 0.0
    handle: int | None = None
    effort: float = 100.0
    velocity: float = 1.0
    damping: float = 0.0
    friction: float = 0.0

    @property
    def movable(self) -> bool:
        return self.type is not JointType.FIXED

    def isclose(self, other: "Joint", atol: float = 1e-9) -> bool:
        return ((self.type, self.parent, self.child, self.handle) == (other.type, other.parent, other.child, other.handle)
                and np.allclose(self.axis, other.axis, atol=atol) and np.allclose(self.origin, other.origin, atol=atol)
                and np.allclose([self.lower, self.upper, self.effort, self.velocity, self.damping, self.friction],
                                [other.lower, other.upper, other.effort, other.velocity, other.damping,
                                 other.friction], atol=atol))


@dataclass(frozen=True, eq=False)
class ArticulatedObject:
    """An object: parts (the first is the root), the part tree as joints, and true contact edges.

    ``T_world_object`` (4, 4); ``size`` (3,) axis-aligned extent of the closed object in its frame;
    ``contacts``: undirected part-id pairs (a < b).
    """

    id: int
    category: str
    parts: tuple[Part, ...]
    joints: tuple[Joint, ...]
    contacts: tuple[tuple[int, int], ...]
    T_world_object: np.ndarray = field(default_factory=lambda: np.eye(4))
    supported_by: int | None = None

    # ------------------------------------------------------------------ lookup
    @property
    def name(self) -> str:
        return object_name(self.category, self.id)

    @property
    def root(self) -> Part:
        return self.parts[0]

    def part(self, part_id: int) -> Part:
        for p in self.parts:
            if p.id == part_id:
                return p
        raise KeyError(f"{self.name}: no part {part_id}")

    def joint_of(self, part_id: int) -> Joint:
        for j in self.joints:
            if j.child == part_id:
                return j
        raise KeyError(f"{self.name}: no joint with child part {part_id}")

    def link(self, part: Part) -> str:
        return link_name(self.category, self.id, part.label, part.id)

    def joint_name(self, joint: Joint) -> str:
        child = self.part(joint.child)
        return joint_name(self.category, self.id, child.label, child.id)

    # ------------------------------------------------------------------ geometry
    def bounds(self) -> np.ndarray:
        """(2, 3) min/max of all shapes in the object frame, closed state."""
        pts = np.vstack([s.corners() @ p.T_object_part[:3, :3].T + p.T_object_part[:3, 3]
                         for p in self.parts for s in p.shapes])
        return np.array([pts.min(0), pts.max(0)])

    @property
    def size(self) -> np.ndarray:
        b = self.bounds()
        return b[1] - b[0]

    def T_object_part_at(self, part_id: int, q: dict[int, float] | None = None) -> np.ndarray:
        """(4, 4) pose of ``part_id`` in the object frame with joint values ``q`` {child part id: value}."""
        q = q or {}
        j = self.joint_of(part_id)
        if j.parent is None:
            return self.part(part_id).T_object_part.copy()
        T_parent = self.T_object_part_at(j.parent, q)
        T_closed_parent = self.part(j.parent).T_object_part
        T_obj_child = self.part(part_id).T_object_part
        # motion of this joint, about/along its object-frame axis (axis fixed to the parent)
        M = _joint_motion(j, q.get(part_id, 0.0))
        return T_parent @ np.linalg.inv(T_closed_parent) @ M @ T_obj_child

    def isclose(self, other: "ArticulatedObject", atol: float = 1e-9) -> bool:
        """Same ids, category, support, pose, parts, joints (frames and limits) and contacts."""
        if (self.id, self.category, self.supported_by, self.contacts) != \
                (other.id, other.category, other.supported_by, tuple(tuple(c) for c in other.contacts)):
            return False
        if len(self.parts) != len(other.parts) or len(self.joints) != len(other.joints):
            return False
        return (np.allclose(self.T_world_object, other.T_world_object, atol=atol)
                and all(a.isclose(b, atol) for a, b in zip(self.parts, other.parts))
                and all(a.isclose(b, atol) for a, b in zip(self.joints, other.joints)))

    # ------------------------------------------------------------------ copies
    def renumbered(self, object_id: int, first_part_id: int) -> "ArticulatedObject":
        """A copy with object id ``object_id`` and parts numbered from ``first_part_id`` in order."""
        m = {p.id: first_part_id + i for i, p in enumerate(self.parts)}
        parts = tuple(dataclasses.replace(p, id=m[p.id]) for p in self.parts)
        joints = tuple(dataclasses.replace(j, parent=None if j.parent is None else m[j.parent],
                                           child=m[j.child],
                                           handle=None if j.handle is None else m[j.handle])
                       for j in self.joints)
        contacts = tuple(sorted(tuple(sorted((m[a], m[b]))) for a, b in self.contacts))
        return dataclasses.replace(self, id=object_id, parts=parts, joints=joints, contacts=contacts)

    def placed(self, T_world_object: np.ndarray, supported_by: int | None = None) -> "ArticulatedObject":
        return dataclasses.replace(self, T_world_object=np.array(T_world_object, float),
                                   supported_by=supported_by)


def _joint_motion(j: Joint, value: float) -> np.ndarray:
    """(4, 4) rigid motion in the object frame of joint ``j`` at ``value``."""
    M = np.eye(4)
    if j.type is JointType.PRISMATIC:
        M[:3, 3] = j.axis * value
    elif j.type is JointType.REVOLUTE:
        M = T_about(j.axis, j.origin, value)
    return M


@dataclass(frozen=True, eq=False)
class Wall:
    """A fixed box wall: ``size`` (3,) metres, ``T_world_wall`` (4, 4) at the box centre."""

    name: str
    size: np.ndarray
    T_world_wall: np.ndarray


@dataclass(frozen=True, eq=False)
class Scene:
    """A room: objects placed in the world, walls, and the floor at z = 0.

    ``room_size`` (2,) the inner floor extent in x and y (metres), centred on the world origin.
    """

    name: str
    seed: int
    objects: tuple[ArticulatedObject, ...]
    walls: tuple[Wall, ...] = ()
    room_size: np.ndarray = field(default_factory=lambda: np.array([5.0, 4.0]))

    def isclose(self, other: "Scene", atol: float = 1e-9) -> bool:
        return (self.name == other.name and self.seed == other.seed
                and len(self.objects) == len(other.objects) and len(self.walls) == len(other.walls)
                and np.allclose(self.room_size, other.room_size, atol=atol)
                and all(a.isclose(b, atol) for a, b in zip(self.objects, other.objects))
                and all(a.name == b.name and np.allclose(a.size, b.size, atol=atol)
                        and np.allclose(a.T_world_wall, b.T_world_wall, atol=atol)
                        for a, b in zip(self.walls, other.walls)))

    def object(self, object_id: int) -> ArticulatedObject:
        for o in self.objects:
            if o.id == object_id:
                return o
        raise KeyError(f"scene {self.name}: no object {object_id}")
