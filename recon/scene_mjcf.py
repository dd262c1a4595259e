"""``scene.xml``: the scene as MJCF, for MuJoCo to load natively (``recon build --mjcf``).

Written from the same description as scene.urdf (:func:`recon.scene_urdf.scene_model`, a
:class:`scenes.description.SceneModel`), so bodies,
joints, inertials and shapes are the URDF's, name for name:

    link            -> ``<body name=link>`` nested under its parent link's body (``world`` = worldbody),
                       posed by the joint origin (``pos``, ``quat`` w x y z); a fixed joint adds no joint
    revolute/prismatic -> ``<joint name type="hinge"/"slide" axis range damping frictionloss armature>``
                       (the URDF's ``<dynamics friction>`` is MuJoCo's ``frictionloss``; URDF has no
                       armature: ``JOINT_ARMATURE``)
    inertial        -> ``<inertial pos quat mass fullinertia>`` (geoms never add mass)
    visual          -> a geom that never collides (group 1), coloured by its part label's material
    collision       -> a geom that collides (group 3, hidden by default), sizes as in the URDF

MuJoCo collides a moving body with the bodies that do not move with it (and with its parent when the
parent is the world); scene.urdf's links do not overlap at q = 0 (recon.clearance), so the model rests.
Link pairs given in ``exclude`` become ``<contact><exclude>`` (for pairs that still overlap).
Gravity pulls against the scene's floor: a scene kept in its scan's frame with a tilted floor (graph.json's
``floor``) gets ``<option gravity>`` along the floor's normal, so MuJoCo loads it standing as simcheck's
world does; a level floor keeps MuJoCo's default (0, 0, -9.81).
Numbers are rounded as in scene.urdf (lengths 1e-6, masses and inertias 9 significant digits).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
from scipy.spatial.transform import Rotation

from scenes.description import WORLD_LINK, Inertial, Joint, Link, SceneModel, Shape, ShapeKind

__all__ = ["mjcf_string", "reconstruction_mjcf", "JOINT_ARMATURE", "GRAVITY"]

JOINT_ARMATURE = 0.0
"""Armature (kg m^2 or kg) of every movable joint: 0, as a URDF joint has none."""

GRAVITY = 9.81
"""Magnitude of gravity, m/s^2 (MuJoCo's default, and simcheck's)."""

_LENGTH_DECIMALS = 6
_SIGNIFICANT = 9


def _len(x: float) -> str:
    text = f"{round(float(x), _LENGTH_DECIMALS) + 0.0:.{_LENGTH_DECIMALS}f}".rstrip("0").rstrip(".")
    return "0" if text in ("", "-0") else text


def _vec(v) -> str:
    return " ".join(_len(x) for x in np.asarray(v, float).ravel())


def _sig(x: float, scale: float | None = None) -> str:
    x = float(x)
    if scale:
        step = 10.0 ** (np.floor(np.log10(scale)) - (_SIGNIFICANT - 1))
        x = round(x / step) * step
    return f"{x + 0.0:.{_SIGNIFICANT}g}"


def _pose(el: ET.Element, T: np.ndarray | None) -> None:
    """``pos`` and ``quat`` (w x y z, sign fixed so that w >= 0) of ``T`` (4, 4) on ``el``; identity omitted."""
    if T is None:
        return
    T = np.asarray(T, float)
    if np.any(np.abs(T[:3, 3]) > 0):
        el.set("pos", _vec(T[:3, 3]))
    if not np.allclose(T[:3, :3], np.eye(3), atol=1e-12):
        x, y, z, w = Rotation.from_matrix(T[:3, :3]).as_quat()
        q = np.array([w, x, y, z])
        q = -q if q[0] < 0 or (q[0] == 0 and q[np.flatnonzero(q)[0]] < 0) else q
        el.set("quat", _vec(q))


def _geom(body: ET.Element, shape: Shape, **attrib) -> None:
    g = ET.SubElement(body, "geom")
    if shape.name:
        g.set("name", shape.name)
    if shape.kind is ShapeKind.BOX:
        g.set("type", "box")
        g.set("size", _vec(shape.size / 2.0))
    elif shape.kind is ShapeKind.CYLINDER:
        g.set("type", "cylinder")
        g.set("size", f"{_len(shape.radius)} {_len(shape.length / 2.0)}")
    elif shape.kind is ShapeKind.SPHERE:
        g.set("type", "sphere")
        g.set("size", _len(shape.radius))
    else:
        raise ValueError(f"geom {shape.name!r}: only box, cylinder and sphere geometry can be written to MJCF")
    _pose(g, shape.T_link_shape)
    for k, v in attrib.items():
        g.set(k, v)


def _inertial(body: ET.Element, inertial: Inertial) -> None:
    """``<inertial pos mass fullinertia>``: MJCF takes a full inertia only in the body's axes, so the
    URDF's tensor (in its inertial frame) is turned: I_body = R I R^T."""
    T = np.asarray(inertial.T_link_com, float)
    el = ET.SubElement(body, "inertial", pos=_vec(T[:3, 3]))
    el.set("mass", _sig(inertial.mass))
    I = T[:3, :3] @ np.asarray(inertial.inertia, float) @ T[:3, :3].T
    scale = float(np.abs(I).max())
    el.set("fullinertia", " ".join(_sig(I[i, k], scale) for i, k in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))))


