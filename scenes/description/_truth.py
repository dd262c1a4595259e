"""The only reader and writer of ``truth.json`` files (format :data:`TRUTH_FORMAT`, ``docs/contracts.md``).

They move the JSON document (a dict) to and from disk and check its format tag; ``scenes.truth_json``
turns a ground-truth :class:`scenes.Scene` into that dict and back, ``recon.metrics.truth`` reads what
the metrics compare from it.
"""

from __future__ import annotations

import json
from pathlib import Path

from collections.abc import Mapping

import numpy as np

from ._atomic import write_text_atomic
from ._errors import DescriptionError
from ._shape import Shape, ShapeKind

__all__ = ["TRUTH_FORMAT", "check_truth_format", "read_truth_doc", "write_truth_doc", "shape_from_truth",
           "truth_shape_dict"]

TRUTH_FORMAT = "partscene.truth/1"


def check_truth_format(doc, source: str = "truth.json") -> dict:
    """``doc`` when it is a dict tagged :data:`TRUTH_FORMAT`; else :class:`DescriptionError` naming ``source``."""
    if not isinstance(doc, dict) or doc.get("format") != TRUTH_FORMAT:
        got = doc.get("format") if isinstance(doc, dict) else type(doc).__name__
        raise DescriptionError(f"{source}: format is {got!r}, expected {TRUTH_FORMAT!r}")
    return doc


def read_truth_doc(path: str | Path) -> dict:
    """The JSON document of the ``truth.json`` at ``path`` (format checked).

    Raises:
        DescriptionError: missing or unreadable file, invalid JSON, or another format (names the file).
    """
    path = Path(path)
    try:
        doc = json.loads(path.read_text())
    except OSError as e:
        raise DescriptionError(f"{path}: cannot read: {e.strerror or e}") from e
    except UnicodeDecodeError as e:
        raise DescriptionError(f"{path}: cannot read: not UTF-8 text ({e})") from e
    except json.JSONDecodeError as e:
        raise DescriptionError(f"{path}: not valid JSON ({e.msg} at line {e.lineno})") from e
    return check_truth_format(doc, str(path))


def write_truth_doc(doc: dict, path: str | Path) -> Path:
    """Write ``doc`` (format checked) to ``path`` atomically, one-space indented; returns the path."""
    check_truth_format(doc, str(path))
    return write_text_atomic(path, json.dumps(doc, indent=1) + "\n")


def truth_shape_dict(shape: Shape) -> dict:
    """The ``truth.json`` entry of a part's box or cylinder ``shape`` (``T_part_shape`` = its ``T_link_shape``)."""
    T = [[float(x) for x in row] for row in shape.T_link_shape]
    if shape.kind is ShapeKind.BOX:
        return {"type": "box", "size": [float(x) for x in shape.size], "T_part_shape": T}
    if shape.kind is ShapeKind.CYLINDER:
        return {"type": "cylinder", "radius": shape.radius, "length": shape.length, "T_part_shape": T}
    raise ValueError(f"truth.json holds boxes and cylinders, not a {shape.kind.value}")


def shape_from_truth(entry, where: str) -> Shape:
    """The :class:`Shape` (in its part's frame) of one ``truth.json`` shape entry: ``box`` (``size``),
    ``cylinder`` (``radius``, ``length``) or ``sphere`` (``radius``), with ``T_part_shape`` (4, 4).

    Raises:
        DescriptionError: naming ``where``: not an object, a missing field, an unknown type, a size that is
            not positive and finite, or a pose that is not a finite 4x4.
    """
    if not isinstance(entry, Mapping):
        raise DescriptionError(f"{where}: a shape must be a JSON object, got {type(entry).__name__}")
    for key in ("type", "T_part_shape"):
        if key not in entry:
            raise DescriptionError(f"{where}: missing field {key!r}")
    kind = entry["type"]
    try:
        T = np.array(entry["T_part_shape"], dtype=np.float64)
    except (TypeError, ValueError):
        T = np.zeros(0)
    if T.shape != (4, 4) or not np.all(np.isfinite(T)):
        raise DescriptionError(f"{where}.T_part_shape: expected a finite 4x4 pose, got {entry['T_part_shape']!r:.80}")
    if kind not in ("box", "cylinder", "sphere"):
        raise DescriptionError(f"{where}: unknown shape type {kind!r} (box, cylinder or sphere)")
    try:
        if kind == "box":
            size = np.asarray(entry["size"], dtype=np.float64).reshape(-1)
        elif kind == "cylinder":
            size = np.array([2 * float(entry["radius"]), 2 * float(entry["radius"]), float(entry["length"])])
        else:
            size = np.full(3, 2 * float(entry["radius"]))
    except (KeyError, TypeError, ValueError) as exc:
        raise DescriptionError(f"{where}: bad {kind} shape: {type(exc).__name__}: {exc}") from exc
    if size.shape != (3,) or not np.all(np.isfinite(size)) or np.any(size <= 0):
        raise DescriptionError(f"{where}: bad {kind} shape: sizes must be positive and finite, got {size.tolist()}")
    return Shape(ShapeKind(kind), size, T)
