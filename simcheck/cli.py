"""``simcheck``: certify opening (and closing) tasks in physics.

    simcheck certify SCENE.urdf (--task open-drawer:JOINT --task close-door:JOINT ... | --all-movable)
                     [--amount A ...] [--from OPENING ...] [--against REFERENCE.urdf] [--out DIR] [--seed S] [--gui] [--video]
                     [--robot SPEC] [--robust N [--min-success P] [--replay-sample I] [--spreads FILE]
                                 [--robust-engine auto|processes|ray] [--address ADDR]] [--json]
                     [--save-plan]
    simcheck certify-plan SCENE.urdf PLAN.json [--against REFERENCE.urdf] [--out DIR] [--robust N ...] [--json]
    simcheck spreads                  (prints the default spreads of --robust: a --spreads FILE to start from)
    simcheck run SCENARIO.yaml [--out DIR] [--seed S] [--gui] [--video] [--json]
    simcheck batch MANIFEST --out DIR [--workers N] [--address ADDR] ...   (simcheck.batching.command)

Exit codes (:func:`scenes.outcome.exit_code` of the task outcomes): 0 every task certified; 2 the input
could not be used (the message says why: missing joint, fixed joint named as a drawer, broken URDF...);
3 an internal error (one line naming what failed; ``-v`` logs the traceback); 130 interrupted (Ctrl-C);
otherwise 1 (some task failed, was not planned or its object is unreachable). ``--out`` is written as a whole
(:mod:`scenes.output_folder`): a rerun with the same inputs replaces it, anything else in it is refused
unless ``--overwrite``.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import logging
import sys
from pathlib import Path

from scenes.command_line import add_output_arguments, root_parser, setup_logging

__all__ = ["main"]

log = logging.getLogger("simcheck")


def _parser() -> argparse.ArgumentParser:
    p, verbosity = root_parser("simcheck", "Certify drawer and door opening in physics.")
    sub = p.add_subparsers(dest="command", required=True)

    def common(sp):
        add_output_arguments(sp, "certificate.json, rollouts/, images/", default="simcheck-out")
        sp.add_argument("--seed", type=int, default=None, help="planning seed (default 0)")
        sp.add_argument("--gui", action="store_true", help="PyBullet GUI window (needs a display)")
        sp.add_argument("--video", action="store_true", help="also write an animated GIF per task")
        sp.add_argument("--no-images", action="store_true", help="skip the key-frame PNGs")
        sp.add_argument("--json", action="store_true",
                        help="print the certificate's summary as JSON on stdout (logging stays on stderr)")

    def robust_options(sp):
        rb = sp.add_argument_group("robust certification (worlds sampled from the scan's uncertainty)")
        rb.add_argument("--robust", type=int, default=None, metavar="N", help="execute the plan in N sampled worlds")
        rb.add_argument("--min-success", type=float, default=0.9, metavar="P",
                        help="certify when, with 95%% confidence, at least P of such worlds succeed (default 0.9)")
        rb.add_argument("--replay-sample", type=int, default=None, metavar="I", help="execute sample I alone")
        rb.add_argument("--spreads", default=None, metavar="FILE",
                        help="physics / robot / default joint spreads (YAML or JSON; `simcheck spreads` prints the "
                             "defaults, every key optional)")
        rb.add_argument("--robust-engine", choices=("auto", "processes", "ray"), default="auto",
                        help="where the sampled worlds run: worker processes, Ray, or auto (Ray when connected or "
                             "--address / RAY_ADDRESS is given, else processes)")
        rb.add_argument("--address", default=None, metavar="ADDR",
                        help="with --robust-engine ray/auto: a Ray cluster to run the samples on (auto, ray://host:10001)")

    c = sub.add_parser("certify", help="certify tasks on a scene URDF", parents=[verbosity])
    c.add_argument("scene", help="scene URDF to plan on (an estimate or a truth)")
    c.add_argument("--task", action="append", default=[], metavar="KIND:JOINT",
                   help="open-drawer:JOINT, open-door:JOINT, close-drawer:JOINT or close-door:JOINT (repeatable)")
    c.add_argument("--all-movable", action="store_true",
                   help="certify every drawer (prismatic joint) and door (revolute joint) of the scene; "
                        "joints without an opening range are listed as untested")
    c.add_argument("--amount", action="append", type=float, default=[],
                   help="opening, m or rad: one for all tasks or one per task (default: 90%% of the range, doors <= 85 deg)")
    c.add_argument("--from", dest="froms", action="append", type=float, default=[], metavar="OPENING",
                   help="close tasks: how far open the part starts, m or rad (one for all or one per task; "
                        "default: what an opening would request)")
    c.add_argument("--against", default=None, help="reference URDF to execute on (joints matched by name)")
    c.add_argument("--robot", default="default",
                   help="'default', 'compliant' (the default robot under a softer joint impedance) or a robot spec "
                        "YAML/JSON file")
    c.add_argument("--save-plan", action="store_true",
                   help="also write each task's plan as DIR/plans/<joint>.plan.json (partscene.plan/1, replayable "
                        "with certify-plan)")
    robust_options(c)
    common(c)
    g = sub.add_parser("certify-plan", help="certify a given plan file (partscene.plan/1) on a scene URDF",
                       parents=[verbosity])
    g.add_argument("scene", help="scene URDF to execute the plan on")
    g.add_argument("plan", help="plan file (partscene.plan/1 JSON; docs/plan_format.md)")
    g.add_argument("--against", default=None, help="reference URDF to execute on instead (joints matched by name)")
    robust_options(g)
    common(g)
    sub.add_parser("spreads", help="print the default spreads of --robust (a --spreads FILE to start from)",
                   parents=[verbosity])
    r = sub.add_parser("run", help="run a scenario YAML (tasks in sequence, world state carried over)",
                       parents=[verbosity])
    r.add_argument("scenario")
    common(r)
    from simcheck.batching.command import add_batch_parser
    add_batch_parser(sub, parents=[verbosity])
    return p


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    # default: WARNING for the libraries, one progress line per task from simcheck; -v: INFO; -vv: DEBUG
    level = setup_logging(args)
    if not args.quiet:
        logging.getLogger("simcheck.certification").setLevel(min(level, logging.INFO))
    if args.command == "batch":
        from simcheck.batching.command import run_batch
        return run_batch(args)
    if args.command == "spreads":
        from simcheck.spreads_file import spreads_yaml
        print(spreads_yaml(), end="")
        return 0
    from scenes.outcome import Outcome, exit_code, internal_error, interrupted
    from scenes.description import InputError

    what = (f"running scenario {args.scenario}" if args.command == "run" else
            f"certifying {args.plan} on {args.scene}" if args.command == "certify-plan" else f"certifying {args.scene}")
    try:
        from planners.task import ALL_MOVABLE
        from scenes.output_folder import output_folder
        from simcheck.certification import certify
        from simcheck.errors import SimcheckInputError
        from simcheck.robot_spec_file import is_named_robot, load_robot_spec
        from simcheck.run import run_scenario
        from simcheck.scenario import load_scenario

        outputs = {"images": not args.no_images, "video": args.video}
        robust_run = ({"spreads": args.spreads, "robust_engine": args.robust_engine, "address": args.address}
                      if args.command != "run" else {})
        if args.command == "certify":
            if args.all_movable and args.task:
                raise SimcheckInputError("give --task or --all-movable, not both")
            robot = load_robot_spec(args.robot)
            spec_file = None if is_named_robot(args.robot) else args.robot
            inputs = {"scene": args.scene, "against": args.against, "robot_spec": spec_file, "spreads": args.spreads}
            settings = {"tasks": args.task, "all_movable": args.all_movable, "amounts": args.amount, "froms": args.froms,
                        "seed": args.seed or 0, "robust": args.robust, "min_success": args.min_success,
                        "replay_sample": args.replay_sample, "save_plan": args.save_plan, **outputs}
            with output_folder(args.out, "simcheck certify", inputs=inputs, settings=settings,
                               overwrite=args.overwrite, verdict="certificate.json") as staging:
                cert = certify(args.scene, ALL_MOVABLE if args.all_movable else args.task, against=args.against,
                               amounts=args.amount or None, froms=args.froms or None, seed=args.seed or 0, out=staging, robot=robot,
                               images=not args.no_images, video=args.video, gui=args.gui, robust=args.robust,
                               min_success=args.min_success, replay_sample=args.replay_sample,
                               save_plan=(args.robot if is_named_robot(args.robot) else str(Path(args.robot).resolve()))
                               if args.save_plan else False,
                               files={k: v for k, v in (("robot_spec", spec_file), ("spreads", args.spreads)) if v}
                               or None, **robust_run)
        elif args.command == "certify-plan":
            from simcheck.given_plan import certify_plan
            inputs = {"scene": args.scene, "plan": args.plan, "against": args.against, "spreads": args.spreads}
            settings = {"seed": args.seed or 0, "robust": args.robust, "min_success": args.min_success,
                        "replay_sample": args.replay_sample, **outputs}
            with output_folder(args.out, "simcheck certify-plan", inputs=inputs, settings=settings,
                               overwrite=args.overwrite, verdict="certificate.json") as staging:
                cert = certify_plan(args.scene, args.plan, against=args.against, out=staging, seed=args.seed or 0,
                                    images=not args.no_images, video=args.video, gui=args.gui, robust=args.robust,
                                    min_success=args.min_success, replay_sample=args.replay_sample,
                                    files={"spreads": args.spreads} if args.spreads else None, **robust_run)
        else:
            sc = load_scenario(args.scenario)
            inputs = {"scenario": args.scenario, "scene": sc.scene, "against": sc.against,
                      "robot_spec": None if is_named_robot(sc.robot) else sc.robot,
                      **{f"plan{i}": t for i, t in enumerate(sc.tasks) if isinstance(t, Path)}}
            with output_folder(args.out, "simcheck run", inputs=inputs, settings={"seed": args.seed, **outputs},
                               overwrite=args.overwrite, verdict="certificate.json") as staging:
                cert = run_scenario(args.scenario, out=staging, seed=args.seed, images=not args.no_images,
                                    video=args.video, gui=args.gui)
        cert = dataclasses.replace(cert, path=Path(args.out) / "certificate.json")
    except InputError as exc:
        print(f"simcheck: error: {exc}", file=sys.stderr)
        return exit_code([Outcome.UNUSABLE])
    except KeyboardInterrupt:
        return interrupted("simcheck", args.out)
    except Exception as exc:
        return internal_error("simcheck", what, exc, log)
    if args.json:
        print(json.dumps(cert.summary_dict(), indent=2))
    else:
        print(cert.summary())
        print(f"certificate: {cert.path}")
    for t in cert.tasks:
        if t.status is Outcome.UNUSABLE:
            print(f"simcheck: error: {t.kind}:{t.joint} cannot be certified: {t.reason}", file=sys.stderr)
    return cert.exit_code


if __name__ == "__main__":
    sys.exit(main())
