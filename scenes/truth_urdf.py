"""Write a :class:`~scenes.model.Scene` as ``truth.urdf`` (the shape fixed in ``docs/contracts.md``).

Root link ``world``; each object's root part hangs from ``world`` by a fixed joint; every other part
hangs from its parent part; walls are fixed boxes on ``world``. Every link has an inertial (from
its shapes' volume and the part's density), a visual and a collision per shape with native
``box``/``cylinder`` geometry. Every joint has ``<limit>`` and ``<dynamics>``. Built as a
:class:`scenes.description.SceneModel` and written by :func:`scenes.description.write_urdf`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .description import (DEFAULT_RGBA, LABEL_RGBA, WORLD_LINK, Dynamics, Inertial, Joint, Limit, Link, Material,
                          SceneModel, Shape, T_translation, mass_properties, urdf_text, write_urdf)
from .model import ArticulatedObject, JointType, Scene

__all__ = ["scene_model", "urdf_from_scene", "write_truth_urdf", "WALL_DENSITY"]

WALL_DENSITY = 1500.0  # kg/m^3, plaster board/brick-ish; walls are fixed, the mass only keeps loaders quiet


def _link(name: str, label: str, shapes, inertial: Inertial) -> Link:
    """A link whose visuals (``name_v{k}``, coloured by ``label``) and collisions (``name_c{k}``) are ``shapes``."""
    material = Material(f"mat_{label}", tuple(float(x) for x in LABEL_RGBA.get(label, DEFAULT_RGBA)))
    return Link(name, inertial,
                tuple(Shape(s.kind, s.size, s.T_link_shape, f"{name}_v{k}", material=material)
                      for k, s in enumerate(shapes)),
                tuple(Shape(s.kind, s.size, s.T_link_shape, f"{name}_c{k}") for k, s in enumerate(shapes)))


def _object_items(obj: ArticulatedObject) -> tuple[list, list]:
    links = []
    for part in obj.parts:
        m, com, inertia = mass_properties(part.shapes, part.density)
        links.append(_link(obj.link(part), part.label, part.shapes, Inertial(m, T_translation(com), inertia)))
    joints = []
    for j in obj.joints:
        child = obj.part(j.child)
        name = obj.joint_name(j)
        if j.parent is None:
            joints.append(Joint(name, JointType.FIXED, WORLD_LINK, obj.link(child),
                                obj.T_world_object @ child.T_object_part, dynamics=Dynamics()))
            continue
        parent = obj.part(j.parent)
        T_parent_child = np.linalg.inv(parent.T_object_part) @ child.T_object_part
        if j.type is JointType.FIXED:
            joints.append(Joint(name, j.type, obj.link(parent), obj.link(child), T_parent_child,
                                dynamics=Dynamics(j.damping, j.friction)))
            continue
        axis_child = child.T_object_part[:3, :3].T @ j.axis
        joints.append(Joint(name, j.type, obj.link(parent), obj.link(child), T_parent_child,
                            axis_child / np.linalg.norm(axis_child), Limit(j.lower, j.upper, j.effort, j.velocity),
                            Dynamics(j.damping, j.friction)))
    return links, joints


def scene_model(scene: Scene) -> SceneModel:
    """The :class:`SceneModel` of ``scene`` (closed state = every joint at 0; see the module docstring)."""
    links = [Link(WORLD_LINK, Inertial(0.0, np.eye(4), np.zeros((3, 3))))]
    joints = []
    for wall in scene.walls:
        box = Shape.box(wall.size)
        m = float(np.prod(wall.size) * WALL_DENSITY)
        links.append(_link(wall.name, "wall", [box], Inertial(m, np.eye(4), box.inertia(m))))
        joints.append(Joint(f"{wall.name}_joint", JointType.FIXED, WORLD_LINK, wall.name, wall.T_world_wall,
                            dynamics=Dynamics()))
    for obj in scene.objects:
        obj_links, obj_joints = _object_items(obj)
        links += obj_links
        joints += obj_joints
    return SceneModel(f"partscene_{scene.name}", links, joints)


def urdf_from_scene(scene: Scene) -> str:
    """The URDF text of ``scene`` (closed state = every joint at 0)."""
    return urdf_text(scene_model(scene))


def write_truth_urdf(scene: Scene, path: str | Path) -> Path:
    """Write ``truth.urdf`` atomically; returns the path."""
    return write_urdf(scene_model(scene), path)
