"""Camera poses of a person walking a loop through the room and looking at the objects.

The loop is a rectangle ``path_inset`` metres inside the walls (shrunk for small rooms); waypoints
inside or within ``BODY_RADIUS`` of an object's footprint are skipped (a person cannot stand there).
At each waypoint the person looks at the object that scores best for a good view: in front of it
(articulated objects are scanned from their opening side), 1-3 m away, and not looked at much yet.
Camera frame (OpenCV): x right, y down, z forward.
"""

from __future__ import annotations

import numpy as np
from shapely.geometry import Point
from shapely.ops import unary_union

from ..errors import ScanError
from ..footprints import footprint
from ..model import Scene
from .params import ScanParams

__all__ = ["BODY_RADIUS", "look_at", "camera_poses"]

BODY_RADIUS = 0.3      # m, free floor a walking person needs around the camera
_GOOD_RANGE = 2.0      # m, preferred viewing distance
_TARGET_JITTER = 0.08  # m, std of the look-at point jitter


def look_at(eye: np.ndarray, target: np.ndarray) -> np.ndarray:
    """(4, 4) ``T_world_camera`` at ``eye`` looking at ``target`` with the image's up toward +z."""
    z = target - eye
    z = z / np.linalg.norm(z)
    x = np.cross(z, [0.0, 0.0, 1.0])
    if np.linalg.norm(x) < 1e-6:
        x = np.array([1.0, 0.0, 0.0])
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    T = np.eye(4)
    T[:3, :3] = np.column_stack([x, y, z])
    T[:3, 3] = eye
    return T


def _loop(room_size: np.ndarray, inset: float, n: int) -> np.ndarray:
    """(m, 2) points evenly spaced on the inset rectangle (m >= n)."""
    hx, hy = np.maximum(room_size / 2 - inset, 0.25)
    corners = np.array([[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy], [-hx, -hy]])
    seg = np.linalg.norm(np.diff(corners, axis=0), axis=1)
    s = np.linspace(0, seg.sum(), n, endpoint=False)
    cum = np.concatenate([[0], np.cumsum(seg)])
    k = np.clip(np.searchsorted(cum, s, side="right") - 1, 0, 3)
    f = (s - cum[k]) / seg[k]
    return corners[k] + f[:, None] * (corners[k + 1] - corners[k])


def camera_poses(scene: Scene, params: ScanParams, rng: np.random.Generator) -> np.ndarray:
    """(k, 4, 4) ``T_world_camera``, k = max(``n_frames``, ``frames_per_object`` x objects) (raises if
    no camera position is free)."""
    if not scene.objects:
        raise ScanError(f"scene {scene.name!r} has no objects to scan")
    blocked = unary_union([footprint(o).buffer(BODY_RADIUS) for o in scene.objects if o.supported_by is None])
    n_frames = max(params.n_frames, params.frames_per_object * len(scene.objects))
    pts = _loop(scene.room_size, params.path_inset, 4 * n_frames)
    free = np.array([not blocked.contains(Point(p)) for p in pts])
    if not free.any():
        pts = _loop(scene.room_size, max(params.path_inset / 2, 0.4), 4 * n_frames)
        free = np.array([not blocked.contains(Point(p)) for p in pts])
    if not free.any():
        raise ScanError(f"scene {scene.name!r}: no free floor for the camera path (inset {params.path_inset} m)")
    pts = pts[free]
    idx = np.linspace(0, len(pts), n_frames, endpoint=False).astype(int)
    walk = pts[idx]
    centres, fronts = [], []
    for o in scene.objects:
        lo, hi = o.bounds()
        c = o.T_world_object[:3, :3] @ ((lo + hi) / 2) + o.T_world_object[:3, 3]
        centres.append(c)
        fronts.append(o.T_world_object[:3, 0] if any(j.movable for j in o.joints) else None)
    looks = np.zeros(len(scene.objects))
    h0, h1 = params.camera_height
    poses = []
    phase = rng.uniform(0, 2 * np.pi)
    for i, p in enumerate(walk):
        h = h0 + (h1 - h0) * (0.5 + 0.5 * np.sin(phase + 2 * np.pi * 3 * i / len(walk)))
        eye = np.array([p[0], p[1], h])
        best, best_score = 0, -np.inf
        for k, (c, f) in enumerate(zip(centres, fronts)):
            d = eye[:2] - c[:2]
            dist = np.linalg.norm(d)
            facing = 0.5 if f is None else float(f[:2] @ d / max(dist, 1e-9))
            score = 1.5 * facing - 0.6 * abs(dist - _GOOD_RANGE) - 0.8 * looks[k]
            if dist < 0.4:
                score = -np.inf
            if score > best_score:
                best, best_score = k, score
        looks[best] += 1
        target = centres[best] + rng.normal(0, _TARGET_JITTER, 3)
        poses.append(look_at(eye, target))
    return np.array(poses)
