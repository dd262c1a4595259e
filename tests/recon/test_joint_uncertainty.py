"""Joint uncertainty (recon/joint_uncertainty.py): a seeded bootstrap of each movable joint's fit.
A sparsely seen noisy door comes out less certain than a well-seen one; the block round-trips through
graph.json; the same seed gives the same spreads; fixed joints carry none."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from recon.config import JointUncertaintyConfig, ReconConfig
from recon.graph_json import graph_dict, reconstruction_from_dict
from recon.pipeline import reconstruct_scan
from recon.scan import scan_from_arrays

NOISE = 0.003     # depth-like noise (m) added to every point


def _scan(synth, density: float, seed: int = 0):
    props, labels = synth.scan_arrays([synth.cabinet()], points_per_m2=density, seed=seed)
    rng = np.random.default_rng(seed + 100)
    for k in ("x", "y", "z"):
        props[k] = props[k] + rng.normal(0.0, NOISE, len(props[k]))
    return scan_from_arrays(props, labels)


def _door(rec):
    return next(j for j in rec.joints() if "door" in j.name)


@pytest.fixture(scope="module")
def dense_and_sparse(synth):
    return (reconstruct_scan(_scan(synth, 8000.0), seed=0), reconstruct_scan(_scan(synth, 500.0), seed=0))


def test_sparsely_seen_door_is_less_certain_than_a_well_seen_one(dense_and_sparse):
    dense, sparse = (_door(r).uncertainty for r in dense_and_sparse)
    assert dense.samples == sparse.samples == JointUncertaintyConfig().samples
    assert dense.method == "bootstrap+template-prior"
    assert sparse.origin_m > 2.0 * dense.origin_m, (dense, sparse)
    assert sparse.axis_deg > dense.axis_deg, (dense, sparse)
    assert 0.0 < dense.origin_m < 0.01


def test_every_movable_joint_has_finite_spreads_and_fixed_joints_none(dense_and_sparse):
    for rec in dense_and_sparse:
        for j in rec.joints():
            if j.type.value == "fixed":
                assert j.uncertainty is None
            else:
                u = j.uncertainty
                assert all(np.isfinite(v) and v >= 0.0 for v in (u.axis_deg, u.origin_m, u.upper)), (j.name, u)


def test_upper_spread_carries_the_template_prior_of_what_no_scan_shows(dense_and_sparse):
    cfg = JointUncertaintyConfig()
    for rec in dense_and_sparse:
        drawer = next(j for j in rec.joints() if "drawer" in j.name)
        assert drawer.uncertainty.upper >= cfg.drawer_travel_prior
        door = _door(rec)
        if door.upper >= ReconConfig().joints.door_max_angle - 1e-9:
            assert door.uncertainty.upper >= cfg.door_stop_prior


def test_uncertainty_round_trips_through_graph_json(dense_and_sparse):
    rec = dense_and_sparse[1]
    doc = graph_dict(rec)
    back = reconstruction_from_dict(doc)
    assert graph_dict(back) == doc
    assert _door(back).uncertainty == _door(rec).uncertainty
    assert doc["objects"][0]["joints"][-1].keys() >= {"name", "type"}
    assert back.config.joint_uncertainty == rec.config.joint_uncertainty


def test_same_seed_same_spreads_and_zero_samples_writes_none(synth):
    scan = _scan(synth, 1500.0, seed=3)
    a = _door(reconstruct_scan(scan, seed=5)).uncertainty
    b = _door(reconstruct_scan(scan, seed=5)).uncertainty
    assert (a.samples, a.method) == (b.samples, b.method)
    # equal up to floating-point summation order (BLAS threads)
    assert [a.axis_deg, a.origin_m, a.upper] == pytest.approx([b.axis_deg, b.origin_m, b.upper], rel=1e-9, abs=1e-15)
    off = ReconConfig(joint_uncertainty=JointUncertaintyConfig(samples=0))
    assert _door(reconstruct_scan(scan, seed=5, config=off)).uncertainty is None
