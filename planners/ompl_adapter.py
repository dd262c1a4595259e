"""The OMPL adapter: joint-space planning between two configurations. The only module importing ``ompl``.

OMPL 2 (nanobind) traps handled here: the validity callable returns a Python ``bool``;
start and goal are checked by the caller before planning (a goal in collision burns the whole time
budget); the RNG is seeded with ``ompl.util.RNG.setSeed``; planner objects live only inside
:func:`plan_joint_path`, so nothing leaks at interpreter exit; OMPL's log is set to warnings.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass

import numpy as np
from ompl import base as ob
from ompl import geometric as og
from ompl import util as ou

__all__ = ["MotionResult", "plan_joint_path", "plan_constrained_path"]

log = logging.getLogger(__name__)
ou.setLogLevel(ou.LOG_WARN)

#: wall-time budget (s) of OMPL's path simplification, which stops by itself once a pass no longer shortens the
#: path (well under a second of CPU for our paths): the budget only bounds a pathological case. A budget that
#: can run out (it was 0.5 s) made the plan, hence the certificate, depend on the machine's load: a loaded run
#: stopped simplifying earlier than an idle one with the same seed.
SIMPLIFY_BUDGET = 20.0

_PLANNERS = {"RRTConnect": og.RRTConnect, "RRT": og.RRT, "PRM": og.PRM, "RRTstar": og.RRTstar,
             "BKPIECE1": og.BKPIECE1, "LBKPIECE1": og.LBKPIECE1}


@dataclass(frozen=True)
class MotionResult:
    """``success``; ``path (n, dof)`` (empty when not found); ``reason``; planning ``seconds``."""

    success: bool
    path: np.ndarray
    reason: str
    seconds: float


def _seeded_box_space(seed: int, lower, upper) -> "ob.RealVectorStateSpace":
    """A ``RealVectorStateSpace`` bounded by ``lower``/``upper`` ((n,) each), with OMPL's seed set to ``seed``.

    Reseeding OMPL's seed generator makes every RNG created afterwards (planner, samplers) deterministic;
    OMPL logs an error that "generation already started" on every call after the first, which is harmless
    here, so logging is silenced around it."""
    ou.setLogLevel(ou.LOG_NONE)
    ou.RNG.setSeed(int(seed) % (2 ** 31 - 1) + 1)
    ou.setLogLevel(ou.LOG_WARN)
    n = len(lower)
    space = ob.RealVectorStateSpace(n)
    bounds = ob.RealVectorBounds(n)
    for i in range(n):
        bounds.setLow(i, float(lower[i]))
        bounds.setHigh(i, float(upper[i]))
    space.setBounds(bounds)
    return space


def plan_joint_path(start: np.ndarray, goal: np.ndarray, lower: np.ndarray, upper: np.ndarray, is_valid, *,
                    time_limit: float, seed: int, planner: str = "RRTConnect",
                    resolution: float = 0.01) -> MotionResult:
    """Plan a path from ``start (dof,)`` to ``goal (dof,)`` in the box ``[lower, upper]``.

    ``is_valid(q (dof,)) -> bool``. ``resolution`` is the validity-checking step as a fraction of the
    space's maximum extent. The returned path is simplified but not densified (see
    :func:`planners.motion.densify`).
    """
    dof = len(start)
    t0 = time.perf_counter()
    for what, q in (("start", start), ("goal", goal)):
        outside = np.flatnonzero((np.asarray(q) < lower) | (np.asarray(q) > upper))
        if len(outside):
            i = int(outside[0])
            return MotionResult(False, np.zeros((0, dof)), f"the {what} lies outside the planning box: coordinate "
                                f"{i} = {q[i]!r} not in [{lower[i]!r}, {upper[i]!r}]", time.perf_counter() - t0)
    space = _seeded_box_space(seed, lower, upper)
    ss = og.SimpleSetup(space)
    buf = np.empty(dof)

    def valid(state) -> bool:
        for i in range(dof):
            buf[i] = state[i]
        return bool(is_valid(buf))

    ss.setStateValidityChecker(valid)
    si = ss.getSpaceInformation()
    si.setStateValidityCheckingResolution(resolution)
    ss.setPlanner(_PLANNERS[planner](si))
    a, b = space.allocState(), space.allocState()
    for i in range(dof):
        a[i], b[i] = float(start[i]), float(goal[i])
    ss.setStartAndGoalStates(a, b)
    try:
        status = ss.solve(float(time_limit))
        if not ss.haveExactSolutionPath():
            return MotionResult(False, np.zeros((0, dof)), f"{planner} found no path in {time_limit:.1f} s "
                                f"({status})", time.perf_counter() - t0)
        ss.simplifySolution(SIMPLIFY_BUDGET)
        p = ss.getSolutionPath()
        path = np.array([[p.getState(k)[i] for i in range(dof)] for k in range(p.getStateCount())])
        del p
        return MotionResult(True, path, "ok", time.perf_counter() - t0)
    finally:
        del ss, si, a, b


class _PoseConstraint(ob.Constraint):
    """``F(x) = 0`` as an OMPL constraint; ``function(x) -> (k,)`` and ``jacobian(x) -> (k, n)`` are numpy."""

    def __init__(self, n: int, k: int, function, jacobian):
        super().__init__(n, k)
        self._f, self._j = function, jacobian

    def function(self, x, out):
        out[:] = self._f(np.asarray(x))

    def jacobian(self, x, out):
        out[:, :] = self._j(np.asarray(x))


def plan_constrained_path(start: np.ndarray, goal: np.ndarray, lower: np.ndarray, upper: np.ndarray,
                          function, jacobian, co_dim: int, is_valid, *, time_limit: float, seed: int,
                          delta: float = 0.05, tolerance: float = 1e-4, max_step: float = 0.02) -> MotionResult:
    """Plan on the manifold ``function(x) = 0`` (``co_dim`` equations) from ``start (n,)`` to ``goal (n,)``.

    OMPL's ProjectedStateSpace + RRTConnect: samples are projected onto the manifold by Newton steps with
    ``jacobian (co_dim, n)``. The returned path is interpolated *on the manifold* so no coordinate moves more
    than about ``max_step`` between samples; it is not re-checked here.
    """
    n = len(start)
    t0 = time.perf_counter()
    rv = _seeded_box_space(seed, lower, upper)
    constraint = _PoseConstraint(n, co_dim, function, jacobian)
    constraint.setTolerance(tolerance)
    css = ob.ProjectedStateSpace(rv, constraint)
    css.setDelta(delta)
    csi = ob.ConstrainedSpaceInformation(css)
    ss = og.SimpleSetup(csi)
    buf = np.empty(n)

    def valid(state) -> bool:
        for i in range(n):
            buf[i] = state[i]
        return bool(is_valid(buf))

    ss.setStateValidityChecker(valid)
    a, b = css.allocState(), css.allocState()
    a.copy([float(v) for v in start])
    b.copy([float(v) for v in goal])
    ss.setStartAndGoalStates(a, b)
    ss.setPlanner(og.RRTConnect(csi))
    try:
        status = ss.solve(float(time_limit))
        if not ss.haveExactSolutionPath():
            return MotionResult(False, np.zeros((0, n)), f"constrained RRTConnect found no path in "
                                f"{time_limit:.1f} s ({status})", time.perf_counter() - t0)
        ss.simplifySolution(SIMPLIFY_BUDGET)
        p = ss.getSolutionPath()
        coarse = np.array([[p.getState(k)[i] for i in range(n)] for k in range(p.getStateCount())])
        steps = int(np.ceil(np.sum(np.max(np.abs(np.diff(coarse, axis=0)), axis=1)) / max_step)) + 1
        p.interpolate(max(steps, len(coarse)))
        path = np.array([[p.getState(k)[i] for i in range(n)] for k in range(p.getStateCount())])
        del p
        return MotionResult(True, path, "ok", time.perf_counter() - t0)
    finally:
        del ss, csi, css, a, b
