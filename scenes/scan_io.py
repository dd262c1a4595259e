"""Write and read the scan format of DESIGN.md: ``scan.ply`` + ``labels.json`` and ``scan.npz``.

``scan.ply`` is binary little-endian with vertex properties ``x y z nx ny nz`` (float32),
``red green blue`` (uchar), ``object_id part_id`` (int32).
"""

from __future__ import annotations

import io
import json
from pathlib import Path

import numpy as np

from .description import write_bytes_atomic, write_text_atomic
from .errors import SceneSpecError
from .scanner.scan import Scan

__all__ = ["PLY_DTYPE", "write_scan_ply", "read_scan_ply", "write_labels_json", "write_scan_npz",
           "write_scan_meta", "write_scan"]

PLY_DTYPE = np.dtype([("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("nx", "<f4"), ("ny", "<f4"), ("nz", "<f4"),
                      ("red", "u1"), ("green", "u1"), ("blue", "u1"), ("object_id", "<i4"), ("part_id", "<i4")])
_PLY_TYPES = {"<f4": "float", "u1": "uchar", "<i4": "int"}


def write_scan_ply(scan: Scan, path: str | Path) -> Path:
    """Write ``scan`` as a binary PLY atomically."""
    v = np.empty(len(scan), PLY_DTYPE)
    for i, k in enumerate("xyz"):
        v[k] = scan.points[:, i]
        v["n" + k] = scan.normals[:, i]
    for i, k in enumerate(("red", "green", "blue")):
        v[k] = scan.colors[:, i]
    v["object_id"] = scan.object_id
    v["part_id"] = scan.part_id
    props = "".join(f"property {_PLY_TYPES[PLY_DTYPE[name].str.replace('|', '')]} {name}\n"
                    for name in PLY_DTYPE.names)
    header = (f"ply\nformat binary_little_endian 1.0\ncomment partscene virtual scan, metres, z up\n"
              f"element vertex {len(v)}\n{props}end_header\n")
    return write_bytes_atomic(path, header.encode("ascii") + v.tobytes())


def read_scan_ply(path: str | Path) -> np.ndarray:
    """Read a PLY written by :func:`write_scan_ply` into a structured array of ``PLY_DTYPE``."""
    data = Path(path).read_bytes()
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply\n") or end < 0:
        raise SceneSpecError(f"{path}: not a PLY file")
    header = data[:end].decode("ascii").splitlines()
    if "format binary_little_endian 1.0" not in header:
        raise SceneSpecError(f"{path}: only binary_little_endian PLY written by scenes is read here")
    n = int(next(h.split()[2] for h in header if h.startswith("element vertex")))
    return np.frombuffer(data, PLY_DTYPE, count=n, offset=end + len(b"end_header\n")).copy()


def write_labels_json(scan: Scan, path: str | Path) -> Path:
    return write_text_atomic(path, json.dumps(scan.labels, indent=1) + "\n")


def write_scan_npz(scan: Scan, path: str | Path) -> Path:
    """Arrays ``points normals colors object_id part_id`` plus ``labels`` (the labels JSON as a string)."""
    buf = io.BytesIO()
    np.savez_compressed(buf, points=scan.points, normals=scan.normals, colors=scan.colors,
                        object_id=scan.object_id, part_id=scan.part_id,
                        labels=np.array(json.dumps(scan.labels)))
    return write_bytes_atomic(path, buf.getvalue())


def write_scan_meta(scan: Scan, path: str | Path, meta: dict) -> Path:
    """``scan_meta.json``: ``meta`` (scene, seed, preset, parameters) + point count + camera poses (world
    frame) + ``T_scan_world`` (the scan's frame from the world's: identity unless the preset tilts it)."""
    d = dict(meta)
    d.update(points=len(scan), frames=len(scan.T_world_cameras),
             T_world_cameras=[[[float(x) for x in row] for row in T] for T in scan.T_world_cameras],
             T_scan_world=[[float(x) for x in row] for row in scan.T_scan_world])
    return write_text_atomic(path, json.dumps(d, indent=1) + "\n")


def write_scan(scan: Scan, out_dir: str | Path, meta: dict | None = None) -> dict[str, Path]:
    """Write ``scan.ply``, ``labels.json``, ``scan.npz`` (and ``scan_meta.json`` with ``meta``) into ``out_dir``."""
    out = Path(out_dir)
    files = {"scan_ply": write_scan_ply(scan, out / "scan.ply"),
             "labels_json": write_labels_json(scan, out / "labels.json"),
             "scan_npz": write_scan_npz(scan, out / "scan.npz")}
    if meta is not None:
        files["scan_meta"] = write_scan_meta(scan, out / "scan_meta.json", meta)
    return files


