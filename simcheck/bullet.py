"""The ``pybullet`` module, imported with its C-level banner logged, and the few PyBullet calls every
part of the world adapter shares: reading a body's joint table and a link's pose or point velocity.

Only the world adapter's modules (:mod:`simcheck.world`, :mod:`simcheck.scene_loading`,
:mod:`simcheck.robot_loading`, :mod:`simcheck.rendering`) import this module; pure modules never do.
PyBullet's (x, y, z, w) quaternion order and its integer ids stay inside them.
"""

from __future__ import annotations

import contextlib
import logging
import os
import re
import tempfile

import numpy as np

from simcheck.bullet_poses import R_rows_from_quat, T_from_pos_quat
from simcheck.joint_table import JointInfo, joint_table

__all__ = ["movable_joints", "point_jacobian", "jacobian_point", "mass_matrix", "pb", "c_output_logged", "pybullet_said", "pybullet_version", "body_joint_table", "link_pose",
           "point_state"]


#: capture files of :func:`c_output_logged` not in use (creating one per call cost more than most PyBullet calls
#: it wraps); a forked child starts with none of its parent's, whose file offsets it would share
_spare_sinks: list = []
_libc = None
os.register_at_fork(after_in_child=_spare_sinks.clear)


@contextlib.contextmanager
def c_output_logged(what: str):
    """Send what C code writes to fd 1/2 inside the block (PyBullet's banner, its URDF importer's
    warnings and parse errors) to this module's logger (debug level) instead of the user's terminal.

    Yields a list that holds that text (one string) once the block has ended, for error messages."""
    global _libc
    if _libc is None:
        import ctypes

        _libc = ctypes.CDLL(None)
    try:
        sink = _spare_sinks.pop()
    except IndexError:
        sink = tempfile.TemporaryFile()
    saved = [os.dup(fd) for fd in (1, 2)]
    said: list[str] = []
    try:
        sink.seek(0)
        sink.truncate()
        _libc.fflush(None)
        for fd in (1, 2):
            os.dup2(sink.fileno(), fd)
        yield said
    finally:
        _libc.fflush(None)
        for fd, keep in zip((1, 2), saved):
            os.dup2(keep, fd)
            os.close(keep)
        sink.seek(0)
        text = sink.read().decode(errors="replace").strip()
        _spare_sinks.append(sink)
        said.append(text)
        if text:
            logging.getLogger(__name__).debug("%s: pybullet wrote: %s", what, text)


def pybullet_said(said: list[str]) -> str:
    """The last lines PyBullet wrote while failing (its reason), for an error message."""
    text = re.sub(r"b*3(Error|Warning|Printf)\[[^\]]*\]:?", "\n", "".join(said))
    lines = list(dict.fromkeys(ln.strip() for ln in text.splitlines() if ln.strip()))
    return f" (PyBullet: {'; '.join(lines[-3:])})" if lines else ""


def _import_pybullet_quietly():
    """Import pybullet with its C-level "pybullet build time" banner (written to fd 1/2) logged."""
    with c_output_logged("import pybullet"):
        import pybullet
    return pybullet


pb = _import_pybullet_quietly()

_JOINT_TYPES = {pb.JOINT_REVOLUTE: "revolute", pb.JOINT_PRISMATIC: "prismatic", pb.JOINT_FIXED: "fixed",
                pb.JOINT_SPHERICAL: "spherical", pb.JOINT_PLANAR: "planar"}


def pybullet_version() -> str:
    """The installed pybullet version (from the package metadata)."""
    from importlib.metadata import version
    return version("pybullet")


def body_joint_table(client: int, body: int) -> tuple[dict[str, JointInfo], dict[str, int]]:
    """(joint name -> :class:`JointInfo`, link name -> PyBullet link index (base: -1)) of ``body``, in
    PyBullet's joint order (:func:`simcheck.joint_table.joint_table` over ``getJointInfo``)."""
    base = pb.getBodyInfo(body, physicsClientId=client)[0].decode()
    joints, parents = [], []
    for j in range(pb.getNumJoints(body, physicsClientId=client)):
        ji = pb.getJointInfo(body, j, physicsClientId=client)
        joints.append(JointInfo(name=ji[1].decode(), type=_JOINT_TYPES.get(ji[2], "unknown"), index=j,
                                child_link=ji[12].decode(), parent_link="", lower=float(ji[8]), upper=float(ji[9]),
                                max_force=float(ji[10]), max_velocity=float(ji[11]), damping=float(ji[6]),
                                friction=float(ji[7])))
        parents.append(ji[16])
    return joint_table(base, joints, parents)


