"""Virtual RGB-D scanner: ray casting from a walking person's camera path, with degradations."""

from .params import PRESETS, ScanParams, params_for_preset
from .scan import Scan, labels_from_scene, scan_scene

__all__ = ["PRESETS", "ScanParams", "params_for_preset", "Scan", "scan_scene", "labels_from_scene"]
