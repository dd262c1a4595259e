"""What every partscene command line (``scenes``, ``recon``, ``simcheck``) shares: ``--version``,
``-v``/``-q`` accepted before or after the subcommand, and one log format on stderr.

>>> ap, common = root_parser("scenes", "Ground-truth rooms.")
>>> sub = ap.add_subparsers(dest="cmd", required=True)
>>> _ = sub.add_parser("list", parents=[common])
>>> args = ap.parse_args(["list", "-vv"])
>>> log_level(args)          # logging.DEBUG
10

Levels: default WARNING (libraries' warnings only), ``-v`` INFO (progress, and the traceback of an internal
error), ``-vv`` DEBUG, ``-q`` ERROR (``-q`` wins over ``-v``). Standard library only, so ``--help`` stays quick.
"""

from __future__ import annotations

import argparse
import logging
import sys
from importlib.metadata import PackageNotFoundError, version

__all__ = ["LOG_FORMAT", "package_version", "root_parser", "log_level", "setup_logging", "is_quiet",
           "add_output_arguments"]

#: the one log line format of the three tools (stderr): ``WARNING recon.joints: door hinge ...``
LOG_FORMAT = "%(levelname)s %(name)s: %(message)s"


def package_version() -> str:
    """``"partscene X.Y.Z"`` from the installed distribution's metadata (``"partscene (not installed)"`` if none)."""
    try:
        return f"partscene {version('partscene')}"
    except PackageNotFoundError:
        return "partscene (not installed)"


def _verbosity_parent() -> argparse.ArgumentParser:
    common = argparse.ArgumentParser(add_help=False)
    # SUPPRESS: a flag given before or after the subcommand is kept (the subparser adds no default that
    # would overwrite the value the main parser read)
    common.add_argument("-v", "--verbose", action="count", default=argparse.SUPPRESS,
                        help="more logging on stderr (-v: progress, -vv: debug)")
    common.add_argument("-q", "--quiet", action="store_true", default=argparse.SUPPRESS,
                        help="print nothing but errors")
    return common


def root_parser(prog: str, description: str) -> tuple[argparse.ArgumentParser, argparse.ArgumentParser]:
    """The main parser of command ``prog`` (with ``--version``, ``-v``, ``-q``) and the parent parser that
    every subcommand's parser must list in ``parents=[...]`` so ``-v``/``-q`` also work after it."""
    common = _verbosity_parent()
    ap = argparse.ArgumentParser(prog=prog, description=description, parents=[common])
    ap.add_argument("--version", action="version", version=package_version())
    return ap, common


def is_quiet(args: argparse.Namespace) -> bool:
    """Whether ``-q`` was given (before or after the subcommand)."""
    return bool(getattr(args, "quiet", False))


def log_level(args: argparse.Namespace) -> int:
    """The logging level that ``-v`` (count) and ``-q`` in ``args`` ask for (module docstring)."""
    if is_quiet(args):
        return logging.ERROR
    return (logging.WARNING, logging.INFO, logging.DEBUG)[min(getattr(args, "verbose", 0) or 0, 2)]


def setup_logging(args: argparse.Namespace) -> int:
    """Configure the root logger to write :data:`LOG_FORMAT` lines to stderr at :func:`log_level`;
    also sets ``args.verbose`` (int) and ``args.quiet`` (bool) so commands can read them. Returns the level."""
    args.verbose = getattr(args, "verbose", 0) or 0
    args.quiet = is_quiet(args)
    level = log_level(args)
    logging.basicConfig(level=level, format=LOG_FORMAT, stream=sys.stderr)
    return level


def add_output_arguments(parser: argparse.ArgumentParser, what: str, default: str | None = None) -> None:
    """Add ``--out DIR`` (required when ``default`` is None) and ``--overwrite`` to ``parser``: the output
    folder is written as a whole (:mod:`scenes.output_folder`); ``what`` lists what goes into it."""
    parser.add_argument("--out", default=default, required=default is None,
                        help=f"output folder ({what}), written as a whole: a rerun with the same inputs replaces it; "
                             "anything else in it is refused unless --overwrite" +
                             (f" (default: {default})" if default else ""))
    parser.add_argument("--overwrite", action="store_true",
                        help="replace the whole content of --out, whatever it holds")
