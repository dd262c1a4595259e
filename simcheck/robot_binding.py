"""What simcheck needs to know about a robot, and how it is read from a ``planners.RobotSpec``.

A :class:`SimRobot` names the robot's URDF, the controlled joints (in the column order of a plan's
``q``), the finger joints with their open/closed positions, the tool link the grasp attaches to, and
the gripper links whose contact with a handle is expected. Any robot whose description provides these
can be certified; simcheck never hard-codes a robot.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from planners.robot import GripperModel
from simcheck.errors import RobotBindingError

__all__ = ["SimRobot", "sim_robot_from_spec"]


@dataclass(frozen=True)
class SimRobot:
    """A robot as simcheck drives it.

    Attributes:
        urdf: the robot URDF (loaded with a fixed base at the world origin; a mobile base is modelled by
            base joints, e.g. prismatic x, prismatic y, revolute yaw).
        joint_names: controlled joints, in the column order of a plan's ``q`` (base joints first).
        finger_joints: the gripper's finger joints (commanded together, open or closed).
        finger_open: finger joint positions when open, one per finger joint (m or rad).
        finger_closed: finger joint positions commanded to close (past contact: the fingers stop on
            the handle, squeezing it with ``finger_force``).
        finger_force: maximum force of each finger motor, N.
        tool_link: link whose frame is the plan's tool frame; the grasp attachment is made to it.
        gripper_links: links allowed to touch the handle (hand, fingers, tool).
        finger_links: links that must touch the handle before the grasp is made.
        base_links: links allowed to touch the floor (the mobile base).
        gripper: what the gripper holds (``planners.robot.GripperModel``): the grasp's force bound.
        max_acceleration: acceleration limits of ``joint_names``, m/s^2 or rad/s^2 (empty: not given).
        joint_stiffness: (joint name, stiffness) pairs, N*m/rad (N/m for a prismatic joint): the joint
            impedance under which the real arm follows a plan; the grasp's spring is the tool's Cartesian
            stiffness under it (:meth:`simcheck.world.World.attach`). Empty: an isotropic spring of
            ``PhysicsConfig.grasp_stiffness``.
    """

    urdf: Path
    joint_names: tuple[str, ...]
    finger_joints: tuple[str, ...]
    finger_open: tuple[float, ...]
    finger_closed: tuple[float, ...]
    tool_link: str
    gripper_links: tuple[str, ...]
    finger_links: tuple[str, ...]
    base_links: tuple[str, ...] = ()
    finger_force: float = 40.0
    gripper: GripperModel = GripperModel()
    max_acceleration: tuple[float, ...] = ()
    joint_stiffness: tuple[tuple[str, float], ...] = ()

    def __post_init__(self) -> None:
        if not Path(self.urdf).is_file():
            raise RobotBindingError(f"robot URDF {self.urdf} does not exist")
        if len(self.finger_open) != len(self.finger_joints) or len(self.finger_closed) != len(self.finger_joints):
            raise RobotBindingError(f"robot {self.urdf}: finger_open/finger_closed need one value per finger "
                                    f"joint {self.finger_joints}")
        if not self.joint_names:
            raise RobotBindingError(f"robot {self.urdf}: no controlled joints")


def _first(spec, names: tuple[str, ...], default=None):
    for name in names:
        if hasattr(spec, name):
            value = getattr(spec, name)
            if value is not None:
                return value
    return default


def sim_robot_from_spec(spec) -> SimRobot:
    """A :class:`SimRobot` from a ``planners.RobotSpec`` (or any object with the same fields).

    Reads ``urdf``, ``joint_names`` (else base + arm joints), ``finger_joints``, ``finger_open`` /
    ``finger_closed`` (one value for all fingers, or one each), ``tool_frame``, ``gripper_links``,
    ``finger_links`` (default: the gripper links named "*finger*"), ``base_link(s)`` and
    ``max_finger_force`` and ``gripper`` (default :class:`GripperModel`); a :class:`SimRobot` is returned unchanged.

    Raises:
        RobotBindingError: a required field is missing (names it).
    """
    if isinstance(spec, SimRobot):
        return spec
    urdf = _first(spec, ("urdf", "urdf_path"))
    if urdf is None:
        raise RobotBindingError(f"robot spec {type(spec).__name__} has no urdf/urdf_path")
    joints = _first(spec, ("joint_names", "controlled_joints"))
    if joints is None:
        joints = tuple(_first(spec, ("base_joints",), ())) + tuple(_first(spec, ("arm_joints",), ()))
    fingers = tuple(_first(spec, ("gripper_joints", "finger_joints"), ()))
    f_open = _first(spec, ("gripper_open", "finger_open"))
    f_closed = _first(spec, ("gripper_closed", "finger_closed"))
    if f_open is None or f_closed is None:
        raise RobotBindingError(f"robot {urdf}: spec needs gripper_open and gripper_closed positions")
    n = len(fingers)
    f_open = tuple(float(v) for v in (f_open if hasattr(f_open, "__len__") else [f_open] * n))
    f_closed = tuple(float(v) for v in (f_closed if hasattr(f_closed, "__len__") else [f_closed] * n))
    tool = _first(spec, ("tool_link", "tool_frame"))
    if tool is None:
        raise RobotBindingError(f"robot {urdf}: spec names no tool_frame/tool_link")
    gripper_links = tuple(_first(spec, ("gripper_links",), ()))
    finger_links = tuple(_first(spec, ("finger_links",), ()))
    if not finger_links:
        finger_links = tuple(l for l in gripper_links if "finger" in l)
    return SimRobot(urdf=Path(urdf), joint_names=tuple(joints), finger_joints=fingers, finger_open=f_open,
                    finger_closed=f_closed, tool_link=str(tool),
                    gripper_links=tuple(gripper_links) or (str(tool),) + finger_links,
                    finger_links=finger_links, base_links=_base_links(spec),
                    finger_force=float(_first(spec, ("finger_force", "max_finger_force", "gripper_force"), 40.0)),
                    gripper=_first(spec, ("gripper",), GripperModel()), joint_stiffness=_joint_stiffness(spec),
                    max_acceleration=tuple(float(v) for v in _first(spec, ("max_acceleration",), ())))


def _joint_stiffness(spec) -> tuple[tuple[str, float], ...]:
    """(joint, stiffness) pairs: ``spec.joint_stiffness`` as such pairs or a mapping, or one value per
    ``spec.arm_joints``; () when the spec has none."""
    value = _first(spec, ("joint_stiffness",), ())
    if isinstance(value, dict):
        return tuple((str(k), float(v)) for k, v in value.items())
    value = tuple(value)
    if value and isinstance(value[0], (tuple, list)):
        return tuple((str(k), float(v)) for k, v in value)
    arm = tuple(_first(spec, ("arm_joints",), ()))
    if value and len(value) != len(arm):
        raise RobotBindingError(f"robot spec: joint_stiffness has {len(value)} values for the {len(arm)} arm joints {arm}")
    return tuple((n, float(v)) for n, v in zip(arm, value))


def _base_links(spec) -> tuple[str, ...]:
    links = _first(spec, ("base_links",), None)
    if links is not None:
        return tuple(links)
    one = _first(spec, ("base_link",), None)
    return (str(one),) if one else ()
