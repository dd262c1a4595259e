"""The pinocchio + coal adapter: robot and scene kinematics and planning-time collision checking.

This is the only module of :mod:`planners` that imports ``pinocchio`` or ``coal``.

The robot's collision meshes are replaced by their convex hulls (coal ``buildConvexRepresentation``).
The scene URDF is loaded as a pinocchio model too and appended to the robot model, so the scene's
articulation state is part of the configuration: the task joint takes the value ``s`` of the check, every
other scene joint the value of ``scene_state``. A check covers robot self-collision (non-adjacent,
non-ignored link pairs), robot vs floor (a half-space on the scene's floor) and robot vs every scene geometry,
through pinocchio's broad-phase manager (coal's sorted sweep-and-prune, :data:`BROADPHASE`), all in C++.
Every call increments :attr:`PlanningWorld.checks`.

Frames: the world is the scene URDF's frame. The robot's root link stands at the floor frame's origin
(:meth:`RobotKinematics.standing_on`, :attr:`scenes.description.SceneFloor.T_scene_floor`; the world origin
for a floor at z = 0), so every pose (tool, frames, shoulder) is in the scene's frame and the base joints'
(x, y, yaw) are floor-frame coordinates.
"""

from __future__ import annotations

import copy
import functools
import hashlib
import logging
from collections import defaultdict
from pathlib import Path

import coal
import numpy as np
import pinocchio as pin

from planners.errors import RobotDescriptionError, SceneURDFError
from planners.robot import RobotSpec
from planners.scene_urdf import read_scene_urdf
from scenes.description import LEVEL_FLOOR, SceneFloor, SceneModel

__all__ = ["LIMIT_TOLERANCE", "PlanningWorld", "RobotKinematics"]

#: the broad phase of every planning check. Any broad phase gives the same answer: it only skips pairs whose
#: bounding boxes, grown by each pair's security margin, stay apart, so a check is true exactly when some active
#: pair is closer than its margin (coal's narrow phase on that pair). Coal's simple sweep-and-prune sorts the
#: boxes along one axis once per check; the dynamic AABB tree rebuilds itself at every check, which costs more
#: (measured in docs/decisions.md, "Planning CPU"). Coal's plain SaP manager is NOT used: it answered some
#: checks differently from the others (docs/decisions.md).
BROADPHASE = pin.BroadPhaseManager_SSaPCollisionManager

#: how far (rad or m) a configuration may lie beyond a joint limit and still count as within it: a robot
#: executed in physics rests on a limit up to rounding (a scenario's next task starts there)
LIMIT_TOLERANCE = 1e-9

log = logging.getLogger(__name__)


def _convexify(geom_model) -> None:
    """Replace every mesh of ``geom_model`` by its convex hull, in place."""
    for go in geom_model.geometryObjects:
        g = go.geometry
        if isinstance(g, coal.BVHModelBase):
            g.buildConvexRepresentation(False)
            go.geometry = g.convex


