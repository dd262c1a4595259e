"""Benchmark of planning + physics certification: ``python -m bench.simcheck_bench [--seeds N] ...``.

Generates kitchens (scenes; each has a cabinet with a door and drawers, a microwave and a refrigerator),
certifies every drawer and door on its own truth, then on the reconstruction of its scan (recon)
``--against`` the truth, then five kinds of WRONG estimates built from the truth (drawer axis 30 deg
off, door hinged on the wrong side, revolute as prismatic, limits 1.5x wider, a neighbour in the swing)
against the truth. Prints: planning time (median, p90), approach time, collision checks per second
(planner and the PyBullet re-check), simulation real-time factor, certification wall time per task,
the share certified, every failure reason tallied, and the targets of the issue.
"""

from __future__ import annotations

import argparse
import json
import logging
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path
from typing import NamedTuple

import numpy as np

from scenes.description import FRONT_CATEGORIES, read_truth_doc
from scenes.outcome import Outcome

__all__ = ["main"]

CATEGORIES = FRONT_CATEGORIES
WRONG_KINDS = ("axis30", "wrong_hinge_side", "revolute_as_prismatic", "wider_limits", "blocked_swing")


class TruthRow(NamedTuple):
    seed: int
    task: str          # "open-drawer:<joint>"
    category: str
    obj: str           # object name, e.g. "cabinet1"
    cert: object       # simcheck TaskCertificate


class ReconRow(NamedTuple):
    seed: int
    preset: str        # scan preset
    task: str
    category: str
    obj: str
    outcome: object    # simcheck TaskCertificate, or a text when no certificate could be made

    @property
    def ok(self) -> bool:
        return not isinstance(self.outcome, str) and self.outcome.ok

    @property
    def key(self) -> str:
        return self.outcome if isinstance(self.outcome, str) else _reason_key(self.outcome)


class WrongRow(NamedTuple):
    seed: int
    kind: str          # one of WRONG_KINDS
    task: str
    cert: object


def _tasks_from_truth(truth_json: Path) -> list[tuple[str, str, str, str]]:
    """(task string, category, joint type, object name) for every drawer/door of cabinets, microwaves and
    refrigerators."""
    doc = read_truth_doc(truth_json)
    out = []
    for o in doc["objects"]:
        if o["category"] not in CATEGORIES:
            continue
        for j in o["joints"]:
            if j["type"] in ("prismatic", "revolute"):
                kind = "open-drawer" if j["type"] == "prismatic" else "open-door"
                out.append((f"{kind}:{j['name']}", o["category"], j["type"], o["name"]))
    return out


def _reason_key(t) -> str:
    """A short tally key for a task's outcome: status + planner status or first failed criteria."""
    if t.status in (Outcome.NOT_PLANNED, Outcome.UNREACHABLE):
        return f"{t.status}: {t.plan_status}"
    if t.status is Outcome.CERTIFIED:
        return "certified"
    return "failed: " + ", ".join(t.failed_criteria[:3])


def _pct(values, q) -> float:
    return float(np.percentile(values, q)) if len(values) else float("nan")


def _table(title: str, header: list[str], rows: list[list]) -> None:
    print(f"\n{title}")
    cells = [header] + [[f"{c:.3g}" if isinstance(c, float) else str(c) for c in r] for r in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(header))]
    for k, r in enumerate(cells):
        print("  " + "  ".join(c.ljust(w) for c, w in zip(r, widths)))
        if k == 0:
            print("  " + "  ".join("-" * w for w in widths))


def _certify_each(simcheck_certify, scene: Path, tasks: list[str], against: Path | None, seed: int) -> list:
    """One certificate task per task string (tasks are independent: each is judged in freshly loaded worlds)."""
    cert = simcheck_certify(scene, tasks, against=against, seed=seed, images=False)
    return list(cert.tasks)


