"""Figures of one certificate task from the rollout simcheck recorded for it (:class:`simcheck.rollout.Rollout`):
the joint opening over time against the plan, and key frames of the robot opening.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping
from pathlib import Path

import numpy as np
from PIL import Image

from scenes.description import file_stem
from simcheck.errors import RolloutFormatError
from simcheck.rollout import Rollout

from ._errors import ArtifactError
from ._key_frames import key_frame_images
from ._layout import DemoLayout
from ._task_images import png_of_key_frames, png_of_opening

__all__ = ["task_figures", "rollout_path", "segment_spans", "key_frames_for", "executed_urdf", "load_rollout"]

log = logging.getLogger(__name__)


def rollout_path(lay: DemoLayout, task: Mapping, key: str) -> Path | None:
    """The task's rollout file: the certificate's ``rollout`` field (relative to the demo dir) or
    ``rollouts/<joint>.npz``; ``None`` when the task has none (it was not executed)."""
    ref = task.get("rollout")
    if ref:
        p = Path(ref)
        return p if p.is_absolute() else lay.root / p
    p = lay.rollouts_dir / f"{file_stem(key)}.npz"
    return p if p.exists() else None


def segment_spans(rollout: Rollout) -> list[tuple[str, float, float]]:
    """``(segment name, t_start, t_end)`` of each run of samples in one segment, seconds."""
    spans: list[tuple[str, float, float]] = []
    seg, t = rollout.segment, rollout.t
    start = 0
    for i in range(1, len(seg) + 1):
        if i == len(seg) or seg[i] != seg[start]:
            if seg[start] >= 0:
                spans.append((rollout.segment_names[int(seg[start])], float(t[start]), float(t[i - 1])))
            start = i
    return spans


def load_rollout(path: Path, key: str) -> Rollout:
    """The rollout at ``path``; :class:`ArtifactError` naming the task and file when unreadable."""
    try:
        return Rollout.load(path)
    except RolloutFormatError as exc:
        raise ArtifactError(f"task {key}: {exc}") from exc


def task_figures(lay: DemoLayout, task: Mapping, key: str, required_fraction: float | None = None,
                 executed_urdf: Path | None = None) -> list[tuple[str, str, bytes]]:
    """``(figure key, caption, PNG)`` for the task: opening over time vs the plan, and key frames.

    ``executed_urdf`` is the scene the rollout was executed in (the reference with ``--against``).
    """
    path = rollout_path(lay, task, key)
    if path is None:
        return []
    if not path.exists():
        raise ArtifactError(f"{lay.certificate_json}: task {key} names rollout {path}, which does not exist")
    rollout = load_rollout(path, key)
    kind = str(task.get("kind", ""))
    unit = str(task.get("unit") or ("rad" if "door" in kind else "m"))
    plan = rollout.planned_object_q
    has_plan = np.isfinite(plan)
    figs = [("opening", f"{key}: joint opening over time, executed with physics against the plan",
             png_of_opening(rollout.t, rollout.object_q, rollout.t[has_plan], plan[has_plan],
                            rollout.requested_amount, required_fraction, unit,
                            f"{key}: joint opening over time", segment_spans(rollout)))]
    caption, frames = key_frames_for(lay, task, key, rollout, executed_urdf)
    if frames:
        figs.append(("frames", caption, png_of_key_frames(frames)))
    else:
        log.warning("task %s: the certificate lists no key-frame images and the rollout cannot be redrawn", key)
    return figs


def key_frames_for(lay: DemoLayout, task: Mapping, key: str, rollout: Rollout,
                   executed_urdf: Path | None) -> tuple[str, list[tuple[str, np.ndarray]]]:
    """``(caption, [(label, (h, w, 3) uint8)])`` key frames of the task.

    The recorded states are redrawn with a camera whose view no wall blocks when the rollout's robot is
    the default robot (the one we can load) and the executed scene is known; else the key frames simcheck
    saved while executing are shown.
    """
    if executed_urdf is not None and _is_default_robot(rollout):
        return (f"{key}: key frames of the recorded execution (robot and object where physics moved them)",
                key_frame_images(rollout, executed_urdf))
    return f"{key}: key frames taken by simcheck while executing with physics", _saved_frames(lay, task, key)


def executed_urdf(lay: DemoLayout, cert: Mapping) -> Path | None:
    """The scene the tasks were executed in: the certificate's reference (``against``), else its scene,
    found as written, relative to the demo dir, or by name in the demo dir or its truth/ folder."""
    for field in ("against", "scene"):
        ref = cert.get(field)
        if isinstance(ref, str) and ref:
            name = Path(ref).name
            for p in (Path(ref), lay.root / ref, lay.root / name, lay.truth_dir / name):
                if p.exists():
                    return p
    return None


def _saved_frames(lay: DemoLayout, task: Mapping, key: str) -> list[tuple[str, np.ndarray]]:
    """The key-frame PNGs the certificate lists for the task (paths relative to the demo dir), captioned
    by what follows the joint name in the file name ("..._joint_grasped.png" -> "grasped")."""
    frames = []
    for ref in task.get("images", []) or []:
        p = Path(ref) if Path(ref).is_absolute() else lay.root / ref
        try:
            with Image.open(p) as im:
                rgb = np.asarray(im.convert("RGB"))
        except OSError as exc:
            raise ArtifactError(f"{lay.certificate_json}: task {key} image {ref}: cannot read ({exc})") from exc
        stem = p.stem
        frames.append((stem[len(key) + 1:] if stem.startswith(key + "_") else stem, rgb))
    return frames


def _is_default_robot(rollout: Rollout) -> bool:
    """True when the rollout was recorded with the default robot (the one the redraw can load)."""
    from planners import default_robot
    return set(rollout.robot_joint_names) == set(default_robot().joint_names)
