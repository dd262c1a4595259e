"""The PyBullet world: the only module of partscene's simcheck that imports ``pybullet``.

A :class:`World` owns one PyBullet client (DIRECT unless ``gui=True``; never a module global). It loads
a floor plane, the scene and the robot URDF with a fixed base at the world origin (a mobile base is
modelled by the robot's base joints). The scene is loaded as separate bodies, not as one multibody: each
never-moving link is a static single-link body and each articulated subtree (a drawer or door with its
handle) a small fixed-base body (:mod:`simcheck.scene_bodies`); Bullet then neither integrates nor collides
static parts with each other (measured speed: docs/decisions.md, "PyBullet step settings"). Link and
joint names are kept (a name map inside this module). On load it

* disables the default velocity motors PyBullet puts on every scene joint (they lock drawers and
  doors) and replaces them with a zero-velocity motor whose force is the joint's Coulomb friction
  (PyBullet applies URDF ``damping`` but ignores ``friction``: we emulate it);
* enables collisions between scene links except between a link and its ancestors, except between two
  never-moving links (static bodies), and except pairs that already interpenetrate in the loaded state
  (reconstructed primitives may overlap by mm); the robot's base links never collide with the floor;
* fixes the time step and solver iterations so that stepping is deterministic.

Everything is addressed by NAME (joints and links); PyBullet indices and the (x, y, z, w) quaternion
order stay inside this module. Poses come out as ``T_world_link`` (4, 4) float64 arrays, metres.
"""

from __future__ import annotations

import contextlib
import dataclasses
import logging
import os
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from simcheck.config import DEFAULT_PHYSICS, PhysicsConfig
from simcheck.errors import RobotBindingError, SceneLoadError, TaskSpecError
from simcheck.grasp import FingerContacts
from scenes.description import DescriptionError, read_urdf
from simcheck.robot_binding import SimRobot
from simcheck.scene_bodies import ANCHOR, scene_bodies


@contextlib.contextmanager
def _c_output_logged(what: str):
    """Send what C code writes to fd 1/2 inside the block (PyBullet's banner, its URDF importer's
    warnings and parse errors) to this module's logger (debug level) instead of the user's terminal.

    Yields a list that holds that text (one string) once the block has ended, for error messages."""
    import ctypes

    libc = ctypes.CDLL(None)
    saved = [os.dup(fd) for fd in (1, 2)]
    said: list[str] = []
    with tempfile.TemporaryFile() as sink:
        try:
            libc.fflush(None)
            for fd in (1, 2):
                os.dup2(sink.fileno(), fd)
            yield said
        finally:
            libc.fflush(None)
            for fd, keep in zip((1, 2), saved):
                os.dup2(keep, fd)
                os.close(keep)
            sink.seek(0)
            text = sink.read().decode(errors="replace").strip()
            said.append(text)
            if text:
                logging.getLogger(__name__).debug("%s: pybullet wrote: %s", what, text)


def _pybullet_said(said: list[str]) -> str:
    """The last lines PyBullet wrote while failing (its reason), for an error message."""
    text = re.sub(r"b*3(Error|Warning|Printf)\[[^\]]*\]:?", "\n", "".join(said))
    lines = list(dict.fromkeys(ln.strip() for ln in text.splitlines() if ln.strip()))
    return f" (PyBullet: {'; '.join(lines[-3:])})" if lines else ""


def _import_pybullet_quietly():
    """Import pybullet with its C-level "pybullet build time" banner (written to fd 1/2) logged."""
    with _c_output_logged("import pybullet"):
        import pybullet
    return pybullet


pb = _import_pybullet_quietly()

__all__ = ["World", "JointInfo", "ContactPoint", "display_available", "pybullet_version"]

log = logging.getLogger(__name__)

FLOOR = "floor"
_JOINT_TYPES = {pb.JOINT_REVOLUTE: "revolute", pb.JOINT_PRISMATIC: "prismatic", pb.JOINT_FIXED: "fixed",
                pb.JOINT_SPHERICAL: "spherical", pb.JOINT_PLANAR: "planar"}


def pybullet_version() -> str:
    """The installed pybullet version (from the package metadata)."""
    from importlib.metadata import version
    return version("pybullet")


def display_available() -> bool:
    """True when an X display is available for ``--gui``."""
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


@dataclass(frozen=True)
class JointInfo:
    """A joint as loaded in PyBullet. ``lower``/``upper`` in rad or m; ``damping``/``friction`` from the URDF."""

    name: str
    type: str
    index: int
    child_link: str
    parent_link: str
    lower: float
    upper: float
    max_force: float
    max_velocity: float
    damping: float
    friction: float