class RobotKinematics:
    """Robot model (pinocchio), convex collision geometry and the map from planned joints to ``q``.

    ``q`` arguments are ``(dof,)`` arrays in ``spec.joint_names`` order; the fingers are set separately.

    Attributes:
        floor: the :class:`scenes.description.SceneFloor` the robot stands on (:data:`LEVEL_FLOOR` as built).
        T_world_root: (4, 4) where the URDF's root link stands in the world: the floor frame.
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
        #: (dof,) bool: the prismatic planned joints (the base's x, y and a torso lift, metres)
        self.prismatic = np.array([self.model.joints[self.model.getJointId(n)].shortname().startswith("JointModelP")
                                   and "Planar" not in self.model.joints[self.model.getJointId(n)].shortname()
                                   for n in spec.joint_names])
        _convexify(self.geom_model)
        self.geom_links = [self.model.frames[go.parentFrame].name for go in self.geom_model.geometryObjects]
        self._add_self_pairs()
        self.geom_data = pin.GeometryData(self.geom_model)
        self.q_full = pin.neutral(self.model)
        self.set_fingers(spec.finger_open)
        # The shoulder: the first revolute arm joint; the prismatic arm joints before it (a torso lift) move it.
        arm_cols = np.arange(len(spec.base_joints), spec.dof)
        first = next((c for c in arm_cols if not self.prismatic[c]), arm_cols[0])
        self.lift_cols = np.array([c for c in arm_cols if c < first], dtype=int)
        self.shoulder_joint = self.model.getJointId(spec.joint_names[first])
        self.reach = self._reach()
        self.floor = LEVEL_FLOOR
        self.T_world_root = np.eye(4)

    def standing_on(self, floor: SceneFloor) -> "RobotKinematics":
        """This robot with its root link at the origin of ``floor``'s frame (itself for a level floor): the
        joints attached to the root are placed by ``floor.T_scene_floor`` in a copy of the model; the convex
        geometry is shared."""
        if floor == self.floor:
            return self
        out = copy.copy(self)
        T = floor.T_scene_floor
        M = pin.SE3(T[:3, :3], T[:3, 3]) * pin.SE3(self.T_world_root).inverse()
        out.model = self.model.copy()
        for j in range(1, out.model.njoints):
            if out.model.parents[j] == 0:
                out.model.jointPlacements[j] = M * out.model.jointPlacements[j]
        for i in range(1, len(out.model.frames)):
            f = out.model.frames[i]
            if f.parentJoint == 0:
                f.placement = M * f.placement
                out.model.frames[i] = f
        out.data = out.model.createData()
        out.geom_data = pin.GeometryData(out.geom_model)
        out.q_full = self.q_full.copy()
        out.floor, out.T_world_root = floor, T.copy()
        return out

    def in_root(self, T_world: np.ndarray) -> np.ndarray:
        """``T_world`` (4, 4) (or a point (3,)) in the robot's root frame, where the base joints' (x, y, yaw)
        are measured (the floor frame)."""
        T_world = np.asarray(T_world, dtype=float)
        if self.floor.level:
            return T_world.copy()
        T_root_world = np.linalg.inv(self.T_world_root)
        return T_root_world @ T_world if T_world.shape == (4, 4) else T_root_world[:3, :3] @ T_world + T_root_world[:3, 3]

    def _reach(self, n: int = 400) -> float:
        """Largest tool distance (m) from the shoulder's origin over ``n`` seeded random arm configurations,
        plus 5%: a cheap upper bound for rejecting stand poses out of reach."""
        rng = np.random.default_rng(0)
        best = 0.0
        for _ in range(n):
            q = rng.uniform(self.lower, self.upper)
            T = self.tool_pose(q)
            best = max(best, float(np.linalg.norm(T[:3, 3] - self.data.oMi[self.shoulder_joint].translation)))
        return 1.05 * best

    def shoulder(self, q: np.ndarray) -> np.ndarray:
        """``(3,)`` world position of the shoulder (the first revolute arm joint's origin) at ``q``."""
        qf = self.full_q(q)
        pin.forwardKinematics(self.model, self.data, qf)
        return np.array(self.data.oMi[self.shoulder_joint].translation)

    def shoulder_distance(self, q: np.ndarray, p: np.ndarray) -> float:
        """Distance (m) from the world point ``p (3,)`` to the shoulder, over the travel of the prismatic
        joints before it (a torso lift), the base and the other joints as in ``q (dof,)``."""
        a = q.copy()
        a[self.lift_cols] = self.lower[self.lift_cols]
        b = q.copy()
        b[self.lift_cols] = self.upper[self.lift_cols]
        pa, pb_ = self.shoulder(a), self.shoulder(b)
        d = pb_ - pa
        u = float(np.clip((p - pa) @ d / max(d @ d, 1e-12), 0.0, 1.0))
        return float(np.linalg.norm(p - (pa + u * d)))

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
        # homogeneous is a new array, the gathered columns too (in the gather's memory order, which the IK's matrix
        # products follow: another order would change their last bits)
        return pin.updateFramePlacement(self.model, self.data, self.tool_id).homogeneous, J[:, self.idx_q]

    def gripper_reach(self, direction=(0.0, 0.0, 1.0)) -> float:
        """How far, m, the gripper links' collision hulls reach past the tool frame's origin along ``direction``
        (3,) (tool frame; default its z, the approach axis), fingers as set (:meth:`set_fingers`): where the
        fingertips touch a face whose inward normal is ``direction``. Reads the gripper's own geometry at the
        home configuration."""
        key = float(self.q_full[self.idx_finger].sum()) if len(self.idx_finger) else 0.0
        cache = self.__dict__.setdefault("_gripper_points", {})
        if key not in cache:
            q = self.spec.home_q
            qf = self.full_q(q)
            pin.framesForwardKinematics(self.model, self.data, qf)
            pin.updateGeometryPlacements(self.model, self.data, self.geom_model, self.geom_data, qf)
            T_tool = self.tool_pose(q)
            grip, pts = set(self.spec.gripper_links), [np.zeros((1, 3))]
            for i, go in enumerate(self.geom_model.geometryObjects):
                g = go.geometry
                if self.geom_links[i] in grip and isinstance(g, coal.ConvexBase) and g.num_points:
                    M = self.geom_data.oMg[i].homogeneous
                    w = np.asarray(g.points())[: g.num_points] @ M[:3, :3].T + M[:3, 3]
                    pts.append((w - T_tool[:3, 3]) @ T_tool[:3, :3])
            cache[key] = np.concatenate(pts)
        d = np.asarray(direction, dtype=float)
        return float((cache[key] @ (d / np.linalg.norm(d))).max())

    def self_collision(self, q: np.ndarray) -> bool:
        """True when two non-adjacent, non-ignored robot links intersect at ``q``."""
        return bool(pin.computeCollisions(self.model, self.data, self.geom_model, self.geom_data,
                                          self.full_q(q), True))


class PlanningWorld:
    """Robot + scene for one task: collision checks as a function of ``(q, s)``.

    The scene model (names prefixed with ``scene::``) is appended to the robot model, so one configuration
    vector holds the robot joints and the scene joints; one geometry model holds the robot's convex hulls,
    the scene geometry and the floor; pinocchio's broad-phase manager (:data:`BROADPHASE`) answers a check in
    C++. Gripper-handle pairs are switched off while ``allow_grasp_contact`` is true.

    Args:
        robot: the robot's kinematics (shared across tasks).
        scene: parsed scene URDF.
        task_joint: URDF name of the joint whose value ``s`` each check takes.
        handle_geoms: ``{(link, collision_index)}`` scene geometries the gripper may touch when allowed.
        scene_state: values of other scene joints (default 0).
        clearance: metres; robot links other than the gripper must stay this far from the scene and the floor
            (coal security margin), so small tracking errors in execution do not touch the scene. While
            :meth:`keep_gripper_clear` is on (the free approach to the pre-grasp), the gripper keeps it too from
            every scene link but the part the task moves: a neighbouring front or handle, estimated a few
            millimetres off, is not brushed on the way; near the grasp (grasp, opening, release, retreat) the
            gripper may come as close as the grasp needs (a pinch next to the carcass).
        approach_clearance: metres the gripper keeps instead while :meth:`keep_gripper_clear` is on (None:
            ``clearance``).
    """

    PREFIX = "scene::"

    def __init__(self, robot: RobotKinematics, scene: SceneModel, task_joint: str,
                 handle_geoms: set, scene_state: dict | None = None, clearance: float = 0.0,
                 approach_clearance: float | None = None):
        self.robot = robot
        self.scene = scene
        self.task_joint = task_joint
        smodel, self.model, self.geom, key_of, nr, fi = _joined_models(robot, scene)
        self.smodel, self.sdata = smodel, smodel.createData()
        pre = self.PREFIX
        path = str(scene.path)
        self.data = self.model.createData()
        self.gdata = pin.GeometryData(self.geom)
        self.q = pin.neutral(self.model)
        self.q[: robot.model.nq] = robot.q_full
        self.sq_offset = robot.model.nq
        for name, value in (scene_state or {}).items():
            self._set_scene_joint(name, float(value))
        if not self.model.existJointName(pre + task_joint):
            raise SceneURDFError(f"{path}: pinocchio model has no joint {task_joint!r}")
        tj = self.model.joints[self.model.getJointId(pre + task_joint)]
        self.task_idx, self.task_nq = tj.idx_q, tj.nq      # nq 2: a continuous joint, stored as (cos, sin)
        self.s0 = float(self.q[self.task_idx]) if tj.nq == 1 else \
            float(np.arctan2(self.q[self.task_idx + 1], self.q[self.task_idx]))
        # Gripper-handle pairs, switched off while grasp contact is allowed.
        grip = {i for i, ln in enumerate(robot.geom_links) if ln in set(robot.spec.gripper_links)}
        handle = {i for i, go in enumerate(self.geom.geometryObjects) if key_of.get(go.name) in handle_geoms}
        self.grasp_pairs = [k for k, cp in enumerate(self.geom.collisionPairs)
                            if (cp.first in grip and cp.second in handle) or (cp.second in grip and cp.first in handle)]
        self.handle_geom_ids = sorted(handle)
        part = self._part_links(scene, task_joint)
        own = {i for i, go in enumerate(self.geom.geometryObjects) if key_of.get(go.name, ("",))[0] in part}
        self.arm_scene_pairs = []   # (non-gripper robot link, scene geometry) pairs: clearance queries
        self._gripper_part_pairs = []    # (gripper link, geometry of the task's part): a free move to push it
        self._gripper_scene_pairs = []   # (gripper link, scene geometry off the task's part): the free approach's
        for k, cp in enumerate(self.geom.collisionPairs):
            a, b = sorted((cp.first, cp.second))
            if a < nr and b >= nr and a not in grip:
                self.gdata.collisionRequests[k].security_margin = float(clearance)
                if b != fi:
                    self.arm_scene_pairs.append(k)
            elif a < nr and b >= nr and b != fi and b not in own:
                self._gripper_scene_pairs.append(k)
            elif a < nr and b >= nr and b in own:
                self._gripper_part_pairs.append(k)
        self._clearance = float(clearance)
        self._approach_clearance = float(clearance if approach_clearance is None else approach_clearance)
        self._allow = False
        self.manager = BROADPHASE(self.model, self.geom, self.gdata)
        self.checks = 0

    @staticmethod
    def _part_links(scene: SceneModel, joint: str) -> set:
        """The links the task's part consists of: the joint's child and the links fixed below it."""
        if joint not in scene.joints:
            return set()
        out, stack = set(), [scene.joints[joint].child]
        while stack:
            link = stack.pop()
            out.add(link)
            stack += [j.child for j in scene.child_joints(link) if j.type == "fixed"]
        return out

    def _set_scene_joint(self, name: str, value: float) -> None:
        full = self.PREFIX + name
        if not self.model.existJointName(full):
            raise SceneURDFError(f"{self.scene.path}: scene_state names joint {name!r}, which does not exist")
        j = self.model.joints[self.model.getJointId(full)]
        if j.nq == 1:
            self.q[j.idx_q] = value
        elif j.nq == 2:   # continuous: (cos, sin)
            self.q[j.idx_q:j.idx_q + 2] = (np.cos(value), np.sin(value))

    def _put_task(self, q: np.ndarray, s: float | None) -> None:
        """Write the task joint's value ``s`` (rad or m; None: its start value) into the full configuration ``q``."""
        s = self.s0 if s is None else float(s)
        if self.task_nq == 1:
            q[self.task_idx] = s
        else:
            q[self.task_idx:self.task_idx + 2] = (np.cos(s), np.sin(s))

    def keep_gripper_clear(self, on: bool, part: bool = False) -> None:
        """From now on the gripper keeps the clearance from scene links other than the task's part (``on``), and
        with ``part`` from the task's part too (a free move to push it), or may touch them (the default, near the
        grasp)."""
        for k in self._gripper_scene_pairs:
            self.gdata.collisionRequests[k].security_margin = self._approach_clearance if on else 0.0
        for k in self._gripper_part_pairs:
            self.gdata.collisionRequests[k].security_margin = self._approach_clearance if on and part else 0.0

    def _set_allow(self, allow: bool) -> None:
        if allow != self._allow:
            for k in self.grasp_pairs:
                if allow:
                    self.gdata.deactivateCollisionPair(k)
                else:
                    self.gdata.activateCollisionPair(k)
            self._allow = allow

    def in_collision(self, q: np.ndarray, s: float | None = None, allow_grasp_contact: bool = False) -> bool:
        """True when the robot at ``q (dof,)`` touches itself, the floor or the scene with the task joint at ``s``.

        ``allow_grasp_contact``: the gripper links may touch the handle geometry (grasp and opening).
        Joint limits are not checked here (see :meth:`within_limits`).
        """
        self.checks += 1
        self._set_allow(bool(allow_grasp_contact))
        self.q[self.robot.idx_q] = q
        self._put_task(self.q, s)
        return bool(pin.computeCollisions(self.model, self.data, self.manager, self.q, True))

    def colliding_pairs(self, q: np.ndarray, s: float | None = None, allow_grasp_contact: bool = False) -> list:
        """Names of every colliding geometry pair at ``(q, s)`` (for reasons and debugging)."""
        self._set_allow(bool(allow_grasp_contact))
        self.q[self.robot.idx_q] = q
        self._put_task(self.q, s)
        pin.computeCollisions(self.model, self.data, self.geom, self.gdata, self.q, False)
        out = []
        for k, r in enumerate(self.gdata.collisionResults):
            if r.isCollision() and self.gdata.activeCollisionPairs[k]:
                cp = self.geom.collisionPairs[k]
                out.append((self.geom.geometryObjects[cp.first].name, self.geom.geometryObjects[cp.second].name))
        return out

    def clearance(self, q: np.ndarray, s: float | None = None) -> float:
        """Smallest distance (m) between the robot's non-gripper links and the scene (floor excluded) at
        ``(q, s)``; negative when they penetrate. Costs one distance query per pair (~ms): for ranking."""
        self.q[self.robot.idx_q] = q
        self._put_task(self.q, s)
        pin.updateGeometryPlacements(self.model, self.data, self.geom, self.gdata, self.q)
        best = np.inf
        for k in self.arm_scene_pairs:
            best = min(best, pin.computeDistance(self.geom, self.gdata, k).min_distance)
        return float(best)

    def within_limits(self, q: np.ndarray) -> bool:
        """Whether ``q (dof,)`` lies within the robot's joint limits, up to :data:`LIMIT_TOLERANCE`."""
        return bool(np.all(q >= self.robot.lower - LIMIT_TOLERANCE) and np.all(q <= self.robot.upper + LIMIT_TOLERANCE))

    def moving_link_pose(self, s: float) -> np.ndarray:
        """``(4, 4)`` world pose of the task joint's child link at joint value ``s``."""
        q = self.q.copy()
        self._put_task(q, s)
        pin.framesForwardKinematics(self.model, self.data, q)
        fid = self.model.getFrameId(self.PREFIX + self.scene.joints[self.task_joint].child)
        return np.array(self.data.oMf[fid].homogeneous)


def _joined_models(robot: RobotKinematics, scene: SceneModel) -> tuple:
    """``(scene model, robot + scene model, robot + scene + floor geometry model, {geometry name: (link, index)},
    number of robot geometries, index of the floor)`` for :class:`PlanningWorld` (which never changes them): built
    once per robot and scene file contents when the scene has no meshes (a mesh file may change under an unchanged
    URDF), so the tasks of one scene (a batch, ``all-movable``) share them."""
    if any(c.mesh is not None for link in scene.links.values() for c in link.collisions):
        return _build_joined(robot, scene.path)
    try:
        digest = hashlib.sha1(Path(scene.path).read_bytes()).hexdigest()
    except OSError:
        return _build_joined(robot, scene.path)
    return _cached_joined(robot, str(scene.path), digest)


@functools.lru_cache(maxsize=4)
def _cached_joined(robot: RobotKinematics, path: str, digest: str) -> tuple:
    return _build_joined(robot, Path(path))


def _build_joined(robot: RobotKinematics, scene_path: Path) -> tuple:
    """See :func:`_joined_models`."""
    path = str(scene_path)
    try:
        smodel = pin.buildModelFromUrdf(path)
        sgeom = pin.buildGeomFromUrdf(smodel, path, pin.GeometryType.COLLISION,
                                      package_dirs=[str(Path(scene_path).parent)])
    except Exception as e:
        raise SceneURDFError(f"{path}: pinocchio cannot load the scene URDF ({e})") from e
    # (link, index) of every scene geometry, in URDF order per link (matches the pure reading), by the
    # geometry's name: pinocchio.appendModel reorders geometries (those fixed to the world first).
    pre = PlanningWorld.PREFIX
    counter = defaultdict(int)
    key_of = {}
    for go in sgeom.geometryObjects:
        link = smodel.frames[go.parentFrame].name
        key_of[pre + go.name] = (link, counter[link])
        counter[link] += 1
    for i in range(1, len(smodel.frames)):
        f = smodel.frames[i]
        f.name = pre + f.name
        smodel.frames[i] = f
    for i in range(1, smodel.njoints):
        smodel.names[i] = pre + smodel.names[i]
    for go in sgeom.geometryObjects:
        go.name = pre + go.name
    nr = robot.geom_model.ngeoms
    model, geom = pin.appendModel(robot.model, smodel, robot.geom_model.copy(), sgeom, 0, pin.SE3.Identity())
    up = robot.floor
    floor = pin.GeometryObject("floor", 0, 0, pin.SE3.Identity(),
                               coal.Halfspace(np.array(up.normal, dtype=float), float(up.height_m)))
    fi = geom.addGeometryObject(floor)
    for a in range(nr):
        geom.addCollisionPair(pin.CollisionPair(a, fi))
    return smodel, model, geom, key_of, nr, fi
