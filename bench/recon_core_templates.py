"""What the articulated-template shapes (hollow carcass, drawer boxes; recon/part_shapes.py) do to the
geometry metrics: the same reconstruction scored with each part as its one fitted primitive and with
its template shapes, next to the object-level baseline.

    python -m bench.recon_core_templates [--scenes kitchen,bedroom,office] [--random 3] [--preset realistic]
                                         [--out DIR] [--samples 10000]

Scenes are made with ``scenes.make_scene`` and cached in ``--out`` (the same layout as
``bench.recon_bench``, so its cache can be reused). Prints one table per preset.
"""

from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path

log = logging.getLogger("bench.recon_core_templates")


def _estimates(rec, solids: bool):
    from recon.metrics import ObjectEstimate, estimate_from_reconstruction

    out = []
    for o in rec.objects:
        base = estimate_from_reconstruction(o, rec.config)
        prims, ids = [], []
        for p in o.parts:
            shapes = p.solids if solids else (p.primitive,)
            prims += list(shapes)
            ids += [p.part_id] * len(shapes)
        out.append(ObjectEstimate(o.id, o.category, tuple(prims), base.joints, base.contact_scores,
                                  base.seconds, tuple(ids)))
    return out


def run(scene: str, seed: int, preset: str, root: Path, samples: int) -> tuple[str, list[float]]:
    import recon
    from recon.baseline import object_level_from_files
    from recon.metrics import MetricsConfig, evaluate_scene, read_truth
    from scenes import make_scene

    d = root / f"{scene}_{seed}_{preset}"
    if not all((d / f).is_file() for f in ("truth.json", "scan.ply", "labels.json")):
        make_scene(scene, seed=seed, preset=preset, out=d, previews=False)
    truth = read_truth(d / "truth.json")
    cfg = MetricsConfig(chamfer_samples=samples, seed=seed)
    rec = recon.reconstruct(d / "scan.ply", d / "labels.json", seed=seed)
    prim = evaluate_scene(truth, _estimates(rec, False), cfg)
    tpl = evaluate_scene(truth, _estimates(rec, True), cfg)
    base = evaluate_scene(truth, object_level_from_files(d / "scan.ply", d / "labels.json").estimates, cfg)
    label = scene if scene != "random" else f"random/{seed}"
    return label, [prim.chamfer, tpl.chamfer, base.chamfer, prim.iou, tpl.iou, base.iou]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.recon_core_templates", description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", default="kitchen,bedroom,office")
    ap.add_argument("--random", type=int, default=3)
    ap.add_argument("--preset", default="clean,realistic")
    ap.add_argument("--out", default="out/bench_recon")
    ap.add_argument("--samples", type=int, default=10000)
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    cases = [(s, 0) for s in args.scenes.split(",") if s] + [("random", k) for k in range(args.random)]
    head = ["scene", "Cd primitives", "Cd templates", "Cd object-level", "IoU primitives", "IoU templates",
            "IoU object-level", "templates win Cd/IoU"]
    for preset in args.preset.split(","):
        rows = []
        for scene, seed in cases:
            label, v = run(scene, seed, preset, Path(args.out), args.samples)
            print(f"[{preset}] {label} done", file=sys.stderr)
            win = f"{'yes' if v[1] < v[2] else 'no'}/{'yes' if v[4] > v[5] else 'no'}"
            rows.append([label] + [f"{x:.4f}" if k < 3 else f"{x:.3f}" for k, x in enumerate(v)] + [win])
        w = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(head)]
        print(f"\n{preset} scans: Chamfer (unit box) and IoU (32^3) with parts as primitives vs template shapes")
        print("  ".join(h.ljust(w[k]) for k, h in enumerate(head)))
        print("  ".join("-" * x for x in w))
        for r in rows:
            print("  ".join(c.ljust(w[k]) for k, c in enumerate(r)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
