"""Key frames of an executed task: the RECORDED robot and object states of a rollout, drawn by
PyBullet's CPU renderer through :class:`simcheck.world.World` (the one module that imports pybullet).

Nothing is simulated here: each frame places the robot at ``rollout.robot_q[i]`` and the task joint at
``rollout.object_q[i]`` (what physics produced while executing) and takes a picture.
"""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np

from simcheck.rollout import Rollout

__all__ = ["key_frame_indices", "key_frame_images", "camera_for", "FRAME_SIZE"]

log = logging.getLogger(__name__)

#: Width, height of a key frame, pixels.
FRAME_SIZE = (400, 300)
#: Camera distance from the handle (m), height above it (m) and angle off the opening direction (deg).
CAMERA_DISTANCE, CAMERA_HEIGHT, CAMERA_ANGLE_DEG = 1.9, 1.0, 50.0


def key_frame_indices(rollout: Rollout) -> list[tuple[str, int]]:
    """``(caption, sample index)``: grasp (start of the open segment), half-way, end of opening, end."""
    open_idx = np.flatnonzero(rollout.in_segment("open"))
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


def camera_for(rollout: Rollout) -> tuple[np.ndarray, np.ndarray]:
    """``(target, eye)`` world points, metres: looking at the handle from in front of it and to the side.

    "In front" is the horizontal direction the handle moved (outwards for a drawer or a door); when it
    did not move, the direction from the handle to the robot tool at the start.
    """
    p = rollout.T_world_handle[:, :3, 3]
    target = p.mean(axis=0)
    d = p[-1] - p[0]
    d[2] = 0.0
    if np.linalg.norm(d) < 0.02:
        d = rollout.tool_pos[0] - p[0]
        d[2] = 0.0
    if np.linalg.norm(d) < 1e-6:
        d = np.array([1.0, 0.0, 0.0])
    d /= np.linalg.norm(d)
    a = np.radians(CAMERA_ANGLE_DEG)
    R = np.array([[np.cos(a), -np.sin(a), 0.0], [np.sin(a), np.cos(a), 0.0], [0.0, 0.0, 1.0]])
    eye = target + CAMERA_DISTANCE * (R @ d) + np.array([0.0, 0.0, CAMERA_HEIGHT])
    return target, eye


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
    target, eye = camera_for(rollout)
    frames = []
    with World(scene_urdf, sim_robot) as world:
        names = list(rollout.robot_joint_names)
        order = [names.index(n) for n in sim_robot.joint_names]
        for caption, i in key_frame_indices(rollout):
            world.reset_robot(rollout.robot_q[i][order], fingers_open=not bool(rollout.grasp_active[i]))
            world.reset_scene_joint(rollout.joint, float(rollout.object_q[i]))
            image = world.render(target, eye, width=FRAME_SIZE[0], height=FRAME_SIZE[1])
            frames.append((f"{caption}: t = {rollout.t[i]:.1f} s", image))
    log.debug("rendered %d key frames of %s", len(frames), rollout.joint)
    return frames
