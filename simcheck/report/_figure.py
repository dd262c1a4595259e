"""Matplotlib (Agg) figures -> PNG bytes -> ``data:`` URIs, so report.html needs no other file."""

from __future__ import annotations

import base64
import io

import matplotlib
import numpy as np
from PIL import Image
from PIL.PngImagePlugin import PngInfo

matplotlib.use("Agg")  # headless: never open a window
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.text import Text  # noqa: E402

__all__ = ["new_figure", "png_from_figure", "data_uri_from_png", "hconcat_pngs", "LABEL_COLOURS", "colour_of_label",
           "MIN_TEXT_PX", "min_text_px", "png_bytes", "crop_alike"]

#: The smallest text the report shows, pixels at 100 % zoom. Every PNG records the height of its smallest
#: text (pixels of the PNG) under :data:`_TEXT_KEY`; the page must not shrink a figure below it.
MIN_TEXT_PX = 12
_TEXT_KEY = "partscene:min_text_px"


def png_bytes(image: Image.Image, text_px: float | None) -> bytes:
    """``image`` as PNG bytes recording ``text_px`` (its smallest text, pixels; None: no text)."""
    info = PngInfo()
    if text_px is not None:
        info.add_text(_TEXT_KEY, f"{text_px:.2f}")
    out = io.BytesIO()
    image.save(out, format="PNG", optimize=True, pnginfo=info)
    return out.getvalue()


def min_text_px(png: bytes) -> float | None:
    """The smallest text of a PNG made here, pixels of the PNG (None: it has no text)."""
    value = Image.open(io.BytesIO(png)).info.get(_TEXT_KEY)
    return float(value) if value is not None else None

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


def png_from_figure(fig: Figure, dpi: int = 90, trim: bool = True) -> bytes:
    """PNG bytes of ``fig``: white background, white margins trimmed to :data:`TRIM_PAD_PX` (3-D axes
    leave wide empty borders around the drawn box; ``trim=False``: the whole figure, so figures of one
    size can be cropped alike by :func:`crop_alike`); records the height of its smallest text (font size
    in points * dpi / 72, pixels: :func:`min_text_px`)."""
    sizes = [t.get_fontsize() for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip()]
    text_px = min(sizes) * dpi / 72.0 if sizes else None
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches="tight" if trim else None, facecolor="white")
    plt.close(fig)
    rgb = np.asarray(Image.open(io.BytesIO(buf.getvalue())).convert("RGB"))
    box = _ink_box(rgb) if trim else None
    if box is None:
        return png_bytes(Image.fromarray(rgb), text_px)
    r0, r1, c0, c1 = box
    return png_bytes(Image.fromarray(rgb[r0:r1, c0:c1]), text_px)


def _ink_box(rgb: np.ndarray) -> tuple[int, int, int, int] | None:
    """(row0, row1, col0, col1) of the non-white pixels of ``rgb`` (h, w, 3) plus :data:`TRIM_PAD_PX`."""
    ink = np.flatnonzero(np.any(rgb < 250, axis=(1, 2))), np.flatnonzero(np.any(rgb < 250, axis=(0, 2)))
    if len(ink[0]) == 0:
        return None
    (r0, r1), (c0, c1) = (ink[0][0], ink[0][-1]), (ink[1][0], ink[1][-1])
    return (max(r0 - TRIM_PAD_PX, 0), min(r1 + TRIM_PAD_PX + 1, rgb.shape[0]),
            max(c0 - TRIM_PAD_PX, 0), min(c1 + TRIM_PAD_PX + 1, rgb.shape[1]))


def crop_alike(pngs: list[bytes]) -> list[bytes]:
    """PNGs of one size cropped to the same box (the union of their non-white content), so views drawn
    with the same camera keep the same framing side by side."""
    rgbs = [np.asarray(Image.open(io.BytesIO(p)).convert("RGB")) for p in pngs]
    if len({r.shape for r in rgbs}) != 1:
        raise ValueError(f"crop_alike: images of different sizes {[r.shape for r in rgbs]}")
    boxes = [b for b in map(_ink_box, rgbs) if b is not None]
    if not boxes:
        return list(pngs)
    r0, r1 = min(b[0] for b in boxes), max(b[1] for b in boxes)
    c0, c1 = min(b[2] for b in boxes), max(b[3] for b in boxes)
    return [png_bytes(Image.fromarray(r[r0:r1, c0:c1]), min_text_px(p)) for r, p in zip(rgbs, pngs)]


def data_uri_from_png(png: bytes) -> str:
    """``data:image/png;base64,...`` for an ``<img src>``."""
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def hconcat_pngs(pngs: list[bytes], height_px: int, gap_px: int = 16) -> bytes:
    """The PNGs side by side on white, each scaled to ``height_px`` pixels high (their smallest text
    scaled with them)."""
    images, texts = [], []
    for png in pngs:
        im = Image.open(io.BytesIO(png))
        px = min_text_px(png)
        im = im.convert("RGB")
        scale = height_px / im.height
        if px is not None:
            texts.append(px * scale)
        images.append(im.resize((max(1, round(im.width * scale)), height_px), Image.LANCZOS))
    width = sum(im.width for im in images) + gap_px * (len(images) - 1)
    canvas = Image.new("RGB", (max(width, 1), height_px), "white")
    x = 0
    for im in images:
        canvas.paste(im, (x, 0))
        x += im.width + gap_px
    return png_bytes(canvas, min(texts) if texts else None)