@dataclass(frozen=True)
class ContactPoint:
    """One contact point between a robot link (or scene link) and another body's link.

    ``force`` is the normal force, N; ``distance`` is negative for penetration, metres;
    ``position`` (3,) on the first body, world frame.
    """

    link_a: str
    link_b: str
    force: float
    distance: float
    position: tuple[float, float, float]


def _T_from_pos_quat(pos, quat_xyzw) -> np.ndarray:
    """(4, 4) transform from a position (3,) and a unit quaternion (x, y, z, w) (PyBullet's order).

    Plain Python arithmetic: called several times per physics step, where numpy's per-call overhead
    would dominate a 3x3 product."""
    x, y, z, w = quat_xyzw
    xx, yy, zz, xy, xz, yz, wx, wy, wz = x * x, y * y, z * z, x * y, x * z, y * z, w * x, w * y, w * z
    return np.array([[1 - 2 * (yy + zz), 2 * (xy - wz), 2 * (xz + wy), pos[0]],
                     [2 * (xy + wz), 1 - 2 * (xx + zz), 2 * (yz - wx), pos[1]],
                     [2 * (xz - wy), 2 * (yz + wx), 1 - 2 * (xx + yy), pos[2]],
                     [0.0, 0.0, 0.0, 1.0]])


def _quat_xyzw_from_R(R: np.ndarray) -> tuple[float, float, float, float]:
    from scipy.spatial.transform import Rotation
    x, y, z, w = Rotation.from_matrix(np.asarray(R, dtype=float)).as_quat()
    return float(x), float(y), float(z), float(w)


