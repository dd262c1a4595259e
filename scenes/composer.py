"""Place objects in a rectangular room without overlap: against walls, in the open, on top of others.

The room's inner floor is ``[-lx/2, lx/2] x [-ly/2, ly/2]`` at z = 0, with four box walls outside it
(``wall_north`` at +y, ``wall_south`` at -y, ``wall_east`` at +x, ``wall_west`` at -x). An object's
keep-out (footprint + the sweep of its opening parts + ``front_clearance`` of free floor in front of an
articulated object, see :mod:`scenes.footprints`) may not meet another object's footprint, and every
keep-out stays inside the room. Objects on a support only have to fit on its top.
"""

from __future__ import annotations

import logging

import numpy as np
from shapely.affinity import affine_transform
from shapely.geometry import Polygon

from .config import DEFAULT_COMPOSER, ComposerConfig
from .errors import PlacementError
from .footprints import footprint, keepout, room_polygon
from .model import ArticulatedObject, Scene, Wall
from .description import pose, transform_points

__all__ = ["WALLS", "RoomComposer"]

log = logging.getLogger(__name__)

# wall name -> (inward normal, yaw that makes an object's +x face into the room)
WALLS = {
    "wall_north": (np.array([0.0, -1.0]), -np.pi / 2),
    "wall_south": (np.array([0.0, 1.0]), np.pi / 2),
    "wall_east": (np.array([-1.0, 0.0]), np.pi),
    "wall_west": (np.array([1.0, 0.0]), 0.0),
}


