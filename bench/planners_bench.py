"""Planning benchmark: success over the drawers and doors of generated scenes, planning times, checks/s.

    python -m bench.planners_bench [--scenes kitchen:0-7,office:0-1] [--seed 0] [--out DIR] [--quick]
                                   [--open-method auto|ik_tracking|constrained] [--recon]

``--recon``: plan on recon's reconstruction (scan -> scene.urdf) of each scene instead of its truth.

Prints three tables: (1) outcome per status and the tally of failure reasons, per kind (drawer/door);
(2) planning times (median, p90) of the stand search, the OMPL approach, the opening and the whole plan;
(3) collision checks per second, on random configurations beside a cabinet and over the plans.
Targets (issue): approach median <= 1 s; planning success on >= 30 generated drawers/doors above the 95%
certification target.
"""

from __future__ import annotations

import argparse
import re
import sys
import tempfile
import time
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np

from scenes.description import read_truth_doc


def _scene_list(spec: str) -> list[tuple[str, int]]:
    out = []
    for item in spec.split(","):
        name, _, seeds = item.partition(":")
        lo, _, hi = seeds.partition("-")
        out += [(name, s) for s in range(int(lo or 0), int(hi or lo or 0) + 1)]
    return out


def _tasks(truth_json: Path, scene_urdf: Path) -> list[tuple[str, str, str]]:
    """(kind, joint, category) of every movable joint of ``scene_urdf`` (kind from its type there; category
    from the truth)."""
    from planners.scene_urdf import read_scene_urdf

    truth = read_truth_doc(truth_json)
    category = {o["name"]: o["category"] for o in truth["objects"]}
    tasks = []
    for j in read_scene_urdf(scene_urdf).joints.values():
        if j.type in ("prismatic", "revolute"):
            cat = next((c for name, c in category.items() if j.name.startswith(name + "_")), "?")
            tasks.append(("drawer" if j.type == "prismatic" else "door", j.name, cat))
    return tasks


def _reason_key(reason: str) -> str:
    """A failure reason without its numbers and names, for tallying."""
    r = re.sub(r"'[^']*'", "'*'", reason)
    r = re.sub(r"scene::\w+", "scene::*", r)
    r = re.sub(r"[-+]?\d+(\.\d+)?", "#", r)
    return r.split(" (")[0][:110]


def _pct(a: list[float], q: float) -> float:
    return float(np.percentile(a, q)) if a else float("nan")


