"""``reconstruct``: the whole pipeline from a labelled scan to a :class:`Reconstruction`, as named stages.

Stages, in order (each a function below; per-object state travels in an :class:`ObjectState`)::

    floor_frame        the floor found in the background (height, tilt); a scan that is upside down, not
                       z-up or not in metres refused; the scan moved into the floor frame (floor z = 0,
                       z up) for every stage below (leveling.py, frame_checks.py)
    remove_outliers    statistical outliers dropped part by part (outliers.py)
    remove_label_fragments  a handle's (leg's) points apart from its largest cluster dropped (label_fragments.py)
    split_labelled_fronts  a drawer/door part showing horizontal gaps split, one part per front (front_split.py)
    fit_primitives     Eq. 3: the best primitive per part, the base part first; a fit that does not cover
                       its points is refitted with the other kinds (fitting.py, coverage.py); a base box
                       tilted off the up direction or turned off the yaw its object's faces show is refitted
                       along them (object_up.py, object_yaw.py); a leg's section from its faces' points
                       (post_section.py)
    complete_parts     a bed frame extended to its mattress and headboard; hidden legs placed; legs and
                       mounted parts extended (completion.py)
    contact_graph      surface planes Π, then the Eq. 1 contacts between parts (planes.py, contacts.py)
    build_part_tree    Eq. 4: the maximum spanning arborescence of the contacts (part_tree.py)
    refine             Alg. 1: children rotated / moved onto their parents' planes (refinement.py)
    shape_handles      a handle's bar and posts (knob: cap and stem) off its mount (handle_shapes.py)
    check_coverage     each part's primitive against its points; a part outside the bounds is named
                       in a warning (coverage.py)
    place_on_supports  upright correction, then every object resting on the floor or its supporter (its
                       base extended down to it when the base is its lowest part, else the object moved)
    estimate_object_joints  joint type, axis, origin and swept limits (joints.py), template shapes,
                       object frame -> ObjectReconstruction
    scene graph        support and proximal relations; walls from the background (walls.py)
    output_frame       everything moved back into the scan's frame, standing on its floor (without
                       ``level_floor``; with it the output stays levelled: floor z = 0, z up)

Every length is in metres. The stages between ``floor_frame`` and ``output_frame`` work in the floor
frame (the floor z = 0, z up); the output is in the scan's frame, or levelled with ``level_floor``.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.spatial import cKDTree

from recon.body_fronts import body_within_fronts
from recon.clearance import cleared_scene
from recon.completion import (VERTICAL_SPAN_LABELS, complete_missing_legs, complete_mounted_parts,
                              complete_reaching_parts, complete_vertical_parts)
from recon.config import ReconConfig
from recon.contacts import contact_edges
from recon.coverage import coverage, coverage_problems
from recon.estimated_normals import with_estimated_normals
from recon.fitting import FitScore, body_behind_face, fit_part, fit_part_covering, score_primitive
from recon.front_split import split_fronts
from recon.handle_shapes import HandleShapes, mounted_handle_shapes, posed_handle_shapes
from recon.joint_uncertainty import with_joint_uncertainty
from recon.joints import estimate_joints
from recon.label_fragments import without_label_fragments
from recon.leveling import Floor, find_floor
from recon.model import ContactEdge, JointEstimate, ObjectReconstruction, PartFit, Reconstruction, SceneGraph
from recon.object_up import measured_up, tilt_to, turned_upright, vertical_axis
from recon.object_yaw import face_yaws, measured_yaw, on_face_planes, turned_about, yaw_difference, yaw_of
from recon.outliers import scan_without_outliers
from recon.part_shapes import template_shapes
from recon.part_tree import PartTree, choose_root, part_distances, part_tree
from recon.planes import part_planes
from recon.post_section import post_primitive
from recon.primitive import Primitive, PrimitiveKind
from recon.refinement import refine_parts
from recon.scan import ObjectPoints, PartPoints, Scan, read_scan
from recon.scene_graph import (object_frame, object_front, proximal_relations, resting_on,
                               support_relations, upright_correction)
from recon.templates import MOVABLE_LABELS
from recon.walls import walls_from_background
from scenes.description import joint_name, link_name, object_name

__all__ = ["reconstruct", "reconstruct_scan", "ObjectState", "FittedPart"]

log = logging.getLogger(__name__)

_NO_FIT = FitScore(0.0, 0.0, 0.0, 0.0, ())
"""Score of a part placed by completion rather than fitted (its PartFit has no candidate scores)."""

Progress = Callable[[str, int, int], None]
"""progress(message, done, total): called as objects are processed."""


@dataclass(frozen=True, eq=False)
class FittedPart:
    """What Eq. 3 chose for one part: the primitive as fitted (world frame, before completion and
    refinement), its score, every candidate's score {name: metres} and the part's number of points."""

    primitive: Primitive
    score: FitScore
    candidate_scores: dict
    n_points: int


@dataclass(eq=False)
class ObjectState:
    """One object between stages; each stage fills or replaces its fields.

    source : the object's scan points (:class:`recon.scan.ObjectPoints`)
    labels : {part_id: label}; points : {part_id: (n, 3) world points} (a placed hidden part gets
        its own few points, or samples of its primitive's surface)
    base : part id of the base part (most points among the base labels), fitted first
    fits : {part_id: FittedPart}
    prims : {part_id: Primitive}, world frame: the current primitive of each part
    contacts : every Eq. 1 contact edge; tree : the Eq. 4 part tree
    handles : {part_id: HandleShapes} of the handles given a bar / knob
    T_moved : (4, 4) the rigid motion (world) the parts made after they were fitted to their points (set upright
        and resting on their support: :func:`place_on_supports`); the scan points moved by it lie on the parts
    """

    source: ObjectPoints
    labels: dict[int, str]
    points: dict[int, np.ndarray]
    base: int
    fits: dict[int, FittedPart] = field(default_factory=dict)
    prims: dict[int, Primitive] = field(default_factory=dict)
    contacts: tuple[ContactEdge, ...] = ()
    tree: PartTree | None = None
    handles: dict[int, HandleShapes] = field(default_factory=dict)
    T_moved: np.ndarray = field(default_factory=lambda: np.eye(4))

    def moved_parts(self) -> tuple:
        """The object's parts' scan points and normals moved by ``T_moved`` (:class:`recon.scan.PartPoints`)."""
        if np.allclose(self.T_moved, np.eye(4)):
            return self.source.parts
        R, t = self.T_moved[:3, :3], self.T_moved[:3, 3]
        return tuple(replace(p, points=p.points @ R.T + t, normals=None if p.normals is None else p.normals @ R.T)
                     for p in self.source.parts)

    @property
    def id(self) -> int:
        return self.source.id

    @property
    def category(self) -> str:
        return self.source.category

    @property
    def name(self) -> str:
        return object_name(self.category, self.id)


@dataclass(eq=False)
class _Run:
    """What every stage may report into: the config, the seed, warnings and stage timings (s)."""

    config: ReconConfig
    seed: int
    warnings: list[str]
    timings: dict[str, float] = field(default_factory=dict)

    def warn(self, msg: str) -> None:
        log.warning(msg)
        self.warnings.append(msg)


def reconstruct(scan_path, labels_path, *, config: ReconConfig = ReconConfig(), level_floor: bool = False,
                seed: int = 0, progress: Progress | None = None) -> Reconstruction:
    """Reconstruct the scene of ``scan_path`` (.ply / .npz) labelled by ``labels_path`` (labels.json).

    level_floor : write the output levelled on the scan's floor (floor z = 0, z up; the scan may then
        also be upside down or not z-up) instead of in the scan's frame.
    seed : every random choice (sampling, RANSAC) derives from it; same inputs + seed = same output.
    Raises :class:`recon.ScanError` on unusable input; per-part problems go to ``.warnings``.
    """
    return reconstruct_scan(read_scan(scan_path, labels_path, config.scan), config=config,
                            level_floor=level_floor, seed=seed, progress=progress)


def reconstruct_scan(scan: Scan, *, config: ReconConfig = ReconConfig(), level_floor: bool = False,
                     seed: int = 0, progress: Progress | None = None) -> Reconstruction:
    """:func:`reconstruct` on an already read :class:`recon.scan.Scan`."""
    t_start = time.perf_counter()
    run = _Run(config, int(seed), list(scan.warnings))
    scan, floor, T_floor_scan = floor_frame(scan, run, level_floor)
    run.timings["floor"] = time.perf_counter() - t_start
    t0 = time.perf_counter()
    scan = remove_outliers(scan, run)
    scan = remove_label_fragments(scan, run)
    run.timings["outliers"] = time.perf_counter() - t0
    scan = with_estimated_normals(scan, run.config.scan.normal_neighbours)
    scan = split_labelled_fronts(scan, run)

    n_obj = len(scan.objects)
    states = []
    t0 = time.perf_counter()
    for k, obj in enumerate(scan.objects):
        if progress:
            progress(f"fitting {object_name(obj.category, obj.id)} ({len(obj.parts)} parts)", k, n_obj)
        state = fit_primitives(obj, run)
        complete_parts(state, run)
        contact_graph(state, run)
        build_part_tree(state, run)
        refine(state, run)
        shape_handles(state, run)
        check_coverage(state, run)
        states.append(state)
    run.timings["parts"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    support = place_on_supports(states, run)
    run.timings["support"] = time.perf_counter() - t0
    # the parts are at their final poses from here on: a step that changes them goes here

    t0 = time.perf_counter()
    obstacles = _Obstacles(scan, states, run)
    objects = []
    for k, state in enumerate(states):
        if progress:
            progress(f"joints of {state.name}", k, n_obj)
        objects.append(estimate_object_joints(state, obstacles, support[state.id][0], run))
    run.timings["joints"] = time.perf_counter() - t0

    graph = SceneGraph(tuple((o.id, o.supported_by) for o in objects),
                       proximal_relations({o.id: list(o.primitives().values()) for o in objects}, config.scene))
    walls = ()
    if config.walls.walls:
        t0 = time.perf_counter()
        walls = room_walls(scan, run)
        run.timings["walls"] = time.perf_counter() - t0
    objects, walls = cleared_scene(objects, walls, config.clearance, run.warn)
    objects, walls, floor = output_frame(objects, walls, floor, T_floor_scan, level_floor, run)
    run.timings["total"] = time.perf_counter() - t_start
    if progress:
        progress("done", n_obj, n_obj)
    T_world_scan = T_floor_scan if level_floor else np.eye(4)
    return Reconstruction(tuple(objects), graph, tuple(run.warnings), config, run.seed, run.timings, walls,
                          floor, T_world_scan)


# --- scan stages ---------------------------------------------------------------------------------------

def floor_frame(scan: Scan, run: _Run, level_floor: bool) -> tuple[Scan, Floor, np.ndarray]:
    """(the scan in the floor frame, its floor in the scan's frame, T_floor_scan (4, 4)).

    Raises ScanError (:mod:`recon.frame_checks`) for a scan upside down or not z-up (unless
    ``level_floor``) or not in metres. Without floor points the frame is kept (T = identity, z = 0
    taken as the floor) with a warning."""
    from recon.errors import ScanError
    from recon.frame_checks import frame_problem, scale_problems

    cfg = run.config.leveling
    floor = find_floor(scan, cfg, run.config.scene, run.seed)
    if floor.found and floor.tilt_deg < cfg.min_floor_tilt_deg:
        log.info("floor tilted %.3f deg: taken as level", floor.tilt_deg)
        floor = floor.levelled()
    if floor.found:
        problem = frame_problem(floor, cfg, scan.source)
        if problem and not level_floor:
            raise ScanError(problem)
        log.info("floor: %d points, %.3f m off the scan's origin, tilted %.2f deg%s", floor.n_points,
                 floor.height_m, floor.tilt_deg, "; levelled" if level_floor else "")
    else:
        run.warn(f"{scan.source}: no floor in the scan (no background plane of {cfg.floor_min_points}+ points "
                 "that an object touches): the scan's frame is kept and its z = 0 taken as the floor"
                 + ("; --level-floor has nothing to level on" if level_floor else ""))
    T = floor.T_floor_frame()
    levelled = scan.transformed(T) if floor.found else scan
    problem = scale_problems(levelled, scan.source)
    if problem:
        raise ScanError(problem)
    return levelled, floor, T


def output_frame(objects: list[ObjectReconstruction], walls: tuple, floor: Floor, T_floor_scan: np.ndarray,
                 level_floor: bool, run: _Run) -> tuple[list[ObjectReconstruction], tuple, Floor]:
    """The objects and walls (floor frame) moved back into the scan's frame, and the floor in the
    output's frame; with ``level_floor`` (and a floor found) they stay levelled: the floor z = 0."""
    cfg = run.config.leveling
    if level_floor and floor.found:
        return objects, walls, floor.transformed(T_floor_scan)
    T = np.linalg.inv(T_floor_scan)
    if floor.found and (abs(floor.height_m) > cfg.floor_offset_warning or floor.tilt_deg > 0.0):
        run.warn(f"the scan's floor is {floor.height_m:+.3f} m off its origin and tilted {floor.tilt_deg:.1f} deg: "
                 "the output stays in the scan's frame, objects on that floor (graph.json \"floor\": planners and "
                 "simcheck stand the robot on it; other simulators put the ground at z = 0): pass --level-floor to "
                 "write the scene levelled on its floor")
    return [o.transformed(T) for o in objects], tuple(w.transformed(T) for w in walls), floor


def remove_outliers(scan: Scan, run: _Run) -> Scan:
    """The scan without statistical outliers (flying pixels), judged part by part."""
    scan, removed = scan_without_outliers(scan, neighbors=run.config.scan.outlier_neighbors,
                                          std_ratio=run.config.scan.outlier_std_ratio)
    if removed:
        log.info("removed %d outlier points (flying pixels)", removed)
    return scan


def remove_label_fragments(scan: Scan, run: _Run) -> Scan:
    """Every handle/knob/leg part reduced to its cluster: the points a segmentation gave its label apart
    from the part are dropped from it (label_fragments.py)."""
    scan, removed = without_label_fragments(scan, run.config.scan)
    if removed:
        log.info("removed %d handle points lying apart from their handles (label fragments)", removed)
    return scan


def split_labelled_fronts(scan: Scan, run: _Run) -> Scan:
    """Each drawer/door part whose points show horizontal gaps split into one part per front, with a
    warning (front_split.py)."""
    scan, warnings = split_fronts(scan, run.config.scan)
    for w in warnings:
        run.warn(w)
    return scan


# --- object stages -------------------------------------------------------------------------------------

def _part_seed(seed: int, part_id: int) -> int:
    return (int(seed) * 1_000_003 + int(part_id) * 7919) % (2**31)


def fit_primitives(obj: ObjectPoints, run: _Run) -> ObjectState:
    """Eq. 3 for every part of ``obj``: the base part and the other large parts first, then the small
    parts (fewer than ``small_part_points`` points), oriented by the base part's axes. A fit outside the
    coverage bounds is refitted with the other kinds of candidates
    (:func:`recon.fitting.fit_part_covering`); one still outside them is named in a warning by
    :func:`check_coverage`. A base box turned off the up direction or the yaw its object's faces show is
    refitted along them (:func:`_base_along_measured_frame`). A body's face reaching past the drawer/door
    fronts closing it, or standing apart behind them, is moved onto them
    (:func:`recon.body_fronts.body_within_fronts`: label bleed and depth noise at a face covered by fronts).
    A body whose points show one face only is given a depth behind it (:func:`recon.fitting.body_behind_face`),
    with a warning. A leg's section is measured from its faces' points (:func:`recon.post_section.post_primitive`),
    not judged by Eq. 3: depth noise as wide as the leg makes its points a blob whose spread Eq. 3 fits. A
    drawer's or door's seen face is read from its points' normals (``front`` of :func:`recon.fitting.fit_part`)."""
    config = run.config.fitting
    labels = {p.part_id: p.label for p in obj.parts}
    base = choose_root(labels, {p.part_id: float(len(p.points)) for p in obj.parts})
    state = ObjectState(obj, labels, {p.part_id: p.points for p in obj.parts}, base)
    fitted: dict[int, tuple] = {}          # {part_id: (name, primitive, score, table)}
    box_only = replace(config, candidates=tuple(c for c in config.candidates if c == "box"))   # box_labels' parts

    def fit(p: PartPoints, R_ref: np.ndarray | None) -> None:
        shape = _degeneracy(p.points, config.min_thickness)
        if shape:
            run.warn(f"object {obj.id} ({obj.category}) part {p.part_id} ({p.label}): its points are {shape}; "
                     f"the primitive is given the minimum thickness {config.min_thickness} m")
        kinds = box_only if p.label in config.box_labels else config
        fit = fit_part_covering(p.points, kinds, run.config.coverage, seed=_part_seed(run.seed, p.part_id),
                                normals=p.normals, R_world_ref=R_ref, front=p.label in MOVABLE_LABELS)
        if fit.refused:
            log.info("%s part %d (%s): the fitted %s did not cover its points; refitted as a %s%s", obj.id,
                     p.part_id, p.label, " then ".join(fit.refused), fit.primitive.kind.value,
                     f" (still: {'; '.join(fit.problems)})" if fit.problems else "")
        fitted[p.part_id] = (fit.name, fit.primitive, fit.score, fit.table)

    small = {p.part_id for p in obj.parts if p.part_id != base and len(p.points) < config.small_part_points}
    for p in sorted(obj.parts, key=lambda p: p.part_id != base):
        if p.part_id not in small:
            fit(p, None)
    base_part = next(p for p in obj.parts if p.part_id == base)
    turned = _base_along_measured_frame(obj, base_part, fitted, run)
    if turned is not None:
        fitted[base] = turned
    completed = {}            # {part_id: primitive} completed beyond what its points show (the fit is kept)
    R_ref = fitted[base][1].T_world_part[:3, :3].copy()
    for p in obj.parts:
        if p.part_id in small:
            fit(p, R_ref)
    if base_part.label == "body":
        name, prim, _, table = fitted[base]
        cut = body_within_fronts(prim, [fitted[p.part_id][1] for p in obj.parts if p.label in MOVABLE_LABELS],
                                 config.panel_ratio)
        if cut is not prim:
            log.info("object %d part %d (body): its faces moved onto the fronts closing them (extents %s -> %s m)",
                     obj.id, base, np.round(prim.size, 3), np.round(cut.size, 3))
            rng = np.random.default_rng(_part_seed(run.seed, base))
            fitted[base] = (name, cut, score_primitive(cut, base_part.points, cKDTree(base_part.points), config, rng),
                            table)
        deep = body_behind_face(fitted[base][1], base_part.normals, config)
        if deep is not None:
            run.warn(f"{link_name(obj.category, obj.id, base_part.label, base)}: its points show one face only; "
                     f"the body is given the depth of its narrower side, {deep.size.min():.2f} m, behind it")
            completed[base] = deep
    for p in obj.parts:
        if p.label in VERTICAL_SPAN_LABELS and p.part_id != base:
            post = post_primitive(p.points, p.normals, R_ref, fitted[p.part_id][1], config)
            if post is not None:
                rng = np.random.default_rng(_part_seed(run.seed, p.part_id))
                fitted[p.part_id] = ("post", post, score_primitive(post, p.points, cKDTree(p.points), config, rng),
                                     fitted[p.part_id][3])
    for p in sorted(obj.parts, key=lambda p: p.part_id != base):
        name, prim, score, table = fitted[p.part_id]
        state.fits[p.part_id] = FittedPart(prim, score, table, len(p.points))
        log.debug("object %d part %d (%s): %s, score %.4f", obj.id, p.part_id, p.label, name, score.total)
    state.prims = {i: completed.get(i, f.primitive) for i, f in state.fits.items()}
    return state


_FRAME_PART_POINTS = 16
"""Parts with fewer points do not vote on their object's up direction and yaw."""


def _base_along_measured_frame(obj: ObjectPoints, base: PartPoints, fitted: dict[int, tuple], run: _Run):
    """The base part's box along the up direction the normals of its object's points show
    (:func:`recon.object_up.measured_up`) and the yaw the planes of its object's large parts' vertical faces
    show (:func:`recon.object_yaw.measured_yaw`), its vertical faces on the planes its own points show
    (:func:`recon.object_yaw.on_face_planes`).

    A box tilted off that up by more than ``base_tilt_tolerance`` (and less than ``max_upright_tilt``,
    beyond which a tilt is taken as intended) is refitted as a box, without ICP, along the up and yaw; a
    box only turned off that yaw by more than ``base_yaw_tolerance`` and 2 standard errors of the measured
    yaw is turned about its centre (its extents are what Eq. 3 fitted). ``fitted`` {part_id: (name,
    primitive, score, table)} holds the base and the object's other large parts. Returns (name, primitive,
    score, table) as :func:`recon.fitting.fit_part` does, or None to keep the fit."""
    config = run.config.fitting
    name, prim, score, table = fitted[base.part_id]
    if prim.kind is not PrimitiveKind.BOX:
        return None
    # every part of 3+ points has normals here: the scan's, else estimated (with_estimated_normals)
    normals = {p.part_id: p.normals for p in obj.parts if len(p.points) >= _FRAME_PART_POINTS}
    up = measured_up(np.concatenate(list(normals.values())), config.normals_frame_cone,
                     config.min_face_points) if normals else None
    parts = [p for p in obj.parts if p.part_id in fitted and p.part_id in normals]
    tilt = 0.0 if up is None else tilt_to(prim, up)
    if tilt > run.config.scene.max_upright_tilt:
        return None
    up = vertical_axis(prim)[1] if up is None else up
    R_up = turned_upright(prim, up)
    faces = [f for p in parts
             for f in face_yaws(fitted[p.part_id][1], p.points, normals[p.part_id], up, config, p.part_id)]
    yaw = measured_yaw(faces, config.yaw_consensus, base.part_id)
    turn = 0.0
    if yaw is not None:
        across = R_up[:, int(np.argmin(np.abs(R_up.T @ up)))]             # a horizontal axis of the box
        turn = yaw_difference(yaw[0], yaw_of(across, up))
        if abs(turn) <= max(config.base_yaw_tolerance, 2.0 * yaw[1]):
            turn = 0.0
    if tilt > config.base_tilt_tolerance:
        log.info("object %d part %d (%s): fitted %.2f deg off the up direction and %.2f deg off the yaw of its "
                 "object's faces; refitted along them", obj.id, base.part_id, base.label, np.degrees(tilt),
                 np.degrees(-turn))
        name, prim, score, table = fit_part(base.points, replace(config, candidates=("box",)),
                                            seed=_part_seed(run.seed, base.part_id), normals=base.normals,
                                            R_world_ref=turned_about(R_up, up, turn), align=False)
    elif turn != 0.0:
        log.info("object %d part %d (%s): fitted %.2f deg off the yaw of its object's faces; turned onto it",
                 obj.id, base.part_id, base.label, np.degrees(-turn))
        T = prim.T_world_part.copy()
        T[:3, :3] = turned_about(R_up, up, turn)
        prim = Primitive(PrimitiveKind.BOX, prim.size, T)
    # a plane does not depend on the frame its points were picked along (a turn of a degree or two)
    others = [p.points for p in obj.parts if p.part_id != base.part_id]
    placed = on_face_planes(prim, [f for f in faces if f.part_id == base.part_id], up, config.yaw_consensus,
                            config.seen_face_band, config.min_thickness,
                            np.concatenate(others) if others else None)
    if placed is fitted[base.part_id][1]:
        return None
    rng = np.random.default_rng(_part_seed(run.seed, base.part_id))
    return name, placed, score_primitive(placed, base.points, cKDTree(base.points), config, rng), table


def complete_parts(state: ObjectState, run: _Run) -> None:
    """A bed frame extended to span its mattress and reach its headboard; hidden legs placed at the free
    corners of their fitted legs' rectangle; legs and mounted parts (handles) extended onto what they stand
    on (completion.py)."""
    config, contacts, obj, labels = run.config.completion, run.config.contacts, state.source, state.labels
    # a bed frame spans its mattress and reaches its headboard before its hidden legs are mirrored about it
    normals = {p.part_id: p.normals for p in obj.parts}
    prims, reached = complete_reaching_parts(state.prims, labels, config, contacts, normals)
    for i, gap in reached.items():
        log.info("object %d part %d (%s): extended %.3f m to the parts it spans and reaches", obj.id, i, labels[i],
                 gap)
    prims, placed = complete_missing_legs(obj.category, prims, labels, obj.skipped, config, state.base)
    for i, centre in placed.items():
        leg = next(p for p in obj.skipped if p.part_id == i)
        labels[i] = leg.label
        state.fits[i] = FittedPart(prims[i], _NO_FIT, {}, len(leg.points))
        state.points[i] = leg.points if len(leg.points) >= 3 else prims[i].sample_surface(
            run.config.fitting.surface_samples, np.random.default_rng(_part_seed(run.seed, i)))[0]
        run.warn(f"{link_name(obj.category, obj.id, leg.label, i)}: part {i} ({leg.label}) has "
                 f"{len(leg.points)} points; placed at the free corner of its fitted legs' rectangle "
                 f"({centre[0]:.3f}, {centre[1]:.3f})")
    prims, completed = complete_vertical_parts(prims, labels, config, contacts)
    for i, (down, up) in completed.items():
        log.info("object %d part %d (%s): extended %.3f m down, %.3f m up to its supports (negative: cut back)",
                 obj.id, i, labels[i], down, up)
    prims, mounted = complete_mounted_parts(prims, labels, config, contacts)
    for i, gap in mounted.items():
        log.info("object %d part %d (%s): extended %.3f m back onto its mount", obj.id, i, labels[i], gap)
    state.prims = prims


def contact_graph(state: ObjectState, run: _Run) -> None:
    """The surface planes Π of every part, then every directed Eq. 1 contact between them."""
    planes = {i: part_planes(state.prims[i], state.points[i], run.config.contacts, _part_seed(run.seed, i))
              for i in state.prims}
    state.contacts = contact_edges(planes, run.config.contacts)


def build_part_tree(state: ObjectState, run: _Run) -> None:
    """Eq. 4: the part tree; a part that touches nothing is fixed to its nearest possible parent and
    reported."""
    prims, labels = state.prims, state.labels
    state.tree = tree = part_tree(state.category, labels, {i: prims[i].volume for i in prims}, state.contacts,
                                  run.config.tree, run.config.contacts, distances=part_distances(prims))
    for i in tree.isolated:
        run.warn(f"{link_name(state.category, state.id, labels[i], i)}: part {i} ({labels[i]}) touches no "
                 f"other part of object {state.id}; fixed to the nearest possible parent, part {tree.parent[i]} "
                 f"({labels[tree.parent[i]]})")


def refine(state: ObjectState, run: _Run) -> None:
    """Alg. 1 (when ``refine`` is on): each child rotated, then moved, onto its parent's planes."""
    if run.config.refinement.refine:
        state.prims = refine_parts(state.prims, state.tree, run.config.refinement, run.config.contacts,
                                   run.config.fitting)


def shape_handles(state: ObjectState, run: _Run) -> None:
    """Each handle's bar where its points are, its posts reaching back to the (refined) mount face."""
    c = run.config
    state.prims, state.handles = mounted_handle_shapes(state.prims, state.labels, state.points, c.handles, c.contacts,
                                                       c.fitting, c.completion, state.name, state.tree.parent)


def check_coverage(state: ObjectState, run: _Run) -> None:
    """Every part's final primitive against its points (coverage.py), before the scene stages move
    the object; a part outside the bounds is reported by name."""
    cfg = run.config.coverage
    normals = {p.part_id: p.normals for p in state.source.parts}
    for i, prim in state.prims.items():
        if i not in state.fits or len(state.points.get(i, ())) < 3:
            continue
        cov = coverage(prim, state.fits[i].primitive, state.points[i], cfg, normals.get(i))
        log.debug("%s part %d: coverage %s", state.name, i, cov)
        problems = coverage_problems(cov, cfg)
        if problems:
            run.warn(f"{link_name(state.category, state.id, state.labels[i], i)}: the fitted {prim.kind.value} "
                     f"does not cover its points: {'; '.join(problems)}")


# --- scene stages --------------------------------------------------------------------------------------

def place_on_supports(states: list[ObjectState], run: _Run) -> dict[int, tuple[int | None, float]]:
    """Every object set upright (tilt below ``max_upright_tilt``), then resting on the floor or its
    supporter, floor-supported objects first; returns :func:`recon.scene_graph.support_relations`."""
    config = run.config.scene
    for s in states:
        R = upright_correction(s.prims[s.tree.root], config)
        if not np.allclose(R, np.eye(3)):
            c = np.concatenate([p.corners() for p in s.prims.values()])
            pivot = np.array([*c[:, :2].mean(axis=0), c[:, 2].min()])
            M = np.eye(4)
            M[:3, :3], M[:3, 3] = R, pivot - R @ pivot
            s.prims = {i: p.transformed(M) for i, p in s.prims.items()}
            s.T_moved = M @ s.T_moved
    by_id = {s.id: s for s in states}
    support = support_relations({i: list(s.prims.values()) for i, s in by_id.items()}, config)
    for i in sorted(by_id, key=lambda i: (support[i][0] is not None, i)):
        state, sup = by_id[i], support[i][0]
        bottom = min(float(p.corners()[:, 2].min()) for p in state.prims.values())
        if sup is None and bottom > config.support_distance:
            run.warn(f"{state.name}: floats {bottom:.3f} m above the floor with nothing under it; "
                     "left where it was scanned")
            continue
        top = 0.0 if sup is None else max(float(p.corners()[:, 2].max()) for p in by_id[sup].prims.values())
        moved = []
        state.prims = resting_on(state.prims, top, state.tree.root, config.base_bottom_tolerance, moved)
        for M in moved:
            state.T_moved = M @ state.T_moved
    return support


class _Obstacles:
    """The obstacles of an object's joint sweeps: every scan point not on the moving parts, and the
    surfaces of the other objects' primitives (a scan only has the faces the camera saw; a door must
    not swing into a neighbour's hidden side), sampled about every ``obstacle_spacing`` metres."""

    def __init__(self, scan: Scan, states: list[ObjectState], run: _Run):
        rng = np.random.default_rng(run.seed)
        self.points, self.part_id = scan.points, scan.part_id
        for s in states:            # each object's points where its parts now are (set upright, resting)
            if not np.allclose(s.T_moved, np.eye(4)):
                own = scan.object_id == s.id
                self.points = self.points.copy() if self.points is scan.points else self.points
                self.points[own] = self.points[own] @ s.T_moved[:3, :3].T + s.T_moved[:3, 3]
        self.shells = {s.id: np.concatenate([_surface_samples(p, run.config.joints.obstacle_spacing, rng)
                                             for p in s.prims.values()]) for s in states}

    def for_object(self, object_id: int) -> Callable[[object], np.ndarray]:
        """obstacles(moving part ids) -> (n, 3) world points, for :func:`recon.joints.estimate_joints`."""
        others = [v for k, v in self.shells.items() if k != object_id]

        def obstacles_for(part_ids):
            pts = self.points[~np.isin(self.part_id, list(part_ids))]
            return np.concatenate([pts] + others) if others else pts
        return obstacles_for


def estimate_object_joints(state: ObjectState, obstacles: _Obstacles, supported_by: int | None,
                           run: _Run) -> ObjectReconstruction:
    """The object's joints (type, axis, origin, swept limits), its parts' template and handle shapes,
    and its frame (bottom centre, x = its front): the finished :class:`ObjectReconstruction`."""
    config, labels, prims, tree = run.config, state.labels, state.prims, state.tree
    names = {i: joint_name(state.category, state.id, labels[i], i) for i in labels}
    parts_seen = state.moved_parts()         # the scan points where the parts now are
    joints = estimate_joints(state.category, names, labels, prims, tree, obstacles.for_object(state.id),
                             config.joints, config.contacts, config.fitting, run.warn,
                             {p.part_id: (p.points, p.normals) for p in parts_seen})
    joints = with_joint_uncertainty(joints, parts_seen, prims, obstacles.for_object(state.id), config, run.seed)
    shapes = (template_shapes(joints, prims, labels, config.shapes, config.joints.drawer_back_clearance)
              if config.shapes.template_shapes else {})
    shapes.update(posed_handle_shapes(state.handles, prims))
    parts = tuple(
        PartFit(i, labels[i], link_name(state.category, state.id, labels[i], i), prims[i],
                float(state.fits[i].score.total), dict(state.fits[i].candidate_scores), int(state.fits[i].n_points),
                prims[i].planes(config.contacts.cylinder_side_faces), shapes.get(i, ()))
        for i in labels)
    T_wo, size = object_frame([prims[tree.root]] + [p for i, p in prims.items() if i != tree.root],
                              object_front(joints, prims))
    return ObjectReconstruction(state.id, state.category, state.name, tree.root, parts, state.contacts, joints,
                                tree.isolated, T_wo, size, supported_by)


def room_walls(scan: Scan, run: _Run) -> tuple:
    """The room's walls fitted to the background points (the points of no object)."""
    labelled = scan.object_id >= 0
    centre = scan.points[labelled].mean(axis=0) if labelled.any() else scan.points.mean(axis=0)
    return walls_from_background(scan.points[~labelled], centre, run.config.walls, run.seed)


def _degeneracy(points: np.ndarray, min_thickness: float) -> str:
    """"" for a solid cloud, else "flat (...)" or "collinear (...)" from its principal extents."""
    c = points - points.mean(axis=0)
    ext = np.sort(np.ptp(c @ np.linalg.svd(c, full_matrices=False)[2].T, axis=0))
    if ext[1] < min_thickness:
        return f"collinear (spread {ext[1] * 1000:.1f} mm across a {ext[2]:.2f} m line)"
    if ext[0] < 1e-4:
        return f"flat (spread {ext[0] * 1000:.2f} mm off a plane)"
    return ""


def _surface_samples(prim: Primitive, spacing: float, rng: np.random.Generator) -> np.ndarray:
    """About one point per ``spacing``^2 of the primitive's surface, (n, 3) world."""
    area = 2 * (prim.size[0] * prim.size[1] + prim.size[1] * prim.size[2] + prim.size[0] * prim.size[2])
    n = int(np.clip(area / spacing**2, 50, 20000))
    return prim.sample_surface(n, rng)[0]
