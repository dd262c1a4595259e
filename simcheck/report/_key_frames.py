"""Key frames of an executed task: the RECORDED robot and object states of a rollout, drawn by
PyBullet's CPU renderer through :class:`simcheck.world.World` (the PyBullet adapter).

Nothing is simulated here: each frame places the robot at ``rollout.robot_q[i]`` and the task joint at
``rollout.object_q[i]`` (what physics produced while executing) and takes a picture.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from simcheck.key_frame_view import CAMERA_DISTANCE, CAMERA_HEIGHT, FOV_DEG, camera_distance
from simcheck.rollout import Rollout

from ._primitives import Solid, solids_from_urdf

__all__ = ["key_frame_indices", "key_frame_images", "camera_for", "part_extent", "FRAME_SIZE"]

log = logging.getLogger(__name__)

#: Width, height of a key frame, pixels.
FRAME_SIZE = (360, 270)
#: Angle of the camera off the opening direction (deg); distances: :mod:`simcheck.key_frame_view`.
CAMERA_ANGLE_DEG = 50.0
#: The last metres of the line of sight before the handle that may cross parts (the drawer, the body).
CLEARANCE = 0.3


def key_frame_indices(rollout: Rollout) -> list[tuple[str, int]]:
    """``(caption, sample index)``: grasp (start of the open segment), half-way, end of opening, end."""
    open_idx = np.flatnonzero(rollout.in_segment(rollout.opening_segment))
    picks: list[tuple[str, int]] = [("start", 0)]
    if len(open_idx):
        picks += [("grasped", int(open_idx[0])), ("opening", int(open_idx[len(open_idx) // 2])),
                  ("opened", int(open_idx[-1]))]
    picks.append(("end", rollout.n - 1))
    seen, out = set(), []
    for caption, i in picks:
        if i not in seen and 0 <= i < rollout.n:
            seen.add(i)
            out.append((caption, i))
    return out


def _segment_hits_box(a: np.ndarray, b: np.ndarray, solid: Solid) -> bool:
    """True when the segment a -> b (world, metres) crosses the solid's oriented bounding box (slab test)."""
    T = solid.T_world_shape
    half = solid.size / 2
    pa, pb = (T[:3, :3].T @ (a - T[:3, 3])), (T[:3, :3].T @ (b - T[:3, 3]))
    d = pb - pa
    t0, t1 = 0.0, 1.0
    for k in range(3):
        if abs(d[k]) < 1e-12:
            if abs(pa[k]) > half[k]:
                return False
            continue
        lo, hi = sorted(((-half[k] - pa[k]) / d[k], (half[k] - pa[k]) / d[k]))
        t0, t1 = max(t0, lo), min(t1, hi)
        if t0 > t1:
            return False
    return True


def _blocked(eye: np.ndarray, target: np.ndarray, obstacles: Sequence[Solid]) -> bool:
    """True when a solid lies between ``eye`` and the last :data:`CLEARANCE` metres before ``target``."""
    v = target - eye
    end = eye + v * max(0.0, 1.0 - CLEARANCE / max(np.linalg.norm(v), 1e-9))
    return any(_segment_hits_box(eye, end, s) for s in obstacles)


def part_extent(rollout: Rollout, moving: Sequence[Solid] = ()) -> tuple[np.ndarray, float]:
    """``(centre (3,), size)`` world metres of what a key frame must show: the handle's whole path and the
    moving part's primitives ``moving`` (as the scene file has them, closed): the centre of their box and
    its largest side."""
    pts = [rollout.T_world_handle[:, :3, 3]]
    for s in moving:
        corners = np.array([[x, y, z] for x in (-.5, .5) for y in (-.5, .5) for z in (-.5, .5)]) * s.size
        pts.append(corners @ s.T_world_shape[:3, :3].T + s.T_world_shape[:3, 3])
    pts = np.concatenate(pts)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    return (lo + hi) / 2, float(np.max(hi - lo))


def camera_for(rollout: Rollout, obstacles: Sequence[Solid] = (), moving: Sequence[Solid] = ()) -> tuple[np.ndarray, np.ndarray]:
    """``(target, eye)`` world points, metres: looking at the part being opened from in front of it and to
    the side, close enough that the part (its primitives ``moving`` and the handle's path) fills the frame.

    "In front" is the horizontal direction the handle moved (outwards for a drawer or a door); when it
    did not move, the direction from the handle to the robot tool at the start. Candidate eyes are tried
    from the preferred view (:data:`CAMERA_ANGLE_DEG` to the side, :func:`camera_distance` away, up in
    the ratio :data:`CAMERA_HEIGHT` : :data:`CAMERA_DISTANCE`) outwards; the first whose line of sight no
    obstacle (e.g. a wall) blocks is taken (the preferred one when all are blocked).
    """
    p = rollout.T_world_handle[:, :3, 3]
    target, size = part_extent(rollout, moving)
    distance = camera_distance(size)
    height = distance * CAMERA_HEIGHT / CAMERA_DISTANCE
    d = p[-1] - p[0]
    d[2] = 0.0
    if np.linalg.norm(d) < 0.02:
        d = rollout.tool_pos[0] - p[0]
        d[2] = 0.0
    if np.linalg.norm(d) < 1e-6:
        d = np.array([1.0, 0.0, 0.0])
    d /= np.linalg.norm(d)
    candidates = []
    for dist_scale in (1.0, 0.75, 0.55):
        for angle in (CAMERA_ANGLE_DEG, -CAMERA_ANGLE_DEG, 30.0, -30.0, 70.0, -70.0, 0.0):
            a = np.radians(angle)
            R = np.array([[np.cos(a), -np.sin(a), 0.0], [np.sin(a), np.cos(a), 0.0], [0.0, 0.0, 1.0]])
            candidates.append(target + dist_scale * (distance * (R @ d) + np.array([0.0, 0.0, height])))
    for eye in candidates:
        if not _blocked(eye, target, obstacles):
            return target, eye
    return target, candidates[0]


def key_frame_images(rollout: Rollout, scene_urdf: str | Path, robot=None) -> list[tuple[str, np.ndarray]]:
    """``(caption, (h, w, 3) uint8)`` key frames of ``rollout`` executed in ``scene_urdf``.

    ``robot`` is a ``planners.RobotSpec`` / :class:`simcheck.robot_binding.SimRobot`; default: the
    default robot. Raises the world's errors (naming the URDF) when the scene or robot cannot be loaded.
    """
    from simcheck.robot_binding import sim_robot_from_spec
    from simcheck.world import World

    if robot is None:
        from planners import default_robot
        robot = default_robot()
    sim_robot = sim_robot_from_spec(robot)
    solids = solids_from_urdf(scene_urdf)
    obstacles = [s for s in solids if s.link != rollout.handle_link]
    moving = [s for s in solids if s.link in (rollout.moving_link, rollout.handle_link)]
    target, eye = camera_for(rollout, obstacles, moving)
    frames = []
    with World(scene_urdf, sim_robot) as world:
        names = list(rollout.robot_joint_names)
        order = [names.index(n) for n in sim_robot.joint_names]
        for caption, i in key_frame_indices(rollout):
            world.reset_robot(rollout.robot_q[i][order], fingers_open=not bool(rollout.grasp_active[i]))
            world.reset_scene_joint(rollout.joint, float(rollout.object_q[i]))
            image = world.render(target, eye, width=FRAME_SIZE[0], height=FRAME_SIZE[1], fov_deg=FOV_DEG)
            frames.append((f"{caption}: t = {rollout.t[i]:.1f} s", image))
    log.debug("rendered %d key frames of %s", len(frames), rollout.joint)
    return frames
