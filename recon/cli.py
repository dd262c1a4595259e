"""``recon`` command line: ``recon build SCAN --labels LABELS --out DIR``.

Exit codes (:func:`scenes.outcome.exit_code`): 0 written; 2 the input could not be used (the message
says why); 1 a reconstruction stage could not produce a valid model (names the object, part or joint);
3 an internal error (one line naming what failed; ``-v`` logs the traceback); 130 interrupted (Ctrl-C).
Progress and warnings go to stderr. ``--out`` is written as a whole (:mod:`scenes.output_folder`): nothing
is written unless every output could be produced (scene.urdf, scene.srdf, graph.json, preview.png, scene.xml).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from recon.config import ScanConfig
from recon.errors import ReconError
from scenes.description import InputError
from scenes.command_line import add_output_arguments, root_parser, setup_logging
from scenes.outcome import Outcome, exit_code, internal_error, interrupted

__all__ = ["main"]


def _parser() -> argparse.ArgumentParser:
    p, common = root_parser("recon", "Part-level reconstruction of a labelled scan.")
    sub = p.add_subparsers(dest="command", required=True)
    b = sub.add_parser("build", help="scan + labels -> scene.urdf, scene.srdf, graph.json, preview.png (+ scene.xml)",
                       parents=[common])
    b.add_argument("scan", type=Path, help="scan.ply or scan.npz (metres, z up unless --level-floor); a scan "
                   "upside down, not z-up or not in metres exits 2")
    b.add_argument("--labels", type=Path, required=True, help="labels.json")
    add_output_arguments(b, "scene.urdf, scene.srdf, graph.json, preview.png, scene.xml")
    b.add_argument("--level-floor", action="store_true",
                   help="write the scene levelled on the scan's floor (floor z = 0, z up; rotated by the floor's "
                        "measured tilt only) instead of in the scan's frame; also takes scans that are upside "
                        "down or not z-up")
    b.add_argument("--seed", type=int, default=0)
    b.add_argument("--min-part-points", type=int, default=None, metavar="N",
                   help=f"skip parts with fewer points (default {ScanConfig.min_part_points}; handles and knobs "
                        f"are kept from {ScanConfig.handle_min_part_points})")
    b.add_argument("--no-preview", action="store_true", help="skip preview.png")
    b.add_argument("--mjcf", action="store_true", help="also write scene.xml (MJCF, for MuJoCo)")
    return p


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    setup_logging(args)

    def progress(msg: str, done: int, total: int):
        if not args.quiet:
            print(f"[{done}/{total}] {msg}", file=sys.stderr, flush=True)

    try:
        from recon.config import ReconConfig
        from recon.output import write_reconstruction
        from recon.pipeline import reconstruct_scan
        from recon.scan import read_scan
        from scenes.output_folder import output_folder

        config = ReconConfig()
        if args.min_part_points is not None:
            if args.min_part_points < 3:
                print(f"recon: error: --min-part-points {args.min_part_points}: a part needs at least 3 points "
                      "to be fitted; give 3 or more", file=sys.stderr)
                return exit_code([Outcome.UNUSABLE])
            config = config.replace(min_part_points=args.min_part_points)
        settings = {"level_floor": args.level_floor, "seed": args.seed, "preview": not args.no_preview,
                    "mjcf": args.mjcf, "min_part_points": config.scan.min_part_points}
        with output_folder(args.out, "recon build", inputs={"scan": args.scan, "labels": args.labels},
                           settings=settings, overwrite=args.overwrite) as staging:
            scan = read_scan(args.scan, args.labels, config)
            rec = reconstruct_scan(scan, config=config, level_floor=args.level_floor, seed=args.seed,
                                   progress=progress)
            written = write_reconstruction(rec, staging, preview_scan=None if args.no_preview else scan,
                                           mjcf=args.mjcf)
        paths = {name: Path(args.out) / name for name in written}
    except InputError as exc:          # ScanError, OutputFolderError
        print(f"recon: error: {exc}", file=sys.stderr)
        return exit_code([Outcome.UNUSABLE])
    except ReconError as exc:
        print(f"recon: reconstruction failed: {exc}", file=sys.stderr)
        return exit_code([Outcome.FAILED])
    except KeyboardInterrupt:
        return interrupted("recon", args.out)
    except Exception as exc:
        return internal_error("recon", f"reconstructing {args.scan}", exc)
    if not args.quiet:
        n_joints = sum(j.type.value != "fixed" for j in rec.joints())
        print(f"recon: {len(rec.objects)} objects, {n_joints} movable joints, {len(rec.warnings)} warnings, "
              f"{rec.timings.get('total', 0.0):.1f} s -> {', '.join(str(p) for p in paths.values())}",
              file=sys.stderr)
    return exit_code([])


if __name__ == "__main__":
    sys.exit(main())
