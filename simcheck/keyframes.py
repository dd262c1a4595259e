"""Headless key-frame pictures and an optional animated GIF of a task (PyBullet's CPU tiny renderer via
:meth:`World.render`, PNG/GIF through Pillow -- a dependency we already have; no mp4 encoder is
installed, so the video is a GIF). Every file is written atomically (temporary file + rename): an
interrupted run leaves no partial PNG or GIF."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np

from scenes.description import write_with_atomic
from simcheck.key_frame_view import CAMERA_DISTANCE, CAMERA_HEIGHT, camera_distance
from simcheck.world import World

__all__ = ["KeyFrameCamera"]

log = logging.getLogger(__name__)


class KeyFrameCamera:
    """Takes pictures of a task in ``world``, aimed at ``target`` (3,) from the side ``toward`` (3,) points to,
    from as close as a part of ``part_size`` (m) allows (:func:`simcheck.key_frame_view.camera_distance`).

    ``out_dir``/``stem``_``label``.png are written on :meth:`snap`; with ``video=True`` a frame is also
    kept every ``video_every`` calls of :meth:`frame` and :meth:`save_video` writes ``stem``.gif.
    """

    def __init__(self, world: World, target: np.ndarray, toward: np.ndarray, out_dir: Path, stem: str,
                 size=(320, 240), video: bool = False, part_size: float | None = None) -> None:
        self.world, self.out_dir, self.stem, self.size, self.video = world, Path(out_dir), stem, size, video
        target = np.asarray(target, float)
        d = np.asarray(toward, float) - target
        d[2] = 0.0
        d = d / np.linalg.norm(d) if np.linalg.norm(d) > 1e-6 else np.array([1.0, 0.0, 0.0])
        side = np.array([-d[1], d[0], 0.0])
        self.target = target
        # the farthest view, 30 deg to the side; closer for a small part (part_size, m: the handle's path)
        scale = (camera_distance(part_size) if part_size is not None else CAMERA_DISTANCE) / CAMERA_DISTANCE
        self.eye = target + scale * (CAMERA_DISTANCE * d + 1.1 * side + np.array([0.0, 0.0, CAMERA_HEIGHT]))
        self.paths: list[Path] = []
        self.frames: list[np.ndarray] = []

    def _image(self) -> np.ndarray:
        return self.world.render(self.target, self.eye, *self.size)

    def snap(self, label: str) -> Path:
        """Write the current view as ``<stem>_<label>.png``; returns the path."""
        from PIL import Image
        self.out_dir.mkdir(parents=True, exist_ok=True)
        path = write_with_atomic(self.out_dir / f"{self.stem}_{label}.png",
                                 lambda tmp: Image.fromarray(self._image()).save(tmp, format="PNG"))
        self.paths.append(path)
        if self.video:
            self.frames.append(self._image())
        return path

    def frame(self) -> None:
        """Keep one video frame (only with ``video=True``)."""
        if self.video:
            self.frames.append(self._image())

    def save_video(self, fps: int = 10) -> Path | None:
        """Write the kept frames as ``<stem>.gif``; returns the path (None without frames)."""
        if not self.frames:
            return None
        from PIL import Image
        imgs = [Image.fromarray(f) for f in self.frames]
        return write_with_atomic(self.out_dir / f"{self.stem}.gif", lambda tmp: imgs[0].save(
            tmp, format="GIF", save_all=True, append_images=imgs[1:], duration=int(1000 / fps), loop=0))
