"""The words partscene agrees on: object categories, part labels and their display colours.

``SCENE_CATEGORIES`` / ``PART_LABELS`` are what ``scenes`` generates and the DESIGN scan format promises
to understand; ``KNOWN_CATEGORIES`` / ``KNOWN_LABELS`` are what ``recon`` reads without a warning (a few
more names of the same families); ``FRONT_CATEGORIES`` are the articulated categories whose drawers and
doors face the room.
"""

from __future__ import annotations

__all__ = ["SCENE_CATEGORIES", "KNOWN_CATEGORIES", "FRONT_CATEGORIES", "PART_LABELS", "KNOWN_LABELS",
           "LABEL_RGBA", "DEFAULT_RGBA"]

SCENE_CATEGORIES = frozenset({"cabinet", "microwave", "refrigerator", "table", "chair", "bed"})
KNOWN_CATEGORIES = SCENE_CATEGORIES | frozenset({"oven", "dishwasher", "wardrobe", "desk", "sofa", "shelf"})
FRONT_CATEGORIES = ("cabinet", "microwave", "refrigerator")

PART_LABELS = frozenset({"body", "drawer", "door", "handle", "top", "leg", "seat", "back", "arm", "frame",
                         "headboard", "mattress", "shelf"})
KNOWN_LABELS = PART_LABELS | frozenset({"knob", "base"})

LABEL_RGBA = {
    "body": (0.75, 0.62, 0.45, 1), "drawer": (0.55, 0.75, 0.90, 1), "door": (0.90, 0.60, 0.45, 1),
    "handle": (0.25, 0.25, 0.28, 1), "top": (0.70, 0.55, 0.35, 1), "leg": (0.45, 0.33, 0.22, 1),
    "seat": (0.65, 0.45, 0.30, 1), "back": (0.55, 0.40, 0.30, 1), "arm": (0.50, 0.36, 0.26, 1),
    "frame": (0.55, 0.45, 0.35, 1), "headboard": (0.45, 0.35, 0.30, 1),
    "mattress": (0.92, 0.92, 0.88, 1), "shelf": (0.80, 0.75, 0.65, 1), "wall": (0.85, 0.85, 0.82, 1),
}
"""RGBA in [0, 1] of each part label (and ``wall``), for URDF materials, previews and scan colours."""

DEFAULT_RGBA = (0.6, 0.6, 0.6, 1)
"""RGBA of a label not in :data:`LABEL_RGBA`."""
