"""Content keys: a result is stored under a hash of everything it depends on, so a rerun finds it
again and a changed input (scene, reference, task, robot, settings or software) gets a new key.

Keys are SHA-256 hex digests (the first :data:`KEY_LENGTH` characters name a result's folder).
"""

from __future__ import annotations

import hashlib
import json
from functools import lru_cache
from pathlib import Path

__all__ = ["file_digest", "code_digest", "task_key", "scan_key", "KEY_LENGTH"]

#: hex characters of a key used in folder names (80 bits: collisions are not a practical concern)
KEY_LENGTH = 20
#: the packages whose source a certification depends on
_PACKAGES = ("simcheck", "planners", "recon", "scenes")


def file_digest(path: str | Path | None) -> str:
    """SHA-256 hex digest of the bytes of ``path`` ("" for None)."""
    from scenes.output_folder import file_sha256

    return "" if path is None else file_sha256(path)


@lru_cache(maxsize=1)
def code_digest() -> str:
    """Digest of the software a result was computed with: the source of simcheck, planners, recon and
    scenes (every ``*.py``, by relative path) and the versions of the engines (pybullet, pinocchio, ompl,
    numpy)."""
    import importlib

    from simcheck.certificate import software_versions

    h = hashlib.sha256(json.dumps(software_versions(), sort_keys=True).encode())
    for name in _PACKAGES:
        root = Path(importlib.import_module(name).__file__).parent
        for p in sorted(root.rglob("*.py")):
            h.update(str(p.relative_to(root.parent)).encode())
            h.update(p.read_bytes())
    return h.hexdigest()


def _key(doc: dict) -> str:
    return hashlib.sha256(json.dumps(doc, sort_keys=True).encode()).hexdigest()[:KEY_LENGTH]


def task_key(scene_digest: str, against_digest: str, task: str, robot_digest: str, settings: dict) -> str:
    """Key of one certification: the scene's and reference's content digests, the task string, the
    robot (its spec file's digest, or "default"), ``settings`` (seed, amount, criteria, physics, images:
    JSON-ready) and :func:`code_digest`."""
    return _key({"scene": scene_digest, "against": against_digest, "task": task, "robot": robot_digest,
                 "settings": settings, "code": code_digest()})


def scan_key(scan_digest: str, labels_digest: str, seed: int) -> str:
    """Key of one reconstruction: the scan's and labels' digests, the seed and :func:`code_digest`."""
    return _key({"scan": scan_digest, "labels": labels_digest, "seed": seed, "code": code_digest()})
