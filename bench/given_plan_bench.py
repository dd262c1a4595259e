"""Our own plans saved and replayed as given plans: ``python -m bench.given_plan_bench [--seeds 0] [--preset clean]``.

For every drawer and door of generated kitchens (truth URDF): ``certify --save-plan``, then ``certify-plan`` of
the saved file on the same scene. Prints per task both verdicts, the largest relative difference of a criterion
value (and the criterion), the given plan's extra criteria that failed, the plan file's size and both wall
times; then how many verdicts agree. Every criterion of a replay should agree within 1 % (or a small absolute
tolerance near zero): the executor gets the same position targets at every control step.
"""

from __future__ import annotations

import argparse
import logging
import tempfile
import time
from pathlib import Path

__all__ = ["main"]

#: absolute differences below these (per unit) count as agreement for values near zero
ABS_TOL = {"m": 1e-3, "N": 1.0, "m/s": 5e-3, "rad/s": 0.02, "rad|m": 1e-3, "": 0.01}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seeds", type=int, nargs="+", default=[0])
    args = p.parse_args(argv)
    logging.basicConfig(level=logging.WARNING)
    import scenes
    from planners.task import movable_joint_tasks
    from simcheck.certification import certify
    from simcheck.given_plan import certify_plan
    from simcheck.scene_joints import read_scene_joints

    agree = total = within = 0
    print(f"{'seed':>4} {'task':44s} {'planned':10s} {'replayed':10s} {'max rel diff':>12s} {'criterion':24s} "
          f"{'extra failed':20s} {'KB':>5s} {'t plan':>7s} {'t replay':>8s}")
    for seed in args.seeds:
        with tempfile.TemporaryDirectory() as tmp:
            d = Path(tmp)
            scenes.make_scene("kitchen", seed=seed, scan=False, previews=False, out=d)
            scene = d / "truth.urdf"
            for task in movable_joint_tasks(read_scene_joints(scene), scene)[0]:
                t0 = time.perf_counter()
                a = certify(scene, [task], out=d / "a", images=False, save_plan=True)[task.joint]
                t1 = time.perf_counter()
                path = d / "a" / "plans" / f"{task.joint}.plan.json"
                if not path.is_file():
                    print(f"{seed:>4} {str(task):44s} {a.status.value:10s} (no plan)")
                    continue
                b = certify_plan(scene, path, images=False)[task.joint]
                t2 = time.perf_counter()
                worst, name, ok, vals = 0.0, "", True, ""
                for c in a.criteria:
                    r = b.criterion(c.name)
                    diff = abs(r.value - c.value)
                    rel = diff / abs(c.value) if c.value else (0.0 if diff == 0 else float("inf"))
                    ok &= diff <= max(0.01 * abs(c.value), ABS_TOL.get(c.unit, 0.0))
                    if diff > ABS_TOL.get(c.unit, 0.0) and rel > worst:
                        worst, name, vals = rel, c.name, f"{c.value:.4g} -> {r.value:.4g} {c.unit}"
                extra = [c.name for c in b.criteria if not c.passed and c.name not in {x.name for x in a.criteria}]
                total += 1
                agree += a.status == b.status
                within += ok
                print(f"{seed:>4} {str(task):44s} {a.status.value:10s} {b.status.value:10s} {worst:12.4f} {name:24s} "
                      f"{','.join(extra) or '-':20s} {path.stat().st_size / 1e3:5.0f} {t1 - t0:7.1f} {t2 - t1:8.1f}"
                      + (f"  [{vals}]" if vals else "")
                      + "  timing: " + ", ".join(f"{n} {b.criterion(n).value:.3f}" for n in
                                                 ("waypoint_gap", "joint_speed", "joint_acceleration")))
                for c in b.criteria:
                    if not c.passed:
                        print(f"       {c.name}: {c.detail[:200]}")
    print(f"verdicts agree: {agree} of {total}; every criterion within 1 % or the absolute tolerance: {within} of {total}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
