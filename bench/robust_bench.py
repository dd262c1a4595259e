"""Benchmark of robust certification:
``python -m bench.robust_bench [--seeds 0 1] [--samples 30] [--modes default ...] [--speed-only] [--no-speed]``.

1. Speed: a generated kitchen is scanned (realistic preset) and reconstructed; its first drawer is certified
   with ``--robust N`` on the reconstruction (no truth). Prints the wall time and a YES/NO line for the
   target (N = 30 under 60 s on 2 cores).
2. Calibration: for every drawer / door of the reconstructed kitchens, the robust verdict (no truth) beside
   the verdict of the same estimate ``--against`` the truth; prints the confusion matrix and the issue's two
   targets: of the tasks certified robustly at most 5 % fail against the truth; of the tasks that fail
   against the truth at least 80 % are not certified robustly. Once per ``--modes``: the default spreads
   (guarded approach), ``open-loop`` (the same errors, the plan replayed without the guarded approach's
   correction), ``robot-errors-off`` (scan and physics spreads only).
"""

from __future__ import annotations

import argparse
import logging
import os
import tempfile
import time
from pathlib import Path

__all__ = ["main"]


def _reconstruction(seed: int, d: Path) -> Path:
    import recon
    import scenes

    scenes.make_scene("kitchen", seed=seed, preset="realistic", previews=False, out=d)
    rec = recon.reconstruct(d / "scan.ply", d / "labels.json", seed=seed)
    recon.write_reconstruction(rec, d / "rec")
    return d / "rec" / "scene.urdf"


def _tasks(scene: Path) -> list[str]:
    from planners.task import movable_joint_tasks
    from simcheck.scene_joints import read_scene_joints

    return [str(t) for t in movable_joint_tasks(read_scene_joints(scene), scene)[0]]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench.robust_bench", description=__doc__.split("\n")[0])
    p.add_argument("--seeds", type=int, nargs="*", default=[0, 1], help="kitchen seeds for the calibration")
    p.add_argument("--samples", type=int, default=30, help="sampled worlds per task (default 30)")
    p.add_argument("--speed-only", action="store_true", help="only the one-drawer timing")
    p.add_argument("--no-speed", action="store_true", help="skip the one-drawer timing")
    p.add_argument("--modes", nargs="+", choices=MODES, default=["default"], help="robot-error modes compared")
    args = p.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    from simcheck.certification import certify

    print(f"cores: {os.cpu_count()}, samples per task: {args.samples}")
    with tempfile.TemporaryDirectory(prefix="robust_bench_") as tmp:
        tmp = Path(tmp)
        if not args.no_speed:
            ok_speed = _speed(args, tmp)
            if args.speed_only:
                return 0 if ok_speed else 1
        rows = []     # (seed, task, {mode: robust status}, against-truth status)
        for seed in args.seeds:
            d = tmp / f"k{seed}"
            scene = _reconstruction(seed, d)
            for task in _tasks(scene):
                t0 = time.perf_counter()
                verdicts, counts = {}, {}
                for mode in args.modes:
                    with _robot_errors(mode):
                        rob = certify(scene, [task], robust=args.samples, seed=seed, images=False).tasks[0]
                    verdicts[mode], counts[mode] = rob.status, (rob.robust or {}).get("successes")
                tru = certify(scene, [task], against=d / "truth.urdf", seed=seed, images=False).tasks[0]
                rows.append((seed, task, verdicts, tru.status))
                print(f"  kitchen {seed} {task}: robust " + ", ".join(
                    f"[{m}] {verdicts[m].value} ({counts[m]}/{args.samples})" for m in args.modes)
                    + f"; against truth {tru.status.value}  [{time.perf_counter() - t0:.0f} s]", flush=True)
    for mode in args.modes:
        _confusion(mode, [(r[2][mode], r[3]) for r in rows])
    return 0


