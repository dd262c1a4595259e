"""The PyBullet world: one client holding a floor, one scene and one robot, addressed by name.

A :class:`World` owns one PyBullet client (DIRECT unless ``gui=True``; never a module global). It loads
a floor plane, the scene (:func:`simcheck.scene_loading.load_scene`: separate bodies, joint friction
emulated, collisions filtered) and the robot with a fixed base at the floor frame's origin
(:func:`simcheck.robot_loading.load_robot`), and fixes the time step and solver iterations so that
stepping is deterministic. It commands the robot, steps the simulation, reads poses, velocities and
contacts (:mod:`simcheck.contacts`), holds a grasp with a force-capped spring (:mod:`simcheck.grasp_spring`)
and renders images (:mod:`simcheck.rendering`).

Everything is addressed by NAME (joints and links); PyBullet indices and the (x, y, z, w) quaternion
order stay inside the adapter modules (:mod:`simcheck.bullet`). Poses come out as ``T_world_link``
(4, 4) float64 arrays, metres.

The world frame is the scene URDF's. The floor is the scene's (:func:`scenes.description.read_scene_floor`:
recon's estimate in graph.json beside the URDF, else z = 0, z up): the ground plane lies on it, gravity
pulls against its normal and the robot's root stands at the floor frame's origin, so the base joints'
(x, y, yaw) are floor-frame coordinates (docs/contracts.md, "The floor").
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

import numpy as np

from scenes.description import SceneFloor, read_scene_floor
from simcheck.bullet import (c_output_logged, jacobian_point, link_pose, mass_matrix, movable_joints, pb,
                             point_jacobian, point_state, pybullet_version)
from simcheck.bullet_poses import quat_xyzw_from_R
from simcheck.config import DEFAULT_PHYSICS, PhysicsConfig
from simcheck.contacts import FLOOR, ContactPoint, excess_penetration, robot_contact_points, scene_link_contact_points
from simcheck.errors import SceneLoadError, TaskSpecError
from simcheck.grasp import FingerContacts
from simcheck.grasp_spring import GraspSpring, cartesian_stiffness, spring_force, stable_damping, stable_stiffness
from simcheck.joint_table import JointInfo
from simcheck.rendering import render
from simcheck.robot_binding import SimRobot
from simcheck.robot_loading import LoadedRobot, load_robot
from simcheck.scene_loading import load_scene, picture_part, reload_part, unload_part

__all__ = ["World", "JointInfo", "ContactPoint", "FLOOR", "display_available", "pybullet_version"]


def display_available() -> bool:
    """True when an X display is available for ``--gui``."""
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


class World:
    """A PyBullet client holding a floor, one scene and one robot.

    Args:
        scene_urdf: the scene URDF (root link ``world`` or any fixed root), loaded with a fixed base.
        robot: the robot to load (fixed base at the floor frame's origin), or ``None`` for a scene-only world.
        config: physics settings.
        gui: open a PyBullet GUI window (raises :class:`SceneLoadError` when no display exists).
        visuals: load the visual shapes, which only :meth:`render` and the GUI need; without them loading
            takes ~1/4 of the time and the physics is the same (a certification without images).
        floor: the floor to stand on; None: the scene's own (:func:`scenes.description.read_scene_floor` of
            ``scene_urdf``; a copy of a scene written elsewhere, e.g. a robust sample, passes its source's).

    Attributes:
        scene_floor: the :class:`scenes.description.SceneFloor` the robot stands on and gravity pulls against.

    Raises:
        SceneLoadError: the scene URDF is missing or PyBullet cannot load it (names the file).
        DescriptionError: the graph.json beside the scene URDF has an unusable ``floor`` (names the field).
        RobotBindingError: a robot joint or link named by ``robot`` is not in its URDF.
    """

    def __init__(self, scene_urdf: str | Path, robot: SimRobot | None = None,
                 config: PhysicsConfig = DEFAULT_PHYSICS, *, gui: bool = False, visuals: bool = True,
                 floor: SceneFloor | None = None) -> None:
        self.config = config
        self.scene_urdf = Path(scene_urdf)
        if not self.scene_urdf.is_file():
            raise SceneLoadError(f"scene URDF {self.scene_urdf} does not exist")
        if gui and not display_available():
            raise SceneLoadError("--gui needs a display (DISPLAY is not set); run headless without --gui")
        self.scene_floor = read_scene_floor(self.scene_urdf) if floor is None else floor
        with c_output_logged("connecting to PyBullet"):
            self.client = pb.connect(pb.GUI if gui else pb.DIRECT)
        self._grasp: GraspSpring | None = None
        self._arm_impedance: tuple[list[int], np.ndarray] | None = None    # (Jacobian columns, joint stiffness)
        self._q_target: np.ndarray | None = None
        self._movable: list[int] | None = None
        self._tool_jac_point: list[float] | None = None
        self._effort_limits: np.ndarray | None = None
        self._tool_index = -1                                   # the robot's tool link index
        self._gains: tuple[list[float], list[float]] = ([], [])  # (position, velocity) gains of each joint
        self._frozen: dict[str, float] = {}                     # frozen scene joint -> its value
        self._frozen_pose: dict[str, np.ndarray] = {}           # frozen scene link -> T_world_link
        self._frozen_parts: list = []                           # the frozen parts, to load again
        self._visuals = visuals or gui
        try:
            self._setup_physics()
            self.floor = self._load_floor()
            self._scene = load_scene(self.client, self.scene_urdf, config, visuals or gui)
            self.disabled_overlaps = self._scene.disabled_overlaps
            self.rest_contacts = self._scene.rest_contacts
            self.robot_spec = robot
            self._robot: LoadedRobot | None = None
            self.robot = None
            if robot is not None:
                self._robot = load_robot(self.client, robot, self.floor, visuals or gui,
                                         self.scene_floor.T_scene_floor)
                self.robot = self._robot.body
                self._effort_limits = np.asarray(self._robot.forces, dtype=float)   # read every physics step
                self._tool_index = self._robot.links[robot.tool_link]
                dof = len(robot.joint_names)
                self._gains = ([float(config.robot_position_gain)] * dof, [1.0] * dof)
        except Exception:
            self.close()
            raise

    # ------------------------------------------------------------------ lifecycle
    def close(self) -> None:
        """Disconnect the client (idempotent)."""
        if self.client is not None and self.client >= 0:
            with contextlib.suppress(Exception), c_output_logged("disconnecting from PyBullet"):
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
        pb.setGravity(*self.scene_floor.gravity(self.config.gravity).tolist(), physicsClientId=c)

    def _load_floor(self) -> int:
        """The ground plane on the scene's floor (its body id)."""
        shape = pb.createCollisionShape(pb.GEOM_PLANE, physicsClientId=self.client)
        if self.scene_floor.level:
            return pb.createMultiBody(0, shape, physicsClientId=self.client)
        T = self.scene_floor.T_scene_floor
        return pb.createMultiBody(0, shape, basePosition=T[:3, 3].tolist(), baseOrientation=quat_xyzw_from_R(T[:3, :3]),
                                  physicsClientId=self.client)

    # ------------------------------------------------------------------ names
    def scene_joint(self, name: str) -> JointInfo:
        """The scene joint ``name``. Raises :class:`TaskSpecError` naming the file when missing."""
        try:
            return self._scene.joints[name]
        except KeyError:
            raise TaskSpecError(f"scene {self.scene_urdf} has no joint {name!r}") from None

    def scene_joint_names(self) -> tuple[str, ...]:
        """Every scene joint's name, in URDF order."""
        return tuple(self._scene.joints)

    def scene_joints(self) -> tuple[JointInfo, ...]:
        """Every scene joint, in URDF order."""
        return tuple(self._scene.joints.values())

    def scene_link_names(self) -> tuple[str, ...]:
        """Every scene link's name, in URDF order."""
        return tuple(self._scene.links)

    def robot_joint(self, name: str) -> JointInfo:
        """The robot joint ``name`` as loaded."""
        return self._robot.joints[name]

    def has_scene_link(self, name: str) -> bool:
        """True when the scene has a link ``name``."""
        return name in self._scene.links

    # ------------------------------------------------------------------ state
    def scene_joint_state(self, name: str) -> tuple[float, float]:
        """(position, velocity) of scene joint ``name`` (rad or m, rad/s or m/s)."""
        if name in self._frozen:
            return self._frozen[name], 0.0
        info = self.scene_joint(name)
        if info.index < 0:                  # a fixed joint between never-moving links
            return 0.0, 0.0
        s = pb.getJointState(self._scene.joint_body[name], info.index, physicsClientId=self.client)
        return float(s[0]), float(s[1])

    def reset_scene_joint(self, name: str, value: float) -> None:
        """Set scene joint ``name`` kinematically (set-up and kinematic re-checks only, never during a task)."""
        if name in self._frozen:
            self.thaw_parts()
        info = self.scene_joint(name)
        if info.index >= 0:
            pb.resetJointState(self._scene.joint_body[name], info.index, value, 0.0, physicsClientId=self.client)

    def robot_q(self) -> np.ndarray:
        """(dof,) positions of the controlled joints, in ``robot.joint_names`` order."""
        states = pb.getJointStates(self.robot, self._robot.q_index, physicsClientId=self.client)
        return np.array([s[0] for s in states], dtype=float)

    def robot_effort_share(self) -> np.ndarray:
        """(dof,) the motor torque (force for a prismatic joint) each controlled joint applied in the last step,
        as a share of its effort limit (the URDF effort the motor is capped at, :meth:`command_robot`)."""
        return np.abs(np.array(self.robot_torques(), dtype=float)) / self._effort_limits

    def robot_torques(self) -> list[float]:
        """(dof,) the signed motor torque, N*m (force, N, for a prismatic joint), each controlled joint applied
        in the last step."""
        return [s[3] for s in pb.getJointStates(self.robot, self._robot.q_index, physicsClientId=self.client)]

    @property
    def robot_effort_limits(self) -> np.ndarray:
        """(dof,) the controlled joints' effort limits, N*m or N (the URDF efforts their motors are capped at)."""
        return self._effort_limits

    def finger_q(self) -> np.ndarray:
        """(n_fingers,) finger joint positions."""
        states = pb.getJointStates(self.robot, self._robot.finger_index, physicsClientId=self.client)
        return np.array([s[0] for s in states], dtype=float)

    def robot_q_target(self) -> np.ndarray:
        """(dof,) the last position targets sent to the controlled joints (:meth:`command_robot`; the
        current positions before any command)."""
        return self.robot_q() if self._q_target is None else self._q_target.copy()

    def robot_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """(lower, upper) (dof,) URDF limits of the controlled joints (+-inf where the joint has none)."""
        lo, hi = [], []
        for n in self.robot_spec.joint_names:
            ji = self._robot.joints[n]
            unlimited = ji.type == "revolute" and ji.lower > ji.upper
            lo.append(-np.inf if unlimited else ji.lower)
            hi.append(np.inf if unlimited else ji.upper)
        return np.array(lo), np.array(hi)

    def robot_max_velocity(self) -> np.ndarray:
        """(dof,) URDF velocity limits of the controlled joints (rad/s or m/s; 0 when unset)."""
        return np.array([self._robot.joints[n].max_velocity for n in self.robot_spec.joint_names])

    def reset_robot(self, q: np.ndarray, fingers_open: bool = True) -> None:
        """Place the robot at ``q`` (dof,) at rest, fingers open or closed, and hold it there."""
        q = np.asarray(q, dtype=float)
        pb.resetJointStatesMultiDof(self.robot, self._robot.q_index, [[v] for v in q], [[0.0]] * len(q),
                                    physicsClientId=self.client)
        f = self.robot_spec.finger_open if fingers_open else self.robot_spec.finger_closed
        pb.resetJointStatesMultiDof(self.robot, self._robot.finger_index, [[v] for v in f], [[0.0]] * len(f),
                                    physicsClientId=self.client)
        self.command_robot(q, np.zeros_like(q))
        self.command_fingers(fingers_open)

    def command_robot(self, q: np.ndarray, qd: np.ndarray) -> None:
        """Position-control targets for the controlled joints: ``q`` (dof,), feed-forward ``qd`` (dof,)."""
        self._q_target = np.array(q, dtype=float)
        gains, velocity_gains = self._gains
        pb.setJointMotorControlArray(self.robot, self._robot.q_index, pb.POSITION_CONTROL,
                                     targetPositions=self._q_target.tolist(),
                                     targetVelocities=np.asarray(qd, dtype=float).tolist(),
                                     forces=self._robot.forces, positionGains=gains[:len(q)],
                                     velocityGains=velocity_gains[:len(q)], physicsClientId=self.client)

    def command_fingers(self, open_: bool) -> None:
        """Drive the fingers open or closed (closing past contact squeezes with ``finger_force``)."""
        target = self.robot_spec.finger_open if open_ else self.robot_spec.finger_closed
        n = len(target)
        if n:
            pb.setJointMotorControlArray(self.robot, self._robot.finger_index, pb.POSITION_CONTROL,
                                         targetPositions=list(target), forces=[self.robot_spec.finger_force] * n,
                                         positionGains=[0.2] * n, physicsClientId=self.client)

    def step(self, n: int = 1) -> None:
        """Advance the simulation ``n`` fixed time steps."""
        for _ in range(n):
            if self._grasp is not None:
                self._apply_grasp_spring()
            pb.stepSimulation(physicsClientId=self.client)

    # ------------------------------------------------------------------ poses and velocities
    def scene_link_pose(self, link: str) -> np.ndarray:
        """T_world_link (4, 4) of scene link ``link`` (its URDF link frame)."""
        static = self._scene.static_pose.get(link, self._frozen_pose.get(link))
        if static is not None:
            return static.copy()
        return link_pose(self.client, *self._scene_link_index(link))

    def robot_link_pose(self, link: str) -> np.ndarray:
        """T_world_link (4, 4) of robot link ``link`` (its URDF link frame)."""
        return link_pose(self.client, self.robot, self._robot.links[link])

    def robot_link_position(self, link: str) -> np.ndarray:
        """(3,) world position of robot link ``link``'s URDF frame, metres (cheaper than the pose)."""
        index = self._robot.links[link]
        if index == -1:
            return self.robot_link_pose(link)[:3, 3]
        return np.array(pb.getLinkState(self.robot, index, computeForwardKinematics=1,
                                        physicsClientId=self.client)[4])

    def _scene_link_index(self, link: str) -> tuple[int, int]:
        """(body, link index) of scene link ``link``."""
        try:
            return self._scene.link_at[link]
        except KeyError:
            raise TaskSpecError(f"scene {self.scene_urdf} has no link {link!r}") from None

    def scene_link_velocity(self, link: str) -> tuple[np.ndarray, np.ndarray]:
        """(linear (3,) m/s, angular (3,) rad/s) world-frame velocity of scene link ``link``."""
        if link in self._frozen_pose:
            return np.zeros(3), np.zeros(3)
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
        rows = pb.getContactPoints(bodyA=self.robot, physicsClientId=self.client)   # one query, all bodies
        return robot_contact_points(rows, self._robot.names, self._scene.names, self.floor, self._robot.base_links,
                                    min_depth)

    def scene_link_contacts(self, link: str, min_depth: float = 0.0) -> list[ContactPoint]:
        """Contacts of scene link ``link`` with other scene links and the floor (not with the robot)."""
        body, idx = self._scene_link_index(link)
        rows = pb.getContactPoints(bodyA=body, linkIndexA=idx, physicsClientId=self.client)
        return scene_link_contact_points(rows, link, (body, idx), self._scene.names, self.floor, min_depth)

    def rest_contacts_of(self, link: str) -> tuple[tuple[str, str, float], ...]:
        """The pairs in contact at rest (:attr:`rest_contacts`) between a link of ``link``'s body (the part
        moved with it: its handle, its drawer box) and a link of another body, as (that link, the other
        link, penetration at rest m)."""
        body = self._scene_link_index(link)[0]
        out = []
        for a, b, depth in self.rest_contacts:
            ba, bb = self._scene.link_at[a][0], self._scene.link_at[b][0]
            if ba == body and bb != body:
                out.append((a, b, depth))
            elif bb == body and ba != body:
                out.append((b, a, depth))
        return tuple(out)

    def rest_contact_excess(self, pairs: tuple[tuple[str, str, float], ...]) -> tuple[float, str]:
        """(largest excess m, the other link) over ``pairs`` (from :meth:`rest_contacts_of`): how much deeper
        than at rest each pair interpenetrates now (their collisions are disabled, so closest points are
        queried); (0, "") when none is deeper."""
        worst, other = 0.0, ""
        for a, b, depth in pairs:
            (ba, ia), (bb, ib) = self._scene.link_at[a], self._scene.link_at[b]
            rows = pb.getClosestPoints(ba, bb, 0.0, linkIndexA=ia, linkIndexB=ib, physicsClientId=self.client)
            e = excess_penetration((r[8] for r in rows), depth)
            if e > worst:
                worst, other = e, b
        return worst, other

    def finger_contact_count(self, scene_link: str, within: float = 0.001) -> int:
        """How many finger links are within ``within`` metres of (touching) scene link ``scene_link`` now.

        Closest points, not contact points: while attached the fingers do not collide with the grasped
        link (see :meth:`attach`), yet they still touch it."""
        body, idx = self._scene_link_index(scene_link)
        return sum(bool(pb.getClosestPoints(self.robot, body, within, linkIndexA=f, linkIndexB=idx,
                                            physicsClientId=self.client)) for f in self._robot.finger_links)

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
            cps = pb.getContactPoints(self.robot, body, self._robot.links[name], idx, physicsClientId=self.client)
            joint = next((i for i, j in enumerate(joints) if self._robot.joints[j].child_link == name),
                         min(k, len(left) - 1))
            out.append(FingerContacts(
                finger=name, positions=np.array([cp[6] for cp in cps], dtype=float).reshape(-1, 3),
                normals=np.array([cp[7] for cp in cps], dtype=float).reshape(-1, 3),
                distances=np.array([cp[8] for cp in cps], dtype=float),
                closing=R_tool @ self._robot.finger_closing[name],
                travel_left=float(left[joint]) if len(left) else 0.0))
        return tuple(out)

    def is_gripper_link(self, link: str) -> bool:
        """True when robot link ``link`` is a gripper, finger or tool link."""
        return self._robot.links.get(link) in self._robot.gripper_links

    # ------------------------------------------------------------------ grasp attachment
    def attach(self, scene_link: str, max_force: float, stiffness, damping: float,
               held_point: np.ndarray | None = None) -> None:
        """Hold the point of ``scene_link`` where the robot's tool frame origin is now with a spring to the
        tool (the compliance of a real arm following a plan under impedance control), applied as equal
        and opposite forces every :meth:`step`; no torque. ``held_point`` (3,) world, metres: hold that point
        of the link instead, to the point of the hand that is there now (a round bar is held on its axis, so
        that it rolls about it between the pads; :func:`simcheck.grasp.round_bar_axis`). ``stiffness``: N/m (an isotropic spring), or a
        mapping robot joint name -> joint stiffness (N*m/rad, N/m for a prismatic joint) of the arm's
        joint impedance: the spring is then the tool's Cartesian stiffness under it at the current
        configuration, recomputed every ``grasp_stiffness_every`` steps (:meth:`tool_stiffness`); joints not
        named are rigid.
        ``damping`` N*s/m. The spring force is capped at ``max_force`` N: above it the handle slides in
        the fingers (the held point moves along so that the spring stays at the cap;
        :func:`simcheck.grasp_spring.spring_force`).

        The spring is integrated explicitly, once per physics step: its stiffness is capped at the
        grasped part's smallest effective mass at the held point over the time step squared
        (:func:`simcheck.grasp_spring.stable_stiffness`; stiffer, a Panda pulling a light microwave door
        along its stiff direction made it diverge), its damping at that mass over the time step
        (:func:`simcheck.grasp_spring.stable_damping`).

        While attached, the fingers hold their current opening and do not collide with ``scene_link``:
        the attachment is the grasp, and finger contacts squeezing the same link made the solver fight
        itself. :meth:`detach` restores both."""
        self.detach()
        c = self.client
        obj_body, obj_idx = self._scene_link_index(scene_link)
        T_w_obj = self.scene_link_pose(scene_link)
        T_tool = self.robot_link_pose(self.robot_spec.tool_link)
        p_held = T_tool[:3, 3] if held_point is None else np.asarray(held_point, dtype=float).reshape(3)
        p_local = (np.linalg.inv(T_w_obj) @ np.append(p_held, 1.0))[:3]
        self._tool_point = T_tool[:3, :3].T @ (p_held - T_tool[:3, 3])
        stable, stable_d = np.inf, np.inf
        if obj_idx >= 0 and movable_joints(c, obj_body):
            J, M = point_jacobian(c, obj_body, obj_idx, p_local), mass_matrix(c, obj_body)
            stable, stable_d = (stable_stiffness(J, M, self.config.time_step),
                                stable_damping(J, M, self.config.time_step))
        self._arm_impedance = None
        if isinstance(stiffness, dict):
            self._arm_impedance = self._joint_columns(stiffness)
            K = self._tool_stiffness(*self._arm_impedance)
        else:
            K = float(stiffness) * np.eye(3)
        self._grasp = GraspSpring(obj_body, obj_idx, p_local, K, float(damping), float(max_force), float(stable),
                                  float(stable_d))
        self._set_finger_collisions(obj_body, obj_idx, enabled=False)
        f = self.finger_q()
        pb.setJointMotorControlArray(self.robot, self._robot.finger_index, pb.POSITION_CONTROL,
                                     targetPositions=list(f), forces=[self.robot_spec.finger_force] * len(f),
                                     positionGains=[0.2] * len(f), physicsClientId=c)

    def tool_stiffness(self, joint_stiffness: dict[str, float]) -> np.ndarray:
        """(3, 3) translational stiffness, N/m, of the robot's tool origin at its current configuration when
        the joints of ``joint_stiffness`` (name -> N*m/rad or N/m) are held by those springs and every
        other joint is rigid (:func:`simcheck.grasp_spring.cartesian_stiffness`)."""
        return self._tool_stiffness(*self._joint_columns(joint_stiffness))

    def _joint_columns(self, joint_stiffness: dict[str, float]) -> tuple[list[int], np.ndarray]:
        movable = self._robot_movable()
        cols = [movable.index(self._robot.joints[n].index) for n in joint_stiffness]
        return cols, np.array([float(k) for k in joint_stiffness.values()])

    def _robot_movable(self) -> list[int]:
        """The robot's movable joint indices (its Jacobians' columns: :func:`simcheck.bullet.movable_joints`),
        read once: the grasp spring needs them every few steps."""
        if self._movable is None:
            self._movable = movable_joints(self.client, self.robot)
        return self._movable

    def _tool_stiffness(self, cols: list[int], joint_stiffness: np.ndarray) -> np.ndarray:
        tool = self._tool_index
        if self._tool_jac_point is None:      # the tool origin as PyBullet's Jacobian takes it: fixed
            self._tool_jac_point = jacobian_point(self.client, self.robot, tool, np.zeros(3))
        J = point_jacobian(self.client, self.robot, tool, np.zeros(3), self._robot_movable(), self._tool_jac_point,
                           columns=cols)
        return cartesian_stiffness(J, joint_stiffness)

    def _apply_grasp_spring(self) -> None:
        g, c = self._grasp, self.client
        if self._arm_impedance is not None and g.steps % self.config.grasp_stiffness_every == 0:
            g.stiffness = self._tool_stiffness(*self._arm_impedance)
        g.steps += 1
        p_h, v_h = point_state(c, g.body, g.index, g.p_local)
        tool = self._tool_index
        p_t, v_t = point_state(c, self.robot, tool, self._tool_point)
        f, slide_to = spring_force(g, p_h, v_h, p_t, v_t)
        if slide_to is not None:
            T = link_pose(c, g.body, g.index)
            g.p_local = T[:3, :3].T @ (slide_to - T[:3, 3])
        pb.applyExternalForce(g.body, g.index, f.tolist(), p_h.tolist(), pb.WORLD_FRAME, physicsClientId=c)
        pb.applyExternalForce(self.robot, tool, (-f).tolist(), p_t.tolist(), pb.WORLD_FRAME, physicsClientId=c)

    def _set_finger_collisions(self, body: int, index: int, enabled: bool) -> None:
        for f in self._robot.finger_links:
            pb.setCollisionFilterPair(self.robot, body, f, index, int(enabled), physicsClientId=self.client)

    def detach(self) -> None:
        """Remove the grasp attachment, if any."""
        if self._grasp is not None:
            g, self._grasp = self._grasp, None
            self._set_finger_collisions(g.body, g.index, enabled=True)

    @property
    def attached(self) -> bool:
        """A grasp attachment holds a scene link."""
        return self._grasp is not None

    def grasp_force(self) -> float:
        """Norm of the force (N) the grasp spring needed in the last step to hold the grasped point, before
        the cap at the gripper's holding force (what was transmitted is at most the cap; 0 when detached)."""
        return 0.0 if self._grasp is None else float(self._grasp.force)

    def grasp_slide(self) -> float:
        """How far, m, the held point has slid on the held link since the grasp was made: the handle sliding
        in the fingers when the grasp had to transmit more than the cap (NaN when detached). Not the
        spring's stretch between the tool and the held point: that is the arm's compliance under load."""
        return float("nan") if self._grasp is None else self._grasp.slide

    @property
    def grasp_slid(self) -> bool:
        """The grasp has reached its force cap (the handle slid in the fingers) since it was made."""
        return self._grasp is not None and bool(self._grasp.slid)

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
        c = self.client
        pb.resetJointStatesMultiDof(self.robot, self._robot.q_index, [[v] for v in q], physicsClientId=c)
        f = self.robot_spec.finger_open if fingers_open else self.robot_spec.finger_closed
        if f:
            pb.resetJointStatesMultiDof(self.robot, self._robot.finger_index, [[v] for v in f], physicsClientId=c)
        if any(name in self._frozen for name in scene_q):
            self.thaw_parts()
        for name, value in scene_q.items():
            info = self.scene_joint(name)
            if info.index >= 0:
                pb.resetJointState(self._scene.joint_body[name], info.index, float(value), physicsClientId=c)
        pb.performCollisionDetection(physicsClientId=c)
        return self.robot_contacts(min_depth=min_depth)

    # ------------------------------------------------------------------ frozen parts
    def moving_parts(self) -> dict[int, tuple[str, ...]]:
        """body id -> the names of its movable joints, for each moving scene part that can be frozen
        (:meth:`freeze_parts`; a part whose collision meshes were split into temporary pieces cannot)."""
        out: dict[int, list[str]] = {body: [] for body in self._scene.parts}
        for name, body in self._scene.joint_body.items():
            if body in out and self._scene.joints[name].type in ("revolute", "prismatic"):
                out[body].append(name)
        return {body: tuple(joints) for body, joints in out.items()}

    def part_joints(self, body: int) -> tuple[str, ...]:
        """The movable scene joints of moving part ``body``."""
        return tuple(n for n, b in self._scene.joint_body.items()
                     if b == body and self._scene.joints[n].type in ("revolute", "prismatic"))

    def moving_rest_pairs(self) -> tuple[tuple[int, int], ...]:
        """(body a, body b) of each pair of different moving parts whose links touch at rest
        (:attr:`rest_contacts`)."""
        moving = set(self._scene.joint_body.values())
        out = set()
        for a, b, _ in self.rest_contacts:
            ba, bb = self._scene.link_at[a][0], self._scene.link_at[b][0]
            if ba != bb and ba in moving and bb in moving:
                out.add((ba, bb))
        return tuple(sorted(out))

    def part_of_joint(self, name: str) -> int:
        """The body id of the moving part holding scene joint ``name`` (-1: none, or frozen)."""
        return self._scene.joint_body.get(name, -1)

    def part_box(self, body: int, joint_values: dict[str, float] | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(lower (3,), upper (3,)) world axis-aligned bounding box, m, of moving part ``body``'s links, now
        or with its joints at ``joint_values`` (name -> m or rad; set kinematically and put back)."""
        c = self.client
        saved = {}
        for name, value in (joint_values or {}).items():
            info = self._scene.joints[name]
            saved[name] = pb.getJointState(body, info.index, physicsClientId=c)[:2]
            pb.resetJointState(body, info.index, float(value), 0.0, physicsClientId=c)
        boxes = [pb.getAABB(body, i, physicsClientId=c) for i in range(-1, pb.getNumJoints(body, physicsClientId=c))]
        for name, (q, qd) in saved.items():
            pb.resetJointState(body, self._scene.joints[name].index, q, qd, physicsClientId=c)
        lo = np.min([b[0] for b in boxes], axis=0)
        hi = np.max([b[1] for b in boxes], axis=0)
        return lo, hi

    def part_gravity_load(self, body: int) -> dict[str, tuple[float, float, float]]:
        """Scene joint name -> (velocity m/s or rad/s, |gravity load| N or N m holding it still, friction N or
        N m its motor resists with) for each movable joint of moving part ``body`` now."""
        c = self.client
        joints = sorted((n for n, b in self._scene.joint_body.items()
                         if b == body and self._scene.joints[n].type in ("revolute", "prismatic")),
                        key=lambda n: self._scene.joints[n].index)
        states = [pb.getJointState(body, self._scene.joints[n].index, physicsClientId=c) for n in joints]
        try:
            tau = pb.calculateInverseDynamics(body, [s[0] for s in states], [0.0] * len(joints),
                                              [0.0] * len(joints), physicsClientId=c)
        except pb.error:                    # a joint PyBullet's inverse dynamics cannot take: load unknown
            tau = [float("inf")] * len(joints)
        return {n: (float(s[1]), abs(float(t)), max(self._scene.joints[n].friction, self.config.min_joint_friction))
                for n, s, t in zip(joints, states, tau)}

    def robot_boxes_along(self, qs: np.ndarray) -> np.ndarray:
        """(n, 2, 3) the world bounding box (lower, upper), m, of every robot link together with the robot at
        each row of ``qs`` (n, dof), fingers open; the robot's joints are put back as they were after."""
        c, r = self.client, self._robot
        index = list(r.q_index) + list(r.finger_index)
        saved = pb.getJointStates(self.robot, index, physicsClientId=c)
        links = range(-1, pb.getNumJoints(self.robot, physicsClientId=c))
        f = [[v] for v in self.robot_spec.finger_open]
        if f:
            pb.resetJointStatesMultiDof(self.robot, r.finger_index, f, physicsClientId=c)
        out = np.empty((len(qs), 2, 3))
        for k, q in enumerate(qs):
            pb.resetJointStatesMultiDof(self.robot, r.q_index, [[float(v)] for v in q], physicsClientId=c)
            boxes = np.array([pb.getAABB(self.robot, i, physicsClientId=c) for i in links])
            out[k, 0], out[k, 1] = boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)
        pb.resetJointStatesMultiDof(self.robot, index, [[s[0]] for s in saved], [[s[1]] for s in saved],
                                    physicsClientId=c)
        return out

    def robot_levers(self) -> np.ndarray:
        """(dof,) how far, m, any robot point can move per unit of each controlled joint: 1 per metre of a
        prismatic joint; for a revolute one, the largest distance from its axis any point beyond it can have
        in any configuration (bounded by the link origins' chain from the joint to each link beyond it plus
        that link's reach from its own origin)."""
        c, r = self.client, self._robot
        origin = {i: (link_pose(c, self.robot, -1)[:3, 3] if i == -1 else
                      np.asarray(pb.getLinkState(self.robot, i, computeForwardKinematics=1, physicsClientId=c)[4]))
                  for i in r.names}
        reach = {}
        for i in r.names:
            lo, hi = pb.getAABB(self.robot, i, physicsClientId=c)
            corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
            reach[i] = float(np.linalg.norm(corners - origin[i], axis=1).max())
        children: dict[int, list[int]] = {}
        for info in r.joints.values():
            children.setdefault(r.links[info.parent_link], []).append(r.links[info.child_link])

        def lever(link: int, chain: float) -> float:
            return max([chain + reach[link]] + [lever(k, chain + float(np.linalg.norm(origin[k] - origin[link])))
                                                for k in children.get(link, [])])

        return np.array([1.0 if r.joints[n].type == "prismatic" else lever(r.links[r.joints[n].child_link], 0.0)
                         for n in self.robot_spec.joint_names])

    def freeze_parts(self, bodies) -> tuple[str, ...]:
        """Take the moving parts ``bodies`` (ids from :meth:`moving_parts`) out of the simulation: each is
        removed from the client with its joints' values and links' poses kept (:meth:`scene_joint_state`
        and :meth:`scene_link_pose` report them; velocities 0) until :meth:`thaw_parts` loads it again as it
        was. Only for parts at rest that nothing can reach (:mod:`simcheck.frozen_bodies` decides). Returns
        the frozen joints' names."""
        out = []
        for body in bodies:
            part = self._scene.parts.pop(body)
            values = {n: self.scene_joint_state(n)[0] for n, b in self._scene.joint_body.items() if b == body}
            for (b, index), name in self._scene.names.items():
                if b == body:
                    self._frozen_pose[name] = link_pose(self.client, b, index)
            unload_part(self.client, self._scene, body)
            self._frozen.update(values)
            self._frozen_parts.append((part, values))
            out.extend(values)
        return tuple(out)

    @property
    def frozen_joints(self) -> tuple[str, ...]:
        """The scene joints of the parts :meth:`freeze_parts` took out of the simulation (none after :meth:`thaw_parts`)."""
        return tuple(self._frozen)

    def thaw_parts(self) -> None:
        """Load every frozen part again, its joints at the values they had, at rest (idempotent)."""
        parts, self._frozen_parts = self._frozen_parts, []
        for part, values in parts:
            reload_part(self.client, self._scene, part, self.config, values)
        self._frozen.clear()
        self._frozen_pose.clear()

    # ------------------------------------------------------------------ images
    def render(self, target: np.ndarray, eye: np.ndarray, width: int = 320, height: int = 240,
               fov_deg: float = 60.0) -> np.ndarray:
        """(height, width, 3) uint8 RGB image from ``eye`` (3,) looking at ``target`` (3,), world frame, z up
        (:func:`simcheck.rendering.render`). Frozen parts (:meth:`freeze_parts`) are in the picture: each is
        loaded as visual shapes only for it and removed after, the last first (the simulation's arrays end as
        they were)."""
        shown = [picture_part(self.client, part, values) for part, values in self._frozen_parts] if self._visuals else []
        try:
            return render(self.client, target, eye, width, height, fov_deg)
        finally:
            for body in reversed(shown):
                pb.removeBody(body, physicsClientId=self.client)
