"""Exact distances from points to the surfaces of primitive shapes and parts (pure numpy).

Used to check that a scanned point labelled part p lies on p's surface, and available to metrics.
"""

from __future__ import annotations

import numpy as np

from .description import Shape, ShapeKind
from .model import Part
from .description import transform_points

__all__ = ["shape_sdf", "part_surface_distance"]


def shape_sdf(shape: Shape, p_part: np.ndarray) -> np.ndarray:
    """(n,) signed distance (m, negative inside) from (n, 3) points in the part frame to ``shape``."""
    T_shape_part = np.linalg.inv(shape.T_link_shape)
    p = transform_points(T_shape_part, p_part)
    if shape.kind is ShapeKind.BOX:
        q = np.abs(p) - shape.size / 2
    else:
        q = np.stack([np.linalg.norm(p[:, :2], axis=1) - shape.radius, np.abs(p[:, 2]) - shape.length / 2], 1)
    outside = np.linalg.norm(np.maximum(q, 0.0), axis=1)
    inside = np.minimum(q.max(axis=1), 0.0)
    return outside + inside


def part_surface_distance(part: Part, T_world_part: np.ndarray, p_world: np.ndarray) -> np.ndarray:
    """(n,) unsigned distance (m) from (n, 3) world points to the nearest shape surface of ``part``."""
    p = transform_points(np.linalg.inv(T_world_part), p_world)
    return np.min(np.abs(np.stack([shape_sdf(s, p) for s in part.shapes])), axis=0)
