"""The pinocchio + coal adapter: robot and scene kinematics and planning-time collision checking.

This is the only module of :mod:`planners` that imports ``pinocchio`` or ``coal``.

The robot and the scene are two pinocchio models. The robot's collision meshes are replaced by their
convex hulls (coal ``buildConvexRepresentation``), which is what makes a check cheap (~20 µs). The
scene's articulation state is a configuration: the task joint takes the value ``s`` of the check, every
other scene joint the value of ``scene_state``. Scene geometry is split into

- *static* objects (everything the task joint does not move) in one coal broad-phase tree, built once;
- *moving* objects (the subtree of the moving link except the handle) re-posed at each ``s``;
- *handle* objects, which the gripper links may touch while grasping/opening (``allow_grasp_contact``).

A check answers: robot self-collision (pinocchio's pair list, in C++), robot vs floor (a half-space at
z = 0), robot vs static, moving and handle objects. Every call increments :attr:`PlanningWorld.checks`.
"""

from __future__ import annotations

import logging
from collections import defaultdict

import coal
import numpy as np
import pinocchio as pin

from planners.errors import RobotDescriptionError, SceneURDFError
from planners.robot import RobotSpec
from planners.scene_urdf import SceneDescription, read_scene_urdf

__all__ = ["PlanningWorld", "RobotKinematics"]

log = logging.getLogger(__name__)


def _convexify(geom_model) -> None:
    """Replace every mesh of ``geom_model`` by its convex hull, in place."""
    for go in geom_model.geometryObjects:
        g = go.geometry
        if isinstance(g, coal.BVHModelBase):
            g.buildConvexRepresentation(False)
            go.geometry = g.convex


def _transform(M) -> coal.Transform3s:
    return coal.Transform3s(np.array(M.rotation), np.array(M.translation))


