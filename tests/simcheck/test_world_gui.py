"""``--gui`` opens a PyBullet window where a display exists: on a virtual X display (xvfb-run, installed
by .ci/system-deps), in a subprocess, a GUI world loads a scene and the robot, steps, renders and closes,
and PyBullet's OpenGL chatter stays off stdout. (A whole GUI certification takes ~50 s with software
OpenGL, so the test stops at the world: certification itself is the same code as headless.)"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import pytest

from simcheck_fixture_plans import DATA

SCRIPT = """
import sys, numpy as np, planners
from simcheck.robot_binding import sim_robot_from_spec
from simcheck.world import World
with World(sys.argv[1], sim_robot_from_spec(planners.default_robot()), gui=True) as w:
    w.step(50)
    rgb = w.render(target=np.array([0.0, 0.0, 0.5]), eye=np.array([2.0, 1.0, 1.5]), width=64, height=48)
    print("gui world ok", w.client, rgb.shape)
"""


@pytest.mark.skipif(shutil.which("xvfb-run") is None, reason="needs xvfb-run (.ci/system-deps installs it)")
def test_a_gui_world_opens_on_a_virtual_display_and_keeps_pybullet_chatter_off_stdout():
    env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
    run = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 640x480x24", sys.executable, "-c", SCRIPT,
                          str(DATA / "cabinet.urdf")], capture_output=True, text=True, timeout=120, env=env)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    assert "gui world ok" in run.stdout and "(48, 64, 3)" in run.stdout
    assert "Created GL" not in run.stdout and "argv[0]" not in run.stdout
