"""The exceptions ``scenes`` raises (under :class:`scenes.description.PartsceneError`). Each message names
the scene, object, part, joint or argument."""

from __future__ import annotations

from .description import InputError, PartsceneError

__all__ = ["ScenesError", "SceneSpecError", "PlacementError", "ScanError"]


class ScenesError(PartsceneError):
    """Base of every error raised by :mod:`scenes`."""


class SceneSpecError(ScenesError, InputError):
    """A bad argument: unknown scene/category/preset, a negative size, an invalid seed, ..."""


class PlacementError(ScenesError):
    """The composer could not place an object without overlap (names the scene and object)."""


class ScanError(ScenesError):
    """The scanner was given an unusable camera, path or parameter."""
