"""The virtual RGB-D scan of a scene: ray cast every frame, degrade, merge and downsample."""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from ..errors import ScanError
from ..model import Scene
from ..description import DEFAULT_RGBA, LABEL_RGBA
from . import degrade
from .camera_path import camera_poses
from .meshes import scene_meshes
from .params import ScanParams
from .raycast_open3d import Raycaster

__all__ = ["Scan", "scan_scene", "pixel_rays", "labels_from_scene"]

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False)
class Scan:
    """A labelled point cloud (the scan's frame, metres, z up: the world's unless the preset tilts it).

    ``points`` (n, 3) float64; ``normals`` (n, 3) float64 unit (true surface normals); ``colors``
    (n, 3) uint8; ``object_id``/``part_id`` (n,) int32 (-1 = background); ``labels``: the labels.json
    dict; ``T_world_cameras`` (k, 4, 4) the frames used (world frame). Truth kept for tests and metrics
    (not written to scan.ply): ``is_outlier`` (n,) bool, ``frame`` (n,) int32 index of the camera that saw
    the point, ``range`` (n,) float64 true (noise-free) distance from that camera, metres;
    ``T_scan_world`` (4, 4) the scan's frame from the world's (identity unless ``frame_tilt_deg`` /
    ``frame_floor_offset``; written to scan_meta.json).
    """

    points: np.ndarray
    normals: np.ndarray
    colors: np.ndarray
    object_id: np.ndarray
    part_id: np.ndarray
    labels: dict
    T_world_cameras: np.ndarray
    is_outlier: np.ndarray
    frame: np.ndarray
    range: np.ndarray
    T_scan_world: np.ndarray = field(default_factory=lambda: np.eye(4))

    def __len__(self) -> int:
        return len(self.points)

    def counts_by_part(self) -> dict[int, int]:
        ids, n = np.unique(self.part_id, return_counts=True)
        return {int(i): int(c) for i, c in zip(ids, n)}


def labels_from_scene(scene: Scene) -> dict:
    """The labels.json dict: every object with its parts' ids and semantic labels."""
    return {"objects": [{"id": o.id, "category": o.category,
                         "parts": [{"id": p.id, "label": p.label} for p in o.parts]} for o in scene.objects]}


