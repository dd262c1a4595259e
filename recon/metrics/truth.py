"""``truth.json`` (format ``partscene.truth/1``, docs/contracts.md) as what the metrics compare.

The file is read and checked by the scene description (:func:`scenes.description.true_scene_from_doc`);
this module poses each part's shapes in the world (:class:`~recon.primitive.Primitive`) and gives the
joints as :class:`~recon.model.JointEstimate`, like an estimate. Every problem raises
:class:`~recon.metrics.errors.TruthFormatError` naming the file, object, part or joint.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Mapping

import numpy as np

from recon.metrics.errors import TruthFormatError
from recon.model import JointEstimate
from recon.primitive import Primitive, volume_weighted_centre
from scenes.description import TRUTH_FORMAT, DescriptionError, TrueObject, read_truth_doc, true_scene_from_doc

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


def _object(o: TrueObject) -> TruthObject:
    parts = tuple(TruthPart(p.id, p.label, p.link, p.T_world_part,
                            tuple(Primitive(sh.kind, sh.size, p.T_world_part @ sh.T_link_shape) for sh in p.shapes))
                  for p in o.parts)
    joints = tuple(JointEstimate(j.name, j.type, j.parent_part_id, j.child_part_id, j.axis, j.origin, j.lower, j.upper,
                                 handle_part_id=j.handle_part_id) for j in o.joints)
    return TruthObject(o.id, o.name, o.category, o.T_world_object, o.size, parts, joints, o.contacts)


def truth_from_dict(data: Mapping, source: str = "truth.json") -> TruthScene:
    """Parse a loaded truth.json document (:func:`scenes.description.true_scene_from_doc`); ``source`` names
    it in error messages."""
    try:
        true = true_scene_from_doc(data, source)
    except DescriptionError as exc:
        raise TruthFormatError(str(exc)) from exc
    return TruthScene(true.scene, true.seed, tuple(_object(o) for o in true.objects))


def read_truth(path: str | Path) -> TruthScene:
    """Read and validate ``truth.json`` at ``path``."""
    path = Path(path)
    try:
        data = read_truth_doc(path)
    except DescriptionError as exc:
        raise TruthFormatError(str(exc)) from exc
    return truth_from_dict(data, str(path))