def _body(parent: ET.Element, link: Link, joint: Joint) -> ET.Element:
    body = ET.SubElement(parent, "body", name=link.name)
    _pose(body, joint.T_parent_joint)
    if joint.type in ("revolute", "prismatic"):
        j = ET.SubElement(body, "joint", name=joint.name, type="hinge" if joint.type == "revolute" else "slide")
        j.set("axis", _vec(joint.axis))
        if joint.limit is not None:
            j.set("range", f"{_len(joint.limit.lower)} {_len(joint.limit.upper)}")
        dyn = joint.dynamics
        j.set("damping", _sig(dyn.damping if dyn is not None else 0.0))
        j.set("frictionloss", _sig(dyn.friction if dyn is not None else 0.0))
        j.set("armature", _sig(JOINT_ARMATURE))
    elif joint.type != "fixed":
        raise ValueError(f"joint {joint.name!r}: type {joint.type.value!r} cannot be written to MJCF "
                         "(only fixed, revolute and prismatic)")
    if link.inertial is not None and link.inertial.mass:
        _inertial(body, link.inertial)
    for v in link.visuals:
        material = v.material.name if v.material is not None and v.material.name else None
        _geom(body, v, group="1", contype="0", conaffinity="0", **({"material": material} if material else {}))
    for c in link.collisions:
        _geom(body, c, group="3")
    return body


def mjcf_string(model: SceneModel, exclude: tuple[tuple[str, str], ...] = (), gravity=None) -> str:
    """The MJCF text of a scene ``model`` (root link ``world``, primitive shapes only); ``gravity`` (3,) m/s^2
    in the scene frame, written as ``<option gravity>`` (None: MuJoCo's default, (0, 0, -9.81))."""
    links = model.links
    children: dict[str, list[Joint]] = {}
    for j in model.joints.values():
        children.setdefault(j.parent, []).append(j)
    root = ET.Element("mujoco", model=model.name)
    ET.SubElement(root, "compiler", angle="radian", autolimits="true", inertiafromgeom="false")
    if gravity is not None:
        ET.SubElement(root, "option", gravity=" ".join(f"{float(g) + 0.0:.9g}" for g in np.ravel(gravity)))
    asset = ET.SubElement(root, "asset")
    materials = {}
    for link in links.values():
        for v in link.visuals:
            m = v.material
            if m is not None and m.name and m.rgba is not None and m.name not in materials:
                materials[m.name] = m.rgba
    for name, rgba in materials.items():
        ET.SubElement(asset, "material", name=name, rgba=" ".join(f"{float(x):.6g}" for x in rgba))
    world = ET.SubElement(root, "worldbody")
    stack = [(world, WORLD_LINK)]
    while stack:
        parent_el, parent = stack.pop(0)
        for j in children.get(parent, []):
            stack.append((_body(parent_el, links[j.child], j), j.child))
    if exclude:
        contact = ET.SubElement(root, "contact")
        for a, b in exclude:
            ET.SubElement(contact, "exclude", body1=a, body2=b)
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode") + "\n"


def reconstruction_mjcf(rec) -> str:
    """scene.xml of a :class:`recon.model.Reconstruction`: :func:`mjcf_string` of its scene.urdf
    description, excluding the contacts of link pairs that still overlap by more than
    ``ClearanceConfig.report_overlap`` (none after recon.clearance, unless it warned), with gravity against
    the floor graph.json records when that is found and not level."""
    from recon.clearance import links_in_contact
    from recon.scene_urdf import scene_model

    limit = rec.config.clearance.report_overlap
    exclude = tuple((a, b) for a, b, s in links_in_contact(rec.objects, rec.walls, 0.0) if s < -limit)
    floor = rec.floor
    tilted = floor is not None and floor.found and not np.array_equal(floor.normal, (0.0, 0.0, 1.0))
    return mjcf_string(scene_model(rec), exclude, -GRAVITY * floor.normal if tilted else None)
