"""``reconstruct``: the whole pipeline from a labelled scan to a :class:`Reconstruction`.

Stages per object: Eq. 3 fit of every part -> planes Π -> Eq. 1 contacts -> Eq. 4 tree -> Alg. 1
refinement; then, for the scene: support relations and upright/resting poses; then joints (they need
the final poses and the other objects' points for their limits); then object frames and relations.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable

import numpy as np

from recon.completion import (complete_missing_legs, complete_mounted_parts, complete_reaching_parts,
                              complete_vertical_parts)
from recon.config import ReconConfig
from recon.contacts import contact_edges
from recon.fitting import FitScore, fit_part
from recon.handle_shapes import mounted_handle_shapes, posed_handle_shapes
from recon.joints import estimate_joints
from recon.model import JointType, ObjectReconstruction, PartFit, Reconstruction, SceneGraph
from recon.part_shapes import carcass_shapes, drawer_shapes
from recon.part_tree import choose_root, part_tree
from recon.planes import part_planes
from recon.primitive import Primitive
from recon.refinement import refine_parts
from recon.scan import Scan, read_scan
from recon.walls import walls_from_background
from recon.scene_graph import (object_frame, proximal_relations, support_relations,
                               upright_correction)
from scenes.naming import joint_name, link_name, object_name

__all__ = ["reconstruct", "reconstruct_scan"]

log = logging.getLogger(__name__)

_NO_FIT = FitScore(0.0, 0.0, 0.0, 0.0, ())
"""Score of a part placed by completion rather than fitted (its PartFit has no candidate scores)."""

Progress = Callable[[str, int, int], None]
"""progress(message, done, total): called as objects are processed."""


def reconstruct(scan_path, labels_path, *, config: ReconConfig = ReconConfig(), level_floor: bool = False,
                seed: int = 0, progress: Progress | None = None) -> Reconstruction:
    """Reconstruct the scene of ``scan_path`` (.ply / .npz) labelled by ``labels_path`` (labels.json).

    level_floor : find the floor and the up direction first (scans in a camera frame).
    seed : every random choice (sampling, RANSAC) derives from it; same inputs + seed = same output.
    Raises :class:`recon.ScanError` on unusable input; per-part problems go to ``.warnings``.
    """
    return reconstruct_scan(read_scan(scan_path, labels_path, config), config=config,
                            level_floor=level_floor, seed=seed, progress=progress)


def _part_seed(seed: int, part_id: int) -> int:
    return (int(seed) * 1_000_003 + int(part_id) * 7919) % (2**31)


def reconstruct_scan(scan: Scan, *, config: ReconConfig = ReconConfig(), level_floor: bool = False,
                     seed: int = 0, progress: Progress | None = None) -> Reconstruction:
    """:func:`reconstruct` on an already read :class:`recon.scan.Scan`."""
    t_start = time.perf_counter()
    timings: dict[str, float] = {}
    warnings = list(scan.warnings)

    def warn(msg: str):
        log.warning(msg)
        warnings.append(msg)

    if level_floor:
        from recon.leveling import floor_transform

        T, tilt = floor_transform(scan, config, seed)
        scan = scan.transformed(T)
        log.info("levelled the scan: up direction was %.1f deg off", np.degrees(tilt))
        timings["level_floor"] = time.perf_counter() - t_start

    t0 = time.perf_counter()
    scan, removed = _without_outliers(scan, config)
    timings["outliers"] = time.perf_counter() - t0
    if removed:
        log.info("removed %d outlier points (flying pixels)", removed)
    n_obj = len(scan.objects)
    staged = []   # (obj, labels, fits, contacts, tree, prims)
    handle_shapes = {}   # {part_id: HandleShapes}: a handle's bar and posts, posed with its primitive at the end
    t0 = time.perf_counter()
    for k, obj in enumerate(scan.objects):
        if progress:
            progress(f"fitting {object_name(obj.category, obj.id)} ({len(obj.parts)} parts)", k, n_obj)
        labels = {p.part_id: p.label for p in obj.parts}
        fits = {}
        # the base part first (most points among the base labels): its axes guide the small parts
        base = choose_root(labels, {p.part_id: float(len(p.points)) for p in obj.parts})
        ordered = sorted(obj.parts, key=lambda p: p.part_id != base)
        R_ref = None
        for p in ordered:
            shape = _degeneracy(p.points, config.min_thickness)
            if shape:
                warn(f"object {obj.id} ({obj.category}) part {p.part_id} ({p.label}): its points are {shape}; "
                     f"the primitive is given the minimum thickness {config.min_thickness} m")
            small = len(p.points) < config.small_part_points
            name, prim, score, table = fit_part(p.points, config, seed=_part_seed(seed, p.part_id),
                                                normals=p.normals, R_world_ref=R_ref if small else None)
            if p.part_id == base:
                R_ref = prim.T_world_part[:3, :3].copy()
            fits[p.part_id] = (prim, score, table, len(p.points))
            log.debug("object %d part %d (%s): %s, score %.4f", obj.id, p.part_id, p.label, name, score.total)
        prims = {i: f[0] for i, f in fits.items()}
        pts_by_part = {p.part_id: p.points for p in obj.parts}
        prims, placed = complete_missing_legs(obj.category, prims, labels, obj.skipped, config, base)
        for i, centre in placed.items():
            leg = next(p for p in obj.skipped if p.part_id == i)
            labels[i] = leg.label
            fits[i] = (prims[i], _NO_FIT, {}, len(leg.points))
            pts_by_part[i] = leg.points if len(leg.points) >= 3 else prims[i].sample_surface(
                config.surface_samples, np.random.default_rng(_part_seed(seed, i)))[0]
            warn(f"{link_name(obj.category, obj.id, leg.label, i)}: part {i} ({leg.label}) has "
                 f"{len(leg.points)} points; placed at the free corner of its fitted legs' rectangle "
                 f"({centre[0]:.3f}, {centre[1]:.3f})")
        prims, reached = complete_reaching_parts(prims, labels, config)
        for i, gap in reached.items():
            log.info("object %d part %d (%s): extended %.3f m to the part it reaches", obj.id, i, labels[i], gap)
        prims, completed = complete_vertical_parts(prims, labels, config)
        for i, (down, up) in completed.items():
            log.info("object %d part %d (%s): extended %.3f m down, %.3f m up to its supports",
                     obj.id, i, labels[i], down, up)
        prims, mounted = complete_mounted_parts(prims, labels, config)
        for i, gap in mounted.items():
            log.info("object %d part %d (%s): extended %.3f m back onto its mount", obj.id, i, labels[i], gap)
        planes = {i: part_planes(prims[i], pts_by_part[i], config, _part_seed(seed, i)) for i in prims}
        contacts = contact_edges(planes, config)
        tree = part_tree(obj.category, labels, {i: prims[i].volume for i in prims}, contacts, config,
                         distances=_part_distances(prims))
        for i in tree.isolated:
            warn(f"{link_name(obj.category, obj.id, labels[i], i)}: part {i} ({labels[i]}) touches no "
                 f"other part of object {obj.id}; fixed to the nearest possible parent, part {tree.parent[i]} "
                 f"({labels[tree.parent[i]]})")
        if config.refine:
            prims = refine_parts(prims, tree, config)
        # the bar where its points are, its posts reaching back to the (refined) mount face
        prims, handles = mounted_handle_shapes(prims, labels, pts_by_part, config, object_name(obj.category, obj.id),
                                               tree.parent)
        handle_shapes.update(handles)
        staged.append((obj, labels, fits, contacts, tree, prims))
    timings["parts"] = time.perf_counter() - t0

    # scene: support and upright poses (floor-supported objects first, then what stands on them)
    t0 = time.perf_counter()
    by_id = {s[0].id: s for s in staged}
    for s in staged:
        obj, _, _, _, tree, prims = s
        R = upright_correction(prims[tree.root], config)
        if not np.allclose(R, np.eye(3)):
            c = np.concatenate([p.corners() for p in prims.values()])
            pivot = np.array([*c[:, :2].mean(axis=0), c[:, 2].min()])
            M = np.eye(4)
            M[:3, :3], M[:3, 3] = R, pivot - R @ pivot
            for i in prims:
                prims[i] = prims[i].transformed(M)
    support = support_relations({i: list(s[5].values()) for i, s in by_id.items()}, config)
    order = sorted(by_id, key=lambda i: (support[i][0] is not None, i))
    for i in order:
        sup, _ = support[i]
        prims = by_id[i][5]
        top = 0.0 if sup is None else max(float(p.corners()[:, 2].max()) for p in by_id[sup][5].values())
        bottom = min(float(p.corners()[:, 2].min()) for p in prims.values())
        if bottom > config.support_distance and sup is None:
            warn(f"{object_name(by_id[i][0].category, i)}: floats {bottom:.3f} m above the floor with "
                 "nothing under it; left where it was scanned")
            continue
        if bottom < top:
            # sunk into its support: noise below the floor / a top surface; cut the parts there
            # instead of lifting the whole object (which would move its fitted drawers and doors)
            for k in prims:
                prims[k] = _clipped_below(prims[k], top)
            bottom = min(float(p.corners()[:, 2].min()) for p in prims.values())
        if abs(top - bottom) > 1e-9:
            M = np.eye(4)
            M[2, 3] = top - bottom
            for k in prims:
                prims[k] = prims[k].transformed(M)
    timings["support"] = time.perf_counter() - t0

    # joints (limits sweep against every other scan point)
    t0 = time.perf_counter()
    all_pts = scan.points
    all_part = scan.part_id
    # other objects are solid: their fitted primitives' surfaces join the scan points as obstacles
    # (a scan only has the faces the camera saw; a door must not swing into a neighbour's hidden side)
    rng = np.random.default_rng(seed)
    shells = {s[0].id: np.concatenate([_surface_samples(p, config.obstacle_spacing, rng) for p in s[5].values()])
              for s in staged}

    def obstacles_for_object(oid):
        others = [v for k, v in shells.items() if k != oid]

        def obstacles_for(part_ids):
            pts = all_pts[~np.isin(all_part, list(part_ids))]
            return np.concatenate([pts] + others) if others else pts
        return obstacles_for

    objects = []
    for k, (obj, labels, fits, contacts, tree, prims) in enumerate(staged):
        if progress:
            progress(f"joints of {object_name(obj.category, obj.id)}", k, n_obj)
        names = {i: joint_name(obj.category, obj.id, labels[i], i) for i in labels}
        joints = estimate_joints(obj.category, names, labels, prims, tree, obstacles_for_object(obj.id),
                                 config, warn)
        shapes = template_shapes(joints, prims, labels, config) if config.template_shapes else {}
        shapes.update(posed_handle_shapes(handle_shapes, prims))
        parts = tuple(
            PartFit(i, labels[i], link_name(obj.category, obj.id, labels[i], i), prims[i],
                    float(fits[i][1].total), dict(fits[i][2]), int(fits[i][3]),
                    prims[i].planes(config.cylinder_side_faces), shapes.get(i, ()))
            for i in labels)
        front = _front(joints, prims)
        T_wo, size = object_frame([prims[tree.root]] + [p for i, p in prims.items() if i != tree.root], front)
        objects.append(ObjectReconstruction(
            obj.id, obj.category, object_name(obj.category, obj.id), tree.root, parts, contacts, joints,
            tree.isolated, T_wo, size, support[obj.id][0]))
    timings["joints"] = time.perf_counter() - t0
    prox = proximal_relations({o.id: list(o.primitives().values()) for o in objects}, config)
    graph = SceneGraph(tuple((o.id, o.supported_by) for o in objects), prox)
    walls = ()
    if config.walls:
        t0 = time.perf_counter()
        labelled = scan.object_id >= 0
        centre = scan.points[labelled].mean(axis=0) if labelled.any() else scan.points.mean(axis=0)
        walls = walls_from_background(scan.points[~labelled], centre, config, seed)
        timings["walls"] = time.perf_counter() - t0
    timings["total"] = time.perf_counter() - t_start
    if progress:
        progress("done", n_obj, n_obj)
    return Reconstruction(tuple(objects), graph, tuple(warnings), config, int(seed), timings, walls)


def _without_outliers(scan: Scan, config: ReconConfig) -> tuple[Scan, int]:
    """The scan without statistical outliers, judged part by part (and the background as one cloud)."""
    from dataclasses import replace

    from recon.outliers import statistical_inliers

    keep = np.ones(len(scan.points), dtype=bool)
    for pid in np.unique(scan.part_id[scan.part_id >= 0]):
        idx = np.flatnonzero(scan.part_id == pid)
        keep[idx] = statistical_inliers(scan.points[idx], neighbors=config.outlier_neighbors,
                                        std_ratio=config.outlier_std_ratio)
    objects = []
    for o in scan.objects:
        parts = []
        for p in o.parts:
            m = keep[scan.part_id == p.part_id]
            if len(m) != len(p.points):    # points of this part carried another object id
                m = statistical_inliers(p.points, neighbors=config.outlier_neighbors,
                                        std_ratio=config.outlier_std_ratio)
            parts.append(replace(p, points=p.points[m], normals=None if p.normals is None else p.normals[m]))
        objects.append(replace(o, parts=tuple(parts)))
    cleaned = replace(scan, points=scan.points[keep], object_id=scan.object_id[keep], part_id=scan.part_id[keep],
                      normals=None if scan.normals is None else scan.normals[keep],
                      colors=None if scan.colors is None else scan.colors[keep], objects=tuple(objects))
    return cleaned, int((~keep).sum())


def _degeneracy(points: np.ndarray, min_thickness: float) -> str:
    """"" for a solid cloud, else "flat (...)" or "collinear (...)" from its principal extents."""
    c = points - points.mean(axis=0)
    ext = np.sort(np.ptp(c @ np.linalg.svd(c, full_matrices=False)[2].T, axis=0))
    if ext[1] < min_thickness:
        return f"collinear (spread {ext[1] * 1000:.1f} mm across a {ext[2]:.2f} m line)"
    if ext[0] < 1e-4:
        return f"flat (spread {ext[0] * 1000:.2f} mm off a plane)"
    return ""


def _clipped_below(prim: Primitive, z: float) -> Primitive:
    """``prim`` with the part below height ``z`` cut off, when it stands upright (an axis within ~3°
    of vertical) and reaches below ``z``; otherwise unchanged."""
    R = prim.T_world_part[:3, :3]
    k = int(np.argmax(np.abs(R[2, :])))
    c = prim.corners()
    lo, hi = float(c[:, 2].min()), float(c[:, 2].max())
    if lo >= z or hi <= z or abs(R[2, k]) < 0.998 or prim.kind.value == "sphere":
        return prim
    if prim.kind.value == "cylinder" and k != 2:
        return prim
    size = prim.size.copy()
    size[k] = (hi - z) / abs(R[2, k])
    T = prim.T_world_part.copy()
    T[2, 3] += (z - lo) / 2
    return Primitive(prim.kind, size, T)


def _surface_samples(prim: Primitive, spacing: float, rng: np.random.Generator) -> np.ndarray:
    """About one point per ``spacing``^2 of the primitive's surface, (n, 3) world."""
    area = 2 * (prim.size[0] * prim.size[1] + prim.size[1] * prim.size[2] + prim.size[0] * prim.size[2])
    n = int(np.clip(area / spacing**2, 50, 20000))
    return prim.sample_surface(n, rng)[0]


