"""Errors raised by the metrics when their inputs cannot be used.

Every message names the file, object, part or joint and what was wrong with it, so a failing benchmark
or test points at the datum to fix, never at a line deep inside numpy. They are :class:`recon.ReconError`
(the project's reconstruction error hierarchy) and ``ValueError``.

    ReconError
    └── MetricsError
        ├── TruthFormatError   truth.json (or its dict) does not follow partscene.truth/1
        └── EstimateError      an estimate is malformed (NaN pose, zero size, unknown part, bad score)
"""

from __future__ import annotations

from scenes.description import InputError

from recon.errors import ReconError

__all__ = ["MetricsError", "TruthFormatError", "EstimateError"]


class MetricsError(ReconError, InputError):
    """Base class of every error raised by :mod:`recon.metrics`."""


class TruthFormatError(MetricsError):
    """A ``truth.json`` (or its in-memory dict) does not follow ``partscene.truth/1``."""


class EstimateError(MetricsError):
    """An estimate (primitives, joints, contact scores) is malformed, e.g. a NaN pose or a zero size."""
