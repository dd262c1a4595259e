"""Pictures of primitive scenes: the reconstruction beside the truth (matplotlib 3-D, Agg)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from scenes.description import FRONT_CATEGORIES

from ._figure import colour_of_label, crop_alike, hconcat_pngs, new_figure, png_from_figure
from ._primitives import Solid, mesh_from_solid

__all__ = ["png_of_scenes", "draw_solids"]

#: Direction towards the light (world frame, unit after normalisation) for Lambert shading.
_LIGHT = np.array([0.4, -0.5, 0.9]) / np.linalg.norm([0.4, -0.5, 0.9])
#: Camera elevation and azimuth of the scene views, degrees.
VIEW_ELEV_DEG, VIEW_AZIM_DEG = 28.0, -60.0


def draw_solids(ax, solids: Sequence[Solid], bounds: np.ndarray | None = None,
                azim_deg: float = VIEW_AZIM_DEG) -> None:
    """Draw ``solids`` as shaded triangles on a 3-D axes; ``bounds`` (2, 3) fixes the view box."""
    polys, colours = [], []
    for solid in solids:
        faces, normals = _faces_of_solid(solid)
        base = np.array(colour_of_label(solid.label))
        shade = 0.55 + 0.45 * np.clip(normals @ _LIGHT, 0.0, 1.0)
        polys.extend(faces)
        colours.append(np.clip(shade[:, None] * base[None, :], 0, 1))
    if polys:
        rgb = np.concatenate(colours)
        # edges in the face colour hide the hairline seams antialiasing leaves between facets
        coll = Poly3DCollection(polys, facecolors=rgb, edgecolors=rgb, linewidths=0.3)
        ax.add_collection3d(coll, autolim=False)      # the view box is set below, not autoscaled
    set_view(ax, scene_bounds(solids) if bounds is None else bounds, azim_deg)


#: Zoom of the 3-D axes box (matplotlib leaves wide margins around it at 1.0).
VIEW_ZOOM = 1.0


def set_view(ax, bounds: np.ndarray, azim_deg: float = VIEW_AZIM_DEG) -> None:
    """Equal-scale 3-D view of the world box ``bounds`` (2, 3) metres (z from the floor up), no axes."""
    lo, hi = np.array(bounds[0], dtype=float), np.array(bounds[1], dtype=float)
    lo[2] = min(lo[2], 0.0)
    hi = np.maximum(hi, lo + 0.1)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(tuple(hi - lo), zoom=VIEW_ZOOM)
    ax.view_init(elev=VIEW_ELEV_DEG, azim=azim_deg)
    ax.set_axis_off()


#: Corner indices of the six quads of a box (outward, counter-clockwise), corners indexed by sign bits.
_BOX_QUADS = np.array([[0, 2, 6, 4], [1, 5, 7, 3], [0, 4, 5, 1], [2, 3, 7, 6], [0, 1, 3, 2], [4, 6, 7, 5]])


def _faces_of_solid(solid: Solid) -> tuple[list[np.ndarray], np.ndarray]:
    """Polygons ((k, 3) world points each) and their (n, 3) unit normals; boxes as 6 quads."""
    if solid.kind == "box":
        signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
        # corner i has sign bits (x, y, z) = (i >> 2, i >> 1, i) & 1; reorder to that convention
        corners_local = signs * solid.size / 2
        corners = corners_local @ solid.T_world_shape[:3, :3].T + solid.T_world_shape[:3, 3]
        faces = [corners[q] for q in _BOX_QUADS]
        normals = np.array([np.cross(f[1] - f[0], f[2] - f[0]) for f in faces])
        normals /= np.linalg.norm(normals, axis=1, keepdims=True)
        centre = solid.T_world_shape[:3, 3]
        flip = np.einsum("ij,ij->i", normals, np.array([f.mean(axis=0) for f in faces]) - centre) < 0
        normals[flip] *= -1
        return faces, normals
    mesh = mesh_from_solid(solid)
    return list(mesh.triangles), mesh.face_normals


def scene_bounds(solids: Sequence[Solid]) -> np.ndarray:
    """(2, 3) axis-aligned world bounds of ``solids`` (a unit box when there are none), metres."""
    if not solids:
        return np.array([[-0.5, -0.5, 0.0], [0.5, 0.5, 1.0]])
    pts = np.concatenate([mesh_from_solid(s, sections=8).vertices for s in solids])
    return np.stack([pts.min(axis=0), pts.max(axis=0)])


def view_azimuth(truth: dict | None) -> float:
    """Camera azimuth (deg) facing the fronts of the objects that stand on the floor: the direction of
    the sum of their front normals (x axes of ``T_world_object`` in truth.json), each weighted by its
    number of drawers and doors, turned :data:`SIDE_TURN_DEG` to show depth. Objects against opposite
    walls cannot both be seen from the front: the one with more drawers and doors wins."""
    if not truth:
        return VIEW_AZIM_DEG
    total = np.zeros(2)
    for o in truth.get("objects", []):
        if o.get("category") not in FRONT_CATEGORIES or "T_world_object" not in o or o.get("supported_by") is not None:
            continue
        movable = sum(1 for j in o.get("joints", []) if j.get("type") in ("prismatic", "revolute"))
        total += (1 + movable) * np.asarray(o["T_world_object"], dtype=float)[:2, 0]
    if np.linalg.norm(total) < 1e-6:
        return VIEW_AZIM_DEG
    return float(np.degrees(np.arctan2(total[1], total[0]))) + SIDE_TURN_DEG


#: Objects whose front (drawers, doors) the views should face.
#: Turn of the view away from straight-on, degrees.
SIDE_TURN_DEG = -30.0


def png_of_scenes(panels: Sequence[tuple[str, Sequence[Solid]]], panel_in: float = 5.0,
                  azim_deg: float = VIEW_AZIM_DEG, height_px: int = 380) -> bytes:
    """One PNG with a 3-D panel per ``(title, solids)``, all drawn in the same view box by the same camera
    and cropped alike (:func:`._figure.crop_alike`), so reconstruction and truth share one framing and
    scale, then scaled to ``height_px``."""
    all_solids = [s for _, solids in panels for s in solids]
    bounds = scene_bounds(all_solids)
    pngs = []
    for title, solids in panels:
        fig = new_figure(panel_in, panel_in)
        ax = fig.add_subplot(1, 1, 1, projection="3d")
        draw_solids(ax, solids, bounds, azim_deg)
        ax.set_title(f"{title} ({len(solids)} primitives)", fontsize=11)
        pngs.append(png_from_figure(fig, dpi=110, trim=False))
    return hconcat_pngs(crop_alike(pngs), height_px)
