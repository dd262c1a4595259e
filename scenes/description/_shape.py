"""The one shape type: a box, cylinder, sphere or mesh posed in the frame of the link (part) holding it.

``size`` is always a (3,) float64 extent in the shape's own frame, centred on it:

    box       (sx, sy, sz)        full edge lengths
    cylinder  (2r, 2r, length)    axis along the local z
    sphere    (2r, 2r, 2r)
    mesh      the mesh file's scale (3,)

Mass properties are of a solid of uniform density (closed forms; a mesh has none here).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

import numpy as np

__all__ = ["ShapeKind", "Material", "SolidProperties", "Shape", "shape_volume", "shape_inertia", "mass_properties"]


class ShapeKind(str, Enum):
    """The kind of a shape (values are the URDF geometry tag names)."""

    BOX = "box"
    CYLINDER = "cylinder"
    SPHERE = "sphere"
    MESH = "mesh"


def shape_volume(kind: ShapeKind, size) -> float:
    """m^3 of a solid ``kind`` of ``size`` (3,) (see the module docstring; 0 for a mesh)."""
    sx, sy, sz = size
    if kind is ShapeKind.BOX:
        return float(sx * sy * sz)
    if kind is ShapeKind.CYLINDER:
        return float(np.pi * (min(sx, sy) / 2.0) ** 2 * sz)
    if kind is ShapeKind.SPHERE:
        return float(4.0 / 3.0 * np.pi * (sx / 2.0) ** 3)
    return 0.0


def shape_inertia(kind: ShapeKind, size, mass: float) -> np.ndarray:
    """(3, 3) inertia (kg m^2) of a solid ``kind`` of ``size`` (3,) and ``mass`` kg about its centre, in its
    own axes (closed forms; ``ValueError`` for a mesh)."""
    sx, sy, sz = size
    if kind is ShapeKind.BOX:
        d = mass / 12.0 * np.array([sy ** 2 + sz ** 2, sx ** 2 + sz ** 2, sx ** 2 + sy ** 2])
    elif kind is ShapeKind.CYLINDER:
        r = min(sx, sy) / 2.0
        side = mass * (3 * r ** 2 + sz ** 2) / 12.0
        d = np.array([side, side, mass * r ** 2 / 2.0])
    elif kind is ShapeKind.SPHERE:
        d = np.full(3, 2.0 / 5.0 * mass * (sx / 2.0) ** 2)
    else:
        raise ValueError("a mesh has no closed-form inertia")
    return np.diag(d)


@dataclass(frozen=True)
class Material:
    """A URDF material: ``name`` and optional ``rgba`` (4,) in [0, 1] (``None``: a reference by name)."""

    name: str | None = None
    rgba: tuple[float, float, float, float] | None = None


def _size3(size) -> np.ndarray:
    s = np.asarray(size, dtype=np.float64).reshape(-1)
    if s.shape == (1,):
        s = np.repeat(s, 3)
    if s.shape != (3,):
        raise ValueError(f"shape size must be 3 numbers, got shape {s.shape}")
    return s


class SolidProperties:
    """Radius, length, volume and inertia of anything with a ``kind`` (:class:`ShapeKind`) and a ``size`` (3,)
    in this module's convention (:class:`Shape`, ``recon.Primitive``)."""

    kind: ShapeKind
    size: np.ndarray

    @property
    def radius(self) -> float:
        """Radius (m) of a cylinder or sphere; half the smaller cross extent of a box."""
        return float(min(self.size[0], self.size[1]) / 2.0)

    @property
    def length(self) -> float:
        """Extent along the local z, metres."""
        return float(self.size[2])

    @property
    def volume(self) -> float:
        """m^3 of the solid (0 for a mesh)."""
        return shape_volume(self.kind, self.size)

    def inertia(self, mass: float) -> np.ndarray:
        """(3, 3) inertia (kg m^2) of a solid of ``mass`` kg about its centre, in its own axes."""
        return shape_inertia(self.kind, self.size, mass)


