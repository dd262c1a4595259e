"""The robot URDF loaded into a PyBullet client with a fixed base on the floor (at the floor frame's origin;
the world origin when the floor is z = 0: a mobile base is modelled by its base joints), bound by name to a :class:`simcheck.robot_binding.SimRobot`: the
controlled joints, the fingers and their closing directions, the gripper and base links. The base links
never collide with the floor (a mobile base stands on it)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from simcheck.bullet import body_joint_table, c_output_logged, link_pose, pb, pybullet_said
from simcheck.bullet_poses import quat_xyzw_from_R
from simcheck.errors import RobotBindingError
from simcheck.joint_table import JointInfo
from simcheck.robot_binding import SimRobot

__all__ = ["LoadedRobot", "load_robot"]


@dataclass(frozen=True)
class LoadedRobot:
    """A robot as loaded in one PyBullet client.

    body : its body id
    joints : joint name -> :class:`JointInfo`; links : link name -> link index (base: -1)
    names : link index -> link name
    q_index : link/joint indices of ``robot.joint_names``; finger_index : of ``robot.finger_joints``
    forces : (dof,) motor force of each controlled joint, N or N*m (the URDF effort, at least 1)
    gripper_links : indices of the gripper, finger and tool links; finger_links : of the finger links
    base_links : indices of the base links and -1 (their floor contacts are never reported)
    finger_closing : finger link name -> (3,) unit direction, tool frame, in which it moves when closing
    """

    body: int
    joints: dict[str, JointInfo]
    links: dict[str, int]
    names: dict[int, str]
    q_index: list[int]
    finger_index: list[int]
    forces: list[float]
    gripper_links: set[int]
    finger_links: set[int]
    base_links: set[int]
    finger_closing: dict[str, np.ndarray]


def load_robot(client: int, robot: SimRobot, floor: int, visuals: bool = True,
               T_world_root: np.ndarray | None = None) -> LoadedRobot:
    """Load ``robot.urdf`` into ``client`` and bind it to ``robot``; ``floor`` is the floor's body id. Without
    ``visuals`` its visual meshes are left out (nothing to render then; ~5x faster to load, same physics).
    ``T_world_root`` (4, 4): where the URDF's root link stands (the floor frame,
    :attr:`scenes.description.SceneFloor.T_scene_floor`); None: the world origin.

    Raises:
        RobotBindingError: PyBullet cannot load the URDF, a joint or link named by ``robot`` is not in it,
            or a finger link does not move when the gripper closes.
    """
    try:
        with c_output_logged(f"loading robot {robot.urdf}") as said:
            at = {} if T_world_root is None or np.array_equal(T_world_root, np.eye(4)) else {
                "basePosition": np.asarray(T_world_root)[:3, 3].tolist(),
                "baseOrientation": quat_xyzw_from_R(np.asarray(T_world_root)[:3, :3])}
            body = pb.loadURDF(str(robot.urdf), useFixedBase=True,
                              flags=0 if visuals else pb.URDF_IGNORE_VISUAL_SHAPES, physicsClientId=client, **at)
    except pb.error as exc:
        raise RobotBindingError(f"PyBullet cannot load robot URDF {robot.urdf}: {exc}{pybullet_said(said)}") from exc
    joints, links = body_joint_table(client, body)
    for name in robot.joint_names + robot.finger_joints:
        if name not in joints:
            raise RobotBindingError(f"robot URDF {robot.urdf} has no joint {name!r}")
    for name in (robot.tool_link,) + robot.gripper_links + robot.finger_links + robot.base_links:
        if name not in links:
            raise RobotBindingError(f"robot URDF {robot.urdf} has no link {name!r}")
    q_index = [joints[n].index for n in robot.joint_names]
    finger_index = [joints[n].index for n in robot.finger_joints]
    for j in range(pb.getNumJoints(body, physicsClientId=client)):
        pb.changeDynamics(body, j, linearDamping=0.0, angularDamping=0.0, physicsClientId=client)
    base = {links[n] for n in robot.base_links} | {-1}
    loaded = LoadedRobot(
        body=body, joints=joints, links=links, names={v: k for k, v in links.items()}, q_index=q_index,
        finger_index=finger_index, forces=[max(joints[n].max_force, 1.0) for n in robot.joint_names],
        gripper_links={links[n] for n in robot.gripper_links + robot.finger_links + (robot.tool_link,)},
        finger_links={links[n] for n in robot.finger_links}, base_links=base,
        finger_closing=_finger_closing_directions(client, body, links, finger_index, robot))
    for link in base:
        # a mobile base stands on the floor: those contacts are never reported (robot_contacts) and
        # only add friction rows for the base motors to fight every step
        pb.setCollisionFilterPair(body, floor, link, -1, 0, physicsClientId=client)
    return loaded


def _finger_closing_directions(client: int, body: int, links: dict[str, int], finger_index: list[int],
                               robot: SimRobot) -> dict[str, np.ndarray]:
    """finger link name -> (3,) unit direction, in the tool frame, in which the finger moves when the
    gripper closes (its link origin from fully open to fully closed, the arm at its loaded pose)."""
    tool = links[robot.tool_link]
    at = {}
    for fingers in (robot.finger_open, robot.finger_closed):
        pb.resetJointStatesMultiDof(body, finger_index, [[v] for v in fingers], physicsClientId=client)
        T_tool = link_pose(client, body, tool)
        for name in robot.finger_links:
            p = link_pose(client, body, links[name])[:3, 3]
            at.setdefault(name, []).append(T_tool[:3, :3].T @ (p - T_tool[:3, 3]))
    pb.resetJointStatesMultiDof(body, finger_index, [[v] for v in robot.finger_open], physicsClientId=client)
    out = {}
    for name, (p_open, p_closed) in at.items():
        d = p_closed - p_open
        if np.linalg.norm(d) < 1e-6:
            raise RobotBindingError(f"robot {robot.urdf}: finger link {name!r} does not move when the gripper "
                                    f"closes (finger_open {robot.finger_open}, finger_closed {robot.finger_closed})")
        out[name] = d / np.linalg.norm(d)
    return out
