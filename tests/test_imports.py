"""Importing a pure module never loads a simulation, planning or scanning engine, and the command lines'
modules import no numerical library at all (so ``--help`` is quick). Checked in a fresh interpreter."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys

#: engines that enter only through their adapter modules, when used
ENGINES = ("pybullet", "pinocchio", "coal", "ompl", "open3d")
#: modules of descriptions, artifacts, criteria and file formats: importable without any engine
PURE = ("scenes", "recon", "planners", "simcheck",
        "scenes.outcome", "scenes.description", "scenes.model", "scenes.truth_json", "scenes.truth_urdf",
        "scenes.generators", "scenes.builtin", "scenes.openings",
        "recon.config", "recon.errors", "recon.primitive", "recon.model", "recon.graph_json", "recon.scan",
        "recon.contacts", "recon.part_tree", "recon.joints", "recon.scene_urdf", "recon.metrics",
        "planners.task", "planners.config", "planners.errors", "planners.scene_urdf", "planners.robot",
        "planners.handle", "planners.handle_surface",
        "simcheck.criteria", "simcheck.certificate", "simcheck.config", "simcheck.errors",
        "simcheck.scene_joints", "simcheck.rollout", "simcheck.estimate_diff", "simcheck.scenario",
        "simcheck.scene_bodies", "simcheck.bullet_poses", "simcheck.joint_table", "simcheck.contacts",
        "simcheck.grasp_spring", "simcheck.plan_file", "simcheck.plan_adapters", "simcheck.plan_timing",
        "simcheck.plan_expectations")
#: modules that exist once the shared scene description has landed
LATER = ()
CLIS = ("scenes.cli", "recon.cli", "simcheck.cli")
#: libraries a command line must not import before it knows what to do (they take 0.1-1 s each)
HEAVY = ENGINES + ("numpy", "scipy", "trimesh", "matplotlib", "yourdfpy", "networkx", "shapely")

_PROBE = """
import importlib, json, sys
watch = {watch!r}
first = {{}}
for name in {modules!r}:
    importlib.import_module(name)
    for lib in watch:
        if lib in sys.modules and lib not in first:
            first[lib] = name
print(json.dumps(first))
"""


def _first_importers(modules, watch) -> dict[str, str]:
    """{library: the first of ``modules`` whose import loaded it}, imported in order in a fresh interpreter."""
    code = _PROBE.format(modules=tuple(modules), watch=tuple(watch))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def test_pure_modules_load_no_engine():
    modules = PURE + tuple(m for m in LATER if _exists(m))
    assert _first_importers(modules, ENGINES) == {}


def test_command_line_modules_import_no_numerical_library():
    assert _first_importers(CLIS, HEAVY) == {}


def _exists(name: str) -> bool:
    try:
        return importlib.util.find_spec(name) is not None
    except ModuleNotFoundError:
        return False
