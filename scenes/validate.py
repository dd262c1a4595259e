"""Structural checks of objects and scenes; each failure raises :class:`SceneSpecError` naming what is wrong."""

from __future__ import annotations

import numpy as np

from .description import PART_LABELS, SCENE_CATEGORIES
from .errors import SceneSpecError
from .model import ArticulatedObject, JointType, Scene

__all__ = ["PART_LABELS", "CATEGORIES", "validate_object", "validate_scene"]

CATEGORIES = SCENE_CATEGORIES


def validate_object(obj: ArticulatedObject, where: str = "") -> None:
    """Check labels, sizes, the part tree and joint parameters of ``obj``."""
    at = f"{where}{obj.name}"
    if obj.category not in CATEGORIES:
        raise SceneSpecError(f"{at}: unknown category {obj.category!r}")
    ids = [p.id for p in obj.parts]
    if len(set(ids)) != len(ids):
        raise SceneSpecError(f"{at}: duplicate part ids {sorted(ids)}")
    for p in obj.parts:
        if p.label not in PART_LABELS:
            raise SceneSpecError(f"{at} part {p.id}: unknown label {p.label!r}")
        if not p.shapes:
            raise SceneSpecError(f"{at} part {p.id} ({p.label}): no shapes")
        for k, s in enumerate(p.shapes):
            if not np.all(np.isfinite(s.size)) or np.any(s.size <= 0):
                raise SceneSpecError(f"{at} part {p.id} ({p.label}) shape {k}: size {s.size.tolist()} must be > 0")
        if p.density <= 0:
            raise SceneSpecError(f"{at} part {p.id} ({p.label}): density {p.density} must be > 0")
    children = [j.child for j in obj.joints]
    if sorted(children) != sorted(ids):
        raise SceneSpecError(f"{at}: every part needs exactly one joint (parts {sorted(ids)}, joint children "
                             f"{sorted(children)})")
    roots = [j for j in obj.joints if j.parent is None]
    if len(roots) != 1 or roots[0].child != obj.parts[0].id or roots[0].type is not JointType.FIXED:
        raise SceneSpecError(f"{at}: needs exactly one fixed root joint to the world, on the first part")
    parent_of = {j.child: j.parent for j in obj.joints}
    for j in obj.joints:
        name = f"{at} joint {obj.joint_name(j)}"
        if j.parent is not None and j.parent not in parent_of:
            raise SceneSpecError(f"{name}: parent part {j.parent} does not exist")
        seen, p = set(), j.child
        while p is not None:
            if p in seen:
                raise SceneSpecError(f"{name}: the part tree has a cycle through part {p}")
            seen.add(p)
            p = parent_of.get(p)
        if j.movable:
            n = np.linalg.norm(j.axis)
            if not np.isfinite(n) or abs(n - 1.0) > 1e-6:
                raise SceneSpecError(f"{name}: axis {j.axis.tolist()} must be a unit vector")
            if not (j.lower == 0.0 and j.upper > 0.0):
                raise SceneSpecError(f"{name}: limits [{j.lower}, {j.upper}] must be [0, upper > 0]")
            if j.type is JointType.REVOLUTE and j.upper > np.pi:
                raise SceneSpecError(f"{name}: revolute upper {j.upper} rad exceeds pi")
            if j.handle is not None and parent_of.get(j.handle) != j.child:
                raise SceneSpecError(f"{name}: handle part {j.handle} is not fixed to part {j.child}")
    for a, b in obj.contacts:
        if a not in parent_of or b not in parent_of:
            raise SceneSpecError(f"{at}: contact edge ({a}, {b}) names a missing part")


def validate_scene(scene: Scene) -> None:
    """Validate every object, unique object ids, part ids unique in the scene and supports that exist."""
    oids = [o.id for o in scene.objects]
    if len(set(oids)) != len(oids):
        raise SceneSpecError(f"scene {scene.name!r}: duplicate object ids {sorted(oids)}")
    seen: dict[int, str] = {}
    for o in scene.objects:
        validate_object(o, f"scene {scene.name!r} ")
        if o.supported_by is not None and o.supported_by not in oids:
            raise SceneSpecError(f"scene {scene.name!r} {o.name}: supported_by {o.supported_by} is not an object")
        for p in o.parts:
            if p.id in seen:
                raise SceneSpecError(f"scene {scene.name!r}: part id {p.id} used by {seen[p.id]} and {o.name}")
            seen[p.id] = o.name
