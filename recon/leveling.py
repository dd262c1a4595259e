"""The floor of a scan: its plane (height and tilt), found among the background points, and the rigid
transform that levels it.

Candidates are the ``floor_candidates`` largest RANSAC planes (open3d) of the background points (object
id -1: floor, walls, clutter). Walls are large planes too, so each candidate's normal is oriented toward
the labelled objects and the floor is the candidate that

1. agrees best with the parts that show which way is up (:func:`upright_share`: drawer and door fronts
   are vertical panels, table tops, seats, mattresses and shelves horizontal ones, legs vertical bars),
2. then is touched by the most objects from one side (95 % of their points on the room's side, three
   within ``support_distance``: furniture stands on the floor; only some of it touches a wall),
3. then has the most points.

A candidate no object touches, or that fewer than half of the parts' votes agree with, is not a floor. The floor is reported in the scan's frame whatever its
direction: :mod:`recon.frame_checks` decides whether the scan is z-up, upside down or sideways.

Frames: a :class:`Floor` is given in one frame (the scan's, or the output's); ``normal`` is the unit
normal pointing into the room (toward the objects), ``height_m`` the plane's offset from the frame's
origin along that normal (``normal · p = height_m`` on the floor: for a level floor, its z).
:meth:`Floor.T_floor_frame` rotates by the floor's tilt only (the shortest rotation taking ``normal``
onto +z) and then moves the floor down to z = 0: in the floor frame the floor is z = 0, z up.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from recon.config import LevelingConfig, SceneConfig
from recon.scan import Scan
from scenes.description import R_onto_up

__all__ = ["Floor", "find_floor", "upright_share"]

_UP = np.array([0.0, 0.0, 1.0])

_VERTICAL_PANELS = frozenset({"drawer", "door"})
"""Labels of parts that are vertical panels (fronts): their normal is horizontal."""
_HORIZONTAL_PANELS = frozenset({"top", "seat", "mattress", "shelf"})
"""Labels of parts that are horizontal panels: their normal is vertical."""
_VERTICAL_BARS = frozenset({"leg"})
"""Labels of parts that are vertical bars: their long axis is vertical."""
_MIN_VOTE_POINTS = 30
"""A part votes on the up direction from this many points."""
_THIN = 0.35
"""A panel is at most this thick relative to its middle extent; a bar at most this wide relative to
its length (ratios of principal extents)."""
_MIN_UPRIGHT_SHARE = 0.5
"""A plane that fewer of the parts' votes agree with is not a floor (a wall behind a row of fronts)."""
_COS_ALONG = np.cos(np.radians(25.0))
"""A direction within 25 deg of another counts as along it ..."""
_COS_ACROSS = np.cos(np.radians(65.0))
"""... and one more than 65 deg from it as across it."""


@dataclass(frozen=True, eq=False)
class Floor:
    """A floor plane in one frame.

    normal : (3,) unit, pointing into the room (toward the objects), in the frame
    height_m : the plane's offset (m) from the frame's origin along ``normal`` (normal · p = height_m on
        the floor; for a level floor, its z)
    n_points : background points it was fitted to; 0 = no floor was found and the frame's z = 0 plane
        is assumed
    """

    normal: np.ndarray
    height_m: float
    n_points: int = 0

    def __post_init__(self):
        n = np.asarray(self.normal, dtype=np.float64).reshape(3)
        object.__setattr__(self, "normal", n / np.linalg.norm(n))
        object.__setattr__(self, "height_m", float(self.height_m))
        object.__setattr__(self, "n_points", int(self.n_points))

    @classmethod
    def assumed(cls) -> "Floor":
        """The frame's own z = 0 plane (no floor points to estimate it from)."""
        return cls(_UP, 0.0, 0)

    def levelled(self) -> "Floor":
        """The same floor taken as level: normal +z, at its height at the origin."""
        return Floor(_UP, self.height_m, self.n_points)

    @property
    def found(self) -> bool:
        return self.n_points > 0

    @property
    def tilt_deg(self) -> float:
        """Angle (deg) between the floor's normal and the frame's +z: 0 level, 180 upside down."""
        return float(np.degrees(np.arccos(np.clip(self.normal[2], -1.0, 1.0))))

    def T_floor_frame(self) -> np.ndarray:
        """(4, 4) rigid transform from this frame into the floor frame (floor z = 0, normal +z): the
        shortest rotation by the tilt about the origin, then down by ``height_m``."""
        T = np.eye(4)
        T[:3, :3] = R_onto_up(self.normal)
        T[2, 3] = -self.height_m
        return T

    def transformed(self, T_new_old: np.ndarray) -> "Floor":
        """The same plane in the frame ``T_new_old`` (4, 4) maps this one into."""
        n = T_new_old[:3, :3] @ self.normal
        return Floor(n, self.height_m + float(n @ T_new_old[:3, 3]), self.n_points)

    def as_dict(self) -> dict:
        """graph.json's ``floor``: {"height_m", "tilt_deg", "normal", "n_points"}."""
        return {"height_m": self.height_m, "tilt_deg": self.tilt_deg, "normal": self.normal.tolist(),
                "n_points": self.n_points}

    @classmethod
    def from_dict(cls, d: dict) -> "Floor":
        return cls(np.asarray(d["normal"], dtype=np.float64), float(d["height_m"]), int(d.get("n_points", 0)))