def _part_distances(prims: dict[int, Primitive]) -> dict[tuple[int, int], float]:
    """{(a, b): distance (m) from part b's corners and centre to part a's surface, min over them}."""
    out = {}
    for a, pa in prims.items():
        for b, pb in prims.items():
            if a != b:
                q = np.vstack([pb.corners(), pb.center[None]])
                out[(a, b)] = float(pa.surface_distance(q).min())
    return out


def template_shapes(joints, prims: dict[int, Primitive], labels: dict[int, str],
                    config: ReconConfig) -> dict[int, tuple[Primitive, ...]]:
    """{part_id: template shapes} of an object's drawers (front + box) and of the parents of its
    drawers/doors (a carcass open at their fronts); other parts keep their primitive (part_shapes.py)."""
    opens: dict[int, list[tuple[np.ndarray, Primitive]]] = {}
    out: dict[int, tuple[Primitive, ...]] = {}
    for j in joints:
        if j.type is JointType.FIXED or j.parent_part_id is None:
            continue
        if j.type is JointType.PRISMATIC:
            normal = j.axis
            if labels[j.child_part_id] == "drawer":
                out[j.child_part_id] = drawer_shapes(prims[j.child_part_id], j.axis, prims[j.parent_part_id], config)
        else:
            n = np.cross(j.axis, prims[j.child_part_id].center - j.origin)
            if np.linalg.norm(n) < 1e-9:
                continue
            normal = n / np.linalg.norm(n)
        opens.setdefault(j.parent_part_id, []).append((normal, prims[j.child_part_id]))
    for i, fronts in opens.items():
        if labels[i] in ("body", "frame", "base"):
            out[i] = carcass_shapes(prims[i], fronts, config)
    return {i: s for i, s in out.items() if len(s) > 1}


def _front(joints, prims: dict[int, Primitive]) -> np.ndarray | None:
    """The object's front: a drawer's axis, else the outward normal of a door, else None."""
    for j in joints:
        if j.type is JointType.PRISMATIC:
            return j.axis
    for j in joints:
        if j.type is JointType.REVOLUTE:
            n = np.cross(j.axis, prims[j.child_part_id].center - j.origin)
            if np.linalg.norm(n) > 1e-9:
                return n / np.linalg.norm(n)
    return None
