"""A one-picture summary of a demo run (the README's picture): scan by part | reconstruction | the robot
opening (a key frame simcheck took), side by side."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from PIL import Image

from ._errors import ArtifactError
from ._figure import new_figure, png_from_figure
from ._layout import DemoLayout
from ._primitives import solids_from_urdf
from ._scan_image import load_scan
from ._scene_image import draw_solids, scene_bounds

__all__ = ["png_of_teaser"]

#: Points drawn in the scan panel (a seeded subsample).
_TEASER_POINTS = 25_000


def _key_frame(lay: DemoLayout) -> tuple[str, np.ndarray] | None:
    """The 'opened' (else last) key frame of the first certified task (else of any task)."""
    if not lay.certificate_json.exists():
        return None
    cert = json.loads(lay.certificate_json.read_text())
    tasks = sorted(cert.get("tasks", []), key=lambda t: t.get("status") != "certified")
    for task in tasks:
        images = [lay.root / p for p in task.get("images", [])]
        images = [p for p in images if p.exists()]
        if images:
            pick = next((p for p in images if "opened" in p.stem), images[-1])
            with Image.open(pick) as im:
                return f"{task.get('kind')}: {task.get('status')}", np.asarray(im.convert("RGB"))
    return None


def png_of_teaser(demo_dir: str | Path, seed: int = 0) -> bytes:
    """PNG bytes of the summary picture of ``demo_dir`` (needs the scan and scene.urdf)."""
    lay = DemoLayout(Path(demo_dir))
    if not lay.scene_urdf.exists():
        raise ArtifactError(f"{lay.scene_urdf}: the teaser needs the reconstruction")
    scan = load_scan(lay.scan_npz, lay.labels_json)
    solids = solids_from_urdf(lay.scene_urdf)
    frame = _key_frame(lay)
    n = 3 if frame else 2
    fig = new_figure(4.0 * n, 3.6)
    bounds = scene_bounds(solids)
    rng = np.random.default_rng(seed)
    keep = rng.choice(len(scan.points), min(_TEASER_POINTS, len(scan.points)), replace=False)
    pts, pid = scan.points[keep], scan.part_id[keep]
    from matplotlib import colormaps
    cmap = colormaps["tab20"]
    colours = np.array([cmap(int(p) % 20)[:3] if p >= 0 else (0.85, 0.85, 0.85) for p in pid])
    ax = fig.add_subplot(1, n, 1, projection="3d")
    ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], c=colours, s=0.8, marker=".", linewidths=0, depthshade=False)
    draw_solids(ax, [], bounds)  # same view box as the reconstruction
    ax.set_title("1. labelled scan", fontsize=11)
    ax = fig.add_subplot(1, n, 2, projection="3d")
    draw_solids(ax, solids, bounds)
    ax.set_title("2. part-level reconstruction (URDF)", fontsize=11)
    if frame:
        ax = fig.add_subplot(1, n, 3)
        ax.imshow(frame[1])
        ax.set_axis_off()
        ax.set_title(f"3. certified in physics ({frame[0]})", fontsize=11)
    return png_from_figure(fig, dpi=80)
