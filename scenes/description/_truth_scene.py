"""The ``truth.json`` document read into checked, typed objects (:class:`TrueScene`): the one parser of its
objects, parts, shapes, joints and contact edges, used by ``recon.metrics`` (what the metrics compare).

Poses and joint axes/origins are in the WORLD frame, as in the file; each part's shapes are in the part's
frame. Every problem raises :class:`DescriptionError` naming the file, object, part, shape or joint.
Required per object: ``id``, ``category``, ``T_world_object``, ``parts`` (``id``, ``label``, ``T_world_part``,
``shapes``), ``joints`` (the whole part tree: ``name``, ``type``, ``parent_part_id``, ``child_part_id``) and
``contacts``; the rest takes the defaults of ``docs/contracts.md`` (limits 0, no handle, no dynamics, on the
floor, no walls).
"""

from __future__ import annotations

from collections.abc import Mapping
import dataclasses
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ._errors import DescriptionError
from ._model import JointType
from ._shape import Shape
from ._truth import check_truth_format, read_truth_doc, shape_from_truth

__all__ = ["TruePart", "TrueJoint", "TrueObject", "TrueWall", "TrueScene", "true_scene_from_doc", "read_true_scene"]


@dataclass(frozen=True)
class TruePart:
    """One true part: ``id``, semantic ``label``, URDF ``link`` name, ``T_world_part`` (4, 4) at joint value 0
    (metres), its ``shapes`` in the part frame, and its ``density`` (kg/m^3; ``None`` when not given)."""

    id: int
    label: str
    link: str
    T_world_part: np.ndarray
    shapes: tuple[Shape, ...]
    density: float | None = None


@dataclass(frozen=True)
class TrueJoint:
    """One true joint: URDF ``name``, ``type``, parent part id (``None``: the root's joint to the world),
    child part id, ``axis`` (3,) unit and ``origin`` (3,) metres in the world frame at q = 0, ``lower`` /
    ``upper`` (m or rad), the grasped handle's part id, and the URDF ``effort`` (N or N m), ``velocity``
    (m/s or rad/s), ``damping`` and ``friction`` (0 when not given)."""

    name: str
    type: JointType
    parent_part_id: int | None
    child_part_id: int
    axis: np.ndarray
    origin: np.ndarray
    lower: float = 0.0
    upper: float = 0.0
    handle_part_id: int | None = None
    effort: float = 0.0
    velocity: float = 0.0
    damping: float = 0.0
    friction: float = 0.0


@dataclass(frozen=True)
class TrueObject:
    """One true object: ``id``, ``name``, ``category``, ``T_world_object`` (4, 4), ``size`` (3,) metres of the
    closed object (nan when not given), parts, joints, undirected contact edges (part id pairs), and the id
    of the object it stands on (``None``: the floor)."""

    id: int
    name: str
    category: str
    T_world_object: np.ndarray
    size: np.ndarray
    parts: tuple[TruePart, ...]
    joints: tuple[TrueJoint, ...]
    contacts: tuple[tuple[int, int], ...]
    supported_by: int | None = None


@dataclass(frozen=True)
class TrueWall:
    """A wall box: ``name``, ``size`` (3,) metres, ``T_world_wall`` (4, 4) of its centre."""

    name: str
    size: np.ndarray
    T_world_wall: np.ndarray


@dataclass(frozen=True)
class TrueScene:
    """Every true object of one scene (``scene`` name and ``seed``), its walls and ``room_size`` (2,) metres."""

    scene: str
    seed: int
    objects: tuple[TrueObject, ...]
    walls: tuple[TrueWall, ...] = ()
    room_size: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(2))


def _pose(value: Any, where: str) -> np.ndarray:
    try:
        T = np.array(value, dtype=np.float64) if value is not None else np.zeros(0)
    except (TypeError, ValueError):
        T = np.zeros(0)
    if T.shape != (4, 4) or not np.all(np.isfinite(T)):
        raise DescriptionError(f"{where}: expected a finite 4x4 pose, got {value!r:.80}")
    return T


def _field(d: Mapping, key: str, where: str) -> Any:
    if not isinstance(d, Mapping) or key not in d:
        raise DescriptionError(f"{where}: missing field {key!r}")
    return d[key]


