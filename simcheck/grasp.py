"""When a grasp forms and what it can hold: pure numpy over finger contacts and the grasp's wrench.

A two-finger gripper holds a handle only when the handle is between its finger pads:

* both fingers touch the handle (contact points no farther apart than ``contact_distance``);
* on their pads, from opposite sides: at each finger the contact normal (from the handle toward the
  finger) points against the direction in which that finger closes, within ``normal_angle`` -- a
  fingertip pressed on the bar's front, a pad on a flat drawer front with the other finger on air, or
  a finger side brushing the bar all have normals across the closing direction, or only one finger;
* the fingers were stopped by the handle: neither finger is within ``min_travel`` of its fully closed
  position, and the handle's width between the two pads' contact points (along the closing direction)
  is at least ``min_width`` -- fingers that closed on air in front of a bar are fully closed.

What it holds is the robot spec's business (``planners.robot.GripperModel``); see :mod:`simcheck.execute`.

A round bar held across its axis (:func:`round_bar_axis`) rolls between the flat pads: the pads touch it along
lines parallel to its axis, and what resists its turn about that axis is the pads' friction over the bar's
radius, at most ``2 * pad_friction * grip_force * radius`` (the Panda's defaults on a 1 cm bar: 1.4 N*m) -- a
door's weight turns it there. Every other turn (of a rectangular bar, a knob, a mesh handle, or of a round bar's
axis against the pads) moves the handle's flat faces or its axis out of the pads, and loses the grasp beyond a
few tens of degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["FingerContacts", "GraspFormation", "grasp_formation", "round_bar_axis"]


@dataclass(frozen=True)
class FingerContacts:
    """One finger's contact points with the handle link, world frame.

    Attributes:
        finger: the finger link's name.
        positions: (k, 3) contact points on the handle, metres.
        normals: (k, 3) unit contact normals, from the handle toward the finger.
        distances: (k,) signed distances, metres (negative: penetration).
        closing: (3,) unit direction in which this finger moves when the gripper closes.
        travel_left: how far, m or rad, the finger joint still is from its fully closed position.
    """

    finger: str
    positions: np.ndarray
    normals: np.ndarray
    distances: np.ndarray
    closing: np.ndarray
    travel_left: float


@dataclass(frozen=True)
class GraspFormation:
    """Whether the fingers hold the handle: ``ok``; ``reason`` says why not (names the finger);
    ``width`` is the handle's width between the pads, metres (NaN when not measured); ``pads`` (2, 3) the
    two pads' mean contact points on the handle, world frame, metres (None when not both found)."""

    ok: bool
    reason: str
    width: float = math.nan
    pads: np.ndarray | None = None


def _touching(f: FingerContacts, contact_distance: float) -> np.ndarray:
    return np.asarray(f.distances, dtype=float) <= contact_distance


def grasp_formation(fingers: tuple[FingerContacts, ...] | list[FingerContacts], handle: str, *,
                    contact_distance: float, normal_angle: float, min_travel: float,
                    min_width: float) -> GraspFormation:
    """Judge whether two fingers hold ``handle`` between their pads (see the module docstring).

    Args:
        fingers: the two fingers' contacts with the handle link (exactly two fingers).
        handle: the handle link's name (for the reason).
        contact_distance: contact points farther than this, metres, do not touch.
        normal_angle: largest angle, rad, between a contact normal and the finger's opening direction.
        min_travel: a finger closer than this, m or rad, to fully closed closed on nothing.
        min_width: smallest handle width between the pads, metres.
    """
    if len(fingers) != 2:
        return GraspFormation(False, f"a two-pad grasp needs 2 finger links, the robot names {len(fingers)}")
    cos_max = math.cos(normal_angle)
    pads = []
    for f in fingers:
        touch = _touching(f, contact_distance)
        if not touch.any():
            return GraspFormation(False, f"finger {f.finger} does not touch handle {handle}")
        closing = np.asarray(f.closing, dtype=float)
        n = np.asarray(f.normals, dtype=float)[touch]
        on_pad = n @ closing <= -cos_max
        if not on_pad.any():
            worst = math.degrees(math.acos(float(np.clip(-(n @ closing).min(), -1.0, 1.0))))
            return GraspFormation(False, f"finger {f.finger} touches handle {handle} only off its pad (contact "
                                         f"normal {worst:.0f} deg from the closing direction, at most "
                                         f"{math.degrees(normal_angle):.0f})")
        if f.travel_left < min_travel:
            return GraspFormation(False, f"finger {f.finger} closed fully ({f.travel_left * 1e3:.1f} mm from closed): "
                                         f"it was not stopped by handle {handle}")
        pads.append(np.asarray(f.positions, dtype=float)[touch][on_pad].mean(axis=0))
    a, b = fingers
    if float(np.dot(a.closing, b.closing)) > -cos_max:
        return GraspFormation(False, f"fingers {a.finger} and {b.finger} do not close against each other")
    width = float(np.dot(pads[1] - pads[0], np.asarray(a.closing, dtype=float)))
    if width < min_width:
        return GraspFormation(False, f"the pads of {a.finger} and {b.finger} hold {width * 1e3:.1f} mm of handle "
                                     f"{handle} between them (at least {min_width * 1e3:.1f} mm)", width,
                              np.array(pads))
    return GraspFormation(True, "", width, np.array(pads))


def round_bar_axis(pads: np.ndarray, closing: np.ndarray, cylinders, *, tolerance: float,
                   max_angle: float) -> tuple[np.ndarray, np.ndarray] | None:
    """The axis of the round bar the two pads hold, if they hold one across its axis.

    A cylinder is a bar when it is longer than its diameter (shorter: a knob, which is judged as any handle).
    The pads hold it across its axis when both pad contact points lie on its round side (within
    ``tolerance`` metres of its radius from the axis, and between its ends) and the fingers close across the
    axis (the closing direction within ``max_angle`` rad of perpendicular to it): the flat pads then touch the
    bar along lines parallel to its axis, and it can roll about that axis between them.

    Args:
        pads: (2, 3) the pads' contact points, handle-link frame, metres.
        closing: (3,) one finger's closing direction, handle-link frame (unit).
        cylinders: iterable of ``(T_link_shape (4, 4), radius, length)`` of the handle link's cylinders
            (metres; the cylinder's axis is its frame's z).
        tolerance: metres.
        max_angle: rad.

    Returns:
        ``(axis (3,) unit, point (3,))`` in the handle-link frame -- the point on the axis nearest the pads'
        midpoint -- or None.
    """
    pads = np.asarray(pads, dtype=float).reshape(2, 3)
    closing = np.asarray(closing, dtype=float)
    for T, radius, length in cylinders:
        T = np.asarray(T, dtype=float)
        if length <= 2.0 * radius:
            continue
        a, c = T[:3, 2], T[:3, 3]
        along = (pads - c) @ a
        radial = np.linalg.norm((pads - c) - along[:, None] * a, axis=1)
        if np.any(np.abs(along) > 0.5 * length) or np.any(np.abs(radial - radius) > tolerance):
            continue
        if abs(float(closing @ a)) > math.sin(max_angle):
            continue
        return a.copy(), c + float(along.mean()) * a
    return None

