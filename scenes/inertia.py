"""Mass properties of parts made of boxes and cylinders (solid, uniform density)."""

from __future__ import annotations

import numpy as np

from .model import Part, Shape, ShapeType

__all__ = ["shape_inertia", "part_mass_properties"]


def shape_inertia(shape: Shape, mass: float) -> np.ndarray:
    """(3, 3) inertia (kg m^2) of ``shape`` about its centre, in the shape's own axes."""
    if shape.type is ShapeType.BOX:
        a, b, c = shape.size
        return mass / 12.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    r, h = shape.radius, shape.length
    ixx = mass * (3 * r * r + h * h) / 12.0
    return np.diag([ixx, ixx, mass * r * r / 2.0])


def part_mass_properties(part: Part) -> tuple[float, np.ndarray, np.ndarray]:
    """``(mass kg, com (3,) in the part frame, inertia (3, 3) about the com in part axes)``.

    Overlapping shapes are counted twice (our generators' shapes only touch).
    """
    masses = np.array([s.volume * part.density for s in part.shapes])
    centres = np.array([s.T_part_shape[:3, 3] for s in part.shapes])
    m = float(masses.sum())
    com = (masses[:, None] * centres).sum(0) / m
    inertia = np.zeros((3, 3))
    for s, ms, c in zip(part.shapes, masses, centres):
        R = s.T_part_shape[:3, :3]
        d = c - com
        inertia += R @ shape_inertia(s, ms) @ R.T + ms * (d @ d * np.eye(3) - np.outer(d, d))
    return m, com, inertia
