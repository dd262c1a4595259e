"""What a certificate does not promise: the README's paragraph, shown at the end of every report (a test
checks that the README still says the same)."""

from __future__ import annotations

import re

from ._html import esc

__all__ = ["DOES_NOT_PROMISE", "does_not_promise_html"]

#: The README's paragraph (section "What a certificate means -- and what it does not promise"), Markdown.
DOES_NOT_PROMISE = (
    "A certificate does **not** promise that a real robot will succeed: it is one seeded plan executed in a "
    "rigid-body simulation with primitive geometry, simplified contact and friction, a grasp modelled as a "
    "force-bounded spring made once both finger pads close on the handle (standing in for the arm's and the "
    "pads' compliance), and no sensing noise or localisation error. It "
    "says the reconstruction is *good enough for this robot, this task and this model of the world*, and "
    "with `--against` how an estimate's plan fares on a more trusted model — not that the scan was right "
    "everywhere, nor that the object is safe to open in reality.")


def does_not_promise_html() -> str:
    """:data:`DOES_NOT_PROMISE` as one HTML paragraph (``**b**``, ``*i*`` and ```code``` marked up)."""
    text = esc(DOES_NOT_PROMISE)
    text = re.sub(r"\*\*(.+?)\*\*", r"<b>\1</b>", text)
    text = re.sub(r"\*(.+?)\*", r"<i>\1</i>", text)
    text = re.sub(r"`(.+?)`", r"<code>\1</code>", text)
    return f"<p>{text}</p>"
