"""``--robot SPEC``: a named robot (:data:`ROBOT_NAMES`: ``default``, or ``compliant`` -- the default robot
under the softer joint impedance of ``planners.robot.PANDA_COMPLIANT_JOINT_STIFFNESS``), or a robot described
in a YAML/JSON file.

A robot spec file holds the fields of ``planners.RobotSpec`` (``urdf`` relative to the file)::

    urdf: my_robot.urdf
    base_joints: [base_x, base_y, base_yaw]
    arm_joints: [j1, j2, j3, j4, j5, j6]
    finger_joints: [finger_left, finger_right]
    tool_frame: tool
    base_link: base_link
    gripper_links: [hand, finger_left_link, finger_right_link]
    home: [0, 0, 0, 0, -0.8, 0, -2.3, 0, 1.6]
    finger_open: 0.04
    finger_closed: 0.0
    gripper: {grip_force: 70, pad_friction: 1.0}   # what the grasp can hold
    joint_stiffness: [3000, 3000, 3000, 2500, 2500, 2000]   # N*m/rad per arm joint (optional)

``gripper`` (optional; default the Franka Hand, see ``planners.robot.GripperModel``) bounds the force an
executed grasp transmits: ``2 * pad_friction * grip_force`` N. Any other key is an error naming it and
the closest valid key (:mod:`simcheck.file_schemas`).
"""

from __future__ import annotations

from pathlib import Path

from simcheck.errors import RobotBindingError
from simcheck.file_schemas import ROBOT_SPEC_SCHEMA, check_document, read_document

__all__ = ["load_robot_spec", "is_named_robot", "ROBOT_NAMES"]

ROBOT_NAMES = ("default", "compliant")
"""Robots ``--robot`` names instead of a spec file: ``planners.default_robot()`` and
``planners.default_robot(compliant=True)``."""


def is_named_robot(spec) -> bool:
    """True when ``spec`` names a built-in robot (None and "" mean "default") rather than a spec file."""
    return spec in (None, "") or spec in ROBOT_NAMES


def load_robot_spec(spec: str | None):
    """``planners.RobotSpec`` for ``spec`` ("default"/None, or a .yaml/.json file).

    Raises:
        RobotBindingError: unreadable file, a missing, ill-typed or unknown field (names the file and the
            field, and for an unknown field the closest valid one; :data:`simcheck.file_schemas.ROBOT_SPEC_SCHEMA`),
            or fields planners rejects (names the file).
    """
    import planners

    if is_named_robot(spec):
        return planners.default_robot(compliant=spec == "compliant")
    path = Path(spec)
    if not path.is_file():
        raise RobotBindingError(f"robot spec {path} does not exist (use --robot {' / '.join(ROBOT_NAMES)} or a "
                               f"YAML/JSON file)")
    doc = read_document(path, "robot spec", RobotBindingError)
    check_document(doc, ROBOT_SPEC_SCHEMA, "robot spec", path, RobotBindingError)
    doc = dict(doc)
    doc["urdf"] = (path.parent / doc["urdf"]).resolve()
    for key in ("base_joints", "arm_joints", "finger_joints", "gripper_links", "home", "max_acceleration", "joint_stiffness"):
        if key in doc:
            doc[key] = tuple(doc[key])
    if "ignore_pairs" in doc:
        doc["ignore_pairs"] = tuple(tuple(p) for p in doc["ignore_pairs"])
    try:
        return planners.RobotSpec(**doc)
    except (TypeError, ValueError) as exc:
        raise RobotBindingError(f"robot spec {path}: {exc}") from exc
