"""Scanner parameters: camera, path and degradations, with the ``clean`` and ``realistic`` presets.

Depth noise is Gaussian along each ray with standard deviation ``sigma(r) = depth_noise_base +
depth_noise_quadratic * r**2`` (metres, r = range in metres; the realistic defaults follow the
Kinect-style model of Khoshelham & Elberink 2012, about 1 mm at 0.5 m and 9 mm at 2 m).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from ..errors import ScanError

__all__ = ["ScanParams", "PRESETS", "params_for_preset"]


@dataclass(frozen=True)
class ScanParams:
    """Everything the virtual RGB-D scanner does, with units.

    Camera: ``width`` x ``height`` pixels, horizontal field of view ``fov_deg`` degrees, ``max_range``
    metres (returns beyond it are missing). Path: ``n_frames`` views (at least ``frames_per_object`` x
    the number of objects, so big rooms get more views) from a person walking a loop
    ``path_inset`` metres inside the walls, camera height in ``camera_height`` (min, max) metres.
    Degradations (each off at 0): ``depth_noise_base`` m and ``depth_noise_quadratic`` 1/m (see the
    module doc); ``missing_rate`` probability a return is dropped; ``grazing_limit_deg``: returns whose
    incidence angle exceeds it are dropped; ``outlier_rate``: fraction of the final (downsampled) points
    moved along their ray by U(-``outlier_range``, ``outlier_range``) m (flying pixels, keeping their
    label);
    ``label_flip_prob``: probability that a point within ``label_boundary_width`` m of another part of
    the same object takes that part's label. Downsampling: one real return is kept per ``voxel_size``
    cube on objects and per ``background_voxel`` cube on the floor/walls (0 = keep all).
    """

    width: int = 256
    height: int = 192
    fov_deg: float = 70.0
    max_range: float = 6.0
    n_frames: int = 40
    frames_per_object: int = 4
    path_inset: float = 1.0
    camera_height: tuple[float, float] = (1.2, 1.7)
    depth_noise_base: float = 0.0
    depth_noise_quadratic: float = 0.0
    missing_rate: float = 0.0
    grazing_limit_deg: float = 90.0
    outlier_rate: float = 0.0
    outlier_range: float = 0.3
    label_boundary_width: float = 0.0
    label_flip_prob: float = 0.0
    voxel_size: float = 0.01
    background_voxel: float = 0.05
    include_background: bool = True

    def __post_init__(self):
        checks = [
            ("width", self.width >= 8), ("height", self.height >= 8),
            ("fov_deg", 10.0 <= self.fov_deg <= 150.0), ("max_range", self.max_range > 0),
            ("n_frames", self.n_frames >= 1), ("frames_per_object", self.frames_per_object >= 0),
            ("path_inset", self.path_inset >= 0),
            ("camera_height", 0.0 < self.camera_height[0] <= self.camera_height[1]),
            ("depth_noise_base", self.depth_noise_base >= 0),
            ("depth_noise_quadratic", self.depth_noise_quadratic >= 0),
            ("missing_rate", 0.0 <= self.missing_rate < 1.0),
            ("grazing_limit_deg", 0.0 < self.grazing_limit_deg <= 90.0),
            ("outlier_rate", 0.0 <= self.outlier_rate < 1.0), ("outlier_range", self.outlier_range >= 0),
            ("label_boundary_width", self.label_boundary_width >= 0),
            ("label_flip_prob", 0.0 <= self.label_flip_prob <= 1.0),
            ("voxel_size", self.voxel_size >= 0), ("background_voxel", self.background_voxel >= 0),
        ]
        for name, ok in checks:
            if not ok:
                raise ScanError(f"scan parameter {name}={getattr(self, name)!r} is out of range")


PRESETS = {
    "clean": ScanParams(),
    "realistic": ScanParams(depth_noise_base=0.0012, depth_noise_quadratic=0.0019, missing_rate=0.05,
                            grazing_limit_deg=80.0, outlier_rate=0.002, outlier_range=0.3,
                            label_boundary_width=0.015, label_flip_prob=0.3, voxel_size=0.012,
                            background_voxel=0.07),
}


def params_for_preset(preset: str, **overrides) -> ScanParams:
    """The preset's parameters with ``overrides`` (field=value) applied."""
    if preset not in PRESETS:
        raise ScanError(f"unknown scan preset {preset!r}; expected one of {', '.join(PRESETS)}")
    try:
        return dataclasses.replace(PRESETS[preset], **overrides)
    except TypeError as e:
        raise ScanError(f"bad scan parameter override for preset {preset!r}: {e}") from e
