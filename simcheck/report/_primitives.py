"""Primitive solids of a scene, from ``truth.json`` or from a scene URDF, as world-frame meshes.

A :class:`Solid` is one ``box`` / ``cylinder`` / ``sphere`` of one part, posed in the world frame
(``T_world_shape``, (4, 4) float64, metres). Both sources give the same kind of list, so the truth and
the reconstruction are drawn by the same code.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh

from scenes.description import DescriptionError, parse_link_name, read_urdf, shape_from_truth

from ._errors import ArtifactError

__all__ = ["Solid", "solids_from_truth", "solids_from_urdf", "mesh_from_solid"]


@dataclass(frozen=True)
class Solid:
    """One primitive of one part.

    kind : "box" | "cylinder" | "sphere"
    size : (3,) float, metres -- box edge lengths; cylinder (2r, 2r, length) along local z;
        sphere (2r, 2r, 2r) (the convention of :class:`scenes.description.Shape`).
    T_world_shape : (4, 4) float64 pose of the primitive's centre.
    link : URDF link name of the part; label : its semantic label ("drawer", ...; "" if unknown).
    """

    kind: str
    size: np.ndarray
    T_world_shape: np.ndarray
    link: str
    label: str


def _matrix(value, where: str) -> np.ndarray:
    T = np.asarray(value, dtype=float)
    if T.shape != (4, 4) or not np.all(np.isfinite(T)):
        raise ArtifactError(f"{where}: expected a finite 4x4 pose, got shape {T.shape}")
    return T


def solids_from_truth(truth: dict, source: str = "truth.json") -> list[Solid]:
    """Every shape of every part of every object in a ``partscene.truth/1`` dict (closed state)."""
    solids: list[Solid] = []
    for obj in truth.get("objects", []):
        for part in obj.get("parts", []):
            where = f"{source}: object {obj.get('name', obj.get('id'))} part {part.get('link', part.get('id'))}"
            T_world_part = _matrix(part.get("T_world_part"), where + " T_world_part")
            for k, entry in enumerate(part.get("shapes", [])):
                try:
                    shape = shape_from_truth(entry, f"{where} shape {k}")
                except DescriptionError as exc:
                    raise ArtifactError(str(exc)) from exc
                solids.append(Solid(shape.kind.value, shape.size, T_world_part @ shape.T_link_shape,
                                    str(part.get("link", "")), str(part.get("label", ""))))
    return solids


def solids_from_urdf(path: str | Path) -> list[Solid]:
    """Visual primitives of every link of a scene URDF at joint values 0 (the scanned state).

    Read by :func:`scenes.description.read_urdf`, the project's one URDF reader; meshes are skipped
    (a scene URDF has none).

    Raises:
        ArtifactError: the file is missing or malformed (names the file and the link or joint).
    """
    try:
        scene = read_urdf(path)
    except DescriptionError as exc:
        raise ArtifactError(str(exc)) from exc
    solids: list[Solid] = []
    for name, link in scene.links.items():
        parsed = parse_link_name(name)
        label = parsed["label"] if parsed else ""
        T_world_link = scene.T_world_link(name)
        for g in link.visuals:
            if g.kind in ("box", "cylinder", "sphere"):
                solids.append(Solid(g.kind, g.size.copy(), T_world_link @ g.T_link_shape, name, label))
    return solids


def mesh_from_solid(solid: Solid, sections: int = 16) -> trimesh.Trimesh:
    """A triangle mesh of ``solid`` in the world frame (cylinders/spheres with ``sections`` facets)."""
    if solid.kind == "box":
        mesh = trimesh.creation.box(extents=solid.size)
    elif solid.kind == "cylinder":
        mesh = trimesh.creation.cylinder(radius=solid.size[0] / 2, height=solid.size[2], sections=sections)
    else:
        mesh = trimesh.creation.icosphere(subdivisions=1, radius=solid.size[0] / 2)
    mesh.apply_transform(solid.T_world_shape)
    return mesh
