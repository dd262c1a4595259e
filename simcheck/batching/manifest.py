"""The batch manifest: a YAML list of entries or JSON Lines (one entry per line), parsed and checked
before anything runs.

Each entry is a scene to certify or a scan to reconstruct first::

    - scene: kitchen0/truth.urdf          # plan on this URDF
      against: kitchen0/truth.urdf        # optional: execute on this reference
      tasks: [open-drawer:cabinet1_drawer4_joint, open-door:cabinet1_door2_joint]   # or: all-movable
    - scan: kitchen1/scan.ply             # reconstructed once (recon), its tasks share the result
      labels: kitchen1/labels.json
      truth: kitchen1/truth.urdf          # optional: certify the reconstruction against it
      tasks: all-movable
      seed: 0                             # optional (default 0): planning and reconstruction seed
      amount: 0.2                         # optional: opening for every task of the entry (m or rad)
      robot: robot.yaml                   # optional: "default", "compliant" or a robot spec file
      robust: 20                          # optional: certify each task in 20 sampled worlds (simcheck.robust)
      min_success: 0.9                    # optional with robust (default 0.9)

Relative paths are relative to the manifest's folder. Any problem (unknown field, missing file, a task
naming a joint the scene lacks...) raises :class:`ManifestError` naming the manifest, the line and the
field, so the CLI exits 2 before Ray starts.

``_fault`` (internal, for the tests of the batch runner only): ``raise``, ``segfault``, ``exit``,
``hang`` or ``memory`` makes the worker misbehave that way before certifying; it is accepted only when
the environment variable ``SIMCHECK_BATCH_TEST_FAULTS=1`` is set.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass
from pathlib import Path

import yaml

from simcheck.errors import SimcheckInputError
from simcheck.robot_spec_file import is_named_robot

__all__ = ["Entry", "ManifestError", "read_manifest", "ALL_MOVABLE", "FAULTS"]

#: the ``tasks`` value that means every prismatic (open-drawer) and revolute (open-door) joint
ALL_MOVABLE = "all-movable"
#: values of the internal ``_fault`` field
FAULTS = ("raise", "segfault", "exit", "hang", "memory")
_FAULTS_ENV = "SIMCHECK_BATCH_TEST_FAULTS"
_FIELDS = {"scene", "against", "scan", "labels", "truth", "tasks", "robot", "seed", "amount", "robust", "min_success",
           "_fault"}


class ManifestError(SimcheckInputError):
    """A manifest entry that cannot be used (the message names the file, line and field)."""


@dataclass(frozen=True)
class Entry:
    """One manifest entry, paths resolved.

    Attributes:
        line: 1-based line of the entry in the manifest.
        name: the entry's scene (or scan) path as written in the manifest (rows are named by it).
        scene: URDF to plan on, or None for a scan entry (its reconstruction is planned on).
        against: reference URDF to execute on (a scan's ``truth``), or None.
        scan, labels: the scan files of a scan entry, else None.
        tasks: task strings ("open-drawer:JOINT", ...) or None for all movable joints.
        robot: "default", "compliant" or a robot spec file path.
        seed: planning (and reconstruction) seed.
        amount: opening for every task (m or rad), or None for the default.
        robust: sampled worlds per task (``simcheck certify --robust N``), or None.
        min_success: the robust success rate a task needs (with ``robust``).
        fault: internal test hook (one of FAULTS) or None.
    """

    line: int
    name: str
    scene: Path | None
    against: Path | None
    scan: Path | None
    labels: Path | None
    tasks: tuple[str, ...] | None
    robot: str
    seed: int
    amount: float | None
    robust: int | None = None
    min_success: float = 0.9
    fault: str | None = None


def read_manifest(path: str | Path) -> list[Entry]:
    """Parse and check the manifest at ``path`` (YAML list, or JSON Lines for ``.jsonl``/``.ndjson``
    or a file whose first non-blank character is ``{``).

    Raises:
        ManifestError: naming ``path:LINE`` and the field at fault.
    """
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise ManifestError(f"manifest {path}: cannot be read ({exc.strerror or exc})") from exc
    raw = _json_lines(path, text) if _is_json_lines(path, text) else _yaml_entries(path, text)
    if not raw:
        raise ManifestError(f"manifest {path}: has no entry (expected a list of scene: or scan: entries)")
    return [_entry(path, line, doc, lines) for line, doc, lines in raw]


def _is_json_lines(path: Path, text: str) -> bool:
    if path.suffix.lower() in (".jsonl", ".ndjson"):
        return True
    if path.suffix.lower() in (".yaml", ".yml"):
        return False
    return text.lstrip().startswith("{")


def _json_lines(path: Path, text: str) -> list[tuple[int, dict, dict]]:
    out = []
    for i, line in enumerate(text.splitlines(), start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        try:
            doc = json.loads(line)
        except json.JSONDecodeError as exc:
            raise ManifestError(f"{path}:{i}: not a JSON object ({exc.msg} at column {exc.colno})") from exc
        if not isinstance(doc, dict):
            raise ManifestError(f"{path}:{i}: expected a JSON object per line, got {type(doc).__name__}")
        out.append((i, doc, {k: i for k in doc}))
    return out


class _LineLoader(yaml.SafeLoader):
    """A SafeLoader that remembers the line of every mapping and of each of its keys."""

    def construct_mapping(self, node, deep=False):
        mapping = super().construct_mapping(node, deep=True)
        mapping["__line__"] = node.start_mark.line + 1
        mapping["__lines__"] = {k.value: k.start_mark.line + 1 for k, _ in node.value}
        return mapping


def _yaml_entries(path: Path, text: str) -> list[tuple[int, dict, dict]]:
    try:
        doc = yaml.load(text, Loader=_LineLoader)  # noqa: S506 - a SafeLoader subclass
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{path}:{mark.line + 1}" if mark is not None else str(path)
        raise ManifestError(f"{where}: not valid YAML ({getattr(exc, 'problem', exc)})") from exc
    if doc is None:
        return []
    if isinstance(doc, dict) and "entries" in doc:
        doc = doc["entries"]
    if not isinstance(doc, list):
        raise ManifestError(f"{path}: expected a YAML list of entries (- scene: ... or - scan: ...)")
    out = []
    for i, item in enumerate(doc):
        if not isinstance(item, dict):
            raise ManifestError(f"{path}: entry {i + 1} is a {type(item).__name__}, expected a mapping "
                                "with scene: or scan:")
        line = item.pop("__line__")
        lines = item.pop("__lines__")
        out.append((line, item, lines))
    return out


def _entry(path: Path, line: int, doc: dict, lines: dict) -> Entry:
    def fail(field: str, what: str) -> ManifestError:
        return ManifestError(f"{path}:{lines.get(field, line)}: field {field!r}: {what}")

    unknown = sorted(set(doc) - _FIELDS)
    if "_fault" in doc and os.environ.get(_FAULTS_ENV) != "1":
        unknown = sorted(set(unknown) | {"_fault"})
    if unknown:
        from simcheck.file_schemas import unknown_key_hint

        raise fail(unknown[0], f"unknown field ({unknown_key_hint(unknown[0], _FIELDS - {'_fault'})})")
    if ("scene" in doc) == ("scan" in doc):
        raise ManifestError(f"{path}:{line}: an entry needs exactly one of 'scene' or 'scan'")
    base = path.parent

    def file(field: str, required: bool = False) -> Path | None:
        if field not in doc or doc[field] is None:
            if required:
                raise ManifestError(f"{path}:{line}: field {field!r} is missing")
            return None
        value = doc[field]
        if not isinstance(value, str) or not value:
            raise fail(field, f"expected a file path, got {value!r}")
        p = (base / value).resolve()
        if not p.is_file():
            raise fail(field, f"{p} is a folder, not a file" if p.is_dir() else f"file {p} does not exist")
        return p

    robust, min_success = doc.get("robust"), doc.get("min_success", 0.9)
    if robust is not None or "min_success" in doc:
        from simcheck.robust_spreads import check_robust_args

        if robust is None:
            raise fail("min_success", "needs 'robust' (the number of sampled worlds)")
        try:
            check_robust_args(robust, min_success)
        except SimcheckInputError as exc:
            raise fail(str(exc).split(":")[0], str(exc)) from exc
    if "scene" in doc:
        for field in ("labels", "truth"):
            if field in doc:
                raise fail(field, "belongs to a scan entry (scene entries use 'against')")
        scene, against, scan, labels = file("scene"), file("against"), None, None
    else:
        if "against" in doc:
            raise fail("against", "a scan entry names its reference with 'truth'")
        scene, scan, labels, against = None, file("scan"), file("labels", required=True), file("truth")
    seed = doc.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise fail("seed", f"expected a non-negative integer, got {seed!r}")
    amount = doc.get("amount")
    if amount is not None and (isinstance(amount, bool) or not isinstance(amount, (int, float))
                               or not (amount != 0 and math.isfinite(amount))):
        raise fail("amount", f"expected a non-zero number (m or rad; negative opens toward the lower limit), "
                             f"got {amount!r}")
    robot = doc.get("robot", "default")
    if not isinstance(robot, str) or not robot:
        raise fail("robot", f"expected 'default', 'compliant' or a robot spec file, got {robot!r}")
    if not is_named_robot(robot):
        robot = str(file("robot"))
    fault = doc.get("_fault")
    if fault is not None and fault not in FAULTS:
        raise fail("_fault", f"expected one of {FAULTS}, got {fault!r}")
    tasks = _tasks(doc.get("tasks", ALL_MOVABLE), fail)
    if scene is not None and tasks is not None:
        _check_tasks(scene, tasks, amount, fail)
    name = str(doc["scene"] if scene is not None else doc["scan"])
    return Entry(line, name, scene, against, scan, labels, tasks, robot, int(seed),
                 float(amount) if amount is not None else None, robust, float(min_success), fault)


def _tasks(value, fail) -> tuple[str, ...] | None:
    if value == ALL_MOVABLE:
        return None
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not value or not all(isinstance(t, str) for t in value):
        raise fail("tasks", f"expected {ALL_MOVABLE!r} or a list of KIND:JOINT strings, got {value!r}")
    if len(set(value)) != len(value):
        raise fail("tasks", "lists a task twice")
    return tuple(value)


def _check_tasks(scene: Path, tasks: tuple[str, ...], amount, fail) -> None:
    from simcheck.scene_joints import read_scene_joints
    from planners.task import check_task, parse_task
    from scenes.description import InputError

    try:
        joints = read_scene_joints(scene)
    except SimcheckInputError as exc:
        raise fail("scene", str(exc)) from exc
    for text in tasks:
        try:
            check_task(parse_task(text, amount), joints, scene)
        except InputError as exc:
            raise fail("tasks", str(exc)) from exc
