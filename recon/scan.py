"""Read and validate a labelled scan: ``scan.ply`` or ``scan.npz`` plus ``labels.json``.

The format (README.md, "Input format"): per point ``x y z`` (metres, z up), optional normals and colours,
``object_id`` (-1 = background) and ``part_id`` (-1 = none); labels.json lists the objects with their
category and parts with their labels. Problems that make the file unusable raise :class:`ScanError`
naming the file and field; problems local to one part (too few points, an unknown label, an id the
labels do not know) are warnings that name the object and part, collected in ``Scan.warnings``.
"""

from __future__ import annotations

import json
import logging
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from recon.config import ReconConfig, ScanConfig
from recon.errors import ScanError
from scenes.description import KNOWN_CATEGORIES, KNOWN_LABELS

__all__ = ["KNOWN_CATEGORIES", "KNOWN_LABELS", "PartPoints", "ObjectPoints", "Scan", "read_scan",
           "scan_from_arrays"]

log = logging.getLogger(__name__)

#: part labels kept from ``handle_min_part_points`` points (small parts placed from their mount)
_SMALL_LABELS = frozenset({"handle", "knob"})

#: a part (or a whole scan) whose points all lie within this distance (m, per axis) is degenerate:
#: a part is skipped with a warning, a whole scan is refused
MIN_PART_EXTENT = 1e-3



@dataclass(frozen=True, eq=False)
class PartPoints:
    """The points of one labelled part. points : (n, 3) float, world, metres; normals : (n, 3) or None."""

    object_id: int
    part_id: int
    label: str
    points: np.ndarray
    normals: np.ndarray | None = None


@dataclass(frozen=True, eq=False)
class ObjectPoints:
    """One labelled object: id, category and its parts (those with enough points).

    skipped : the parts labels.json declares that have fewer than ``min_part_points`` points (maybe
    none): too few to fit, but known to exist (completion.py places a hidden leg from them).
    """

    id: int
    category: str
    parts: tuple[PartPoints, ...]
    skipped: tuple[PartPoints, ...] = ()


@dataclass(frozen=True, eq=False)
class Scan:
    """A validated labelled scan.

    points : (N, 3) float64, world, metres (every point, background included)
    object_id, part_id : (N,) int64
    normals : (N, 3) float64 or None;  colors : (N, 3) uint8 or None
    objects : the labelled objects, in labels.json order
    warnings : per-object / per-part problems found while reading
    source : the scan's path (for messages)
    """

    points: np.ndarray
    object_id: np.ndarray
    part_id: np.ndarray
    normals: np.ndarray | None
    colors: np.ndarray | None
    objects: tuple[ObjectPoints, ...]
    warnings: tuple[str, ...] = ()
    source: str = "<arrays>"

    def transformed(self, T_new_old: np.ndarray) -> "Scan":
        """The scan moved rigidly by ``T_new_old`` (4, 4): points, normals and every part."""
        R, t = T_new_old[:3, :3], T_new_old[:3, 3]
        pts = self.points @ R.T + t
        nrm = None if self.normals is None else self.normals @ R.T
        def moved(parts):
            return tuple(replace(p, points=p.points @ R.T + t, normals=None if p.normals is None else p.normals @ R.T)
                         for p in parts)
        objs = tuple(replace(o, parts=moved(o.parts), skipped=moved(o.skipped)) for o in self.objects)
        return replace(self, points=pts, normals=nrm, objects=objs)


def _read_ply(path: Path) -> dict[str, np.ndarray]:
    """The vertex properties of a PLY (ascii or binary) as {name: (N,) array}, via trimesh's reader."""
    import trimesh.exchange.ply as ply

    try:
        with open(path, "rb") as f:
            raw = ply.load_ply(f)["metadata"]["_ply_raw"]
    except Exception as exc:  # trimesh raises bare ValueError/KeyError on malformed headers
        raise ScanError(f"{path}: not a readable PLY point cloud ({type(exc).__name__}: {exc})") from exc
    if "vertex" not in raw:
        raise ScanError(f"{path}: PLY has no 'vertex' element")
    if "data" not in raw["vertex"]:  # trimesh keeps no data for an element of 0 vertices
        raise ScanError(f"{path}: the scan has no points (the PLY header declares 0 vertices)")
    data = raw["vertex"]["data"]
    if isinstance(data, dict):  # ascii: {name: (N, 1)}
        out = {k: np.asarray(v).reshape(-1) for k, v in data.items()}
    else:
        out = {k: np.asarray(data[k]).reshape(-1) for k in data.dtype.names}
    declared = int(raw["vertex"].get("length", -1))
    read = min((len(v) for v in out.values()), default=0)
    if declared >= 0 and read != declared:
        raise ScanError(f"{path}: the PLY header declares {declared} vertices but the file holds {read} "
                        "(cut short?); re-export or copy the whole file")
    return out


