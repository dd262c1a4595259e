"""Walls of the room from the scan's background (object id -1): vertical RANSAC planes -> thin boxes.

A plan made on a reconstruction must avoid the walls the camera saw, so the background above the floor
is searched for vertical planes (open3d RANSAC through :mod:`recon.open3d_engine`); each becomes a box
``wall_thickness`` thick standing on the floor *behind* its plane (on the side away from the labelled
objects), spanning its inliers' 1st..99th percentile along the wall and from the floor to its highest
inlier. Duplicates (parallel planes closer than ``wall_merge_distance``) are dropped.

Frames: ``T_world_wall`` (4, 4) has x = the wall's normal pointing into the room, z up, origin at the
box centre; ``size`` = (thickness, length, height), metres. Links are named ``wall0``, ``wall1``, ...
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

from recon.config import WallConfig

__all__ = ["Wall", "walls_from_background"]

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False)
class Wall:
    """A fitted wall: name (URDF link ``wallK``), size (3,) (thickness, length, height) in metres, and
    T_world_wall (4, 4) (x = normal into the room, z up, at the box centre)."""

    name: str
    size: np.ndarray
    T_world_wall: np.ndarray
    n_points: int = 0

    def __post_init__(self):
        object.__setattr__(self, "size", np.asarray(self.size, dtype=np.float64).reshape(3))
        object.__setattr__(self, "T_world_wall", np.asarray(self.T_world_wall, dtype=np.float64).reshape(4, 4))

    def transformed(self, T_new_world: np.ndarray) -> "Wall":
        """The wall moved rigidly by ``T_new_world`` (4, 4)."""
        return Wall(self.name, self.size, T_new_world @ self.T_world_wall, self.n_points)

    def isclose(self, other: "Wall", atol: float = 1e-6) -> bool:
        return (self.name == other.name and np.allclose(self.size, other.size, atol=atol)
                and np.allclose(self.T_world_wall, other.T_world_wall, atol=atol))


def walls_from_background(points: np.ndarray, room_centre: np.ndarray, config: WallConfig,
                          seed: int = 0) -> tuple[Wall, ...]:
    """Walls found in the background ``points`` (n, 3) world (floor z = 0); ``room_centre`` (3,) is a
    point inside the room (the labelled objects' centroid) that tells which side of a plane is the
    room. Returns () when there is too little background."""
    from recon.open3d_engine import segment_planes

    pts = np.asarray(points, dtype=np.float64)
    pts = pts[pts[:, 2] > config.wall_floor_margin]
    if len(pts) < config.wall_min_points:
        return ()
    rng = np.random.default_rng(seed)
    if len(pts) > config.wall_max_points:
        pts = pts[np.sort(rng.choice(len(pts), config.wall_max_points, replace=False))]
    found = segment_planes(pts, distance=config.wall_ransac_distance, count=config.wall_max_planes, seed=seed,
                           min_inliers=max(config.wall_min_points, int(config.wall_min_fraction * len(pts))))
    walls: list[Wall] = []
    kept: list[tuple[np.ndarray, float]] = []
    for plane, idx in found:
        n, d = plane[:3], float(plane[3])
        if abs(n[2]) > config.wall_max_tilt:
            continue                                   # not vertical (a table-height shelf of clutter)
        n = np.array([n[0], n[1], 0.0])
        scale = np.linalg.norm(n)
        n, d = n / scale, d / scale
        if n @ room_centre + d < 0:                    # normal into the room
            n, d = -n, -d
        d = -float(np.median(pts[idx] @ n))            # robust offset of the noisy inliers
        if any(abs(float(n @ m)) > 0.99 and abs(d - e) < config.wall_merge_distance for m, e in kept):
            continue
        inl = pts[idx]
        t = np.cross([0.0, 0.0, 1.0], n)
        s = inl @ t
        a, b = np.percentile(s, [1, 99])
        height = float(np.percentile(inl[:, 2], 99))
        if b - a < config.wall_min_length or height < config.wall_min_length:
            continue
        p0 = -d * n                                    # the plane's point nearest the world origin (z = 0)
        centre = p0 + t * ((a + b) / 2 - float(p0 @ t)) - n * config.wall_thickness / 2
        centre[2] = height / 2
        T = np.eye(4)
        T[:3, 0], T[:3, 1], T[:3, 2], T[:3, 3] = n, t, [0.0, 0.0, 1.0], centre
        walls.append(Wall(f"wall{len(walls)}", [config.wall_thickness, b - a, height], T, len(idx)))
        kept.append((n, d))
        log.info("wall%d: %d points, %.2f m long, %.2f m high", len(walls) - 1, len(idx), b - a, height)
    return tuple(walls)
