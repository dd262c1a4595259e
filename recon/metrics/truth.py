"""Reading ``truth.json`` (format ``partscene.truth/1``, docs/contracts.md) into what the metrics compare.

Only what the metrics need is read (objects, parts and their exact shapes, joints, contact edges); every
problem raises :class:`~recon.metrics.errors.TruthFormatError` naming the file, object, part or joint.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from recon.metrics.errors import TruthFormatError
from recon.model import JointEstimate, JointType
from recon.primitive import Primitive, volume_weighted_centre
from scenes.description import TRUTH_FORMAT, DescriptionError, check_truth_format, read_truth_doc, shape_from_truth

__all__ = ["TRUTH_FORMAT", "TruthPart", "TruthObject", "TruthScene", "read_truth", "truth_from_dict"]



@dataclass(frozen=True)
class TruthPart:
    """One true part: id, semantic label, URDF link name, pose at joint value 0, exact shapes (world)."""

    id: int
    label: str
    link: str
    T_world_part: np.ndarray
    primitives: tuple[Primitive, ...]

    @property
    def centre(self) -> np.ndarray:
        """(3,) float, metres, world — mean of the part's shape centres weighted by volume."""
        return volume_weighted_centre(self.primitives)


@dataclass(frozen=True)
class TruthObject:
    """One true object (see the truth.json schema)."""

    id: int
    name: str
    category: str
    T_world_object: np.ndarray
    size: np.ndarray
    parts: tuple[TruthPart, ...]
    joints: tuple[JointEstimate, ...]
    contacts: tuple[tuple[int, int], ...]

    @property
    def primitives(self) -> tuple[Primitive, ...]:
        """Every shape of every part, world frame."""
        return tuple(p for part in self.parts for p in part.primitives)

    def part(self, part_id: int) -> TruthPart:
        """The part with id ``part_id`` (``KeyError`` naming the object if absent)."""
        for part in self.parts:
            if part.id == part_id:
                return part
        raise KeyError(f"{self.name}: no part {part_id}")


@dataclass(frozen=True)
class TruthScene:
    """All true objects of one scene."""

    scene: str
    seed: int
    objects: tuple[TruthObject, ...]

    def object(self, object_id: int) -> TruthObject:
        """The object with id ``object_id`` (``KeyError`` naming the scene if absent)."""
        for obj in self.objects:
            if obj.id == object_id:
                return obj
        raise KeyError(f"scene {self.scene}: no object {object_id}")


def _pose(value: Any, where: str) -> np.ndarray:
    T = np.array(value, dtype=np.float64) if value is not None else np.zeros(0)
    if T.shape != (4, 4) or not np.all(np.isfinite(T)):
        raise TruthFormatError(f"{where}: expected a finite 4x4 pose, got {value!r:.80}")
    return T


def _field(d: Mapping, key: str, where: str) -> Any:
    if not isinstance(d, Mapping) or key not in d:
        raise TruthFormatError(f"{where}: missing field {key!r}")
    return d[key]


def _shape(shape: Mapping, T_world_part: np.ndarray, where: str) -> Primitive:
    try:
        s = shape_from_truth(shape, where)
    except DescriptionError as exc:
        raise TruthFormatError(str(exc)) from exc
    return Primitive(s.kind, s.size, T_world_part @ s.T_link_shape)


def _joint(j: Mapping, part_ids: set, where: str) -> JointEstimate:
    name = str(_field(j, "name", where))
    where = f"{where} joint {name}"
    try:
        jtype = JointType(_field(j, "type", where))
    except ValueError as exc:
        raise TruthFormatError(f"{where}: unknown joint type {j.get('type')!r}") from exc
    axis = np.array(j.get("axis", [0.0, 0.0, 0.0]), dtype=np.float64).reshape(-1)
    origin = np.array(j.get("origin", [0.0, 0.0, 0.0]), dtype=np.float64).reshape(-1)
    if axis.shape != (3,) or origin.shape != (3,) or not np.all(np.isfinite(np.r_[axis, origin])):
        raise TruthFormatError(f"{where}: axis and origin must be 3 finite numbers each")
    if jtype is not JointType.FIXED and abs(np.linalg.norm(axis) - 1.0) > 1e-6:
        raise TruthFormatError(f"{where}: {jtype.value} axis {axis.tolist()} is not a unit vector")
    parent_raw = _field(j, "parent_part_id", where)
    parent = None if parent_raw is None else int(parent_raw)      # None: the root's joint to the world
    child = int(_field(j, "child_part_id", where))
    for side in (child,) if parent is None else (parent, child):
        if side not in part_ids:
            raise TruthFormatError(f"{where}: names unknown part {side}")
    lower, upper = float(j.get("lower", 0.0)), float(j.get("upper", 0.0))
    if not (np.isfinite(lower) and np.isfinite(upper)):
        raise TruthFormatError(f"{where}: limits must be finite")
    handle = j.get("handle_part_id")
    return JointEstimate(name, jtype, parent, child, axis, origin, lower, upper,
                         handle_part_id=None if handle is None else int(handle))


def _object(o: Mapping, where: str) -> TruthObject:
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
            raise TruthFormatError(f"{pwhere}: has no shapes")
        prims = tuple(_shape(s, T_wp, f"{pwhere} shape {k}") for k, s in enumerate(shapes))
        parts.append(TruthPart(int(pid), str(_field(part, "label", pwhere)), str(part.get("link", "")), T_wp, prims))
    if not parts:
        raise TruthFormatError(f"{where}: has no parts")
    part_ids = {p.id for p in parts}
    if len(part_ids) != len(parts):
        raise TruthFormatError(f"{where}: duplicate part ids")
    joints = [_joint(j, part_ids, where) for j in o.get("joints", [])]
    contacts = []
    for edge in o.get("contacts", []):
        if len(edge) != 2 or not set(int(e) for e in edge) <= part_ids or edge[0] == edge[1]:
            raise TruthFormatError(f"{where}: contact edge {edge!r} must join two distinct parts of the object")
        contacts.append((int(edge[0]), int(edge[1])))
    return TruthObject(oid, name, str(_field(o, "category", where)),
                       _pose(_field(o, "T_world_object", where), f"{where}.T_world_object"),
                       np.array(o.get("size", [np.nan] * 3), dtype=np.float64), tuple(parts), tuple(joints),
                       tuple(contacts))


def truth_from_dict(data: Mapping, source: str = "truth.json") -> TruthScene:
    """Parse a loaded truth.json document; ``source`` names it in error messages."""
    try:
        check_truth_format(data if isinstance(data, dict) else dict(data) if isinstance(data, Mapping) else data,
                           source)
    except DescriptionError as exc:
        raise TruthFormatError(str(exc)) from exc
    objects = tuple(_object(o, source) for o in _field(data, "objects", source))
    ids = [o.id for o in objects]
    if len(set(ids)) != len(ids):
        raise TruthFormatError(f"{source}: duplicate object ids {sorted(ids)}")
    return TruthScene(str(data.get("scene", "")), int(data.get("seed", 0) or 0), objects)


def read_truth(path: str | Path) -> TruthScene:
    """Read and validate ``truth.json`` at ``path``."""
    path = Path(path)
    try:
        data = read_truth_doc(path)
    except DescriptionError as exc:
        raise TruthFormatError(str(exc)) from exc
    return truth_from_dict(data, str(path))
