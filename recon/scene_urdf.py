"""``scene.urdf`` from a :class:`Reconstruction` (built with yourdfpy's schema dataclasses).

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

Every visual carries a material coloured by its part label (``scenes.description.LABEL_RGBA``;
walls ``wall``). Numbers are written rounded so that the same reconstruction gives the same bytes:
lengths and angles (origins, sizes, axes, limits) to ``LENGTH_DECIMALS`` decimals, masses and
inertias to ``SIGNIFICANT_DIGITS`` significant digits (an inertia term relative to the largest
term of its tensor, so round-off terms near zero are written as 0).
"""

from __future__ import annotations

import numpy as np
import yourdfpy

from recon.model import JointType, Reconstruction
from recon.primitive import Primitive, PrimitiveKind
from scenes.description import DEFAULT_RGBA, LABEL_RGBA, WORLD_LINK

__all__ = ["urdf_robot", "urdf_string", "link_frames", "compound_inertial", "label_rgba",
           "LENGTH_DECIMALS", "SIGNIFICANT_DIGITS"]

LENGTH_DECIMALS = 6
"""Lengths (m) and angles (rad) in scene.urdf are rounded to 1e-6."""
SIGNIFICANT_DIGITS = 9
"""Masses and inertias in scene.urdf keep this many significant digits."""


WALL_DENSITY = 1500.0
"""kg/m^3 of a wall box (fixed to the world; the mass only keeps loaders quiet)."""


def _translation(p: np.ndarray) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = p
    return T


def label_rgba(label: str) -> tuple[float, float, float, float]:
    """(r, g, b, a) in 0..1 of a part label (grey for a label without a colour)."""
    return tuple(float(x) for x in LABEL_RGBA.get(label, DEFAULT_RGBA))


def _material(label: str) -> yourdfpy.Material:
    return yourdfpy.Material(name=f"label_{label}", color=yourdfpy.Color(rgba=np.array(label_rgba(label))))


def _geometry(prim: Primitive) -> yourdfpy.Geometry:
    if prim.kind is PrimitiveKind.BOX:
        return yourdfpy.Geometry(box=yourdfpy.Box(size=np.asarray(prim.size, float)))
    if prim.kind is PrimitiveKind.CYLINDER:
        return yourdfpy.Geometry(cylinder=yourdfpy.Cylinder(radius=prim.radius, length=prim.length))
    return yourdfpy.Geometry(sphere=yourdfpy.Sphere(radius=prim.size[0] / 2.0))


def compound_inertial(solids, density: float, T_link_world: np.ndarray) -> tuple[np.ndarray, float, np.ndarray]:
    """(T_link_com (4, 4), mass kg, (3, 3) inertia about the centre of mass in the link's axes) of the
    union of ``solids`` (world-frame primitives, overlaps counted twice: panels meet only at edges)
    of uniform ``density`` (kg/m^3). A single primitive keeps its own axes (T_link_com = T_link_part)."""
    if len(solids) == 1:
        T_lp = T_link_world @ solids[0].T_world_part
        mass = density * solids[0].volume
        return T_lp, mass, solids[0].inertia(mass)
    masses = np.array([density * p.volume for p in solids])
    T_lps = [T_link_world @ p.T_world_part for p in solids]
    centres = np.array([T[:3, 3] for T in T_lps])
    mass = float(masses.sum())
    com = (masses[:, None] * centres).sum(axis=0) / mass
    inertia = np.zeros((3, 3))
    for m, T, p in zip(masses, T_lps, solids):
        R, r = T[:3, :3], T[:3, 3] - com
        inertia += R @ p.inertia(float(m)) @ R.T + m * (float(r @ r) * np.eye(3) - np.outer(r, r))
    T_lc = np.eye(4)
    T_lc[:3, 3] = com
    return T_lc, mass, inertia


def link_frames(rec: Reconstruction) -> dict[str, np.ndarray]:
    """{link name: T_world_link (4, 4)} of every part link (joint value 0)."""
    out = {}
    for obj in rec.objects:
        for j in obj.joints:
            link = obj.part(j.child_part_id).link
            out[link] = _translation(j.origin if j.type is not JointType.FIXED else obj.part(j.child_part_id).primitive.center)
    return out


