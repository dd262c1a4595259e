"""A handle that is part of its front's own surface (a door exported as one mesh, panel and handle
together): found where the part's surface stands out of its front face (pure numpy + trimesh).

The part's geometries are sampled on their surface (seeded, area-uniform). The front face is the
outermost level, along the outward direction, that holds at least ``FACE_SHARE`` of the samples; the
handle is what stands more than ``MIN_STANDOUT`` beyond it; the grasp is at the centre of its outer half
(a bar rather than its posts, a knob's cap rather than its stem).
"""

from __future__ import annotations

import numpy as np

__all__ = ["SurfaceHandle", "protruding_surface", "FACE_SHARE", "MIN_STANDOUT"]

FACE_SHARE = 0.1
"""Share of the sampled surface a level (2 mm thick) must hold to be the front face (a handle holds less)."""

MIN_STANDOUT = 0.008
"""Metres a surface point must stand out of the front face to belong to the handle."""

_SAMPLES = 6000
_BIN = 0.002


class SurfaceHandle:
    """``p`` (3,) grasp point, ``axis`` (3,) unit bar direction or None (a knob), ``width`` bar thickness m,
    ``normal`` (3,) unit outward face normal, ``geoms``: (link, collision index) of the geometries the handle
    is on; all in the frame the geometries were given in."""

    def __init__(self, p, axis, width, normal, geoms):
        self.p, self.axis, self.width, self.normal, self.geoms = p, axis, width, normal, geoms


def _mesh(shape, T):
    import trimesh
    kind = shape.kind.value
    if kind == "box":
        m = trimesh.creation.box(np.asarray(shape.size, float))
    elif kind == "cylinder":
        m = trimesh.creation.cylinder(radius=shape.radius, height=shape.length, sections=24)
    elif kind == "sphere":
        m = trimesh.creation.icosphere(subdivisions=2, radius=shape.radius)
    else:
        m = trimesh.load(shape.mesh, force="mesh")
        m.apply_scale(np.asarray(shape.size, float))
    m.apply_transform(T)
    return m


def protruding_surface(geoms: list, outward: np.ndarray, prismatic: bool, seed: int = 0) -> SurfaceHandle | None:
    """The handle standing out of the front of a part made of ``geoms`` ((link, Shape, T_frame_geom (4, 4),
    index) tuples, one frame for all), or None. ``outward`` (3,): roughly the direction the part's front
    moves when it opens, in that frame; the face normal is the mean normal of the surface facing within
    45 deg of it (the front face and the handle's). ``prismatic`` is kept for callers' clarity."""
    import trimesh
    meshes = []
    for g in geoms:
        try:
            meshes.append(_mesh(g[1], g[2]))
        except Exception:                       # unreadable mesh: not part of the surface
            meshes.append(None)
    areas = np.array([0.0 if m is None else float(m.area) for m in meshes])
    if areas.sum() <= 0:
        return None
    counts = np.maximum(1, np.round(_SAMPLES * areas / areas.sum()).astype(int)) * (areas > 0)
    pts, owner, normals = [], [], []
    for k, (m, n) in enumerate(zip(meshes, counts)):
        if n:
            p, faces = trimesh.sample.sample_surface(m, int(n), seed=seed + k)
            pts.append(p)
            normals.append(m.face_normals[faces])
            owner.append(np.full(len(p), k))
    pts, owner, normals = np.vstack(pts), np.concatenate(owner), np.vstack(normals)
    if not np.linalg.norm(outward) > 1e-9:
        return None
    n = np.asarray(outward, float) / np.linalg.norm(outward)
    facing = normals[normals @ n > 0.7]        # the surface facing outward: the front face (and the handle's)
    if len(facing):
        n = facing.mean(0) / np.linalg.norm(facing.mean(0))
    h = pts @ n
    top = h.max()
    bins = np.floor((top - h) / _BIN).astype(int)
    hist = np.bincount(bins)
    face_bins = np.nonzero(hist >= FACE_SHARE * len(h))[0]
    if not len(face_bins):
        return None
    face = top - (face_bins[0] + 1) * _BIN            # the face level's outer edge
    out = h > face + MIN_STANDOUT
    if not out.any() or out.mean() > 0.5 * FACE_SHARE * 3:
        return None
    bar = out & (h >= face + 0.5 * (top - face))
    q = pts[bar]
    p = q.mean(0)
    flat = (q - p) - np.outer((q - p) @ n, n)
    w, v = np.linalg.eigh(np.cov(flat.T) if len(q) > 3 else np.eye(3))
    axis = v[:, 2] if w[2] > 2.25 * max(w[1], 1e-12) else None
    across = v[:, 1] if axis is not None else v[:, 2]
    width = float(np.ptp(flat @ across)) if len(q) > 1 else 0.0
    return SurfaceHandle(p, axis, width, n, sorted({(geoms[k][0], geoms[k][3]) for k in set(owner[out].tolist())}))
