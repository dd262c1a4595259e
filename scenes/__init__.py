"""partscene ``scenes``: ground-truth articulated rooms and a virtual RGB-D scanner.

>>> from scenes import make_scene
>>> made = make_scene("kitchen", seed=0, preset="realistic", out="out/kitchen")   # doctest: +SKIP
>>> made.files["truth_urdf"], made.scan.points.shape                              # doctest: +SKIP

Command line: ``scenes list`` and ``scenes make NAME [--seed S] [--preset clean|realistic] --out DIR``
(also ``python -m scenes``). Files: ``truth.urdf``, ``truth.json`` (``docs/contracts.md``),
``scan.ply`` + ``labels.json`` + ``scan.npz`` (DESIGN.md scan format), ``scan_meta.json``,
``preview_room.png``, ``preview_scan.png``.

Layout: ``generators/`` (one module per object family, all built with ``generators.builder``),
``composer`` + ``footprints`` (room placement), ``builtin`` (named scenes), ``truth_urdf`` /
``truth_json`` (ground truth on disk), ``scanner/`` (camera path, open3d ray casting adapter,
degradations, presets), ``scan_io``, ``preview``; checks in ``validate``, ``overlap`` and
``surface_distance``; every constant in ``config`` and ``scanner.params``.
"""

from .api import MadeScene, list_scenes, make_scene
from .builtin import SCENES, build_scene
from .errors import PlacementError, ScanError, ScenesError, SceneSpecError
from .model import ArticulatedObject, Joint, JointType, Part, Scene, Shape, ShapeType, Wall
from .scanner import PRESETS, Scan, ScanParams, scan_scene
from .truth_json import read_truth_json, write_truth_json
from .truth_urdf import urdf_from_scene, write_truth_urdf

__all__ = ["make_scene", "MadeScene", "list_scenes", "build_scene", "SCENES", "scan_scene", "Scan",
           "ScanParams", "PRESETS", "Scene", "ArticulatedObject", "Part", "Joint", "JointType", "Shape",
           "ShapeType", "Wall", "write_truth_urdf", "urdf_from_scene", "write_truth_json", "read_truth_json",
           "ScenesError", "SceneSpecError", "PlacementError", "ScanError"]
