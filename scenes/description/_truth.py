"""The only reader and writer of ``truth.json`` files (format :data:`TRUTH_FORMAT`, ``docs/contracts.md``).

They move the JSON document (a dict) to and from disk and check its format tag; ``scenes.truth_json``
turns a ground-truth :class:`scenes.Scene` into that dict and back, ``recon.metrics.truth`` reads what
the metrics compare from it.
"""

from __future__ import annotations

import json
from pathlib import Path

from ._atomic import write_text_atomic
from ._errors import DescriptionError

__all__ = ["TRUTH_FORMAT", "check_truth_format", "read_truth_doc", "write_truth_doc"]

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