class RoomComposer:
    """Builds a :class:`~scenes.model.Scene` object by object (ids 1, 2, ...; part ids unique in the scene).

    Every placement draws from ``rng`` and raises :class:`~scenes.errors.PlacementError` (naming the
    scene and the object) when ``cfg.max_tries`` random candidates all collide.
    """

    def __init__(self, name: str, seed: int, room_size, rng: np.random.Generator,
                 cfg: ComposerConfig = DEFAULT_COMPOSER):
        self.name, self.seed, self.cfg, self.rng = name, int(seed), cfg, rng
        self.room_size = np.asarray(room_size, float)
        self.room = room_polygon(self.room_size)
        self.objects: list[ArticulatedObject] = []
        self._fp: dict[int, Polygon] = {}
        self._ko: dict[int, Polygon] = {}
        self._local: dict[int, tuple[tuple, Polygon, Polygon]] = {}
        self._next_part = 1

    # ------------------------------------------------------------------ checks
    def _polygons(self, cand: ArticulatedObject) -> tuple[Polygon, Polygon]:
        """(footprint, keep-out) of ``cand`` in the world: computed once in the object frame, then moved."""
        key = id(cand.parts)
        if key not in self._local or self._local[key][0] is not cand.parts:   # ids can be reused
            local = cand.placed(np.eye(4))
            self._local[key] = (cand.parts, footprint(local),
                                keepout(local, self.cfg.front_clearance, self.cfg.robot_reach))
        T = cand.T_world_object
        m = [T[0, 0], T[0, 1], T[1, 0], T[1, 1], T[0, 3], T[1, 3]]
        _, fp, ko = self._local[key]
        return affine_transform(fp, m), affine_transform(ko, m)

    def _fits(self, cand: ArticulatedObject, support: int | None) -> bool:
        fp, ko = self._polygons(cand)
        if support is not None:
            top = self._fp[support].buffer(1e-6)
            if not top.contains(fp):
                return False
        if not self.room.buffer(1e-6).contains(ko):
            return False
        fpg = fp.buffer(self.cfg.object_gap)
        for o in self.objects:
            if o.id == support:
                continue
            if fpg.intersects(self._ko[o.id]) or ko.intersects(self._fp[o.id].buffer(self.cfg.object_gap)):
                return False
        return True

    def _add(self, obj: ArticulatedObject) -> int:
        self.objects.append(obj)
        self._fp[obj.id], self._ko[obj.id] = self._polygons(obj)
        self._next_part += len(obj.parts)
        log.debug("%s: placed %s at %s", self.name, obj.name, np.round(obj.T_world_object[:3, 3], 3))
        return obj.id

    def _numbered(self, obj: ArticulatedObject) -> ArticulatedObject:
        return obj.renumbered(len(self.objects) + 1, self._next_part)

    def _fail(self, obj: ArticulatedObject, where: str) -> PlacementError:
        return PlacementError(f"scene {self.name!r} (seed {self.seed}): could not place {obj.name} "
                              f"({where}) without overlap in {self.cfg.max_tries} tries")

    # ------------------------------------------------------------------ placements
    def against_wall(self, obj: ArticulatedObject, walls: tuple[str, ...] | None = None) -> int:
        """Put ``obj`` with its back against one of ``walls`` (default: any), facing into the room."""
        obj = self._numbered(obj)
        names = tuple(walls or WALLS)
        lo, hi = obj.bounds()
        lx, ly = self.room_size
        for _ in range(self.cfg.max_tries):
            wname = names[int(self.rng.integers(len(names)))]
            n, yaw = WALLS[wname]
            half_len = (lx if n[0] == 0 else ly) / 2
            back = -lo[0] + self.cfg.wall_gap
            span = half_len - max(-lo[1], hi[1]) - 0.01
            if span <= 0:
                continue
            s = float(self.rng.uniform(-span, span))
            if n[0] == 0:
                p = np.array([0.0, -n[1] * ly / 2]) + back * n + s * np.array([1.0, 0.0])
            else:
                p = np.array([-n[0] * lx / 2, 0.0]) + back * n + s * np.array([0.0, 1.0])
            cand = obj.placed(pose([p[0], p[1], 0.0], yaw=yaw))
            if self._fits(cand, None):
                return self._add(cand)
        raise self._fail(obj, f"against {names}")

    def in_open(self, obj: ArticulatedObject, yaws=(0.0, np.pi / 2, np.pi, -np.pi / 2),
                region: Polygon | None = None) -> int:
        """Put ``obj`` anywhere on the free floor (optionally inside ``region``) with one of ``yaws``."""
        obj = self._numbered(obj)
        minx, miny, maxx, maxy = (region or self.room).bounds
        for _ in range(self.cfg.max_tries):
            yaw = float(yaws[int(self.rng.integers(len(yaws)))])
            p = self.rng.uniform([minx, miny], [maxx, maxy])
            cand = obj.placed(pose([p[0], p[1], 0.0], yaw=yaw))
            if self._fits(cand, None):
                return self._add(cand)
        raise self._fail(obj, "in the open")

    def on_top(self, obj: ArticulatedObject, support_id: int, front_setback: float = 0.03) -> int:
        """Put ``obj`` on the top of object ``support_id``, facing the same way, front near its front."""
        obj = self._numbered(obj)
        sup = next(o for o in self.objects if o.id == support_id)
        root = sup.root
        pts = np.vstack([transform_points(root.T_object_part, s.corners()) for s in root.shapes])
        s_lo, s_hi = pts.min(0), pts.max(0)
        lo, hi = obj.bounds()
        x = s_hi[0] - front_setback - hi[0]
        span = (s_hi[1] - s_lo[1]) / 2 - max(-lo[1], hi[1]) - 0.02
        for _ in range(self.cfg.max_tries):
            y = (s_lo[1] + s_hi[1]) / 2 + (float(self.rng.uniform(-span, span)) if span > 0 else 0.0)
            T = sup.T_world_object @ pose([x, y, s_hi[2]])
            cand = obj.placed(T, supported_by=support_id)
            if self._fits(cand, support_id):
                return self._add(cand)
        raise self._fail(obj, f"on object {support_id}")

    def around(self, chairs: list[ArticulatedObject], table_id: int, gap: float = 0.08) -> list[int]:
        """Put chairs at the free sides of table ``table_id`` facing it; returns the ids placed."""
        table = next(o for o in self.objects if o.id == table_id)
        lo, hi = table.bounds()
        sides = [(np.array([hi[0], 0.0]), np.pi), (np.array([lo[0], 0.0]), 0.0),
                 (np.array([0.0, hi[1]]), -np.pi / 2), (np.array([0.0, lo[1]]), np.pi / 2)]
        order = self.rng.permutation(len(sides))
        placed = []
        for chair in chairs:
            for k in order:
                c = self._numbered(chair)
                edge, yaw_local = sides[k]
                clo, chi = c.bounds()
                off = edge + (np.sign(edge) * (chi[0] + gap) if np.any(edge) else 0)
                T = table.T_world_object @ pose([off[0], off[1], 0.0], yaw=yaw_local)
                cand = c.placed(T)
                if self._fits(cand, None):
                    placed.append(self._add(cand))
                    order = [i for i in order if i != k]
                    break
        return placed

    # ------------------------------------------------------------------ result
    def walls(self) -> tuple[Wall, ...]:
        lx, ly = self.room_size
        th, h = self.cfg.wall_thickness, self.cfg.wall_height
        return (
            Wall("wall_north", np.array([lx + 2 * th, th, h]), pose([0, ly / 2 + th / 2, h / 2])),
            Wall("wall_south", np.array([lx + 2 * th, th, h]), pose([0, -ly / 2 - th / 2, h / 2])),
            Wall("wall_east", np.array([th, ly, h]), pose([lx / 2 + th / 2, 0, h / 2])),
            Wall("wall_west", np.array([th, ly, h]), pose([-lx / 2 - th / 2, 0, h / 2])),
        )

    def build(self) -> Scene:
        return Scene(self.name, self.seed, tuple(self.objects), self.walls(), self.room_size.copy())
