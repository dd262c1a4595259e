"""``truth.json`` (format ``partscene.truth/1``, see ``docs/contracts.md``): write and read back."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .description import (TRUTH_FORMAT, DescriptionError, TrueScene, read_truth_doc, true_scene_from_doc,
                          truth_shape_dict, write_truth_doc)
from .config import DEFAULT_GENERATOR
from .errors import SceneSpecError
from .validate import validate_scene
from .model import ArticulatedObject, Joint, Part, Scene, Wall

__all__ = ["TRUTH_FORMAT", "truth_dict_from_scene", "write_truth_json", "scene_from_truth_dict",
           "read_truth_json"]



def _m(T: np.ndarray) -> list[list[float]]:
    return [[float(x) for x in row] for row in np.asarray(T)]


def _v(v) -> list[float]:
    return [float(x) for x in v]


def _object_dict(o: ArticulatedObject) -> dict:
    R = o.T_world_object[:3, :3]
    parts = [{"id": p.id, "label": p.label, "link": o.link(p),
              "T_world_part": _m(o.T_world_object @ p.T_object_part),
              "density": p.density,
              "shapes": [truth_shape_dict(s) for s in p.shapes]} for p in o.parts]
    joints = []
    for j in o.joints:
        joints.append({
            "name": o.joint_name(j), "type": j.type.value,
            "parent_part_id": j.parent, "child_part_id": j.child,
            "axis": _v(R @ j.axis / np.linalg.norm(j.axis)),
            "origin": _v(o.T_world_object[:3, :3] @ j.origin + o.T_world_object[:3, 3]),
            "lower": float(j.lower), "upper": float(j.upper), "handle_part_id": j.handle,
            "effort": j.effort, "velocity": j.velocity, "damping": j.damping, "friction": j.friction,
        })
    return {"id": o.id, "name": o.name, "category": o.category, "T_world_object": _m(o.T_world_object),
            "size": _v(o.size), "supported_by": o.supported_by, "parts": parts, "joints": joints,
            "contacts": [[int(a), int(b)] for a, b in o.contacts]}


def truth_dict_from_scene(scene: Scene) -> dict:
    """The JSON-ready dict of ``scene``."""
    return {
        "format": TRUTH_FORMAT, "scene": scene.name, "seed": int(scene.seed),
        "floor": {"z": 0.0}, "room_size": _v(scene.room_size),
        "walls": [{"name": w.name, "size": _v(w.size), "T_world_wall": _m(w.T_world_wall)} for w in scene.walls],
        "objects": [_object_dict(o) for o in scene.objects],
    }


def write_truth_json(scene: Scene, path: str | Path) -> Path:
    """Write ``truth.json`` atomically; returns the path."""
    return write_truth_doc(truth_dict_from_scene(scene), path)


def scene_from_truth_dict(d: dict, source: str = "truth.json") -> Scene:
    """Inverse of :func:`truth_dict_from_scene` (joint axes/origins back to object frames), read through the
    description's checked truth (:func:`scenes.description.true_scene_from_doc`)."""
    try:
        true = true_scene_from_doc(d, source)
    except DescriptionError as e:
        raise SceneSpecError(str(e)) from e
    try:
        return _scene_from(true)
    except (KeyError, TypeError, ValueError, DescriptionError) as e:
        raise SceneSpecError(f"{source}: malformed truth ({type(e).__name__}: {e})") from e


def _scene_from(true: TrueScene) -> Scene:
    objects = []
    default_density = DEFAULT_GENERATOR.densities.default
    for o in true.objects:
        T_ow = np.linalg.inv(o.T_world_object)
        parts = tuple(Part(p.id, p.label, T_ow @ p.T_world_part, p.shapes,
                           default_density if p.density is None else p.density) for p in o.parts)
        joints = tuple(Joint(j.type, j.parent_part_id, j.child_part_id, T_ow[:3, :3] @ j.axis,
                             T_ow[:3, :3] @ j.origin + T_ow[:3, 3], j.lower, j.upper, j.handle_part_id,
                             j.effort, j.velocity, j.damping, j.friction)
                       for j in o.joints)
        objects.append(ArticulatedObject(o.id, o.category, parts, joints, o.contacts, o.T_world_object,
                                         o.supported_by))
    walls = tuple(Wall(w.name, w.size, w.T_world_wall) for w in true.walls)
    return Scene(true.scene, true.seed, tuple(objects), walls, true.room_size)


def read_truth_json(path: str | Path) -> Scene:
    path = Path(path)
    try:
        d = read_truth_doc(path)
    except DescriptionError as e:
        raise SceneSpecError(str(e)) from e
    scene = scene_from_truth_dict(d, str(path))
    validate_scene(scene)
    return scene
