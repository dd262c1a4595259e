"""The Python API: build a named scene, scan it, write truth + scan + previews."""

from __future__ import annotations

import dataclasses
import logging
from dataclasses import dataclass, field
from pathlib import Path

from .builtin import SCENES, build_scene
from .errors import SceneSpecError
from .model import Scene
from .scan_io import write_scan
from .scanner import Scan, params_for_preset, scan_scene
from .scanner.params import PRESETS
from .truth_json import write_truth_json
from .truth_urdf import write_truth_urdf

__all__ = ["MadeScene", "make_scene", "list_scenes"]

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False)
class MadeScene:
    """What :func:`make_scene` produced: the scene, its scan, and the files written (name -> path)."""

    scene: Scene
    scan: Scan | None
    files: dict[str, Path] = field(default_factory=dict)


def list_scenes() -> tuple[str, ...]:
    return SCENES


def make_scene(name: str, seed: int = 0, preset: str = "clean", out: str | Path | None = None,
               scan: bool = True, previews: bool = True, **scan_overrides) -> MadeScene:
    """Build scene ``name`` for ``seed``, scan it with ``preset`` (+ ``scan_overrides``) and, if ``out``
    is given, write ``truth.urdf``, ``truth.json``, ``scan.ply``, ``labels.json``, ``scan.npz``,
    ``scan_meta.json`` (preset, parameters, camera poses) and (``previews``) ``preview_room.png`` and
    ``preview_scan.png`` there. Bad names/presets/seeds raise :class:`~scenes.errors.ScenesError`.
    """
    if preset not in PRESETS:
        raise SceneSpecError(f"unknown scan preset {preset!r}; expected one of {', '.join(PRESETS)}")
    scene = build_scene(name, seed)
    params = params_for_preset(preset, **scan_overrides)
    s = scan_scene(scene, params, seed) if scan else None
    files: dict[str, Path] = {}
    if out is not None:
        out = Path(out)
        if out.exists() and not out.is_dir():
            raise SceneSpecError(f"output {out} exists and is not a directory")
        files["truth_urdf"] = write_truth_urdf(scene, out / "truth.urdf")
        files["truth_json"] = write_truth_json(scene, out / "truth.json")
        if s is not None:
            meta = {"format": "partscene.scan_meta/1", "scene": name, "seed": int(seed), "preset": preset,
                    "params": dataclasses.asdict(params)}
            files.update(write_scan(s, out, meta))
        if previews:
            from .preview import write_room_preview, write_scan_preview

            files["preview_room"] = write_room_preview(scene, out / "preview_room.png")
            if s is not None:
                files["preview_scan"] = write_scan_preview(s, out / "preview_scan.png", seed)
        log.info("wrote %s", ", ".join(str(p) for p in files.values()))
    return MadeScene(scene, s, files)
