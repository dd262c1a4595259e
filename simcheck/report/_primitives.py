"""Primitive solids of a scene, from ``truth.json`` or from a scene URDF, as world-frame meshes.

A :class:`Solid` is one ``box`` / ``cylinder`` / ``sphere`` of one part, posed in the world frame
(``T_world_shape``, (4, 4) float64, metres). Both sources give the same kind of list, so the truth and
the reconstruction are drawn by the same code.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh

from scenes.naming import parse_link_name

from ._errors import ArtifactError

__all__ = ["Solid", "solids_from_truth", "solids_from_urdf", "mesh_from_solid"]


@dataclass(frozen=True)
class Solid:
    """One primitive of one part.

    kind : "box" | "cylinder" | "sphere"
    size : (3,) float, metres -- box edge lengths; cylinder (radius, radius, length) along local z;
        sphere (radius, radius, radius).
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


def _size_of_shape(shape: dict, where: str) -> tuple[str, np.ndarray]:
    kind = shape.get("type")
    if kind == "box":
        size = np.asarray(shape.get("size"), dtype=float)
        if size.shape != (3,) or np.any(size <= 0):
            raise ArtifactError(f"{where}: box size must be 3 positive numbers, got {shape.get('size')}")
        return kind, size
    if kind == "cylinder":
        r, length = float(shape.get("radius", 0)), float(shape.get("length", 0))
        if r <= 0 or length <= 0:
            raise ArtifactError(f"{where}: cylinder needs positive radius and length, got {shape}")
        return kind, np.array([r, r, length])
    if kind == "sphere":
        r = float(shape.get("radius", 0))
        if r <= 0:
            raise ArtifactError(f"{where}: sphere needs a positive radius, got {shape}")
        return kind, np.array([r, r, r])
    raise ArtifactError(f"{where}: unknown shape type {kind!r} (expected box, cylinder or sphere)")


def solids_from_truth(truth: dict, source: str = "truth.json") -> list[Solid]:
    """Every shape of every part of every object in a ``partscene.truth/1`` dict (closed state)."""
    solids: list[Solid] = []
    for obj in truth.get("objects", []):
        for part in obj.get("parts", []):
            where = f"{source}: object {obj.get('name', obj.get('id'))} part {part.get('link', part.get('id'))}"
            T_world_part = _matrix(part.get("T_world_part"), where + " T_world_part")
            for shape in part.get("shapes", []):
                kind, size = _size_of_shape(shape, where)
                T_part_shape = _matrix(shape.get("T_part_shape", np.eye(4)), where + " T_part_shape")
                solids.append(Solid(kind, size, T_world_part @ T_part_shape,
                                    str(part.get("link", "")), str(part.get("label", ""))))
    return solids


def _T_from_origin(el: ET.Element | None) -> np.ndarray:
    T = np.eye(4)
    if el is None:
        return T
    xyz = np.array([float(v) for v in el.get("xyz", "0 0 0").split()])
    rpy = [float(v) for v in el.get("rpy", "0 0 0").split()]
    T[:3, :3] = trimesh.transformations.euler_matrix(*rpy, axes="sxyz")[:3, :3]
    T[:3, 3] = xyz
    return T


def solids_from_urdf(path: str | Path) -> list[Solid]:
    """Visual primitives of every link of a scene URDF at joint values 0 (the scanned state).

    Reads the XML directly (forward kinematics over the joint origins), so a URDF that PyBullet
    would load is enough; meshes are skipped (a scene URDF has none).
    """
    path = Path(path)
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        raise ArtifactError(f"{path}: cannot read URDF ({exc})") from exc
    parent_of: dict[str, tuple[str, np.ndarray]] = {}
    for joint in root.findall("joint"):
        parent, child = joint.find("parent"), joint.find("child")
        if parent is None or child is None:
            raise ArtifactError(f"{path}: joint {joint.get('name')!r} lacks <parent> or <child>")
        parent_of[child.get("link")] = (parent.get("link"), _T_from_origin(joint.find("origin")))

    cache: dict[str, np.ndarray] = {}

    def T_world(link: str) -> np.ndarray:
        chain, seen = [], set()  # walk up to the root (or a cached link), then compose downwards
        while link not in cache and link in parent_of:
            if link in seen:
                raise ArtifactError(f"{path}: the joints around link {link!r} form a cycle")
            seen.add(link)
            chain.append(link)
            link = parent_of[link][0]
        T = cache.get(link, np.eye(4))
        for child in reversed(chain):
            T = T @ parent_of[child][1]
            cache[child] = T
        return T

    solids: list[Solid] = []
    for link in root.findall("link"):
        name = link.get("name", "")
        parsed = parse_link_name(name)
        label = parsed["label"] if parsed else ""
        for visual in link.findall("visual"):
            geom = visual.find("geometry")
            if geom is None or len(geom) == 0:
                continue
            g = geom[0]
            where = f"{path}: link {name!r} visual"
            if g.tag == "box":
                shape = {"type": "box", "size": [float(v) for v in g.get("size", "").split()]}
            elif g.tag in ("cylinder", "sphere"):
                shape = {"type": g.tag, "radius": float(g.get("radius", 0)),
                         "length": float(g.get("length", 0) or 0)}
            else:
                continue  # meshes are not drawn
            kind, size = _size_of_shape(shape, where)
            solids.append(Solid(kind, size, T_world(name) @ _T_from_origin(visual.find("origin")), name, label))
    return solids


def mesh_from_solid(solid: Solid, sections: int = 16) -> trimesh.Trimesh:
    """A triangle mesh of ``solid`` in the world frame (cylinders/spheres with ``sections`` facets)."""
    if solid.kind == "box":
        mesh = trimesh.creation.box(extents=solid.size)
    elif solid.kind == "cylinder":
        mesh = trimesh.creation.cylinder(radius=solid.size[0], height=solid.size[2], sections=sections)
    else:
        mesh = trimesh.creation.icosphere(subdivisions=1, radius=solid.size[0])
    mesh.apply_transform(solid.T_world_shape)
    return mesh
