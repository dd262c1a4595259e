"""A scene URDF loaded into a PyBullet client as separate bodies (:mod:`simcheck.scene_bodies`), with
every link and joint addressed by name, the joint friction emulated and the collisions filtered.

On load it

* lets PyBullet validate the whole URDF once and reads its joint table exactly as PyBullet parses it (once
  per file contents and process: :func:`_whole_table`);
* loads each never-moving link as a static single-link body and each articulated subtree as a small
  fixed-base body (measured speed: docs/decisions.md, "PyBullet step settings");
* disables the default velocity motors PyBullet puts on every scene joint (they lock drawers and
  doors) and replaces them with a zero-velocity motor whose force is the joint's Coulomb friction
  (PyBullet applies URDF ``damping`` but ignores ``friction``: it is emulated here);
* disables collisions between a link and its never-moving ancestors, and between scene links in contact
  as loaded: closer than ``rest_contact_gap``, touching or interpenetrating (:func:`simcheck.contacts.rest_contacts`;
  sibling fronts and doors in their frames of a third-party file often touch; partscene's own scene.urdf
  and truth.urdf keep their links apart, recon.clearance). Pairs deeper than ``overlap_tolerance`` are
  logged as a warning. Every such pair is kept in ``LoadedScene.rest_contacts`` with its depth at rest, so
  that execution can tell when they interpenetrate further (docs/decisions.md, "Touching at rest").
"""

from __future__ import annotations

import dataclasses
import hashlib
import logging
import tempfile
import threading
from collections import OrderedDict
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from scenes.description import DescriptionError, read_urdf
from simcheck.bullet import body_joint_table, c_output_logged, link_pose, pb, pybullet_said
from simcheck.bullet_poses import quat_xyzw_from_R
from simcheck.config import PhysicsConfig
from simcheck.contacts import rest_contacts
from simcheck.errors import SceneLoadError
from simcheck.joint_table import JointInfo
from simcheck.scene_bodies import ANCHOR, scene_bodies

