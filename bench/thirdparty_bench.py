"""Benchmark on the third-party corpus: ``python -m bench.thirdparty_bench [--only NAME ...] [--no-wrong]
[--end-to-end]``.

Builds every object of :data:`thirdparty.CATALOGUE` (URDFs in other people's conventions), certifies each
drawer and door on its own URDF (target: >= 95 % certified; every other one is listed with its reason),
then plans each front's wrong estimates (``thirdparty.wrong``: 30 deg axis; for doors also door-as-drawer
and the hinge on the wrong side) and executes them ``--against`` the object's own URDF (target: none
certified). With ``--end-to-end``: each object is scanned (``thirdparty.scannable``, realistic preset),
rebuilt by ``recon`` and each front planned on the reconstruction and executed ``--against`` the object's
own URDF (its joints renamed as recon names them; no target, reported). Prints per-category tables, every
non-certified truth task with its reason, and YES/NO target lines. Exit 0 when both targets are met, 1
otherwise.
"""

from __future__ import annotations

import argparse
import logging
import sys
import tempfile
import time
from collections import Counter, defaultdict
from pathlib import Path

__all__ = ["main", "reconstructed_fronts"]

TRUTH_TARGET = 0.95


def _certify_one(urdf: Path, task: str, against: Path | None):
    """(status name, reason, seconds) of one task; unusable input / errors come back as their class name."""
    from simcheck.certification import certify
    t0 = time.perf_counter()
    try:
        cert = certify(urdf, [task], against=against, images=False)
        t = cert.tasks[0]
        return str(t.status.value if hasattr(t.status, "value") else t.status), t.reason, time.perf_counter() - t0
    except Exception as exc:          # unusable input is a result of this benchmark, not a crash
        return f"unusable:{type(exc).__name__}", str(exc), time.perf_counter() - t0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.thirdparty_bench", description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="*", help="catalogue object names (default: all)")
    ap.add_argument("--no-wrong", action="store_true", help="skip the wrong estimates")
    ap.add_argument("--out", help="folder for the built corpus (default: a temporary folder)")
    ap.add_argument("--end-to-end", action="store_true", help="also scan, reconstruct and certify --against")
    ap.add_argument("--no-truth", action="store_true", help="skip the truth and wrong runs")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    import thirdparty
    from thirdparty.wrong import WRONG_KINDS, wrong_estimate

    with tempfile.TemporaryDirectory(prefix="thirdparty_bench_") as tmp:
        root = Path(args.out or tmp)
        objs = thirdparty.build_corpus(root / "corpus", args.only or None)
        n_fronts = sum(len(o.fronts) for o in objs)
        print(f"corpus: {len(objs)} objects, {n_fronts} drawers and doors", flush=True)
        truth = []          # (category, object, front, status, reason, seconds)
        if args.end_to_end:
            _end_to_end(objs, root / "e2e")
        if args.no_truth:
            return 0
        for o in objs:
            for f in o.fronts:
                status, reason, dt = _certify_one(o.urdf, f.task, None)
                truth.append((o.spec.category, o.spec.name, f, status, reason, dt))
                print(f"  truth {o.spec.name:28s} {f.task:40s} {status:12s} {dt:5.1f} s", flush=True)
        _report_truth(truth, len(objs), n_fronts)
        wrong = []          # (kind, object, front, status, reason)
        if not args.no_wrong:
            for o in objs:
                for f in o.fronts:
                    kinds = ("axis30",) if f.kind == "drawer" else WRONG_KINDS
                    for kind in kinds:
                        try:
                            est = wrong_estimate(o.urdf, f.joint, kind,
                                                 root / "wrong" / f"{o.spec.name}_{f.joint}_{kind}.urdf")
                        except Exception as exc:      # the benchmark reports it and goes on
                            wrong.append((kind, o.spec.name, f, f"not built:{type(exc).__name__}", str(exc)))
                            continue
                        status, reason, dt = _certify_one(est, _task_for(f, kind), o.urdf)
                        wrong.append((kind, o.spec.name, f, status, reason))
                        print(f"  wrong {kind:16s} {o.spec.name:28s} {f.joint:24s} {status:12s} {dt:5.1f} s", flush=True)
    return _report(truth, wrong, len(objs), n_fronts, args.no_wrong)


def reconstructed_fronts(built, folder: Path, seed: int = 0) -> tuple[Path, Path, list]:
    """Scan ``built`` (a corpus object; realistic preset, scan ``seed``), rebuild it with ``recon`` and name its
    reference as recon names the joints.

    Returns (the reconstruction's scene.urdf, the object's own URDF with its fronts' joints renamed as recon
    names them, [(front, the front's task on the reconstruction)] in the object's front order), all under
    ``folder``. Raises whatever the scan or recon raises (a reconstruction that fails is the caller's result).
    """
    from recon import reconstruct, write_reconstruction
    from scenes.scan_io import write_scan
    from scenes.scanner import scan_scene
    from scenes.scanner.params import params_for_preset
    from thirdparty.scannable import reference_named_as_scan, scene_of
    scene, joint_part = scene_of(built)
    scan = scan_scene(scene, params_for_preset("realistic"), seed=seed)
    files = write_scan(scan, folder / "scan")
    rec = reconstruct(files["scan_ply"], files["labels_json"], seed=seed)
    est = Path(write_reconstruction(rec, folder / "recon")["scene.urdf"])
    ref, names = reference_named_as_scan(built, scene, joint_part, folder / "reference.urdf")
    return est, ref, [(f, f"{f.task.split(':')[0]}:{names[f.joint]}") for f in built.fronts]


