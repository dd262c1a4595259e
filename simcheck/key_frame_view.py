"""How far a key-frame camera stands from the part being opened (pure: no engine), shared by the frames
simcheck saves while executing (:mod:`simcheck.keyframes`) and the report's redrawn ones
(:mod:`simcheck.report._key_frames`)."""

from __future__ import annotations

import numpy as np

__all__ = ["CAMERA_DISTANCE", "CAMERA_HEIGHT", "MIN_CAMERA_DISTANCE", "FOV_DEG", "PART_FILL", "camera_distance"]

#: The farthest camera distance from the part (m) and the height above it at that distance (m).
CAMERA_DISTANCE, CAMERA_HEIGHT = 1.9, 1.0
#: The nearest camera distance (m): the gripper and the arm's wrist stay in view.
MIN_CAMERA_DISTANCE = 1.0
#: Vertical field of view of the key frames (deg), and the share of it the moving part fills.
FOV_DEG, PART_FILL = 60.0, 0.6


def camera_distance(size: float) -> float:
    """Distance (m) from which a part of ``size`` (m, its largest side with the handle's path) fills
    :data:`PART_FILL` of the frame's height, within [:data:`MIN_CAMERA_DISTANCE`, :data:`CAMERA_DISTANCE`]."""
    d = size / PART_FILL / (2.0 * np.tan(np.radians(FOV_DEG) / 2))
    return float(np.clip(d, MIN_CAMERA_DISTANCE, CAMERA_DISTANCE))
