"""Benchmark on third-party MJCF furniture from the package index: ``python -m bench.mjcf_assets_bench
[--assets DIR ...] [--only NAME ...] [--end-to-end] [--out DIR]``.

Imports every object of :data:`thirdparty.mjcf_assets.MJCF_ASSETS` (Franka Kitchen from gymnasium-robotics,
LIBERO's articulated objects) found installed or as wheels / unpacked packages under ``--assets`` (objects
not found are listed and skipped), certifies each hinge and slide joint on the object's own URDF (the
estimate is the truth) and prints per object and task the verdict and its reason. With ``--end-to-end``
each object is also scanned (realistic preset), rebuilt by ``recon`` and each front executed ``--against``
its own URDF (``bench.thirdparty_bench``'s end-to-end run). Target line: certified on their own URDF
>= 95 % of the drawers and doors (the controls of the oven -- knobs, burners, switch -- are listed apart:
they are not drawers or doors). Exit 0 when met, 1 otherwise; 0 with a "skipped" line when no asset is
found (the packages are not dependencies: ``python -m bench`` runs this one with no arguments).
"""

from __future__ import annotations

import argparse
import logging
import sys
import tempfile
from collections import Counter
from pathlib import Path

__all__ = ["main"]

TRUTH_TARGET = 0.95
CONTROLS = ("oven",)          # categories whose joints are controls, not drawers or doors


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.mjcf_assets_bench", description=__doc__.splitlines()[0])
    ap.add_argument("--assets", nargs="*", default=[], help="folders holding the wheels or unpacked packages")
    ap.add_argument("--only", nargs="*", help="asset names (default: all)")
    ap.add_argument("--out", help="folder for the imported objects (default: a temporary folder)")
    ap.add_argument("--end-to-end", action="store_true", help="also scan, reconstruct and certify --against")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    from bench.thirdparty_bench import _certify_one, _end_to_end
    from thirdparty.mjcf_assets import MJCF_ASSETS, asset_named, asset_roots, build_mjcf_object

    with tempfile.TemporaryDirectory(prefix="mjcf_assets_bench_") as tmp:
        root = Path(args.out or tmp)
        roots = asset_roots(args.assets, unpack_to=root / "wheels")
        chosen = [asset_named(n) for n in args.only] if args.only else list(MJCF_ASSETS)
        objs, missing = [], []
        for a in chosen:
            try:
                objs.append(build_mjcf_object(a, roots, root / "imported"))
            except FileNotFoundError as exc:
                missing.append((a.name, str(exc)))
            except Exception as exc:        # an import the tool refuses is a result
                missing.append((a.name, f"{type(exc).__name__}: {exc}"))
        for name, why in missing:
            print(f"not imported: {name}: {why}")
        if not objs:
            print("skipped: no MJCF asset found (install gymnasium-robotics / the LIBERO assets, or give --assets DIR "
                  "holding their wheels)")
            return 0
        print(f"imported: {len(objs)} objects, {sum(len(o.fronts) for o in objs)} joints", flush=True)
        rows = []
        for o in objs:
            for f in o.fronts:
                status, reason, dt = _certify_one(o.urdf, f.task, None)
                rows.append((o, f, status, reason))
                print(f"  {o.spec.name:24s} {f.task:36s} {f.kind:11s} {status:12s} {dt:5.1f} s", flush=True)
        if args.end_to_end:
            _end_to_end([o for o in objs if o.spec.category not in CONTROLS], root / "e2e")
    return _report(rows)


def _report(rows) -> int:
    print("\n## Per object (own URDF)")
    print(f"{'object':24s} {'size (d x w x h, m)':20s} {'stands at':9s} {'certified':>9s} {'of':>3s}")
    seen = {}
    for o, f, status, _ in rows:
        c = seen.setdefault(o.spec.name, [o, 0, 0])
        c[1] += status == "certified"
        c[2] += 1
    for name, (o, ok, n) in seen.items():
        s = o.spec
        print(f"{name:24s} {s.depth:.2f} x {s.width:.2f} x {s.height:.2f}    {s.elevation:5.2f} m   {ok:9d} {n:3d}")
    fronts = [r for r in rows if r[0].spec.category not in CONTROLS]
    controls = [r for r in rows if r[0].spec.category in CONTROLS]
    for title, group in (("Drawers and doors not certified", fronts), ("Controls (not drawers or doors)", controls)):
        bad = [r for r in group if r[2] != "certified"]
        print(f"\n## {title} ({len(bad)} of {len(group)})")
        for o, f, status, reason in bad:
            print(f"- {o.spec.name} {f.task} [{status}]: {reason[:400]}")
    c = Counter(r[2] for r in fronts)
    ok = c["certified"]
    share = ok / max(1, len(fronts))
    print("\noutcomes (drawers and doors): " + ", ".join(f"{k} {n}" for k, n in sorted(c.items())))
    met = share >= TRUTH_TARGET
    print(f"{'YES' if met else 'NO '} certified on their own URDF >= {TRUTH_TARGET:.0%}: {ok}/{len(fronts)} ({share:.1%})",
          flush=True)
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main())
