"""The results of a batch, under its output folder and nowhere else.

    DIR/results/<key>/result.json        one task: status, reason, key criteria, times, attempts
    DIR/results/<key>/certificate.json   its certificate (as ``simcheck certify`` writes it), rollouts/, images/
    DIR/scans/<key>/scene.urdf, graph.json   a scan's reconstruction, shared by the scan's tasks
    DIR/summary.json, summary.html       written at the end of every run

A result folder is built under a temporary name in the same folder and renamed into place, so a folder
named by a key is always complete; a run killed mid-way leaves at most ``.tmp-*`` folders, which the
next run removes. A result whose folder exists is never computed again.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from pathlib import Path
from typing import Callable

from scenes.description import write_text_atomic

__all__ = ["Store", "RESULT_FORMAT"]

RESULT_FORMAT = "partscene.batch-result/1"


class Store:
    """Result folders under ``root`` (created if missing)."""

    def __init__(self, root: str | Path) -> None:
        self.root = Path(root).resolve()
        self.results = self.root / "results"
        self.scans = self.root / "scans"
        self.results.mkdir(parents=True, exist_ok=True)
        self.scans.mkdir(parents=True, exist_ok=True)

    def remove_partial(self) -> int:
        """Delete temporary folders left by a killed run; returns how many."""
        n = 0
        for folder in (self.results, self.scans):
            for p in folder.glob(".tmp-*"):
                shutil.rmtree(p, ignore_errors=True)
                n += 1
        return n

    def result_dir(self, key: str) -> Path:
        return self.results / key

    def has(self, key: str) -> bool:
        return (self.results / key / "result.json").is_file()

    def load(self, key: str) -> dict:
        return json.loads((self.results / key / "result.json").read_text())

    def keys(self) -> list[str]:
        """Keys of every complete result."""
        return sorted(p.parent.name for p in self.results.glob("*/result.json") if not p.parent.name.startswith("."))

    def commit(self, folder: Path, key: str, build: Callable[[Path], None]) -> bool:
        """Build a folder with ``build(tmp)`` and rename it to ``folder/key``; False (and nothing
        changed) when ``folder/key`` already exists."""
        tmp = Path(tempfile.mkdtemp(prefix=f".tmp-{key}-", dir=folder))
        try:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o777 & ~umask)   # mkdtemp makes 0700; give the folder ordinary permissions
            build(tmp)
            os.rename(tmp, folder / key)
            return True
        except OSError:
            if (folder / key).exists():
                return False
            raise
        finally:
            if tmp.exists():
                shutil.rmtree(tmp, ignore_errors=True)

    def put_result(self, key: str, make: Callable[[Path], dict]) -> bool:
        """Store a result: ``make(tmp)`` writes its files (certificate.json, rollouts/...) into ``tmp`` and
        returns the record written as ``result.json``; then the folder becomes ``results/<key>``.
        False when that result already existed (the new one is discarded)."""
        def write(tmp: Path) -> None:
            record = make(tmp)
            write_text_atomic(tmp / "result.json", json.dumps({"format": RESULT_FORMAT, "key": key, **record},
                                                               indent=2, allow_nan=False) + "\n")
        return self.commit(self.results, key, write)
