"""Speed of ``recon.reconstruct`` on a room of 10+ objects (the issue's target: < 10 s on 2 cores).

    python -m bench.recon_core_speed [--scene studio] [--preset clean] [--repeat 3] [--out DIR]

Prints the scene size (objects, parts, points per part) and, per run, the wall time of each stage
(the first run includes importing open3d). The machine is shared: read the minimum.
"""

from __future__ import annotations

import argparse
import logging
import sys
import time
from pathlib import Path

import numpy as np


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.recon_core_speed", description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="studio")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--preset", default="clean")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default="out/bench_recon_speed")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    import scenes

    from recon import reconstruct
    from recon.scan import read_scan

    d = Path(args.out) / f"{args.scene}_{args.seed}_{args.preset}"
    if not (d / "scan.ply").exists():
        scenes.make_scene(args.scene, seed=args.seed, preset=args.preset, out=d, previews=False)
    scan = read_scan(d / "scan.ply", d / "labels.json")
    per_part = [len(p.points) for o in scan.objects for p in o.parts]
    print(f"{args.scene} seed {args.seed} ({args.preset}): {len(scan.objects)} objects, {len(per_part)} parts, "
          f"{len(scan.points)} points; points/part median {int(np.median(per_part))}, "
          f"mean {int(np.mean(per_part))}, max {max(per_part)}")
    stages = None
    for k in range(args.repeat):
        t0 = time.perf_counter()
        rec = reconstruct(d / "scan.ply", d / "labels.json")
        wall = time.perf_counter() - t0
        if stages is None:
            stages = list(rec.timings)
            print(f"{'run':>4s} {'wall s':>8s} " + " ".join(f"{s:>12s}" for s in stages))
        print(f"{k:4d} {wall:8.2f} " + " ".join(f"{rec.timings.get(s, 0.0):12.2f}" for s in stages))
    return 0


if __name__ == "__main__":
    sys.exit(main())
