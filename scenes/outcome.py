"""The outcome of one task (:class:`Outcome`) and the exit code of a run (:func:`exit_code`).

One vocabulary for every package and command line: the certificate records a task's outcome, the CLIs
and the batch runner turn the outcomes of a run into an exit code, the report counts them.

==========  ==============================================================================
exit code   when
==========  ==============================================================================
0           every task is ``certified`` (a run that judges nothing, such as ``scenes make``,
            exits 0 when it succeeds)
2           some input is ``unusable`` (the message names the file, object, part or joint)
3           an internal ``error`` (a bug: the message names what failed; ``-v`` logs the traceback)
1           otherwise: some task ``failed``, was ``not_planned``, ``unreachable`` or hit a ``timeout``
==========  ==============================================================================

The rules are applied in this order, so unusable input wins over an internal error elsewhere in the run.
Engine-free (standard library only), so any module may import it.
"""

from __future__ import annotations

import enum
import logging
import sys
from typing import Iterable

__all__ = ["Outcome", "exit_code", "internal_error", "interrupted", "INTERRUPTED_EXIT"]


class Outcome(enum.StrEnum):
    """What became of one task; the value is the lowercase string written to ``certificate.json``."""

    CERTIFIED = "certified"       #: executed, and every criterion passed
    FAILED = "failed"             #: executed (or judged), and some criterion failed
    NOT_PLANNED = "not_planned"   #: the planner found no motion (IK, path or opening motion failed)
    UNREACHABLE = "unreachable"   #: the planner found no base pose from which the handle can be grasped
    UNUSABLE = "unusable"         #: the input cannot be used (missing or fixed joint, broken file, ...)
    ERROR = "error"               #: an internal error (a bug), not a verdict on the input
    TIMEOUT = "timeout"           #: the task did not finish within its time budget

    @classmethod
    def _missing_(cls, value):
        # certificate.json files of format partscene.certificate/1 spell NOT_PLANNED "not-planned"
        if isinstance(value, str) and value.replace("-", "_") in cls._value2member_map_:
            return cls(value.replace("-", "_"))
        return None


def exit_code(outcomes: Iterable[Outcome | str]) -> int:
    """The exit code of a run whose tasks ended with ``outcomes`` (the table in the module docstring).

    ``outcomes`` may be :class:`Outcome` members or their string values; an empty run exits 0.
    """
    seen = {Outcome(o) for o in outcomes}
    if Outcome.UNUSABLE in seen:
        return 2
    if Outcome.ERROR in seen:
        return 3
    return 0 if seen <= {Outcome.CERTIFIED} else 1


def internal_error(prog: str, what: str, exc: BaseException, log: logging.Logger | None = None) -> int:
    """Report an unexpected exception of a command line and return its exit code (3).

    Writes one line to stderr, ``"<prog>: internal error while <what>: <Type>: <message> (-v: traceback)"``,
    and logs the traceback at INFO on ``log`` (default: the logger named ``prog``), so ``-v`` shows it.
    """
    text = str(exc).strip().splitlines()
    detail = f"{type(exc).__name__}: {text[0]}" if text else type(exc).__name__
    sys.stderr.write(f"{prog}: internal error while {what}: {detail} (run with -v for the traceback)\n")
    (log or logging.getLogger(prog)).info("traceback of the internal error:", exc_info=exc)
    return exit_code([Outcome.ERROR])


#: the exit code of a command stopped by Ctrl-C (128 + SIGINT, as shells report it)
INTERRUPTED_EXIT = 130


def interrupted(prog: str, out=None) -> int:
    """Report a Ctrl-C and return :data:`INTERRUPTED_EXIT`: one line on stderr saying that nothing was
    written to ``out`` (the output folder, left as it was) when it is given."""
    where = f"; nothing was written, {out} is as it was" if out is not None else ""
    sys.stderr.write(f"{prog}: interrupted{where}\n")
    return INTERRUPTED_EXIT
