"""Pictures of one executed task: the joint opening over time against the plan, and key frames.

Matplotlib (the plot) and Pillow (the frame strip) over arrays; where the arrays come from is
:mod:`._tasks`' business.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ._figure import new_figure, png_bytes, png_from_figure

__all__ = ["png_of_opening", "png_of_key_frames"]


def png_of_opening(t: np.ndarray, q: np.ndarray, t_plan: np.ndarray | None, q_plan: np.ndarray | None,
                   amount: float | None, required_fraction: float | None, unit: str, title: str,
                   segments: Sequence[tuple[str, float, float]] = ()) -> bytes:
    """Executed joint value ``q`` (n,) at times ``t`` (n,) s, against the plan ``q_plan`` at ``t_plan``.

    ``amount`` is the requested opening (drawn dashed) and ``required_fraction`` * amount the level the
    certificate demands (dotted). ``segments`` are ``(name, t_start, t_end)`` spans shaded behind.
    ``unit`` is "m" or "rad" (radians are shown in degrees).
    """
    scale, shown_unit = (np.degrees(1.0), "deg") if unit == "rad" else (1.0, unit)
    fig = new_figure(7.2, 3.8)
    ax = fig.add_subplot(1, 1, 1)
    t_total = max(float(t[-1] - t[0]) if len(t) else 1.0, 1e-9)
    for i, (name, t0, t1) in enumerate(segments):
        ax.axvspan(t0, t1, color="#000000", alpha=0.04 if i % 2 else 0.09, lw=0)
        if (t1 - t0) / t_total < 0.07:
            continue  # too narrow to label legibly
        ax.text((t0 + t1) / 2, 1.0, name, transform=ax.get_xaxis_transform(), ha="center", va="bottom",
                fontsize=10, color="#555555")
    if t_plan is not None and q_plan is not None and len(t_plan):
        ax.plot(t_plan, np.asarray(q_plan) * scale, color="#1f77b4", lw=2.0, ls="--", label="plan")
    ax.plot(t, np.asarray(q) * scale, color="#d62728", lw=1.6, label="executed (physics)")
    if amount is not None:
        ax.axhline(amount * scale, color="#444444", lw=0.8, ls="-.", label="requested")
        if required_fraction is not None:
            ax.axhline(required_fraction * amount * scale, color="#2ca02c", lw=0.8, ls=":",
                       label=f"certified above ({required_fraction:.0%})")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"joint opening ({shown_unit})")
    ax.set_title(title, fontsize=11, pad=16)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=10, loc="upper left")
    return png_from_figure(fig)


def png_of_key_frames(frames: Sequence[tuple[str, np.ndarray]], per_row: int = 3, caption_px: int = 16,
                      gap_px: int = 8) -> bytes:
    """A strip of ``(caption, (h, w, 3) uint8 RGB)`` images, ``per_row`` per row, each captioned above
    (composed with Pillow: no figure needed for images that are already pixels)."""
    if not frames:
        raise ValueError("png_of_key_frames: no frames")
    h, w = frames[0][1].shape[:2]
    cols = min(per_row, len(frames))
    rows = -(-len(frames) // per_row)
    cell_h = caption_px + 6 + h
    canvas = Image.new("RGB", (cols * w + (cols - 1) * gap_px, rows * cell_h + (rows - 1) * gap_px), "white")
    draw = ImageDraw.Draw(canvas)
    font = ImageFont.load_default(size=caption_px)
    for i, (caption, image) in enumerate(frames):
        x, y = (i % per_row) * (w + gap_px), (i // per_row) * (cell_h + gap_px)
        tw = draw.textlength(caption, font=font)
        draw.text((x + (w - tw) / 2, y), caption, fill=(40, 40, 40), font=font)
        tile = Image.fromarray(np.asarray(image, dtype=np.uint8)[:, :, :3]).resize((w, h))
        canvas.paste(tile, (x, y + caption_px + 6))
    return png_bytes(canvas, float(caption_px))
