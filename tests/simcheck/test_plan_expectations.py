"""simcheck/plan_expectations.py: a given plan's expectations judged on a recorded articulation trace, without
PyBullet; each criterion shown passing and failing with the segment named."""

import numpy as np
import pytest

from planners.task import Expectation
from simcheck.plan_expectations import ArticulationTrace, articulations_still, expectation_met

SEGMENTS = ("reach", "pull", "let_go")
E = Expectation("drawer_a", 0.0, 0.3)


def _trace(a, b):
    """Samples: one before the plan, 3 per segment, 2 in the hold after it; ``a``/``b`` (10,) joint values."""
    seg = np.array([-1, 0, 0, 0, 1, 1, 1, 2, 2, 2, -1, -1][:len(a)])
    return ArticulationTrace(("drawer_a", "drawer_b"), np.stack([a, b], axis=1), 0.1 * np.arange(len(a)), seg, SEGMENTS)


def test_the_expected_drawer_opened_passes():
    a = np.array([0, 0, 0, 0, 0.1, 0.2, 0.29, 0.29, 0.29, 0.29, 0.29, 0.29])
    t = _trace(a, np.zeros(12))
    r = expectation_met(t, 1, E)
    assert r.passed and r.value == pytest.approx(0.29 / 0.3)
    assert articulations_still(t, {1: {"drawer_a"}}).passed


def test_the_wrong_drawer_opened_fails_both_naming_segment_and_joint():
    b = np.array([0, 0, 0, 0, 0.1, 0.2, 0.29, 0.29, 0.29, 0.29, 0.29, 0.29])
    t = _trace(np.zeros(12), b)
    r = expectation_met(t, 1, E)
    assert not r.passed and r.value == 0.0
    assert "segment 'pull' expected drawer_a to move from 0.000 to 0.300; at its end (t=0.60 s) it was at 0.000" in r.detail
    s = articulations_still(t, {1: {"drawer_a"}})
    assert not s.passed and s.value == pytest.approx(0.29)
    assert "segment 'pull' moved scene joint drawer_b by 0.290" in s.detail
    drawers = ArticulationTrace(t.joints, t.q, t.t, t.segment, t.segment_names, units=("m", "m"))
    assert articulations_still(drawers, {1: {"drawer_a"}}).unit == "m"      # the moved joint's unit


def test_a_drawer_that_drifts_after_the_plan_or_starts_elsewhere_fails():
    a = np.array([0, 0, 0, 0, 0.1, 0.2, 0.3, 0.3, 0.3, 0.3, 0.25, 0.2])
    s = articulations_still(_trace(a, np.zeros(12)), {1: {"drawer_a"}})
    assert not s.passed and "the hold after the plan moved scene joint drawer_a by 0.100" in s.detail
    late = expectation_met(_trace(np.full(12, 0.1), np.zeros(12)), 1, E)
    assert not late.passed and "expected drawer_a to start at 0.000; it was at 0.100" in late.detail
