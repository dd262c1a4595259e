"""A door's hinge line moved to the door's other edge (pure numpy).

Used where a door's hinge side is a guess (no handle, both edges as near its body's edges): recon measures
its joint's spread about either line, and a robust certificate hinges half of its worlds at the other one.
"""

from __future__ import annotations

import numpy as np

__all__ = ["other_edge_origin"]


def other_edge_origin(origin, axis, T_world_door: np.ndarray, size) -> np.ndarray:
    """(3,) a point on the hinge line mirrored across the door's middle along its width.

    origin (3,), axis (3,) : the hinge line (any frame F, metres); T_world_door (4, 4) : the door's box in F
    (its axes are the box's); size (3,) : the box's extents along them. The door's thickness is the box's
    smallest extent across the axis; its width the direction across both. The line keeps its depth across
    the door; hinged there the door opens about the reversed axis.
    """
    a = np.asarray(axis, dtype=np.float64)
    a = a / np.linalg.norm(a)
    o = np.asarray(origin, dtype=np.float64)
    T = np.asarray(T_world_door, dtype=np.float64)
    R = T[:3, :3]
    across = [k for k in range(3) if abs(R[:, k] @ a) < 0.5] or [0, 1, 2]
    normal = R[:, min(across, key=lambda k: float(size[k]))]
    width = np.cross(a, normal)
    width /= np.linalg.norm(width)
    return o + 2.0 * float((T[:3, 3] - o) @ width) * width
