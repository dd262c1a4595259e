"""``scene.urdf`` from a :class:`Reconstruction`: its :class:`scenes.description.SceneModel`, written by
:func:`scenes.description.urdf_text` (rounded).

Shape (docs/contracts.md "Scene URDF shape"): root link ``world``; each object's root part fixed to
``world``; every other part hangs from its tree parent by its estimated joint; handles are their own
links fixed to their drawer/door. Walls fitted to the background are fixed boxes on ``world``
(links ``wall0``, ``wall1``, ...; joints ``wall0_joint``, ...).

Frames: every link frame is world-aligned (identity rotation in the world at joint value 0) and sits
at the joint's origin — on the axis for a movable joint, at the part's centre for a fixed one — so a
URDF ``<axis>`` equals the world axis of graph.json and a joint origin is a pure translation. The
primitive sits in its link at ``T_link_part``; a part with articulated-template shapes (a drawer's box,
a body's carcass; ``PartFit.solids``) has one visual and one collision per shape. Mass = ``density`` ×
volume; inertia is the closed form of the primitive (of each shape, combined about their centre of mass
with the parallel-axis theorem), in the link frame. Parts that move (drawers, doors and what
hangs from them) get collision shapes shrunk by ``collision_clearance`` so they do not start in
contact with their body or siblings.

A door hinged about a horizontal axis (a flap, an oven's or a dishwasher's drop-down door) gets the
joint friction of the stay or counterbalance spring such doors carry and a scan does not show
(:func:`scenes.description.stay_friction`: 1.2 × the largest gravity torque on it); every other movable
joint ``joint_friction``.

Every visual carries a material coloured by its part label (``scenes.description.LABEL_RGBA``;
walls ``wall``). Numbers are written rounded (:func:`scenes.description.round_numbers`) so that the
same reconstruction gives the same bytes.
"""

from __future__ import annotations

import numpy as np

from recon.model import JointType, Reconstruction
from recon.primitive import Primitive, PrimitiveKind
from scenes.description import (DEFAULT_RGBA, LABEL_RGBA, WORLD_LINK, Dynamics, Inertial, Joint, Limit, Link,
                                Material, SceneModel, Shape, T_translation, mass_properties, urdf_text,
                                with_stays)

__all__ = ["scene_model", "urdf_string", "link_frames", "compound_inertial", "label_rgba"]

WALL_DENSITY = 1500.0
"""kg/m^3 of a wall box (fixed to the world; the mass only keeps loaders quiet)."""


def label_rgba(label: str) -> tuple[float, float, float, float]:
    """(r, g, b, a) in 0..1 of a part label (grey for a label without a colour)."""
    return tuple(float(x) for x in LABEL_RGBA.get(label, DEFAULT_RGBA))


def _material(label: str) -> Material:
    return Material(f"label_{label}", label_rgba(label))


def _shape(prim: Primitive, T_link_shape: np.ndarray, name: str, material: Material | None = None) -> Shape:
    return Shape(prim.kind, prim.size, T_link_shape, name, None, material)


def compound_inertial(solids, density: float, T_link_world: np.ndarray) -> tuple[np.ndarray, float, np.ndarray]:
    """(T_link_com (4, 4), mass kg, (3, 3) inertia about the centre of mass in the link's axes) of the
    union of ``solids`` (world-frame primitives, overlaps counted twice: panels meet only at edges)
    of uniform ``density`` (kg/m^3). A single primitive keeps its own axes (T_link_com = T_link_part)."""
    if len(solids) == 1:
        T_lp = T_link_world @ solids[0].T_world_part
        mass = density * solids[0].volume
        return T_lp, mass, solids[0].inertia(mass)
    mass, com, inertia = mass_properties([_shape(p, T_link_world @ p.T_world_part, "") for p in solids], density)
    return T_translation(com), mass, inertia


