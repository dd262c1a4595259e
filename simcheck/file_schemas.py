"""JSON Schemas of the files simcheck reads (a scenario, a robot spec) and :func:`check_document`, which
turns every way a document breaks its schema into one message naming the file, the field and what to do.

An unknown key is an error, with the closest valid key suggested (``againts:`` -> "did you mean
'against'?"): a misspelt optional field would otherwise be silently ignored. Every property schema has a
``description`` saying what the field must be; it is the message's expectation when the value is wrong.
"""

from __future__ import annotations

import difflib
from pathlib import Path

from planners.task import ACTIONS

__all__ = ["SCENARIO_SCHEMA", "ROBOT_SPEC_SCHEMA", "check_document", "read_document", "schema_problems",
           "unknown_key_hint"]

_NAMES = {"type": "array", "items": {"type": "string"}, "description": "a list of names"}
_NUMBERS = {"type": "array", "items": {"type": "number"}, "description": "a list of numbers"}
_POINT = {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3,
          "description": "a point [x, y, z] in metres (world frame, joint closed)"}

#: ``SCENARIO.yaml`` (:mod:`simcheck.scenario`); a task is a string or a mapping
SCENARIO_SCHEMA = {
    "type": "object", "required": ["scene", "tasks"], "additionalProperties": False,
    "description": "a mapping with 'scene' and 'tasks'",
    "properties": {
        "scene": {"type": "string", "description": "the path of the scene URDF to plan on"},
        "against": {"type": ["string", "null"], "description": "the path of a reference URDF, or null"},
        "robot": {"type": "string", "description": "'default', 'compliant' or the path of a robot spec file"},
        "seed": {"type": "integer", "description": "an integer"},
        "tasks": {
            "type": "array", "minItems": 1, "description": "a non-empty list",
            "items": {
                "type": ["string", "object"], "additionalProperties": False,
                "description": "'open-drawer:JOINT' or a mapping such as {kind: open-door, joint: JOINT}",
                "properties": {
                    "kind": {"type": "string", "enum": list(ACTIONS),
                             "description": "'open-drawer', 'open-door', 'close-drawer' or 'close-door'"},
                    "joint": {"type": "string", "description": "a joint name"},
                    **{action: {"type": "string", "description": "a joint name"} for action in ACTIONS},
                    "amount": {"type": "number", "not": {"const": 0},
                               "description": "a non-zero opening, m (drawer) or rad (door); negative "
                                              "opens toward the lower limit"},
                    "from": {"type": "number", "not": {"const": 0},
                             "description": "for a close task, how far open the part starts: a non-zero "
                                            "opening, m (drawer) or rad (door)"},
                    "grasp_point": _POINT,
                    "grasp_link": {"type": "string", "description": "a link name"},
                    "plan": {"type": "string", "description": "the path of a plan file (partscene.plan/1)"},
                },
            },
        },
    },
}

#: a robot spec file (:mod:`simcheck.robot_spec_file`): the fields of ``planners.RobotSpec``
ROBOT_SPEC_SCHEMA = {
    "type": "object", "additionalProperties": False,
    "required": ["urdf", "base_joints", "arm_joints", "finger_joints", "tool_frame", "base_link", "gripper_links",
                 "home"],
    "description": "a mapping of planners.RobotSpec fields",
    "properties": {
        "urdf": {"type": "string", "description": "the path of the robot URDF (relative to the spec file)"},
        "base_joints": {**_NAMES, "minItems": 3, "maxItems": 3, "description": "three names (x, y, yaw)"},
        "arm_joints": _NAMES,
        "finger_joints": _NAMES,
        "tool_frame": {"type": "string", "description": "a link name"},
        "base_link": {"type": "string", "description": "a link name"},
        "gripper_links": _NAMES,
        "home": {**_NUMBERS, "description": "one number per base and arm joint (m, rad)"},
        "ignore_pairs": {"type": "array", "description": "a list of [link, link] pairs",
                         "items": {"type": "array", "items": {"type": "string"}, "minItems": 2, "maxItems": 2,
                                   "description": "a [link, link] pair"}},
        "finger_open": {"type": "number", "description": "a finger opening in metres"},
        "finger_closed": {"type": "number", "description": "a finger opening in metres"},
        "max_finger_force": {"type": "number", "exclusiveMinimum": 0, "description": "a force in newtons"},
        "max_acceleration": {**_NUMBERS, "description": "one acceleration limit per base and arm joint (m/s^2, rad/s^2)"},
        "joint_stiffness": {**_NUMBERS, "description": "one joint stiffness per arm joint (N*m/rad, N/m)"},
        "gripper": {
            "type": "object", "additionalProperties": False,
            "description": "a mapping with grip_force (N) and pad_friction",
            "properties": {
                "grip_force": {"type": "number", "exclusiveMinimum": 0, "description": "a force in newtons"},
                "pad_friction": {"type": "number", "exclusiveMinimum": 0, "description": "a friction coefficient"},
            },
        },
    },
}


def _where(path) -> str:
    """``tasks[1].amount`` from a JSON path such as ``["tasks", 1, "amount"]``."""
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def unknown_key_hint(key, valid) -> str:
    """``"did you mean 'against'?"`` for the valid key closest to ``key`` (difflib), else the valid keys.

    >>> unknown_key_hint("againts", ["scene", "against", "tasks"])
    "did you mean 'against'?"
    """
    valid = sorted(valid)
    close = difflib.get_close_matches(str(key), valid, n=1)
    return f"did you mean {close[0]!r}?" if close else f"valid fields: {', '.join(valid)}"


def _problem(error) -> str:
    where = _where(error.absolute_path)
    at = f"{where}: " if where else ""
    if error.validator == "additionalProperties":
        valid = error.schema.get("properties", {})
        return "; ".join(f"{at}unknown field {key!r} ({unknown_key_hint(key, valid)})"
                         for key in sorted(k for k in error.instance if k not in valid))
    if error.validator == "required":
        missing = [k for k in error.validator_value if k not in error.instance]
        return "; ".join(f"{at}field {k!r} is missing" for k in missing)
    expected = error.schema.get("description", error.message)
    field = f"field {where!r}" if where else "the document"
    return f"{field} must be {expected}, got {error.instance!r}"


def schema_problems(doc, schema: dict) -> list[str]:
    """Every way ``doc`` breaks ``schema``, one message each (field path, what it must be), in file order of
    the fields; ``[]`` if it conforms."""
    import jsonschema

    errors = sorted(jsonschema.Draft202012Validator(schema).iter_errors(doc),
                    key=lambda e: [str(p) for p in e.absolute_path])
    return [_problem(e) for e in errors]


def check_document(doc, schema: dict, what: str, path: str | Path, error: type[Exception]) -> None:
    """Raise ``error("<what> <path>: <problem>; <problem>...")`` if ``doc`` breaks ``schema``
    (:func:`schema_problems`); ``what`` names the kind of file ("scenario", "robot spec")."""
    problems = schema_problems(doc, schema)
    if problems:
        raise error(f"{what} {path}: {'; '.join(problems)}")


def read_document(path: Path, what: str, error: type[Exception]):
    """The document in ``path``: JSON for a ``.json`` file, else YAML. Raises ``error("<what> <path> cannot be
    parsed: ...")`` when it cannot be read or parsed."""
    try:
        if path.suffix.lower() == ".json":
            import json
            return json.loads(path.read_text())
        import yaml
        return yaml.safe_load(path.read_text())
    except Exception as exc:
        raise error(f"{what} {path} cannot be parsed: {exc}") from exc