def _speed(args, tmp: Path) -> bool:
    """Time ``--robust N`` on the first drawer of the first kitchen's reconstruction; print it and the target.
    Returns whether the target holds (always True unless N = 30)."""
    from simcheck.certification import certify

    scene = _reconstruction(args.seeds[0] if args.seeds else 0, tmp / "speed")
    drawer = next(t for t in _tasks(scene) if t.startswith("open-drawer"))
    t0 = time.perf_counter()
    cert = certify(scene, [drawer], robust=args.samples, images=False)
    wall = time.perf_counter() - t0
    r = cert.tasks[0].robust or {}
    print(f"\nspeed: {drawer} on kitchen {args.seeds[0] if args.seeds else 0} (realistic reconstruction): "
          f"{cert.tasks[0].status.value}, {r.get('successes')} of {r.get('samples')} worlds, bound "
          f"{r.get('success_lower_bound', float('nan')):.3f}; {wall:.1f} s wall "
          f"(samples {r.get('seconds', float('nan')):.1f} s)")
    print(f"TARGET robust 30 on one drawer under 60 s on 2 cores: {'YES' if wall < 60.0 else 'NO'} ({wall:.1f} s)")
    return args.samples != 30 or wall < 60.0


MODES = ("default", "open-loop", "robot-errors-off")
"""Robust verdicts compared: the default spreads (the guarded approach corrects the base error as
re-perceived); the same errors with the plan replayed open loop; no robot errors at all (base pose,
perceived handle, tracking): the scan's and the physics' spreads only."""


def _robot_errors(mode: str):
    """A context in which robust certification samples the robot errors of ``mode``."""
    import contextlib
    import dataclasses

    import simcheck.robust
    from simcheck.robust_spreads import RobotErrors

    @contextlib.contextmanager
    def ctx():
        saved = simcheck.robust.DEFAULT_ROBOT_ERRORS
        if mode == "robot-errors-off":
            simcheck.robust.DEFAULT_ROBOT_ERRORS = RobotErrors(0.0, 0.0, 0.0, (1.0, 1.0), guarded_approach=False)
        elif mode == "open-loop":
            simcheck.robust.DEFAULT_ROBOT_ERRORS = dataclasses.replace(saved, guarded_approach=False)
        try:
            yield
        finally:
            simcheck.robust.DEFAULT_ROBOT_ERRORS = saved
    return ctx()


def _confusion(mode: str, pairs) -> None:
    """Print the confusion matrix of (robust status, against-truth status) pairs and the two targets."""
    from scenes.outcome import Outcome

    C = Outcome.CERTIFIED
    rc_tc = sum(1 for r, t in pairs if r is C and t is C)
    rc_tn = sum(1 for r, t in pairs if r is C and t is not C)
    rn_tc = sum(1 for r, t in pairs if r is not C and t is C)
    rn_tn = sum(1 for r, t in pairs if r is not C and t is not C)
    print(f"\nconfusion matrix, robust spreads '{mode}' (rows: robust verdict without truth; columns: against truth)")
    print("                        truth certified   truth not certified")
    print(f"  robust certified      {rc_tc:>15}   {rc_tn:>19}")
    print(f"  robust not certified  {rn_tc:>15}   {rn_tn:>19}")
    cert_r, fail_t = rc_tc + rc_tn, rc_tn + rn_tn
    print(f"TARGET [{mode}] of the tasks certified robustly at most 5% fail against the truth: "
          + (f"{'YES' if rc_tn <= 0.05 * cert_r else 'NO'} ({rc_tn} of {cert_r})" if cert_r else "n/a (none certified)"))
    print(f"TARGET [{mode}] of the tasks failing against the truth at least 80% not certified robustly: "
          + (f"{'YES' if rn_tn >= 0.8 * fail_t else 'NO'} ({rn_tn} of {fail_t})" if fail_t else "n/a (none failed)"))


if __name__ == "__main__":
    raise SystemExit(main())
