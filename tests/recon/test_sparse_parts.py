"""Sparse parts (issue 12, item 3): handles seen by a few points (ScanNet density: 9-14) are kept and
hung from their drawer/door; ``recon build --min-part-points`` sets the limit for the other parts."""

from __future__ import annotations

import json

import numpy as np
import pytest

from recon.cli import main
from recon.config import ScanConfig
from recon.pipeline import reconstruct_scan
from recon.scan import scan_from_arrays

HANDLES = {103: (102, (0.515, 0.0, 0.60)), 105: (104, (0.515, 0.31, 0.225))}
"""The synthetic cabinet's handles: part id -> (its drawer / door, its true centre (m))."""


def _sparse_handles(synth, n: int, seed: int = 0):
    """The synthetic cabinet with each handle cut down to ``n`` points, 3 mm noise on every point."""
    props, labels = synth.scan_arrays([synth.cabinet()], points_per_m2=3000.0, seed=seed)
    rng = np.random.default_rng(seed)
    keep = np.ones(len(props["x"]), bool)
    for hid in HANDLES:
        idx = np.flatnonzero(props["part_id"] == hid)
        keep[rng.choice(idx, len(idx) - n, replace=False)] = False
    props = {k: v[keep] for k, v in props.items()}
    for k in ("x", "y", "z"):
        props[k] = props[k] + rng.normal(0.0, 0.003, len(props[k]))
    return props, labels


@pytest.mark.parametrize("seed, n", [(0, 9), (1, 9), (0, 4), (1, 4)])
def test_handles_of_four_to_nine_points_are_kept_on_their_fronts(synth, seed, n):
    rec = reconstruct_scan(scan_from_arrays(*_sparse_handles(synth, n, seed)), seed=seed)
    obj = rec.objects[0]
    parts = {p.part_id: p for p in obj.parts}
    for hid, (mount, centre) in HANDLES.items():
        assert parts[hid].n_points == n
        assert np.linalg.norm(parts[hid].primitive.center - centre) < 0.03
        joint = next(j for j in obj.joints if j.child_part_id == hid)
        assert joint.parent_part_id == mount and joint.type.value == "fixed"


def test_a_handle_below_the_handle_limit_is_skipped_with_a_warning(synth):
    n = ScanConfig().handle_min_part_points - 1
    scan = scan_from_arrays(*_sparse_handles(synth, n))
    assert {p.part_id for p in scan.objects[0].parts}.isdisjoint(HANDLES)
    assert f"part 103 (handle): {n} points, fewer than {n + 1}; the part is skipped" in "\n".join(scan.warnings)


def test_min_part_points_flag(synth, tmp_path):
    props, labels = synth.scan_arrays([synth.cabinet()], points_per_m2=2000.0)
    synth.write_ply(tmp_path / "scan.ply", props)
    (tmp_path / "labels.json").write_text(json.dumps({"objects": labels}))
    args = ["build", str(tmp_path / "scan.ply"), "--labels", str(tmp_path / "labels.json"), "--no-preview", "-q"]
    assert main(args + ["--out", str(tmp_path / "bad"), "--min-part-points", "2"]) == 2
    n_door = int((props["part_id"] == 104).sum())
    assert main(args + ["--out", str(tmp_path / "out"), "--min-part-points", str(n_door + 1)]) == 0
    graph = json.loads((tmp_path / "out" / "graph.json").read_text())
    assert any(f"part 104 (door): {n_door} points, fewer than {n_door + 1}" in w for w in graph["warnings"])
