"""The error base every partscene package derives from.

    PartsceneError                 base of every error partscene raises on purpose
    └── InputError (ValueError)    the input cannot be used (CLIs exit 2; the message names what and where)
        └── DescriptionError       a URDF or truth.json is missing or malformed (names the file and element)

``scenes``, ``recon``, ``planners`` and ``simcheck`` keep their own error classes (``ScenesError``,
``ReconError``, ``PlannerError``, ``SimcheckError``, ...) as subclasses of these.
"""

from __future__ import annotations

__all__ = ["PartsceneError", "InputError", "DescriptionError"]


class PartsceneError(Exception):
    """Base of every error raised by partscene."""


class InputError(PartsceneError, ValueError):
    """A bad input: a file, argument or field that cannot be used (the message names it)."""


class DescriptionError(InputError):
    """A scene description on disk (URDF, truth.json) is missing or malformed (names the file and element)."""