def _wrong_estimates(truth: Path, tasks: list[tuple[str, str, str, str]], tmp: Path) -> list[tuple[str, Path, str, Path]]:
    """(kind, estimate, task, reference) for the first drawer and the first door of the truth."""
    import simcheck.estimate_faults as wrong

    drawer = next((t.split(":", 1)[1] for t, _, jt, _ in tasks if jt == "prismatic"), None)
    door = next((t.split(":", 1)[1] for t, c, jt, _ in tasks if jt == "revolute" and c == "refrigerator"),
                next((t.split(":", 1)[1] for t, _, jt, _ in tasks if jt == "revolute"), None))
    out = []
    if drawer:
        out.append(("axis30", wrong.rotate_axis(truth, drawer, 30.0, tmp / "axis30.urdf"), f"open-drawer:{drawer}", truth))
        out.append(("wider_limits", wrong.widen_limits(truth, drawer, 1.5, tmp / "wide.urdf"), f"open-drawer:{drawer}", truth))
    if door:
        out.append(("wrong_hinge_side", wrong.flip_hinge(truth, door, tmp / "flip.urdf"), f"open-door:{door}", truth))
        out.append(("revolute_as_prismatic", wrong.revolute_as_prismatic(truth, door, tmp / "pris.urdf"),
                    f"open-drawer:{door}", truth))
        out.append(("blocked_swing", truth, f"open-door:{door}", wrong.blocker_in_swing(truth, door, tmp / "blocked.urdf")))
    return out


