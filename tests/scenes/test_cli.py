"""API and CLI end to end: every file written, readable and consistent; clear errors on bad input."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from scenes import make_scene
from scenes.cli import main
from scenes.errors import SceneSpecError
from scenes.scan_io import read_scan_ply


def test_cli_make_writes_truth_scan_and_previews(tmp_path):
    out = tmp_path / "k"
    r = subprocess.run([sys.executable, "-m", "scenes", "make", "kitchen", "--seed", "1", "--out", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "kitchen seed 1" in r.stdout
    for name in ("truth.urdf", "truth.json", "scan.ply", "labels.json", "scan.npz", "preview_room.png",
                 "preview_scan.png"):
        assert (out / name).stat().st_size > 1000, name
    assert (out / "preview_room.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    ply = read_scan_ply(out / "scan.ply")
    npz = np.load(out / "scan.npz")
    assert len(ply) == len(npz["points"]) > 10000
    assert np.allclose(np.stack([ply["x"], ply["y"], ply["z"]], 1), npz["points"], atol=1e-6)
    assert np.array_equal(ply["part_id"], npz["part_id"]) and np.array_equal(ply["object_id"], npz["object_id"])
    labels = json.loads((out / "labels.json").read_text())
    assert json.loads(str(npz["labels"])) == labels
    truth = json.loads((out / "truth.json").read_text())
    meta = json.loads((out / "scan_meta.json").read_text())
    assert meta["preset"] == "clean" and meta["seed"] == 1 and meta["points"] == len(ply)
    assert np.array(meta["T_world_cameras"]).shape == (meta["frames"], 4, 4)
    assert {o["id"] for o in labels["objects"]} == {o["id"] for o in truth["objects"]}
    # part ids are unique in the file and map to one object each
    pairs = set(zip(ply["object_id"].tolist(), ply["part_id"].tolist()))
    by_part = {}
    for oid, pid in pairs:
        by_part.setdefault(pid, set()).add(oid)
    assert all(len(v) == 1 for pid, v in by_part.items() if pid >= 0)
    # open3d reads the PLY too (recon may use it)
    import open3d as o3d

    assert len(o3d.io.read_point_cloud(str(out / "scan.ply")).points) == len(ply)


def test_cli_list_and_errors(tmp_path, capsys):
    assert main(["list"]) == 0
    listed = capsys.readouterr().out
    assert all(n in listed for n in ("kitchen", "bedroom", "office", "random"))
    assert main(["make", "garage", "--out", str(tmp_path / "g")]) == 2
    assert "unknown scene 'garage'" in capsys.readouterr().err
    assert main(["make", "kitchen", "--preset", "noisy", "--out", str(tmp_path / "n")]) == 2
    assert "unknown scan preset 'noisy'" in capsys.readouterr().err
    assert main(["make", "kitchen", "--seed", "-2", "--out", str(tmp_path / "s")]) == 2
    assert "seed must be a non-negative integer" in capsys.readouterr().err
    assert not (tmp_path / "g").exists()
    with pytest.raises(SystemExit):
        main(["make", "kitchen"])          # --out is required


def test_api_truth_only_and_output_that_is_a_file(tmp_path):
    made = make_scene("bedroom", seed=2, out=tmp_path / "b", scan=False, previews=False)
    assert made.scan is None and sorted(made.files) == ["truth_json", "truth_urdf"]
    f = tmp_path / "file"
    f.write_text("x")
    with pytest.raises(SceneSpecError, match="exists and is not a directory"):
        make_scene("bedroom", out=f, scan=False)
    assert f.read_text() == "x"


def test_realistic_preset_density(tmp_path):
    """recon needs ~1-3k points per visible part; the whole scan stays under ~300k points."""
    made = make_scene("kitchen", seed=0, preset="realistic", previews=False)
    s = made.scan
    assert len(s) < 300_000
    counts = s.counts_by_part()
    fronts = [p.id for o in made.scene.objects for p in o.parts if p.label in ("drawer", "door")]
    assert all(counts.get(pid, 0) >= 800 for pid in fronts), {pid: counts.get(pid, 0) for pid in fronts}
    assert 0.0 < s.is_outlier.mean() < 0.01
