"""Images of a PyBullet client's world from a camera, on the CPU renderer (headless)."""

from __future__ import annotations

import numpy as np

from simcheck.bullet import pb

__all__ = ["render"]


def render(client: int, target: np.ndarray, eye: np.ndarray, width: int = 320, height: int = 240,
           fov_deg: float = 60.0) -> np.ndarray:
    """(height, width, 3) uint8 RGB image from ``eye`` (3,) looking at ``target`` (3,), world frame, z up,
    metres; vertical field of view ``fov_deg`` degrees. Uses PyBullet's ``ER_TINY_RENDERER``."""
    view = pb.computeViewMatrix(list(map(float, eye)), list(map(float, target)), [0, 0, 1])
    proj = pb.computeProjectionMatrixFOV(fov_deg, width / height, 0.05, 20.0)
    img = pb.getCameraImage(width, height, view, proj, renderer=pb.ER_TINY_RENDERER, physicsClientId=client)
    rgba = np.asarray(img[2], dtype=np.uint8).reshape(height, width, 4)
    return rgba[:, :, :3].copy()