def _part_votes(scan: Scan) -> list[tuple[str, np.ndarray]]:
    """(kind, unit axis) per part that shows the up direction: ("across", a panel's normal, which is
    vertical for a horizontal panel), ("level", a front's normal, horizontal) or ("along", a leg's axis)."""
    votes = []
    for o in scan.objects:
        for p in o.parts:
            kind = ("level" if p.label in _VERTICAL_PANELS else "across" if p.label in _HORIZONTAL_PANELS
                    else "along" if p.label in _VERTICAL_BARS else None)
            if kind is None or len(p.points) < _MIN_VOTE_POINTS:
                continue
            c = p.points - p.points.mean(axis=0)
            _, s, vt = np.linalg.svd(c, full_matrices=False)
            if kind == "along":
                if s[1] <= _THIN * s[0]:
                    votes.append((kind, vt[0]))
            elif s[2] <= _THIN * s[1]:
                votes.append((kind, vt[2]))
    return votes


def upright_share(votes: list[tuple[str, np.ndarray]], up: np.ndarray) -> float:
    """The share of ``votes`` (:func:`_part_votes`) that agree with the direction ``up`` (3,) unit:
    a horizontal panel's normal and a leg's axis along it, a front's normal across it (1.0 without votes)."""
    if not votes:
        return 1.0
    ok = 0
    for kind, axis in votes:
        c = abs(float(axis @ up))
        ok += c >= _COS_ALONG if kind in ("across", "along") else c <= _COS_ACROSS
    return ok / len(votes)


def find_floor(scan: Scan, config: LevelingConfig, scene: SceneConfig, seed: int = 0) -> Floor:
    """The floor of ``scan`` in its own frame (see the module docstring), whatever its direction;
    :meth:`Floor.assumed` when the background holds no plane that an object touches."""
    from recon.open3d_engine import segment_planes

    rng = np.random.default_rng(seed)
    bg = scan.points[scan.object_id < 0]
    if len(bg) < config.floor_min_points or not scan.objects:
        return Floor.assumed()
    if len(bg) > config.floor_max_points:
        bg = bg[np.sort(rng.choice(len(bg), config.floor_max_points, replace=False))]
    planes = segment_planes(bg, distance=config.floor_ransac_distance, count=config.floor_candidates, seed=seed,
                            min_inliers=config.floor_min_points)
    objects = []
    for o in scan.objects:
        pts = np.concatenate([p.points for p in o.parts]) if o.parts else np.zeros((0, 3))
        if len(pts) > 2000:
            pts = pts[np.sort(rng.choice(len(pts), 2000, replace=False))]
        if len(pts):
            objects.append(pts)
    if not objects:
        return Floor.assumed()
    every = np.concatenate(objects)
    votes = _part_votes(scan)
    best = None
    for plane, inliers in planes:
        n, d = plane[:3], float(plane[3])
        if np.median(every @ n + d) < 0:
            n, d = -n, -d
        touching = 0
        for pts in objects:
            s = pts @ n + d
            if np.mean(s > -2 * config.floor_ransac_distance) > 0.95 and np.sort(s)[min(2, len(s) - 1)] < scene.support_distance:
                touching += 1
        share = upright_share(votes, n)
        if touching == 0 or share < _MIN_UPRIGHT_SHARE:
            continue
        key = (round(share, 1), touching, len(inliers))
        if best is None or key > best[0]:
            best = (key, n, d, bg[inliers])
    if best is None:
        return Floor.assumed()
    _, n, d, inl = best
    # RANSAC's plane is from 3 points and its inlier band is centred on it: refit by least squares, then
    # take the band again around the refit (twice), the offset as the band's median distance
    c = -d
    for _ in range(3):
        centre = inl.mean(axis=0)
        m = np.linalg.svd(inl - centre, full_matrices=False)[2][2]
        n = m if m @ n > 0 else -m
        c = float(np.median(inl @ n))
        inl = bg[np.abs(bg @ n - c) < config.floor_ransac_distance]
    return Floor(n, c, len(inl))