def _read_npz(path: Path) -> dict[str, np.ndarray]:
    try:
        with np.load(path, allow_pickle=False) as z:
            arrays = {k: z[k] for k in z.files}
    except Exception as exc:
        raise ScanError(f"{path}: not a readable NPZ ({type(exc).__name__}: {exc})") from exc
    if "points" not in arrays:
        raise ScanError(f"{path}: NPZ has no 'points' array (has {sorted(arrays)})")
    pts = np.asarray(arrays.pop("points"))
    if pts.ndim != 2 or pts.shape[1] != 3:
        raise ScanError(f"{path}: 'points' must be (N, 3), got {pts.shape}")
    out = {"x": pts[:, 0], "y": pts[:, 1], "z": pts[:, 2]}
    if "normals" in arrays:
        n = np.asarray(arrays["normals"])
        if n.ndim != 2 or n.shape != (len(pts), 3):
            raise ScanError(f"{path}: 'normals' must be ({len(pts)}, 3) like 'points', got {n.shape}; "
                            "fix or drop the array")
        out.update(nx=n[:, 0], ny=n[:, 1], nz=n[:, 2])
    if "colors" in arrays:
        c = np.asarray(arrays["colors"])
        if c.ndim != 2 or len(c) != len(pts) or c.shape[1] < 3:
            raise ScanError(f"{path}: 'colors' must be ({len(pts)}, 3 or 4) like 'points', got {c.shape}; "
                            "fix or drop the array")
        out.update(red=c[:, 0], green=c[:, 1], blue=c[:, 2])
    for k in ("object_id", "part_id"):
        if k in arrays:
            out[k] = np.asarray(arrays[k]).reshape(-1)
    return out


def _read_labels(path: Path) -> list[dict]:
    try:
        doc = json.loads(Path(path).read_text())
    except FileNotFoundError:
        raise ScanError(f"{path}: labels file not found") from None
    except IsADirectoryError:
        raise ScanError(f"{path}: is a folder; give the labels.json file inside it") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise ScanError(f"{path}: labels file is not valid JSON ({exc})") from exc
    if not isinstance(doc, dict) or not isinstance(doc.get("objects"), list):
        raise ScanError(f"{path}: labels must be an object with an 'objects' list")
    seen_obj, seen_part = set(), {}
    for i, o in enumerate(doc["objects"]):
        if not isinstance(o, dict) or "id" not in o or "category" not in o or not isinstance(o.get("parts"), list):
            raise ScanError(f"{path}: objects[{i}] needs 'id', 'category' and a 'parts' list")
        if not _is_int(o["id"]):
            raise ScanError(f"{path}: objects[{i}] id {o['id']!r} must be an integer (the object_id of its points)")
        _check_name(path, f"object {o['id']} category", o["category"])
        if o["id"] in seen_obj:
            raise ScanError(f"{path}: object id {o['id']} appears twice")
        seen_obj.add(o["id"])
        for j, p in enumerate(o["parts"]):
            if not isinstance(p, dict) or "id" not in p or "label" not in p:
                raise ScanError(f"{path}: object {o['id']} parts[{j}] needs 'id' and 'label'")
            if not _is_int(p["id"]):
                raise ScanError(f"{path}: object {o['id']} parts[{j}] id {p['id']!r} must be an integer "
                                "(the part_id of its points)")
            _check_name(path, f"object {o['id']} part {p['id']} label", p["label"])
            if p["id"] in seen_part:
                raise ScanError(f"{path}: part id {p['id']} is listed under object {seen_part[p['id']]} "
                                f"and object {o['id']}; part ids must be unique in the file")
            seen_part[p["id"]] = o["id"]
        bodies = [p["id"] for p in o["parts"] if str(p["label"]).lower() == "body"]
        if len(bodies) > 1:
            raise ScanError(f"{path}: object {o['id']} has {len(bodies)} 'body' parts ({', '.join(map(str, bodies))}); "
                            "an object has one body: relabel the others (e.g. 'door', 'drawer') or merge them")
    return doc["objects"]