def _reconstruction_rows(scene: str, seed: int, preset: str, d: Path, tasks, certify) -> list[tuple]:
    """Scan scene ``seed`` with ``preset`` into ``d``, reconstruct it, and certify every truth drawer/door
    on the reconstruction ``--against`` the truth: one (seed, preset, task, category, object, certificate
    task or failure text) per truth task (a missing joint or a failed reconstruction is a result, not a crash)."""
    import recon
    import scenes
    from simcheck.scene_joints import read_scene_joints

    scenes.make_scene(scene, seed=seed, preset=preset, previews=False, out=d)
    try:
        rec = recon.reconstruct(d / "scan.ply", d / "labels.json", seed=seed)
        recon.write_reconstruction(rec, d / "rec")
        est = read_scene_joints(d / "rec" / "scene.urdf")
    except Exception as exc:  # a reconstruction failure is a benchmark result, not a crash
        return [ReconRow(seed, preset, task, cat, obj, f"reconstruction failed: {type(exc).__name__}: {exc}")
                for task, cat, _, obj in tasks]
    rows = []
    for task, cat, _, obj in tasks:
        joint = task.split(":", 1)[1]
        ej = est.get(joint)
        if ej is None or ej.type not in ("prismatic", "revolute"):
            rows.append(ReconRow(seed, preset, task, cat, obj, "joint missing or fixed in the reconstruction"))
            continue
        kind = "open-drawer" if ej.type == "prismatic" else "open-door"
        try:
            t = certify(d / "rec" / "scene.urdf", [f"{kind}:{joint}"], against=d / "truth.urdf", seed=seed,
                        images=False).tasks[0]
            rows.append(ReconRow(seed, preset, task, cat, obj, t))
        except Exception as exc:
            rows.append(ReconRow(seed, preset, task, cat, obj, f"input error: {type(exc).__name__}: {exc}"))
    return rows


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.simcheck_bench", description=__doc__.split("\n")[0])
    p.add_argument("--scene", default="kitchen", help="built-in scene to generate (default kitchen)")
    p.add_argument("--seeds", type=int, default=10,
                   help="scenes on which every drawer/door is certified on truth (10 kitchens = 30 cabinets, "
                        "microwaves and refrigerators)")
    p.add_argument("--recon-seeds", type=int, default=10, help="of those, how many are scanned + reconstructed")
    p.add_argument("--recon-presets", default="clean,realistic",
                   help="scan presets reconstructed for each of those seeds, comma-separated")
    p.add_argument("--wrong-seeds", type=int, default=2, help="of those, on how many wrong estimates are built")
    p.add_argument("--out", default=None, help="keep the generated files here (default: a temp folder)")
    args = p.parse_args(argv)
    logging.basicConfig(level=logging.WARNING)
    import scenes
    from simcheck.certification import certify

    presets = [x for x in args.recon_presets.split(",") if x]
    tmp_ctx = tempfile.TemporaryDirectory(prefix="simcheck_bench_") if args.out is None else None
    root = Path(args.out or tmp_ctx.name)
    truth_rows, recon_rows, wrong_rows = [], [], []
    t_start = time.perf_counter()
    for seed in range(args.seeds):
        d = root / f"{args.scene}{seed}"
        scenes.make_scene(args.scene, seed=seed, scan=False, previews=False, out=d)
        tasks = _tasks_from_truth(d / "truth.json")
        for (task, cat, _, obj), t in zip(tasks, _certify_each(certify, d / "truth.urdf", [x[0] for x in tasks], None, seed)):
            truth_rows.append(TruthRow(seed, task, cat, obj, t))
        print(f"[{time.perf_counter() - t_start:6.0f} s] {args.scene} seed {seed}: truth "
              f"{sum(r.cert.ok for r in truth_rows if r.seed == seed)}/{len(tasks)} certified", flush=True)
        for preset in presets if seed < args.recon_seeds else ():
            rows = _reconstruction_rows(args.scene, seed, preset, d / preset, tasks, certify)
            recon_rows += rows
            print(f"[{time.perf_counter() - t_start:6.0f} s] {args.scene} seed {seed}: {preset} reconstruction "
                  f"{sum(r.ok for r in rows)}/{len(tasks)} certified "
                  f"against truth", flush=True)
        if seed < args.wrong_seeds:
            (d / "wrong").mkdir(exist_ok=True)
            for kind, est_urdf, task, ref in _wrong_estimates(d / "truth.urdf", tasks, d / "wrong"):
                t = certify(est_urdf, [task], against=ref, seed=seed, images=False).tasks[0]
                wrong_rows.append(WrongRow(seed, kind, task, t))
            print(f"[{time.perf_counter() - t_start:6.0f} s] {args.scene} seed {seed}: wrong estimates "
                  f"{sum(r.cert.ok for r in wrong_rows if r.seed == seed)} certified (must be 0)", flush=True)

    _report(truth_rows, recon_rows, wrong_rows)
    ok = _targets(truth_rows, wrong_rows)
    if tmp_ctx is not None:
        tmp_ctx.cleanup()
    return 0 if ok else 1