def _camera_dirs(width: int, height: int, fov_deg: float) -> np.ndarray:
    """(w*h, 3) unit ray directions through pixel centres in the camera frame (x right, y down, z ahead)."""
    f = (width / 2) / np.tan(np.radians(fov_deg) / 2)
    u, v = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    d = np.stack([(u - width / 2) / f, (v - height / 2) / f, np.ones_like(u)], -1).reshape(-1, 3)
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def pixel_rays(T_world_camera: np.ndarray, width: int, height: int, fov_deg: float,
               dirs_camera: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Pinhole rays through pixel centres: (origins (w*h, 3), unit directions (w*h, 3)), world frame."""
    d_cam = _camera_dirs(width, height, fov_deg) if dirs_camera is None else dirs_camera
    d = d_cam @ T_world_camera[:3, :3].T
    return np.broadcast_to(T_world_camera[:3, 3], d.shape), d


def _colors(rgba: np.ndarray, normals: np.ndarray, dirs: np.ndarray) -> np.ndarray:
    """(n, 3) uint8 label colours (``rgba`` (n, 4) in [0, 1]) shaded by the incidence angle."""
    shade = 0.35 + 0.65 * np.abs(np.einsum("ij,ij->i", normals, dirs))
    return np.clip(rgba[:, :3] * shade[:, None] * 255, 0, 255).astype(np.uint8)


def scan_scene(scene: Scene, params: ScanParams, seed: int = 0) -> Scan:
    """Scan ``scene`` (closed state) with ``params``; deterministic for ``seed``."""
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ScanError(f"scan of scene {scene.name!r}: seed must be a non-negative integer, got {seed!r}")
    rng = np.random.default_rng([int(seed), 7919])
    meshes = scene_meshes(scene, floor=params.include_background)
    caster = Raycaster(meshes)
    poses = camera_poses(scene, params, rng)
    mesh_obj = np.array([m.object_id for m in meshes], np.int32)
    mesh_part = np.array([m.part_id for m in meshes], np.int32)
    label_of = {p.id: p.label for o in scene.objects for p in o.parts}
    chunks = []
    d_cam = _camera_dirs(params.width, params.height, params.fov_deg)
    drift = _drifts(len(poses), params, rng)
    for k, T in enumerate(poses):
        o, d = pixel_rays(T, params.width, params.height, params.fov_deg, d_cam)
        hits = caster.cast(o, d)
        ok = (hits.mesh >= 0) & (hits.t <= params.max_range)
        o, d, t, mi, n = o[ok], d[ok], hits.t[ok], hits.mesh[ok], hits.normal[ok]
        n = np.where((np.einsum("ij,ij->i", n, d) > 0)[:, None], -n, n)   # face the camera
        keep = degrade.keep_returns(d, n, params.missing_rate, params.grazing_limit_deg, rng)
        o, d, t, mi, n = o[keep], d[keep], t[keep], mi[keep], n[keep]
        t_true = t
        t = degrade.add_depth_noise(t, params.depth_noise_base, params.depth_noise_quadratic, rng)
        p = o + t[:, None] * d
        if drift is not None:        # registered with the drifted pose T_world_camera @ drift[k]
            M = T @ drift[k] @ np.linalg.inv(T)
            p = p @ M[:3, :3].T + M[:3, 3]
        oid = mesh_obj[mi]
        # per-frame downsampling first keeps memory small; the merged cloud is downsampled again below
        fg, bg = np.flatnonzero(oid >= 0), np.flatnonzero(oid < 0)
        sel = np.concatenate([fg[degrade.voxel_keep(p[fg], params.voxel_size, rng)],
                              bg[degrade.voxel_keep(p[bg], params.background_voxel, rng)]])
        chunks.append((p[sel], n[sel], d[sel], oid[sel], mesh_part[mi][sel],
                       np.full(len(sel), k, np.int32), t_true[sel]))
    if not chunks or sum(len(c[0]) for c in chunks) == 0:
        raise ScanError(f"scan of scene {scene.name!r}: no camera ray hit anything")
    pts, nrm, dirs, oid, pid, frame, rng_true = (np.concatenate(a) for a in zip(*chunks))
    # downsample objects and background separately
    fg = np.flatnonzero(oid >= 0)
    bg = np.flatnonzero(oid < 0)
    keep = np.concatenate([fg[degrade.voxel_keep(pts[fg], params.voxel_size, rng)],
                           bg[degrade.voxel_keep(pts[bg], params.background_voxel, rng)]])
    keep.sort()
    pts, nrm, dirs, oid, pid = pts[keep], nrm[keep], dirs[keep], oid[keep], pid[keep]
    frame, rng_true = frame[keep], rng_true[keep]
    # flying pixels after downsampling, so that outlier_rate is their fraction of the written cloud
    shift, out = degrade.add_outliers(np.zeros(len(pts)), params.outlier_rate, params.outlier_range, rng,
                                      floor=-np.inf)
    pts = pts + shift[:, None] * dirs
    T_scan_world = _scan_frame(params, rng)
    pts, nrm = _tilted_objects(scene, pts, nrm, oid, params, T_scan_world[:3, :3], rng)
    keep = np.ones(len(pts), bool)
    for sel, spacing in ((oid >= 0, params.voxel_size), (oid < 0, params.background_voxel)):
        idx = np.flatnonzero(sel)
        keep[idx] = degrade.punch_holes(pts[idx], params.holes_per_m2, params.hole_radius, spacing, rng)
    pts, nrm, dirs, oid, pid = pts[keep], nrm[keep], dirs[keep], oid[keep], pid[keep]
    frame, rng_true, out = frame[keep], rng_true[keep], out[keep]
    pid = degrade.flip_boundary_labels(pts, oid, pid, params.label_boundary_width, params.label_flip_prob, rng)
    pid = degrade.label_fragments(pts, oid, pid, params.fragments_per_object, params.fragment_radius, rng)
    oid, pid = degrade.bleed_into_background(pts, oid, pid, params.background_bleed_width,
                                             params.background_bleed_prob, rng)
    pid, labels = _merged_fronts(scene, pts, nrm, oid, pid, params.merge_fronts_prob, rng)
    # colour lookup table indexed by part id + 1 (row 0 = background/wall)
    lut = np.tile(np.array(LABEL_RGBA["wall"], float), (max(label_of, default=0) + 2, 1))
    for part_id, label in label_of.items():
        lut[part_id + 1] = LABEL_RGBA.get(label, DEFAULT_RGBA)
    colors = _colors(lut[pid + 1], nrm, dirs)
    if not np.array_equal(T_scan_world, np.eye(4)):
        pts = pts @ T_scan_world[:3, :3].T + T_scan_world[:3, 3]
        nrm = nrm @ T_scan_world[:3, :3].T
    log.info("scanned %s: %d frames, %d points", scene.name, len(poses), len(pts))
    return Scan(pts, nrm, colors, oid.astype(np.int32), pid.astype(np.int32), labels,
                poses, out, frame, rng_true, T_scan_world)


def _drifts(n: int, params: ScanParams, rng: np.random.Generator) -> np.ndarray | None:
    """(n, 4, 4) each frame's camera pose error (camera frame): a random walk of ``drift_m`` m and
    ``drift_deg`` deg per frame; None without drift."""
    if params.drift_m <= 0 and params.drift_deg <= 0:
        return None
    t = np.cumsum(rng.normal(0.0, params.drift_m, (n, 3)), axis=0)
    r = np.cumsum(rng.normal(0.0, np.radians(params.drift_deg), (n, 3)), axis=0)
    out = np.tile(np.eye(4), (n, 1, 1))
    out[:, :3, :3] = Rotation.from_rotvec(r).as_matrix()
    out[:, :3, 3] = t
    return out


def _horizontal_axis(rng: np.random.Generator) -> np.ndarray:
    a = rng.uniform(0.0, 2.0 * np.pi)
    return np.array([np.cos(a), np.sin(a), 0.0])


def _scan_frame(params: ScanParams, rng: np.random.Generator) -> np.ndarray:
    """(4, 4) T_scan_world: tilted ``frame_tilt_deg`` about a random horizontal axis, the floor
    ``frame_floor_offset`` m from the origin along its normal (identity when both are 0)."""
    T = np.eye(4)
    if params.frame_tilt_deg[1] <= 0 and params.frame_floor_offset == (0.0, 0.0):
        return T
    angle = np.radians(rng.uniform(*params.frame_tilt_deg))
    T[:3, :3] = Rotation.from_rotvec(angle * _horizontal_axis(rng)).as_matrix()
    T[:3, 3] = rng.uniform(*params.frame_floor_offset) * T[:3, 2]
    return T


def _tilted_objects(scene: Scene, pts: np.ndarray, nrm: np.ndarray, oid: np.ndarray, params: ScanParams,
                    R_scan_world: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Each object's points and normals (world) tilted about its bottom centre so that, once in the
    scan's frame (rotated by ``R_scan_world`` (3, 3)), its up direction is U(``object_tilt_deg``) deg
    off the frame's z, about a random horizontal axis."""
    if params.object_tilt_deg[1] <= 0:
        return pts, nrm
    pts, nrm = pts.copy(), nrm.copy()
    for o in scene.objects:
        idx = np.flatnonzero(oid == o.id)
        if not len(idx):
            continue
        angle = np.radians(rng.uniform(*params.object_tilt_deg))
        up_scan = Rotation.from_rotvec(angle * _horizontal_axis(rng)).apply([0.0, 0.0, 1.0])
        rot, _ = Rotation.align_vectors([R_scan_world.T @ up_scan], [[0.0, 0.0, 1.0]])
        R = rot.as_matrix()
        lo, hi = o.bounds()
        c = o.T_world_object[:3, :3] @ ((lo + hi) / 2) + o.T_world_object[:3, 3]
        pivot = np.array([c[0], c[1], float(pts[idx, 2].min())])
        pts[idx] = degrade.tilt_about(pts[idx], R, pivot)
        nrm[idx] = nrm[idx] @ R.T
    return pts, nrm


def _merged_fronts(scene: Scene, pts: np.ndarray, nrm: np.ndarray, oid: np.ndarray, pid: np.ndarray, prob: float,
                   rng: np.random.Generator) -> tuple[np.ndarray, dict]:
    """(part ids, labels.json dict): with probability ``prob`` per column of two or more drawer fronts
    (same lateral place in their object, within 5 cm), the column's points carry the lowest drawer's id
    and labels.json lists that drawer only. Lateral: the object's horizontal axis across the one its drawers'
    points' normals ``nrm`` (n, 3, world) mostly lie along (the fronts face it), whichever way its author
    turned the object's frame."""
    labels = labels_from_scene(scene)
    if prob <= 0:
        return pid, labels
    pid = pid.copy()
    dropped: set[int] = set()
    for o in scene.objects:
        drawers = [p.id for p in o.parts if p.label == "drawer"]
        where = {}
        facing = np.abs(nrm[(oid == o.id) & np.isin(pid, drawers)] @ o.T_world_object[:3, :3]).sum(axis=0)
        lateral = 1 if facing[0] >= facing[1] else 0
        for d in drawers:
            m = (oid == o.id) & (pid == d)
            if m.sum() >= 3:
                q = (pts[m] - o.T_world_object[:3, 3]) @ o.T_world_object[:3, :3]
                where[d] = (float(np.median(q[:, lateral])), float(np.median(q[:, 2])))
        columns: dict[int, list[int]] = {}
        for d, (y, _) in sorted(where.items(), key=lambda kv: kv[1]):
            key = next((k for k in columns if abs(where[k][0] - y) < 0.05), d)
            columns.setdefault(key, []).append(d)
        for col in columns.values():
            if len(col) < 2 or rng.random() >= prob:
                continue
            low = min(col, key=lambda d: where[d][1])
            for d in col:
                if d != low:
                    pid[(oid == o.id) & (pid == d)] = low
                    dropped.add(d)
    for obj in labels["objects"]:
        obj["parts"] = [p for p in obj["parts"] if p["id"] not in dropped]
    return pid, labels
