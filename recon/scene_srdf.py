"""``scene.srdf`` beside ``scene.urdf``: the link pairs in contact at rest, for planners that read an SRDF.

Every pair of links whose shapes come within ``ClearanceConfig.contact_distance`` at q = 0 (a handle on
its front, a drawer in its carcass, a cabinet against a wall, legs under a top) gets a
``<disable_collisions link1= link2= reason=>``: ``reason="Adjacent"`` when a joint connects the two,
else ``"Default"`` (in contact in the default state) — the reasons MoveIt's setup assistant writes.
No pair of scene.urdf overlaps (recon.clearance); the SRDF only saves a planner from reporting the
resting contacts as collisions. Pairs are sorted by name, so the same reconstruction gives the same bytes.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from recon.clearance import links_in_contact
from recon.model import Reconstruction
from scenes.description import WORLD_LINK

__all__ = ["srdf_string", "resting_contacts"]


def resting_contacts(rec: Reconstruction) -> tuple[tuple[str, str, str], ...]:
    """((link a, link b, reason), ...) of the pairs in contact at rest (see the module docstring)."""
    adjacent = set()
    for obj in rec.objects:
        for j in obj.joints:
            parent = WORLD_LINK if j.parent_part_id is None else obj.part(j.parent_part_id).link
            adjacent.add(frozenset((parent, obj.part(j.child_part_id).link)))
    pairs = links_in_contact(rec.objects, rec.walls, rec.config.clearance.contact_distance)
    return tuple((a, b, "Adjacent" if frozenset((a, b)) in adjacent else "Default") for a, b, _ in pairs)


def srdf_string(rec: Reconstruction, name: str = "scene") -> str:
    """The scene.srdf text (``name`` = the URDF's robot name)."""
    robot = ET.Element("robot", name=name)
    for a, b, reason in resting_contacts(rec):
        ET.SubElement(robot, "disable_collisions", link1=a, link2=b, reason=reason)
    ET.indent(robot, space="  ")
    return '<?xml version="1.0"?>\n' + ET.tostring(robot, encoding="unicode") + "\n"
