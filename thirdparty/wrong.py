"""Wrong estimates of a corpus front, for ``--against`` its own URDF (which must never certify them).

Unlike :mod:`simcheck.estimate_faults` these assume nothing about the joint frame (it may be rotated,
sit at the far end of the hinge, open toward negative values): every change is computed in the world
from the closed state and written back in the joint frame.

* ``axis30``          -- the joint axis turned 30 deg (a drawer's about the vertical; a vertical hinge
  about the front normal; a horizontal hinge about the vertical);
* ``door_as_drawer``  -- a door estimated as a drawer sliding 0.3 m the way its free edge first moves;
* ``wrong_hinge_side``-- the hinge on the door's free edge (axis reversed: the same sign still opens).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from scenes.description import JointType, Limit, SceneModel, read_urdf, write_urdf
from simcheck.estimate_faults import _move_joint_keep_geometry

__all__ = ["WRONG_KINDS", "wrong_estimate"]

WRONG_KINDS = ("axis30", "door_as_drawer", "wrong_hinge_side")


def _corners_world(model: SceneModel, link: str) -> np.ndarray:
    """(n, 3) world corners of the box collisions and the bounding boxes of the meshes (centres of the
    others) of ``link``, closed state."""
    T = model.T_world_link(link)
    pts = []
    for c in model.links[link].collisions:
        if c.kind.value in ("box", "mesh"):
            if c.kind.value == "box":
                lo, hi = -np.asarray(c.size) / 2, np.asarray(c.size) / 2
            else:
                import trimesh
                lo, hi = trimesh.load(c.mesh, force="mesh").bounds * np.asarray(c.size)
            local = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
            pts += [(T @ c.T_link_shape @ np.append(p, 1))[:3] for p in local]
        else:
            pts.append((T @ c.T_link_shape)[:3, 3])
    return np.array(pts)


def _axis_world(model: SceneModel, name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(T_world_joint (4, 4), unit axis (3,) world, a point on the axis (3,) world)."""
    j = model.joints[name]
    T = model.T_world_link(j.child)
    a = T[:3, :3] @ (j.axis / np.linalg.norm(j.axis))
    return T, a, T[:3, 3]


def _far_offset(model: SceneModel, name: str) -> np.ndarray:
    """World vector, perpendicular to the hinge axis, from the axis to the moving panel's farthest corner."""
    j = model.joints[name]
    _, a, p = _axis_world(model, name)
    d = _corners_world(model, j.child) - p
    perp = d - np.outer(d @ a, a)
    return perp[int(np.argmax(np.linalg.norm(perp, axis=1)))]


def wrong_estimate(src, joint: str, kind: str, out) -> Path:
    """Write the ``kind`` wrong estimate (one of :data:`WRONG_KINDS`) of ``joint`` of URDF ``src`` to
    ``out``; the input file is not modified. ValueError for a kind that does not apply to the joint type."""
    m = read_urdf(src)
    j = m.joints[joint]
    T, a, _ = _axis_world(m, joint)
    R = T[:3, :3]
    up = np.array([0.0, 0.0, 1.0])
    door = j.type is not JointType.PRISMATIC
    if kind == "axis30":
        about = up
        if door and abs(a @ up) > 0.7:      # vertical hinge: lean it in the door's plane
            about = np.cross(a, _far_offset(m, joint))
        a_new = Rotation.from_rotvec(np.deg2rad(30.0) * about / np.linalg.norm(about)).apply(a)
        new = [dataclasses.replace(j, axis=R.T @ a_new)]
    elif kind == "door_as_drawer" and door:
        sign = 1.0 if j.upper >= -j.lower else -1.0          # a continuous joint opens positive
        d = sign * np.cross(a, _far_offset(m, joint))
        limit = Limit(0.0, 0.3, 100.0, 1.0) if j.limit is None else dataclasses.replace(j.limit, lower=0.0, upper=0.3)
        new = [dataclasses.replace(j, type=JointType.PRISMATIC, axis=R.T @ (d / np.linalg.norm(d)), limit=limit)]
    elif kind == "wrong_hinge_side" and door:
        shift = R.T @ _far_offset(m, joint)
        new = _move_joint_keep_geometry(m, j, shift, axis=-j.axis)
    else:
        raise ValueError(f"wrong estimate {kind!r} does not apply to {j.type.value} joint {joint!r}")
    return write_urdf(m.replaced(*new), out)