#: the longest object category or part label accepted in labels.json (characters); link and joint names
#: are built from them and URDF readers limit names (:data:`scenes.description.MAX_NAME_LENGTH`)
MAX_LABEL_LENGTH = 64


def _is_int(v) -> bool:
    """``v`` is a JSON integer (not a bool, string, list or float)."""
    return isinstance(v, int) and not isinstance(v, bool)


def _check_name(path: Path, what: str, value) -> None:
    """Refuse a category or label that is not a string of at most :data:`MAX_LABEL_LENGTH` characters."""
    if not isinstance(value, str):
        raise ScanError(f"{path}: {what} {value!r} must be a string")
    if len(value) > MAX_LABEL_LENGTH:
        raise ScanError(f"{path}: {what} is {len(value)} characters long (at most {MAX_LABEL_LENGTH}): "
                        f"shorten {value[:32]!r}...")


def read_scan(scan_path: str | Path, labels_path: str | Path,
              config: ScanConfig | ReconConfig = ScanConfig()) -> Scan:
    """Read ``scan_path`` (.ply or .npz) and ``labels_path`` (labels.json) into a validated :class:`Scan`.

    config : the scan group (a whole :class:`ReconConfig` gives its ``scan`` group).

    Raises ScanError when a file is missing or malformed, when coordinates are NaN/inf, when the
    scan is empty, or when its extent says millimetres. Per-part problems become warnings.
    """
    scan_path = Path(scan_path)
    if not scan_path.is_file():
        raise ScanError(f"{scan_path}: scan file not found")
    suffix = scan_path.suffix.lower()
    if suffix == ".ply":
        props = _read_ply(scan_path)
    elif suffix == ".npz":
        props = _read_npz(scan_path)
    else:
        raise ScanError(f"{scan_path}: unknown scan format {suffix!r} (expected .ply or .npz)")
    labels = _read_labels(Path(labels_path))
    return scan_from_arrays(props, labels, config=config, source=str(scan_path))