def link_frames(rec: Reconstruction) -> dict[str, np.ndarray]:
    """{link name: T_world_link (4, 4)} of every part link (joint value 0)."""
    out = {}
    for obj in rec.objects:
        for j in obj.joints:
            part = obj.part(j.child_part_id)
            out[part.link] = T_translation(j.origin if j.type is not JointType.FIXED else part.primitive.center)
    return out


def _moving_parts(obj) -> set:
    """Part ids moved by a movable joint, and everything hanging from them."""
    moving = {j.child_part_id for j in obj.joints if j.type is not JointType.FIXED}
    parent_of = {j.child_part_id: j.parent_part_id for j in obj.joints}
    changed = True
    while changed:
        changed = False
        for c, p in parent_of.items():
            if p in moving and c not in moving:
                moving.add(c)
                changed = True
    return moving


def scene_model(rec: Reconstruction, name: str = "scene") -> SceneModel:
    """The scene as a :class:`SceneModel` (see the module docstring for frames and inertials)."""
    cfg = rec.config.urdf
    frames = link_frames(rec)
    links, joints = [Link(WORLD_LINK)], []
    for obj in rec.objects:
        moving = _moving_parts(obj)
        for part in obj.parts:
            T_lw = np.linalg.inv(frames[part.link])
            solids = part.solids
            T_lc, mass, inertia = compound_inertial(solids, cfg.density, T_lw)
            visuals, collisions = [], []
            for k, prim in enumerate(solids):
                T_lp = T_lw @ prim.T_world_part
                suffix = "" if len(solids) == 1 else str(k)
                coll = prim.shrunk(cfg.collision_clearance) if part.part_id in moving else prim
                visuals.append(_shape(prim, T_lp, f"{part.link}_visual{suffix}", _material(part.label)))
                collisions.append(_shape(coll, T_lp, f"{part.link}_collision{suffix}"))
            links.append(Link(part.link, Inertial(float(mass), T_lc, inertia), tuple(visuals), tuple(collisions)))
        for j in obj.joints:
            child = obj.part(j.child_part_id).link
            parent = WORLD_LINK if j.parent_part_id is None else obj.part(j.parent_part_id).link
            T_wp = np.eye(4) if j.parent_part_id is None else frames[parent]
            origin = np.linalg.inv(T_wp) @ frames[child]
            if j.type is not JointType.FIXED:
                joints.append(Joint(j.name, j.type.value, parent, child, origin, np.asarray(j.axis, float),
                                    Limit(float(j.lower), float(j.upper), cfg.joint_effort, cfg.joint_velocity),
                                    Dynamics(cfg.joint_damping, cfg.joint_friction)))
            else:
                joints.append(Joint(j.name, "fixed", parent, child, origin, dynamics=Dynamics(0.0, 0.0)))
    for wall in rec.walls:       # fixed boxes on the world, named like the truth's (wall0, wall1, ...)
        prim = Primitive(PrimitiveKind.BOX, wall.size, np.eye(4))
        mass = WALL_DENSITY * prim.volume
        links.append(Link(wall.name, Inertial(float(mass), np.eye(4), prim.inertia(mass)),
                          (_shape(prim, np.eye(4), f"{wall.name}_visual", _material("wall")),),
                          (_shape(prim, np.eye(4), f"{wall.name}_collision"),)))
        joints.append(Joint(f"{wall.name}_joint", "fixed", WORLD_LINK, wall.name, wall.T_world_wall,
                            dynamics=Dynamics(0.0, 0.0)))
    up = rec.floor.normal if rec.floor is not None else np.array([0.0, 0.0, 1.0])
    return with_stays(SceneModel(name, links, joints), -cfg.gravity * up)     # a scan shows no flap's stay


def urdf_string(rec: Reconstruction, name: str = "scene") -> str:
    """The scene.urdf text (numbers rounded)."""
    return urdf_text(scene_model(rec, name), rounded=True)
