"""The scan, coloured by part and by part label (matplotlib 3-D scatter, Agg)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from matplotlib import colormaps
from matplotlib.lines import Line2D

from ._errors import ArtifactError
from ._figure import colour_of_label, new_figure, png_from_figure
from ._scene_image import VIEW_AZIM_DEG, VIEW_ELEV_DEG

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


def png_of_scan(scan: ScanPoints, seed: int = 0, panel_in: float = 5.5) -> bytes:
    """Two panels: every part in its own colour, and points coloured by their part's label."""
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

    fig = new_figure(2 * panel_in, panel_in)
    lo, hi = (pts.min(axis=0), pts.max(axis=0)) if len(pts) else (np.zeros(3), np.ones(3))
    centre, half = (lo + hi) / 2, max(float(np.max(hi - lo)) / 2, 0.1)
    for i, (title, colours) in enumerate([(f"scan by part ({len(parts)} parts, {n} points)", by_part),
                                          ("scan by part label", by_label)]):
        ax = fig.add_subplot(1, 2, i + 1, projection="3d")
        ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], c=colours, s=0.6, marker=".", linewidths=0,
                   depthshade=False)
        ax.set_xlim(centre[0] - half, centre[0] + half)
        ax.set_ylim(centre[1] - half, centre[1] + half)
        ax.set_zlim(max(0.0, centre[2] - half), max(0.0, centre[2] - half) + 2 * half)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=VIEW_ELEV_DEG, azim=VIEW_AZIM_DEG)
        ax.set_axis_off()
        ax.set_title(title, fontsize=11)
    handles = [Line2D([], [], marker="o", linestyle="", color=colour_of_label(lb), label=lb or "(none)")
               for lb in sorted(labels_seen)]
    if handles:
        fig.legend(handles=handles, loc="lower right", fontsize=8, ncol=2, frameon=False)
    return png_from_figure(fig)
