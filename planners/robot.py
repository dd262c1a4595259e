"""The robot description: one URDF (loaded by PyBullet and pinocchio alike) plus a small :class:`RobotSpec`.

The default robot is a planar mobile base (prismatic x, prismatic y, revolute yaw, then a box body) with a
prismatic torso lift (a column that raises the arm, as mobile manipulators have) that carries the 7-DOF
Franka Panda with its parallel gripper from ``pybullet_data``. The lift is the first arm joint: planners
move it like any arm joint, and a robot spec without it (``arm_joints`` the seven Panda joints) keeps the
arm at the lift's lowest position.

Mesh paths: the Panda meshes ship with the pip-installed ``pybullet_data`` package, so nothing is copied
into git. At first use :func:`default_robot` writes the combined URDF into a cache directory
(``$PARTSCENE_CACHE``, else ``$XDG_CACHE_HOME/partscene``, else ``~/.cache/partscene``) with the
``package://meshes/...`` references of ``panda.urdf`` rewritten to absolute paths inside the installed
``pybullet_data``. Absolute paths load unchanged in PyBullet, pinocchio and yourdfpy, so no consumer needs
to know about package directories. The file name carries a hash of its content, so a changed description
or a moved ``pybullet_data`` gives a new file instead of a stale one; it is written atomically.

Robots are pluggable: any URDF whose root is the world, with the base joints, arm joints, finger joints
and a tool frame named in a :class:`RobotSpec`, is planned for without planner changes.
"""

from __future__ import annotations

import math

import hashlib
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from scenes.description import write_text_atomic

__all__ = ["RobotSpec", "GripperModel", "default_robot", "robot_cache_dir", "PANDA_HOME", "PANDA_JOINT_STIFFNESS",
           "PANDA_COMPLIANT_JOINT_STIFFNESS"]

#: Panda arm joint acceleration limits, rad/s^2 (Franka Emika's published joint limits, libfranka docs).
PANDA_MAX_ACCELERATION = (15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0)
#: the default base's acceleration limits (x, y m/s^2, yaw rad/s^2): an ASSUMPTION, not a vendor figure --
#: what simcheck's executor asks of the base (docs/decisions.md, "Given plans"); set a real base's own.
BASE_MAX_ACCELERATION = (4.0, 4.0, 4.0)

#: Panda arm home configuration (rad): elbow up, hand pointing down in front of the base.
PANDA_HOME = (0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785)
#: Joint stiffness, N*m/rad, of the Panda's internal joint impedance controller under which it follows a
#: joint trajectory: the values libfranka's examples set (``setDefaultBehavior`` in examples_common.cpp).
PANDA_JOINT_STIFFNESS = (3000.0, 3000.0, 3000.0, 2500.0, 2500.0, 2000.0, 2000.0)
#: Joint stiffness, N*m/rad, of a compliant Panda: the gains of libfranka's joint impedance example
#: (``examples/joint_impedance_control.cpp``, ``k_gains``): the kind of compliant control real door and drawer
#: opening uses (docs/decisions.md). ``default_robot(compliant=True)``.
PANDA_COMPLIANT_JOINT_STIFFNESS = (600.0, 600.0, 600.0, 600.0, 250.0, 150.0, 50.0)


@dataclass(frozen=True)
class GripperModel:
    """What a two-finger parallel gripper can hold: the basis of the simulated grasp's force bound.

    The grasp holds by friction between two finger pads squeezing the handle from opposite sides, so the
    force it transmits is at most ``2 * pad_friction * grip_force`` (two contacts, each pressed with the
    grip force); above it the handle slips out of the fingers. A two-pad grip resists little torque (pad
    friction over a patch about a centimetre across: about 1 N*m for the defaults): the handle turns in
    the fingers instead, so the simulated grasp transmits no torque.

    Defaults -- the Franka Hand of the Panda: ``grip_force`` 70 N is its rated continuous grip force
    (Franka Emika's datasheet: 70 N continuous, 140 N maximum); ``pad_friction`` 1.0 is an ASSUMPTION
    for rubber-covered fingertip pads on a dry metal or lacquered handle (dry rubber on dry hard surfaces:
    about 0.6 to above 1 in engineering friction tables); stock hard-plastic fingertips hold less -- set
    the value of the real pads. Holding force: 140 N.

    Attributes:
        grip_force: rated continuous squeeze of the fingers, N.
        pad_friction: static friction coefficient between a finger pad and a handle (dimensionless).
    """

    grip_force: float = 70.0
    pad_friction: float = 1.0

    def __post_init__(self) -> None:
        for name in ("grip_force", "pad_friction"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and value > 0 and np.isfinite(value)):
                raise ValueError(f"GripperModel: {name} must be a positive number, got {value!r}")

    @property
    def holding_force(self) -> float:
        """The largest force, N, the grasp transmits before the handle slips: 2 * mu * grip force."""
        return 2.0 * self.pad_friction * self.grip_force


