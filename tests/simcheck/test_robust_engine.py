"""Where robust samples run: the engine is chosen as documented, and a worker that dies costs only its own
sample (an ``error`` naming it), the others keep their results, in order."""

from __future__ import annotations

import os

import pytest

from scenes.outcome import Outcome
from simcheck.errors import SimcheckInputError
from simcheck.perturbations import sample_perturbation
from simcheck.robust_engine import choose_engine, run_samples
from simcheck.robust_spreads import DEFAULT_SPREADS
from simcheck.robust_verdict import SampleResult


def _sample(tag, p):
    """A stand-in for run_sample: dies in sample 1, else succeeds reporting its process."""
    if p.index == 1:
        os._exit(3)
    return SampleResult(p, Outcome.CERTIFIED, f"{tag} {os.getpid()}", {"m": float(p.index)})


def _perts(n):
    return [sample_perturbation(i, 0, "J", "prismatic", (1, 0, 0), (0, 0, 0), 0.4, None,
                                DEFAULT_SPREADS.joint_defaults["prismatic"], DEFAULT_SPREADS.physics,
                                DEFAULT_SPREADS.robot) for i in range(n)]


def test_engine_names_are_checked_and_auto_picks_processes_without_ray(monkeypatch):
    with pytest.raises(SimcheckInputError, match="engine: must be one of auto, processes, ray"):
        choose_engine("threads")
    monkeypatch.delenv("RAY_ADDRESS", raising=False)
    monkeypatch.setattr("simcheck.robust_engine._ray_connected", lambda: False)
    assert choose_engine("auto") == "processes" and choose_engine("processes") == "processes"
    assert choose_engine("auto", address="auto") == "ray"
    monkeypatch.setenv("RAY_ADDRESS", "127.0.0.1:6379")
    assert choose_engine("auto") == "ray"


def test_a_dead_worker_costs_only_its_own_sample():
    perts = _perts(4)
    out = run_samples(_sample, [("t", p) for p in perts], engine="processes", workers=2)
    assert [r.perturbation.index for r in out] == [0, 1, 2, 3]
    assert [r.outcome for r in out] == [Outcome.CERTIFIED, Outcome.ERROR, Outcome.CERTIFIED, Outcome.CERTIFIED]
    assert "sample 1 could not be executed: its worker failed" in out[1].reason
    assert all(str(os.getpid()) not in r.reason for r in out)      # run in other processes
