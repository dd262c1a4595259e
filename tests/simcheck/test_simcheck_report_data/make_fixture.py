"""Regenerate this folder from the REAL pipeline: ``python tests/simcheck/test_simcheck_report_data/make_fixture.py``.

Runs ``simcheck.demo`` (kitchen, seed 0, realistic scan, one drawer and two door tasks) in a temporary
folder and keeps what report.html is drawn from, made small enough to commit: the scan is a seeded
subsample of ``KEEP_POINTS`` points (scan.ply and previews are dropped); everything else (truth, scene.urdf,
graph.json, metrics.json, certificate.json, rollouts, key-frame images, demo.json) is kept as written.

The report test needs at least one EXECUTED task. When no task of the demo's certificate was executed
(e.g. the planner found no plan on the reconstruction), the same tasks are certified again on the truth
(plan and execute on truth.urdf) and that certificate is kept instead; the script says so.
"""

from __future__ import annotations

import json
import shutil
import sys
import tempfile
from pathlib import Path

import numpy as np

from simcheck.demo import DemoConfig, run_demo
from simcheck.report import DemoLayout

HERE = Path(__file__).resolve().parent
KEEP_POINTS = 20_000


def main() -> int:
    with tempfile.TemporaryDirectory() as tmp:
        result = run_demo(Path(tmp) / "demo", DemoConfig(max_drawers=1, max_doors=2))
        src = DemoLayout(result.out)
        cert = json.loads(src.certificate_json.read_text())
        if not any(t.get("rollout") for t in cert["tasks"]):
            import simcheck
            print("no task of the demo was executed: certifying the same tasks on the truth instead")
            shutil.rmtree(src.rollouts_dir, ignore_errors=True)
            shutil.rmtree(src.root / "images", ignore_errors=True)
            simcheck.certify(src.truth_urdf, [f"{t['kind']}:{t['joint']}" for t in cert["tasks"]], out=src.root,
                             seed=0)
        for name in ("truth", "rollouts", "images"):
            shutil.rmtree(HERE / name, ignore_errors=True)
        for f in ("scene.urdf", "graph.json", "metrics.json", "certificate.json", "demo.json"):
            (HERE / f).unlink(missing_ok=True)
            if (src.root / f).exists():
                shutil.copy(src.root / f, HERE / f)
        for d in ("rollouts", "images"):
            if (src.root / d).exists():
                shutil.copytree(src.root / d, HERE / d)
        (HERE / "truth").mkdir()
        for f in ("truth.json", "truth.urdf", "labels.json"):
            shutil.copy(src.truth_dir / f, HERE / "truth" / f)
        with np.load(src.scan_npz) as z:
            arrays = {k: z[k] for k in z.files}
        n = len(arrays["points"])
        keep = np.sort(np.random.default_rng(0).choice(n, min(KEEP_POINTS, n), replace=False))
        np.savez_compressed(HERE / "truth" / "scan.npz",
                            **{k: (v[keep] if v.ndim and len(v) == n else v) for k, v in arrays.items()})
    stages = json.loads((HERE / "demo.json").read_text())["stages"]
    for s in stages:
        print(f"{s['name']:12s} {s['status']:12s} {s['seconds']:7.1f} s  {s['message'][:100]}")
    return 0 if result.complete else 1


if __name__ == "__main__":
    sys.exit(main())