@dataclass(frozen=True)
class RobotSpec:
    """What the planners need to know about a robot besides its URDF.

    Attributes:
        urdf (Path): The robot URDF. Its root link is the world; the base joints move the base in the plane.
        base_joints (tuple of str): Planar base joints in the order (x, y, yaw): prismatic x, prismatic y (metres),
            revolute yaw (rad).
        arm_joints (tuple of str): Arm joints, base to tip (a torso lift, when the robot has one, is the first; a
            joint of the URDF left out of the spec stays at 0).
        finger_joints (tuple of str): Gripper finger joints (prismatic, metres per finger; 0 = closed).
        tool_frame (str): A frame between the fingertips; planned grasp poses are poses of this frame. Its z axis is
            the approach direction, its y axis the finger closing direction.
        base_link (str): The body link of the base (the stand pose is the pose of this link).
        gripper_links (tuple of str): Links allowed to touch the handle while grasping and opening.
        home (tuple of float): Home configuration of ``base_joints + arm_joints`` (the order of ``joint_names``).
        ignore_pairs (tuple of (str, str)): Link pairs never checked for self-collision (besides parent-child pairs,
            always skipped).
        finger_open, finger_closed (float): Finger joint value (metres, per finger) with the gripper open / closed.
        max_finger_force (float): Newtons per finger that an executor may apply to close the gripper.
        gripper (GripperModel): What the gripper can hold (grip force, pad friction): bounds the force an executed
            grasp transmits.
        max_acceleration (tuple of float): Acceleration limit of each joint of ``joint_names``, m/s^2 or rad/s^2
            (URDF has none); empty: not given (a given plan's accelerations are then not judged).
        joint_stiffness (tuple of float): One per arm joint, N*m/rad (N/m for a prismatic joint; inf: rigid): the joint
            impedance under which the real arm follows a plan. An executed grasp pulls with the tool's Cartesian
            stiffness under it (the base is taken as rigid). Empty: the simulator's isotropic default.
    """

    urdf: Path
    base_joints: tuple[str, ...]
    arm_joints: tuple[str, ...]
    finger_joints: tuple[str, ...]
    tool_frame: str
    base_link: str
    gripper_links: tuple[str, ...]
    home: tuple[float, ...]
    ignore_pairs: tuple[tuple[str, str], ...] = field(default=())
    finger_open: float = 0.04
    finger_closed: float = 0.0
    max_finger_force: float = 20.0
    gripper: GripperModel = field(default_factory=GripperModel)
    max_acceleration: tuple[float, ...] = ()
    joint_stiffness: tuple[float, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "joint_stiffness", tuple(float(k) for k in self.joint_stiffness))
        if self.joint_stiffness and (len(self.joint_stiffness) != len(self.arm_joints)
                                     or min(self.joint_stiffness) <= 0 or np.isnan(self.joint_stiffness).any()):
            raise ValueError(f"RobotSpec({self.urdf}): joint_stiffness needs one positive number (inf: rigid) per arm "
                             f"joint {self.arm_joints}, got {self.joint_stiffness}")
        object.__setattr__(self, "urdf", Path(self.urdf))
        if isinstance(self.gripper, dict):
            object.__setattr__(self, "gripper", GripperModel(**self.gripper))
        if len(self.base_joints) != 3:
            raise ValueError(f"RobotSpec({self.urdf}): base_joints must be (x, y, yaw), got {self.base_joints}")
        if self.max_acceleration and len(self.max_acceleration) != len(self.joint_names):
            raise ValueError(f"RobotSpec({self.urdf}): max_acceleration has {len(self.max_acceleration)} values for "
                             f"{len(self.joint_names)} joints {self.joint_names}")
        if len(self.home) != len(self.joint_names):
            raise ValueError(f"RobotSpec({self.urdf}): home has {len(self.home)} values for "
                             f"{len(self.joint_names)} joints {self.joint_names}")

    @property
    def joint_names(self) -> tuple[str, ...]:
        """Planned joints, the columns of every ``q`` array: ``base_joints + arm_joints``."""
        return tuple(self.base_joints) + tuple(self.arm_joints)

    @property
    def dof(self) -> int:
        """Number of planned joints."""
        return len(self.joint_names)

    @property
    def home_q(self) -> np.ndarray:
        """``(dof,) float`` home configuration."""
        return np.asarray(self.home, dtype=float)

    def q_with_base(self, q: np.ndarray, x: float, y: float, yaw: float) -> np.ndarray:
        """Copy of ``q (dof,)`` with the base joints set to ``(x, y, yaw)``."""
        out = np.array(q, dtype=float)
        out[:3] = (x, y, yaw)
        return out


