"""``truth.json`` (format ``partscene.truth/1``, see ``docs/contracts.md``): write and read back."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .description import (TRUTH_FORMAT, DescriptionError, check_truth_format, read_truth_doc, shape_from_truth,
                          truth_shape_dict, write_truth_doc)
from .config import DEFAULT_GENERATOR
from .errors import SceneSpecError
from .validate import validate_scene
from .model import ArticulatedObject, Joint, JointType, Part, Scene, Wall

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
    """Inverse of :func:`truth_dict_from_scene` (joint axes/origins back to object frames)."""
    try:
        check_truth_format(d, source)
    except DescriptionError as e:
        raise SceneSpecError(str(e)) from e
    try:
        return _scene_from(d)
    except (KeyError, TypeError, ValueError, DescriptionError) as e:
        raise SceneSpecError(f"{source}: malformed truth ({type(e).__name__}: {e})") from e


def _scene_from(d: dict) -> Scene:
    objects = []
    for od in d["objects"]:
        T_wo = np.array(od["T_world_object"], float)
        T_ow = np.linalg.inv(T_wo)
        parts = tuple(Part(p["id"], p["label"], T_ow @ np.array(p["T_world_part"], float),
                           tuple(shape_from_truth(s, f"part {p['id']} shape {k}") for k, s in enumerate(p["shapes"])),
                           float(p.get("density", DEFAULT_GENERATOR.densities.default)))
                      for p in od["parts"])
        joints = tuple(Joint(JointType(j["type"]), j["parent_part_id"], j["child_part_id"],
                             T_ow[:3, :3] @ np.array(j["axis"], float),
                             T_ow[:3, :3] @ np.array(j["origin"], float) + T_ow[:3, 3],
                             float(j["lower"]), float(j["upper"]), j.get("handle_part_id"),
                             float(j.get("effort", 0.0)), float(j.get("velocity", 0.0)),
                             float(j.get("damping", 0.0)), float(j.get("friction", 0.0)))
                       for j in od["joints"])
        objects.append(ArticulatedObject(od["id"], od["category"], parts, joints,
                                         tuple(tuple(c) for c in od["contacts"]), T_wo, od["supported_by"]))
    walls = tuple(Wall(w["name"], np.array(w["size"], float), np.array(w["T_world_wall"], float))
                  for w in d.get("walls", []))
    return Scene(d["scene"], int(d["seed"]), tuple(objects), walls,
                 np.array(d.get("room_size", [0.0, 0.0]), float))


def read_truth_json(path: str | Path) -> Scene:
    path = Path(path)
    try:
        d = read_truth_doc(path)
    except DescriptionError as e:
        raise SceneSpecError(str(e)) from e
    scene = scene_from_truth_dict(d, str(path))
    validate_scene(scene)
    return scene