class World:
    """A PyBullet client holding a floor, one scene and one robot.

    Args:
        scene_urdf: the scene URDF (root link ``world`` or any fixed root), loaded with a fixed base.
        robot: the robot to load (fixed base at the origin), or ``None`` for a scene-only world.
        config: physics settings.
        gui: open a PyBullet GUI window (raises :class:`SceneLoadError` when no display exists).

    Raises:
        SceneLoadError: the scene URDF is missing or PyBullet cannot load it (names the file).
        RobotBindingError: a robot joint or link named by ``robot`` is not in its URDF.
    """

    def __init__(self, scene_urdf: str | Path, robot: SimRobot | None = None,
                 config: PhysicsConfig = DEFAULT_PHYSICS, *, gui: bool = False) -> None:
        self.config = config
        self.scene_urdf = Path(scene_urdf)
        if not self.scene_urdf.is_file():
            raise SceneLoadError(f"scene URDF {self.scene_urdf} does not exist")
        if gui and not display_available():
            raise SceneLoadError("--gui needs a display (DISPLAY is not set); run headless without --gui")
        with _c_output_logged("connecting to PyBullet"):
            self.client = pb.connect(pb.GUI if gui else pb.DIRECT)
        self._grasp: int | None = None
        self._grasped: tuple[int, int] = (-1, -1)    # (body, link index) held by the attachment
        try:
            self._setup_physics()
            self.floor = self._load_floor()
            self._load_scene()
            self.robot_spec = robot
            self.robot = self._load_robot(robot) if robot is not None else None
        except Exception:
            self.close()
            raise

    # ------------------------------------------------------------------ lifecycle
    def close(self) -> None:
        """Disconnect the client (idempotent)."""
        if self.client is not None and self.client >= 0:
            with contextlib.suppress(Exception), _c_output_logged("disconnecting from PyBullet"):
                pb.disconnect(physicsClientId=self.client)
        self.client = None

    def __enter__(self) -> "World":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _setup_physics(self) -> None:
        c = self.client
        pb.resetSimulation(physicsClientId=c)
        pb.setPhysicsEngineParameter(fixedTimeStep=self.config.time_step, numSolverIterations=self.config.solver_iterations,
                                     numSubSteps=0, deterministicOverlappingPairs=1,
                                     contactBreakingThreshold=self.config.contact_breaking_threshold, physicsClientId=c)
        pb.setGravity(0, 0, -self.config.gravity, physicsClientId=c)

    def _load_floor(self) -> int:
        shape = pb.createCollisionShape(pb.GEOM_PLANE, physicsClientId=self.client)
        return pb.createMultiBody(0, shape, physicsClientId=self.client)

    def _load_scene(self) -> None:
        """Load the scene as separate bodies (:func:`simcheck.scene_bodies.scene_bodies`), keeping every name.

        The URDF is first loaded whole once, to let PyBullet validate it and to read its joint table
        exactly as PyBullet parses it; then it is removed and loaded split."""
        c = self.client
        flags = (pb.URDF_USE_INERTIA_FROM_FILE | pb.URDF_USE_SELF_COLLISION
                 | pb.URDF_USE_SELF_COLLISION_EXCLUDE_ALL_PARENTS)
        try:
            with _c_output_logged(f"loading {self.scene_urdf}") as said:
                whole = pb.loadURDF(str(self.scene_urdf), useFixedBase=True, flags=flags, physicsClientId=c)
        except pb.error as exc:
            raise SceneLoadError(f"PyBullet cannot load scene URDF {self.scene_urdf}: {exc}"
                                 f"{_pybullet_said(said)}") from exc
        joints, links = self._index(whole)
        pb.removeBody(whole, physicsClientId=c)
        try:
            parts = scene_bodies(read_urdf(self.scene_urdf))
        except DescriptionError as exc:
            raise SceneLoadError(f"cannot split scene URDF {self.scene_urdf} into bodies: {exc}") from exc
        self._link_at: dict[str, tuple[int, int]] = {}      # scene link name -> (body, link index)
        self._scene_names: dict[tuple[int, int], str] = {}  # (body, link index) -> scene link name
        self._static_pose: dict[str, np.ndarray] = {}       # never-moving link -> T_world_link (4, 4)
        joint_at: dict[str, tuple[int, int]] = {}
        with tempfile.TemporaryDirectory(prefix="partscene_scene_") as tmp:
            for k, part in enumerate(parts):
                f = Path(tmp) / f"body{k}.urdf"
                f.write_text(part.urdf)
                try:
                    with _c_output_logged(f"loading part {k} of {self.scene_urdf}") as said:
                        body = pb.loadURDF(str(f), part.T_world_root[:3, 3].tolist(),
                                           _quat_xyzw_from_R(part.T_world_root[:3, :3]), useFixedBase=True,
                                           flags=flags if part.moving else pb.URDF_USE_INERTIA_FROM_FILE,
                                           physicsClientId=c)
                except pb.error as exc:
                    raise SceneLoadError(f"PyBullet cannot load a part of scene URDF {self.scene_urdf}: {exc}"
                                         f"{_pybullet_said(said)}") from exc
                bj, bl = self._index(body)
                for name, index in bl.items():
                    if name != ANCHOR:
                        self._link_at[name] = (body, index)
                        self._scene_names[(body, index)] = name
                for info in bj.values():
                    joint_at[info.name] = (body, info.index)
                if not part.moving:
                    self._static_pose[next(iter(bl))] = self._link_pose(body, -1)
                    continue
                for info in bj.values():
                    if info.type in ("revolute", "prismatic"):
                        friction = max(joints[info.name].friction, self.config.min_joint_friction)
                        pb.setJointMotorControl2(body, info.index, pb.VELOCITY_CONTROL, targetVelocity=0.0,
                                                 force=friction, physicsClientId=c)
                        pb.changeDynamics(body, info.index, linearDamping=self.config.scene_joint_damping,
                                          angularDamping=self.config.scene_joint_damping, physicsClientId=c)
                for ancestor in part.static_ancestors:       # a link never collides with its ancestors
                    if ancestor in self._static_pose:
                        for index in bl.values():
                            pb.setCollisionFilterPair(body, self._link_at[ancestor][0], index, -1, 0,
                                                      physicsClientId=c)
        self._scene_bodies = frozenset(b for b, _ in self._link_at.values())
        self._scene_links = {name: self._link_at[name] for name in links}            # URDF order
        self._scene_joints = {name: dataclasses.replace(info, index=joint_at[name][1] if name in joint_at else -1)
                              for name, info in joints.items()}
        self._joint_body = {name: joint_at[name][0] for name in joints if name in joint_at}
        self._filter_initial_overlaps()

    def _filter_initial_overlaps(self) -> None:
        """Disable collision between scene links that already interpenetrate as loaded, deeper than
        ``overlap_tolerance``: a third-party file's links may (partscene's own scene.urdf and truth.urdf
        keep their links apart, recon.clearance). Each pair is logged as a warning and recorded in
        :attr:`disabled_overlaps` as (link a, link b, depth m)."""
        pb.performCollisionDetection(physicsClientId=self.client)
        seen: dict[tuple, float] = {}
        for cp in pb.getContactPoints(physicsClientId=self.client):
            a, b, dist = (cp[1], cp[3]), (cp[2], cp[4]), cp[8]
            if a in self._scene_names and b in self._scene_names and dist < -self.config.overlap_tolerance:
                if (a, b) not in seen:
                    pb.setCollisionFilterPair(a[0], b[0], a[1], b[1], 0, physicsClientId=self.client)
                seen[(a, b)] = max(seen.get((a, b), 0.0), -dist)
        self.disabled_overlaps = tuple((self._scene_names[a], self._scene_names[b], depth)
                                       for (a, b), depth in seen.items())
        for a, b, depth in self.disabled_overlaps:
            log.warning("scene %s: links %s and %s overlap by %.1f mm as loaded: collisions between them "
                        "disabled", self.scene_urdf, a, b, depth * 1e3)

    def _load_robot(self, robot: SimRobot) -> int:
        try:
            with _c_output_logged(f"loading robot {robot.urdf}") as said:
                body = pb.loadURDF(str(robot.urdf), useFixedBase=True, physicsClientId=self.client)
        except pb.error as exc:
            raise RobotBindingError(f"PyBullet cannot load robot URDF {robot.urdf}: {exc}{_pybullet_said(said)}") from exc
        self._robot_joints, self._robot_links = self._index(body)
        for name in robot.joint_names + robot.finger_joints:
            if name not in self._robot_joints:
                raise RobotBindingError(f"robot URDF {robot.urdf} has no joint {name!r}")
        for name in (robot.tool_link,) + robot.gripper_links + robot.finger_links + robot.base_links:
            if name not in self._robot_links:
                raise RobotBindingError(f"robot URDF {robot.urdf} has no link {name!r}")
        self._q_idx = [self._robot_joints[n].index for n in robot.joint_names]
        self._f_idx = [self._robot_joints[n].index for n in robot.finger_joints]
        for j in range(pb.getNumJoints(body, physicsClientId=self.client)):
            pb.changeDynamics(body, j, linearDamping=0.0, angularDamping=0.0, physicsClientId=self.client)
        gripper = {self._robot_links[n] for n in robot.gripper_links + robot.finger_links + (robot.tool_link,)}
        self._gripper_idx = gripper
        self._robot_names = {v: k for k, v in self._robot_links.items()}
        self._forces = [max(self._robot_joints[n].max_force, 1.0) for n in robot.joint_names]
        self._finger_idx = {self._robot_links[n] for n in robot.finger_links}
        self._base_idx = {self._robot_links[n] for n in robot.base_links} | {-1}
        self._finger_closing = self._finger_closing_directions(body, robot)
        for link in self._base_idx:
            # a mobile base stands on the floor: those contacts are never reported (robot_contacts) and
            # only add friction rows for the base motors to fight every step
            pb.setCollisionFilterPair(body, self.floor, link, -1, 0, physicsClientId=self.client)
        return body

    def _finger_closing_directions(self, body: int, robot: SimRobot) -> dict[str, np.ndarray]:
        """finger link name -> (3,) unit direction, in the tool frame, in which the finger moves when the
        gripper closes (its link origin from fully open to fully closed, the arm at its loaded pose)."""
        c, tool = self.client, self._robot_links[robot.tool_link]
        at = {}
        for fingers in (robot.finger_open, robot.finger_closed):
            pb.resetJointStatesMultiDof(body, self._f_idx, [[v] for v in fingers], physicsClientId=c)
            T_tool = self._link_pose(body, tool)
            for name in robot.finger_links:
                p = self._link_pose(body, self._robot_links[name])[:3, 3]
                at.setdefault(name, []).append(T_tool[:3, :3].T @ (p - T_tool[:3, 3]))
        pb.resetJointStatesMultiDof(body, self._f_idx, [[v] for v in robot.finger_open], physicsClientId=c)
        out = {}
        for name, (p_open, p_closed) in at.items():
            d = p_closed - p_open
            if np.linalg.norm(d) < 1e-6:
                raise RobotBindingError(f"robot {robot.urdf}: finger link {name!r} does not move when the gripper "
                                        f"closes (finger_open {robot.finger_open}, finger_closed {robot.finger_closed})")
            out[name] = d / np.linalg.norm(d)
        return out

    def _index(self, body: int) -> tuple[dict[str, JointInfo], dict[str, int]]:
        c = self.client
        base = pb.getBodyInfo(body, physicsClientId=c)[0].decode()
        links = {base: -1}
        joints = {}
        parents = {}
        for j in range(pb.getNumJoints(body, physicsClientId=c)):
            ji = pb.getJointInfo(body, j, physicsClientId=c)
            link = ji[12].decode()
            links[link] = j
            parents[j] = ji[16]
        names = {v: k for k, v in links.items()}
        for j in range(pb.getNumJoints(body, physicsClientId=c)):
            ji = pb.getJointInfo(body, j, physicsClientId=c)
            joints[ji[1].decode()] = JointInfo(
                name=ji[1].decode(), type=_JOINT_TYPES.get(ji[2], "unknown"), index=j, child_link=ji[12].decode(),
                parent_link=names[parents[j]], lower=float(ji[8]), upper=float(ji[9]), max_force=float(ji[10]),
                max_velocity=float(ji[11]), damping=float(ji[6]), friction=float(ji[7]))
        return joints, links

    # ------------------------------------------------------------------ names
    def scene_joint(self, name: str) -> JointInfo:
        """The scene joint ``name``. Raises :class:`TaskSpecError` naming the file when missing."""
        try:
            return self._scene_joints[name]
        except KeyError:
            raise TaskSpecError(f"scene {self.scene_urdf} has no joint {name!r}") from None

    def scene_joint_names(self) -> tuple[str, ...]:
        return tuple(self._scene_joints)

    def scene_joints(self) -> tuple[JointInfo, ...]:
        """Every scene joint, in URDF order."""
        return tuple(self._scene_joints.values())

    def scene_link_names(self) -> tuple[str, ...]:
        return tuple(self._scene_links)

    def robot_joint(self, name: str) -> JointInfo:
        return self._robot_joints[name]

    def has_scene_link(self, name: str) -> bool:
        return name in self._scene_links

    # ------------------------------------------------------------------ state
    def scene_joint_state(self, name: str) -> tuple[float, float]:
        """(position, velocity) of scene joint ``name`` (rad or m, rad/s or m/s)."""
        info = self.scene_joint(name)
        if info.index < 0:                  # a fixed joint between never-moving links
            return 0.0, 0.0
        s = pb.getJointState(self._joint_body[name], info.index, physicsClientId=self.client)
        return float(s[0]), float(s[1])

    def reset_scene_joint(self, name: str, value: float) -> None:
        """Set scene joint ``name`` kinematically (set-up and kinematic re-checks only, never during a task)."""
        info = self.scene_joint(name)
        if info.index >= 0:
            pb.resetJointState(self._joint_body[name], info.index, value, 0.0, physicsClientId=self.client)

    def robot_q(self) -> np.ndarray:
        """(dof,) positions of the controlled joints, in ``robot.joint_names`` order."""
        states = pb.getJointStates(self.robot, self._q_idx, physicsClientId=self.client)
        return np.array([s[0] for s in states], dtype=float)

    def finger_q(self) -> np.ndarray:
        """(n_fingers,) finger joint positions."""
        states = pb.getJointStates(self.robot, self._f_idx, physicsClientId=self.client)
        return np.array([s[0] for s in states], dtype=float)

    def robot_q_target(self) -> np.ndarray:
        """(dof,) the last position targets sent to the controlled joints (:meth:`command_robot`; the
        current positions before any command)."""
        target = getattr(self, "_q_target", None)
        return self.robot_q() if target is None else target.copy()

    def robot_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """(lower, upper) (dof,) URDF limits of the controlled joints (+-inf where the joint has none)."""
        lo, hi = [], []
        for n in self.robot_spec.joint_names:
            ji = self._robot_joints[n]
            unlimited = ji.type == "revolute" and ji.lower > ji.upper
            lo.append(-np.inf if unlimited else ji.lower)
            hi.append(np.inf if unlimited else ji.upper)
        return np.array(lo), np.array(hi)

    def robot_max_velocity(self) -> np.ndarray:
        """(dof,) URDF velocity limits of the controlled joints (rad/s or m/s; 0 when unset)."""
        return np.array([self._robot_joints[n].max_velocity for n in self.robot_spec.joint_names])

    def reset_robot(self, q: np.ndarray, fingers_open: bool = True) -> None:
        """Place the robot at ``q`` (dof,) at rest, fingers open or closed, and hold it there."""
        q = np.asarray(q, dtype=float)
        pb.resetJointStatesMultiDof(self.robot, self._q_idx, [[v] for v in q], [[0.0]] * len(q),
                                    physicsClientId=self.client)
        f = self.robot_spec.finger_open if fingers_open else self.robot_spec.finger_closed
        pb.resetJointStatesMultiDof(self.robot, self._f_idx, [[v] for v in f], [[0.0]] * len(f),
                                    physicsClientId=self.client)
        self.command_robot(q, np.zeros_like(q))
        self.command_fingers(fingers_open)

    def command_robot(self, q: np.ndarray, qd: np.ndarray) -> None:
        """Position-control targets for the controlled joints: ``q`` (dof,), feed-forward ``qd`` (dof,)."""
        gain = self.config.robot_position_gain
        self._q_target = np.array(q, dtype=float)
        pb.setJointMotorControlArray(self.robot, self._q_idx, pb.POSITION_CONTROL, targetPositions=list(map(float, q)),
                                     targetVelocities=list(map(float, qd)), forces=self._forces,
                                     positionGains=[gain] * len(q), velocityGains=[1.0] * len(q),
                                     physicsClientId=self.client)

    def command_fingers(self, open_: bool) -> None:
        """Drive the fingers open or closed (closing past contact squeezes with ``finger_force``)."""
        target = self.robot_spec.finger_open if open_ else self.robot_spec.finger_closed
        n = len(target)
        if n:
            pb.setJointMotorControlArray(self.robot, self._f_idx, pb.POSITION_CONTROL, targetPositions=list(target),
                                         forces=[self.robot_spec.finger_force] * n, positionGains=[0.2] * n,
                                         physicsClientId=self.client)

    def step(self, n: int = 1) -> None:
        """Advance the simulation ``n`` fixed time steps."""
        for _ in range(n):
            if self._grasp is not None:
                self._apply_grasp_spring()
            pb.stepSimulation(physicsClientId=self.client)

    # ------------------------------------------------------------------ poses and velocities
    def scene_link_pose(self, link: str) -> np.ndarray:
        """T_world_link (4, 4) of scene link ``link`` (its URDF link frame)."""
        static = self._static_pose.get(link)
        if static is not None:
            return static.copy()
        return self._link_pose(*self._scene_link_index(link))

    def robot_link_pose(self, link: str) -> np.ndarray:
        """T_world_link (4, 4) of robot link ``link`` (its URDF link frame)."""
        return self._link_pose(self.robot, self._robot_links[link])

    def robot_link_position(self, link: str) -> np.ndarray:
        """(3,) world position of robot link ``link``'s URDF frame, metres (cheaper than the pose)."""
        index = self._robot_links[link]
        if index == -1:
            return self.robot_link_pose(link)[:3, 3]
        return np.array(pb.getLinkState(self.robot, index, computeForwardKinematics=1,
                                        physicsClientId=self.client)[4])

    def _scene_link_index(self, link: str) -> tuple[int, int]:
        """(body, link index) of scene link ``link``."""
        try:
            return self._link_at[link]
        except KeyError:
            raise TaskSpecError(f"scene {self.scene_urdf} has no link {link!r}") from None

    def _link_pose(self, body: int, index: int) -> np.ndarray:
        if index == -1:
            pos, quat = pb.getBasePositionAndOrientation(body, physicsClientId=self.client)
            # base pose is the inertial frame; correct by the local inertial offset
            dyn = pb.getDynamicsInfo(body, -1, physicsClientId=self.client)
            T_world_inertial = _T_from_pos_quat(pos, quat)
            T_link_inertial = _T_from_pos_quat(dyn[3], dyn[4])
            return T_world_inertial @ np.linalg.inv(T_link_inertial)
        s = pb.getLinkState(body, index, computeForwardKinematics=1, physicsClientId=self.client)
        return _T_from_pos_quat(s[4], s[5])

    def scene_link_velocity(self, link: str) -> tuple[np.ndarray, np.ndarray]:
        """(linear (3,) m/s, angular (3,) rad/s) world-frame velocity of scene link ``link``."""
        body, index = self._scene_link_index(link)
        if index == -1:
            return np.zeros(3), np.zeros(3)
        s = pb.getLinkState(body, index, computeLinkVelocity=1, physicsClientId=self.client)
        return np.asarray(s[6], dtype=float), np.asarray(s[7], dtype=float)

    # ------------------------------------------------------------------ contacts
    def robot_contacts(self, min_depth: float = 0.0) -> list[ContactPoint]:
        """Contacts of robot links with scene links and with the floor (``link_b == "floor"``).

        Floor contacts of ``robot.base_links`` are omitted (a mobile base stands on the floor). Only
        points with distance <= ``-min_depth`` are returned.
        """
        out = []
        rnames, snames = self._robot_names, self._scene_names
        for cp in pb.getContactPoints(bodyA=self.robot, physicsClientId=self.client):   # one query, all bodies
            if cp[8] > -min_depth:
                continue
            if cp[2] == self.floor:
                if cp[3] not in self._base_idx:
                    out.append(ContactPoint(rnames[cp[3]], FLOOR, float(cp[9]), float(cp[8]), tuple(cp[5])))
            elif (cp[2], cp[4]) in snames:
                out.append(ContactPoint(rnames[cp[3]], snames[cp[2], cp[4]], float(cp[9]), float(cp[8]),
                                        tuple(cp[5])))
        return out

    def scene_link_contacts(self, link: str, min_depth: float = 0.0) -> list[ContactPoint]:
        """Contacts of scene link ``link`` with other scene links and the floor (not with the robot)."""
        body, idx = self._scene_link_index(link)
        snames = self._scene_names
        out = []
        for cp in pb.getContactPoints(bodyA=body, linkIndexA=idx, physicsClientId=self.client):
            if cp[8] > -min_depth:
                continue
            if cp[2] == self.floor:
                out.append(ContactPoint(link, FLOOR, float(cp[9]), float(cp[8]), tuple(cp[5])))
            elif (cp[2], cp[4]) in snames and (cp[2], cp[4]) != (body, idx):
                out.append(ContactPoint(link, snames[cp[2], cp[4]], float(cp[9]), float(cp[8]), tuple(cp[5])))
        return out

    def finger_contact_count(self, scene_link: str, within: float = 0.001) -> int:
        """How many finger links are within ``within`` metres of (touching) scene link ``scene_link`` now.

        Closest points, not contact points: while attached the fingers do not collide with the grasped
        link (see :meth:`attach`), yet they still touch it."""
        body, idx = self._scene_link_index(scene_link)
        return sum(bool(pb.getClosestPoints(self.robot, body, within, linkIndexA=f, linkIndexB=idx,
                                            physicsClientId=self.client)) for f in self._finger_idx)

    def finger_contacts(self, scene_link: str) -> tuple[FingerContacts, ...]:
        """Each finger link's contact points with scene link ``scene_link`` from the last step (PyBullet's
        contact manifold: positions on the scene link, normals toward the finger, signed distances),
        with the finger's closing direction in the world and its travel left to fully closed."""
        body, idx = self._scene_link_index(scene_link)
        R_tool = self.robot_link_pose(self.robot_spec.tool_link)[:3, :3]
        q = self.finger_q()
        left = np.abs(q - np.asarray(self.robot_spec.finger_closed, dtype=float))
        out = []
        joints = self.robot_spec.finger_joints
        for k, name in enumerate(self.robot_spec.finger_links):
            cps = pb.getContactPoints(self.robot, body, self._robot_links[name], idx, physicsClientId=self.client)
            joint = next((i for i, j in enumerate(joints) if self._robot_joints[j].child_link == name),
                         min(k, len(left) - 1))
            out.append(FingerContacts(
                finger=name, positions=np.array([cp[6] for cp in cps], dtype=float).reshape(-1, 3),
                normals=np.array([cp[7] for cp in cps], dtype=float).reshape(-1, 3),
                distances=np.array([cp[8] for cp in cps], dtype=float),
                closing=R_tool @ self._finger_closing[name], travel_left=float(left[joint]) if len(left) else 0.0))
        return tuple(out)

    def is_gripper_link(self, link: str) -> bool:
        return self._robot_links.get(link) in self._gripper_idx

    # ------------------------------------------------------------------ grasp attachment
    def attach(self, scene_link: str, max_force: float, stiffness: float, damping: float) -> None:
        """Hold the point of ``scene_link`` where the robot's tool frame origin is now with a spring to the
        tool (``stiffness`` N/m, ``damping`` N*s/m: the compliance of a real arm under impedance control
        and of the finger pads), applied as equal and opposite forces every :meth:`step`; no torque. The
        spring force is capped at ``max_force`` N: above it the handle slides in the fingers (the held
        point moves along so that the spring stays at the cap).

        While attached, the fingers hold their current opening and do not collide with ``scene_link``:
        the attachment is the grasp, and finger contacts squeezing the same link made the solver fight
        itself. :meth:`detach` restores both."""
        self.detach()
        obj_body, obj_idx = self._scene_link_index(scene_link)
        T_w_obj = self.scene_link_pose(scene_link)
        p_tool = self.robot_link_position(self.robot_spec.tool_link)
        p_local = np.linalg.inv(T_w_obj) @ np.append(p_tool, 1.0)
        self._grasp = {"body": obj_body, "index": obj_idx, "p_local": p_local[:3], "K": float(stiffness),
                       "D": float(damping), "cap": float(max_force), "force": 0.0, "slid": False}
        self._grasped = (obj_body, obj_idx)
        self._set_finger_collisions(obj_body, obj_idx, enabled=False)
        f = self.finger_q()
        pb.setJointMotorControlArray(self.robot, self._f_idx, pb.POSITION_CONTROL, targetPositions=list(f),
                                     forces=[self.robot_spec.finger_force] * len(f), positionGains=[0.2] * len(f),
                                     physicsClientId=self.client)

    def _point_state(self, body: int, index: int, p_local: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(position (3,) m, velocity (3,) m/s), world frame, of the point ``p_local`` of a link."""
        s = pb.getLinkState(body, index, computeLinkVelocity=1, computeForwardKinematics=1,
                            physicsClientId=self.client)
        T = _T_from_pos_quat(s[4], s[5])
        p = T[:3, :3] @ p_local + T[:3, 3]
        v = np.asarray(s[6]) + np.cross(np.asarray(s[7]), p - np.asarray(s[0]))
        return p, v

    def _apply_grasp_spring(self) -> None:
        g = self._grasp
        p_h, v_h = self._point_state(g["body"], g["index"], g["p_local"])
        tool = self._robot_links[self.robot_spec.tool_link]
        p_t, v_t = self._point_state(self.robot, tool, np.zeros(3))
        stretch = p_t - p_h
        f = g["K"] * stretch + g["D"] * (v_t - v_h)
        norm = float(np.linalg.norm(f))
        g["force"] = norm                       # what holding the point would take (before the cap)
        if norm > g["cap"]:
            f *= g["cap"] / norm
            g["slid"] = True
            s = float(np.linalg.norm(stretch))
            if s > g["cap"] / g["K"]:           # the held point slides along: the spring stays at the cap
                p_new = p_t - stretch * (g["cap"] / g["K"] / s)
                T = self._link_pose(g["body"], g["index"])
                g["p_local"] = T[:3, :3].T @ (p_new - T[:3, 3])
        pb.applyExternalForce(g["body"], g["index"], f.tolist(), p_h.tolist(), pb.WORLD_FRAME, physicsClientId=self.client)
        pb.applyExternalForce(self.robot, tool, (-f).tolist(), p_t.tolist(), pb.WORLD_FRAME, physicsClientId=self.client)

    def _set_finger_collisions(self, body: int, index: int, enabled: bool) -> None:
        for f in self._finger_idx:
            pb.setCollisionFilterPair(self.robot, body, f, index, int(enabled), physicsClientId=self.client)

    def _com_offset(self, body: int, index: int) -> np.ndarray:
        """T_link_com (4, 4): the link's inertial frame in its URDF link frame."""
        dyn = pb.getDynamicsInfo(body, index, physicsClientId=self.client)
        return _T_from_pos_quat(dyn[3], dyn[4])

    def detach(self) -> None:
        """Remove the grasp attachment, if any."""
        if self._grasp is not None:
            self._grasp = None
            self._set_finger_collisions(*self._grasped, enabled=True)

    @property
    def attached(self) -> bool:
        return self._grasp is not None

    def grasp_force(self) -> float:
        """Norm of the force (N) the grasp spring needed in the last step to hold the grasped point, before
        the cap at the gripper's holding force (what was transmitted is at most the cap; 0 when detached)."""
        return 0.0 if self._grasp is None else float(self._grasp["force"])

    @property
    def grasp_slid(self) -> bool:
        """The grasp has reached its force cap (the handle slid in the fingers) since it was made."""
        return self._grasp is not None and bool(self._grasp["slid"])

    # ------------------------------------------------------------------ kinematic queries
    @contextlib.contextmanager
    def saved_state(self):
        """Context manager: every kinematic change inside is undone on exit (PyBullet saveState)."""
        sid = pb.saveState(physicsClientId=self.client)
        try:
            yield self
        finally:
            pb.restoreState(stateId=sid, physicsClientId=self.client)
            pb.removeState(sid, physicsClientId=self.client)

    def collisions_at(self, q: np.ndarray, fingers_open: bool, scene_q: dict[str, float],
                      min_depth: float) -> list[ContactPoint]:
        """Robot-scene/floor contacts deeper than ``min_depth`` (m) with the robot at ``q`` (dof,) and the
        scene joints at ``scene_q`` (name -> value). Moves the world: call inside :meth:`saved_state`."""
        q = np.asarray(q, dtype=float)
        pb.resetJointStatesMultiDof(self.robot, self._q_idx, [[v] for v in q], physicsClientId=self.client)
        f = self.robot_spec.finger_open if fingers_open else self.robot_spec.finger_closed
        if f:
            pb.resetJointStatesMultiDof(self.robot, self._f_idx, [[v] for v in f], physicsClientId=self.client)
        for name, value in scene_q.items():
            info = self.scene_joint(name)
            if info.index >= 0:
                pb.resetJointState(self._joint_body[name], info.index, float(value), physicsClientId=self.client)
        pb.performCollisionDetection(physicsClientId=self.client)
        return self.robot_contacts(min_depth=min_depth)

    # ------------------------------------------------------------------ images
    def render(self, target: np.ndarray, eye: np.ndarray, width: int = 320, height: int = 240,
               fov_deg: float = 60.0) -> np.ndarray:
        """(height, width, 3) uint8 RGB image from ``eye`` (3,) looking at ``target`` (3,), world frame, z up.

        Uses the CPU ``ER_TINY_RENDERER`` (headless).
        """
        view = pb.computeViewMatrix(list(map(float, eye)), list(map(float, target)), [0, 0, 1])
        proj = pb.computeProjectionMatrixFOV(fov_deg, width / height, 0.05, 20.0)
        img = pb.getCameraImage(width, height, view, proj, renderer=pb.ER_TINY_RENDERER, physicsClientId=self.client)
        rgba = np.asarray(img[2], dtype=np.uint8).reshape(height, width, 4)
        return rgba[:, :, :3].copy()
