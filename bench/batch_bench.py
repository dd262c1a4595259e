"""Benchmark of ``simcheck batch``: ``python -m bench.batch_bench [--kitchens 4] [--out DIR]``.

Generates kitchens (truth only: each has a cabinet with a door and three drawers, a microwave door and
two refrigerator doors, so 7 tasks each) and certifies every drawer and door of their truth scenes:
1. plain ``simcheck.certify`` of each task in this process, one after the other (the reference, and
   where the time of one certification goes: world set-up, planning, re-check, physics, writing);
2. ``simcheck.batch`` of the same tasks on a local Ray with 1 worker, then with 2 workers;
3. the batch again on its finished folder (the resume).
Prints certifications per core-hour at 1 and 2 workers (wall time x workers, Ray start-up included),
the speed-up, the per-task overhead over plain certify, the resume time, worker memory, whether every
batch certificate equals the plain one (criteria to 1e-9), and the issue's targets (YES/NO).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["main"]


def _plain(tasks: list[tuple[Path, str]], out: Path) -> tuple[float, list, dict]:
    """Certify each task with plain certify; returns (wall s, certificates, mean seconds by stage)."""
    import simcheck

    certs, stages = [], {"setup+write": [], "plan": [], "recheck": [], "execute": [], "total": []}
    t_all, cpu_all = time.perf_counter(), time.process_time()
    for i, (scene, task) in enumerate(tasks):
        t0 = time.perf_counter()
        cert = simcheck.certify(scene, [task], seed=0, out=out / f"plain{i}", images=False)
        wall = time.perf_counter() - t0
        t = cert.tasks[0].timings
        certs.append(cert)
        for k in ("plan", "recheck", "execute"):
            stages[k].append(t.get(k, 0.0))
        stages["total"].append(wall)
        stages["setup+write"].append(wall - t.get("total", 0.0))
    stages["cpu"] = [(time.process_time() - cpu_all) / len(tasks)]
    return time.perf_counter() - t_all, certs, {k: statistics.mean(v) for k, v in stages.items()}


def _images_cost(scene: Path, task: str, out: Path) -> float:
    import simcheck

    t0 = time.perf_counter()
    simcheck.certify(scene, [task], seed=0, out=out / "img", images=True)
    return time.perf_counter() - t0


def _batch(manifest: Path, out: Path, workers: int) -> tuple[float, object]:
    import simcheck

    t0 = time.perf_counter()
    result = simcheck.batch(manifest, out, workers=workers, progress=False)
    return time.perf_counter() - t0, result


def _same(rows: list[dict], out: Path, plain: list) -> tuple[bool, float]:
    """Whether every row's certificate equals the plain one (status and criteria to 1e-9); worst diff."""
    from simcheck.certificate import Certificate

    worst, ok = 0.0, True
    for row, cert in zip(rows, plain, strict=True):
        t = Certificate.load(out / row["certificate"]).tasks[0]
        p = cert.tasks[0]
        ok &= t.status == p.status and [c.name for c in t.criteria] == [c.name for c in p.criteria]
        for a, b in zip(t.criteria, p.criteria):
            worst = max(worst, abs(a.value - b.value))
    return ok and worst <= 1e-9, worst


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.batch_bench", description=__doc__.splitlines()[0])
    p.add_argument("--kitchens", type=int, default=4, help="generated kitchens (7 tasks each; default 4)")
    p.add_argument("--out", default=None, help="keep the files here (default: a temp folder)")
    args = p.parse_args(argv)
    import logging

    logging.basicConfig(level=logging.WARNING)
    import scenes
    from simcheck.batching.runner import all_movable_tasks

    root = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="batch-bench-"))
    tasks: list[tuple[Path, str]] = []
    lines = []
    for seed in range(args.kitchens):
        d = root / f"kitchen{seed}"
        if not (d / "truth.urdf").is_file():
            scenes.make_scene("kitchen", seed=seed, scan=False, previews=False, out=d)
        ts = all_movable_tasks(d / "truth.urdf")[0]
        tasks += [(d / "truth.urdf", t) for t in ts]
        lines.append(json.dumps({"scene": str(d / "truth.urdf"), "tasks": ts}))
    manifest = root / "manifest.jsonl"
    manifest.write_text("\n".join(lines) + "\n")
    n = len(tasks)
    import os

    print(f"{n} tasks ({args.kitchens} kitchens, truth scenes), folder {root}; {os.cpu_count()} cores, load "
          f"average {os.getloadavg()[0]:.1f} (wall-time rates and the speed-up mean little when it exceeds the cores)")

    plain_wall, plain, stages = _plain(tasks, root / "plain")
    img = _images_cost(*tasks[0], root / "plain")
    print(f"\nplain certify, one process: {plain_wall:.1f} s, {plain_wall / n:.3f} s a task")
    print("where one certification's time goes (mean s): " + ", ".join(f"{k} {v:.3f}" for k, v in stages.items()))
    print(f"the same first task with key-frame images: {img:.3f} s (without: {stages['total']:.3f} s mean)")

    w1, r1 = _batch(manifest, root / "batch1", 1)
    w2, r2 = _batch(manifest, root / "batch2", 2)
    wr, rr = _batch(manifest, root / "batch2", 2)
    same1, d1 = _same(r1.rows, root / "batch1", plain)
    same2, d2 = _same(r2.rows, root / "batch2", plain)
    per_hour1, per_hour2 = n / (w1 / 3600), n / (w2 * 2 / 3600)
    row_s1 = statistics.mean(r["seconds"] for r in r1.rows if r["seconds"])
    overhead_total = w1 / plain_wall - 1
    recs2 = _records(root / "batch2", r2.rows)
    rss = [r["worker"]["peak_rss_mb"] for r in recs2]
    cpu2 = sum(r.get("cpu_seconds", 0.0) for r in recs2)
    cpu_per_hour = n / (cpu2 / 3600)
    print(f"\nbatch, 1 worker: {w1:.1f} s wall ({r1.totals}), {per_hour1:,.0f} certifications per core-hour")
    print(f"batch, 2 workers: {w2:.1f} s wall ({r2.totals}), {per_hour2:,.0f} certifications per core-hour")
    print(f"speed-up on 2 cores: {w1 / w2:.2f}x (load average now {os.getloadavg()[0]:.1f})")
    print(f"CPU time of the tasks in the workers (2-worker run): {cpu2 / n:.3f} s a task = {cpu_per_hour:,.0f} "
          f"certifications per CPU-core-hour (plain certify: {stages['cpu']:.3f} s a task of process CPU time)")
    print(f"overhead over plain certify at 1 worker: {100 * overhead_total:+.1f}% of the wall time "
          f"(Ray start-up included); a task's own time in the batch {row_s1:.3f} s vs plain {stages['total']:.3f} s")
    print(f"resume of the finished batch: {wr:.2f} s = {100 * wr / w2:.1f}% of its first run "
          f"(computed {rr.computed}, resumed {rr.resumed})")
    print(f"worker peak resident memory: median {statistics.median(rss):.0f} MB, max {max(rss):.0f} MB")
    print(f"batch certificates equal to plain certify (criteria to 1e-9): 1 worker {same1} (max diff {d1:.2g}), "
          f"2 workers {same2} (max diff {d2:.2g})")

    targets = [(f">= 5,000 certifications per core-hour of task CPU time ({cpu_per_hour:,.0f})", cpu_per_hour >= 5000),
               (f">= 5,000 certifications per core-hour (1 worker: {per_hour1:,.0f})", per_hour1 >= 5000),
               (f">= 5,000 certifications per core-hour (2 workers: {per_hour2:,.0f})", per_hour2 >= 5000),
               (f"speed-up on 2 cores >= 1.7x ({w1 / w2:.2f}x)", w1 / w2 >= 1.7),
               (f"overhead over plain certify <= 10% ({100 * overhead_total:+.1f}%)", overhead_total <= 0.10),
               (f"resume < 10% of the first run ({100 * wr / w2:.1f}%)", wr < 0.1 * w2),
               ("every batch certificate equals plain certify", same1 and same2)]
    print("\nTargets (issue 13)")
    for text, met in targets:
        print(f"  {'YES' if met else 'NO '}  {text}")
    return 0


def _records(out: Path, rows: list[dict]) -> list[dict]:
    return [json.loads((out / "results" / r["key"] / "result.json").read_text()) for r in rows]


if __name__ == "__main__":
    sys.exit(main())
