"""What the metrics compare on the estimate side: :class:`ObjectEstimate`, one object's primitives,
joints and contact scores (the truth side lives in :mod:`recon.metrics.truth`).

It is the common currency of the part-level reconstruction (:func:`estimate_from_reconstruction`) and of
the object-level baseline (:mod:`recon.baseline`). Frames: world, z up, metres, radians. Joints are
:class:`recon.model.JointEstimate` on both sides (truth and estimate).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

import numpy as np

from recon.config import ReconConfig
from recon.metrics.errors import EstimateError
from recon.model import JointEstimate, ObjectReconstruction
from recon.primitive import Primitive

__all__ = ["ObjectEstimate", "estimate_from_reconstruction"]


@dataclass(frozen=True)
class ObjectEstimate:
    """One reconstructed object as the metrics consume it.

    object_id : the object's id in the scan's labels (= its id in truth.json)
    category : e.g. ``"cabinet"``
    primitives : the object's solid primitives, world frame (one per part for the part-level method,
        the whole scaled template for the object-level baseline)
    joints : estimated joints, matched to the truth by ``child_part_id`` (a method without parts has
        none: every true joint then counts as missing)
    contact_scores : ``{(part_p, part_q): score >= 0}`` estimated contact edges with their Eq. 1 contact
        scores, directed or undirected (see :mod:`recon.metrics.kinematic_ap`); empty for a method
        without parts, whose AP is then 0 for every object with true edges
    seconds : wall time spent reconstructing this object (``nan`` if unknown)
    part_ids : the scan part id of each primitive, parallel to ``primitives`` (empty when the method
        has no parts); used only by the per-part diagnostics (:mod:`recon.metrics.part_errors`)
    """

    object_id: int
    category: str
    primitives: tuple[Primitive, ...]
    joints: tuple[JointEstimate, ...] = ()
    contact_scores: Mapping[tuple[int, int], float] = field(default_factory=dict)
    seconds: float = float("nan")
    part_ids: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "object_id", int(self.object_id))
        prims = tuple(self.primitives)
        where = f"object {self.object_id} ({self.category})"
        if not prims:
            raise EstimateError(f"{where}: the estimate has no primitives")
        for p in prims:
            if not isinstance(p, Primitive):
                raise EstimateError(f"{where}: primitives must be recon.Primitive, got {type(p).__name__}")
            if not np.all(np.isfinite(p.T_world_part)):
                raise EstimateError(f"{where}: a {p.kind.value} primitive has a NaN/inf pose")
        for j in self.joints:
            if not isinstance(j, JointEstimate):
                raise EstimateError(f"{where}: joints must be recon.JointEstimate, got {type(j).__name__}")
        part_ids = tuple(int(i) for i in self.part_ids)
        if part_ids and len(part_ids) != len(prims):
            raise EstimateError(f"{where}: {len(part_ids)} part ids for {len(prims)} primitives")
        object.__setattr__(self, "part_ids", part_ids)
        object.__setattr__(self, "primitives", prims)
        object.__setattr__(self, "joints", tuple(self.joints))
        scores = {(int(p), int(q)): float(s) for (p, q), s in dict(self.contact_scores).items()}
        object.__setattr__(self, "contact_scores", MappingProxyType(scores))


def estimate_from_reconstruction(obj: ObjectReconstruction, config: ReconConfig,
                                 seconds: float = float("nan")) -> ObjectEstimate:
    """The metrics' view of one object of :func:`recon.reconstruct`: the geometry it writes to scene.urdf
    (each part's ``solids``: its articulated-template shapes, else its fitted primitive), its joints (the
    world joint of the root is kept; it matches no true joint) and every Eq. 1 contact with its score
    (not only the tree edges: the AP ranks all of them), scored by :func:`recon.part_tree.contact_scores`
    with ``config``, the reconstruction's config (``rec.config``)."""
    from recon.part_tree import contact_scores

    solids = [(p.part_id, s) for p in obj.parts for s in p.solids]
    return ObjectEstimate(obj.id, obj.category, tuple(s for _, s in solids), tuple(obj.joints),
                          contact_scores(obj, config.tree), seconds, tuple(i for i, _ in solids))