def _end_to_end(objs, root: Path) -> None:
    """Scan (realistic), reconstruct and certify each front --against its own URDF; print the outcomes."""
    rows = []
    for o in objs:
        try:
            est, ref, tasks = reconstructed_fronts(o, root / o.spec.name)
        except Exception as exc:          # a reconstruction that fails is a result here
            for f in o.fronts:
                rows.append((o.spec.name, f.task, f"recon:{type(exc).__name__}", str(exc)))
            continue
        for f, task in tasks:
            status, reason, dt = _certify_one(est, task, ref)
            rows.append((o.spec.name, f.task, status, reason))
            print(f"  e2e   {o.spec.name:28s} {f.task:40s} {status:12s} {dt:5.1f} s", flush=True)
    c = Counter(r[2] for r in rows)
    print(f"\n## End to end (realistic scan -> recon -> certify --against the own URDF): "
          f"{c['certified']} of {len(rows)} certified; " + ", ".join(f"{k} {n}" for k, n in sorted(c.items())))
    for name, task, status, reason in rows:
        if status != "certified":
            print(f"- {name} {task} [{status}]: {reason[:300]}")


def _truth_met(truth, n_objects: int, n_fronts: int) -> bool:
    n_ok = sum(t[3] == "certified" for t in truth)
    return n_objects >= 20 and n_fronts >= 40 and n_ok / max(1, len(truth)) >= TRUTH_TARGET


def _task_for(front, kind: str) -> str:
    return f"open-drawer:{front.joint}" if kind == "door_as_drawer" else front.task


def _report_truth(truth, n_objects: int, n_fronts: int) -> bool:
    """Print the truth tables and target lines; True when both truth targets are met."""
    by_cat = defaultdict(Counter)
    by_kind = defaultdict(Counter)
    for cat, _, f, status, _, _ in truth:
        by_cat[cat][status == "certified"] += 1
        by_kind[f"{f.kind} handle={f.handle} sign={f.sign:+d}"][status == "certified"] += 1
    print("\n## Certified on their own URDF, by category")
    print(f"{'category':16s} {'certified':>9s} {'of':>4s}")
    for cat, c in sorted(by_cat.items()):
        print(f"{cat:16s} {c[True]:9d} {c[True] + c[False]:4d}")
    print("\n## By front kind, handle and sign")
    for k, c in sorted(by_kind.items()):
        print(f"{k:40s} {c[True]:3d} / {c[True] + c[False]:3d}")
    failed = [(o, f, s, r) for _, o, f, s, r, _ in truth if s != "certified"]
    print(f"\n## Not certified on their own URDF ({len(failed)})")
    for o, f, s, r in failed:
        print(f"- {o} {f.task} [{s}]: {r[:400]}")
    n_ok = sum(s == "certified" for *_, s, _r, _t in truth)
    share = n_ok / max(1, len(truth))
    print(f"\nseconds per truth task: median {sorted(t[5] for t in truth)[len(truth) // 2]:.1f}")
    n_reach = sum(s != "unreachable" for *_, s, _r, _t in truth)
    print(f"certified of the tasks the robot reaches (an unreachable task is a verdict of the robot, not of the "
          f"articulation): {n_ok}/{n_reach} ({n_ok / max(1, n_reach):.1%})")
    met = share >= TRUTH_TARGET
    big = n_objects >= 20 and n_fronts >= 40
    print(f"\n{'YES' if big else 'NO '} corpus >= 20 objects and >= 40 drawers/doors: {n_objects} objects, {n_fronts}")
    print(f"{'YES' if met else 'NO '} certified on their own URDF >= {TRUTH_TARGET:.0%}: {n_ok}/{len(truth)} "
          f"({share:.1%})", flush=True)
    return met and big


def _report(truth, wrong, n_objects: int, n_fronts: int, skipped_wrong: bool) -> int:
    met = _truth_met(truth, n_objects, n_fronts)          # its tables were printed before the wrong runs
    if skipped_wrong:
        return 0 if met else 1
    wk = defaultdict(Counter)
    for kind, _, _, status, _ in wrong:
        wk[kind][status] += 1
    print("\n## Wrong estimates executed --against their own URDF (outcomes)")
    for kind, c in sorted(wk.items()):
        print(f"{kind:18s} " + ", ".join(f"{s} {n}" for s, n in sorted(c.items())))
    bad = [(k, o, f.joint, r) for k, o, f, s, r in wrong if s == "certified"]
    for k, o, j, r in bad:
        print(f"- CERTIFIED WRONG {k} {o} {j}: {r[:300]}")
    none_ok = not bad
    print(f"{'YES' if none_ok else 'NO '} wrong estimates never certified: {len(bad)} of {len(wrong)} certified")
    return 0 if met and none_ok else 1


if __name__ == "__main__":
    sys.exit(main())
