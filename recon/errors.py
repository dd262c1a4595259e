"""The errors ``recon`` raises. Every message names the file, object, part or joint at fault.

    ReconError          base of everything recon raises on purpose (a scenes.description.PartsceneError)
    ├── ScanError       the scan or labels file cannot be used (an InputError: missing, malformed, NaN, ...)
    └── ReconstructionError  a stage could not produce a valid model (names object / part / joint)

Expected, recoverable problems (a part with too few points, an unknown label, a part that touches
nothing) are not errors: they are logged and collected in ``Reconstruction.warnings``.
"""

from __future__ import annotations

from scenes.description import InputError, PartsceneError

__all__ = ["ReconError", "ScanError", "ReconstructionError"]


class ReconError(PartsceneError):
    """Base class of the errors raised by :mod:`recon`."""


class ScanError(ReconError, InputError):
    """The scan (PLY / NPZ) or its labels JSON is unusable; the message names the file and field."""


class ReconstructionError(ReconError, RuntimeError):
    """A reconstruction stage failed; the message names the object, part or joint."""
