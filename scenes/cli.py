"""``scenes`` command line: ``scenes list`` and ``scenes make NAME [--seed S] [--preset P] --out DIR``.

Exit codes (:func:`scenes.outcome.exit_code`): 0 done; 2 bad arguments or a scene that cannot be made
(the message says why); 3 an internal error (one line naming what failed; ``-v`` logs the traceback).
"""

from __future__ import annotations

import argparse
import sys

from .command_line import root_parser, setup_logging
from .errors import ScenesError
from .outcome import Outcome, exit_code, internal_error

__all__ = ["main"]


def _parser() -> argparse.ArgumentParser:
    ap, common = root_parser("scenes", "Ground-truth articulated rooms and virtual RGB-D scans.")
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("list", help="list the built-in scenes", parents=[common])
    mk = sub.add_parser("make", help="make and scan a scene", parents=[common])
    mk.add_argument("name", help="scene name (see `scenes list`)")
    mk.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    mk.add_argument("--preset", default="clean", help="scan preset: clean | realistic (default clean)")
    mk.add_argument("--out", required=True, help="output directory")
    mk.add_argument("--no-scan", action="store_true", help="write the ground truth only")
    mk.add_argument("--no-previews", action="store_true", help="skip the preview PNGs")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    setup_logging(args)
    try:
        if args.cmd == "list":
            from .builtin import SCENE_DESCRIPTIONS

            for name, desc in SCENE_DESCRIPTIONS.items():
                sys.stdout.write(f"{name:10s} {desc}\n")
            return exit_code([])
        from .api import make_scene

        made = make_scene(args.name, seed=args.seed, preset=args.preset, out=args.out,
                          scan=not args.no_scan, previews=not args.no_previews)
    except ScenesError as e:
        sys.stderr.write(f"scenes: error: {e}\n")
        return exit_code([Outcome.UNUSABLE])
    except Exception as e:
        return internal_error("scenes", f"running scenes {args.cmd}", e)
    if not args.quiet:
        n = len(made.scan) if made.scan is not None else 0
        sys.stdout.write(f"{args.name} seed {args.seed}: {len(made.scene.objects)} objects, {n} scan points\n")
        for key, path in made.files.items():
            sys.stdout.write(f"  {key:13s} {path}\n")
    return exit_code([])
