"""A PyBullet body's joints and links by name (pure: the rows come from the adapter's ``getJointInfo``)."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["JointInfo", "JointRow", "joint_table"]


@dataclass(frozen=True)
class JointInfo:
    """A joint as loaded in PyBullet. ``lower``/``upper`` in rad or m; ``damping``/``friction`` from the URDF."""

    name: str
    type: str
    index: int
    child_link: str
    parent_link: str
    lower: float
    upper: float
    max_force: float
    max_velocity: float
    damping: float
    friction: float


@dataclass(frozen=True)
class JointRow:
    """One joint as PyBullet reports it: its parent is a link INDEX (-1: the base link); ``type`` is
    "revolute", "prismatic", "fixed", "spherical", "planar" or "unknown"."""

    name: str
    type: str
    child_link: str
    parent_index: int
    lower: float
    upper: float
    max_force: float
    max_velocity: float
    damping: float
    friction: float


def joint_table(base_link: str, rows: list[JointRow]) -> tuple[dict[str, JointInfo], dict[str, int]]:
    """(joint name -> :class:`JointInfo`, link name -> link index) of a body whose base link is
    ``base_link`` (index -1) and whose joint ``j`` is ``rows[j]`` (its child link has index ``j``)."""
    links = {base_link: -1}
    for j, row in enumerate(rows):
        links[row.child_link] = j
    names = {v: k for k, v in links.items()}
    joints = {}
    for j, row in enumerate(rows):
        joints[row.name] = JointInfo(
            name=row.name, type=row.type, index=j, child_link=row.child_link, parent_link=names[row.parent_index],
            lower=row.lower, upper=row.upper, max_force=row.max_force, max_velocity=row.max_velocity,
            damping=row.damping, friction=row.friction)
    return joints, links
