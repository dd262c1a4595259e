"""``python -m simcheck.report DEMO_DIR [--out report.html] [--teaser picture.png]``: (re-)render a
demo directory's report without re-running the pipeline."""

from __future__ import annotations

import argparse
import logging
import sys
from collections.abc import Sequence
from pathlib import Path

from scenes.description import write_bytes_atomic

from ._errors import ReportError
from ._render import render_report
from ._teaser import png_of_teaser


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m simcheck.report",
                                description="(Re-)render a demo directory's report.html from its artifacts.")
    p.add_argument("demo_dir", help="a directory written by python -m simcheck.demo")
    p.add_argument("--out", help="where to write the report (default: DEMO_DIR/report.html)")
    p.add_argument("--teaser", help="also write the one-picture summary PNG here")
    p.add_argument("-v", "--verbose", action="store_true")
    args = p.parse_args(argv)
    logging.basicConfig(level=logging.DEBUG if args.verbose else logging.INFO, stream=sys.stderr,
                        format="%(name)s: %(message)s")
    for noisy in ("matplotlib", "PIL"):
        logging.getLogger(noisy).setLevel(logging.WARNING)
    try:
        path = render_report(args.demo_dir, args.out)
        if args.teaser:
            write_bytes_atomic(Path(args.teaser), png_of_teaser(args.demo_dir))
    except ReportError as exc:
        print(f"simcheck.report: {exc}", file=sys.stderr)
        return 2
    print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
