"""Robust samples on the Ray batch engine: with a Ray connected, ``engine="auto"`` sends the sampled
executions to it as Ray tasks (in Ray's worker processes, results in sample order), and a worker that dies
costs only its own sample."""

from __future__ import annotations

import os
import sys

import pytest

ray = pytest.importorskip("ray")

from scenes.outcome import Outcome  # noqa: E402
from simcheck.perturbations import sample_perturbation  # noqa: E402
from simcheck.robust_engine import run_samples  # noqa: E402
from simcheck.robust_spreads import DEFAULT_SPREADS  # noqa: E402
from simcheck.robust_verdict import SampleResult  # noqa: E402


@pytest.fixture(scope="module")
def local_ray():
    from ray import cloudpickle

    cloudpickle.register_pickle_by_value(sys.modules[__name__])     # Ray's workers need not import this test
    ray.init(address="local", num_cpus=2, include_dashboard=False, log_to_driver=False, logging_level="ERROR")
    yield
    ray.shutdown()
    cloudpickle.unregister_pickle_by_value(sys.modules[__name__])


def _sample(tag, p):
    """A stand-in for run_sample: dies in sample 1, else succeeds naming its process (pid and name, read
    while it runs: a worker may be gone by the time the test looks)."""
    if p.index == 1:
        os._exit(3)
    import psutil

    return SampleResult(p, Outcome.CERTIFIED, f"{os.getpid()} {psutil.Process().name()}", {"m": float(p.index)})


def test_samples_run_as_ray_tasks_when_ray_is_connected(local_ray):
    perts = [sample_perturbation(i, 0, "J", "prismatic", (1, 0, 0), (0, 0, 0), 0.4, None,
                                 DEFAULT_SPREADS.joint_defaults["prismatic"], DEFAULT_SPREADS.physics,
                                 DEFAULT_SPREADS.robot) for i in range(3)]
    out = run_samples(_sample, [("t", p) for p in perts], engine="auto")
    assert [r.perturbation for r in out] == perts
    assert [r.outcome for r in out] == [Outcome.CERTIFIED, Outcome.ERROR, Outcome.CERTIFIED]
    assert "sample 1 could not be executed: its worker failed" in out[1].reason
    for r in (out[0], out[2]):
        pid, name = r.reason.split(" ", 1)
        assert int(pid) != os.getpid() and name.startswith("ray::"), r.reason