def urdf_robot(rec: Reconstruction, name: str = "scene") -> yourdfpy.Robot:
    """The scene as a yourdfpy ``Robot`` (see the module docstring for frames and inertials)."""
    cfg = rec.config
    frames = link_frames(rec)
    links = [yourdfpy.Link(name=WORLD_LINK)]
    joints = []
    for obj in rec.objects:
        moving = set()
        parent_of = {j.child_part_id: j.parent_part_id for j in obj.joints}
        for j in obj.joints:
            if j.type is not JointType.FIXED:
                moving.add(j.child_part_id)
        changed = True
        while changed:   # everything hanging from a moving part moves too
            changed = False
            for c, p in parent_of.items():
                if p in moving and c not in moving:
                    moving.add(c)
                    changed = True
        for part in obj.parts:
            T_lw = np.linalg.inv(frames[part.link])
            solids = part.solids
            T_lc, mass, inertia = compound_inertial(solids, cfg.density, T_lw)
            visuals, collisions = [], []
            for k, prim in enumerate(solids):
                T_lp = T_lw @ prim.T_world_part
                suffix = "" if len(solids) == 1 else str(k)
                coll = prim.shrunk(cfg.collision_clearance) if part.part_id in moving else prim
                visuals.append(yourdfpy.Visual(name=f"{part.link}_visual{suffix}", origin=T_lp,
                                               geometry=_geometry(prim), material=_material(part.label)))
                collisions.append(yourdfpy.Collision(name=f"{part.link}_collision{suffix}", origin=T_lp,
                                                     geometry=_geometry(coll)))
            links.append(yourdfpy.Link(
                name=part.link, inertial=yourdfpy.Inertial(origin=T_lc, mass=float(mass), inertia=inertia),
                visuals=visuals, collisions=collisions))
        for j in obj.joints:
            child = obj.part(j.child_part_id).link
            if j.parent_part_id is None:
                parent, T_wp = WORLD_LINK, np.eye(4)
            else:
                parent = obj.part(j.parent_part_id).link
                T_wp = frames[parent]
            origin = np.linalg.inv(T_wp) @ frames[child]
            kw = {}
            if j.type is not JointType.FIXED:
                kw = dict(axis=np.asarray(j.axis, float),
                          limit=yourdfpy.Limit(effort=cfg.joint_effort, velocity=cfg.joint_velocity,
                                               lower=float(j.lower), upper=float(j.upper)),
                          dynamics=yourdfpy.Dynamics(damping=cfg.joint_damping, friction=cfg.joint_friction))
            else:
                kw = dict(dynamics=yourdfpy.Dynamics(damping=0.0, friction=0.0))
            joints.append(yourdfpy.Joint(name=j.name, type=j.type.value, parent=parent, child=child,
                                         origin=origin, **kw))
    for wall in rec.walls:       # fixed boxes on the world, named like the truth's (wall0, wall1, ...)
        prim = Primitive(PrimitiveKind.BOX, wall.size, np.eye(4))
        mass = WALL_DENSITY * prim.volume
        links.append(yourdfpy.Link(
            name=wall.name, inertial=yourdfpy.Inertial(origin=np.eye(4), mass=float(mass), inertia=prim.inertia(mass)),
            visuals=[yourdfpy.Visual(name=f"{wall.name}_visual", origin=np.eye(4), geometry=_geometry(prim),
                                     material=_material("wall"))],
            collisions=[yourdfpy.Collision(name=f"{wall.name}_collision", origin=np.eye(4), geometry=_geometry(prim))]))
        joints.append(yourdfpy.Joint(name=f"{wall.name}_joint", type="fixed", parent=WORLD_LINK, child=wall.name,
                                     origin=wall.T_world_wall, dynamics=yourdfpy.Dynamics(damping=0.0, friction=0.0)))
    return yourdfpy.Robot(name=name, links=links, joints=joints)


def urdf_string(rec: Reconstruction, name: str = "scene") -> str:
    """The scene.urdf text."""
    from lxml import etree

    urdf = yourdfpy.URDF(robot=urdf_robot(rec, name), build_scene_graph=False, load_meshes=False)
    xml = urdf.write_xml()
    _round_numbers(xml.getroot())
    # pretty-printed: PyBullet's tinyxml2 fails to parse yourdfpy's one-line output of a large scene
    return etree.tostring(xml, xml_declaration=True, encoding="UTF-8", pretty_print=True).decode()


_LENGTH_ATTRIBUTES = {("origin", "xyz"), ("origin", "rpy"), ("box", "size"), ("cylinder", "radius"),
                      ("cylinder", "length"), ("sphere", "radius"), ("axis", "xyz"), ("limit", "lower"),
                      ("limit", "upper")}
_INERTIA_KEYS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def _length(x: float) -> str:
    text = f"{round(float(x), LENGTH_DECIMALS) + 0.0:.{LENGTH_DECIMALS}f}".rstrip("0").rstrip(".")
    return "0" if text in ("", "-0") else text


def _significant(x: float, scale: float | None = None) -> str:
    """``x`` to SIGNIFICANT_DIGITS digits (of ``scale`` when given: terms far below it become 0)."""
    x = float(x)
    if scale is not None and scale > 0:
        step = 10.0 ** (np.floor(np.log10(scale)) - (SIGNIFICANT_DIGITS - 1))
        x = round(x / step) * step
    return f"{x + 0.0:.{SIGNIFICANT_DIGITS}g}"


def _round_numbers(root) -> None:
    """Rewrite the numbers of a URDF element tree in place (see the module docstring)."""
    for el in root.iter():
        for key in list(el.attrib):
            if (el.tag, key) in _LENGTH_ATTRIBUTES:
                el.set(key, " ".join(_length(float(v)) for v in el.get(key).split()))
            elif el.tag == "mass" and key == "value":
                el.set(key, _significant(float(el.get(key))))
        if el.tag == "inertia":
            vals = [float(el.get(k, 0.0)) for k in _INERTIA_KEYS]
            scale = max(abs(v) for v in vals)
            for k, v in zip(_INERTIA_KEYS, vals):
                el.set(k, _significant(v, scale))
