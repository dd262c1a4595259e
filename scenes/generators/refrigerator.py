"""Refrigerator generator: an insulated shell with shelves and one or two doors with long bar handles.

Layouts: ``single`` (one door), ``top_freezer`` (two stacked doors hinged on the same side),
``side_by_side`` (two doors hinged on the outer sides).
"""

from __future__ import annotations

import numpy as np

from ..config import DEFAULT_GENERATOR, GeneratorConfig
from ..model import ArticulatedObject
from .builder import ObjectBuilder
from .casework import Bay, add_door

__all__ = ["FRIDGE_LAYOUTS", "make_refrigerator"]

FRIDGE_LAYOUTS = ("single", "top_freezer", "side_by_side")
_SHELL = 0.03  # m, insulated wall thickness
_FOOT = 0.02   # m, gap under the shell (feet are part of the body)


def make_refrigerator(rng: np.random.Generator, layout: str | None = None,
                      cfg: GeneratorConfig = DEFAULT_GENERATOR) -> ArticulatedObject:
    """A refrigerator 0.60-0.80 m wide, 0.60-0.72 m deep, 1.55-1.85 m high."""
    if layout is None:
        layout = FRIDGE_LAYOUTS[int(rng.integers(len(FRIDGE_LAYOUTS)))]
    if layout not in FRIDGE_LAYOUTS:
        raise ValueError(f"unknown refrigerator layout {layout!r}; expected one of {FRIDGE_LAYOUTS}")
    W = float(rng.uniform(0.60, 0.80)) if layout != "side_by_side" else float(rng.uniform(0.80, 0.95))
    D = float(rng.uniform(0.60, 0.72))
    H = float(rng.uniform(1.55, 1.85))
    t, gap = _SHELL, cfg.front_gap
    z0 = _FOOT
    b = ObjectBuilder("refrigerator", cfg)
    shapes = [
        b.box([0, -W / 2 + t / 2, (z0 + H) / 2], [D, t, H - z0]),
        b.box([0, W / 2 - t / 2, (z0 + H) / 2], [D, t, H - z0]),
        b.box([0, 0, H - t / 2], [D, W - 2 * t, t]),
        b.box([0, 0, z0 + t / 2], [D, W - 2 * t, t]),
        b.box([-D / 2 + t / 2, 0, (z0 + H) / 2], [t, W - 2 * t, H - z0 - 2 * t]),
    ]
    for sx in (-1, 1):
        for sy in (-1, 1):
            shapes.append(b.cylinder([sx * (D / 2 - 0.06), sy * (W / 2 - 0.06), z0 / 2], 0.02, z0))
    xb, zb, zt = -D / 2 + t, z0 + t, H - t
    shelf_x = (xb + D / 2 - 0.06) / 2
    for zs in np.linspace(zb, zt, 5)[1:-1]:
        shapes.append(b.box([shelf_x, 0, zs], [D / 2 - 0.06 - xb, W - 2 * t, 0.008]))
    zsplit = z0 + 0.68 * (H - z0)
    if layout == "top_freezer":
        shapes.append(b.box([(xb + D / 2) / 2, 0, zsplit], [D / 2 - xb, W - 2 * t, t]))
    body = b.add_part("body", shapes)
    b.fix(None, body)
    lo, hi = cfg.door_upper
    hinge = ("left", "right")[int(rng.integers(2))]
    y0, y1 = -W / 2 + t, W / 2 - t
    fy0, fy1 = -W / 2 + gap, W / 2 - gap
    if layout == "single":
        bay = Bay(y0, y1, zb, zt, fy0, fy1, z0 + gap, H - gap, D / 2, xb)
        add_door(b, body, bay, hinge, float(rng.uniform(lo, hi)), "bar", handle_z=1.05)
    elif layout == "top_freezer":
        low = Bay(y0, y1, zb, zsplit - t / 2, fy0, fy1, z0 + gap, zsplit - gap / 2, D / 2, xb)
        up = Bay(y0, y1, zsplit + t / 2, zt, fy0, fy1, zsplit + gap / 2, H - gap, D / 2, xb)
        add_door(b, body, low, hinge, float(rng.uniform(lo, hi)), "bar", handle_z=low.fz1 - 0.25)
        add_door(b, body, up, hinge, float(rng.uniform(lo, hi)), "bar", handle_z=up.fz0 + 0.2)
    else:
        mid = 0.0
        bay = Bay(y0, y1, zb, zt, fy0, fy1, z0 + gap, H - gap, D / 2, xb)
        add_door(b, body, bay, "left", float(rng.uniform(lo, hi)), "bar", handle_z=1.05,
                 fy0=fy0, fy1=mid - gap / 2)
        add_door(b, body, bay, "right", float(rng.uniform(lo, hi)), "bar", handle_z=1.05,
                 fy0=mid + gap / 2, fy1=fy1)
    return b.build()
