"""Figures of one certificate task from the rollout simcheck recorded for it.

PROVISIONAL reader: written against the expected rollout arrays before simcheck's rollout format
landed; adapted to it in a later commit.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np

from ._errors import ArtifactError
from ._layout import DemoLayout
from ._task_images import png_of_opening

__all__ = ["task_figures"]


def _rollout_path(lay: DemoLayout, task: Mapping, key: str) -> Path | None:
    ref = task.get("rollout")
    if ref:
        p = Path(ref)
        return p if p.is_absolute() else lay.root / p
    p = lay.rollouts_dir / f"{key}.npz"
    return p if p.exists() else None


def task_figures(lay: DemoLayout, task: Mapping, key: str) -> list[tuple[str, str, bytes]]:
    """``(figure key, caption, PNG)`` for the task: opening over time vs the plan (and key frames)."""
    path = _rollout_path(lay, task, key)
    if path is None or not path.exists():
        return []
    try:
        with np.load(path) as z:
            arrays = {k: z[k] for k in z.files}
    except (OSError, ValueError) as exc:
        raise ArtifactError(f"{path}: cannot read rollout of task {key} ({exc})") from exc
    for name in ("t", "object_q"):
        if name not in arrays:
            raise ArtifactError(f"{path}: rollout of task {key} lacks array {name!r}")
    png = png_of_opening(arrays["t"], arrays["object_q"], arrays.get("plan_t"), arrays.get("plan_object_q"),
                         task.get("amount"), None, "rad" if task.get("kind") == "open-door" else "m",
                         f"{key}: joint opening over time")
    return [("opening", f"{key}: executed joint opening against the plan", png)]
