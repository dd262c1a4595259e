"""A corpus of articulated objects written the way third-party files are (other naming, frames, sign
conventions, handle kinds), to certify partscene against models it did not generate.

``build_object(spec, folder)`` writes one object's URDF (and meshes); ``build_corpus(folder, names)`` all
or some of :data:`CATALOGUE`. How to scan them and what their labels mean: ``docs/thirdparty.md``.
"""

from __future__ import annotations

from pathlib import Path

from thirdparty.build import BuiltObject, Front, FrontSpec, ObjectSpec, build_object
from thirdparty.catalogue import CATALOGUE, FIXTURES, spec_named

__all__ = ["BuiltObject", "Front", "FrontSpec", "ObjectSpec", "build_object", "build_corpus", "CATALOGUE",
           "FIXTURES", "spec_named"]


def build_corpus(folder, names=None) -> list[BuiltObject]:
    """Build the catalogue objects called ``names`` (default: all) into ``folder``, in catalogue order."""
    chosen = [spec_named(n) for n in names] if names is not None else list(CATALOGUE)
    return [build_object(s, Path(folder)) for s in chosen]
