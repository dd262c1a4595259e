"""A sampled world as a scene URDF: the certified scene with one :class:`~simcheck.perturbations.Perturbation`
applied (the input file is never modified). XML is edited as :mod:`simcheck.estimate_faults` does.

* the task joint's axis, hinge line and upper limit set to the perturbation's (world frame at q = 0); the
  moving part's geometry, inertia and child joints stay where they are (only the articulation changes);
* the joint's ``<dynamics friction damping>``; the moving link's mass and inertia scaled;
* every link fixed below the moving link whose name contains "handle": ``<contact><lateral_friction>``
  set, and moved by ``handle_shift`` (world);
* the robot's base error (dx, dy, dyaw about the ``pivot`` (x, y) -- where the robot stands): the whole
  scene moved by the inverse error, so the robot stands where it thinks it does relative to a scene that
  is elsewhere. A new root link ``robust_root`` holds the old root by a fixed joint ``robust_base_error``.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from planners.scene_urdf import read_scene_urdf
from simcheck.estimate_faults import _fmt, _joint, _move_joint_keep_geometry, _vec
from simcheck.perturbations import Perturbation

__all__ = ["perturbed_scene_text", "write_perturbed_scene", "ROOT_LINK", "ROOT_JOINT"]

ROOT_LINK = "robust_root"
ROOT_JOINT = "robust_base_error"


def _child(root, j):
    name = j.find("child").get("link")
    return next(l for l in root.findall("link") if l.get("name") == name)


def _T_error_inverse(base_error, pivot_xy) -> np.ndarray:
    """(4, 4) the inverse of the base error: a rotation by -dyaw about the pivot, then -(dx, dy)."""
    dx, dy, dyaw = (float(v) for v in base_error)
    c, s = np.cos(-dyaw), np.sin(-dyaw)
    R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    p = np.array([float(pivot_xy[0]), float(pivot_xy[1]), 0.0])
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p - R @ p - np.array([dx, dy, 0.0])
    return T


def perturbed_scene_text(src: str | Path, p: Perturbation, pivot_xy=(0.0, 0.0)) -> str:
    """The URDF text of scene ``src`` with ``p`` applied (see the module docstring)."""
    scene = read_scene_urdf(src)
    tree = ET.parse(src)
    root = tree.getroot()
    j = _joint(root, p.joint)
    sj = scene.joints[p.joint]
    T_world_joint = scene.T_world_link(sj.parent) @ sj.T_parent_joint
    R = T_world_joint[:3, :3]
    shift_world = np.asarray(p.origin) - T_world_joint[:3, 3]
    if np.linalg.norm(shift_world) > 0.0:
        _move_joint_keep_geometry(root, j, R.T @ shift_world)
    axis = j.find("axis")
    if axis is None:
        axis = ET.SubElement(j, "axis")
    axis.set("xyz", _fmt(R.T @ np.asarray(p.axis)))
    limit = j.find("limit")
    if limit is None:
        limit = ET.SubElement(j, "limit", lower="0", effort="100", velocity="1")
    limit.set("upper", f"{p.upper:.9g}")
    dyn = j.find("dynamics")
    if dyn is None:
        dyn = ET.SubElement(j, "dynamics")
    dyn.set("friction", f"{p.joint_friction:.6g}")
    dyn.set("damping", f"{p.joint_damping:.6g}")
    link = _child(root, j)
    inertial = link.find("inertial")
    if inertial is not None:
        mass = inertial.find("mass")
        if mass is not None:
            mass.set("value", f"{float(mass.get('value')) * p.mass_scale:.9g}")
        inertia = inertial.find("inertia")
        if inertia is not None:
            for k in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz"):
                if inertia.get(k) is not None:
                    inertia.set(k, f"{float(inertia.get(k)) * p.mass_scale:.9g}")
    _perturb_handles(root, link.get("name"), p, R_world_part=R)
    if any(abs(v) > 0.0 for v in p.base_error):
        _move_scene(root, _T_error_inverse(p.base_error, pivot_xy))
    return ET.tostring(root, encoding="unicode")


def _perturb_handles(root, part: str, p: Perturbation, R_world_part: np.ndarray) -> None:
    """Handles fixed (at any depth) below link ``part``: friction set, moved by ``p.handle_shift`` (world)."""
    joints = root.findall("joint")
    stack = [part]
    while stack:
        parent = stack.pop()
        for h in joints:
            if h.find("parent").get("link") != parent or h.get("type") != "fixed":
                continue
            child = h.find("child").get("link")
            stack.append(child)
            if "handle" not in child.lower():
                continue
            link = _child(root, h)
            contact = link.find("contact")
            if contact is None:
                contact = ET.SubElement(link, "contact")
            lat = contact.find("lateral_friction")
            if lat is None:
                lat = ET.SubElement(contact, "lateral_friction")
            lat.set("value", f"{p.handle_friction:.6g}")
            if parent == part and any(abs(v) > 0.0 for v in p.handle_shift):
                o = h.find("origin")
                if o is None:
                    o = ET.SubElement(h, "origin")
                o.set("xyz", _fmt(_vec(o, "xyz") + R_world_part.T @ np.asarray(p.handle_shift)))


def _move_scene(root, T: np.ndarray) -> None:
    """Hang the whole scene from a new root link by a fixed joint at pose ``T`` (4, 4)."""
    from scipy.spatial.transform import Rotation

    children = {j.find("child").get("link") for j in root.findall("joint")}
    old_root = next(l.get("name") for l in root.findall("link") if l.get("name") not in children)
    root.insert(0, ET.Element("link", name=ROOT_LINK))
    jt = ET.SubElement(root, "joint", name=ROOT_JOINT, type="fixed")
    ET.SubElement(jt, "parent", link=ROOT_LINK)
    ET.SubElement(jt, "child", link=old_root)
    ET.SubElement(jt, "origin", xyz=_fmt(T[:3, 3]), rpy=_fmt(Rotation.from_matrix(T[:3, :3]).as_euler("xyz")))


def write_perturbed_scene(src: str | Path, p: Perturbation, out: str | Path, pivot_xy=(0.0, 0.0)) -> Path:
    """Write :func:`perturbed_scene_text` to ``out`` (atomically) and return its path. Relative mesh paths
    are resolved against ``src``'s folder, so ``out`` may live elsewhere."""
    text = perturbed_scene_text(src, p, pivot_xy)
    root = ET.fromstring(text)
    base = Path(src).resolve().parent
    for mesh in root.iter("mesh"):
        fn = mesh.get("filename", "")
        if fn and "://" not in fn and not Path(fn).is_absolute():
            mesh.set("filename", str((base / fn).resolve()))
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_suffix(out.suffix + ".tmp")
    tmp.write_text(ET.tostring(root, encoding="unicode"))
    tmp.replace(out)
    return out