def _report(truth_rows, recon_rows, wrong_rows) -> None:
    tasks = [r.cert for r in truth_rows]
    planned = [t for t in tasks if t.plan_status == "OK"]
    executed = [t for t in planned if "execute" in t.timings]
    plan_s = [t.timings["plan"] for t in tasks]
    approach_s = [t.timings["planner_approach"] for t in planned if "planner_approach" in t.timings]
    checks = [t.timings.get("plan_collision_checks", 0) / t.timings["plan"] for t in planned if t.timings["plan"] > 0]
    recheck = [t.timings["recheck_states"] / t.timings["recheck"] for t in planned if t.timings.get("recheck", 0) > 0]
    rtf = [t.timings["simulated"] / t.timings["execute"] for t in executed]
    rtf_cpu = [t.timings["simulated"] / t.timings["execute_cpu"] for t in executed if t.timings.get("execute_cpu", 0) > 0]
    wall = [t.timings["total"] for t in tasks]
    wall_drawer = [t.timings["total"] for t in tasks if t.kind == "open-drawer" and t.plan_status == "OK"]
    _table("Speed (truth tasks)", ["measure", "n", "median", "p90", "max"], [
        ["planning time, s", len(plan_s), _pct(plan_s, 50), _pct(plan_s, 90), max(plan_s, default=float("nan"))],
        ["approach plan time, s", len(approach_s), _pct(approach_s, 50), _pct(approach_s, 90), max(approach_s, default=float("nan"))],
        ["planner collision checks / s", len(checks), _pct(checks, 50), _pct(checks, 90), max(checks, default=float("nan"))],
        ["PyBullet re-check states / s", len(recheck), _pct(recheck, 50), _pct(recheck, 90), max(recheck, default=float("nan"))],
        ["simulation real-time factor (wall)", len(rtf), _pct(rtf, 50), _pct(rtf, 10), min(rtf, default=float("nan"))],
        ["simulation real-time factor (CPU)", len(rtf_cpu), _pct(rtf_cpu, 50), _pct(rtf_cpu, 10),
         min(rtf_cpu, default=float("nan"))],
        ["certification wall / task, s", len(wall), _pct(wall, 50), _pct(wall, 90), max(wall, default=float("nan"))],
        ["open-drawer certification wall, s", len(wall_drawer), _pct(wall_drawer, 50), _pct(wall_drawer, 90),
         max(wall_drawer, default=float("nan"))],
    ])
    print("  (real-time factor: p90 column shows the 10th percentile, max column the minimum)")
    _speed_table(executed)
    rows = []
    for cat in CATEGORIES:
        for kind in ("open-drawer", "open-door"):
            sel = [r for r in truth_rows if r.category == cat and r.cert.kind == kind]
            if sel:
                n_ok = sum(r.cert.ok for r in sel)
                rows.append([cat, kind, _objects(sel), len(sel), n_ok, n_ok / len(sel)])
    rows.append(["all", "", _objects(truth_rows), len(tasks), sum(t.ok for t in tasks),
                 sum(t.ok for t in tasks) / max(len(tasks), 1)])
    _table("Certified on their own truth", ["category", "task", "objects", "n", "certified", "share"], rows)
    _tally("Outcomes on truth (every failure reason)", [_reason_key(t) for t in tasks])
    for r in truth_rows:
        if not r.cert.ok:
            print(f"    seed {r.seed} {r.task}: {r.cert.reason[:220]}")
    if recon_rows:
        rows = []
        presets = list(dict.fromkeys(r.preset for r in recon_rows))
        for preset in presets:
            for cat in CATEGORIES + ("all",):
                sel = [r for r in recon_rows if r.preset == preset and cat in ("all", r.category)]
                n_ok = sum(r.ok for r in sel)
                rows.append([preset, cat, _objects(sel), len(sel), n_ok, n_ok / max(len(sel), 1)])
        _table("Reconstructions --against truth (scan -> recon -> plan on the estimate, execute on the truth)",
               ["scan", "category", "objects", "drawers+doors", "certified", "share"], rows)
        for preset in presets:
            sel = [r for r in recon_rows if r.preset == preset]
            _tally(f"Outcomes on {preset} reconstructions (every failure reason)", [r.key for r in sel])
            for r in sel:
                if not isinstance(r.outcome, str) and not r.ok:
                    print(f"    seed {r.seed} {r.task}: {r.outcome.reason[:220]}")
    if wrong_rows:
        rows = []
        for kind in WRONG_KINDS:
            sel = [r.cert for r in wrong_rows if r.kind == kind]
            rows.append([kind, len(sel), sum(t.ok for t in sel), sum(t.status is Outcome.FAILED for t in sel),
                         sum(t.status in (Outcome.NOT_PLANNED, Outcome.UNREACHABLE) for t in sel),
                         sum(_points_at_fault(kind, t.reason) for t in sel)])
        _table("Wrong estimates --against truth", ["kind", "n", "CERTIFIED (false)", "failed", "not planned",
                                                   "reason names the fault"], rows)


def _objects(rows) -> int:
    """Distinct objects (seed, object name) among rows."""
    return len({(r.seed, r.obj) for r in rows})


