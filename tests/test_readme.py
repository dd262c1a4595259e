"""Every command and code example in README.md runs, in order, in one fresh temporary directory.

Fenced blocks by info string:
  ```sh          run with bash (-e -u -o pipefail), the venv's bin first on PATH (scenes, recon, simcheck, pytest)
  ```python      run with the venv's python; a block whose first line is ``# file: NAME`` is written to
                 NAME instead (a later ``sh`` block runs it, e.g. with pytest)
  ```json        parsed (a format example must be valid JSON)
  ``` ... skip="why"   not run; the reason is reported (only the make demo / make test block may use it)
Blocks share the directory, so a later block may use an earlier one's output, as a reader would.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
#: Seconds one block may take before the test fails (the whole README must stay well under 90 s).
BLOCK_TIMEOUT = 120

_FENCE = re.compile(r"^```([A-Za-z]*)([^\n]*)\n(.*?)^```\s*$", re.S | re.M)


@dataclass(frozen=True)
class Block:
    lang: str
    info: str
    code: str
    line: int

    @property
    def skip_reason(self) -> str | None:
        m = re.search(r'skip="([^"]+)"', self.info)
        return m.group(1) if m else None

    def where(self) -> str:
        return f"README.md line {self.line} ({self.lang} block)"


def readme_blocks(text: str) -> list[Block]:
    """The fenced code blocks of ``text`` in order, with the line of their opening fence."""
    return [Block(m.group(1), m.group(2).strip(), m.group(3), text.count("\n", 0, m.start()) + 1)
            for m in _FENCE.finditer(text)]


def test_readme_starts_with_the_two_commands():
    blocks = readme_blocks(README.read_text())
    first = blocks[0]
    assert first.lang == "sh" and first.skip_reason, "the first block is the make demo / make test block, skipped"
    assert re.search(r"^make demo\b", first.code, re.M) and re.search(r"^make test\b", first.code, re.M)
    others = [b for b in blocks[1:] if b.skip_reason]
    assert not others, f"only the make block may be skipped: {[b.where() for b in others]}"


def test_fence_parser_finds_blocks_and_skip_reasons():
    text = 'x\n```sh skip="too slow"\nmake demo\n```\n\n```python\nprint(1)\n```\n'
    blocks = readme_blocks(text)
    assert [(b.lang, b.skip_reason, b.line) for b in blocks] == [("sh", "too slow", 2), ("python", None, 6)]


def _env() -> dict:
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env.setdefault("MPLBACKEND", "Agg")
    env["PYTHONHASHSEED"] = "0"
    return env


def test_every_readme_example_runs(tmp_path):
    blocks = readme_blocks(README.read_text())
    ran, timings = 0, []
    for block in blocks:
        if block.skip_reason:
            continue
        t0 = time.perf_counter()
        if block.lang == "json":
            try:
                json.loads(block.code)
            except ValueError as exc:
                pytest.fail(f"{block.where()}: not valid JSON: {exc}")
            continue
        if block.lang == "python":
            first = block.code.splitlines()[0] if block.code.strip() else ""
            m = re.match(r"#\s*file:\s*(\S+)", first)
            if m:
                (tmp_path / m.group(1)).write_text(block.code)
                continue
            cmd = [sys.executable, "-c", block.code]
        elif block.lang == "sh":
            cmd = ["bash", "-euo", "pipefail", "-c", block.code]
        else:
            continue  # text / output examples
        res = subprocess.run(cmd, cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=BLOCK_TIMEOUT)
        timings.append((block.line, time.perf_counter() - t0))
        assert res.returncode == 0, (f"{block.where()} exited {res.returncode}\n--- code\n{block.code}\n"
                                     f"--- stdout\n{res.stdout[-3000:]}\n--- stderr\n{res.stderr[-5000:]}")
        ran += 1
    assert ran >= 5, f"only {ran} README blocks ran"
    print("README block timings (line, s):", [(ln, round(s, 1)) for ln, s in timings])
