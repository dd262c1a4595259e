"""Scanner parameters: camera, path and degradations, with the ``clean``, ``realistic`` and ``scannet`` presets.

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

    ScanNet-style capture (each off at 0; ranges are (min, max) drawn uniformly per scan / object):
    the scan's frame is the world tilted ``frame_tilt_deg`` degrees about a random horizontal axis with
    the floor ``frame_floor_offset`` metres from its origin along the floor's normal (``Scan.T_scan_world``);
    each object's points are tilted about its bottom centre so that its up direction is
    ``object_tilt_deg`` degrees off the scan frame's z (the frame's tilt included: a fused
    reconstruction's warp); the camera pose drifts along the path by a random walk of ``drift_m`` metres
    and ``drift_deg`` degrees per frame (standard deviations); ``holes_per_m2`` holes per square metre of
    scanned surface, balls of radius ``hole_radius`` metres, are cut out. Segmentation-network label
    noise: a background point within ``background_bleed_width`` m of an object takes its label with
    probability ``background_bleed_prob``; ``fragments_per_object`` (Poisson mean) balls of radius
    ``fragment_radius`` m take another part's label of their object; with probability
    ``merge_fronts_prob`` a column of two or more drawer fronts carries one part id (the lowest drawer's;
    labels.json then lists the column as that one drawer).
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
    frame_tilt_deg: tuple[float, float] = (0.0, 0.0)
    frame_floor_offset: tuple[float, float] = (0.0, 0.0)
    object_tilt_deg: tuple[float, float] = (0.0, 0.0)
    drift_m: float = 0.0
    drift_deg: float = 0.0
    holes_per_m2: float = 0.0
    hole_radius: tuple[float, float] = (0.03, 0.10)
    background_bleed_width: float = 0.0
    background_bleed_prob: float = 0.0
    fragments_per_object: float = 0.0
    fragment_radius: tuple[float, float] = (0.02, 0.05)
    merge_fronts_prob: float = 0.0

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
            ("frame_tilt_deg", 0.0 <= self.frame_tilt_deg[0] <= self.frame_tilt_deg[1] <= 10.0),
            ("frame_floor_offset", -1.0 <= self.frame_floor_offset[0] <= self.frame_floor_offset[1] <= 1.0),
            ("object_tilt_deg", 0.0 <= self.object_tilt_deg[0] <= self.object_tilt_deg[1] <= 10.0),
            ("drift_m", self.drift_m >= 0), ("drift_deg", self.drift_deg >= 0),
            ("holes_per_m2", self.holes_per_m2 >= 0),
            ("hole_radius", 0.0 < self.hole_radius[0] <= self.hole_radius[1]),
            ("background_bleed_width", self.background_bleed_width >= 0),
            ("background_bleed_prob", 0.0 <= self.background_bleed_prob <= 1.0),
            ("fragments_per_object", self.fragments_per_object >= 0),
            ("fragment_radius", 0.0 < self.fragment_radius[0] <= self.fragment_radius[1]),
            ("merge_fronts_prob", 0.0 <= self.merge_fronts_prob <= 1.0),
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
    # ScanNet-style (issue 12): handles of 9-14 points, the floor 4-7 cm off the frame's origin and tilted
    # about 1 deg, objects 1.6-2.9 deg off the frame's z, drift, holes and a segmentation network's labels
    "scannet": ScanParams(depth_noise_base=0.0015, depth_noise_quadratic=0.002, missing_rate=0.08,
                          grazing_limit_deg=78.0, outlier_rate=0.002, outlier_range=0.3, label_boundary_width=0.02,
                          label_flip_prob=0.3, voxel_size=0.035, background_voxel=0.07, frame_tilt_deg=(0.8, 1.2),
                          frame_floor_offset=(0.04, 0.07), object_tilt_deg=(1.6, 2.9), drift_m=0.0005,
                          drift_deg=0.01, holes_per_m2=0.3, hole_radius=(0.03, 0.08), background_bleed_width=0.02,
                          background_bleed_prob=0.3, fragments_per_object=1.0, fragment_radius=(0.02, 0.04),
                          merge_fronts_prob=0.5),
}


def params_for_preset(preset: str, **overrides) -> ScanParams:
    """The preset's parameters with ``overrides`` (field=value) applied."""
    if preset not in PRESETS:
        raise ScanError(f"unknown scan preset {preset!r}; expected one of {', '.join(PRESETS)}")
    try:
        return dataclasses.replace(PRESETS[preset], **overrides)
    except TypeError as e:
        raise ScanError(f"bad scan parameter override for preset {preset!r}: {e}") from e