@dataclass(frozen=True, eq=False)
class Shape(SolidProperties):
    """One shape of a link.

    kind : ShapeKind
    size : (3,) float, metres (see the module docstring; a mesh's scale, unitless)
    T_link_shape : (4, 4) float, pose of the shape's centre frame in the link (part) frame
    name : the URDF ``<visual>``/``<collision>`` name, or ``None``
    mesh : a mesh's file (absolute path or ``package://`` URI), else ``None``
    material : a visual's material, else ``None``
    """

    kind: ShapeKind
    size: np.ndarray
    T_link_shape: np.ndarray = field(default_factory=lambda: np.eye(4))
    name: str | None = None
    mesh: str | None = None
    material: Material | None = None

    def __post_init__(self):
        object.__setattr__(self, "kind", ShapeKind(self.kind))
        object.__setattr__(self, "size", _size3(self.size))
        T = np.array(self.T_link_shape, dtype=np.float64)
        if T.shape != (4, 4):
            raise ValueError(f"T_link_shape must be a (4, 4) pose, got shape {T.shape}")
        object.__setattr__(self, "T_link_shape", T)

    # ----- construction
    @staticmethod
    def box(size, T_link_shape=None, **kw) -> "Shape":
        """A box of full edge lengths ``size`` (3,), metres."""
        return Shape(ShapeKind.BOX, size, np.eye(4) if T_link_shape is None else T_link_shape, **kw)

    @staticmethod
    def cylinder(radius: float, length: float, T_link_shape=None, **kw) -> "Shape":
        """A cylinder of ``radius`` and ``length`` (metres) along the local z."""
        return Shape(ShapeKind.CYLINDER, [2.0 * radius, 2.0 * radius, length],
                     np.eye(4) if T_link_shape is None else T_link_shape, **kw)

    @staticmethod
    def sphere(radius: float, T_link_shape=None, **kw) -> "Shape":
        """A sphere of ``radius`` (metres)."""
        return Shape(ShapeKind.SPHERE, [2.0 * radius] * 3, np.eye(4) if T_link_shape is None else T_link_shape, **kw)

    # ----- geometry
    def corners(self) -> np.ndarray:
        """(8, 3) corners of the shape's bounding box, in the link frame (a cylinder's box is tight)."""
        h = self.size / 2
        c = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float) * h
        return c @ self.T_link_shape[:3, :3].T + self.T_link_shape[:3, 3]

    def moved(self, T_new_link: np.ndarray) -> "Shape":
        """The same shape in another frame: ``T_new_shape = T_new_link @ T_link_shape``."""
        return Shape(self.kind, self.size.copy(), T_new_link @ self.T_link_shape, self.name, self.mesh, self.material)

    def isclose(self, other: "Shape", atol: float = 1e-9) -> bool:
        """Same kind, mesh and size and pose within ``atol`` (names and materials are not compared)."""
        return (self.kind == other.kind and self.mesh == other.mesh
                and np.allclose(self.size, other.size, atol=atol)
                and np.allclose(self.T_link_shape, other.T_link_shape, atol=atol))


def mass_properties(shapes, density: float) -> tuple[float, np.ndarray, np.ndarray]:
    """``(mass kg, com (3,) in the link frame, inertia (3, 3) about the com in link axes)`` of ``shapes``.

    Solids of uniform ``density`` (kg/m^3); overlaps are counted twice (our parts' shapes only touch).
    """
    masses = np.array([s.volume * density for s in shapes])
    centres = np.array([s.T_link_shape[:3, 3] for s in shapes])
    m = float(masses.sum())
    com = (masses[:, None] * centres).sum(0) / m
    inertia = np.zeros((3, 3))
    for s, ms, c in zip(shapes, masses, centres):
        R = s.T_link_shape[:3, :3]
        d = c - com
        inertia += R @ s.inertia(float(ms)) @ R.T + ms * (d @ d * np.eye(3) - np.outer(d, d))
    return m, com, inertia
