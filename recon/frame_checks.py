"""Is the scan z-up, the right way up and in metres? Messages for a scan that is not.

* Orientation (:func:`frame_problem`): the floor found by :func:`recon.leveling.find_floor` must lie
  under the labelled objects, its normal within ``max_floor_tilt_deg`` of +z. Above them the scan is
  upside down; beside them (or more tilted) it is not z-up. ``level_floor`` rotates such a scan level.
* Scale (:func:`scale_problems`): in the floor frame (z up), no object may be more than
  :data:`UNIT_ERROR_MARGIN` times taller or longer than the largest real object of its category
  (:data:`MAX_SIZE`, generous bounds from furniture ranges: a kitchen run of cabinets, a conference
  table, a bunk bed). A wrong unit scales everything by 10 or more (centimetres 100, inches 39.4);
  the margin keeps what a real segmentation lumps with an object (a microwave's stand, a cabinet's
  plinth) from looking like one. Nor may every object of a category we know be smaller than
  :data:`MIN_SIZE` over the margin (a scan scaled down by 10 or more: kilometres, decimetres,
  a room normalised into a unit box); one small object among real-sized ones is a fragment, not a unit.

The messages name the scan, the evidence and the fix; the pipeline raises them as
:class:`recon.errors.ScanError` (``recon build`` exits 2).
"""

from __future__ import annotations

import numpy as np

from recon.config import LevelingConfig
from recon.leveling import Floor
from recon.scan import Scan

__all__ = ["MAX_SIZE", "MIN_SIZE", "UNIT_ERROR_MARGIN", "frame_problem", "scale_problems"]

MAX_SIZE = {
    "cabinet": (6.0, 2.8), "wardrobe": (4.5, 2.8), "shelf": (6.0, 3.0), "refrigerator": (2.0, 2.4),
    "microwave": (1.0, 0.8), "oven": (1.6, 2.4), "dishwasher": (1.0, 1.0), "table": (6.0, 1.3),
    "desk": (3.5, 2.2), "chair": (1.5, 1.6), "sofa": (4.5, 1.5), "bed": (3.0, 2.5),
}
"""{category: (longest side on the floor, height)}, metres: larger than any real object of the category."""
DEFAULT_MAX_SIZE = (8.0, 3.5)
"""... of a category not in :data:`MAX_SIZE` (a room is rarely taller)."""
MIN_SIZE = {
    "cabinet": 0.2, "wardrobe": 0.8, "shelf": 0.2, "refrigerator": 0.4, "microwave": 0.3, "oven": 0.4,
    "dishwasher": 0.4, "table": 0.4, "desk": 0.6, "chair": 0.4, "sofa": 0.8, "bed": 1.0,
}
"""{category: largest dimension (longest side on the floor or height), metres}: shorter than any real object
of the category (a wall-hung spice cabinet, a mini fridge, a side table, a stool, a crib)."""
UNIT_ERROR_MARGIN = 2.0
"""An object is implausibly scaled beyond this multiple of :data:`MAX_SIZE` (a unit error is at least 10)."""
_PERCENTILES = (2.0, 98.0)
"""An object's extent is measured between these percentiles of its points (label noise, flying pixels)."""


def _vec(v: np.ndarray) -> str:
    return "(" + ", ".join(f"{x:+.2f}" for x in v) + ")"


def frame_problem(floor: Floor, config: LevelingConfig, source: str) -> str | None:
    """Why a scan whose floor is ``floor`` (in the scan's frame) is not z-up, or None when it is (or when
    no floor was found: nothing to judge by)."""
    if not floor.found:
        return None
    tilt = floor.tilt_deg
    if tilt <= config.max_floor_tilt_deg:
        return None
    seen = f"its floor ({floor.n_points} background points, normal toward the objects {_vec(floor.normal)})"
    fix = "pass --level-floor to rotate it level on its floor"
    if tilt >= 180.0 - config.max_floor_tilt_deg:
        return (f"{source}: the scan is upside down: {seen} lies above the labelled objects, {tilt:.0f} deg "
                f"from +z; turn it over (z -> -z, and y -> -y to keep it right-handed) or {fix}")
    k = int(np.argmax(np.abs(floor.normal)))
    axis = ("+" if floor.normal[k] > 0 else "-") + "xyz"[k]
    where = "under" if tilt < 45 else "beside" if tilt <= 135 else "above"
    looks = f"; the scan looks {axis}-up" if k != 2 else ""
    return (f"{source}: the scan is not z-up: {seen} lies {where} the labelled objects, {tilt:.0f} deg from +z "
            f"(at most {config.max_floor_tilt_deg:g} deg is taken as a floor){looks}; rotate it so that z is up "
            f"or {fix}")


def _extents(points: np.ndarray) -> tuple[float, float]:
    """(longest horizontal side, height), m, of ``points`` (n, 3) in a z-up frame, between
    :data:`_PERCENTILES`."""
    lo, hi = _PERCENTILES
    z = np.percentile(points[:, 2], [lo, hi])
    xy = points[:, :2] - points[:, :2].mean(axis=0)
    axes = np.linalg.svd(xy, full_matrices=False)[2] if len(xy) > 2 else np.eye(2)
    q = xy @ axes.T
    side = np.percentile(q, hi, axis=0) - np.percentile(q, lo, axis=0)
    return float(side.max()), float(z[1] - z[0])


def scale_problems(scan: Scan, source: str) -> str | None:
    """Why the objects of ``scan`` (floor frame, z up) cannot be in metres, or None: the objects
    larger than any of their category, named with their sizes, or every object of a known category
    smaller than any real one."""
    big, small, known = [], [], 0
    for o in scan.objects:
        if not o.parts:
            continue
        side, height = _extents(np.concatenate([p.points for p in o.parts]))
        max_side, max_height = (UNIT_ERROR_MARGIN * m for m in MAX_SIZE.get(o.category, DEFAULT_MAX_SIZE))
        if side > max_side or height > max_height:
            big.append(f"object {o.id} ({o.category}) is {height:.2f} m tall and {side:.2f} m long (no {o.category} "
                       f"is taller than {max_height:g} m or longer than {max_side:g} m)")
        if o.category in MIN_SIZE:
            known += 1
            least = MIN_SIZE[o.category] / UNIT_ERROR_MARGIN
            if max(side, height) < least:
                small.append(f"object {o.id} ({o.category}) is {height:.3f} m tall and {side:.3f} m long (no "
                             f"{o.category} is under {least:g} m in every direction)")
    fix = "The scan must be in metres: scale its coordinates to metres"
    if big:
        return (f"{source}: implausibly scaled: {len(big)} of {len(scan.objects)} objects are larger than any of "
                f"their category: {'; '.join(big[:3])}{'; ...' if len(big) > 3 else ''}. {fix} (a scan in "
                "centimetres or scaled by 10 looks like this)")
    if small and len(small) == known:
        return (f"{source}: implausibly scaled: every object is smaller than any real one of its category: "
                f"{'; '.join(small[:3])}"
                f"{'; ...' if len(small) > 3 else ''}. {fix} (a scan scaled down by 10 or more, or normalised into a "
                "unit box, looks like this)")
    return None
