"""Benchmark of ``scenes``: time and peak memory to make and scan each built-in scene, point counts.

    python -m bench.scenes_bench [--seeds 0 1] [--presets clean realistic]

Each (scene, seed, preset) runs in a fresh interpreter so its peak RSS (``ru_maxrss``) is its own;
``py peak`` is the tracemalloc peak of Python/numpy allocations during make+scan (excludes open3d's
C++ buffers). Times exclude interpreter start-up and imports.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys

__all__ = ["main"]


def _one(name: str, seed: int, preset: str) -> dict:
    import resource
    import time
    import tracemalloc

    import numpy as np

    import scenes.scanner.raycast_open3d  # noqa: F401  (import cost outside the timing)
    from scenes.builtin import build_scene
    from scenes.scanner import params_for_preset, scan_scene

    tracemalloc.start()
    t0 = time.perf_counter()
    scene = build_scene(name, seed)
    t1 = time.perf_counter()
    import open3d  # noqa: F401

    t2 = time.perf_counter()
    scan = scan_scene(scene, params_for_preset(preset), seed)
    t3 = time.perf_counter()
    _, peak = tracemalloc.get_traced_memory()
    counts = scan.counts_by_part()
    fronts = [counts.get(p.id, 0) for o in scene.objects for p in o.parts if p.label in ("drawer", "door")]
    visible = [c for pid, c in counts.items() if pid >= 0]
    return {"scene": name, "seed": seed, "preset": preset, "objects": len(scene.objects),
            "parts": sum(len(o.parts) for o in scene.objects),
            "joints": sum(j.movable for o in scene.objects for j in o.joints),
            "make_s": t1 - t0, "scan_s": t3 - t2, "points": len(scan),
            "object_points": int(np.count_nonzero(scan.object_id >= 0)),
            "median_part": int(np.median(visible)) if visible else 0,
            "min_front": min(fronts) if fronts else 0, "max_front": max(fronts) if fronts else 0,
            "py_peak_mb": peak / 2**20, "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.scenes_bench", description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, nargs="+", default=[0])
    ap.add_argument("--presets", nargs="+", default=["clean", "realistic"])
    ap.add_argument("--one", nargs=3, metavar=("NAME", "SEED", "PRESET"), help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.one:
        sys.stdout.write(json.dumps(_one(args.one[0], int(args.one[1]), args.one[2])) + "\n")
        return 0
    from scenes.builtin import SCENES

    cols = ["scene", "seed", "preset", "objects", "parts", "joints", "make_s", "scan_s", "points",
            "object_points", "median_part", "min_front", "max_front", "py_peak_mb", "rss_mb"]
    sys.stdout.write(" ".join(f"{c:>13s}" for c in cols) + "\n")
    for name in SCENES:
        for seed in args.seeds:
            for preset in args.presets:
                r = subprocess.run([sys.executable, "-m", "bench.scenes_bench", "--one", name, str(seed), preset],
                                   capture_output=True, text=True)
                if r.returncode != 0:
                    sys.stdout.write(f"{name} {seed} {preset}: FAILED {r.stderr.strip().splitlines()[-1]}\n")
                    continue
                row = json.loads(r.stdout.strip().splitlines()[-1])
                sys.stdout.write(" ".join(f"{row[c]:>13.2f}" if isinstance(row[c], float) else f"{row[c]!s:>13s}"
                                          for c in cols) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
