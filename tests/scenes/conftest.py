"""Shared, session-scoped fixtures of the scenes tests (built once: scenes and scans cost seconds)."""

from __future__ import annotations

import pytest

from scenes.builtin import build_scene
from scenes.scanner import params_for_preset, scan_scene
from scenes.truth_json import write_truth_json
from scenes.truth_urdf import write_truth_urdf

# a cheap scan: fewer, smaller frames than the presets (same code path)
SMALL = dict(width=160, height=120, n_frames=24, frames_per_object=0)


@pytest.fixture(scope="session")
def small():
    """Overrides for a cheap scan (fewer, smaller frames)."""
    return dict(SMALL)


@pytest.fixture(scope="session")
def kitchen():
    return build_scene("kitchen", 0)


@pytest.fixture(scope="session")
def kitchen_files(tmp_path_factory, kitchen):
    out = tmp_path_factory.mktemp("kitchen0")
    return write_truth_urdf(kitchen, out / "truth.urdf"), write_truth_json(kitchen, out / "truth.json")


@pytest.fixture(scope="session")
def clean_scan(kitchen):
    return scan_scene(kitchen, params_for_preset("clean", **SMALL), seed=3)
