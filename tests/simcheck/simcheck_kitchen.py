"""The generated kitchen (seed 0, truth only) that the simcheck tests certify on (a helper module beside the
tests; tests/simcheck/conftest.py makes it importable)."""

import json
from pathlib import Path

import scenes


def kitchen_truth(tmp_path_factory, *joints: str) -> Path:
    """Folder holding truth.urdf + truth.json of kitchen seed 0; asserts the scene still has ``joints``."""
    out = tmp_path_factory.mktemp("kitchen0")
    scenes.make_scene("kitchen", seed=0, scan=False, previews=False, out=out)
    truth = json.loads((out / "truth.json").read_text())
    movable = {j["name"] for o in truth["objects"] for j in o["joints"] if j["type"] != "fixed"}
    assert set(joints) <= movable, f"kitchen seed 0 changed: movable joints {sorted(movable)}"
    return out