def scan_from_arrays(props: dict[str, np.ndarray], labels: list[dict], *,
                     config: ScanConfig | ReconConfig = ScanConfig(), source: str = "<arrays>") -> Scan:
    """Validate per-point arrays ``props`` (x, y, z, object_id, part_id, optional nx.., red..) against
    the parsed ``labels`` (the 'objects' list of labels.json). See :func:`read_scan`."""
    if isinstance(config, ReconConfig):
        config = config.scan
    for k in ("x", "y", "z", "object_id", "part_id"):
        if k not in props:
            raise ScanError(f"{source}: missing per-point field {k!r} (has {sorted(props)})")
    pts = np.stack([props["x"], props["y"], props["z"]], axis=1).astype(np.float64)
    n = len(pts)
    if n == 0:
        raise ScanError(f"{source}: the scan has no points")
    obj = np.asarray(props["object_id"]).astype(np.int64)
    part = np.asarray(props["part_id"]).astype(np.int64)
    if len(obj) != n or len(part) != n:
        raise ScanError(f"{source}: object_id/part_id have {len(obj)}/{len(part)} values for {n} points")
    bad = ~np.all(np.isfinite(pts), axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ScanError(f"{source}: {int(bad.sum())} points have NaN/inf coordinates "
                        f"(first: point {i}, object {obj[i]}, part {part[i]})")
    extent = float(np.max(pts.max(axis=0) - pts.min(axis=0)))
    if extent < MIN_PART_EXTENT:
        raise ScanError(f"{source}: all {n} points lie within {extent:.3g} m of each other; "
                        "this is not a scan of a room (check the export)")
    if extent > config.max_scene_extent:
        raise ScanError(f"{source}: the scan spans {extent:.1f} units; scans must be in metres "
                        f"(this looks like millimetres: divide the coordinates by 1000)")
    normals = None
    if all(k in props for k in ("nx", "ny", "nz")):
        if not all(len(props[k]) == n for k in ("nx", "ny", "nz")):
            raise ScanError(f"{source}: the normals have {len(props['nx'])} rows for {n} points")
        normals = np.stack([props["nx"], props["ny"], props["nz"]], axis=1).astype(np.float64)
        if not np.all(np.isfinite(normals)):
            normals = None
    colors = None
    if all(k in props for k in ("red", "green", "blue")):
        if not all(len(props[k]) == n for k in ("red", "green", "blue")):
            raise ScanError(f"{source}: the colours have {len(props['red'])} rows for {n} points")
        colors = np.stack([props["red"], props["green"], props["blue"]], axis=1).astype(np.uint8)

    warnings: list[str] = []

    def warn(msg: str):
        log.warning(msg)
        warnings.append(msg)

    known_parts = {int(p["id"]): int(o["id"]) for o in labels for p in o["parts"]}
    known_objects = {int(o["id"]) for o in labels}
    for oid in sorted(set(np.unique(obj).tolist()) - known_objects - {-1}):
        warn(f"{source}: object id {oid} ({int((obj == oid).sum())} points) is not in labels.json; "
             "its points are treated as background")
    labelled = np.isin(part, list(known_parts)) if known_parts else np.zeros(n, bool)
    for pid in sorted(set(np.unique(part[obj >= 0]).tolist()) - set(known_parts) - {-1}):
        warn(f"{source}: part id {pid} ({int((part == pid).sum())} points) is not in labels.json; "
             "treated as background")
    objects = []
    for o in labels:
        oid, cat = int(o["id"]), str(o["category"]).lower()
        if cat not in KNOWN_CATEGORIES:
            warn(f"object {oid}: unknown category {cat!r}; its parts get generic joint templates")
        parts, skipped = [], []
        for p in o["parts"]:
            pid, label = int(p["id"]), str(p["label"]).lower()
            mask = labelled & (part == pid)
            wrong_obj = mask & (obj != oid)
            if wrong_obj.any():
                warn(f"object {oid} part {pid}: {int(wrong_obj.sum())} points carry object id "
                     f"{int(obj[wrong_obj][0])}; they are kept with part {pid}")
            count = int(mask.sum())
            need = (min(config.handle_min_part_points, config.min_part_points) if label in _SMALL_LABELS
                    else config.min_part_points)
            if count < need:
                warn(f"object {oid} ({cat}) part {pid} ({label}): {count} points, fewer than "
                     f"{need}; the part is skipped")
                skipped.append(PartPoints(oid, pid, label, pts[mask], None if normals is None else normals[mask]))
                continue
            span = float(np.max(np.ptp(pts[mask], axis=0)))
            if span < MIN_PART_EXTENT:
                warn(f"object {oid} ({cat}) part {pid} ({label}): its {count} points lie within {span:.3g} m "
                     f"(less than {MIN_PART_EXTENT} m); the part is skipped")
                skipped.append(PartPoints(oid, pid, label, pts[mask], None if normals is None else normals[mask]))
                continue
            if label not in KNOWN_LABELS:
                warn(f"object {oid} ({cat}) part {pid}: unknown label {label!r}; reconstructed as a "
                     "rigid part fixed to its parent")
            parts.append(PartPoints(oid, pid, label, pts[mask],
                                    None if normals is None else normals[mask]))
        if not parts:
            warn(f"object {oid} ({cat}): no part has enough points; the object is skipped")
            continue
        if all(p.label in _SMALL_LABELS for p in parts):
            warn(f"object {oid} ({cat}): only its handles / knobs have enough points (nothing of at least "
                 f"{config.min_part_points} points to mount them on); the object is skipped")
            continue
        objects.append(ObjectPoints(oid, cat, tuple(parts), tuple(skipped)))
    if not objects:
        raise ScanError(f"{source}: no labelled object has a part with at least "
                        f"{config.min_part_points} points")
    return Scan(pts, obj, part, normals, colors, tuple(objects), tuple(warnings), source)
