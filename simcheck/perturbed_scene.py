"""A sampled world as a scene URDF: the certified scene with one :class:`~simcheck.perturbations.Perturbation`
applied (the input file is never modified). The scene model is edited as :mod:`simcheck.estimate_faults`
does and written by :func:`scenes.description.write_urdf`.

* the task joint's axis, hinge line and upper limit set to the perturbation's (world frame at q = 0; the axis
  written as a unit vector in the joint frame, whatever the perturbation's length); the moving part's
  geometry, inertia and child joints stay where they are (only the articulation changes);
* the joint's ``<dynamics friction damping>``; the moving link's mass and inertia scaled; a flap's or a
  drop-down door's friction at least its stay's in that world (:func:`scenes.description.stay_friction`);
* every link fixed below the moving link whose name contains "handle": its ``lateral_friction``
  (``<contact><lateral_friction>``) set, and moved by ``handle_shift`` (world);
* the robot's base error (dx, dy, dyaw about the ``pivot`` (x, y) -- where the robot stands): the whole
  scene moved by the inverse error, so the robot stands where it thinks it does relative to a scene that
  is elsewhere. A new root link ``robust_root`` holds the old root by a fixed joint ``robust_base_error``.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from planners.scene_urdf import read_scene_urdf
from scenes.description import (Dynamics, Joint, JointType, Limit, Link, SceneModel, read_scene_floor,
                                urdf_text, with_stays, write_urdf)
from simcheck.config import PhysicsConfig
from simcheck.estimate_faults import _move_joint_keep_geometry, _shifted
from simcheck.perturbations import Perturbation

__all__ = ["perturbed_scene", "perturbed_scene_text", "write_perturbed_scene", "base_error_inverse", "ROOT_LINK", "ROOT_JOINT"]

ROOT_LINK = "robust_root"
ROOT_JOINT = "robust_base_error"


def base_error_inverse(base_error, pivot_xy) -> np.ndarray:
    """(4, 4) the inverse of the base error (dx m, dy m, dyaw rad): a rotation by -dyaw about the pivot
    (x, y) m, then a shift by -(dx, dy): where a sampled world puts its scene."""
    dx, dy, dyaw = (float(v) for v in base_error)
    c, s = np.cos(-dyaw), np.sin(-dyaw)
    R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    p = np.array([float(pivot_xy[0]), float(pivot_xy[1]), 0.0])
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p - R @ p - np.array([dx, dy, 0.0])
    return T


def _g6(x: float) -> float:
    """``x`` to 6 significant digits (what a sampled friction or damping is worth)."""
    return float(f"{float(x):.6g}")


def perturbed_scene(src: str | Path, p: Perturbation, pivot_xy=(0.0, 0.0)) -> SceneModel:
    """The scene model of ``src`` with ``p`` applied (see the module docstring)."""
    model = read_scene_urdf(src)
    j = model.joints[p.joint]
    T_world_joint = model.T_world_link(j.parent) @ j.T_parent_joint
    R = T_world_joint[:3, :3]
    shift_world = np.asarray(p.origin) - T_world_joint[:3, 3]
    limit = j.limit if j.limit is not None else Limit(0.0, 0.0, 100.0, 1.0)
    axis = R.T @ np.asarray(p.axis, dtype=float)
    changes = dict(axis=axis / np.linalg.norm(axis), limit=dataclasses.replace(limit, upper=float(p.upper)),
                   dynamics=Dynamics(damping=_g6(p.joint_damping), friction=_g6(p.joint_friction)))
    if np.linalg.norm(shift_world) > 0.0:
        items = _move_joint_keep_geometry(model, j, R.T @ shift_world, **changes)
    else:
        items = [dataclasses.replace(j, **changes), model.links[j.child]]
    link = items[1]
    if link.inertial is not None:
        items[1] = dataclasses.replace(link, inertial=dataclasses.replace(
            link.inertial, mass=link.inertial.mass * p.mass_scale, inertia=link.inertial.inertia * p.mass_scale))
    model = model.replaced(*items)
    model = with_stays(model, read_scene_floor(src).gravity(PhysicsConfig.gravity), [p.joint])
    model = model.replaced(*_perturbed_handles(model, j.child, p, R_world_part=R))
    if any(abs(v) > 0.0 for v in p.base_error):
        model = _moved_scene(model, base_error_inverse(p.base_error, pivot_xy))
    return model


def perturbed_scene_text(src: str | Path, p: Perturbation, pivot_xy=(0.0, 0.0)) -> str:
    """The URDF text of scene ``src`` with ``p`` applied (mesh paths absolute)."""
    return urdf_text(perturbed_scene(src, p, pivot_xy))


def _perturbed_handles(model: SceneModel, part: str, p: Perturbation, R_world_part: np.ndarray) -> list:
    """Handles fixed (at any depth) below link ``part``: friction set, moved by ``p.handle_shift`` (world)."""
    out, stack = [], [part]
    while stack:
        parent = stack.pop()
        for h in model.child_joints(parent):
            if h.type is not JointType.FIXED:
                continue
            stack.append(h.child)
            if "handle" not in h.child.lower():
                continue
            out.append(dataclasses.replace(model.links[h.child], lateral_friction=_g6(p.handle_friction)))
            if parent == part and any(abs(v) > 0.0 for v in p.handle_shift):
                out.append(dataclasses.replace(
                    h, T_parent_joint=_shifted(h.T_parent_joint, R_world_part.T @ np.asarray(p.handle_shift))))
    return out


def _moved_scene(model: SceneModel, T: np.ndarray) -> SceneModel:
    """The whole scene hung from a new root link by a fixed joint at pose ``T`` (4, 4)."""
    return SceneModel(model.name, [Link(ROOT_LINK)] + list(model.links.values()),
                      list(model.joints.values()) + [Joint(ROOT_JOINT, JointType.FIXED, ROOT_LINK, model.root, T)],
                      model.materials, model.path)


def write_perturbed_scene(src: str | Path, p: Perturbation, out: str | Path, pivot_xy=(0.0, 0.0)) -> Path:
    """Write the perturbed scene to ``out`` (atomically) and return its path. Mesh paths are absolute, so
    ``out`` may live elsewhere than ``src``."""
    return write_urdf(perturbed_scene(src, p, pivot_xy), out)
