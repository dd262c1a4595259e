"""The OMPL adapter: joint-space planning between two configurations. The only module importing ``ompl``.

OMPL 2 (nanobind) traps handled here (see STACK.md): the validity callable returns a Python ``bool``;
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

__all__ = ["MotionResult", "plan_joint_path"]

log = logging.getLogger(__name__)
ou.setLogLevel(ou.LOG_WARN)

_PLANNERS = {"RRTConnect": og.RRTConnect, "RRT": og.RRT, "PRM": og.PRM, "RRTstar": og.RRTstar,
             "BKPIECE1": og.BKPIECE1, "LBKPIECE1": og.LBKPIECE1}


@dataclass(frozen=True)
class MotionResult:
    """``success``; ``path (n, dof)`` (empty when not found); ``reason``; planning ``seconds``."""

    success: bool
    path: np.ndarray
    reason: str
    seconds: float


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
    # Reseeding OMPL's seed generator makes every RNG created below (planner, samplers) deterministic; OMPL
    # logs an error that "generation already started" on every call after the first, which is harmless here.
    ou.setLogLevel(ou.LOG_NONE)
    ou.RNG.setSeed(int(seed) % (2 ** 31 - 1) + 1)
    ou.setLogLevel(ou.LOG_WARN)
    space = ob.RealVectorStateSpace(dof)
    bounds = ob.RealVectorBounds(dof)
    for i in range(dof):
        bounds.setLow(i, float(lower[i]))
        bounds.setHigh(i, float(upper[i]))
    space.setBounds(bounds)
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
        ss.simplifySolution(min(0.5, time_limit))
        p = ss.getSolutionPath()
        path = np.array([[p.getState(k)[i] for i in range(dof)] for k in range(p.getStateCount())])
        del p
        return MotionResult(True, path, "ok", time.perf_counter() - t0)
    finally:
        del ss, si, a, b
