"""Articulated templates: which joint a part gets, keyed by object category and part label.

A template gives the joint type of a child part and the parent labels it expects; the part tree uses
the expectation as a prior (a handle hangs from its drawer or door, not from the body beside it) and
the joint stage uses the type. A label without a template is a rigid part (fixed joint).
"""

from __future__ import annotations

from dataclasses import dataclass

from recon.model import JointType

__all__ = ["JointTemplate", "ROOT_LABELS", "MOVABLE_LABELS", "template_for", "expected_contact", "designed_neighbours"]

ROOT_LABELS = ("body", "frame", "base", "top", "seat", "mattress")
"""Labels that can be an object's base part (fixed to the world), in order of preference."""

_CASE = frozenset({"body", "frame", "base"})


@dataclass(frozen=True)
class JointTemplate:
    """joint : the child's joint type; parents : the parent labels the template expects."""

    joint: JointType
    parents: frozenset[str]


_BY_LABEL = {
    "drawer": JointTemplate(JointType.PRISMATIC, _CASE),
    "door": JointTemplate(JointType.REVOLUTE, _CASE),
    "handle": JointTemplate(JointType.FIXED, frozenset({"drawer", "door"})),
    "knob": JointTemplate(JointType.FIXED, frozenset({"drawer", "door"})),
    "leg": JointTemplate(JointType.FIXED, frozenset({"top", "seat", "frame", "base", "body"})),
    "top": JointTemplate(JointType.FIXED, frozenset({"leg", "body", "frame", "base"})),
    "seat": JointTemplate(JointType.FIXED, frozenset({"leg", "frame", "base", "body"})),
    "back": JointTemplate(JointType.FIXED, frozenset({"seat", "frame"})),
    "arm": JointTemplate(JointType.FIXED, frozenset({"seat", "frame"})),
    "headboard": JointTemplate(JointType.FIXED, frozenset({"frame"})),
    "mattress": JointTemplate(JointType.FIXED, frozenset({"frame"})),
    "shelf": JointTemplate(JointType.FIXED, frozenset({"body", "frame"})),
    "body": JointTemplate(JointType.FIXED, frozenset({"frame", "base"})),
    "frame": JointTemplate(JointType.FIXED, frozenset({"base", "leg"})),
}

_BY_CATEGORY: dict[tuple[str, str], JointTemplate] = {
    # a table's legs hang from its top, a chair's from its seat
    ("table", "leg"): JointTemplate(JointType.FIXED, frozenset({"top"})),
    ("chair", "leg"): JointTemplate(JointType.FIXED, frozenset({"seat"})),
    ("bed", "leg"): JointTemplate(JointType.FIXED, frozenset({"frame"})),
}

MOVABLE_LABELS = frozenset(k for k, t in _BY_LABEL.items() if t.joint is not JointType.FIXED)


def template_for(category: str, label: str) -> JointTemplate | None:
    """The template of a part ``label`` in an object of ``category``; None = no template (rigid)."""
    return _BY_CATEGORY.get((category, label)) or _BY_LABEL.get(label)


_NEIGHBOURS: dict[str, frozenset[frozenset[str]]] = {
    # a mattress rests against its headboard (two children of the frame that touch by design); a leg
    # beside the headboard touches it only by accident of where the generator or carpenter put it
    "bed": frozenset({frozenset({"headboard", "mattress"})}),
}
"""Per category: label pairs that touch by design without one hanging from the other."""


def expected_contact(category: str, label_a: str, label_b: str) -> bool:
    """True when the templates expect parts ``label_a`` and ``label_b`` of a ``category`` object to
    touch: one is a parent the other's template expects (either way round), a label without a
    template is involved, or the pair is a designed neighbour contact (a bed's mattress against its
    headboard)."""
    ta, tb = template_for(category, label_a), template_for(category, label_b)
    if ta is None or tb is None or label_b in ta.parents or label_a in tb.parents:
        return True
    return designed_neighbours(category, label_a, label_b)


def designed_neighbours(category: str, label_a: str, label_b: str) -> bool:
    """True when parts ``label_a`` and ``label_b`` of a ``category`` object touch by design without one
    hanging from the other (a bed's mattress against its headboard)."""
    return frozenset({label_a, label_b}) in _NEIGHBOURS.get(category, frozenset())
