"""Preview PNGs (matplotlib, Agg): the room from above and in 3D, and the scan coloured by part."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .description import DEFAULT_RGBA, LABEL_RGBA, transform_points, write_with_atomic
from .model import Scene
from .scanner.scan import Scan

__all__ = ["write_room_preview", "write_scan_preview", "MAX_PREVIEW_POINTS"]

MAX_PREVIEW_POINTS = 60_000  # points drawn in a scan preview (a deterministic subsample)


def _plt():
    import matplotlib

    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    return plt


def _box_faces(corners: np.ndarray) -> list[np.ndarray]:
    """The 6 quads of a box given its 8 corners in :meth:`Shape.corners` order."""
    idx = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return [corners[list(q)] for q in idx]


def write_room_preview(scene: Scene, path: str | Path) -> Path:
    """A two-panel PNG: top view (parts by label, walls, object names) and a 3D view."""
    plt = _plt()
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    fig = plt.figure(figsize=(14, 6.5))
    ax = fig.add_subplot(1, 2, 1)
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    polys, cols = [], []
    for w in scene.walls:
        c = transform_points(w.T_world_wall, (np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1)
                                                        for z in (-1, 1)]) * w.size / 2))
        ax.fill(*c[[0, 2, 6, 4]][:, :2].T, color=LABEL_RGBA["wall"][:3], ec="k", lw=0.5)
    for o in scene.objects:
        for p in o.parts:
            T = o.T_world_object @ p.T_object_part
            rgb = LABEL_RGBA.get(p.label, DEFAULT_RGBA)[:3]
            for s in p.shapes:
                c = transform_points(T, s.corners())
                ax.fill(*c[[0, 2, 6, 4]][:, :2].T, color=rgb, ec="k", lw=0.3, alpha=0.7)
                for f in _box_faces(c):
                    polys.append(f)
                    cols.append(rgb)
        lo, hi = o.bounds()
        ctr = transform_points(o.T_world_object, [(lo + hi) / 2])[0]
        front = o.T_world_object[:3, 0]
        ax.annotate(o.name, ctr[:2], fontsize=7, ha="center")
        if any(j.movable for j in o.joints):
            ax.arrow(ctr[0], ctr[1], 0.3 * front[0], 0.3 * front[1], width=0.01, color="r")
    ax.set_aspect("equal")
    ax.set_title(f"{scene.name} (seed {scene.seed}): top view, red arrows = fronts")
    ax3.add_collection3d(Poly3DCollection(polys, facecolors=cols, edgecolors=(0, 0, 0, 0.2), linewidths=0.2))
    lx, ly = scene.room_size / 2
    ax3.set_xlim(-lx, lx), ax3.set_ylim(-ly, ly), ax3.set_zlim(0, 2.2)
    ax3.set_box_aspect((2 * lx, 2 * ly, 2.2))
    ax3.view_init(elev=35, azim=-60)
    ax3.set_title("3D (closed)")
    fig.tight_layout()
    out = write_with_atomic(path, lambda tmp: fig.savefig(tmp, dpi=90, format="png"))
    plt.close(fig)
    return out


def write_scan_preview(scan: Scan, path: str | Path, seed: int = 0) -> Path:
    """A two-panel PNG of the scan coloured by part id (top view and 3D), background in grey."""
    plt = _plt()
    rng = np.random.default_rng(seed)
    n = len(scan)
    idx = np.sort(rng.choice(n, MAX_PREVIEW_POINTS, replace=False)) if n > MAX_PREVIEW_POINTS else np.arange(n)
    p, pid = scan.points[idx], scan.part_id[idx]
    palette = plt.get_cmap("tab20")
    col = np.where((pid >= 0)[:, None], palette((pid % 20) / 19.999)[:, :3], 0.75)
    fig = plt.figure(figsize=(14, 6.5))
    ax = fig.add_subplot(1, 2, 1)
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    order = np.argsort(p[:, 2])
    ax.scatter(p[order, 0], p[order, 1], c=col[order], s=0.3, linewidths=0)
    ax.plot(scan.T_world_cameras[:, 0, 3], scan.T_world_cameras[:, 1, 3], "k.-", lw=0.5, ms=3)
    ax.set_aspect("equal")
    ax.set_title(f"scan: {n} points, {len(scan.T_world_cameras)} frames (black = camera path)")
    fg = pid >= 0
    ax3.scatter(p[fg, 0], p[fg, 1], p[fg, 2], c=col[fg], s=0.3, linewidths=0)
    ax3.set_box_aspect(tuple(np.ptp(p[fg], axis=0) + 1e-3) if fg.any() else (1, 1, 1))
    ax3.view_init(elev=35, azim=-60)
    ax3.set_title("objects coloured by part")
    fig.tight_layout()
    out = write_with_atomic(path, lambda tmp: fig.savefig(tmp, dpi=90, format="png"))
    plt.close(fig)
    return out
