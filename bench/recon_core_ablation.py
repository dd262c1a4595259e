"""What each design choice of recon's core does, measured on the built-in scenes (clean and realistic).

    python -m bench.recon_core_ablation [--scenes kitchen,bedroom,office] [--preset clean,realistic]
                                        [--out DIR] [--samples 4000]

Variants (each a ``ReconConfig`` change from the default):
    default      observed-face Eq. 3 score + point term, exact primitive faces as planes, Alg. 1 on
    plain-eq3    the paper's Eq. 3 as written (every face counts, no point term)
    ransac       planes Π by RANSAC on the part's points (the paper's Sec. III-B) instead of exact faces
    no-refine    Alg. 1 off
For each: scene IoU / Chamfer (recon.metrics), contact-edge mAP, the share of tree edges that are real
Eq. 1 contacts (not fallbacks), joint type accuracy, median axis / hinge errors, and the total volume
shared by parent/child primitives (the interpenetration Alg. 1 is meant to remove).
"""

from __future__ import annotations

import argparse
import logging
import sys
import time
from pathlib import Path

import numpy as np

VARIANTS = {
    "default": {},
    "plain-eq3": {"min_face_coverage": 0.0, "point_term_weight": 0.0},
    "ransac": {"planes": "ransac"},
    "no-refine": {"refine": False},
}


def interpenetration_volume(rec) -> float:
    """Sum over tree edges of the volume (m^3) shared by parent and child primitives."""
    from recon.refinement import interpenetration

    total = 0.0
    for o in rec.objects:
        for p, c in o.tree_edges():
            total += interpenetration(o.part(p).primitive, o.part(c).primitive)
    return total


def run(scene_dir: Path, variant: str, samples: int) -> dict:
    from recon import ReconConfig, reconstruct
    from recon.metrics import (MetricsConfig, estimate_from_reconstruction, evaluate_scene, joint_summary,
                               mean_average_precision, read_truth)

    cfg = ReconConfig().replace(**VARIANTS[variant])
    t0 = time.perf_counter()
    rec = reconstruct(scene_dir / "scan.ply", scene_dir / "labels.json", config=cfg)
    seconds = time.perf_counter() - t0
    truth = read_truth(scene_dir / "truth.json")
    m = evaluate_scene(truth, [estimate_from_reconstruction(o, rec.config) for o in rec.objects],
                       MetricsConfig(chamfer_samples=samples))
    js = joint_summary([j for o in m.objects for j in o.joints])
    n_edges = sum(len(o.tree_edges()) for o in rec.objects)
    n_contact = n_edges - sum(len(o.isolated_part_ids) for o in rec.objects)
    map_ = mean_average_precision(o.ap for o in m.objects)
    return {"iou": float(np.mean([o.iou for o in m.objects])), "chamfer": float(np.mean([o.chamfer for o in m.objects])),
            "map": float(map_), "contact_edges": n_contact / max(n_edges, 1),
            "type_acc": js.type_accuracy, "axis_deg": js.median_axis_error_deg, "hinge_m": js.median_hinge_distance_m,
            "penetration_cm3": interpenetration_volume(rec) * 1e6, "seconds": seconds}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.recon_core_ablation", description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", default="kitchen,bedroom,office")
    ap.add_argument("--preset", default="clean,realistic")
    ap.add_argument("--variants", default=",".join(VARIANTS))
    ap.add_argument("--out", default="out/bench_recon_core")
    ap.add_argument("--samples", type=int, default=4000, help="Chamfer samples per side")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    import scenes

    rows = []
    for preset in args.preset.split(","):
        for name in args.scenes.split(","):
            d = Path(args.out) / f"{name}_{preset}"
            if not (d / "truth.json").exists():
                scenes.make_scene(name, seed=0, preset=preset, out=d, previews=False)
            for variant in args.variants.split(","):
                print(f"[{preset}] {name} {variant} ...", file=sys.stderr, flush=True)
                rows.append((preset, name, variant, run(d, variant, args.samples)))
    cols = ["iou", "chamfer", "map", "contact_edges", "type_acc", "axis_deg", "hinge_m", "penetration_cm3", "seconds"]
    print(f"{'preset':10s} {'scene':8s} {'variant':10s} " + " ".join(f"{c:>15s}" for c in cols))
    for preset, name, variant, r in rows:
        print(f"{preset:10s} {name:8s} {variant:10s} " + " ".join(f"{r[c]:15.4f}" for c in cols))
    print("\nmeans over scenes")
    for preset in args.preset.split(","):
        for variant in args.variants.split(","):
            sel = [r for p, _, v, r in rows if p == preset and v == variant]
            print(f"{preset:10s} {'mean':8s} {variant:10s} " +
                  " ".join(f"{np.nanmean([r[c] for r in sel]):15.4f}" for c in cols))
    return 0


if __name__ == "__main__":
    sys.exit(main())
