"""Write a reconstruction's files atomically: every file is rendered in memory first, then written to a
temporary name in the output folder and renamed into place, so a failure leaves no half-written file.
(``recon build`` writes them into a temporary folder that becomes ``--out`` as a whole:
:mod:`scenes.output_folder`.)"""

from __future__ import annotations

from pathlib import Path

from recon.graph_json import graph_json_string
from recon.model import Reconstruction
from recon.scene_srdf import srdf_string
from recon.scene_urdf import urdf_string
from scenes.description import write_bytes_atomic

__all__ = ["write_reconstruction"]


def write_reconstruction(rec: Reconstruction, out_dir, *, preview_scan=None, mjcf: bool = False) -> dict[str, Path]:
    """Write scene.urdf, scene.srdf (the link pairs in contact at rest), graph.json, scene.xml (MJCF) when
    ``mjcf`` and preview.png if ``preview_scan`` is given, into ``out_dir``."""
    out_dir = Path(out_dir)
    files = {"scene.urdf": urdf_string(rec).encode(), "scene.srdf": srdf_string(rec).encode(),
             "graph.json": graph_json_string(rec).encode()}
    if mjcf:
        from recon.scene_mjcf import reconstruction_mjcf

        files["scene.xml"] = reconstruction_mjcf(rec).encode()
    if preview_scan is not None:
        from recon.preview import preview_png

        files["preview.png"] = preview_png(rec, preview_scan, seed=rec.seed)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = {}
    for name, data in files.items():
        paths[name] = write_bytes_atomic(out_dir / name, data)
    return paths
