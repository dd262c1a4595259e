"""Did a given plan do to the world what it said it would? Pure numpy criteria over the scene joints'
values recorded at the rollout's samples (an :class:`ArticulationTrace`).

* :func:`expectation_met` -- the expected joint, at the end of its segment, reached ``from + fraction * (to -
  from)`` with ``fraction >= CriteriaConfig.opened_fraction``, and it started near ``from``.
* :func:`articulations_still` -- every scene joint that no expectation of the segment names stayed where it
  was (within ``CriteriaConfig.articulation_tolerance``) during every segment and the hold after the last.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from planners.task import Expectation
from simcheck.config import DEFAULT_CRITERIA, CriteriaConfig
from simcheck.criteria import CriterionResult, _judge

__all__ = ["ArticulationTrace", "expectation_met", "articulations_still"]


@dataclass(frozen=True)
class ArticulationTrace:
    """The scene's movable joints over an executed plan.

    Attributes:
        joints: (J,) scene joint names.
        q: (n, J) their values, m or rad, at the rollout's n samples.
        t: (n,) seconds.  segment: (n,) index of the plan segment each sample belongs to (-1: after the plan).
        segment_names: the plan's segment names.
        units: (J,) "m" (prismatic) or "rad" per joint; () when unknown (then "rad").
    """

    joints: tuple[str, ...]
    q: np.ndarray
    t: np.ndarray
    segment: np.ndarray
    segment_names: tuple[str, ...]
    units: tuple[str, ...] = ()

    def value(self, joint: str) -> np.ndarray:
        """(n,) the values of ``joint``."""
        return self.q[:, self.joints.index(joint)]

    def span(self, i: int) -> tuple[int, int]:
        """(first sample before segment ``i``, last sample of it): the reference and the end of the segment."""
        idx = np.flatnonzero(self.segment == i)
        if not len(idx):
            return -1, -1
        return max(int(idx[0]) - 1, 0), int(idx[-1])


def expectation_met(trace: ArticulationTrace, i: int, e: Expectation, c: CriteriaConfig = DEFAULT_CRITERIA
                    ) -> CriterionResult:
    """Fraction of the expected move ``e`` (``from`` -> ``to``) of joint ``e.joint`` done by the end of segment ``i``,
    at least ``c.opened_fraction``; ``-inf`` when the joint started farther than ``c.articulation_tolerance``
    from ``e.start``."""
    name = trace.segment_names[i]
    desc = "fraction of the expected move of its joint done by the end of the segment"
    start, end = trace.span(i)
    if start < 0:
        return _judge("expectation_met", -np.inf, c.opened_fraction, ">=", "", desc,
                      f"segment {name!r} was not executed")
    q = trace.value(e.joint)
    q0, q1 = float(q[start]), float(q[end])
    if abs(q0 - e.start) > c.articulation_tolerance:
        return _judge("expectation_met", -np.inf, c.opened_fraction, ">=", "", desc,
                      f"segment {name!r} expected {e.joint} to start at {e.start:.3f}; it was at {q0:.3f}")
    frac = (q1 - e.start) / e.amount
    return _judge("expectation_met", frac, c.opened_fraction, ">=", "", desc,
                  f"segment {name!r} expected {e.joint} to move from {e.start:.3f} to {e.end:.3f}; at its end "
                  f"(t={trace.t[end]:.2f} s) it was at {q1:.3f} ({frac:.0%} of the move, needs "
                  f"{c.opened_fraction:.0%})",
                  f"segment {name!r}: {e.joint} {q0:.3f} -> {q1:.3f} (expected {e.end:.3f})")


def articulations_still(trace: ArticulationTrace, expected: dict[int, set[str]],
                        c: CriteriaConfig = DEFAULT_CRITERIA) -> CriterionResult:
    """Largest move of a scene joint (in its unit: ``trace.units``) during a segment (or the hold after the plan) whose
    expectations (``expected``: segment index -> joint names) do not name it; at most
    ``c.articulation_tolerance``."""
    worst, where, unit = 0.0, "", "rad"
    executed = np.flatnonzero(trace.segment >= 0)
    for i in [*range(len(trace.segment_names)), -1]:
        idx = np.flatnonzero(trace.segment == i)
        if i < 0:                              # the hold after the plan (not the first sample, taken before it)
            idx = idx[idx > executed[-1]] if len(executed) else idx[1:]
        if not len(idx):
            continue
        ref = trace.q[max(int(idx[0]) - 1, 0)]
        moved = np.abs(trace.q[idx] - ref[None])
        for j, joint in enumerate(trace.joints):
            if joint in expected.get(i, set()) or not moved[:, j].max() > worst:
                continue
            k = int(np.argmax(moved[:, j]))
            worst = float(moved[k, j])
            unit = trace.units[j] if trace.units else "rad"
            seg = f"segment {trace.segment_names[i]!r}" if i >= 0 else "the hold after the plan"
            where = (f"{seg} moved scene joint {joint} by {worst:.3f} {unit} (t={trace.t[idx[k]]:.2f} s) without an "
                     "expectation naming it")
    return _judge("articulations_still", worst, c.articulation_tolerance, "<=", unit,
                  "largest move of a scene joint in a segment that does not expect it", where, where)
