"""Named built-in scenes (``kitchen``, ``bedroom``, ``office``, ``studio``) and ``random``.

Each recipe draws every size, layout and position from ``numpy.random.default_rng([seed, attempt])``;
if a draw cannot be placed without overlap the next attempt is tried (deterministically), up to
``MAX_ATTEMPTS``.
"""

from __future__ import annotations

import logging
from typing import Callable

import numpy as np

from .composer import RoomComposer
from .config import DEFAULT_COMPOSER, DEFAULT_GENERATOR, ComposerConfig, GeneratorConfig
from .errors import PlacementError, SceneSpecError
from .generators import (MIXED_CABINET_LAYOUTS, make_bed, make_cabinet, make_chair, make_microwave,
                         make_refrigerator, make_table)
from .model import Scene
from .validate import validate_scene

__all__ = ["SCENES", "SCENE_DESCRIPTIONS", "build_scene", "MAX_ATTEMPTS"]

log = logging.getLogger(__name__)
MAX_ATTEMPTS = 8


def _chairs(rng, n: int, gcfg: GeneratorConfig):
    return [make_chair(rng, arms=False, cfg=gcfg) for _ in range(n)]


def _kitchen(c: RoomComposer, rng: np.random.Generator, g: GeneratorConfig) -> None:
    layout = MIXED_CABINET_LAYOUTS[int(rng.integers(len(MIXED_CABINET_LAYOUTS)))]
    cab = c.against_wall(make_cabinet(rng, layout, g), ("wall_north", "wall_west"))
    c.on_top(make_microwave(rng, g), cab)
    c.against_wall(make_refrigerator(rng, cfg=g))
    if rng.random() < 0.5:
        c.against_wall(make_cabinet(rng, ("drawer_stack", "doors")[int(rng.integers(2))], g))
    table = c.in_open(make_table(rng, cfg=g))
    placed = c.around(_chairs(rng, int(rng.integers(2, 5)), g), table)
    if not placed:
        raise PlacementError(f"scene {c.name!r}: no chair fits around the table")


def _bedroom(c: RoomComposer, rng: np.random.Generator, g: GeneratorConfig) -> None:
    c.against_wall(make_bed(rng, g), ("wall_north", "wall_south"))
    c.against_wall(make_cabinet(rng, "drawer_stack", g))
    c.against_wall(make_cabinet(rng, ("doors", "drawers_over_doors")[int(rng.integers(2))], g))
    desk = c.against_wall(make_table(rng, pedestal=False, cfg=g))
    c.around([make_chair(rng, cfg=g)], desk)


def _office(c: RoomComposer, rng: np.random.Generator, g: GeneratorConfig) -> None:
    cab = c.against_wall(make_cabinet(rng, ("drawers_doors", "door_drawers_door")[int(rng.integers(2))], g))
    if rng.random() < 0.5:
        c.on_top(make_microwave(rng, g), cab)
    c.against_wall(make_cabinet(rng, "drawer_stack", g))
    desk = c.in_open(make_table(rng, pedestal=False, cfg=g))
    c.around([make_chair(rng, arms=True, cfg=g), make_chair(rng, cfg=g)], desk)


def _studio(c: RoomComposer, rng: np.random.Generator, g: GeneratorConfig) -> None:
    cab = c.against_wall(make_cabinet(rng, MIXED_CABINET_LAYOUTS[int(rng.integers(3))], g))
    c.on_top(make_microwave(rng, g), cab)
    c.against_wall(make_cabinet(rng, cfg=g))
    c.against_wall(make_cabinet(rng, cfg=g))
    c.against_wall(make_refrigerator(rng, cfg=g))
    c.against_wall(make_bed(rng, g))
    table = c.in_open(make_table(rng, pedestal=False, cfg=g))
    if len(c.around(_chairs(rng, 4, g), table)) < 3:
        raise PlacementError(f"scene {c.name!r}: fewer than 3 chairs fit around the table")


def _random(c: RoomComposer, rng: np.random.Generator, g: GeneratorConfig) -> None:
    n = int(rng.integers(3, 7))
    cabinets = []
    for _ in range(n):
        kind = ("cabinet", "cabinet", "refrigerator", "bed", "table")[int(rng.integers(5))]
        if kind == "cabinet":
            cabinets.append(c.against_wall(make_cabinet(rng, cfg=g)))
        elif kind == "refrigerator":
            c.against_wall(make_refrigerator(rng, cfg=g))
        elif kind == "bed":
            c.against_wall(make_bed(rng, g))
        else:
            t = c.in_open(make_table(rng, cfg=g))
            c.around(_chairs(rng, int(rng.integers(1, 4)), g), t)
    for cab in cabinets[:1]:
        c.on_top(make_microwave(rng, g), cab)


_RECIPES: dict[str, tuple[Callable, tuple[float, float], tuple[float, float], str]] = {
    "kitchen": (_kitchen, (5.0, 6.0), (4.2, 5.0),
                "mixed drawer/door cabinet with a microwave on it, refrigerator, table and chairs"),
    "bedroom": (_bedroom, (4.5, 5.5), (4.0, 5.0), "bed, chest of drawers, door cabinet, desk and chair"),
    "office": (_office, (4.5, 5.5), (4.0, 5.0), "cabinets (one maybe with a microwave), desk and chairs"),
    "studio": (_studio, (7.0, 8.0), (6.0, 7.0),
               "a large room of 10+ objects: three cabinets (one with a microwave), refrigerator, bed, "
               "table and chairs"),
    "random": (_random, (5.0, 6.5), (4.5, 5.5), "3-6 random objects of every category"),
}
SCENES = tuple(_RECIPES)
SCENE_DESCRIPTIONS = {k: v[3] for k, v in _RECIPES.items()}


def build_scene(name: str, seed: int = 0, gcfg: GeneratorConfig = DEFAULT_GENERATOR,
                ccfg: ComposerConfig = DEFAULT_COMPOSER) -> Scene:
    """Compose the built-in scene ``name`` for ``seed`` (deterministic)."""
    if name not in _RECIPES:
        raise SceneSpecError(f"unknown scene {name!r}; expected one of {', '.join(SCENES)}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise SceneSpecError(f"scene {name!r}: seed must be a non-negative integer, got {seed!r}")
    recipe, (lx0, lx1), (ly0, ly1), _ = _RECIPES[name]
    last = None
    for attempt in range(MAX_ATTEMPTS):
        rng = np.random.default_rng([int(seed), attempt])
        room = (float(rng.uniform(lx0, lx1)), float(rng.uniform(ly0, ly1)))
        comp = RoomComposer(name, int(seed), room, rng, ccfg)
        try:
            recipe(comp, rng, gcfg)
        except PlacementError as e:
            log.debug("scene %s seed %d attempt %d: %s", name, seed, attempt, e)
            last = e
            continue
        scene = comp.build()
        validate_scene(scene)
        return scene
    raise PlacementError(f"scene {name!r} seed {seed}: no valid layout in {MAX_ATTEMPTS} attempts ({last})")