def _checks_per_second(robot, scene_urdf: Path, joint: str, n: int = 3000) -> float:
    from planners import OpenTask, PlannerConfig
    from planners.handle import find_handle
    from planners.pin_world import PlanningWorld
    from planners.plan import robot_kinematics
    from planners.scene_urdf import read_scene_urdf

    kin = robot_kinematics(robot)
    scene = read_scene_urdf(scene_urdf)
    task = OpenTask("drawer" if scene.joints[joint].type == "prismatic" else "door", joint)
    handle = find_handle(scene, task, {}, PlannerConfig())
    world = PlanningWorld(kin, scene, joint, set(handle.handle_geoms), {})
    p = scene.T_world_link(handle.moving_link)[:2, 3]
    rng = np.random.default_rng(0)
    qs = rng.uniform(kin.lower, kin.upper, size=(n, robot.dof))
    qs[:, :2] = p + rng.uniform(-1.2, 1.2, size=(n, 2))
    qs[:, 2] = rng.uniform(-np.pi, np.pi, n)
    t = time.perf_counter()
    for q in qs:
        world.in_collision(q, 0.0)
    return n / (time.perf_counter() - t)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.planners_bench", description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", default="kitchen:0-7", help="NAME:SEED-SEED,... (default kitchen:0-7)")
    ap.add_argument("--seed", type=int, default=0, help="planning seed")
    ap.add_argument("--out", type=Path, default=None, help="keep generated scenes here")
    ap.add_argument("--quick", action="store_true", help="kitchen:0-1 only")
    ap.add_argument("--recon", action="store_true", help="plan on recon's reconstruction of each scene")
    ap.add_argument("--open-method", default=None, choices=("auto", "ik_tracking", "constrained"),
                    help="PlannerConfig.open_method (default: the config's default)")
    args = ap.parse_args(argv)

    import scenes
    from dataclasses import replace

    from planners import OpenTask, PlannerConfig, PlannerInputError, default_robot, plan_open_task

    robot = default_robot()
    cfg = PlannerConfig() if args.open_method is None else replace(PlannerConfig(), open_method=args.open_method)
    spec = "kitchen:0-1" if args.quick else args.scenes
    tmp = tempfile.TemporaryDirectory() if args.out is None else None
    root = Path(tmp.name) if tmp else args.out
    rows = []
    first_scene = None
    try:
        for name, sseed in _scene_list(spec):
            out = root / f"{name}_{sseed}"
            if not (out / "truth.urdf").exists() or (args.recon and not (out / "scan.ply").exists()):
                scenes.make_scene(name, seed=sseed, out=out, scan=args.recon, previews=False)
            urdf = out / "truth.urdf"
            if args.recon:
                urdf = out / "recon" / "scene.urdf"
                if not urdf.exists():
                    from recon import reconstruct, write_reconstruction
                    write_reconstruction(reconstruct(out / "scan.ply", out / "labels.json", seed=sseed), out / "recon")
            for kind, joint, category in _tasks(out / "truth.json", urdf):
                first_scene = first_scene or (urdf, joint)
                t = time.perf_counter()
                try:
                    plan = plan_open_task(robot, urdf, OpenTask(kind, joint), seed=args.seed,
                                          config=cfg)
                    status, reason = plan.status.name, plan.reason
                    timings, checks = dict(plan.timings), plan.collision_checks
                except PlannerInputError as e:
                    status, reason, timings, checks = "INPUT_ERROR", str(e), {}, 0
                wall = time.perf_counter() - t
                method = plan.method if status != "INPUT_ERROR" else ""
                rows.append(dict(scene=f"{name}:{sseed}", kind=kind, category=category, joint=joint,
                                 status=status, reason=reason, timings=timings, checks=checks, wall=wall,
                                 method=method))
                print(f"  {name}:{sseed} {category:<12} {joint:<32} {status:<16} {method:<12} {wall:5.2f} s",
                      flush=True)
        if not rows:
            print("no drawers or doors in the chosen scenes")
            return 1

        which = "reconstructions" if args.recon else "truth scenes"
        print(f"\nTable 1. Planning outcome on {len(rows)} drawers/doors of {spec} ({which}, seed {args.seed}, "
              f"open_method {cfg.open_method})")
        print(f"{'kind':<8}{'tasks':>7}{'OK':>7}{'share':>9}")
        for kind in ("drawer", "door", "all"):
            sel = [r for r in rows if kind == "all" or r["kind"] == kind]
            ok = sum(r["status"] == "OK" for r in sel)
            print(f"{kind:<8}{len(sel):>7}{ok:>7}{(100.0 * ok / max(len(sel), 1)):>8.1f}%")
        used = Counter(r["method"] for r in rows if r["status"] == "OK")
        print("opening planned by: " + ", ".join(f"{k} {v}" for k, v in sorted(used.items())))
        fails = Counter((r["status"], _reason_key(r["reason"])) for r in rows if r["status"] != "OK")
        if fails:
            print("\nFailure reasons (status: reason pattern -> count)")
            for (st, why), c in fails.most_common():
                print(f"  {c:>3}  {st}: {why}")

        print("\nTable 2. Planning time, seconds (median / p90 / max) over all tasks")
        stages = defaultdict(list)
        for r in rows:
            for k, v in r["timings"].items():
                stages[k].append(v)
            stages["wall"].append(r["wall"])
        print(f"{'stage':<10}{'n':>5}{'median':>9}{'p90':>9}{'max':>9}")
        for k in ("stand", "approach", "grasp", "open", "retreat", "total", "wall"):
            v = stages.get(k, [])
            if v:
                print(f"{k:<10}{len(v):>5}{_pct(v, 50):>9.3f}{_pct(v, 90):>9.3f}{max(v):>9.3f}")
        med = _pct(stages.get("approach", []), 50)
        print(f"approach median {med:.3f} s (target <= 1 s): {'met' if med <= 1.0 else 'NOT met'}")

        print("\nTable 3. Collision checking (pinocchio + coal broad phase, one thread)")
        cps = _checks_per_second(robot, *first_scene)
        tot_checks = sum(r["checks"] for r in rows)
        tot_time = sum(r["timings"].get("total", 0.0) for r in rows)
        print(f"  random configurations beside {first_scene[1]}: {cps:,.0f} checks/s")
        print(f"  during planning: {tot_checks:,} checks in {tot_time:.1f} s of planning "
              f"({tot_checks / max(tot_time, 1e-9):,.0f} checks per planning second, IK included)")
        return 0
    finally:
        if tmp:
            tmp.cleanup()


if __name__ == "__main__":
    sys.exit(main())
