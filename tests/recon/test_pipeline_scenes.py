"""End to end against the ground truth of a generated room (scenes): joint types, axes, hinge lines,
limits and part trees compared with truth.json, matched by joint name."""

import json

import numpy as np
import pytest

from recon import reconstruct
from recon.part_tree import contact_scores


@pytest.fixture(scope="module")
def kitchen(tmp_path_factory):
    scenes = pytest.importorskip("scenes")
    out = tmp_path_factory.mktemp("kitchen_clean")
    scenes.make_scene("kitchen", seed=0, preset="clean", out=out, previews=False)
    truth = json.loads((out / "truth.json").read_text())
    return reconstruct(out / "scan.ply", out / "labels.json", seed=0), truth


def _line_distance(p, a, q):
    d = q - p
    return float(np.linalg.norm(d - (d @ a) * a))


def test_joints_match_truth(kitchen):
    rec, truth = kitchen
    est = {j.name: j for j in rec.joints()}
    true = {j["name"]: j for o in truth["objects"] for j in o["joints"]}
    assert est.keys() == true.keys()
    moving = [n for n, t in true.items() if t["type"] != "fixed"]
    assert len(moving) >= 4
    for name, t in true.items():
        e = est[name]
        assert e.type.value == t["type"], name
        assert e.parent_part_id == t["parent_part_id"], name
        if t["type"] == "fixed":
            continue
        a = np.asarray(t["axis"])
        assert np.degrees(np.arccos(np.clip(e.axis @ a, -1, 1))) < 2.0, name
        assert _line_distance(np.asarray(t["origin"]), a, e.origin) < 0.02, name
        if t["type"] == "prismatic":
            assert e.upper == pytest.approx(t["upper"], abs=0.03), name
        else:
            assert e.upper == pytest.approx(t["upper"], abs=0.35), name     # truth draws 1.6-1.9 rad


def test_every_true_contact_is_found_and_supports_are_right(kitchen):
    rec, truth = kitchen
    for o in truth["objects"]:
        est = contact_scores(rec.object(o["id"]), rec.config.tree)
        for a, b in o["contacts"]:
            assert (min(a, b), max(a, b)) in est, (o["name"], a, b)
        assert rec.object(o["id"]).supported_by == o["supported_by"], o["name"]
    assert not [w for w in rec.warnings if "touches no" in w]
