"""How partscene names the links and joints of a scene URDF.

Ground truth (``scenes``) and reconstruction (``recon``) both name things this way, so a joint of a
reconstruction and the same joint of the truth share one URDF name; ``simcheck certify --against``
matches joints by that name.

    object_name("cabinet", 3)              -> "cabinet3"
    link_name("cabinet", 3, "drawer", 12)  -> "cabinet3_drawer12"
    joint_name("cabinet", 3, "drawer", 12) -> "cabinet3_drawer12_joint"

The joint is named after its child link. The joint that fixes an object's root part to the world is
``f"{link_name(...)}_joint"`` as well (its parent is the ``world`` link).
"""

from __future__ import annotations

import hashlib
import re

__all__ = ["WORLD_LINK", "object_name", "link_name", "joint_name", "parse_link_name", "file_stem"]

WORLD_LINK = "world"

_SAFE = re.compile(r"[^A-Za-z0-9]+")
_LINK = re.compile(r"^(?P<category>[a-z]+)(?P<object_id>\d+)_(?P<label>[a-z]+)(?P<part_id>\d+)$")


def _token(text: str) -> str:
    """Lower-case ``text`` with every run of non-alphanumerics removed (URDF- and pinocchio-safe)."""
    return _SAFE.sub("", str(text)).lower() or "x"


def object_name(category: str, object_id: int) -> str:
    """Name of object ``object_id`` of ``category``, e.g. ``"cabinet3"``."""
    return f"{_token(category)}{int(object_id)}"


def link_name(category: str, object_id: int, label: str, part_id: int) -> str:
    """URDF link name of part ``part_id`` (semantic ``label``) of object ``object_id``."""
    return f"{object_name(category, object_id)}_{_token(label)}{int(part_id)}"


def joint_name(category: str, object_id: int, label: str, part_id: int) -> str:
    """URDF name of the joint whose child is part ``part_id``."""
    return f"{link_name(category, object_id, label, part_id)}_joint"


def parse_link_name(name: str) -> dict | None:
    """Inverse of :func:`link_name`: ``{"category", "object_id", "label", "part_id"}`` or ``None``."""
    m = _LINK.match(name)
    if m is None:
        return None
    d = m.groupdict()
    return {"category": d["category"], "object_id": int(d["object_id"]),
            "label": d["label"], "part_id": int(d["part_id"])}


#: the longest file stem :func:`file_stem` makes of a name (characters, before its hash suffix)
STEM_LENGTH = 100


def file_stem(name: str) -> str:
    """A file stem for ``name`` (a joint's, for its rollout and images): the name itself when it is made of
    ``[A-Za-z0-9._-]`` and at most :data:`STEM_LENGTH` long; otherwise the sanitised, shortened name plus
    8 hex digits of its SHA-1, so two names never share a file. The one place names become file names."""
    safe = "".join(ch if ch.isascii() and (ch.isalnum() or ch in "-_.") else "_" for ch in name)
    if safe == name and len(name) <= STEM_LENGTH and name not in (".", ".."):
        return name
    return f"{safe[:STEM_LENGTH]}-{hashlib.sha1(name.encode()).hexdigest()[:8]}"
