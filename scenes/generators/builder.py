"""Assemble an :class:`~scenes.model.ArticulatedObject` part by part (used by every generator).

Shapes are given by centre/size in the OBJECT frame and stored in the part frame, so generators
think in one frame: x = front normal, z up, origin on the floor at the footprint centre.
"""

from __future__ import annotations

import numpy as np

from ..config import GeneratorConfig
from ..description import Shape
from ..model import ArticulatedObject, Joint, JointType, Part
from ..description import pose

__all__ = ["ObjectBuilder"]


class ObjectBuilder:
    """Collects parts (local ids 0, 1, ...), joints and contact edges of one object."""

    def __init__(self, category: str, cfg: GeneratorConfig):
        self.category = category
        self.cfg = cfg
        self._parts: list[Part] = []
        self._joints: list[Joint] = []
        self._contacts: set[tuple[int, int]] = set()

    # ---------------------------------------------------------------- shapes (object frame)
    @staticmethod
    def box(center, size, R=None) -> Shape:
        """Box of full extents ``size`` (3,) centred at ``center`` (3,) in the object frame."""
        return Shape.box(size, pose(center, R=R))

    @staticmethod
    def cylinder(center, radius: float, length: float, along: str = "z") -> Shape:
        """Cylinder centred at ``center`` with its axis along object ``x``, ``y`` or ``z``."""
        R = {"z": np.eye(3),
             "x": np.array([[0, 0, 1], [0, 1, 0], [-1, 0, 0]], float),   # local z -> x
             "y": np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]], float)}[along]  # local z -> y
        return Shape.cylinder(radius, length, pose(center, R=R))

    # ---------------------------------------------------------------- parts and joints
    def add_part(self, label: str, shapes: list[Shape], T_object_part=None) -> int:
        """Add a part; ``shapes`` are in the object frame and re-expressed in the part frame.

        Default frame: the object frame for the first (root) part, else the centre of the shapes'
        bounding box with the object's orientation.
        """
        if T_object_part is not None:
            T = np.asarray(T_object_part, float)
        elif not self._parts:
            T = np.eye(4)
        else:
            pts = np.vstack([s.corners() for s in shapes])
            T = pose((pts.min(0) + pts.max(0)) / 2)
        T_part_object = np.linalg.inv(T)
        pid = len(self._parts)
        density = self.cfg.densities.for_part(self.category, label)
        self._parts.append(Part(pid, label, T, tuple(s.moved(T_part_object) for s in shapes), density))
        return pid

    def fix(self, parent: int | None, child: int) -> None:
        self._joints.append(Joint(JointType.FIXED, parent, child,
                                  origin=self._parts[child].T_object_part[:3, 3].copy()))
        if parent is not None:
            self.contact(parent, child)

    def prismatic(self, parent: int, child: int, axis, upper: float, handle: int | None = None) -> None:
        d = self.cfg.dynamics
        self._joints.append(Joint(JointType.PRISMATIC, parent, child, np.asarray(axis, float),
                                  self._parts[child].T_object_part[:3, 3].copy(), 0.0, float(upper),
                                  handle, d.prismatic_effort, d.prismatic_velocity,
                                  d.prismatic_damping, d.prismatic_friction))
        self.contact(parent, child)

    def revolute(self, parent: int, child: int, axis, upper: float, handle: int | None = None) -> None:
        """Revolute joint about ``axis`` through the child's frame origin (the hinge line)."""
        d = self.cfg.dynamics
        self._joints.append(Joint(JointType.REVOLUTE, parent, child, np.asarray(axis, float),
                                  self._parts[child].T_object_part[:3, 3].copy(), 0.0, float(upper),
                                  handle, d.revolute_effort, d.revolute_velocity,
                                  d.revolute_damping, d.revolute_friction))
        self.contact(parent, child)

    def contact(self, a: int, b: int) -> None:
        self._contacts.add((min(a, b), max(a, b)))

    def build(self) -> ArticulatedObject:
        return ArticulatedObject(0, self.category, tuple(self._parts), tuple(self._joints),
                                 tuple(sorted(self._contacts)))
