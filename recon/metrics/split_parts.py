"""Parts a reconstruction created by splitting one labelled part, matched to the true parts they are.

A segmentation that gives one label to several fronts leaves the truth's other fronts without a label of
their own; when recon splits that part (:mod:`recon.front_split`), the new parts carry ids the scan never
had, so their joints could never be matched to the truth's by id. An estimated part whose id is no true
part's is taken for the true part -- one the estimate has no part of -- whose box holds its centre (the
volume-weighted centre of its primitives, world frame; the true part's box: the smallest box in the
part's frame around its shapes, so a hollow drawer holds the centre of its estimate); each true part at
most once, the part whose centre is nearest the true part's first. Joints and contact edges are then scored under the true
ids; a split the truth does not bear out (a centre inside no unmatched true part) stays unmatched.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Mapping

import numpy as np

from recon.metrics.objects import ObjectEstimate
from recon.metrics.truth import TruthObject, TruthPart
from recon.primitive import volume_weighted_centre

__all__ = ["true_ids_of_new_parts", "renamed_estimate"]


def true_ids_of_new_parts(truth: TruthObject, estimate: ObjectEstimate) -> dict[int, int]:
    """``{estimated part id: true part id}`` for the estimated parts whose ids the truth does not have."""
    true_ids = {p.id for p in truth.parts}
    est_ids = set(estimate.part_ids)
    new = sorted(i for i in est_ids if i not in true_ids)
    unseen = [p for p in truth.parts if p.id not in est_ids]
    if not new or not unseen:
        return {}
    centres = {i: volume_weighted_centre([s for s, j in zip(estimate.primitives, estimate.part_ids) if j == i])
               for i in new}
    pairs = sorted((float(np.linalg.norm(centres[i] - t.centre)), i, t.id) for i in new for t in unseen
                   if _in_part_box(centres[i], t))
    out: dict[int, int] = {}
    for _, i, t in pairs:
        if i not in out and t not in out.values():
            out[i] = t
    return out


def _in_part_box(p: np.ndarray, part: TruthPart) -> bool:
    """Whether the world point ``p`` (3,) lies in the smallest box, in ``part``'s frame, around its shapes."""
    R, t = part.T_world_part[:3, :3], part.T_world_part[:3, 3]
    local = np.concatenate([s.corners() for s in part.primitives]) - t
    q = local @ R
    x = (p - t) @ R
    return bool(np.all(x >= q.min(axis=0)) and np.all(x <= q.max(axis=0)))


def renamed_estimate(estimate: ObjectEstimate, ids: Mapping[int, int]) -> ObjectEstimate:
    """``estimate`` with its part ids (primitives, joints' child and parent, contact edges) renamed by ``ids``."""
    if not ids:
        return estimate

    def r(i):
        return ids.get(i, i)

    joints = tuple(replace(j, child_part_id=r(j.child_part_id),
                           parent_part_id=None if j.parent_part_id is None else r(j.parent_part_id))
                   for j in estimate.joints)
    scores = {(r(p), r(q)): s for (p, q), s in estimate.contact_scores.items()}
    return replace(estimate, joints=joints, contact_scores=scores, part_ids=tuple(r(i) for i in estimate.part_ids))
