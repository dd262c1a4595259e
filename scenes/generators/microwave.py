"""Microwave generator: a hollow shell with a control block and a left-hinged door with a bar handle."""

from __future__ import annotations

import numpy as np

from ..config import DEFAULT_GENERATOR, GeneratorConfig
from ..model import ArticulatedObject
from .builder import ObjectBuilder
from .casework import Bay, add_door

__all__ = ["make_microwave"]

_SHELL = 0.012  # m, shell thickness


def make_microwave(rng: np.random.Generator, cfg: GeneratorConfig = DEFAULT_GENERATOR) -> ArticulatedObject:
    """A microwave 0.45-0.60 m wide, 0.34-0.42 m deep, 0.26-0.34 m high; door hinged on the left (-y)."""
    W = float(rng.uniform(0.45, 0.60))
    D = float(rng.uniform(0.34, 0.42))
    H = float(rng.uniform(0.26, 0.34))
    t, gap = _SHELL, cfg.front_gap
    b = ObjectBuilder("microwave", cfg)
    yc = W / 2 - t - float(rng.uniform(0.10, 0.14))   # cavity | control block boundary
    shapes = [
        b.box([0, -W / 2 + t / 2, H / 2], [D, t, H]),
        b.box([0, W / 2 - t / 2, H / 2], [D, t, H]),
        b.box([0, 0, H - t / 2], [D, W - 2 * t, t]),
        b.box([0, 0, t / 2], [D, W - 2 * t, t]),
        b.box([-D / 2 + t / 2, 0, H / 2], [t, W - 2 * t, H - 2 * t]),
        b.box([(-D / 2 + t + D / 2) / 2, (yc + W / 2 - t) / 2, H / 2], [D - t, W / 2 - t - yc, H - 2 * t]),
    ]
    body = b.add_part("body", shapes)
    b.fix(None, body)
    bay = Bay(-W / 2 + t, yc, t, H - t, -W / 2 + gap, yc - gap, gap, H - gap, D / 2, -D / 2 + t)
    style = ("bar", "rod")[int(rng.integers(2))]
    lo, hi = cfg.door_upper
    add_door(b, body, bay, "left", float(rng.uniform(lo, hi)), style)
    return b.build()
