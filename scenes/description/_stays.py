"""The stay of a door hinged about a horizontal axis: what holds a flap or a drop-down door where it is left.

A wall cabinet's flap carries a stay (a lid support, a gas strut), an oven's or a dishwasher's door a
counterbalance spring; without one the flap falls shut and the drop-down door falls open as soon as the
hand lets go. A scan does not show them. Every partscene package models one the same way: Coulomb
friction of the joint at least :data:`STAY_HOLD` times the largest gravity torque on the links the joint
moves (:func:`stay_friction`), so the door stays where it was left, and moving it takes that torque on top
of gravity. A door hinged about an axis nearer the vertical than :data:`STAY_MAX_TILT_DEG` from the
horizontal has none (gravity does not turn it), nor has a drawer (its runners hold it).

Units: N·m, kg, metres, m/s^2; frames: the model's root ("world") frame at joint value 0.
"""

from __future__ import annotations

import numpy as np

import dataclasses

from scenes.description._model import Dynamics, JointType, SceneModel

__all__ = ["STAY_HOLD", "STAY_MAX_TILT_DEG", "gravity_torque", "stay_friction", "with_stays"]

STAY_HOLD = 1.2
"""Holding torque of a stay / counterbalance over the largest gravity torque on the door (a 20 % margin:
a door that only just holds creeps in simulation)."""

STAY_MAX_TILT_DEG = 45.0
"""A revolute axis within this angle (deg) of the horizontal (the plane normal to gravity) carries a stay."""


def _world_axis(model: SceneModel, joint: str) -> tuple[np.ndarray, np.ndarray]:
    """(a point on ``joint``'s axis (3,) m, its unit direction (3,)), root frame at joint value 0."""
    j = model.joints[joint]
    T = model.T_world_link(j.parent) @ j.T_parent_joint
    return T[:3, 3], T[:3, :3] @ (j.axis / np.linalg.norm(j.axis))


def gravity_torque(model: SceneModel, joint: str, gravity) -> float:
    """The largest torque (N·m) ``gravity`` (3,) m/s^2 (root frame) exerts about revolute ``joint``'s axis on
    the links it moves, over a whole turn: M |r⊥| |g⊥|, with M their mass, r⊥ their centre of mass off the
    axis and g⊥ gravity across the axis. 0 for links without inertials."""
    j = model.joints[joint]
    o, a = _world_axis(model, joint)
    mass, moment = 0.0, np.zeros(3)
    for name in model.subtree_links(j.child):
        inertial = model.links[name].inertial
        if inertial is None or inertial.mass <= 0.0:
            continue
        com = (model.T_world_link(name) @ inertial.T_link_com)[:3, 3]
        mass += inertial.mass
        moment += inertial.mass * com
    if mass <= 0.0:
        return 0.0
    r = moment / mass - o
    g = np.asarray(gravity, dtype=np.float64)
    return float(mass * np.linalg.norm(r - (r @ a) * a) * np.linalg.norm(g - (g @ a) * a))


def stay_friction(model: SceneModel, joint: str, gravity) -> float:
    """Coulomb friction (N·m) of ``joint``'s stay: :data:`STAY_HOLD` × :func:`gravity_torque` for a revolute
    joint whose axis lies within :data:`STAY_MAX_TILT_DEG` of the horizontal, else 0 (see the module
    docstring). ``gravity`` (3,) m/s^2, root frame."""
    j = model.joints[joint]
    if j.type is not JointType.REVOLUTE:
        return 0.0
    g = np.asarray(gravity, dtype=np.float64)
    _, a = _world_axis(model, joint)
    if abs(a @ g) > np.linalg.norm(g) * np.sin(np.radians(STAY_MAX_TILT_DEG)):
        return 0.0
    return STAY_HOLD * gravity_torque(model, joint, g)


def with_stays(model: SceneModel, gravity, joints=None) -> SceneModel:
    """``model`` with the friction of each of ``joints`` (names; default: every joint) raised to its
    :func:`stay_friction` where that is larger; ``gravity`` (3,) m/s^2, root frame."""
    held = []
    for name in model.joints if joints is None else joints:
        j = model.joints[name]
        friction = stay_friction(model, name, gravity)
        if friction > (j.dynamics.friction if j.dynamics is not None else 0.0):
            damping = j.dynamics.damping if j.dynamics is not None else 0.0
            held.append(dataclasses.replace(j, dynamics=Dynamics(damping, friction)))
    return model.replaced(*held) if held else model
