"""An output folder (``--out DIR``) written as a whole: the command writes into a temporary folder beside
``DIR`` and, once everything is written, that folder is renamed onto ``DIR``.

    with output_folder(out, "recon build", inputs={"scan": scan, "labels": labels},
                       settings={"seed": 0}, overwrite=False) as staging:
        write_reconstruction(rec, staging)          # files go into staging, never half into out
    # out now holds exactly what was written, plus the run record .partscene-run.json

What happens to an existing ``DIR``:

* missing or empty: created;
* written by an earlier run of the same command with the same input files (sha256 of their content) and
  settings: replaced;
* anything else -- an earlier run with other inputs or settings, a file the run record does not list (a
  user's ``scene.urdf``), a folder without a run record -- is refused (:class:`OutputFolderError`, naming the
  file) unless ``overwrite``: then its whole content is replaced.

An input file inside ``DIR`` is always refused (replacing the folder would delete it), and so is a ``DIR``
that holds the current directory. When a run starts over an earlier one, the earlier run's verdict file
(``verdict``, e.g. ``certificate.json``) is removed at once, so a run that crashes never leaves a verdict
that looks like its own; the rest of the earlier folder stays until the new one is complete. A failure, a
``KeyboardInterrupt`` or a full disk removes the temporary folder: no partial file is ever left in ``DIR``.
A full disk (or a read-only file system) raises :class:`OutputFolderError` naming ``DIR``.

Standard library only.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import os
import shutil
import tempfile
from pathlib import Path
from typing import Iterator, Mapping

from scenes.description import InputError

__all__ = ["RUN_RECORD", "OutputFolderError", "output_folder", "file_sha256", "run_record"]

#: the run record a command leaves in its output folder: what it was run on, and which files it wrote
RUN_RECORD = ".partscene-run.json"
RUN_FORMAT = "partscene.run/1"
#: errors of the file system (not of the command) while writing the output: named, exit 2
_DISK_ERRNOS = (errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EROFS)


class OutputFolderError(InputError):
    """The output folder cannot be used or written (the message names it and what to do)."""


def file_sha256(path: str | os.PathLike) -> str:
    """Hex sha256 of the file's content."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def run_record(command: str, inputs: Mapping[str, str | os.PathLike | None], settings: Mapping) -> dict:
    """The record of a run: ``command``, each input file's absolute path and sha256 (None inputs left out),
    and the ``settings`` (JSON-ready values). Two runs are the same run when command, input hashes and
    settings are equal."""
    files = {role: {"path": str(Path(p).resolve()), "sha256": file_sha256(p)}
             for role, p in inputs.items() if p is not None and Path(p).is_file()}
    return {"format": RUN_FORMAT, "command": command, "inputs": files,
            "settings": json.loads(json.dumps(dict(settings), default=str))}


def _same_run(a: dict, b: dict) -> bool:
    def key(r):
        return (r.get("command"), {k: v.get("sha256") for k, v in (r.get("inputs") or {}).items()},
                r.get("settings"))
    return key(a) == key(b)


def _what_differs(old: dict, new: dict) -> str:
    if old.get("command") != new.get("command"):
        return f"it holds the output of `{old.get('command')}`"
    old_in, new_in = old.get("inputs") or {}, new.get("inputs") or {}
    for role in sorted(set(old_in) | set(new_in)):
        if (old_in.get(role) or {}).get("sha256") != (new_in.get(role) or {}).get("sha256"):
            was = (old_in.get(role) or {}).get("path", "nothing")
            return f"it holds a run on another {role} ({was})"
    for k in sorted(set(old.get("settings") or {}) | set(new.get("settings") or {})):
        a, b = (old.get("settings") or {}).get(k), (new.get("settings") or {}).get(k)
        if a != b:
            return f"it holds a run with {k} = {a!r} (this run: {b!r})"
    return "it holds another run"


def _listing(folder: Path) -> list[str]:
    """Every file and empty folder under ``folder``, relative, sorted."""
    out = []
    for root, dirs, files in os.walk(folder):
        rel = Path(root).relative_to(folder)
        out += [str(rel / f) for f in files]
        out += [str(rel / d) + "/" for d in dirs if not os.listdir(Path(root) / d)]
    return sorted(out)


