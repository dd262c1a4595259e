"""``--spreads FILE``: the spreads a robust certificate samples, from a YAML/JSON file.

Every key is optional; a key left out keeps its default (:data:`simcheck.robust_spreads.DEFAULT_SPREADS`).
``simcheck spreads`` prints the defaults in this format, one comment per key with its unit::

    physics:                        # uniform ranges [lo, hi] of what a scan cannot see
      joint_friction: [0.5, 2.5]    # N (drawer) or N*m (door), the task joint's Coulomb friction
      joint_damping: [0.5, 3.0]     # N*s/m or N*m*s/rad
      mass_scale: [0.7, 1.5]        # factor on the moving part's mass and inertia (> 0)
      handle_friction: [0.5, 1.0]   # lateral friction coefficient of the handle
    robot:                          # the robot's own errors
      base_xy_m: 0.014              # sigma (m) of the base position error per horizontal axis
      base_yaw_deg: 1.0             # sigma (deg) of its heading error
      handle_m: 0.005               # sigma (m) per axis of the handle position as perceived
      tracking_gain: [0.7, 1.3]     # uniform range of the factor on the arm's position gain (> 0)
      guarded_approach: true        # re-perceive the handle at the stand pose and correct the rest of the path
      reperception_m: 0.003         # sigma (m) per axis (x, y, z) of that re-perception
      reperception_yaw_deg: 0.5     # sigma (deg) of its heading
    joint_defaults:                 # the task joint's RMS spreads without recon's graph.json
      prismatic: {axis_deg: 1.0, origin_m: 0.005, upper: 0.02}
      revolute: {axis_deg: 1.0, origin_m: 0.01, upper: 0.05}

Every number must be finite and >= 0 (a range also lo <= hi; mass_scale and tracking_gain above 0). An
unknown key, a missing file or a bad value is a :class:`simcheck.errors.SimcheckInputError` (exit 2) naming
the file and the field.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

from simcheck.errors import SimcheckInputError
from simcheck.file_schemas import check_document, read_document
from simcheck.robust_spreads import DEFAULT_SPREADS, JointSpreads, PhysicsRanges, RobotErrors, RobustSpreads

__all__ = ["SPREADS_SCHEMA", "load_spreads", "spreads_yaml"]

_RANGE = {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2,
          "description": "a range [lo, hi] of two numbers"}
_SIGMA = {"type": "number", "description": "a number >= 0"}

#: comment per key of :func:`spreads_yaml` (unit, meaning); also the schema's descriptions
_DOC = {
    "physics": "uniform ranges [lo, hi] of what a scan cannot see",
    "physics.joint_friction": "N (drawer) or N*m (door), the task joint's Coulomb friction",
    "physics.joint_damping": "N*s/m or N*m*s/rad",
    "physics.mass_scale": "factor on the moving part's mass and inertia (> 0)",
    "physics.handle_friction": "lateral friction coefficient of the handle",
    "robot": "the robot's own errors",
    "robot.base_xy_m": "sigma (m) of the base position error per horizontal axis",
    "robot.base_yaw_deg": "sigma (deg) of its heading error",
    "robot.handle_m": "sigma (m) per axis of the handle position as perceived",
    "robot.tracking_gain": "uniform range of the factor on the arm's position gain (> 0)",
    "robot.guarded_approach": "re-perceive the handle at the stand pose and correct the rest of the path",
    "robot.reperception_m": "sigma (m) per axis (x, y, z) of that re-perception",
    "robot.reperception_yaw_deg": "sigma (deg) of its heading",
    "joint_defaults": "the task joint's RMS spreads without recon's graph.json (axis deg, origin m, upper m or rad)",
}


def _group(cls) -> dict:
    props = {}
    for f in dataclasses.fields(cls):
        if f.type in ("bool", bool):
            props[f.name] = {"type": "boolean", "description": "true or false"}
        else:
            props[f.name] = _RANGE if "tuple" in str(f.type) else _SIGMA
    return {"type": "object", "additionalProperties": False, "properties": props,
            "description": f"a mapping of {', '.join(props)}"}


_JOINT = {"type": "object", "additionalProperties": False, "description": "a mapping of axis_deg, origin_m, upper",
          "properties": {k: _SIGMA for k in ("axis_deg", "origin_m", "upper")}}

#: a spreads file (:func:`load_spreads`)
SPREADS_SCHEMA = {
    "type": "object", "additionalProperties": False,
    "description": "a mapping with physics, robot and joint_defaults (each optional)",
    "properties": {
        "physics": _group(PhysicsRanges),
        "robot": _group(RobotErrors),
        "joint_defaults": {"type": "object", "additionalProperties": False,
                           "description": "a mapping with prismatic and revolute",
                           "properties": {"prismatic": _JOINT, "revolute": _JOINT}},
    },
}

_POSITIVE = {"physics.mass_scale", "robot.tracking_gain"}


def _check_value(field: str, value, path) -> None:
    """Raise naming ``field`` when a number of ``value`` is NaN/inf/negative, a range is reversed, or a factor
    range reaches 0."""
    numbers = list(value) if isinstance(value, (list, tuple)) else [value]
    if isinstance(value, bool):
        return
    for v in numbers:
        if not math.isfinite(float(v)) or float(v) < 0.0:
            raise SimcheckInputError(f"spreads {path}: field {field!r} must be finite and >= 0, got {value!r}")
    if isinstance(value, (list, tuple)):
        if value[0] > value[1]:
            raise SimcheckInputError(f"spreads {path}: field {field!r} must be a range [lo, hi] with lo <= hi, "
                                     f"got {value!r}")
        if field in _POSITIVE and value[0] <= 0.0:
            raise SimcheckInputError(f"spreads {path}: field {field!r} is a factor: its range must be above 0, "
                                     f"got {value!r}")


def load_spreads(spreads) -> RobustSpreads:
    """The spreads of a robust certificate: ``None`` -> the defaults; a :class:`RobustSpreads` as it is;
    a path -> that YAML/JSON file over the defaults (module docstring).

    Raises:
        SimcheckInputError: a missing or unparsable file, an unknown key (with the closest valid one), a value
            of the wrong type, NaN, infinite or negative, or a reversed range (names the file and the field).
    """
    if spreads is None:
        return DEFAULT_SPREADS
    if isinstance(spreads, RobustSpreads):
        return spreads
    path = Path(spreads)
    if not path.is_file():
        raise SimcheckInputError(f"spreads {path} does not exist (a YAML file of spreads; `simcheck spreads` prints "
                                 "the defaults to start from)")
    doc = read_document(path, "spreads", SimcheckInputError)
    doc = {} if doc is None else doc
    check_document(doc, SPREADS_SCHEMA, "spreads", path, SimcheckInputError)
    base = DEFAULT_SPREADS
    groups = {}
    for group, current in (("physics", base.physics), ("robot", base.robot)):
        values = doc.get(group) or {}
        for key, v in values.items():
            _check_value(f"{group}.{key}", v, path)
        groups[group] = dataclasses.replace(current, **{k: tuple(v) if isinstance(v, list) else v
                                                        for k, v in values.items()})
    joints = dict(base.joint_defaults)
    for kind, values in (doc.get("joint_defaults") or {}).items():
        for key, v in values.items():
            _check_value(f"joint_defaults.{kind}.{key}", v, path)
        joints[kind] = dataclasses.replace(joints[kind], **values)
    return RobustSpreads(groups["physics"], groups["robot"], joints, source=str(path))


def spreads_yaml(spreads: RobustSpreads = DEFAULT_SPREADS) -> str:
    """``spreads`` in the format :func:`load_spreads` reads, one comment per key (what ``simcheck spreads``
    prints)."""
    def fmt(v) -> str:
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, tuple):
            return f"[{', '.join(fmt(x) for x in v)}]"
        return repr(float(v)) if isinstance(v, float) else str(v)

    lines = ["# robust certification spreads (simcheck certify --robust N --spreads FILE); every key optional"]
    for group, obj in (("physics", spreads.physics), ("robot", spreads.robot)):
        lines.append(f"{group + ':':<32}# {_DOC[group]}")
        for f in dataclasses.fields(obj):
            lines.append(f"{f'  {f.name}: {fmt(getattr(obj, f.name))}':<32}# {_DOC[f'{group}.{f.name}']}")
    lines.append(f"{'joint_defaults:':<32}# {_DOC['joint_defaults']}")
    for kind in ("prismatic", "revolute"):
        j: JointSpreads = spreads.joint_defaults[kind]
        lines.append(f"  {kind}: {{axis_deg: {fmt(j.axis_deg)}, origin_m: {fmt(j.origin_m)}, upper: {fmt(j.upper)}}}")
    return "\n".join(lines) + "\n"
