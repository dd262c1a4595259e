"""Matplotlib (Agg) figures -> PNG bytes -> ``data:`` URIs, so report.html needs no other file."""

from __future__ import annotations

import base64
import io

import matplotlib
import numpy as np
from PIL import Image

matplotlib.use("Agg")  # headless: never open a window
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

__all__ = ["new_figure", "png_from_figure", "data_uri_from_png", "hconcat_pngs", "LABEL_COLOURS", "colour_of_label"]

#: Face colour (RGB in [0, 1]) of a part by its semantic label; anything else gets ``_OTHER``.
LABEL_COLOURS: dict[str, tuple[float, float, float]] = {
    "body": (0.72, 0.72, 0.70), "drawer": (0.27, 0.51, 0.71), "door": (0.93, 0.55, 0.20),
    "handle": (0.15, 0.15, 0.15), "top": (0.62, 0.44, 0.27), "leg": (0.45, 0.32, 0.20),
    "seat": (0.55, 0.71, 0.36), "back": (0.42, 0.60, 0.30), "arm": (0.35, 0.50, 0.25),
    "frame": (0.60, 0.50, 0.65), "headboard": (0.50, 0.40, 0.60), "mattress": (0.90, 0.88, 0.80),
    "shelf": (0.80, 0.70, 0.50), "wall": (0.92, 0.92, 0.92),
}
_OTHER = (0.80, 0.40, 0.60)


def colour_of_label(label: str) -> tuple[float, float, float]:
    """RGB in [0, 1] for a part label (see :data:`LABEL_COLOURS`)."""
    return LABEL_COLOURS.get(label, _OTHER)


def new_figure(width_in: float, height_in: float) -> Figure:
    """A figure on the Agg canvas, not registered with pyplot's global state (no leaks)."""
    fig = Figure(figsize=(width_in, height_in), dpi=100)
    fig.patch.set_facecolor("white")
    return fig


#: White margin (pixels) kept around a figure's content after trimming.
TRIM_PAD_PX = 10


def png_from_figure(fig: Figure, dpi: int = 90) -> bytes:
    """PNG bytes of ``fig``: white background, white margins trimmed to :data:`TRIM_PAD_PX` (3-D axes
    leave wide empty borders around the drawn box)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight", facecolor="white")
    plt.close(fig)
    rgb = np.asarray(Image.open(io.BytesIO(buf.getvalue())).convert("RGB"))
    ink = np.flatnonzero(np.any(rgb < 250, axis=(1, 2))), np.flatnonzero(np.any(rgb < 250, axis=(0, 2)))
    if len(ink[0]) == 0:
        return buf.getvalue()
    (r0, r1), (c0, c1) = (ink[0][0], ink[0][-1]), (ink[1][0], ink[1][-1])
    r0, c0 = max(r0 - TRIM_PAD_PX, 0), max(c0 - TRIM_PAD_PX, 0)
    r1, c1 = min(r1 + TRIM_PAD_PX + 1, rgb.shape[0]), min(c1 + TRIM_PAD_PX + 1, rgb.shape[1])
    out = io.BytesIO()
    Image.fromarray(rgb[r0:r1, c0:c1]).save(out, format="PNG", optimize=True)
    return out.getvalue()


def data_uri_from_png(png: bytes) -> str:
    """``data:image/png;base64,...`` for an ``<img src>``."""
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def hconcat_pngs(pngs: list[bytes], height_px: int, gap_px: int = 16) -> bytes:
    """The PNGs side by side on white, each scaled to ``height_px`` pixels high."""
    images = []
    for png in pngs:
        im = Image.open(io.BytesIO(png)).convert("RGB")
        images.append(im.resize((max(1, round(im.width * height_px / im.height)), height_px), Image.LANCZOS))
    width = sum(im.width for im in images) + gap_px * (len(images) - 1)
    canvas = Image.new("RGB", (max(width, 1), height_px), "white")
    x = 0
    for im in images:
        canvas.paste(im, (x, 0))
        x += im.width + gap_px
    out = io.BytesIO()
    canvas.save(out, format="PNG", optimize=True)
    return out.getvalue()
