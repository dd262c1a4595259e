"""A PyBullet body's joints and links by name (pure: the rows come from the adapter's ``getJointInfo``)."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass

__all__ = ["JointInfo", "joint_table"]


@dataclass(frozen=True)
class JointInfo:
    """A joint as loaded in PyBullet: ``type`` "revolute", "prismatic", "fixed", "spherical", "planar" or
    "unknown"; ``index`` in its body (its child link's index); ``lower``/``upper`` in rad or m; ``max_force``
    N or N m, ``max_velocity`` m/s or rad/s; ``damping``/``friction`` from the URDF."""

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


def joint_table(base_link: str, joints: Sequence[JointInfo],
                parent_index: Sequence[int]) -> tuple[dict[str, JointInfo], dict[str, int]]:
    """(joint name -> :class:`JointInfo`, link name -> link index) of a body whose base link is ``base_link``
    (index -1) and whose joint ``j`` is ``joints[j]`` (its child link has index ``j``) with parent link index
    ``parent_index[j]`` (-1: the base link). Fills in each joint's ``index`` and ``parent_link``."""
    links = {base_link: -1}
    for j, info in enumerate(joints):
        links[info.child_link] = j
    names = {v: k for k, v in links.items()}
    return ({info.name: dataclasses.replace(info, index=j, parent_link=names[parent_index[j]])
             for j, info in enumerate(joints)}, links)
