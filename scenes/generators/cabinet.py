"""Cabinet generator: a hollow carcass on a plinth with columns of drawers and doors.

Layouts (``CABINET_LAYOUTS``):

* ``drawers_doors``      -- a drawer stack beside a door (door hinged on the cabinet's outer side);
* ``door_drawers_door``  -- door | drawer stack | door;
* ``drawers_over_doors`` -- one row of drawers above a pair of doors hinged on the outer sides;
* ``drawer_stack``       -- drawers only;
* ``doors``              -- a pair of doors.
"""

from __future__ import annotations

import numpy as np

from ..config import DEFAULT_GENERATOR, GeneratorConfig
from ..model import ArticulatedObject
from .builder import ObjectBuilder
from .casework import Bay, add_door, add_drawer
from .handles import HANDLE_STYLES

__all__ = ["CABINET_LAYOUTS", "MIXED_CABINET_LAYOUTS", "make_cabinet"]

CABINET_LAYOUTS = ("drawers_doors", "door_drawers_door", "drawers_over_doors", "drawer_stack", "doors")
MIXED_CABINET_LAYOUTS = CABINET_LAYOUTS[:3]
_PLINTH = 0.08  # m, kick height under the carcass bottom


def _columns(layout: str, rng: np.random.Generator) -> list[tuple[str, float]]:
    """[(kind, interior width)] left (-y) to right (+y); kind in drawers | door | drawers_over_doors | doors."""
    drawers = ("drawers", float(rng.uniform(0.40, 0.60)))
    if layout == "drawers_doors":
        door = ("door", float(rng.uniform(0.35, 0.50)))
        return [drawers, door] if rng.random() < 0.5 else [door, drawers]
    if layout == "door_drawers_door":
        w = float(rng.uniform(0.35, 0.45))
        return [("door", w), drawers, ("door", w)]
    if layout == "drawers_over_doors":
        return [("drawers_over_doors", float(rng.uniform(0.70, 1.00)))]
    if layout == "drawer_stack":
        return [drawers]
    if layout == "doors":
        return [("doors", float(rng.uniform(0.60, 0.90)))]
    raise ValueError(f"unknown cabinet layout {layout!r}; expected one of {CABINET_LAYOUTS}")


def make_cabinet(rng: np.random.Generator, layout: str | None = None,
                 cfg: GeneratorConfig = DEFAULT_GENERATOR) -> ArticulatedObject:
    """A cabinet with randomised size (depth 0.45-0.60 m, height 0.72-0.92 m), layout and handles.

    The object is returned with id 0 and local part ids; the composer renumbers and places it.
    """
    if layout is None:
        layout = CABINET_LAYOUTS[int(rng.integers(len(CABINET_LAYOUTS)))]
    cols = _columns(layout, rng)
    t, gap = cfg.panel, cfg.front_gap
    D = float(rng.uniform(0.45, 0.60))
    H = float(rng.uniform(0.72, 0.92))
    W = sum(w for _, w in cols) + t * (len(cols) + 1)
    style = HANDLE_STYLES[int(rng.integers(len(HANDLE_STYLES)))]
    b = ObjectBuilder("cabinet", cfg)

    zb, zt = _PLINTH + t, H - t           # interior bottom/top
    xb = -D / 2 + t                       # interior back
    shapes = [
        b.box([0, -W / 2 + t / 2, H / 2], [D, t, H]),
        b.box([0, W / 2 - t / 2, H / 2], [D, t, H]),
        b.box([0, 0, H - t / 2], [D, W - 2 * t, t]),
        b.box([0, 0, _PLINTH + t / 2], [D, W - 2 * t, t]),
        b.box([-D / 2 + t / 2, 0, (zb + zt) / 2], [t, W - 2 * t, zt - zb]),
        b.box([D / 2 - 0.05 - t / 2, 0, _PLINTH / 2], [t, W - 2 * t, _PLINTH]),
    ]
    # columns: interior y-ranges separated by vertical dividers
    ranges, y = [], -W / 2 + t
    for i, (_, w) in enumerate(cols):
        ranges.append((y, y + w))
        y += w
        if i < len(cols) - 1:
            shapes.append(b.box([(xb + D / 2) / 2, y + t / 2, (zb + zt) / 2], [D / 2 - xb, t, zt - zb]))
            y += t

    cells = []  # (kind, Bay, hinge)

    def front_y(y0: float, y1: float) -> tuple[float, float]:
        ext0 = t - gap if np.isclose(y0, -W / 2 + t) else t / 2 - gap / 2
        ext1 = t - gap if np.isclose(y1, W / 2 - t) else t / 2 - gap / 2
        return y0 - ext0, y1 + ext1

    def rows(y0: float, y1: float, heights: list[float]) -> list[Bay]:
        """Split the column [y0, y1] into rows (bottom to top) with horizontal dividers."""
        out, z = [], zb
        fy0, fy1 = front_y(y0, y1)
        for i, h in enumerate(heights):
            z1 = z + h
            fz0 = z - (t - gap if i == 0 else t / 2 - gap / 2)
            fz1 = z1 + (t - gap if i == len(heights) - 1 else t / 2 - gap / 2)
            out.append(Bay(y0, y1, z, z1, fy0, fy1, fz0, fz1, D / 2, xb))
            if i < len(heights) - 1:
                shapes.append(b.box([(xb + D / 2) / 2, (y0 + y1) / 2, z1 + t / 2], [D / 2 - xb, y1 - y0, t]))
                z = z1 + t
        return out

    def split(total: float, n: int) -> list[float]:
        return [(total - (n - 1) * t) / n] * n

    interior_h = zt - zb
    for (kind, _), (y0, y1) in zip(cols, ranges):
        outer = "left" if np.isclose(y0, -W / 2 + t) else "right"
        if kind == "drawers":
            n = int(rng.integers(2, 5)) if interior_h > 0.5 else 2
            cells += [("drawer", bay, None) for bay in rows(y0, y1, split(interior_h, n))]
        elif kind == "door":
            bay = rows(y0, y1, [interior_h])[0]
            cells.append(("door", bay, outer))
            shapes.append(b.box([(xb + D / 2 - 0.03) / 2, (y0 + y1) / 2, (zb + zt) / 2 + t / 2],
                                [D / 2 - 0.03 - xb, y1 - y0, t]))  # a shelf behind the door
        elif kind in ("doors", "drawers_over_doors"):
            top = 0.16 if kind == "drawers_over_doors" else None
            hs = [interior_h] if top is None else [interior_h - top - t, top]
            bays = rows(y0, y1, hs)
            fy0, fy1 = bays[0].fy0, bays[0].fy1
            mid = (fy0 + fy1) / 2
            cells.append(("door", bays[0], ("left", fy0, mid - gap / 2)))
            cells.append(("door", bays[0], ("right", mid + gap / 2, fy1)))
            if top is not None:
                cells.append(("drawer", bays[1], None))
    body = b.add_part("body", shapes)
    b.fix(None, body)
    lo, hi = cfg.door_upper
    for kind, bay, hinge in cells:
        if kind == "drawer":
            add_drawer(b, body, bay, style)
        elif isinstance(hinge, tuple):
            add_door(b, body, bay, hinge[0], float(rng.uniform(lo, hi)), style,
                     handle_z=bay.fz1 - 0.12, fy0=hinge[1], fy1=hinge[2])
        else:
            add_door(b, body, bay, hinge, float(rng.uniform(lo, hi)), style, handle_z=bay.fz1 - 0.12)
    return b.build()
