"""The object-level baseline's model library: whole articulated objects per category, in their own frame.

A :class:`Template` is one object model (the paper's [9] retrieves CAD models; we use the ``scenes``
generators' objects) described in its object frame (origin on the floor at the footprint centre,
x = front normal, z up): its parts' primitives, its joints and its part contact edges. The baseline
replaces a scanned object by a template *as a whole*; the parts only serve to carry the template's
joints over to the scan for the joint metrics.

:func:`library_from_generators` builds the default library: ``variants`` objects per category, each
from a fixed seed, so the library is the same on every run (and never the scene's own objects, whose
seeds differ).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Mapping

import numpy as np

from recon.model import JointEstimate, JointType
from recon.primitive import Primitive, volume_weighted_centre

__all__ = ["TemplatePart", "Template", "TemplateLibrary", "template_from_object", "library_from_generators",
           "DEFAULT_LIBRARY_SEED",
           "DEFAULT_VARIANTS"]

#: Seed of the default library (scene seeds are small integers; this keeps the library distinct).
DEFAULT_LIBRARY_SEED = 9001
#: Objects per category in the default library.
DEFAULT_VARIANTS = 3


@dataclass(frozen=True, eq=False)
class TemplatePart:
    """A template part: local id, semantic label, primitives in the template's object frame."""

    id: int
    label: str
    primitives: tuple[Primitive, ...]

    @property
    def centre(self) -> np.ndarray:
        """(3,) float, metres, object frame — volume-weighted centre of the part's primitives."""
        return volume_weighted_centre(self.primitives)


@dataclass(frozen=True, eq=False)
class Template:
    """One whole-object model of a category (object frame; ``T_world_part`` of its primitives means
    pose in the *object* frame here).

    name : e.g. ``"cabinet/1"``
    parts : the template's parts
    joints : its part-to-part joints (axis / origin in the object frame)
    contacts : its undirected part contact edges (local ids)
    bounds : (2, 3) float, metres — [min, max] of all primitives in the object frame
    """

    name: str
    category: str
    parts: tuple[TemplatePart, ...]
    joints: tuple[JointEstimate, ...]
    contacts: tuple[tuple[int, int], ...]
    bounds: np.ndarray

    @property
    def primitives(self) -> tuple[Primitive, ...]:
        return tuple(p for part in self.parts for p in part.primitives)

    def part(self, part_id: int) -> TemplatePart:
        for p in self.parts:
            if p.id == part_id:
                return p
        raise KeyError(f"template {self.name}: no part {part_id}")


TemplateLibrary = Mapping[str, tuple[Template, ...]]
"""{category: templates} — the small fixed library the baseline picks from."""


def _bounds(primitives) -> np.ndarray:
    pts = np.vstack([p.corners() for p in primitives])
    return np.stack([pts.min(axis=0), pts.max(axis=0)])


def template_from_object(obj, name: str) -> Template:
    """A :class:`Template` from a ``scenes.model.ArticulatedObject`` (its object frame, closed state)."""
    parts = []
    for part in obj.parts:
        prims = tuple(Primitive(s.kind.value, s.size, part.T_object_part @ s.T_link_shape) for s in part.shapes)
        parts.append(TemplatePart(int(part.id), str(part.label), prims))
    joints = []
    for j in obj.joints:
        if j.parent is None:
            continue
        joints.append(JointEstimate(f"{name}:{j.child}", JointType(j.type.value), int(j.parent), int(j.child),
                                    np.asarray(j.axis, float), np.asarray(j.origin, float), float(j.lower),
                                    float(j.upper), handle_part_id=None if j.handle is None else int(j.handle)))
    all_prims = [p for part in parts for p in part.primitives]
    return Template(name, str(obj.category), tuple(parts), tuple(joints),
                    tuple((int(a), int(b)) for a, b in obj.contacts), _bounds(all_prims))


def library_from_generators(variants: int = DEFAULT_VARIANTS, seed: int = DEFAULT_LIBRARY_SEED) -> TemplateLibrary:
    """``variants`` templates per category from the ``scenes`` generators, template k of category c from
    ``numpy.random.default_rng([seed, k])`` (deterministic; imported lazily so ``recon`` does not need
    ``scenes`` unless the default library is used)."""
    from scenes.generators import GENERATORS

    lib = {}
    for category, make in GENERATORS.items():
        lib[category] = tuple(template_from_object(make(np.random.default_rng([seed, k])), f"{category}/{k}")
                              for k in range(variants))
    return MappingProxyType(lib)
