"""Errors of the report renderer: each names the file (and object/part/joint/task) that was wrong."""

from __future__ import annotations

from simcheck.errors import SimcheckError, SimcheckInputError

__all__ = ["ReportError", "ArtifactError"]


class ReportError(SimcheckError):
    """Base of every error raised while rendering report.html."""


class ArtifactError(ReportError, SimcheckInputError):
    """An artifact of the demo directory is unreadable or malformed (the message names the file)."""
