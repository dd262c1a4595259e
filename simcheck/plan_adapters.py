"""Plans from what other motion planners print: OMPL's ``PathGeometric.printAsMatrix`` (the format of OMPL's
geometric paths as text: one state per line, its coordinates separated by spaces; for a compound state
space the components in the order they were added, e.g. an ``SE2StateSpace`` base then a
``RealVectorStateSpace`` arm: ``x y yaw q1 ... q7``). Worked example: docs/plan_format.md.

A geometric path has no timing: the caller gives it (``t`` or ``dt``), and the waypoints are used as they
are -- nothing is interpolated or re-timed here (simcheck judges the timing, :mod:`simcheck.plan_timing`).
"""

from __future__ import annotations

import numpy as np

from simcheck.errors import PlanFileError
from simcheck.plan_file import GivenPlan, plan_from_arrays

__all__ = ["waypoints_from_ompl_matrix", "plan_from_ompl_matrix"]


def waypoints_from_ompl_matrix(text: str, source: str = "<OMPL matrix>") -> np.ndarray:
    """(n, dof) float waypoints from ``printAsMatrix`` text (blank lines ignored).

    Raises:
        PlanFileError: a line that is not numbers, rows of different lengths, or no row (naming the line).
    """
    rows = []
    for k, line in enumerate(text.splitlines(), start=1):
        if not line.strip():
            continue
        try:
            rows.append([float(v) for v in line.split()])
        except ValueError:
            raise PlanFileError(f"{source}: line {k} is not a row of numbers: {line.strip()[:80]!r}") from None
        if len(rows[-1]) != len(rows[0]):
            raise PlanFileError(f"{source}: line {k} has {len(rows[-1])} numbers, the first row {len(rows[0])}")
    if not rows:
        raise PlanFileError(f"{source}: no state in the matrix")
    return np.asarray(rows, dtype=float)


def plan_from_ompl_matrix(text: str, joint_names, *, t=None, dt=None, gripper: str = "hold", name: str = "path",
                          expect=None, robot: str = "default", source: str = "<OMPL matrix>") -> GivenPlan:
    """A one-segment :class:`GivenPlan` from ``printAsMatrix`` text whose columns are ``joint_names`` (m, rad),
    reached at times ``t`` (n,) s or every ``dt`` s; ``gripper``, ``expect`` as for
    :func:`simcheck.plan_file.plan_from_arrays`. Join segments with :func:`simcheck.plan_file.join_plans`."""
    return plan_from_arrays(waypoints_from_ompl_matrix(text, source), joint_names, t=t, dt=dt, gripper=gripper,
                            name=name, expect=expect, robot=robot)
