"""partscene ``scenes``: ground-truth articulated rooms and a virtual RGB-D scanner.

>>> from scenes import make_scene
>>> made = make_scene("kitchen", seed=0, preset="realistic", out="out/kitchen")   # doctest: +SKIP
>>> made.files["truth_urdf"], made.scan.points.shape                              # doctest: +SKIP

Command line: ``scenes list`` and ``scenes make NAME [--seed S] [--preset clean|realistic] --out DIR``
(also ``python -m scenes``). Files: ``truth.urdf``, ``truth.json`` (``docs/contracts.md``),
``scan.ply`` + ``labels.json`` + ``scan.npz`` (DESIGN.md scan format), ``scan_meta.json``,
``preview_room.png``, ``preview_scan.png``.

Layout: ``description/`` (the engine-free scene description every partscene package imports: errors,
naming, vocabulary, poses, shapes, the scene model, the only URDF and truth.json readers and writers),
``generators/`` (one module per object family, all built with ``generators.builder``),
``composer`` + ``footprints`` (room placement), ``builtin`` (named scenes), ``truth_urdf`` /
``truth_json`` (ground truth on disk), ``scanner/`` (camera path, open3d ray casting adapter,
degradations, presets), ``scan_io``, ``preview``; checks in ``validate``, ``overlap`` and
``surface_distance``; every constant in ``config`` and ``scanner.params``.
"""

import lazy_loader

# Names are imported on first use, so importing a light module (scenes.outcome, scenes.description) or running
# `scenes --help` does not load trimesh, scipy or open3d.
__getattr__, __dir__, __all__ = lazy_loader.attach(__name__, submod_attrs={
    "api": ["make_scene", "MadeScene", "list_scenes"],
    "builtin": ["SCENES", "build_scene"],
    "scanner": ["scan_scene", "Scan", "ScanParams", "PRESETS"],
    "model": ["Scene", "ArticulatedObject", "Part", "Joint", "JointType", "Wall"],
    "description": ["Shape", "ShapeKind"],
    "truth_urdf": ["write_truth_urdf", "urdf_from_scene"],
    "truth_json": ["write_truth_json", "read_truth_json"],
    "openings": ["Opening", "openings"],
    "errors": ["ScenesError", "SceneSpecError", "PlacementError", "ScanError"],
    "outcome": ["Outcome", "exit_code"],
})
