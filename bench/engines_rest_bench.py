"""Does the scene rest in every engine? ``python -m bench.engines_rest_bench [--scenes kitchen:0 bedroom:0]
[--preset realistic] [--no-clearance] [--out DIR]``.

For each built-in scene and seed: scan (``--preset``), reconstruct (``--no-clearance``: without the
clearance stage, to measure what it does), write scene.urdf + scene.xml; then for scene.urdf, scene.xml and
the truth's truth.urdf: the link pairs interpenetrating more than 0.5 mm at q = 0 (coal) and the largest
joint motion after 2 s of gravity with no robot in MuJoCo, PyBullet (self-collision on) and Drake (each when
installed; MJCF only in MuJoCo). Prints one row per file and the target line: every file rests (no joint
moves more than 1 mm / 0.01 rad) with no pair over 0.5 mm.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib.util
import logging
import tempfile
from pathlib import Path

__all__ = ["main"]


def _engines() -> list[str]:
    return [e for e, mod in (("mujoco", "mujoco"), ("pybullet", "pybullet"), ("drake", "pydrake"))
            if importlib.util.find_spec(mod) is not None]


def _files(name: str, seed: int, preset: str, clearance: bool, out: Path) -> dict[str, Path]:
    import recon
    import scenes
    from recon.config import ClearanceConfig, ReconConfig

    scenes.make_scene(name, seed=seed, preset=preset, out=out / "truth", previews=False)
    config = dataclasses.replace(ReconConfig(), clearance=ClearanceConfig(enabled=clearance))
    rec = recon.reconstruct(out / "truth" / "scan.npz", out / "truth" / "labels.json", config=config, seed=0)
    paths = recon.write_reconstruction(rec, out, mjcf=True)
    return {"scene.urdf": paths["scene.urdf"], "scene.xml": paths["scene.xml"], "truth.urdf": out / "truth" / "truth.urdf"}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.engines_rest_bench", description=__doc__.split("\n\n")[0])
    p.add_argument("--scenes", nargs="+", default=["kitchen:0", "kitchen:1", "bedroom:0", "office:0"],
                   help="NAME:SEED of built-in scenes")
    p.add_argument("--preset", default="realistic")
    p.add_argument("--no-clearance", action="store_true", help="reconstruct without recon.clearance")
    p.add_argument("--out", type=Path, help="keep the files here (default: a temporary folder)")
    args = p.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    from simcheck.rest import link_overlaps, rest_motion

    engines = _engines()
    print(f"engines: {', '.join(engines)}; preset {args.preset}; clearance {'off' if args.no_clearance else 'on'}")
    print(f"{'scene':12s} {'file':11s} {'pairs>0.5mm':>11s} {'deepest mm':>10s} "
          + " ".join(f"{e + ' max':>14s}" for e in engines))
    ok = True
    with tempfile.TemporaryDirectory(prefix="engines_rest_") as tmp:
        root = args.out or Path(tmp)
        for spec in args.scenes:
            name, seed = spec.split(":")
            files = _files(name, int(seed), args.preset, not args.no_clearance, root / f"{name}{seed}")
            for label, path in files.items():
                overlaps = link_overlaps(path) if path.suffix == ".urdf" else []
                cells = []
                for e in engines:
                    if path.suffix == ".xml" and e != "mujoco":
                        cells.append(f"{'-':>14s}")
                        continue
                    motion = rest_motion(path, e)
                    worst = max(motion.items(), key=lambda kv: abs(kv[1][1]) / (1e-3 if kv[1][0] == "slide" else 0.01),
                                default=(None, ("slide", 0.0)))
                    kind, v = worst[1]
                    unit = "m" if kind == "slide" else "rad"
                    ok &= abs(v) <= (1e-3 if kind == "slide" else 0.01)
                    cells.append(f"{abs(v):>10.4f} {unit:3s}")
                ok &= not overlaps
                deepest = max((d for _, _, d in overlaps), default=0.0) * 1e3
                pairs = (f"{len(overlaps):>11d} {deepest:>10.1f}" if path.suffix == ".urdf"
                         else f"{'-':>11s} {'-':>10s}")      # scene.xml: the URDF's shapes, contacts of overlapping pairs excluded
                print(f"{spec:12s} {label:11s} {pairs} " + " ".join(cells), flush=True)
    print(f"TARGET every file rests (<= 1 mm / 0.01 rad in 2 s) with no link pair over 0.5 mm: {'YES' if ok else 'NO'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
