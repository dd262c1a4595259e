"""Synthetic labelled scans for recon's unit tests: furniture built from trimesh boxes and cylinders,
sampled (seeded) on the faces a camera in front of and above the object would see.

Each builder returns a list of ``(object_id, category, [(part_id, label, [trimesh meshes])...])``;
``scan_arrays`` turns such a list into the per-point arrays + labels the scan reader validates.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh

FRONT = np.array([1.0, 0.0, 0.0])


# helper modules beside the tests (recon_*.py) importable under --import-mode=importlib
_HERE = str(Path(__file__).parent)
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)


def box(lo, hi) -> trimesh.Trimesh:
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    T = np.eye(4)
    T[:3, 3] = (lo + hi) / 2
    return trimesh.creation.box(extents=hi - lo, transform=T)


def cylinder_z(xy, r, z0, z1) -> trimesh.Trimesh:
    T = np.eye(4)
    T[:3, 3] = [xy[0], xy[1], (z0 + z1) / 2]
    return trimesh.creation.cylinder(radius=r, height=z1 - z0, transform=T, sections=48)


def cabinet(oid=1, base=100, *, door_handle_side=+1, x0=0.0, y0=0.0):
    """A 0.5 x 0.8 x 0.8 m cabinet facing +x: hollow body, a drawer (front panel) with a handle
    above a side-hinged door with a handle at ``door_handle_side`` (±y)."""
    b = [box([x0, y0 - 0.4, 0.78], [x0 + 0.5, y0 + 0.4, 0.8]),          # top
         box([x0, y0 - 0.4, 0.0], [x0 + 0.5, y0 + 0.4, 0.02]),          # bottom
         box([x0, y0 - 0.4, 0.0], [x0 + 0.5, y0 - 0.38, 0.8]),          # sides
         box([x0, y0 + 0.38, 0.0], [x0 + 0.5, y0 + 0.4, 0.8]),
         box([x0, y0 - 0.4, 0.0], [x0 + 0.02, y0 + 0.4, 0.8]),          # back
         box([x0 + 0.48, y0 - 0.38, 0.40], [x0 + 0.5, y0 + 0.38, 0.42])]  # rail between drawer and door
    drawer = [box([x0 + 0.48, y0 - 0.375, 0.425], [x0 + 0.5, y0 + 0.375, 0.775])]
    dhandle = [box([x0 + 0.5, y0 - 0.08, 0.59], [x0 + 0.53, y0 + 0.08, 0.61])]
    door = [box([x0 + 0.48, y0 - 0.375, 0.025], [x0 + 0.5, y0 + 0.375, 0.395])]
    hy = y0 + door_handle_side * 0.31
    ohandle = [box([x0 + 0.5, hy - 0.01, 0.15], [x0 + 0.53, hy + 0.01, 0.3])]
    return (oid, "cabinet", [(base + 1, "body", b), (base + 2, "drawer", drawer),
                             (base + 3, "handle", dhandle), (base + 4, "door", door),
                             (base + 5, "handle", ohandle)])


def table(oid=2, base=200, x0=2.0, y0=0.0):
    """A 1.2 x 0.8 x 0.76 m table: a top on four cylinder legs."""
    top = [box([x0 - 0.6, y0 - 0.4, 0.72], [x0 + 0.6, y0 + 0.4, 0.76])]
    parts = [(base + 1, "top", top)]
    for k, (sx, sy) in enumerate([(-1, -1), (-1, 1), (1, -1), (1, 1)]):
        parts.append((base + 2 + k, "leg", [cylinder_z((x0 + sx * 0.52, y0 + sy * 0.32), 0.03, 0.0, 0.72)]))
    return (oid, "table", parts)


def scan_arrays(objects, *, points_per_m2=6000, seed=0, hidden=((-1, 0, 0), (0, 0, -1)),
                floor=True, T=None):
    """Sample the objects' surfaces -> (props dict for ``scan_from_arrays``, labels list).

    Faces whose normal is within 60 deg of a ``hidden`` direction are not sampled (the back against
    a wall, the underside). ``T`` (4, 4) moves the whole scan afterwards.
    """
    rng = np.random.default_rng(seed)
    pts, obj, part, labels = [], [], [], []
    hidden = np.asarray(hidden, float).reshape(-1, 3)
    for oid, cat, parts in objects:
        labels.append({"id": oid, "category": cat, "parts": [{"id": pid, "label": lab} for pid, lab, _ in parts]})
        for pid, _, meshes in parts:
            for m in meshes:
                keep = np.all(m.face_normals @ hidden.T < 0.5, axis=1)
                sub = m.submesh([np.flatnonzero(keep)], append=True)
                n = max(int(sub.area * points_per_m2), 30)
                p, _ = trimesh.sample.sample_surface(sub, n, seed=int(rng.integers(1 << 30)))
                pts.append(p)
                obj.append(np.full(len(p), oid))
                part.append(np.full(len(p), pid))
    if floor:
        f = np.c_[rng.uniform(-1, 3.5, 4000), rng.uniform(-1.5, 1.5, 4000), np.zeros(4000)]
        pts.append(f)
        obj.append(np.full(len(f), -1))
        part.append(np.full(len(f), -1))
    pts = np.concatenate(pts)
    if T is not None:
        pts = pts @ T[:3, :3].T + T[:3, 3]
    props = {"x": pts[:, 0], "y": pts[:, 1], "z": pts[:, 2],
             "object_id": np.concatenate(obj), "part_id": np.concatenate(part)}
    return props, labels


def write_ply(path, props, binary=True):
    """Write ``props`` as a PLY vertex list (float x y z, int object_id part_id)."""
    n = len(props["x"])
    names = [("x", "<f4", "float"), ("y", "<f4", "float"), ("z", "<f4", "float"),
             ("object_id", "<i4", "int"), ("part_id", "<i4", "int")]
    header = "ply\nformat {} 1.0\nelement vertex {}\n".format("binary_little_endian" if binary else "ascii", n)
    header += "".join(f"property {t} {k}\n" for k, _, t in names) + "end_header\n"
    if binary:
        a = np.zeros(n, dtype=[(k, d) for k, d, _ in names])
        for k, _, _ in names:
            a[k] = props[k]
        path.write_bytes(header.encode() + a.tobytes())
    else:
        rows = "\n".join(f"{x:.6f} {y:.6f} {z:.6f} {o} {p}" for x, y, z, o, p in
                         zip(props["x"], props["y"], props["z"], props["object_id"], props["part_id"]))
        path.write_text(header + rows + "\n")


@pytest.fixture(scope="session")
def kitchen_scan():
    """A cabinet and a table on a floor: (Scan, objects)."""
    from recon.scan import scan_from_arrays

    objects = [cabinet(), table()]
    props, labels = scan_arrays(objects)
    return scan_from_arrays(props, labels), objects


@pytest.fixture(scope="session")
def kitchen_rec(kitchen_scan):
    from recon.pipeline import reconstruct_scan

    return reconstruct_scan(kitchen_scan[0], seed=0)


@pytest.fixture(scope="session")
def synth():
    """The builders of this module (tests cannot import conftest under --import-mode=importlib)."""
    from types import SimpleNamespace

    return SimpleNamespace(box=box, cylinder_z=cylinder_z, cabinet=cabinet, table=table,
                           scan_arrays=scan_arrays, write_ply=write_ply)