class RobotKinematics:
    """Robot model (pinocchio), convex collision geometry and the map from planned joints to ``q``.

    ``q`` arguments are ``(dof,)`` arrays in ``spec.joint_names`` order; the fingers are set separately.
    """

    def __init__(self, spec: RobotSpec):
        self.spec = spec
        path = str(spec.urdf)
        try:
            self.model = pin.buildModelFromUrdf(path)
            self.geom_model = pin.buildGeomFromUrdf(self.model, path, pin.GeometryType.COLLISION)
        except Exception as e:  # pinocchio raises plain ValueError/RuntimeError with its own text
            raise RobotDescriptionError(f"{path}: pinocchio cannot load the robot URDF ({e})") from e
        self.data = self.model.createData()
        self.idx_q = np.array([self._joint_index(n) for n in spec.joint_names])
        self.idx_finger = np.array([self._joint_index(n) for n in spec.finger_joints], dtype=int)
        if not self.model.existFrame(spec.tool_frame):
            raise RobotDescriptionError(f"{path}: tool frame {spec.tool_frame!r} does not exist")
        self.tool_id = self.model.getFrameId(spec.tool_frame)
        self.lower = np.array(self.model.lowerPositionLimit)[self.idx_q]
        self.upper = np.array(self.model.upperPositionLimit)[self.idx_q]
        _convexify(self.geom_model)
        self.geom_links = [self.model.frames[go.parentFrame].name for go in self.geom_model.geometryObjects]
        self._add_self_pairs()
        self.geom_data = pin.GeometryData(self.geom_model)
        self.q_full = pin.neutral(self.model)
        self.set_fingers(spec.finger_open)

    def _joint_index(self, name: str) -> int:
        if not self.model.existJointName(name):
            raise RobotDescriptionError(f"{self.spec.urdf}: joint {name!r} of the RobotSpec is not in the URDF")
        j = self.model.joints[self.model.getJointId(name)]
        if j.nq != 1:
            raise RobotDescriptionError(f"{self.spec.urdf}: joint {name!r} must have one coordinate, has {j.nq}")
        return j.idx_q

    def _add_self_pairs(self) -> None:
        desc = read_scene_urdf(self.spec.urdf)
        adjacent = {frozenset((j.parent, j.child)) for j in desc.joints.values()}
        ignore = adjacent | {frozenset(p) for p in self.spec.ignore_pairs}
        n = len(self.geom_links)
        for a in range(n):
            for b in range(a + 1, n):
                la, lb = self.geom_links[a], self.geom_links[b]
                if la != lb and frozenset((la, lb)) not in ignore:
                    self.geom_model.addCollisionPair(pin.CollisionPair(a, b))

    def set_fingers(self, value: float) -> None:
        """Set every finger joint to ``value`` (metres per finger) for the following checks."""
        self.q_full[self.idx_finger] = value

    def full_q(self, q: np.ndarray) -> np.ndarray:
        out = self.q_full.copy()
        out[self.idx_q] = q
        return out

    def tool_pose(self, q: np.ndarray) -> np.ndarray:
        """``(4, 4)`` pose of the tool frame in the world at ``q (dof,)``."""
        qf = self.full_q(q)
        pin.framesForwardKinematics(self.model, self.data, qf)
        return np.array(self.data.oMf[self.tool_id].homogeneous)

    def frame_pose(self, q: np.ndarray, frame: str) -> np.ndarray:
        """``(4, 4)`` pose of any robot ``frame`` in the world at ``q (dof,)``."""
        qf = self.full_q(q)
        pin.framesForwardKinematics(self.model, self.data, qf)
        return np.array(self.data.oMf[self.model.getFrameId(frame)].homogeneous)

    def tool_pose_jacobian(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Tool pose ``(4, 4)`` and its ``(6, dof)`` Jacobian (linear; angular), world-aligned at the tool."""
        qf = self.full_q(q)
        J = pin.computeFrameJacobian(self.model, self.data, qf, self.tool_id, pin.LOCAL_WORLD_ALIGNED)
        pin.updateFramePlacement(self.model, self.data, self.tool_id)
        return np.array(self.data.oMf[self.tool_id].homogeneous), np.array(J[:, self.idx_q])

    def self_collision(self, q: np.ndarray) -> bool:
        """True when two non-adjacent, non-ignored robot links intersect at ``q``."""
        return bool(pin.computeCollisions(self.model, self.data, self.geom_model, self.geom_data,
                                          self.full_q(q), True))

    def placements(self) -> list:
        """Geometry placements (pinocchio SE3) of the last self-collision call."""
        return self.geom_data.oMg


class PlanningWorld:
    """Robot + scene for one task: collision checks as a function of ``(q, s)``.

    Parameters
    ----------
    robot : the robot's kinematics (shared across tasks).
    scene : parsed scene URDF.
    task_joint : URDF name of the joint whose value ``s`` each check takes.
    handle_geoms : ``{(link, collision_index)}`` scene geometries the gripper may touch when allowed.
    scene_state : values of other scene joints (default 0).
    """

    def __init__(self, robot: RobotKinematics, scene: SceneDescription, task_joint: str,
                 handle_geoms: set, scene_state: dict | None = None):
        self.robot = robot
        self.scene = scene
        self.task_joint = task_joint
        path = str(scene.path)
        try:
            self.smodel = pin.buildModelFromUrdf(path)
            self.sgeom = pin.buildGeomFromUrdf(self.smodel, path, pin.GeometryType.COLLISION,
                                               package_dirs=[str(scene.path.parent)])
        except Exception as e:
            raise SceneURDFError(f"{path}: pinocchio cannot load the scene URDF ({e})") from e
        self.sdata = self.smodel.createData()
        self.sgdata = pin.GeometryData(self.sgeom)
        self.sq = pin.neutral(self.smodel)
        for name, value in (scene_state or {}).items():
            self._set_scene_joint(name, float(value))
        if not self.smodel.existJointName(task_joint):
            raise SceneURDFError(f"{path}: pinocchio model has no joint {task_joint!r}")
        self.task_idx = self.smodel.joints[self.smodel.getJointId(task_joint)].idx_q
        self.s0 = float(self.sq[self.task_idx])
        moving = set(scene.subtree_links(scene.joints[task_joint].child))
        # Geometry objects in URDF order per link: match (link, index) of the pure reading.
        counter = defaultdict(int)
        pin.forwardKinematics(self.smodel, self.sdata, self.sq)
        pin.updateGeometryPlacements(self.smodel, self.sdata, self.sgeom, self.sgdata)
        self.static_mgr = coal.DynamicAABBTreeCollisionManager()
        self._keep = []
        self.floor = coal.CollisionObject(coal.Halfspace(np.array([0.0, 0.0, 1.0]), 0.0), coal.Transform3s())
        self.static_mgr.registerObject(self.floor)
        self.moving, self.handle = [], []   # (geometry index, CollisionObject)
        for gi, go in enumerate(self.sgeom.geometryObjects):
            link = self.smodel.frames[go.parentFrame].name
            key = (link, counter[link])
            counter[link] += 1
            obj = coal.CollisionObject(go.geometry, _transform(self.sgdata.oMg[gi]))
            obj.computeAABB()
            self._keep.append(obj)
            if key in handle_geoms:
                self.handle.append((gi, obj))
            elif link in moving:
                self.moving.append((gi, obj))
            else:
                self.static_mgr.registerObject(obj)
        self.static_mgr.setup()
        grip = set(robot.spec.gripper_links)
        self.robot_objs = [coal.CollisionObject(go.geometry, coal.Transform3s())
                           for go in robot.geom_model.geometryObjects]
        self.grip_mask = np.array([ln in grip for ln in robot.geom_links])
        self.robot_mgr = coal.DynamicAABBTreeCollisionManager()
        for o in self.robot_objs:
            self.robot_mgr.registerObject(o)
        self.robot_mgr.setup()
        self._req = coal.CollisionRequest()
        self._res = coal.CollisionResult()
        self._cb = coal.CollisionCallBackDefault()
        self._s_posed = None
        self.checks = 0

    def _set_scene_joint(self, name: str, value: float) -> None:
        if not self.smodel.existJointName(name):
            raise SceneURDFError(f"{self.scene.path}: scene_state names joint {name!r}, which does not exist")
        j = self.smodel.joints[self.smodel.getJointId(name)]
        if j.nq == 1:
            self.sq[j.idx_q] = value
        elif j.nq == 2:   # continuous: (cos, sin)
            self.sq[j.idx_q:j.idx_q + 2] = (np.cos(value), np.sin(value))

    def _pose_moving(self, s: float) -> None:
        if self._s_posed == s:
            return
        self.sq[self.task_idx] = s
        pin.forwardKinematics(self.smodel, self.sdata, self.sq)
        pin.updateGeometryPlacements(self.smodel, self.sdata, self.sgeom, self.sgdata)
        for gi, obj in self.moving + self.handle:
            obj.setTransform(_transform(self.sgdata.oMg[gi]))
            obj.computeAABB()
        self._s_posed = s

    def _pair(self, a, b) -> bool:
        self._res.clear()
        return coal.collide(a, b, self._req, self._res) > 0

    def in_collision(self, q: np.ndarray, s: float | None = None, allow_grasp_contact: bool = False) -> bool:
        """True when the robot at ``q (dof,)`` touches itself, the floor or the scene with the task joint at ``s``.

        ``allow_grasp_contact``: the gripper links may touch the handle geometry (grasp and opening).
        Joint limits are not checked here (see :meth:`within_limits`).
        """
        self.checks += 1
        rb = self.robot
        if rb.self_collision(q):
            return True
        for o, M in zip(self.robot_objs, rb.placements()):
            o.setTransform(_transform(M))
            o.computeAABB()
        self.robot_mgr.update()
        self._cb.init()
        self.robot_mgr.collide(self.static_mgr, self._cb)
        if self._cb.data.result.isCollision():
            return True
        self._pose_moving(self.s0 if s is None else float(s))
        for o in self.robot_objs:
            ao = o.getAABB()
            for _, m in self.moving:
                if ao.overlap(m.getAABB()) and self._pair(o, m):
                    return True
        for o, g in zip(self.robot_objs, self.grip_mask):
            if allow_grasp_contact and g:
                continue
            ao = o.getAABB()
            for _, m in self.handle:
                if ao.overlap(m.getAABB()) and self._pair(o, m):
                    return True
        return False

    def within_limits(self, q: np.ndarray) -> bool:
        return bool(np.all(q >= self.robot.lower) and np.all(q <= self.robot.upper))

    def moving_link_pose(self, s: float) -> np.ndarray:
        """``(4, 4)`` world pose of the task joint's child link at joint value ``s``."""
        sq = self.sq.copy()
        sq[self.task_idx] = s
        pin.framesForwardKinematics(self.smodel, self.sdata, sq)
        fid = self.smodel.getFrameId(self.scene.joints[self.task_joint].child)
        T = np.array(self.sdata.oMf[fid].homogeneous)
        self._s_posed = None   # data was overwritten
        return T
