"""A corpus object as a :class:`scenes.model.Scene`, so the virtual scanner (:mod:`scenes.scanner`) can scan
it with part labels (``scan_scene(scene_of(built), params)``) and ``recon`` can rebuild it.

Parts: the carcass ("body": every link labelled so), each front ("drawer" / "door") and each handle
("handle": a handle link, or the handle geometry of a front split off as its own part, fixed to the front).
A counter the object stands on (links labelled "counter") is a second object, a cabinet of one body part
supporting the first, as a segmentation of a real room separates them. Shapes are the URDF's
collision shapes; a mesh is replaced by its bounding box (the scanner ray-casts primitives). Joints are
re-expressed in the scenes convention (axis and a point on it in the object frame, closed = 0, positive
opens): a file's negative range becomes a positive one about the reversed axis; a continuous hinge gets
``[0, pi]``. The object frame is the URDF's root frame, placed at the world origin.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from pathlib import Path
from xml.etree import ElementTree as ET

from scenes.description import JointType, Shape, ShapeKind, joint_name, read_urdf
from scenes.model import ArticulatedObject, Joint, Part, Scene
from thirdparty.build import BuiltObject

__all__ = ["scene_of", "reference_named_as_scan", "SCANNED_CATEGORY"]

#: corpus categories as the scanner's labels.json names them (recon understands these)
SCANNED_CATEGORY = {"cabinet": "cabinet", "wall_cabinet": "cabinet", "microwave": "microwave",
                    "refrigerator": "refrigerator", "dishwasher": "cabinet", "oven": "cabinet"}

DENSITY = 500.0   # kg/m^3, for the scene's inertials only


def _scannable(shape: Shape) -> Shape:
    if shape.kind is not ShapeKind.MESH:
        return shape
    import trimesh
    lo, hi = trimesh.load(shape.mesh, force="mesh").bounds * np.asarray(shape.size)
    T = shape.T_link_shape.copy()
    T[:3, 3] = T[:3, :3] @ ((lo + hi) / 2) + T[:3, 3]
    return Shape(ShapeKind.BOX, hi - lo, T, shape.name)


def scene_of(built: BuiltObject, object_id: int = 1, name: str | None = None) -> tuple[Scene, dict]:
    """(the Scene holding the object, {URDF joint name: child part id}) for ``built``."""
    m = read_urdf(built.urdf)
    parts, joints, joint_part = [], [], {}
    pid = [10 * object_id]

    def part(label, link, shapes, T=None):
        pid[0] += 1
        T = m.T_world_link(link) if T is None else T
        parts.append(Part(pid[0], label, T, tuple(_scannable(s) for s in shapes), DENSITY))
        return pid[0]

    body_links = [link for link, lab in built.labels.items() if lab == "body"]       # the carcass (and a counter)
    T_body = m.T_world_link(body_links[0])
    body = part("body", body_links[0], [s.moved(np.linalg.solve(T_body, m.T_world_link(link)))
                                        for link in body_links for s in m.links[link].collisions])
    joints.append(Joint(JointType.FIXED, None, body))
    for f in built.fronts:
        j = m.joints[f.joint]
        cols = m.links[f.moving_link].collisions
        own = [c for k, c in enumerate(cols) if k not in f.handle_geoms]
        front = part("drawer" if f.kind == "drawer" else "door", f.moving_link, own)
        T_w_joint = m.T_world_link(f.moving_link)
        sign = 1.0 if j.upper >= -j.lower else -1.0
        span = np.pi if not np.isfinite(j.upper - j.lower) else max(j.upper, -j.lower)
        typ = JointType.PRISMATIC if j.type is JointType.PRISMATIC else JointType.REVOLUTE
        handle = None
        if f.handle_geoms:
            handle = part("handle", f.moving_link, [cols[k] for k in f.handle_geoms])
        for link, lab in f.labels.items():
            if lab == "handle":
                handle = part("handle", link, m.links[link].collisions)
        joints.append(Joint(typ, body, front, sign * (T_w_joint[:3, :3] @ j.axis), T_w_joint[:3, 3].copy(),
                            0.0, float(span), handle=handle, damping=j.dynamics.damping if j.dynamics else 0.0))
        if handle is not None:
            joints.append(Joint(JointType.FIXED, front, handle))
        joint_part[f.joint] = front
    obj = ArticulatedObject(object_id, SCANNED_CATEGORY.get(built.spec.category, "cabinet"), tuple(parts),
                            tuple(joints), ())
    objects = (obj,)
    counter_links = [link for link, lab in built.labels.items() if lab == "counter"]
    if counter_links:
        T_c = m.T_world_link(counter_links[0])
        top = Part(pid[0] + 1, "body", T_c,
                   tuple(_scannable(s.moved(np.linalg.solve(T_c, m.T_world_link(link))))
                         for link in counter_links for s in m.links[link].collisions), DENSITY)
        counter = ArticulatedObject(object_id + 1, "cabinet", (top,), (Joint(JointType.FIXED, None, top.id),), ())
        objects = (dataclasses.replace(obj, supported_by=counter.id), counter)
    return Scene(name or built.spec.name, 0, objects, (), np.array([6.0, 6.0])), joint_part


def reference_named_as_scan(built: BuiltObject, scene: Scene, joint_part: dict, out) -> tuple[Path, dict]:
    """Write a copy of ``built.urdf`` to ``out`` with each front's joint renamed to the name ``recon`` gives the
    joint of the same part (``cabinet1_door12_joint``), so a reconstruction of ``scene``'s scan can be
    certified ``--against`` the third-party file itself (joints are matched by name). Returns (the path,
    {the file's joint name: the new name}). Geometry, frames and limits are unchanged."""
    obj = scene.objects[0]
    names = {j: joint_name(obj.category, obj.id, obj.part(pid).label, pid) for j, pid in joint_part.items()}
    tree = ET.parse(built.urdf)
    for el in tree.getroot().iter("joint"):
        if el.get("name") in names:
            el.set("name", names[el.get("name")])
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    for el in tree.getroot().iter("mesh"):       # meshes stay where the corpus wrote them
        f = Path(el.get("filename"))
        if not f.is_absolute():
            el.set("filename", str((built.urdf.parent / f).resolve()))
    tree.write(out, encoding="unicode", xml_declaration=True)
    return out, names
