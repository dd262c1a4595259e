"""Write a reconstruction's files atomically: every file is rendered in memory first, then written to a
temporary name in the output folder and renamed into place, so a failure leaves no half-written file."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from recon.graph_json import graph_json_string
from recon.model import Reconstruction
from recon.scene_urdf import urdf_string

__all__ = ["write_reconstruction", "write_atomic"]


def write_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` via a temporary file in the same folder and an atomic rename."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)      # mkstemp makes 0600; give the file ordinary permissions
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def write_reconstruction(rec: Reconstruction, out_dir, *, preview_scan=None) -> dict[str, Path]:
    """Write scene.urdf, graph.json (and preview.png if ``preview_scan`` is given) into ``out_dir``."""
    out_dir = Path(out_dir)
    files = {"scene.urdf": urdf_string(rec).encode(), "graph.json": graph_json_string(rec).encode()}
    if preview_scan is not None:
        from recon.preview import preview_png

        files["preview.png"] = preview_png(rec, preview_scan, seed=rec.seed)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = {}
    for name, data in files.items():
        write_atomic(out_dir / name, data)
        paths[name] = out_dir / name
    return paths
