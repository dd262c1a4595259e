"""The three command lines share their conventions (scenes.command_line): ``--version`` prints the package
version, ``-v``/``-q`` work before or after the subcommand, and one log format."""

from __future__ import annotations

import logging
import subprocess
import sys
from importlib.metadata import version

import pytest

import recon.cli
import scenes.cli
import simcheck.cli
from scenes.command_line import LOG_FORMAT, log_level

PARSERS = {"scenes": (scenes.cli._parser, ["list"]),
           "recon": (recon.cli._parser, ["build", "s.ply", "--labels", "l.json", "--out", "o"]),
           "simcheck": (simcheck.cli._parser, ["certify", "scene.urdf"])}


@pytest.mark.parametrize("tool", sorted(PARSERS))
def test_version_prints_the_package_version(tool):
    r = subprocess.run([sys.executable, "-m", tool, "--version"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == f"partscene {version('partscene')}"


@pytest.mark.parametrize("tool", sorted(PARSERS))
@pytest.mark.parametrize("before, after, level", [
    ([], [], logging.WARNING), (["-v"], [], logging.INFO), ([], ["-v"], logging.INFO),
    (["-vv"], [], logging.DEBUG), ([], ["-vv"], logging.DEBUG), (["-v"], ["-v"], logging.INFO),
    (["-q"], [], logging.ERROR), ([], ["-q"], logging.ERROR), (["-v"], ["-q"], logging.ERROR),
])
def test_verbosity_flags_work_before_or_after_the_subcommand(tool, before, after, level):
    parser, argv = PARSERS[tool]
    args = parser().parse_args(before + argv + after)
    assert log_level(args) == level


def test_simcheck_batch_takes_the_same_flags():
    args = simcheck.cli._parser().parse_args(["batch", "m.yaml", "--out", "o", "-q"])
    assert log_level(args) == logging.ERROR


def test_one_log_format_names_level_and_logger():
    record = logging.LogRecord("recon.joints", logging.WARNING, __file__, 1, "hinge side guessed", None, None)
    assert logging.Formatter(LOG_FORMAT).format(record) == "WARNING recon.joints: hinge side guessed"
