"""The moving scene parts a rollout leaves out of the simulation (frozen), and the guard that brings them back.

A generated kitchen has several articulated objects; a task moves one. Every other drawer and door held
still by its joint friction still costs its Featherstone pass, broad phase and friction motor every physics
step (measured: docs/decisions.md, "Frozen scene parts"). :func:`far_parts` picks the parts nothing of the
task can reach, so that :meth:`simcheck.world.World.freeze_parts` takes them out for the rollout:

* a part is kept (simulated) when its bounding box comes within ``margin`` of the robot's bounding box at
  any configuration of the plan (its waypoints, fingers open, measured every ``step`` of the bound on how far
  a robot point moves: :meth:`simcheck.world.World.robot_levers`; the margin is widened by ``step``), or within
  ``margin`` of the range a kept part can sweep (every kept part's joints over their whole limits: the task's
  part, and anything the robot could push), repeated until no more part is kept;
* a part is kept when it is not at rest (a joint faster than :data:`REST_SPEED`), when gravity loads a joint
  beyond :data:`HOLD_SHARE` of the friction its motor holds it with (it might move on its own), or when it
  touches another moving part at rest (:attr:`simcheck.scene_loading.LoadedScene.rest_contacts`).

What is frozen is exactly what the simulation would hold still: a part at rest, in equilibrium, that nothing
touches. Its joints keep their values and its links their poses (reported as such); it is never teleported.
During the rollout :class:`FreezeGuard` bounds how far the robot strays from the planned path (the joint
tracking error, each revolute joint's error times the farthest any robot point beyond it can be from its axis,
plus each prismatic joint's); when the
bound passes half the margin, every frozen part is loaded again as it was, before the robot can reach it,
and the rollout goes on with the whole scene. Robust samples execute in their own perturbed world, so their
base error is already in the plan's poses there.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["far_parts", "path_samples", "box_gaps", "FreezeGuard", "REST_SPEED", "HOLD_SHARE"]

REST_SPEED = 1e-6
"""A frozen part's joints are slower than this, m/s or rad/s."""

HOLD_SHARE = 0.5
"""A frozen part's joints carry a gravity load below this share of the friction their motor holds them with."""


def box_gaps(lo: np.ndarray, hi: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """(n,) distances, m, between the box (``lo`` (3,), ``hi`` (3,)) and each of ``boxes`` (n, 2, 3) (0: they
    overlap)."""
    boxes = np.asarray(boxes, dtype=float).reshape(-1, 2, 3)
    d = np.maximum(0.0, np.maximum(boxes[:, 0] - hi, lo - boxes[:, 1]))
    return np.linalg.norm(d, axis=1)


def path_samples(q: np.ndarray, weights: np.ndarray, step: float) -> np.ndarray:
    """The rows of ``q`` (n, dof) to measure so that every row lies within ``step`` (m) of the last measured
    row before it along the path, in the weighted joint distance sum(weights * |dq|): the first row of each
    ``step`` of weighted path length, and the last row."""
    run = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(q, axis=0)) @ weights)])
    bins = np.floor(run / step)
    keep = np.flatnonzero(np.concatenate([[True], bins[1:] != bins[:-1]]))
    return q[np.union1d(keep, [len(q) - 1])]


def _range_values(info) -> np.ndarray:
    lo, hi = (info.lower, info.upper) if info.lower <= info.upper else (-math.pi, math.pi)
    return np.linspace(lo, hi, 9 if info.type == "prismatic" else 17)


def _sweep(world, body: int, joints: tuple[str, ...]) -> np.ndarray:
    """(2, 3) the box part ``body`` can sweep, each joint over its limits (the others where they are)."""
    boxes = [np.array(world.part_box(body))]
    for name in joints:
        info = world.scene_joint(name)
        boxes += [np.array(world.part_box(body, {name: v})) for v in _range_values(info)]
    boxes = np.array(boxes)
    return np.array([boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)])


def far_parts(world, plan, margin: float, step: float = 0.05) -> tuple[tuple[int, ...], np.ndarray]:
    """(body ids of the moving parts to freeze for executing ``plan`` in ``world``, the robot joints' weights
    (dof,) m per unit: :meth:`simcheck.world.World.robot_levers`) --
    see the module docstring. ``margin`` and ``step`` in metres. The robot is left where it was."""
    parts = world.moving_parts()                      # the freezable ones
    moving = {world.part_of_joint(j.name) for j in world.scene_joints()} - {-1}
    qs = np.concatenate([world.robot_q()[None]] + [np.asarray(s.q, dtype=float) for s in plan.segments])
    weights = world.robot_levers()
    robot = world.robot_boxes_along(path_samples(qs, weights, step))
    kept = {world.part_of_joint(plan.task.joint)} | (moving - set(parts))
    now = {b: np.array(world.part_box(b)) for b in moving}
    for body, joints in parts.items():
        if body in kept:
            continue
        load = world.part_gravity_load(body)
        if (any(abs(v) > REST_SPEED or g > HOLD_SHARE * f for v, g, f in load.values())
                or box_gaps(*now[body], robot).min() <= margin + step):
            kept.add(body)
    touching = world.moving_rest_pairs()
    kept |= {b for a, b2 in touching for b in (a, b2) if {a, b2} & kept}
    sweeps: dict[int, np.ndarray] = {}
    while True:
        for body in kept - set(sweeps):
            sweeps[body] = _sweep(world, body, world.part_joints(body))
        more = {b for b in moving - kept if box_gaps(*now[b], np.array(list(sweeps.values()))).min() <= margin}
        more |= {b for a, b2 in touching for b in (a, b2) if {a, b2} & (kept | more)} - kept
        if not more:
            break
        kept |= more
    return tuple(sorted(set(parts) - kept)), weights


class FreezeGuard:
    """Loads the frozen parts of ``world`` again as soon as the robot may have strayed from its planned path
    by half the ``margin`` (m) they were frozen with: checked at every recorded sample from the robot's
    joint positions ``q`` (dof,) and the planned (commanded) ones ``q_target`` (dof,); ``weights`` (dof,), m
    per unit of each joint: :meth:`simcheck.world.World.robot_levers`."""

    def __init__(self, world, weights: np.ndarray, margin: float) -> None:
        self.world, self.weights, self.allowance = world, np.asarray(weights, dtype=float), 0.5 * margin
        self.thawed_at: float | None = None

    def check(self, q: np.ndarray, q_target: np.ndarray, t: float) -> None:
        """Thaw the frozen parts when sum(weights * |q - q_target|) passes the allowance (at time ``t`` s)."""
        if self.thawed_at is None and float((self.weights * np.abs(q - q_target)).sum()) > self.allowance:
            self.world.thaw_parts()
            self.thawed_at = t