# ------------------------------------------------------------------------------------------------------
# The default mobile Panda
# ------------------------------------------------------------------------------------------------------

#: Base box (metres): length along the base x (forward), width, height; its bottom clears the floor.
BASE_SIZE = (0.60, 0.50, 0.41)
BASE_CLEARANCE = 0.03
#: Where the torso lift's column carries the Panda's link0 (metres, base frame) with the lift at its lowest:
#: forward of centre, on top of the box.
ARM_MOUNT_XYZ = (0.16, 0.0, round(BASE_CLEARANCE + BASE_SIZE[2] + 0.01, 6))
#: The torso lift (prismatic, along the base z): travel (m), speed limit (m/s) and force limit (N), of the
#: order of real mobile manipulators' torsos (Fetch: 0.386 m, 0.1 m/s, 450 N; TIAGo: 0.35 m, 0.07 m/s);
#: the force holds the arm (about 18 kg) and the gripper's 140 N holding force together.
TORSO_TRAVEL = 0.4
TORSO_SPEED = 0.1
TORSO_FORCE = 600.0
#: the torso lift's acceleration limit, m/s^2: an ASSUMPTION like the base's (above what simcheck's executor
#: asks of it: its speed limit reached within ``PhysicsConfig.ramp_time``)
TORSO_ACCELERATION = 1.0
#: The torso column under link0 (m, torso frame): a box reaching down into the base at the lowest position.
TORSO_COLUMN = (0.2, 0.2, TORSO_TRAVEL)

_BASE_TEMPLATE = """<?xml version="1.0" ?>
<!-- partscene mobile Panda: planar base (x, y, yaw) + torso lift + Franka Panda from pybullet_data.
     Generated by planners.robot; mesh paths are absolute into the installed pybullet_data. -->
<robot name="mobile_panda">
  <link name="world"/>
  <link name="base_x_link">
    <inertial><origin xyz="0 0 0"/><mass value="1.0"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="base_y_link">
    <inertial><origin xyz="0 0 0"/><mass value="1.0"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="base_link">
    <inertial><origin xyz="0 0 {bz}"/><mass value="30.0"/><inertia ixx="1.0" ixy="0" ixz="0" iyy="1.2" iyz="0" izz="1.5"/></inertial>
    <visual><origin xyz="0 0 {bz}"/><geometry><box size="{sx} {sy} {sz}"/></geometry>
      <material name="base_grey"><color rgba="0.35 0.35 0.38 1"/></material></visual>
    <collision><origin xyz="0 0 {bz}"/><geometry><box size="{sx} {sy} {sz}"/></geometry></collision>
  </link>
  <joint name="base_x" type="prismatic">
    <parent link="world"/><child link="base_x_link"/><origin xyz="0 0 0"/><axis xyz="1 0 0"/>
    <limit lower="-50" upper="50" effort="2000" velocity="1.0"/><dynamics damping="0" friction="0"/>
  </joint>
  <joint name="base_y" type="prismatic">
    <parent link="base_x_link"/><child link="base_y_link"/><origin xyz="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-50" upper="50" effort="2000" velocity="1.0"/><dynamics damping="0" friction="0"/>
  </joint>
  <joint name="base_yaw" type="revolute">
    <parent link="base_y_link"/><child link="base_link"/><origin xyz="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-6.2832" upper="6.2832" effort="1000" velocity="1.5"/><dynamics damping="0" friction="0"/>
  </joint>
  <link name="torso_link">
    <inertial><origin xyz="-0.04 0 {cz}"/><mass value="5.0"/><inertia ixx="0.08" ixy="0" ixz="0" iyy="0.08" iyz="0" izz="0.03"/></inertial>
    <visual><origin xyz="-0.04 0 {cz}"/><geometry><box size="{cx} {cy} {ch}"/></geometry>
      <material name="torso_grey"><color rgba="0.5 0.5 0.52 1"/></material></visual>
    <collision><origin xyz="-0.04 0 {cz}"/><geometry><box size="{cx} {cy} {ch}"/></geometry></collision>
  </link>
  <joint name="torso_lift" type="prismatic">
    <parent link="base_link"/><child link="torso_link"/><origin xyz="{mx} {my} {mz}" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="{lift}" effort="{effort}" velocity="{speed}"/><dynamics damping="0" friction="0"/>
  </joint>
  <joint name="torso_to_panda" type="fixed">
    <parent link="torso_link"/><child link="panda_link0"/><origin xyz="0 0 0" rpy="0 0 0"/>
  </joint>
{panda}
</robot>
"""