def link_pose(client: int, body: int, index: int) -> np.ndarray:
    """T_world_link (4, 4) of link ``index`` of ``body`` (its URDF link frame; index -1: the base link)."""
    if index == -1:
        pos, quat = pb.getBasePositionAndOrientation(body, physicsClientId=client)
        # base pose is the inertial frame; correct by the local inertial offset
        dyn = pb.getDynamicsInfo(body, -1, physicsClientId=client)
        T_world_inertial = T_from_pos_quat(pos, quat)
        T_link_inertial = T_from_pos_quat(dyn[3], dyn[4])
        return T_world_inertial @ np.linalg.inv(T_link_inertial)
    s = pb.getLinkState(body, index, computeForwardKinematics=1, physicsClientId=client)
    return T_from_pos_quat(s[4], s[5])


def point_state(client: int, body: int, index: int, p_local: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(position (3,) m, velocity (3,) m/s), world frame, of the point ``p_local`` (3,) (link frame, m) of
    link ``index`` (>= 0) of ``body``."""
    s = pb.getLinkState(body, index, computeLinkVelocity=1, computeForwardKinematics=1, physicsClientId=client)
    p = np.array(R_rows_from_quat(s[5])) @ p_local + s[4]
    (cx, cy, cz), (wx, wy, wz), (vx, vy, vz) = s[0], s[7], s[6]
    px, py, pz = p.tolist()
    rx, ry, rz = px - cx, py - cy, pz - cz
    # v = v_com + w x r, in Python floats (numpy costs ~1 us per operation on (3,) vectors; the same result)
    return p, np.array([vx + (wy * rz - wz * ry), vy + (wz * rx - wx * rz), vz + (wx * ry - wy * rx)])


def movable_joints(client: int, body: int) -> list[int]:
    """Indices of the non-fixed joints of ``body``, in PyBullet's order (the columns of its Jacobians)."""
    return [j for j in range(pb.getNumJoints(body, physicsClientId=client))
            if pb.getJointInfo(body, j, physicsClientId=client)[2] != pb.JOINT_FIXED]


def jacobian_point(client: int, body: int, index: int, p_local: np.ndarray) -> list[float]:
    """The point ``p_local`` (3,) (frame of link ``index`` >= 0 of ``body``, m) as PyBullet's
    ``calculateJacobian`` takes it: from the link frame's origin, in the axes of the link's inertial frame
    (not from the centre of mass its documentation names; bullet3 issue 4668), m. The inertial frame is
    fixed in the link: a caller that needs the Jacobian of the same point every step keeps this."""
    s = pb.getLinkState(body, index, computeForwardKinematics=1, physicsClientId=client)
    R_link_inertial = T_from_pos_quat(s[2], s[3])[:3, :3]
    return (R_link_inertial.T @ np.asarray(p_local, dtype=float)).tolist()


def point_jacobian(client: int, body: int, index: int, p_local: np.ndarray,
                   movable: list[int] | None = None, p_arg: list[float] | None = None,
                   columns: list[int] | None = None) -> np.ndarray:
    """(3, n) linear Jacobian, world frame, m per joint unit, of the point ``p_local`` (3,) (link frame, m)
    of link ``index`` (>= 0) over the n :func:`movable_joints` of ``body`` at its current state
    (``movable``: that list when the caller keeps it, ``p_arg``: :func:`jacobian_point` of ``p_local`` when
    it keeps that; the grasp spring calls this every physics step; ``columns``: only these of the n columns,
    (3, len(columns))). A door whose centre of mass is 0.3 m
    from its hinge would get the Jacobian of a point 0.3 m off the handle were the point taken from the
    centre of mass (:func:`jacobian_point`)."""
    movable = movable_joints(client, body) if movable is None else movable
    q = [st[0] for st in pb.getJointStates(body, movable, physicsClientId=client)]
    p_arg = jacobian_point(client, body, index, p_local) if p_arg is None else p_arg
    zero = [0.0] * len(q)
    rows = pb.calculateJacobian(body, index, p_arg, q, zero, zero, physicsClientId=client)[0]
    if columns is not None:
        return np.array([[row[i] for i in columns] for row in rows], dtype=float).reshape(3, len(columns))
    return np.asarray(rows, dtype=float).reshape(3, len(q))


def mass_matrix(client: int, body: int) -> np.ndarray:
    """(n, n) joint-space mass matrix of ``body`` over its :func:`movable_joints` at its current state."""
    q = [float(st[0]) for st in pb.getJointStates(body, movable_joints(client, body), physicsClientId=client)]
    return np.asarray(pb.calculateMassMatrix(body, q, physicsClientId=client), dtype=float).reshape(len(q), len(q))

