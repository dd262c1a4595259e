"""Plan files (``partscene.plan/1``): a user's own plan -- robot joint waypoints with their timing, gripper
commands and what each segment is meant to do to the world -- read into and written from a
:class:`GivenPlan` of ``planners.Segment``\\ s (the planner's own segment type, with ``t``, ``command`` and
``expect`` set). Format: docs/plan_format.md. Engine-free (numpy, json, jsonschema).

    plan = read_plan("drawer.plan.json")             # PlanFileError (exit 2) naming the field if malformed
    write_plan(plan, "copy.plan.json")

Why here and not in ``planners``: simcheck is what reads these files (``simcheck certify-plan``) and writes
them (``simcheck certify --save-plan`` records the timing its executor gave the planner's plan); the
in-memory type stays the planner's :class:`planners.task.Segment`.

A plan's checks: the schema (:data:`PLAN_SCHEMA`, unknown keys refused), then what a schema cannot say --
one row of ``len(joint_names)`` finite numbers per waypoint, ``t`` (one time per waypoint, 0 first,
increasing) or ``dt`` (> 0), unique segment and joint names, an expectation's ``from`` != ``to``. Each
problem names the file and the field (``segments[1].waypoints[3][4] (panda_joint2)``). Whether the joint
names are the robot's is checked against the robot (:mod:`simcheck.given_plan`).
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from planners.task import GRIPPER_COMMANDS, Expectation, Segment
from simcheck.errors import PlanFileError
from simcheck.file_schemas import check_document
from simcheck.robot_spec_file import is_named_robot

__all__ = ["PLAN_FORMAT", "PLAN_SCHEMA", "GivenPlan", "read_plan", "plan_from_dict", "plan_to_dict", "write_plan",
           "plan_from_arrays", "join_plans"]

PLAN_FORMAT = "partscene.plan/1"

_ROWS = {"type": "array", "minItems": 1, "items": {"type": "array", "items": {"type": "number"},
                                                   "description": "a list of numbers"},
         "description": "a non-empty list of rows of numbers"}

#: the JSON schema of a plan file (semantic checks follow in :func:`plan_from_dict`)
PLAN_SCHEMA = {
    "type": "object", "additionalProperties": False, "required": ["format", "joint_names", "segments"],
    "description": "a mapping with 'format', 'joint_names' and 'segments'",
    "properties": {
        "format": {"type": "string", "description": f"the string {PLAN_FORMAT!r}"},
        "robot": {"type": "string", "description": "'default', 'compliant' or the path of a robot spec file"},
        "joint_names": {"type": "array", "minItems": 1, "items": {"type": "string"},
                        "description": "a non-empty list of the robot's joint names (base x, y, yaw first)"},
        "segments": {
            "type": "array", "minItems": 1, "description": "a non-empty list of segments",
            "items": {
                "type": "object", "additionalProperties": False, "required": ["name", "waypoints", "gripper"],
                "description": "a mapping with 'name', 'waypoints', 'gripper' and 't' or 'dt'",
                "properties": {
                    "name": {"type": "string", "minLength": 1, "description": "a non-empty name"},
                    "t": {"type": "array", "items": {"type": "number"},
                          "description": "one time per waypoint, seconds from the segment's start"},
                    "dt": {"type": "number", "description": "the time between waypoints, seconds (> 0)"},
                    "waypoints": _ROWS,
                    "gripper": {"type": "string", "enum": list(GRIPPER_COMMANDS),
                                "description": "'open', 'close' or 'hold'"},
                    "expect": {
                        "type": "object", "additionalProperties": False, "required": ["joint", "from", "to"],
                        "description": "a mapping {joint: NAME, from: VALUE, to: VALUE}",
                        "properties": {"joint": {"type": "string", "description": "a scene joint name"},
                                       "from": {"type": "number", "description": "a joint value, m or rad"},
                                       "to": {"type": "number", "description": "a joint value, m or rad"}}},
                    "tool_positions": {**_ROWS, "description": "one [x, y, z] per waypoint, metres, world frame"},
                },
            },
        },
    },
}


@dataclass(frozen=True)
class GivenPlan:
    """A plan read from a file (or made from arrays).

    Attributes:
        robot: ``"default"`` or the path of a robot spec file (resolved against the plan file's folder).
        joint_names: the columns of every segment's ``q`` (as the file gives them).
        segments: ``planners.Segment``\\ s with ``t`` (s), ``command`` and ``expect`` set; ``object_q`` NaN and
            ``T_world_tool`` NaN (a plan file gives joint positions; the tool path is known once the robot is,
            except the positions a file gives as ``tool_positions``); ``gripper`` is the fingers' state
            while the segment moves ("open" until a ``close`` segment's end, "closed" after it).
        source: the file it was read from (or ``"<arrays>"``).
    """

    robot: str
    joint_names: tuple[str, ...]
    segments: tuple[Segment, ...]
    source: str = "<arrays>"

    @property
    def expectations(self) -> tuple[tuple[int, Expectation], ...]:
        """(segment index, expectation) of every segment that has one, in order."""
        return tuple((i, s.expect) for i, s in enumerate(self.segments) if s.expect is not None)

    def isclose(self, other: "GivenPlan", atol: float = 1e-9) -> bool:
        """Same robot, joints, segment names, commands, expectations, times and waypoints (within ``atol``)."""
        return (self.robot == other.robot and self.joint_names == other.joint_names
                and len(self.segments) == len(other.segments)
                and all(a.name == b.name and a.command == b.command and a.expect == b.expect
                        and a.q.shape == b.q.shape and np.allclose(a.q, b.q, atol=atol)
                        and np.allclose(a.t, b.t, atol=atol) for a, b in zip(self.segments, other.segments)))


def _fail(source, problem: str) -> PlanFileError:
    return PlanFileError(f"plan {source}: {problem}")


def _segment(doc: dict, i: int, names: tuple[str, ...], fingers_open: bool, source) -> tuple[Segment, bool]:
    where = f"segments[{i}]"
    rows = doc["waypoints"]
    dof = len(names)
    for k, row in enumerate(rows):
        if len(row) != dof:
            raise _fail(source, f"field '{where}.waypoints[{k}]' has {len(row)} values, 'joint_names' has {dof} "
                                f"(one column per joint: {', '.join(names)})")
        for j, v in enumerate(row):
            if not math.isfinite(v):
                raise _fail(source, f"field '{where}.waypoints[{k}][{j}]' ({names[j]}) is {v}, not a finite number")
    q = np.asarray(rows, dtype=float).reshape(len(rows), dof)
    n = len(q)
    if ("t" in doc) == ("dt" in doc):
        raise _fail(source, f"segment '{where}' ({doc['name']!r}) needs exactly one of 't' (one time per "
                            f"waypoint) or 'dt' (the step between waypoints), got "
                            f"{'both' if 't' in doc else 'neither'}")
    if "dt" in doc:
        dt = doc["dt"]
        if not (math.isfinite(dt) and dt > 0):
            raise _fail(source, f"field '{where}.dt' must be a positive number of seconds, got {dt!r}")
        t = dt * np.arange(n, dtype=float)
    else:
        t = np.asarray(doc["t"], dtype=float)
        if len(t) != n:
            raise _fail(source, f"field '{where}.t' has {len(t)} times for {n} waypoints")
        bad = np.flatnonzero(~np.isfinite(t))
        if len(bad):
            raise _fail(source, f"field '{where}.t[{bad[0]}]' is {t[bad[0]]}, not a finite number")
        if t[0] != 0.0:
            raise _fail(source, f"field '{where}.t[0]' must be 0 (times are seconds from the segment's start), "
                                f"got {t[0]!r}")
        back = np.flatnonzero(np.diff(t) <= 0)
        if len(back):
            k = int(back[0]) + 1
            raise _fail(source, f"field '{where}.t[{k}]' = {t[k]!r} does not increase (t[{k - 1}] = {t[k - 1]!r})")
    T = np.full((n, 4, 4), np.nan)
    if "tool_positions" in doc:
        p = doc["tool_positions"]
        if len(p) != n or any(len(r) != 3 or not all(math.isfinite(v) for v in r) for r in p):
            raise _fail(source, f"field '{where}.tool_positions' must be {n} rows of 3 finite numbers (x, y, z)")
        T[:, :3, 3] = np.asarray(p, dtype=float)
    expect = None
    if "expect" in doc:
        e = doc["expect"]
        if not (math.isfinite(e["from"]) and math.isfinite(e["to"])) or e["from"] == e["to"]:
            raise _fail(source, f"field '{where}.expect' must move joint {e['joint']!r}: 'from' and 'to' finite and "
                                f"different, got from {e['from']!r} to {e['to']!r}")
        expect = Expectation(e["joint"], float(e["from"]), float(e["to"]))
    command = doc["gripper"]
    moving_open = True if command == "open" else fingers_open
    seg = Segment(doc["name"], q, np.full(n, np.nan), T, "open" if moving_open else "closed", t=t, command=command,
                  expect=expect)
    return seg, (False if command == "close" else moving_open)


def plan_from_dict(doc, source="<dict>", base: Path | None = None) -> GivenPlan:
    """Check a plan document (parsed JSON) and return the :class:`GivenPlan`; ``base``: the folder a relative
    robot spec path is resolved against.

    Raises:
        PlanFileError: naming ``source`` and the field (segment index, waypoint index, column and joint).
    """
    if isinstance(doc, dict) and "format" in doc and doc["format"] != PLAN_FORMAT:
        raise _fail(source, f"field 'format' is {doc['format']!r}: this partscene reads {PLAN_FORMAT!r} (a newer "
                            "format needs a newer partscene)")
    check_document(doc, PLAN_SCHEMA, "plan", source, PlanFileError)
    names = tuple(doc["joint_names"])
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise _fail(source, f"field 'joint_names' names {dup[0]!r} twice")
    seg_names = [s["name"] for s in doc["segments"]]
    dup = sorted({n for n in seg_names if seg_names.count(n) > 1})
    if dup:
        raise _fail(source, f"field 'segments': two segments are called {dup[0]!r} (names must be unique: reasons "
                            "name the segment)")
    segments, fingers_open = [], True
    for i, s in enumerate(doc["segments"]):
        seg, fingers_open = _segment(s, i, names, fingers_open, source)
        segments.append(seg)
    robot = str(doc.get("robot", "default"))
    if not is_named_robot(robot) and base is not None:
        robot = str((base / robot).resolve())
    return GivenPlan(robot=robot, joint_names=names, segments=tuple(segments), source=str(source))


def read_plan(path: str | Path) -> GivenPlan:
    """Read and check the plan file at ``path`` (:func:`plan_from_dict`).

    Raises:
        PlanFileError: missing file, not JSON, or a malformed field (named).
    """
    path = Path(path)
    if not path.is_file():
        raise PlanFileError(f"plan {path} does not exist")
    try:
        doc = json.loads(path.read_text())
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise PlanFileError(f"plan {path} is not valid JSON: {exc}") from exc
    return plan_from_dict(doc, path, path.parent)


def plan_to_dict(plan: GivenPlan) -> dict:
    """The JSON-ready document of ``plan`` (every segment written with ``t``; ``tool_positions`` when known)."""
    segs = []
    for s in plan.segments:
        d = {"name": s.name, "t": [float(v) for v in s.t], "waypoints": s.q.tolist(), "gripper": s.command}
        tool = s.T_world_tool[:, :3, 3]
        if np.isfinite(tool).all():
            d["tool_positions"] = tool.tolist()
        if s.expect is not None:
            d["expect"] = {"joint": s.expect.joint, "from": s.expect.start, "to": s.expect.end}
        segs.append(d)
    return {"format": PLAN_FORMAT, "robot": plan.robot, "joint_names": list(plan.joint_names), "segments": segs}


#: a JSON list of numbers only (no nested list or object), as ``json.dumps(indent=...)`` spreads it over lines
_NUMBER_LIST = re.compile(r"\[\s+([-+0-9.eE,\s]+?)\s+\]")


def write_plan(plan: GivenPlan, path: str | Path) -> Path:
    """Write ``plan`` to ``path`` as JSON (one line per waypoint, numbers at full precision), atomically;
    returns the path."""
    from scenes.description import write_text_atomic

    text = json.dumps(plan_to_dict(plan), indent=1, allow_nan=False)
    text = _NUMBER_LIST.sub(lambda m: "[" + re.sub(r",\s+", ", ", m.group(1)) + "]", text)
    return write_text_atomic(Path(path), text + "\n")


def plan_from_arrays(waypoints, joint_names, *, t=None, dt=None, gripper: str = "hold", name: str = "plan",
                     expect: dict | Expectation | None = None, robot: str = "default") -> GivenPlan:
    """A one-segment plan from arrays: ``waypoints`` (n, dof) robot joint positions (m, rad) whose columns are
    ``joint_names``, reached at times ``t`` (n,) s (0 first, increasing) or every ``dt`` s; ``gripper`` one of
    ``open``, ``close``, ``hold``; ``expect`` ``{"joint": J, "from": a, "to": b}`` or an Expectation.
    Checked as a file is (:func:`plan_from_dict`). Join several with :func:`join_plans`."""
    return plan_from_dict(_arrays_doc(waypoints, joint_names, t, dt, gripper, name, expect, robot), "<arrays>")


def _arrays_doc(waypoints, joint_names, t, dt, gripper, name, expect, robot) -> dict:
    seg = {"name": name, "waypoints": np.asarray(waypoints, dtype=float).tolist(), "gripper": gripper}
    if t is not None:
        seg["t"] = np.asarray(t, dtype=float).reshape(-1).tolist()
    if dt is not None:
        seg["dt"] = float(dt)
    if isinstance(expect, Expectation):
        expect = {"joint": expect.joint, "from": expect.start, "to": expect.end}
    if expect is not None:
        seg["expect"] = dict(expect)
    return {"format": PLAN_FORMAT, "robot": robot, "joint_names": list(joint_names), "segments": [seg]}


def join_plans(*plans: GivenPlan) -> GivenPlan:
    """One plan of the segments of ``plans`` in order (same robot and joint names; checked as a file is). A
    segment name already used by an earlier plan gets the plan's number (1-based): the second plan's
    ``open`` becomes ``open_2`` (segment names are unique in a plan)."""
    docs = [plan_to_dict(p) for p in plans]
    for p in plans[1:]:
        if p.joint_names != plans[0].joint_names or p.robot != plans[0].robot:
            raise PlanFileError("join_plans: the plans have different robots or joint names")
    segments, used = [], set()
    for k, d in enumerate(docs):
        for s in d["segments"]:
            name = s["name"] if s["name"] not in used else f"{s['name']}_{k + 1}"
            segments.append({**s, "name": name})
            used.add(name)
    return plan_from_dict({**docs[0], "segments": segments}, "<arrays>")
