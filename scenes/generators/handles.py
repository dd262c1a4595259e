"""Handle parts: bars, round rods and knobs mounted on a drawer or door front."""

from __future__ import annotations

import numpy as np

from ..description import pose
from .builder import ObjectBuilder

__all__ = ["HANDLE_STYLES", "add_handle"]

HANDLE_STYLES = ("bar", "rod", "knob")
_POST_RADIUS = 0.006   # m, standoff posts
_POST_INSET = 0.015    # m, post centre from the bar end
_BAR = 0.014           # m, square bar side
_ROD_RADIUS = 0.008    # m


def add_handle(b: ObjectBuilder, front: int, mount, style: str, vertical: bool, length: float) -> int:
    """Add a handle on the front face and fix it to part ``front``; returns its part id.

    ``mount`` (3,): the point on the front face (object frame) where the handle is centred; the face
    normal is object +x. ``vertical`` puts a bar/rod along z, else along y. ``length``: bar length (m).
    """
    mount = np.asarray(mount, float)
    so = b.cfg.handle_standoff
    along = "z" if vertical else "y"
    e = np.array([0.0, 0.0, 1.0]) if vertical else np.array([0.0, 1.0, 0.0])
    shapes = []
    if style in ("bar", "rod"):
        for sgn in (-1, 1):
            c = mount + np.array([so / 2, 0, 0]) + sgn * (length / 2 - _POST_INSET) * e
            shapes.append(b.cylinder(c, _POST_RADIUS, so, along="x"))
        if style == "bar":
            size = np.array([_BAR, _BAR, _BAR]) + (length - _BAR) * e
            shapes.append(b.box(mount + np.array([so + _BAR / 2, 0, 0]), size))
        else:
            shapes.append(b.cylinder(mount + np.array([so + _ROD_RADIUS, 0, 0]), _ROD_RADIUS, length, along))
    elif style == "knob":
        shapes.append(b.cylinder(mount + np.array([0.0125, 0, 0]), 0.007, 0.025, along="x"))
        shapes.append(b.cylinder(mount + np.array([0.025 + 0.01, 0, 0]), 0.018, 0.02, along="x"))
    else:
        raise ValueError(f"unknown handle style {style!r}; expected one of {HANDLE_STYLES}")
    h = b.add_part("handle", shapes, pose(mount))
    b.fix(front, h)
    return h