def _joint(j: Mapping, part_ids: set, where: str) -> TrueJoint:
    name = str(_field(j, "name", where))
    where = f"{where} joint {name}"
    try:
        jtype = JointType(_field(j, "type", where))
    except ValueError as exc:
        raise DescriptionError(f"{where}: unknown joint type {j.get('type')!r}") from exc
    axis = np.array(j.get("axis", [0.0, 0.0, 0.0]), dtype=np.float64).reshape(-1)
    origin = np.array(j.get("origin", [0.0, 0.0, 0.0]), dtype=np.float64).reshape(-1)
    if axis.shape != (3,) or origin.shape != (3,) or not np.all(np.isfinite(np.r_[axis, origin])):
        raise DescriptionError(f"{where}: axis and origin must be 3 finite numbers each")
    if jtype is not JointType.FIXED and abs(np.linalg.norm(axis) - 1.0) > 1e-6:
        raise DescriptionError(f"{where}: {jtype.value} axis {axis.tolist()} is not a unit vector")
    parent_raw = _field(j, "parent_part_id", where)
    parent = None if parent_raw is None else int(parent_raw)      # None: the root's joint to the world
    child = int(_field(j, "child_part_id", where))
    for side in (child,) if parent is None else (parent, child):
        if side not in part_ids:
            raise DescriptionError(f"{where}: names unknown part {side}")
    lower, upper = float(j.get("lower", 0.0)), float(j.get("upper", 0.0))
    if not (np.isfinite(lower) and np.isfinite(upper)):
        raise DescriptionError(f"{where}: limits must be finite")
    handle = j.get("handle_part_id")
    return TrueJoint(name, jtype, parent, child, axis, origin, lower, upper, None if handle is None else int(handle),
                     float(j.get("effort", 0.0)), float(j.get("velocity", 0.0)), float(j.get("damping", 0.0)),
                     float(j.get("friction", 0.0)))


def _object(o: Mapping, where: str) -> TrueObject:
    oid = int(_field(o, "id", where))
    name = str(o.get("name", f"object{oid}"))
    where = f"{where} object {oid} ({name})"
    parts = []
    for part in _field(o, "parts", where):
        pid = _field(part, "id", where)
        pwhere = f"{where} part {pid}"
        T_wp = _pose(_field(part, "T_world_part", pwhere), f"{pwhere}.T_world_part")
        shapes = _field(part, "shapes", pwhere)
        if not shapes:
            raise DescriptionError(f"{pwhere}: has no shapes")
        density = part.get("density")
        parts.append(TruePart(int(pid), str(_field(part, "label", pwhere)), str(part.get("link", "")), T_wp,
                              tuple(shape_from_truth(s, f"{pwhere} shape {k}") for k, s in enumerate(shapes)),
                              None if density is None else float(density)))
    if not parts:
        raise DescriptionError(f"{where}: has no parts")
    part_ids = {p.id for p in parts}
    if len(part_ids) != len(parts):
        raise DescriptionError(f"{where}: duplicate part ids")
    joints = [_joint(j, part_ids, where) for j in _field(o, "joints", where)]
    contacts = []
    for edge in _field(o, "contacts", where):
        if len(edge) != 2 or not set(int(e) for e in edge) <= part_ids or edge[0] == edge[1]:
            raise DescriptionError(f"{where}: contact edge {edge!r} must join two distinct parts of the object")
        contacts.append((int(edge[0]), int(edge[1])))
    return TrueObject(oid, name, str(_field(o, "category", where)),
                      _pose(_field(o, "T_world_object", where), f"{where}.T_world_object"),
                      np.array(o.get("size", [np.nan] * 3), dtype=np.float64), tuple(parts), tuple(joints),
                      tuple(contacts), None if o.get("supported_by") is None else int(o["supported_by"]))


def _wall(w: Mapping, where: str) -> TrueWall:
    name = str(_field(w, "name", where))
    size = np.array(_field(w, "size", f"{where} wall {name}"), dtype=np.float64).reshape(-1)
    if size.shape != (3,) or not np.all(np.isfinite(size)):
        raise DescriptionError(f"{where} wall {name}: size must be 3 finite numbers")
    return TrueWall(name, size, _pose(_field(w, "T_world_wall", f"{where} wall {name}"), f"{where} wall {name}.T_world_wall"))


def true_scene_from_doc(doc: Mapping, source: str = "truth.json") -> TrueScene:
    """The :class:`TrueScene` of a loaded ``truth.json`` document; ``source`` names it in error messages.

    Raises:
        DescriptionError: another format, a missing field, a bad pose, shape, joint or contact edge, or
            duplicate ids (naming ``source`` and the object, part, shape or joint).
    """
    check_truth_format(dict(doc) if isinstance(doc, Mapping) and not isinstance(doc, dict) else doc, source)
    objects = tuple(_object(o, source) for o in _field(doc, "objects", source))
    ids = [o.id for o in objects]
    if len(set(ids)) != len(ids):
        raise DescriptionError(f"{source}: duplicate object ids {sorted(ids)}")
    walls = tuple(_wall(w, source) for w in doc.get("walls", []))
    room = np.array(doc.get("room_size", [0.0, 0.0]), dtype=np.float64)
    return TrueScene(str(doc.get("scene", "")), int(doc.get("seed", 0) or 0), objects, walls, room)


def read_true_scene(path: str | Path) -> TrueScene:
    """Read and check the ``truth.json`` at ``path`` (:func:`read_truth_doc`, :func:`true_scene_from_doc`)."""
    return true_scene_from_doc(read_truth_doc(path), str(path))
