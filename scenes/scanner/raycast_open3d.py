"""The one place open3d enters the scanner: cast rays against tagged meshes.

Uses ``open3d.t.geometry.RaycastingScene`` (C++, multithreaded, float32 internally).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .meshes import TaggedMesh

__all__ = ["RayHits", "Raycaster"]


@dataclass(frozen=True, eq=False)
class RayHits:
    """Per ray: ``t`` (n,) hit distance along the unit direction (inf = miss), ``mesh`` (n,) index into
    the caster's meshes (-1 = miss), ``normal`` (n, 3) unit outward face normal, world frame."""

    t: np.ndarray
    mesh: np.ndarray
    normal: np.ndarray


class Raycaster:
    """Holds an open3d raycasting scene built from ``meshes`` (their order defines ``RayHits.mesh``)."""

    def __init__(self, meshes: list[TaggedMesh]):
        import open3d as o3d

        self._o3d = o3d
        self._scene = o3d.t.geometry.RaycastingScene()
        self._gid_to_mesh = {}
        for i, m in enumerate(meshes):
            gid = self._scene.add_triangles(
                o3d.core.Tensor(m.vertices.astype(np.float32)),
                o3d.core.Tensor(np.asarray(m.faces, dtype=np.uint32)))
            self._gid_to_mesh[int(gid)] = i
        self._lut = np.full(max(self._gid_to_mesh) + 2, -1, dtype=np.int64)
        for gid, i in self._gid_to_mesh.items():
            self._lut[gid] = i

    def cast(self, origins: np.ndarray, directions: np.ndarray) -> RayHits:
        """Cast (n, 3) rays (unit ``directions``, world frame, metres)."""
        rays = np.hstack([origins, directions]).astype(np.float32)
        ans = self._scene.cast_rays(self._o3d.core.Tensor(rays))
        t = ans["t_hit"].numpy().astype(np.float64)
        gid = ans["geometry_ids"].numpy().astype(np.int64)
        hit = np.isfinite(t)
        mesh = np.full(t.shape, -1, dtype=np.int64)
        mesh[hit] = self._lut[np.clip(gid[hit], 0, len(self._lut) - 1)]
        normal = ans["primitive_normals"].numpy().astype(np.float64)
        return RayHits(t, mesh, normal)
