"""Hollow carcasses with drawer and door fronts: shared by cabinets, microwaves and refrigerators.

A carcass is a set of thin panels in the body part with an open front. Bays (openings) are closed by
overlay fronts just in front of the body's front plane ``x = depth / 2``: a drawer is an open box
(bottom + sides + back; its front panel is its front wall) that slides along +x inside its bay with
``drawer_clearance`` on every side; a door is a panel hinged at a vertical outer edge of its front.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..description import pose
from .builder import ObjectBuilder
from .handles import add_handle

__all__ = ["Bay", "add_drawer", "add_door"]


@dataclass(frozen=True)
class Bay:
    """An opening of a carcass, object frame, metres.

    ``y0, y1, z0, z1``: the free interior of the bay; ``fy0, fy1, fz0, fz1``: the extent of the
    overlay front that closes it; ``x_front``: the body's front plane; ``x_back``: the bay's back.
    """

    y0: float
    y1: float
    z0: float
    z1: float
    fy0: float
    fy1: float
    fz0: float
    fz1: float
    x_front: float
    x_back: float


def add_drawer(b: ObjectBuilder, body: int, bay: Bay, handle_style: str) -> tuple[int, int]:
    """Add a drawer (open box + front panel) in ``bay`` and its handle; returns (drawer, handle) ids."""
    cfg = b.cfg
    c, w, tf, gap = cfg.drawer_clearance, cfg.drawer_wall, cfg.front, cfg.front_gap
    xf = bay.x_front + gap                      # back face of the front panel
    xb = bay.x_back + 0.01                      # the box's back, 1 cm off the bay's back
    y0, y1, z0, z1 = bay.y0 + c, bay.y1 - c, bay.z0 + c, bay.z1 - c
    box_h = min(z1 - z0, 0.25)
    zc0 = z0
    shapes = [
        b.box([(xf + xb) / 2, (y0 + y1) / 2, zc0 + w / 2], [xf - xb, y1 - y0, w]),               # bottom
        b.box([(xf + xb) / 2, y0 + w / 2, zc0 + w + (box_h - w) / 2], [xf - xb, w, box_h - w]),    # left
        b.box([(xf + xb) / 2, y1 - w / 2, zc0 + w + (box_h - w) / 2], [xf - xb, w, box_h - w]),    # right
        b.box([xb + w / 2, (y0 + y1) / 2, zc0 + w + (box_h - w) / 2], [w, y1 - y0 - 2 * w, box_h - w]),  # back
        b.box([xf + tf / 2, (bay.fy0 + bay.fy1) / 2, (bay.fz0 + bay.fz1) / 2],
              [tf, bay.fy1 - bay.fy0, bay.fz1 - bay.fz0]),                                           # front
    ]
    centre = np.array([xf, (bay.fy0 + bay.fy1) / 2, (bay.fz0 + bay.fz1) / 2])
    d = b.add_part("drawer", shapes, pose(centre))
    width = bay.fy1 - bay.fy0
    mount = centre + np.array([tf, 0.0, 0.0])
    h = add_handle(b, d, mount, handle_style, vertical=False, length=float(np.clip(0.5 * width, 0.1, 0.3)))
    b.prismatic(body, d, [1.0, 0.0, 0.0], cfg.drawer_travel * (xf - xb), handle=h)
    return d, h


def add_door(b: ObjectBuilder, body: int, bay: Bay, hinge: str, upper: float, handle_style: str,
             handle_z: float | None = None, fy0: float | None = None, fy1: float | None = None) -> tuple[int, int]:
    """Add a door panel covering ``bay``'s front (or ``[fy0, fy1]``) hinged on its ``hinge`` edge.

    ``hinge``: "left" (object -y) or "right" (+y). The door frame sits on the hinge line at the panel's
    back face; the axis is -z for a left hinge and +z for a right hinge so that a positive angle swings
    the free edge outwards (+x). ``handle_z``: handle height (default: the front's centre).
    """
    cfg = b.cfg
    tf, gap = cfg.front, cfg.front_gap
    fy0 = bay.fy0 if fy0 is None else fy0
    fy1 = bay.fy1 if fy1 is None else fy1
    xf = bay.x_front + gap
    zc = (bay.fz0 + bay.fz1) / 2
    hy = fy0 if hinge == "left" else fy1
    panel = b.box([xf + tf / 2, (fy0 + fy1) / 2, zc], [tf, fy1 - fy0, bay.fz1 - bay.fz0])
    d = b.add_part("door", [panel], pose([xf, hy, zc]))
    free = fy1 if hinge == "left" else fy0
    inset = min(0.05, 0.2 * (fy1 - fy0))
    hy_mount = free - inset if hinge == "left" else free + inset
    hz = zc if handle_z is None else handle_z
    length = float(np.clip(0.3 * (bay.fz1 - bay.fz0), 0.1, 0.35))
    hz = float(np.clip(hz, bay.fz0 + length / 2 + 0.02, bay.fz1 - length / 2 - 0.02))
    h = add_handle(b, d, [xf + tf, hy_mount, hz], handle_style, vertical=True, length=length)
    axis = [0.0, 0.0, -1.0] if hinge == "left" else [0.0, 0.0, 1.0]
    b.revolute(body, d, axis, upper, handle=h)
    return d, h
