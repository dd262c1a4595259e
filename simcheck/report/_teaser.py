"""A one-picture summary of a demo run (the README's picture): scan by part | reconstruction | the robot
opening (a key frame simcheck took), side by side."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from matplotlib import colormaps

from scenes.description import read_truth_doc
from scenes.outcome import Outcome

from ._errors import ArtifactError
from ._figure import hconcat_pngs, new_figure, png_from_figure
from ._layout import DemoLayout
from ._primitives import solids_from_urdf
from ._scan_image import load_scan, view_bounds
from ._scene_image import draw_solids, set_view, view_azimuth
from ._tasks import executed_urdf, key_frames_for, load_rollout, rollout_path

__all__ = ["png_of_teaser"]

#: Points drawn in the scan panel (a seeded subsample).
_TEASER_POINTS = 25_000
#: Height of the picture, pixels.
_TEASER_HEIGHT_PX = 300


def _key_frame(lay: DemoLayout) -> tuple[str, np.ndarray] | None:
    """The 'opened' (else last) key frame of the first certified task (else of any executed task)."""
    if not lay.certificate_json.exists():
        return None
    cert = json.loads(lay.certificate_json.read_text())
    urdf = executed_urdf(lay, cert)
    tasks = sorted(cert.get("tasks", []), key=lambda t: t.get("status") != Outcome.CERTIFIED)
    for task in tasks:
        key = str(task.get("joint"))
        path = rollout_path(lay, task, key)
        if path is None or not path.exists():
            continue
        _, frames = key_frames_for(lay, task, key, load_rollout(path, key), urdf)
        if frames:
            label, image = next((f for f in frames if f[0].startswith("opened")), frames[-1])
            return f"{task.get('kind')}: {task.get('status')}", image
    return None


def png_of_teaser(demo_dir: str | Path, seed: int = 0) -> bytes:
    """PNG bytes of the summary picture of ``demo_dir`` (needs the scan and scene.urdf)."""
    lay = DemoLayout(Path(demo_dir))
    if not lay.scene_urdf.exists():
        raise ArtifactError(f"{lay.scene_urdf}: the teaser needs the reconstruction")
    scan = load_scan(lay.scan_npz, lay.labels_json)
    azim = view_azimuth(read_truth_doc(lay.truth_json) if lay.truth_json.exists() else None)
    solids = solids_from_urdf(lay.scene_urdf)
    frame = _key_frame(lay)
    bounds = view_bounds(scan.points, scan.part_id)
    rng = np.random.default_rng(seed)
    keep = rng.choice(len(scan.points), min(_TEASER_POINTS, len(scan.points)), replace=False)
    pts, pid = scan.points[keep], scan.part_id[keep]
    inside = np.all((pts >= bounds[0]) & (pts <= bounds[1]), axis=1) & (pid >= 0)
    pts, pid = pts[inside], pid[inside]
    cmap = colormaps["tab20"]
    order = {p: k for k, p in enumerate(np.unique(pid))}
    colours = np.array([cmap(order[p] % 20)[:3] for p in pid]).reshape(-1, 3)
    pngs = []
    fig = new_figure(4.0, 4.0)
    ax = fig.add_subplot(1, 1, 1, projection="3d")
    ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], c=colours, s=1.5, marker=".", linewidths=0, depthshade=False)
    set_view(ax, bounds, azim)
    ax.set_title("1. labelled scan", fontsize=11)
    pngs.append(png_from_figure(fig, dpi=100))
    fig = new_figure(4.0, 4.0)
    ax = fig.add_subplot(1, 1, 1, projection="3d")
    draw_solids(ax, solids, bounds, azim)
    ax.set_title("2. part-level reconstruction (URDF)", fontsize=11)
    pngs.append(png_from_figure(fig, dpi=100))
    if frame:
        fig = new_figure(4.0, 3.3)
        ax = fig.add_subplot(1, 1, 1)
        ax.imshow(frame[1])
        ax.set_axis_off()
        ax.set_title(f"3. the robot opening it in physics ({frame[0]})", fontsize=11)
        pngs.append(png_from_figure(fig, dpi=100))
    return hconcat_pngs(pngs, _TEASER_HEIGHT_PX)
