"""``preview.png``: the scan (coloured by part) beside the reconstruction (primitive wireframes, joint
axes), seen from the same viewpoint. Rendered off-screen with matplotlib's Agg backend."""

from __future__ import annotations

import io

import numpy as np

from recon.model import JointType, Reconstruction
from recon.scan import Scan

__all__ = ["preview_png"]


def _box_edges(prim) -> list[np.ndarray]:
    c = prim.corners()       # index = 4*ix + 2*iy + iz
    pairs = [(a, b) for a in range(8) for b in range(a + 1, 8) if bin(a ^ b).count("1") == 1]
    return [c[[a, b]] for a, b in pairs]


def preview_png(rec: Reconstruction, scan: Scan | None, *, max_points: int = 20000, seed: int = 0,
                dpi: int = 90) -> bytes:
    """PNG bytes of the side-by-side preview (no file is written here)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    fig = Figure(figsize=(12, 6), dpi=dpi)
    ax_scan = fig.add_subplot(1, 2, 1, projection="3d")
    ax_rec = fig.add_subplot(1, 2, 2, projection="3d")
    cmap = matplotlib.colormaps["tab20"]
    all_c = np.concatenate([p.primitive.corners() for o in rec.objects for p in o.parts])
    lo, hi = all_c.min(axis=0), all_c.max(axis=0)
    if scan is not None:
        rng = np.random.default_rng(seed)
        idx = np.arange(len(scan.points))
        if len(idx) > max_points:
            idx = np.sort(rng.choice(idx, max_points, replace=False))
        p, part = scan.points[idx], scan.part_id[idx]
        colors = np.where(part[:, None] >= 0, cmap((np.maximum(part, 0) % 20) / 20.0)[:, :3], 0.7)
        ax_scan.scatter(p[:, 0], p[:, 1], p[:, 2], s=0.3, c=colors, depthshade=False)
    for o in rec.objects:
        for part in o.parts:
            col = cmap((part.part_id % 20) / 20.0)
            for e in _box_edges(part.primitive):
                ax_rec.plot(e[:, 0], e[:, 1], e[:, 2], color=col, linewidth=0.8)
        for j in o.joints:
            if j.type is JointType.FIXED:
                continue
            seg = np.stack([j.origin, j.origin + 0.3 * j.axis])
            ax_rec.plot(seg[:, 0], seg[:, 1], seg[:, 2], color="red" if j.type is JointType.REVOLUTE else "blue",
                        linewidth=2.0)
    span = float(np.max(hi - lo)) / 2 + 0.1
    mid = (hi + lo) / 2
    for ax, title in ((ax_scan, "scan (by part)"), (ax_rec, "reconstruction (red: hinge, blue: slide)")):
        ax.set_title(title)
        ax.set_xlim(mid[0] - span, mid[0] + span)
        ax.set_ylim(mid[1] - span, mid[1] + span)
        ax.set_zlim(max(mid[2] - span, lo[2] - 0.05), mid[2] + span)
        ax.view_init(elev=25, azim=-60)
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    return buf.getvalue()
