"""``scenes`` command line: ``scenes list`` and ``scenes make NAME [--seed S] [--preset P] --out DIR``.

Exit codes (:func:`scenes.outcome.exit_code`): 0 done; 2 bad arguments or a scene that cannot be made
(the message says why, also an ``--out`` holding something else: :mod:`scenes.output_folder`); 3 an internal
error (one line naming what failed; ``-v`` logs the traceback); 130 interrupted. ``--out`` is written as a whole.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .command_line import add_output_arguments, root_parser, setup_logging
from .description import InputError
from .errors import ScenesError
from .outcome import Outcome, exit_code, internal_error, interrupted

__all__ = ["main"]


def _parser() -> argparse.ArgumentParser:
    ap, common = root_parser("scenes", "Ground-truth articulated rooms and virtual RGB-D scans.")
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("list", help="list the built-in scenes", parents=[common])
    mk = sub.add_parser("make", help="make and scan a scene", parents=[common])
    mk.add_argument("name", help="scene name (see `scenes list`)")
    mk.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    mk.add_argument("--preset", default="clean", help="scan preset: clean | realistic | scannet (default clean)")
    add_output_arguments(mk, "truth.urdf, truth.json, scan.ply, labels.json, scan.npz, scan_meta.json, previews")
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
        from .output_folder import output_folder

        settings = {"name": args.name, "seed": args.seed, "preset": args.preset, "scan": not args.no_scan,
                    "previews": not args.no_previews}
        with output_folder(args.out, "scenes make", inputs={}, settings=settings, overwrite=args.overwrite) as staging:
            made = make_scene(args.name, seed=args.seed, preset=args.preset, out=staging,
                              scan=not args.no_scan, previews=not args.no_previews)
        files = {key: Path(args.out) / Path(path).relative_to(staging) for key, path in made.files.items()}
    except (ScenesError, InputError) as e:
        sys.stderr.write(f"scenes: error: {e}\n")
        return exit_code([Outcome.UNUSABLE])
    except KeyboardInterrupt:
        return interrupted("scenes", args.out)
    except Exception as e:
        return internal_error("scenes", f"running scenes {args.cmd}", e)
    if not args.quiet:
        n = len(made.scan) if made.scan is not None else 0
        sys.stdout.write(f"{args.name} seed {args.seed}: {len(made.scene.objects)} objects, {n} scan points\n")
        for key, path in files.items():
            sys.stdout.write(f"  {key:13s} {path}\n")
    return exit_code([])
