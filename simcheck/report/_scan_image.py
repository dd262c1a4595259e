"""The scan, coloured by part and by part label (matplotlib 3-D scatter, Agg)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from matplotlib import colormaps
from matplotlib.lines import Line2D

from ._errors import ArtifactError
from ._figure import colour_of_label, crop_alike, hconcat_pngs, new_figure, png_from_figure
from ._scene_image import VIEW_AZIM_DEG, set_view

__all__ = ["ScanPoints", "load_scan", "png_of_scan", "MAX_DRAWN_POINTS"]

#: At most this many points are drawn (a seeded uniform subsample); enough to read the parts.
MAX_DRAWN_POINTS = 40_000
#: Colour of points with part_id -1 (background / unlabelled).
_BACKGROUND = (0.85, 0.85, 0.85)


class ScanPoints:
    """A labelled scan: ``points`` (n, 3) float metres (world, z up), ``part_id`` (n,) int,
    ``object_id`` (n,) int, and ``label_of_part`` {part_id: label} from labels.json."""

    def __init__(self, points: np.ndarray, part_id: np.ndarray, object_id: np.ndarray,
                 label_of_part: dict[int, str]):
        self.points, self.part_id, self.object_id = points, part_id, object_id
        self.label_of_part = label_of_part


def load_scan(npz_path: str | Path, labels_path: str | Path) -> ScanPoints:
    """Read ``scan.npz`` (arrays points, object_id, part_id) and ``labels.json``."""
    npz_path, labels_path = Path(npz_path), Path(labels_path)
    try:
        with np.load(npz_path) as data:
            points = np.asarray(data["points"], dtype=float)
            part_id = np.asarray(data["part_id"], dtype=int)
            object_id = np.asarray(data["object_id"], dtype=int)
    except (OSError, KeyError, ValueError) as exc:
        raise ArtifactError(f"{npz_path}: cannot read scan arrays points/object_id/part_id ({exc})") from exc
    if points.ndim != 2 or points.shape[1] != 3 or part_id.shape != (len(points),):
        raise ArtifactError(f"{npz_path}: points must be (n, 3) with part_id (n,), got "
                            f"{points.shape} and {part_id.shape}")
    try:
        labels = json.loads(labels_path.read_text())
        label_of_part = {int(p["id"]): str(p["label"]) for o in labels["objects"] for p in o["parts"]}
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise ArtifactError(f"{labels_path}: cannot read objects[].parts[].id/label ({exc})") from exc
    return ScanPoints(points, part_id, object_id, label_of_part)


#: Margin (m) around the labelled points that is still drawn (walls and floor beyond it are cut away).
VIEW_MARGIN = 0.05


def view_bounds(points: np.ndarray, part_id: np.ndarray) -> np.ndarray:
    """(2, 3) world box of the labelled points (part_id >= 0) grown by :data:`VIEW_MARGIN`, metres."""
    labelled = points[part_id >= 0] if np.any(part_id >= 0) else points
    if len(labelled) == 0:
        return np.array([[-0.5, -0.5, 0.0], [0.5, 0.5, 1.0]])
    return np.stack([labelled.min(axis=0) - VIEW_MARGIN, labelled.max(axis=0) + VIEW_MARGIN])


def png_of_scan(scan: ScanPoints, seed: int = 0, panel_in: float = 5.5, azim_deg: float = VIEW_AZIM_DEG,
                height_px: int = 380) -> bytes:
    """Two panels: every part in its own colour, and points coloured by their part's label (with a
    legend), each trimmed to its content and scaled to ``height_px``."""
    rng = np.random.default_rng(seed)
    n = len(scan.points)
    keep = np.sort(rng.choice(n, MAX_DRAWN_POINTS, replace=False)) if n > MAX_DRAWN_POINTS else np.arange(n)
    pts, pid = scan.points[keep], scan.part_id[keep]

    parts = np.unique(pid[pid >= 0])
    cmap = colormaps["tab20"]
    by_part = np.tile(np.array(_BACKGROUND), (len(pts), 1))
    for k, p in enumerate(parts):
        by_part[pid == p] = cmap(k % 20)[:3]
    by_label = np.tile(np.array(_BACKGROUND), (len(pts), 1))
    labels_seen: list[str] = []
    for p in parts:
        label = scan.label_of_part.get(int(p), "")
        by_label[pid == p] = colour_of_label(label)
        if label not in labels_seen:
            labels_seen.append(label)

    bounds = view_bounds(scan.points, scan.part_id)
    inside = np.all((pts >= bounds[0]) & (pts <= bounds[1]), axis=1)
    pts, by_part, by_label, pid_in = pts[inside], by_part[inside], by_label[inside], pid[inside]
    handles = [Line2D([], [], marker="o", linestyle="", color=colour_of_label(lb), label=lb or "(none)")
               for lb in sorted(labels_seen)]
    pngs = []
    for title, colours, legend in [(f"scan by part ({len(parts)} parts, {n} points)", by_part, False),
                                   ("scan by part label", by_label, True)]:
        fig = new_figure(panel_in, panel_in)
        ax = fig.add_subplot(1, 1, 1, projection="3d")
        bg = pid_in < 0  # unlabelled points: faint context
        ax.scatter(pts[bg, 0], pts[bg, 1], pts[bg, 2], c=[_BACKGROUND], s=0.3, alpha=0.3, marker=".",
                   linewidths=0, depthshade=False)
        ax.scatter(pts[~bg, 0], pts[~bg, 1], pts[~bg, 2], c=colours[~bg], s=1.2, marker=".", linewidths=0,
                   depthshade=False)
        set_view(ax, bounds, azim_deg)
        ax.set_title(title, fontsize=11)
        if legend and handles:
            ax.legend(handles=handles, loc="upper right", fontsize=10, ncol=2, frameon=False)
        pngs.append(png_from_figure(fig, dpi=110, trim=False))
    return hconcat_pngs(crop_alike(pngs), height_px)
