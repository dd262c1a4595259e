"""Does a fitted shape cover its points? Three measures per part, checked against ``CoverageConfig``.

For a part's scan points P (n, 3) and its primitive M (world frame, metres):

- ``mean_distance`` (m): mean over P of the distance to the surface of M (a point deep inside an
  oversized box is far from its surface, so an oversized or misplaced shape scores high);
- ``near_fraction``: the share of P inside M or near its surface: within ``coverage_near_distance``, or
  within ``coverage_noise_sigmas`` times the points' depth noise when that is more (the robust spread of
  P across the face of its own oriented box that holds most of it, :mod:`recon.depth_noise`: measured on
  the points alone, so a wrong shape cannot widen its own tolerance);
- ``volume_ratio``: volume of the shape Eq. 3 fitted to the points (before completion extended it and
  without the template shapes completed behind a seen front) over the volume of the points' oriented
  box (extents floored at ``coverage_min_extent``: a face seen alone has no thickness).

A part outside the bounds gets a warning naming it and the measure that failed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from recon.bounding import oriented_box
from recon.config import CoverageConfig
from recon.depth_noise import seen_face
from recon.primitive import Primitive

__all__ = ["Coverage", "coverage", "coverage_problems"]


@dataclass(frozen=True)
class Coverage:
    """mean_distance : m; near_fraction : 0..1; volume_ratio : fitted volume / points' box volume;
    near_distance : m, how near the surface a point counted as covered."""

    mean_distance: float
    near_fraction: float
    volume_ratio: float
    near_distance: float = float("nan")


def coverage(prim: Primitive, fitted: Primitive, points: np.ndarray, config: CoverageConfig,
             normals: np.ndarray | None = None) -> Coverage:
    """The coverage of ``points`` (n, 3) world by ``prim`` (the part's final primitive) and the volume
    of ``fitted`` (its Eq. 3 primitive) against the points' oriented box. ``normals`` (n, 3) world unit,
    optional: the points' normals, which tell the depth noise's face (:func:`recon.depth_noise.seen_face`).
    NaN measures for n < 3."""
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if len(points) < 3:
        return Coverage(float("nan"), float("nan"), float("nan"))
    box = oriented_box(points, min_thickness=config.coverage_min_extent, upright_tolerance=0.0)
    ext = np.maximum(box.extents, config.coverage_min_extent)
    R = box.T_world_box[:3, :3]
    q = (points - box.T_world_box[:3, 3]) @ R
    n_box = None if normals is None or len(normals) != len(points) else np.asarray(normals, dtype=np.float64) @ R
    noise = (seen_face(q, ext, config.coverage_noise_face_points, n_box).sigma
             if len(points) >= config.coverage_noise_min_points else 0.0)
    within = max(config.coverage_near_distance, config.coverage_noise_sigmas * noise)
    d = prim.surface_distance(points)
    near = (d <= within) | prim.contains(points)
    return Coverage(float(d.mean()), float(near.mean()), float(fitted.volume / np.prod(ext)), within)


def coverage_problems(cov: Coverage, config: CoverageConfig) -> list[str]:
    """What is outside the bounds, one phrase each (empty when the fit covers its points)."""
    out = []
    if cov.mean_distance > config.max_mean_surface_distance:
        out.append(f"mean point-to-surface distance {cov.mean_distance * 1000:.0f} mm "
                   f"(at most {config.max_mean_surface_distance * 1000:.0f} mm)")
    if cov.near_fraction < config.min_near_fraction:
        out.append(f"{cov.near_fraction:.0%} of its points on or inside it (within {cov.near_distance * 1000:.0f} mm; "
                   f"at least {config.min_near_fraction:.0%})")
    if cov.volume_ratio > config.max_volume_ratio:
        out.append(f"{cov.volume_ratio:.1f}x the volume of its points' oriented box (at most "
                   f"{config.max_volume_ratio:.1f}x)")
    return out