def robot_cache_dir() -> Path:
    """Directory where generated robot URDFs are cached (created on demand)."""
    env = os.environ.get("PARTSCENE_CACHE")
    if env:
        root = Path(env)
    else:
        root = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "partscene"
    return root / "robots"


def _panda_body_xml() -> str:
    """The links and joints of pybullet_data's ``panda.urdf`` with absolute mesh paths."""
    import pybullet_data  # a data-only package; importing it does not start pybullet

    panda_dir = Path(pybullet_data.getDataPath()) / "franka_panda"
    text = (panda_dir / "panda.urdf").read_text()
    body = text[text.index(">", text.index("<robot")) + 1: text.rindex("</robot>")]
    body = body.replace("package://meshes/", f"{(panda_dir / 'meshes').as_posix()}/")
    # pybullet_data's panda_link8 has zero mass but a non-zero inertia; give it an explicit tiny mass so
    # pinocchio and pybullet agree and no loader warns.
    body = re.sub(r'(<link name="panda_link8">\s*<inertial>.*?)<mass value="0.0"/>',
                  r'\1<mass value="0.001"/>', body, flags=re.S)
    body = re.sub(r'(<link name="panda_grasptarget">\s*<inertial>.*?)<mass value="0.0"/>',
                  r'\1<mass value="0.001"/>', body, flags=re.S)
    return body


def default_robot(compliant: bool = False) -> RobotSpec:
    """The default mobile manipulator: planar base + torso lift (0 to :data:`TORSO_TRAVEL` m, home at 0) +
    Franka Panda + parallel gripper. Its arm follows a plan under the joint impedance of
    :data:`PANDA_JOINT_STIFFNESS` (libfranka's default), or with ``compliant`` under the softer
    :data:`PANDA_COMPLIANT_JOINT_STIFFNESS` (simcheck's ``--robot compliant``).

    Writes the combined URDF into :func:`robot_cache_dir` at first use (see the module docstring).
    """
    sx, sy, sz = BASE_SIZE
    text = _BASE_TEMPLATE.format(sx=sx, sy=sy, sz=sz, bz=BASE_CLEARANCE + sz / 2,
                                 mx=ARM_MOUNT_XYZ[0], my=ARM_MOUNT_XYZ[1], mz=ARM_MOUNT_XYZ[2],
                                 cx=TORSO_COLUMN[0], cy=TORSO_COLUMN[1], ch=TORSO_COLUMN[2], cz=-TORSO_COLUMN[2] / 2,
                                 lift=TORSO_TRAVEL, effort=TORSO_FORCE, speed=TORSO_SPEED,
                                 panda=_panda_body_xml())
    digest = hashlib.sha1(text.encode()).hexdigest()[:12]
    path = robot_cache_dir() / f"mobile_panda_{digest}.urdf"
    if not path.exists():
        write_text_atomic(path, text)
    arm = ("torso_lift",) + tuple(f"panda_joint{i}" for i in range(1, 8))
    return RobotSpec(
        urdf=path,
        base_joints=("base_x", "base_y", "base_yaw"),
        arm_joints=arm,
        finger_joints=("panda_finger_joint1", "panda_finger_joint2"),
        tool_frame="panda_grasptarget",
        base_link="base_link",
        gripper_links=("panda_hand", "panda_leftfinger", "panda_rightfinger"),
        home=(0.0, 0.0, 0.0, 0.0) + PANDA_HOME,
        max_acceleration=BASE_MAX_ACCELERATION + (TORSO_ACCELERATION,) + PANDA_MAX_ACCELERATION,
        # Always touching in the convex-hull model (or through the fixed mount / the hand flange).
        ignore_pairs=(("panda_link7", "panda_hand"), ("panda_link6", "panda_link7"),
                      ("panda_link5", "panda_link7"), ("panda_link6", "panda_hand"),
                      ("base_link", "panda_link0"), ("base_link", "panda_link1"),
                      ("torso_link", "panda_link1"), ("torso_link", "panda_link2"),
                      ("panda_leftfinger", "panda_rightfinger"),
                      ("panda_link7", "panda_leftfinger"), ("panda_link7", "panda_rightfinger")),
        finger_open=0.04,
        finger_closed=0.0,
        max_finger_force=20.0,
        joint_stiffness=(math.inf,) + (PANDA_COMPLIANT_JOINT_STIFFNESS if compliant else PANDA_JOINT_STIFFNESS),
        # (the torso lift's column taken as rigid)
    )
