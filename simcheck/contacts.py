"""Contact points by link name, from PyBullet's raw contact rows (pure: the rows come from the adapter's
``getContactPoints``; a row is PyBullet's tuple: [1] body A, [2] body B, [3] link A, [4] link B,
[5] position on A (3,), [8] signed distance m (negative: penetration), [9] normal force N)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

__all__ = ["FLOOR", "ContactPoint", "robot_contact_points", "scene_link_contact_points", "deep_overlaps",
           "rest_contacts", "excess_penetration"]

FLOOR = "floor"
"""``link_b`` of a contact with the floor plane."""


@dataclass(frozen=True)
class ContactPoint:
    """One contact point between a robot link (or scene link) and another body's link.

    ``force`` is the normal force, N; ``distance`` is negative for penetration, metres;
    ``position`` (3,) on the first body, world frame.
    """

    link_a: str
    link_b: str
    force: float
    distance: float
    position: tuple[float, float, float]


def robot_contact_points(rows: Iterable[Sequence], robot_names: Mapping[int, str],
                         scene_names: Mapping[tuple[int, int], str], floor: int, base_links: set[int],
                         min_depth: float) -> list[ContactPoint]:
    """The rows (body A: the robot) with scene links and with the floor, deeper than ``min_depth`` (m).

    ``robot_names``: robot link index -> name; ``scene_names``: (body, link index) -> scene link name;
    ``floor``: the floor's body id; floor contacts of the links ``base_links`` (indices) are left out
    (a mobile base stands on the floor)."""
    out = []
    for cp in rows:
        if cp[8] > -min_depth:
            continue
        if cp[2] == floor:
            if cp[3] not in base_links:
                out.append(ContactPoint(robot_names[cp[3]], FLOOR, float(cp[9]), float(cp[8]), tuple(cp[5])))
        elif (cp[2], cp[4]) in scene_names:
            out.append(ContactPoint(robot_names[cp[3]], scene_names[cp[2], cp[4]], float(cp[9]), float(cp[8]),
                                    tuple(cp[5])))
    return out


def scene_link_contact_points(rows: Iterable[Sequence], link: str, at: tuple[int, int],
                              scene_names: Mapping[tuple[int, int], str], floor: int,
                              min_depth: float) -> list[ContactPoint]:
    """The rows (body A: scene link ``link`` at (body, link index) ``at``) with other scene links and the
    floor, deeper than ``min_depth`` (m); contacts with the robot are left out."""
    out = []
    for cp in rows:
        if cp[8] > -min_depth:
            continue
        if cp[2] == floor:
            out.append(ContactPoint(link, FLOOR, float(cp[9]), float(cp[8]), tuple(cp[5])))
        elif (cp[2], cp[4]) in scene_names and (cp[2], cp[4]) != at:
            out.append(ContactPoint(link, scene_names[cp[2], cp[4]], float(cp[9]), float(cp[8]), tuple(cp[5])))
    return out


def deep_overlaps(rows: Iterable[Sequence], scene_names: Mapping[tuple[int, int], str],
                  tolerance: float) -> dict[tuple[tuple[int, int], tuple[int, int]], float]:
    """{((body, link) a, (body, link) b): deepest penetration m} of the rows between two scene links
    that interpenetrate deeper than ``tolerance`` (m), in the order the pairs first appear."""
    seen: dict[tuple, float] = {}
    for cp in rows:
        a, b, dist = (cp[1], cp[3]), (cp[2], cp[4]), cp[8]
        if a in scene_names and b in scene_names and dist < -tolerance:
            seen[(a, b)] = max(seen.get((a, b), 0.0), -dist)
    return seen


def rest_contacts(rows: Iterable[Sequence], scene_names: Mapping[tuple[int, int], str],
                  gap: float) -> dict[tuple[tuple[int, int], tuple[int, int]], float]:
    """{((body, link) a, (body, link) b): penetration at rest m (negative: the gap between them)} of the
    rows between two scene links closer than ``gap`` (m): touching or interpenetrating, in the order the
    pairs first appear; a pair is listed once whichever way round PyBullet reports it."""
    seen: dict[tuple, float] = {}
    for cp in rows:
        a, b, dist = (cp[1], cp[3]), (cp[2], cp[4]), cp[8]
        if a in scene_names and b in scene_names and a != b and dist < gap:
            key = (a, b) if (b, a) not in seen else (b, a)
            seen[key] = max(seen.get(key, -gap), -dist)
    return seen


def excess_penetration(distances: Iterable[float], at_rest: float) -> float:
    """How much deeper than ``at_rest`` (m, positive: penetration) two links interpenetrate now, m (>= 0),
    given their current signed closest-point ``distances`` (m, negative: penetration; none: apart)."""
    deepest = max((-float(d) for d in distances), default=0.0)
    return max(0.0, deepest - max(at_rest, 0.0))