def _speed_table(executed) -> None:
    """Physics execution speed: simulated seconds per second of wall and of CPU (``time.process_time``,
    which other processes on a shared machine do not inflate as much as wall time), per task kind and in
    total, with the physics steps per CPU second."""
    from simcheck.config import DEFAULT_PHYSICS

    rows = []
    for kind in ("open-drawer", "open-door", "all"):
        sel = [t for t in executed if kind == "all" or t.kind == kind]
        if not sel:
            continue
        sim = sum(t.timings["simulated"] for t in sel)
        wall = sum(t.timings["execute"] for t in sel)
        cpu = sum(t.timings.get("execute_cpu", float("nan")) for t in sel)
        each_cpu = [t.timings["simulated"] / t.timings["execute_cpu"] for t in sel if t.timings.get("execute_cpu", 0) > 0]
        rows.append([kind, len(sel), sim, wall, cpu, sim / wall, sim / cpu, min(each_cpu, default=float("nan")),
                     sim / DEFAULT_PHYSICS.time_step / cpu])
    _table("Simulation real-time factor (simulated s / execution s; target >= 20x)",
           ["tasks", "n", "simulated s", "wall s", "CPU s", "RTF wall", "RTF CPU", "min RTF CPU", "steps / CPU s"], rows)


_FAULT_TEXT = {"axis30": "deg off the reference axis", "wrong_hinge_side": "hinged on the wrong side",
               "revolute_as_prismatic": "prismatic in the estimate but revolute", "wider_limits": "exceeds the reference",
               "blocked_swing": "blocker99_box99"}


def _points_at_fault(kind: str, reason: str) -> bool:
    return _FAULT_TEXT[kind] in reason


def _tally(title: str, keys: list[str]) -> None:
    rows = [[k, n] for k, n in Counter(keys).most_common()]
    _table(title, ["outcome", "n"], rows)


def _targets(truth_rows, wrong_rows) -> bool:
    tasks = [r.cert for r in truth_rows]
    share = sum(t.ok for t in tasks) / max(len(tasks), 1)
    drawers = [t.timings["total"] for t in tasks if t.kind == "open-drawer" and t.plan_status == "OK"]
    rtf = [t.timings["simulated"] / t.timings["execute"] for t in tasks if "execute" in t.timings]
    rtf_cpu = [t.timings["simulated"] / t.timings["execute_cpu"] for t in tasks if t.timings.get("execute_cpu", 0) > 0]
    approach = [t.timings["planner_approach"] for t in tasks if "planner_approach" in t.timings]
    false_certs = sum(r.cert.ok for r in wrong_rows)
    checks = [
        (">= 95% certified on truth", share >= 0.95, f"{share:.1%} of {len(tasks)}"),
        ("approach plan median <= 1 s", bool(approach) and _pct(approach, 50) <= 1.0, f"{_pct(approach, 50):.2f} s"),
        ("open-drawer certification <= 15 s wall (max)", bool(drawers) and max(drawers) <= 15.0,
         f"max {max(drawers, default=float('nan')):.1f} s"),
        ("simulation >= 20x real time (min, wall)", bool(rtf) and min(rtf) >= 20.0,
         f"min {min(rtf, default=float('nan')):.1f}x, median {_pct(rtf, 50):.1f}x"),
        ("simulation >= 20x real time (min, CPU time)", bool(rtf_cpu) and min(rtf_cpu) >= 20.0,
         f"min {min(rtf_cpu, default=float('nan')):.1f}x, median {_pct(rtf_cpu, 50):.1f}x"),
        ("zero false certificates (wrong estimates)", false_certs == 0, f"{false_certs} of {len(wrong_rows)}"),
    ]
    _table("Targets", ["target", "met", "measured"], [[n, "yes" if ok else "NO", m] for n, ok, m in checks])
    return all(ok for _, ok, _ in checks)


if __name__ == "__main__":
    sys.exit(main())
