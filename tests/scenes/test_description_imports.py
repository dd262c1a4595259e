"""``import scenes.description`` stays engine-free (checked in a fresh interpreter)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

FIXTURE = Path(__file__).parents[1] / "planners" / "data" / "cabinet_fixture.urdf"
ENGINES = ("pybullet", "pinocchio", "coal", "ompl", "open3d")


def test_description_loads_no_engine():
    code = ("import json, sys; import scenes.description as d; "
            "d.read_urdf(%r); print(json.dumps(sorted(m for m in sys.modules if m.split('.')[0] in %r)))" % (str(FIXTURE), ENGINES))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout.strip().splitlines()[-1]) == []
