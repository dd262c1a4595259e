"""Handles as the shapes a gripper meets: a bar on two standoff posts, or a knob's cap on its stem.

A fitted handle primitive, extended back onto its mount by completion (``complete_mounted_parts``), is
one solid box from the drawer/door face out to the bar. A gripper aimed at that box's centre reaches
half a standoff too deep and its fingertips hit the front. The articulated template of a handle says
more: a bar (or a knob's cap) at the handle's outer extent, held off the face by thin posts (a stem).

The handle hangs from its part-tree parent (its drawer/door), on the parent's face it stands in front
of (:func:`facing_plane`), after refinement. Measured along that face's outward normal ``n``:

- the face the camera saw: the median height of the mount's own points around the handle (a refined or
  noise-thickened front may sit a centimetre or two off its points; the bar belongs where its points
  are, and its posts reach back to the fitted face); their robust spread is the depth noise σ there;
- ``x`` = height of a handle point above that seen face; points within ``handle_bleed_margin`` of it
  are dropped: the front's own surface labelled handle (label bleed) or its depth noise;
- the bar's centre height is the **median** ``x`` of the points left, but at most half a bar below the
  outer face, the ``handle_outer_percentile`` height less ``handle_outer_noise`` σ: posts and bleed
  pull the median in, a bar seen mostly from the front has its median on its outer face;
- extents along the face from the ``[p, 100 - p]`` percentiles (``handle_extent_percentile``), widened
  by ``1 / (1 - 2p/100)`` (exact for points spread evenly); the middle across the bar (see
  :func:`_middle_across`): across a vertical bar (a horizontal direction) its points' median, across a
  horizontal bar the mean of the ``handle_middle_percentile`` pair; a knob's cap so along both directions;
- the longer in-face extent is the bar's length; shorter than ``handle_knob_max_length`` -> a knob;
- the bar's thickness (across it and out from the face) is its measured width, at most
  ``handle_max_thickness`` (a wider measure is lateral noise and bleed, not a thicker bar);
- the posts (``handle_post_width`` thick, ``handle_post_inset`` in from the bar's ends; unseen, so a
  typical value) or the knob's stem run from the mount's fitted face to the bar's inner face.

Points farther behind the mount's fitted face than ``handle_face_window`` are another part's (a segmentation's
label fragments: a knob's label on the body's back behind its door); an envelope reaching that far behind is
first rebuilt from the points in front (:func:`_in_front`), so a handle's solid never stands inside its mount.
A handle with fewer than ``handle_min_points`` points clear of the face, whose bar would stand less
than ``handle_min_standoff`` off the seen face, or whose posts would be shorter than
``handle_min_post`` (a mount fitted in front of its points), keeps its envelope (status ``ENVELOPE``,
logged with the reason). Frames: every primitive is in the world frame (z up, metres).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from enum import Enum

import numpy as np
import shapely

from recon.completion import MOUNTED_LABELS, mount_face
from recon.config import CompletionConfig, ContactConfig, FittingConfig, HandleConfig
from recon.primitive import Primitive, PrimitiveKind, SurfacePlane

__all__ = ["HandleStyle", "HandleShapes", "handle_shapes", "facing_plane", "mounted_handle_shapes",
           "posed_handle_shapes"]

log = logging.getLogger(__name__)

_SEEN_FACE_ROUNDS = 3
"""Rounds of re-centring the window of mount points on their median height (converges in 2-3)."""


class HandleStyle(str, Enum):
    """What a handle part is written as."""

    BAR = "bar"              # a bar on two posts
    KNOB = "knob"            # a cap on a stem
    ENVELOPE = "envelope"    # its one fitted (and completed) primitive: the points could not support more


@dataclass(frozen=True, eq=False)
class HandleShapes:
    """The shapes of one handle part, world frame, at the time they were measured.

    style : HandleStyle
    reason : why (for ENVELOPE: what was missing), with the measured numbers
    envelope : the part's primitive — the box enclosing ``shapes`` (BAR/KNOB) or the input (ENVELOPE)
    shapes : the bar (or cap) first, then its posts (stem); ``()`` for ENVELOPE
    """

    style: HandleStyle
    reason: str
    envelope: Primitive
    shapes: tuple[Primitive, ...] = ()

    def posed(self, envelope: Primitive) -> tuple[Primitive, ...]:
        """``shapes`` moved rigidly with the envelope to ``envelope``'s pose (after refinement and the
        scene's upright/support corrections moved the part)."""
        T = envelope.T_world_part @ np.linalg.inv(self.envelope.T_world_part)
        return tuple(s.transformed(T) for s in self.shapes)