def _check_existing(out: Path, record: dict, overwrite: bool) -> bool:
    """Refuse an ``out`` that may not be replaced; True when it exists and will be replaced."""
    if not out.exists():
        return False
    if not out.is_dir():
        raise OutputFolderError(f"--out {out} exists and is not a folder; choose another --out")
    present = _listing(out)
    if not present or overwrite:
        return True
    old = None
    if (out / RUN_RECORD).is_file():
        try:
            old = json.loads((out / RUN_RECORD).read_text())
        except (OSError, ValueError):
            old = None
    if old is None or old.get("format") != RUN_FORMAT:
        first = next((p for p in present if p != RUN_RECORD), RUN_RECORD)
        raise OutputFolderError(
            f"{out / first}: --out {out} holds files that no partscene run wrote there; the output folder is "
            "replaced as a whole, so choose an empty or new --out, or pass --overwrite to replace its content")
    written = set(old.get("files") or ()) | {RUN_RECORD}
    foreign = [p for p in present if p not in written and not p.endswith("/")]
    if foreign:
        raise OutputFolderError(
            f"{out / foreign[0]}: this file in --out {out} was not written by the earlier run there; the output "
            "folder is replaced as a whole, so move it, choose another --out, or pass --overwrite to replace it")
    if not _same_run(old, record):
        raise OutputFolderError(
            f"--out {out}: {_what_differs(old, record)}; choose another --out, or pass --overwrite to replace it")
    return True


def _check_inputs(out: Path, inputs: Mapping) -> None:
    out_r = out.resolve()
    cwd = Path.cwd().resolve()
    if out_r == cwd or out_r in cwd.parents or out_r == Path.home().resolve():
        raise OutputFolderError(f"--out {out} is the current folder, one above it or the home folder: the output "
                                "folder is replaced as a whole; choose a folder of its own")
    for role, p in inputs.items():
        if p is not None and out_r in Path(p).resolve().parents:
            raise OutputFolderError(f"{p}: this input ({role}) lies inside --out {out}, which is replaced as a "
                                    "whole; move the input or choose another --out")


def _fresh_name(out: Path, tag: str) -> Path:
    return Path(tempfile.mkdtemp(prefix=f".{out.name}.{tag}-", dir=out.parent))


@contextlib.contextmanager
def output_folder(out: str | os.PathLike, command: str, *, inputs: Mapping[str, str | os.PathLike | None],
                  settings: Mapping, overwrite: bool = False, verdict: str | None = None) -> Iterator[Path]:
    """Yield a temporary folder beside ``out`` to write into; on leaving the block without an exception it
    becomes ``out`` (module docstring: what is refused, what is replaced).

    Args:
        out: the output folder.
        command: the command's name ("recon build", "simcheck certify"), recorded and compared.
        inputs: role -> input file (None: not given); refused when inside ``out``; their sha256 identify the run.
        settings: the arguments that change the output (seed, tasks, ...), compared with the earlier run's.
        overwrite: replace whatever ``out`` holds.
        verdict: a file name whose earlier copy in ``out`` is removed as soon as the run starts.

    Raises:
        OutputFolderError: ``out`` may not be replaced or written (names the file or folder and what to do).
    """
    out = Path(out)
    _check_inputs(out, inputs)
    record = run_record(command, inputs, settings)
    replacing = _check_existing(out, record, overwrite)
    out.parent.mkdir(parents=True, exist_ok=True)
    if replacing and verdict and (out / verdict).is_file():
        (out / verdict).unlink()
    staging = _fresh_name(out, "partial")
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(staging, 0o777 & ~umask)       # mkdtemp makes 0700; the output is an ordinary folder
    try:
        yield staging
        record["files"] = [p for p in _listing(staging) if p != RUN_RECORD]
        (staging / RUN_RECORD).write_text(json.dumps(record, indent=1) + "\n")
        if out.exists():
            old = _fresh_name(out, "old")
            os.rmdir(old)
            os.rename(out, old)
            os.rename(staging, out)
            shutil.rmtree(old, ignore_errors=True)
        else:
            os.rename(staging, out)
    except OSError as exc:
        shutil.rmtree(staging, ignore_errors=True)
        if exc.errno in _DISK_ERRNOS:
            raise OutputFolderError(f"--out {out}: cannot write ({os.strerror(exc.errno)}); nothing was written and "
                                    f"{out} is as it was; free space or choose another --out") from exc
        raise
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