__all__ = ["LoadedScene", "load_scene", "reload_part", "unload_part", "picture_part"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class LoadedScene:
    """A scene as loaded in one PyBullet client.

    link_at : scene link name -> (body id, link index)
    names : (body id, link index) -> scene link name
    static_pose : never-moving link name -> T_world_link (4, 4), metres
    links : scene link name -> (body id, link index), in URDF order
    joints : scene joint name -> :class:`JointInfo` (index in its body; -1 for a fixed joint between
        never-moving links), in URDF order
    joint_body : scene joint name -> the body id holding it (joints with an index >= 0)
    disabled_overlaps : (link a, link b, depth m) of each pair overlapping deeper than ``overlap_tolerance``
    rest_contacts : (link a, link b, penetration at rest m, negative: a gap) of each pair in contact as
        loaded (their collisions disabled; the deep overlaps included)
    parts : body id -> the moving part loaded as it (what :func:`reload_part` loads again; parts whose URDF
        uses mesh pieces of the loading's temporary folder are left out)
    flags : the PyBullet loadURDF flags of the moving parts
    """

    link_at: dict[str, tuple[int, int]]
    names: dict[tuple[int, int], str]
    static_pose: dict[str, np.ndarray]
    links: dict[str, tuple[int, int]]
    joints: dict[str, JointInfo]
    joint_body: dict[str, int]
    disabled_overlaps: tuple[tuple[str, str, float], ...]
    rest_contacts: tuple[tuple[str, str, float], ...] = ()
    parts: dict = dataclasses.field(default_factory=dict)
    flags: int = 0


def load_scene(client: int, scene_urdf: Path, config: PhysicsConfig, visuals: bool = True) -> LoadedScene:
    """Load ``scene_urdf`` into ``client`` (see the module docstring); without ``visuals`` the visual shapes
    are left out (nothing to render then; the physics is the same).

    Raises:
        SceneLoadError: PyBullet cannot load the file or a part of it, or it cannot be split (names the file).
    """
    c = client
    plain = pb.URDF_USE_INERTIA_FROM_FILE | (0 if visuals else pb.URDF_IGNORE_VISUAL_SHAPES)
    flags = plain | pb.URDF_USE_SELF_COLLISION | pb.URDF_USE_SELF_COLLISION_EXCLUDE_ALL_PARENTS
    key = _file_key(Path(scene_urdf))     # the file read and hashed once: both caches below use it
    joints, links = _whole_table(c, scene_urdf, flags, key)
    link_at: dict[str, tuple[int, int]] = {}
    names: dict[tuple[int, int], str] = {}
    static_pose: dict[str, np.ndarray] = {}
    joint_at: dict[str, tuple[int, int]] = {}
    parts: dict[int, _Body] = {}
    with tempfile.TemporaryDirectory(prefix="partscene_scene_") as tmp:
        for k, part in enumerate(_bodies(scene_urdf, tmp, key)):
            body = _load_part(c, Path(tmp) / f"body{k}.urdf", part, flags if part.moving else plain,
                              f"a part of scene URDF {scene_urdf}")
            bj, bl = _register(c, body, link_at, names, joint_at)
            if not part.moving:
                static_pose[next(iter(bl))] = link_pose(c, body, -1)
                continue
            _set_up_moving(c, body, part, bj, bl, joints, config, static_pose, link_at)
            if tmp not in part.urdf:                # no mesh piece of the temporary folder: loadable again
                parts[body] = part
    disabled, resting = _filter_initial_overlaps(c, scene_urdf, names, config.overlap_tolerance,
                                                 config.rest_contact_gap)
    return LoadedScene(
        link_at=link_at, names=names, static_pose=static_pose,
        links={name: link_at[name] for name in links},
        joints={name: dataclasses.replace(info, index=joint_at[name][1] if name in joint_at else -1)
                for name, info in joints.items()},
        joint_body={name: joint_at[name][0] for name in joints if name in joint_at}, disabled_overlaps=disabled,
        rest_contacts=resting, parts=parts, flags=flags)


def _load_part(c: int, path: Path, part: "_Body", flags: int, what: str) -> int:
    path.write_text(part.urdf)
    try:
        with c_output_logged(f"loading {what}") as said:
            return pb.loadURDF(str(path), part.position, part.quat_xyzw, useFixedBase=True, flags=flags,
                               physicsClientId=c)
    except pb.error as exc:
        raise SceneLoadError(f"PyBullet cannot load {what}: {exc}{pybullet_said(said)}") from exc


def _register(c: int, body: int, link_at: dict, names: dict, joint_at: dict) -> tuple[dict, dict]:
    """Enter ``body``'s links and joints into the name tables; returns its (joint table, link table)."""
    bj, bl = body_joint_table(c, body)
    for name, index in bl.items():
        if name != ANCHOR:
            link_at[name] = (body, index)
            names[(body, index)] = name
    for info in bj.values():
        joint_at[info.name] = (body, info.index)
    return bj, bl


def _set_up_moving(c: int, body: int, part: "_Body", bj: dict, bl: dict, joints: dict[str, JointInfo],
                   config: PhysicsConfig, static_pose: dict, link_at: dict) -> None:
    """A moving part's joints get their friction motor and damping; its links never collide with its
    never-moving ancestors."""
    for info in bj.values():
        if info.type in ("revolute", "prismatic"):
            friction = max(joints[info.name].friction, config.min_joint_friction)
            pb.setJointMotorControl2(body, info.index, pb.VELOCITY_CONTROL, targetVelocity=0.0,
                                     force=friction, physicsClientId=c)
            pb.changeDynamics(body, info.index, linearDamping=config.scene_joint_damping,
                              angularDamping=config.scene_joint_damping, physicsClientId=c)
    for ancestor in part.static_ancestors:       # a link never collides with its ancestors
        if ancestor in static_pose:
            for index in bl.values():
                pb.setCollisionFilterPair(body, link_at[ancestor][0], index, -1, 0, physicsClientId=c)


def unload_part(client: int, scene: LoadedScene, body: int) -> None:
    """Remove the moving part ``body`` (one of ``scene.parts``) from the client and from ``scene``'s name
    tables; :func:`reload_part` puts it back."""
    for key in [k for k in scene.names if k[0] == body]:
        del scene.link_at[scene.names.pop(key)]
    for name in [n for n, b in scene.joint_body.items() if b == body]:
        del scene.joint_body[name]
    pb.removeBody(body, physicsClientId=client)


def reload_part(client: int, scene: LoadedScene, part: "_Body", config: PhysicsConfig,
                joint_values: dict[str, float]) -> int:
    """Load the moving ``part`` again (as :func:`load_scene` did: friction motors, damping, collision filters
    with its ancestors and with the links it touched at rest) with its joints at ``joint_values`` (name ->
    m or rad), at rest; enter it into ``scene``'s name tables. Returns its new body id."""
    c = client
    with tempfile.TemporaryDirectory(prefix="partscene_part_") as tmp:
        body = _load_part(c, Path(tmp) / "part.urdf", part, scene.flags, "a scene part again")
    joint_at: dict[str, tuple[int, int]] = {}
    bj, bl = _register(c, body, scene.link_at, scene.names, joint_at)
    joints = {name: scene.joints[name] for name in bj}
    _set_up_moving(c, body, part, bj, bl, joints, config, scene.static_pose, scene.link_at)
    for name, (b, index) in joint_at.items():
        scene.joint_body[name] = b
        if name in joint_values and bj[name].type in ("revolute", "prismatic"):
            pb.resetJointState(b, index, float(joint_values[name]), 0.0, physicsClientId=c)
    own = {n for n in bl if n != ANCHOR}
    for a, b, _ in scene.rest_contacts:                  # collisions disabled at load stay disabled
        if a in own or b in own:
            (ba, ia), (bb, ib) = scene.link_at[a], scene.link_at[b]
            pb.setCollisionFilterPair(ba, bb, ia, ib, 0, physicsClientId=c)
    scene.parts[body] = part
    return body


@dataclass(frozen=True)
class _Body:
    """A :class:`simcheck.scene_bodies.SceneBody` as PyBullet loads it: its root's position (3,) m and
    quaternion (x, y, z, w)."""

    urdf: str
    position: list
    quat_xyzw: tuple
    moving: bool
    static_ancestors: tuple


#: how many scenes' bodies :func:`_bodies` and joint tables :func:`_whole_table` keep
BODIES_KEPT = 8
_kept_bodies: OrderedDict[tuple, tuple] = OrderedDict()
_kept_tables: OrderedDict[tuple, tuple] = OrderedDict()
_kept_lock = threading.Lock()


def _file_key(path: Path) -> tuple | None:
    """(absolute path, SHA-256 of the bytes) of the file at ``path``; None when it cannot be read."""
    try:
        return str(path.absolute()), hashlib.sha256(path.read_bytes()).digest()
    except OSError:
        return None


def _kept(store: OrderedDict, key: tuple | None):
    """What ``store`` keeps under ``key`` (None: nothing)."""
    with _kept_lock:
        kept = store.get(key)
        if kept is not None:
            store.move_to_end(key)
        return kept


def _keep(store: OrderedDict, key: tuple, value) -> None:
    """Keep ``value`` in ``store`` under ``key``; the oldest beyond :data:`BODIES_KEPT` go."""
    with _kept_lock:
        store[key] = value
        while len(store) > BODIES_KEPT:
            store.popitem(last=False)


def _whole_table(c: int, scene_urdf: Path, flags: int,
                 key: tuple | None) -> tuple[dict[str, JointInfo], dict[str, int]]:
    """(joint name -> :class:`JointInfo`, link name -> link index) of ``scene_urdf`` loaded whole, as PyBullet
    parses it: loaded into ``c`` (which validates the file), read and removed. The tables of the last
    :data:`BODIES_KEPT` files are kept under the file's path and SHA-256 (a batch certifies many tasks of one
    scene in one process, each in fresh worlds): an unchanged file is not loaded whole again. ``key``: the
    file's :func:`_file_key`."""
    kept = _kept(_kept_tables, key)
    if kept is not None:
        return dict(kept[0]), dict(kept[1])
    try:
        with c_output_logged(f"loading {scene_urdf}") as said:
            whole = pb.loadURDF(str(scene_urdf), useFixedBase=True, flags=flags, physicsClientId=c)
    except pb.error as exc:
        raise SceneLoadError(f"PyBullet cannot load scene URDF {scene_urdf}: {exc}"
                             f"{pybullet_said(said)}") from exc
    joints, links = body_joint_table(c, whole)
    pb.removeBody(whole, physicsClientId=c)
    if key is not None:
        _keep(_kept_tables, key, (dict(joints), dict(links)))
    return joints, links


def _bodies(scene_urdf: Path, mesh_dir: str, key: tuple | None) -> tuple:
    """The bodies of ``scene_urdf`` (:func:`simcheck.scene_bodies.scene_bodies`, mesh pieces written into
    ``mesh_dir``). The last :data:`BODIES_KEPT` scenes whose split wrote no mesh piece are kept under the
    file's path and SHA-256 (a batch certifies many tasks of one scene in one process, each in fresh worlds):
    an unchanged file is not split again; the same bodies, computed the same way, so the same physics. The key
    is the URDF's bytes: a moving link's mesh replaced by one of several pieces under an unchanged URDF, within
    one process, would keep its old (unsplit) body. ``key``: the file's :func:`_file_key`."""
    kept = _kept(_kept_bodies, key)
    if kept is not None:
        return kept
    try:
        parts = scene_bodies(read_urdf(scene_urdf), mesh_dir=mesh_dir)
    except DescriptionError as exc:
        raise SceneLoadError(f"cannot split scene URDF {scene_urdf} into bodies: {exc}") from exc
    bodies = tuple(_Body(p.urdf, p.T_world_root[:3, 3].tolist(), quat_xyzw_from_R(p.T_world_root[:3, :3]), p.moving,
                         p.static_ancestors) for p in parts)
    if key is not None and not any(Path(mesh_dir).iterdir()):     # mesh pieces live only while loading
        _keep(_kept_bodies, key, bodies)
    return bodies


def _filter_initial_overlaps(client: int, scene_urdf: Path, names: dict[tuple[int, int], str],
                             tolerance: float, gap: float) -> tuple[tuple, tuple]:
    """Disable collision between scene links in contact as loaded (closer than ``gap`` m: touching or
    interpenetrating); returns ((link a, link b, depth m) of the pairs deeper than ``tolerance``, each logged
    as a warning; (link a, link b, penetration at rest m, negative: a gap) of every such pair)."""
    pb.performCollisionDetection(physicsClientId=client)
    seen = rest_contacts(pb.getContactPoints(physicsClientId=client), names, gap)
    for a, b in seen:
        pb.setCollisionFilterPair(a[0], b[0], a[1], b[1], 0, physicsClientId=client)
    resting = tuple((names[a], names[b], depth) for (a, b), depth in seen.items())
    disabled = tuple(r for r in resting if r[2] > tolerance)
    for a, b, depth in disabled:
        log.warning("scene %s: links %s and %s overlap by %.1f mm as loaded: collisions between them "
                    "disabled", scene_urdf, a, b, depth * 1e3)
    for a, b, depth in resting:
        if depth <= tolerance:
            log.info("scene %s: links %s and %s touch at rest (%.1f mm): they do not block each other",
                     scene_urdf, a, b, depth * 1e3)
    return disabled, resting


def picture_part(client: int, part: "_Body", joint_values: dict[str, float]) -> int:
    """Load ``part`` for pictures only: its visual shapes, no collision shape (nothing collides with it, nothing
    of the simulation sees it), joints at ``joint_values`` (name -> m or rad). Returns its body id; remove it
    (``pb.removeBody``) before the next step, the last loaded first."""
    with tempfile.TemporaryDirectory(prefix="partscene_part_") as tmp:
        body = _load_part(client, Path(tmp) / "part.urdf", part,
                          pb.URDF_USE_INERTIA_FROM_FILE | pb.URDF_IGNORE_COLLISION_SHAPES, "a scene part's picture")
    joints, _ = body_joint_table(client, body)
    for name, info in joints.items():
        if name in joint_values and info.type in ("revolute", "prismatic"):
            pb.resetJointState(body, info.index, float(joint_values[name]), 0.0, physicsClientId=client)
    return body
