"""Small HTML building blocks for one self-contained page: escaped text, numbers tagged with
``data-key`` (so a test can compare what is shown with the source file), tables, images as data URIs.
"""

from __future__ import annotations

import html
import math
from collections.abc import Iterable, Sequence

import numpy as np

from ._figure import data_uri_from_png, min_text_px

__all__ = ["esc", "format_number", "num", "table", "img", "section", "page", "note", "badge"]

#: Significant digits of every number shown (a test parses the text back with this precision).
SIGNIFICANT_DIGITS = 4


def esc(text: object) -> str:
    """``text`` as HTML-escaped text."""
    return html.escape(str(text), quote=True)


#: Magnitudes below this are shown as 0: no quantity the report shows (metres, radians, m/s, N, seconds,
#: fractions) is resolved below a nanounit; 3.553e-15 m/s is a settled part, written "0 m/s".
ZERO_BELOW = 1e-9


def format_number(value: object) -> str:
    """How a number is shown: bools as yes/no, ints as is, floats with 4 significant digits -- written out
    (0.00006604, 12350) between 1e-6 and 1e6, in scientific notation outside, 0 below :data:`ZERO_BELOW`."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    v = float(value)  # type: ignore[arg-type]
    if math.isnan(v):
        return "nan"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    if abs(v) < ZERO_BELOW:
        return "0"
    if 1e-6 <= abs(v) < 1e6:
        return np.format_float_positional(v, precision=SIGNIFICANT_DIGITS, unique=False, fractional=False, trim="-")
    return f"{v:.{SIGNIFICANT_DIGITS}g}"


def num(value: object, key: str, unit: str = "") -> str:
    """A ``<span class="num" data-key=KEY>`` showing ``value`` (and its unit outside the span)."""
    span = f'<span class="num" data-key="{esc(key)}">{esc(format_number(value))}</span>'
    return span + (f"&nbsp;{esc(unit)}" if unit else "")


def table(headers: Sequence[str], rows: Iterable[Sequence[str]], cls: str = "") -> str:
    """A table; ``headers`` are escaped here, cells must already be HTML (use :func:`esc` / :func:`num`)."""
    head = "".join(f"<th>{esc(h)}</th>" for h in headers)
    body = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in row) + "</tr>" for row in rows)
    return f'<table class="{esc(cls)}"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


def img(png: bytes, alt: str, key: str) -> str:
    """An ``<img>`` with the PNG inline as a data URI; ``key`` names the figure (``data-figure``);
    ``data-min-text-px`` is the height of its smallest text in the PNG's pixels (``_figure.min_text_px``)."""
    px = min_text_px(png)
    text = f' data-min-text-px="{px:.2f}"' if px is not None else ""
    return (f'<figure><img src="{data_uri_from_png(png)}" alt="{esc(alt)}" data-figure="{esc(key)}"{text}>'
            f"<figcaption>{esc(alt)}</figcaption></figure>")


def note(text: str, kind: str = "missing") -> str:
    """A highlighted paragraph (``kind`` "missing" or "info")."""
    return f'<p class="note {esc(kind)}">{esc(text)}</p>'


def badge(text: str, ok: bool | None) -> str:
    """A coloured status label (green ok, red not ok, grey unknown)."""
    cls = "unknown" if ok is None else ("ok" if ok else "bad")
    return f'<span class="badge {cls}">{esc(text)}</span>'


def section(anchor: str, title: str, body: str) -> str:
    """A numbered-by-CSS ``<section>`` with an ``<h2>``."""
    return f'<section id="{esc(anchor)}"><h2>{esc(title)}</h2>{body}</section>'


_CSS = """
body{font-family:system-ui,-apple-system,'DejaVu Sans',sans-serif;margin:0 auto;max-width:1200px;
 padding:1.5em;color:#222;line-height:1.45}
h1{margin-bottom:.2em} h2{border-bottom:2px solid #ddd;padding-bottom:.2em;margin-top:1.8em}
h3{margin-bottom:.3em} .lead{color:#555;margin-top:0}
nav a{margin-right:1em} figure{margin:.6em 0} figure img{max-width:100%;border:1px solid #eee}
figcaption{color:#666;font-size:.85em}
table{border-collapse:collapse;margin:.6em 0;font-size:.92em}
th,td{border:1px solid #ddd;padding:.25em .6em;text-align:left} th{background:#f5f5f5}
td .num{font-variant-numeric:tabular-nums}
code{font-family:'DejaVu Sans Mono',monospace;font-size:.92em}
.badge{display:inline-block;padding:.05em .6em;border-radius:.8em;font-weight:600;font-size:.85em}
.badge.ok{background:#d4f4dd;color:#14632b} .badge.bad{background:#fbdada;color:#8b1a1a}
.badge.unknown{background:#eee;color:#555}
.note{padding:.5em .8em;border-left:4px solid #aaa;background:#fafafa}
.note.missing{border-color:#e0a800;background:#fff8e1}
.grid{display:grid;grid-template-columns:1fr;gap:.8em}
.task{border:1px solid #e3e3e3;border-radius:6px;padding:.2em 1em 1em;margin:1em 0}
"""


def page(title: str, lead: str, nav: Sequence[tuple[str, str]], body: str) -> str:
    """The whole HTML document: inline CSS, no script, no external URL."""
    links = "".join(f'<a href="#{esc(a)}">{esc(t)}</a>' for a, t in nav)
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{esc(title)}</title><style>{_CSS}</style></head><body>"
            f"<h1>{esc(title)}</h1><p class=\"lead\">{lead}</p><nav>{links}</nav>{body}</body></html>\n")