def _face_axes(envelope: Primitive, n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit in-face axes (3,) from the envelope's axes other than the one nearest ``n``."""
    R = envelope.T_world_part[:3, :3]
    k = int(np.argmax(np.abs(R.T @ n)))
    a = R[:, (k + 1) % 3] - (R[:, (k + 1) % 3] @ n) * n
    a /= np.linalg.norm(a)
    return a, np.cross(n, a)


def _extent(x: np.ndarray, p: float) -> tuple[float, float]:
    """(middle, length) of coordinates ``x`` (n,) from the [p, 100 - p] percentiles, widened by
    1 / (1 - 2p/100) (exact for evenly spread points)."""
    lo, hi = np.percentile(x, [p, 100.0 - p])
    return float((lo + hi) / 2.0), float((hi - lo) / (1.0 - 2.0 * p / 100.0))


def _posed(kind: PrimitiveKind, size, R: np.ndarray, centre: np.ndarray) -> Primitive:
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, centre
    return Primitive(kind, size, T)


def _seen_face(mount_points: np.ndarray | None, n: np.ndarray, d: float, centre: np.ndarray,
               radius: float, config: HandleConfig) -> tuple[float, float, int]:
    """(height (m) above the plane ``n·p + d = 0`` where the camera saw the mount's face around the
    handle, depth noise σ (m) there, number of mount points they rest on): the median and the robust
    spread (1.4826 × MAD) of the heights of the mount's points (k, 3) within ``radius`` (m) of
    ``centre`` along the face and ``handle_face_window`` of that median (re-centred a few rounds,
    starting at the plane); (0, 0, 0) when fewer than ``handle_min_points``."""
    if mount_points is None or len(mount_points) == 0:
        return 0.0, 0.0, 0
    h = mount_points @ n + d
    along = mount_points - centre
    along = along - np.outer(along @ n, n)
    around = np.linalg.norm(along, axis=1) <= radius
    seen = 0.0
    for _ in range(_SEEN_FACE_ROUNDS):   # the window follows the points (a fitted face off its points
        near = around & (np.abs(h - seen) <= config.handle_face_window)   # cuts their noise unevenly)
        if near.sum() < config.handle_min_points:
            return 0.0, 0.0, 0
        seen = float(np.median(h[near]))
    return seen, 1.4826 * float(np.median(np.abs(h[near] - seen))), int(near.sum())


def _is_horizontal(direction: np.ndarray) -> bool:
    """Whether the unit ``direction`` (3,) world, z up, lies within 45 deg of horizontal."""
    return abs(float(direction[2])) < np.sqrt(0.5)


def _middle_across(across: np.ndarray, v: np.ndarray, config: HandleConfig) -> float:
    """The middle (m) of a bar's points' coordinates ``across`` (k,) along the in-face unit direction
    ``v`` (3,) world, z up.

    A camera carried at standing height sees a horizontal bar from above: its top face adds points along
    the bar's upper edge, which pull their median up; the mean of the ``handle_middle_percentile`` pair
    finds the middle. A camera passing a vertical bar sees it along oblique rays whose depth noise
    leaves a trail of points off one of its edges: the pair follows the trail, the median stays on the
    bar. A knob's cap is placed so along both in-face directions.
    """
    if _is_horizontal(v):                              # a vertical bar
        return float(np.median(across))
    mid_pct = config.handle_middle_percentile
    return float(np.mean(np.percentile(across, [mid_pct, 100.0 - mid_pct])))


def _in_front(points: np.ndarray, envelope: Primitive, face: SurfacePlane, R: np.ndarray, config: HandleConfig,
              fitting: FittingConfig) -> tuple[np.ndarray, Primitive]:
    """(points, envelope) of a handle without what lies behind its mount's face: a handle stands in front of
    the face it hangs from, so its ``points`` (k, 3) world farther behind ``face`` (the mount's fitted plane,
    normal out of it) than ``handle_face_window`` are another part's, labelled handle by a segmentation (a
    knob's label fragments on the body's back 45 cm behind its door). An ``envelope`` reaching that far
    behind is rebuilt as the box, along ``R``'s columns (u, v, n: in-face axes and the face's normal), of the
    points left, from the face out to the outermost of them. Unchanged when no point or no corner of the
    envelope lies that far behind, or when no point is left in front."""
    h = points @ face.normal + face.d
    keep = h >= -config.handle_face_window
    reaches_behind = float((envelope.corners() @ face.normal).min() + face.d) < -config.handle_face_window
    if keep.all() or not keep.any() or not reaches_behind:
        return points, envelope
    q = points[keep] @ R
    lo, hi = q.min(axis=0), q.max(axis=0)
    lo[2], hi[2] = min(lo[2], -face.d), max(hi[2], -face.d)     # from the face (n . p + d = 0) out
    size = np.maximum(hi - lo, fitting.min_thickness)
    return points[keep], _posed(PrimitiveKind.BOX, size, R, R @ ((lo + hi) / 2.0))


def handle_shapes(points: np.ndarray, envelope: Primitive, face: SurfacePlane,
                  config: HandleConfig, fitting: FittingConfig, mount_points: np.ndarray | None = None) -> HandleShapes:
    """A handle's bar and posts (or knob's cap and stem) measured from its ``points`` (k, 3) world.

    envelope : the handle's fitted primitive (its axes give the in-face directions)
    face : the mount's surface plane the handle hangs from (normal out of the mount); the posts reach it
    mount_points : (m, 3) world, the mount's points, optional. Where they show the face around the handle
        (their median height) is the face the handle is measured from: a refined mount may sit a
        centimetre or two off its points, while the bar belongs where its points are.
    Returns BAR / KNOB shapes with their enclosing box as the new envelope, or ENVELOPE (the input, or the box
    of its points in front of the face when it reached behind it: :func:`_in_front`) with the reason when the
    points cannot support a bar (see the module docstring).
    """
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    n = np.asarray(face.normal, float) / np.linalg.norm(face.normal)
    u, v = _face_axes(envelope, n)                     # (u, v, n) right-handed
    points, envelope = _in_front(points, envelope, face, np.column_stack([u, v, n]), config, fitting)
    reach = 0.5 * float(np.max(np.abs(envelope.T_world_part[:3, :3].T @ np.column_stack([u, v])).T @ envelope.size))
    seen, sigma, n_seen = _seen_face(mount_points, n, face.d, envelope.center, reach + config.handle_face_window,
                                     config)
    x = points @ n + face.d - seen                     # height above the face the camera saw
    clear = x > config.handle_bleed_margin
    if clear.sum() < config.handle_min_points:
        return HandleShapes(HandleStyle.ENVELOPE, f"{int(clear.sum())} of {len(points)} points stand more than "
                            f"{config.handle_bleed_margin * 1000:.0f} mm off the face (needs "
                            f"{config.handle_min_points})", envelope)
    q, xc = points[clear], float(np.median(x[clear]))
    outer = float(np.percentile(x[clear], config.handle_outer_percentile)) - config.handle_outer_noise * sigma
    pct = config.handle_extent_percentile
    (mu, length), (mv, width) = _extent(q @ u, pct), _extent(q @ v, pct)
    if width > length:                                 # u along the bar
        u, v = v, -u
        (mu, length), (mv, width) = _extent(q @ u, pct), _extent(q @ v, pct)
    mv = _middle_across(q @ v, v, config)
    knob = length < config.handle_knob_max_length
    if knob:
        mu = _middle_across(q @ u, u, config)          # a knob has no along: its middle as across a bar
        across = float(np.clip((length + width) / 2.0, fitting.min_thickness, config.handle_knob_max_diameter))
        depth = min(across, config.handle_max_thickness)
    else:
        across = float(np.clip(width, fitting.min_thickness, config.handle_max_thickness))
        depth = across
    xc = min(xc, outer - depth / 2.0)                  # a bar seen mostly from the front: its face is the median
    inner, base = xc - depth / 2.0, -seen              # base: the mount face the posts reach
    if inner < config.handle_min_standoff or inner - base < config.handle_min_post:
        return HandleShapes(HandleStyle.ENVELOPE, f"its {'cap' if knob else 'bar'} ({depth * 1000:.0f} mm thick, "
                            f"centre {xc * 1000:.1f} mm off the seen face, {(xc - base) * 1000:.1f} mm off the "
                            f"mount's fitted face) leaves too little room for its {'stem' if knob else 'posts'} "
                            f"({inner * 1000:.1f} mm off the seen face, needs {config.handle_min_standoff * 1000:.0f}; "
                            f"{(inner - base) * 1000:.1f} mm long, needs {config.handle_min_post * 1000:.0f})",
                            envelope)
    R = np.column_stack([u, v, n])

    def at(su: float, sx: float) -> np.ndarray:   # world point at in-face (mu + su, mv), height sx above the seen face
        return (mu + su) * u + mv * v + (sx + seen - face.d) * n

    w, post, mid = config.handle_post_width, inner - base, (inner + base) / 2.0
    if knob:
        shapes = (_posed(PrimitiveKind.CYLINDER, [across, across, depth], R, at(0.0, xc)),
                  _posed(PrimitiveKind.CYLINDER, [w, w, post], R, at(0.0, mid)))
    else:
        off = max(length / 2.0 - config.handle_post_inset, 0.0)
        shapes = (_posed(PrimitiveKind.BOX, [length, across, depth], R, at(0.0, xc)),
                  *(_posed(PrimitiveKind.CYLINDER, [w, w, post], R, at(s * off, mid)) for s in (-1, 1)))
    top = xc + depth / 2.0
    env = _posed(PrimitiveKind.BOX, [length, across, top - base], R, at(0.0, (top + base) / 2.0))
    style = HandleStyle.KNOB if knob else HandleStyle.BAR
    reason = (f"{style.value} {length * 1000:.0f} x {across * 1000:.0f} x {depth * 1000:.0f} mm, centre "
              f"{xc * 1000:.1f} mm off the face seen at {seen * 1000:+.1f} mm from the mount's "
              f"(noise {sigma * 1000:.1f} mm, {n_seen} mount points), from {int(clear.sum())} of {len(points)} points")
    return HandleShapes(style, reason, env, shapes)


def facing_plane(mount: Primitive, points: np.ndarray, config: HandleConfig, contacts: ContactConfig
                 ) -> SurfacePlane | None:
    """The face of ``mount`` a handle's ``points`` (k, 3) world stand in front of: of the faces whose
    outline, grown by ``handle_face_window`` (a fitted door may come out a little narrower than the
    handle near its edge), holds the points' median (projected onto the face), the one it stands highest
    above; None when it stands above none of them."""
    centre = np.median(np.asarray(points, float).reshape(-1, 3), axis=0)
    best = None
    for pl in mount.planes(contacts.cylinder_side_faces):
        h = float(centre @ pl.normal + pl.d)
        if h <= 0 or (best is not None and h <= best[0]):
            continue
        B = np.linalg.svd(np.eye(3) - np.outer(pl.normal, pl.normal))[0][:, :2]
        if shapely.Polygon(pl.polygon @ B).buffer(config.handle_face_window).contains(shapely.Point(*(centre @ B))):
            best = (h, pl)
    return None if best is None else best[1]


def mounted_handle_shapes(prims: dict[int, Primitive], labels: dict[int, str], points: dict[int, np.ndarray],
                          config: HandleConfig, contacts: ContactConfig, fitting: FittingConfig,
                          completion: CompletionConfig, where: str = "", parents: dict[int, int] | None = None
                          ) -> tuple[dict[int, Primitive], dict[int, HandleShapes]]:
    """Every handle/knob of an object as its bar and posts (knob cap and stem).

    prims : {part_id: primitive}; labels : {part_id: label}; points : {part_id: (k, 3) world}
    where : names the object in log messages.
    parents : {part_id: parent part id} of the part tree: a handle's mount is its parent (the link it
        hangs from), on the face it stands in front of (:func:`facing_plane`). Without it, the face
        completion would mount it on (:func:`recon.completion.mount_face`).
    Returns (prims with each measured handle's envelope replaced by the box enclosing its shapes,
    {part_id: HandleShapes} of the measured ones). Nothing changes when ``config.handle_shapes`` is off.
    """
    out, shapes = dict(prims), {}
    if not config.handle_shapes:
        return out, shapes
    for i, prim in prims.items():
        if labels[i] not in MOUNTED_LABELS or i not in points or len(points[i]) == 0:
            continue
        if parents is not None:
            j = parents.get(i)
            face = None if j not in prims else facing_plane(prims[j], points[i], config, contacts)
        else:
            found = mount_face(i, prims, labels, completion, contacts)
            j, face = (None, None) if found is None else found[:2]
        if face is None:
            log.info("%s part %d (%s): no mount face found (mount part %s); kept as one %s", where, i, labels[i],
                     j, prim.kind.value)
            continue
        hs = handle_shapes(points[i], prim, face, config, fitting, points.get(j))
        if hs.style is HandleStyle.ENVELOPE:
            if hs.envelope is not prim:
                out[i] = hs.envelope
                log.info("%s part %d (%s): its %s reached behind its mount's face; kept as the box of its points "
                         "in front of it (%s m)", where, i, labels[i], prim.kind.value, np.round(hs.envelope.size, 3))
            log.info("%s part %d (%s): kept as one %s: %s", where, i, labels[i], out[i].kind.value, hs.reason)
            continue
        log.debug("%s part %d (%s) on part %d: %s", where, i, labels[i], j, hs.reason)
        out[i], shapes[i] = hs.envelope, hs
    return out, shapes


def posed_handle_shapes(shapes: dict[int, HandleShapes],
                        prims: dict[int, Primitive]) -> dict[int, tuple[Primitive, ...]]:
    """{part_id: the handle's shapes at its final primitive's pose} for the parts of ``prims`` in ``shapes``."""
    return {i: hs.posed(prims[i]) for i, hs in shapes.items() if i in prims}
