"""``simcheck batch MANIFEST --out DIR [--workers N] [--address ADDR] [--task-timeout S] [--task-memory MB]
[--retries N] [--images] [--junit FILE] [--baseline OLD/summary.json]``: the command line of
:func:`simcheck.batching.batch`.

Exit codes as for ``simcheck certify``: 0 every task certified; 2 some input unusable, or a malformed
manifest (nothing started; the message names the line and field); 3 an internal error; otherwise 1.
Ctrl-C or SIGTERM stops the run (exit 130); a rerun does only what is missing.
"""

from __future__ import annotations

import argparse
import logging
import sys

__all__ = ["add_batch_parser", "run_batch"]

log = logging.getLogger("simcheck")


def add_batch_parser(sub, parents: list[argparse.ArgumentParser] = ()) -> None:
    """Add the ``batch`` subcommand to ``sub``; ``parents`` carry the shared ``-v``/``-q`` options."""
    from simcheck.batching import DEFAULT_TASK_TIMEOUT

    b = sub.add_parser("batch", help="certify every task of a manifest on Ray (resumable)", parents=list(parents))
    b.add_argument("manifest", help="YAML list or JSON Lines of scene:/scan: entries")
    b.add_argument("--out", required=True, help="output folder: results/, scans/, summary.json, summary.html")
    b.add_argument("--workers", type=int, default=None, help="local CPUs to use (default: all)")
    b.add_argument("--address", default=None, help="a running Ray cluster: auto, HOST:6379 or ray://HOST:10001")
    b.add_argument("--task-timeout", type=float, default=DEFAULT_TASK_TIMEOUT,
                   help=f"seconds per task before it is recorded as timeout (default {DEFAULT_TASK_TIMEOUT:g}; 0: none)")
    b.add_argument("--task-memory", type=float, default=None,
                   help="MB of worker memory a task may use before it is stopped as error (default: no limit)")
    b.add_argument("--retries", type=int, default=1, help="reruns of a task whose worker died (default 1)")
    b.add_argument("--chunk", type=int, default=None,
                   help="certifications of one scene per Ray task (default: from the task and CPU counts, at most 16)")
    b.add_argument("--images", action="store_true", help="also render each task's key-frame PNGs")
    b.add_argument("--junit", default=None, help="also write JUnit XML here")
    b.add_argument("--baseline", default=None, help="an older summary.json: list the tasks that newly fail")


def run_batch(args) -> int:
    from scenes.outcome import internal_error
    from simcheck.batching import batch
    from simcheck.errors import SimcheckInputError

    if args.workers is not None and args.workers < 1:
        print("simcheck: error: --workers must be at least 1", file=sys.stderr)
        return 2
    try:
        result = batch(args.manifest, args.out, workers=args.workers, address=args.address,
                       task_timeout=args.task_timeout or None, task_memory=args.task_memory, retries=args.retries,
                       images=args.images, junit=args.junit, baseline=args.baseline, progress=not args.quiet,
                       chunk=args.chunk)
    except SimcheckInputError as exc:
        print(f"simcheck: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("simcheck: batch interrupted; rerun the same command to finish it", file=sys.stderr)
        return 130
    except Exception as exc:  # noqa: BLE001 - an internal error: exit 3 with one line
        if type(exc).__name__ == "_Stop":
            print(f"simcheck: batch stopped ({exc}); rerun the same command to finish it", file=sys.stderr)
            return 130
        return internal_error("simcheck", "running the batch", exc, log)
    if not args.quiet:
        totals = ", ".join(f"{k} {v}" for k, v in result.totals.items())
        print(f"{len(result.rows)} tasks: {totals} ({result.computed} run now, {result.resumed} from earlier runs"
              f"{f', {result.retried} worker deaths retried' if result.retried else ''})")
        for n in result.newly_failing or []:
            print(f"newly failing: {n['scene']} {n['task']}: {n['status']} (certified in the baseline)")
        print(f"summary: {result.summary_path} and {result.summary_path.with_suffix('.html')}")
    return result.exit_code
