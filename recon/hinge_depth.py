"""How deep behind a door's front face its hinge line lies, from the scan points at the hinge edge.

A scanner sees a door's front face; a front is then given an 18 mm board behind it
(``FittingConfig.front_thickness``) and the hinge put on that board's back face. Real doors are often
thicker (a microwave's or a refrigerator's door 3-6 cm), and where the pivot lies across a thick door
is decided by the door and its carcass, which the scan shows at the hinge edge:

- **Overlay door** (it stands in front of its carcass and, closed, rests on it): at the hinge edge the
  door's edge strip and the carcass's side face meet where the door's back face rests on the carcass's
  front. The labels change there, along the depth: door points in front, carcass points behind. That
  depth is the door's thickness. Most of the door's points there lie on its front face, though, whose
  depth noise spreads them behind it (a 2 cm noise: 6 cm deep) whatever the door's thickness, so they
  cannot tell a thick door from a board; the carcass's side face can: it begins at the door's back face.
  A door is read thicker than its board only when its carcass's points rule out (likelihood ratio,
  ``JointConfig.hinge_depth_p_value``; the depth noise modelled, :func:`onset_likelihood`) every onset
  of that face up to the board plus ``hinge_depth_tolerance`` (the label bleed at the seam). Its
  thickness is then the cut that misplaces the smallest shares of door and of carcass points (counts
  would slide it into the side seen by fewer points). Any pivot between the door's front and back faces
  lets the door swing without sweeping through its carcass (every point behind the pivot moves forward
  and across the carcass's front edge), so one static scan cannot tell where in the thickness the pivot is: the
  estimate keeps the usual place, the back face at the carcass's front (where a hinge's leaf is screwed
  on the carcass), and reports the thickness beyond a board as *undecided* (the joint's uncertainty
  widens by it: :mod:`recon.joint_uncertainty`).
- **Inset door** (it closes inside its carcass's opening: the carcass's front face stands beside the hinge
  edge, level with the door's front), or a door with another front level with it just beyond its hinge
  edge (an oven door above its drawer): a door pivoting behind its front face would sweep its front
  corner at the hinge edge across that edge, into the face beside it; it can only pivot at its front face.
- The carcass's side face at the hinge edge hidden (a neighbour stands against it, the camera never saw
  that side): the door's back face rests on the carcass's front all around, so the carcass's faces that
  continue the door's other edges (its top and bottom panels, the side face at the free edge, seen in the
  same windows) begin at the same depth and are tested the same way. The hinge edge stays the first
  witness: its own points decide whenever it has enough.
- None of them shown: the board rule stays.

What the scan does not resolve behind the door: its carcass's side face is known to begin only within the
onsets its points do not rule out (likelihood ratio, ``JointConfig.hinge_clearance_p_value``), and between the
hinge's depth and the deepest of them the scan cannot tell door from gap. Were it a gap, the pivot could also
lie in from the hinge edge: a pivot ``e`` in from the edge swings the hinge-side back corner up to ``e`` deeper
(radius ``e`` about it), so it needs ``e`` of clearance behind the door; were it door, the back face (and the
hinge on it) lies deeper. Both fill the right triangle whose legs are that *clearance*, across the door and along
its normal, at the estimate (``HingeDepth.clearance``; the joint's uncertainty widens by its RMS, clearance /
sqrt(3): :mod:`recon.joint_uncertainty`). The estimate stays on the triangle's corner (the door's back face at its
edge: where our generators and the third-party corpus hinge their doors).

All depths are measured along the opening's outward normal, from the door box's front face, in metres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.stats import chi2, norm

from recon.config import JointConfig

__all__ = ["SeenPoints", "HingeDepth", "hinge_depth", "onset_likelihood"]

_MIN_NOISE = 0.001
"""m: the depth noise assumed at least (a noiseless scan's onset is then its first carcass point's depth)."""
_STRAY_SHARES = (0.01, 0.03, 0.1, 0.3)
"""Shares of a window's carcass points the onset model lets be stray (the likeliest is taken)."""


@dataclass(frozen=True)
class SeenPoints:
    """The scan points a hinge is placed from, world: the door's (n, 3); its parent's (m, 3); the rest of
    its object's (k, 3) (the parent's and the other parts', not the door's or its handles') and their
    normals (k, 3); the door's normals (n, 3). None where not given."""

    door: np.ndarray | None = None
    body: np.ndarray | None = None
    others: np.ndarray | None = None
    others_normals: np.ndarray | None = None
    door_normals: np.ndarray | None = None


@dataclass(frozen=True)
class HingeDepth:
    """Where the hinge line lies across the door: ``depth`` (m) behind the door's front face;
    ``undecided`` (m): the span of depths (in front of ``depth``) where the pivot could equally lie
    (0 when the scan decides it or the board rule is used); ``how``: "board", "carcass front"
    (overlay door resting on its carcass) or "front face" (inset door); ``clearance`` (m): how far behind
    ``depth`` the carcass's side face at the door's edge may begin, as far as its points tell (0 for an inset
    door or when no carcass points were there): the pivot may lie that much deeper or that much in from the
    edge (see the module docstring)."""

    depth: float
    undecided: float
    how: str
    clearance: float = 0.0


def hinge_depth(front: float, board: float, normal: np.ndarray, out: np.ndarray, edge: float,
                axis: np.ndarray, span: tuple[float, float], seen: SeenPoints | None,
                config: JointConfig, noise: float = 0.0, edges: tuple = ()) -> HingeDepth:
    """The hinge line's depth behind the door's front face (see the module docstring).

    front : the door's front face along ``normal`` (3,) (unit, outward), m; board : the depth the door
    box's back face has (the board rule); out : (3,) unit, in the door's plane, pointing out of the door
    across its hinge edge, which lies at ``edge`` (m) along it; axis : (3,) the hinge's direction, the
    door spanning ``span`` (lo, hi) m along it; seen : the points (None: the board rule); noise : m, the
    depth noise of the door's points across its face (:mod:`recon.depth_noise`); edges : the door's edges,
    each as (out, edge, axis, span) like the hinge edge's, whose carcass faces witness the door's back face
    when the hinge edge shows too few points (empty: the hinge edge alone).
    """
    board_rule = HingeDepth(board, 0.0, "board")
    if seen is None:
        return board_rule
    band, trim, n_min = config.hinge_edge_band, config.hinge_edge_trim, config.hinge_edge_min_points

    def window(p, out=out, edge=edge, axis=axis, span=span):
        depth = front - p @ normal
        across = p @ out - edge
        along = p @ axis
        keep = ((np.abs(across) <= band) & (along >= span[0] + trim) & (along <= span[1] - trim)
                & (depth >= -band) & (depth <= config.door_max_thickness + band))
        return keep, depth, across

    def pooled(p):
        keep, depth, _ = window(p)
        for e in edges:
            keep |= window(p, *e)[0]
        return keep, depth

    if seen.others is not None and len(seen.others):
        # inset: the carcass's (or another front's) face beside the hinge edge, level with the door's front
        ko, do, ao = window(seen.others)
        beside = ko & (ao > band / 4) & (np.abs(do) <= board / 2)
        if seen.others_normals is not None:
            beside &= seen.others_normals @ normal > 0.7
        if int(beside.sum()) >= n_min:
            return HingeDepth(0.0, 0.0, "front face")
    if seen.door is None or seen.body is None or not len(seen.door) or not len(seen.body):
        return board_rule
    kb, db, _ = window(seen.body)
    kd, dd, _ = window(seen.door)
    if edges and (kb.sum() < n_min or kd.sum() < n_min):     # the hinge edge not seen: the door's other edges
        kb, db = pooled(seen.body)
        kd, dd = pooled(seen.door)
    d_door, d_body = np.sort(dd[kd]), np.sort(db[kb])
    if len(d_door) < n_min or len(d_body) < n_min:
        return board_rule
    # overlay: thick only when the carcass's points rule out its side face beginning where a board door's would
    onsets, loglik = onset_likelihood(d_body, max(noise, _MIN_NOISE), -band, config.door_max_thickness + band)
    # the deepest onset the carcass's points do not rule out: behind the hinge, door or gap up to there
    deepest = float(onsets[2.0 * (loglik.max() - loglik) <= chi2.isf(config.hinge_clearance_p_value, 1)].max())
    board_rule = HingeDepth(board, 0.0, "board", max(0.0, deepest - board))
    thin = onsets <= board + config.hinge_depth_tolerance
    ratio = 2.0 * (float(loglik.max()) - float(loglik[thin].max()))
    if thin[int(np.argmax(loglik))] or ratio < chi2.isf(config.hinge_depth_p_value, 1):
        return board_rule
    # where the labels change from door (in front) to carcass (behind): the cut misplacing the smallest shares of
    # each (their counts would slide it into the more sparsely seen one), the middle of the best cuts
    cuts = np.unique(np.concatenate([d_door, d_body]))
    wrong = ((len(d_door) - np.searchsorted(d_door, cuts, side="left")) / len(d_door)
             + np.searchsorted(d_body, cuts, side="left") / len(d_body))
    cut = float(np.median(cuts[wrong == wrong.min()]))
    behind = int(np.sum((d_body >= cut) & (d_body <= cut + band)))
    if cut <= board + config.hinge_depth_tolerance or behind < n_min:
        return board_rule
    return HingeDepth(cut, cut - board, "carcass front", max(0.0, deepest - cut))


def onset_likelihood(depths: np.ndarray, noise: float, lo: float, hi: float, step: float = 0.001
                     ) -> tuple[np.ndarray, np.ndarray]:
    """(onsets (k,), log-likelihoods (k,)): how well a carcass side face beginning at each onset explains the
    carcass's points ``depths`` (n,) (m behind the door's front, all within the window [``lo``, ``hi``]).

    The model: a face seen evenly from its onset on, each point moved along the depth by Gaussian noise of
    ``noise`` (m, the door face's depth noise: the same camera's rays), plus a share of stray points (label
    fragments, flying pixels) spread evenly over the window; that share is the likeliest of
    ``_STRAY_SHARES`` for each onset (profile likelihood). Onsets run from 0 to ``hi`` less the window's
    margin ``-lo`` in ``step`` (m).
    """
    x = np.asarray(depths, dtype=np.float64)
    onsets = np.arange(0.0, hi + lo + step / 2, step)
    u = (hi - onsets) / noise, (lo - onsets) / noise
    # the face's density, Phi((x - onset) / noise), integrated over the window (the integral of Phi is u Phi + phi)
    mass = noise * ((u[0] * norm.cdf(u[0]) + norm.pdf(u[0])) - (u[1] * norm.cdf(u[1]) + norm.pdf(u[1])))
    loglik = np.empty(len(onsets))
    for i, onset in enumerate(onsets):          # one onset at a time: a noiseless scan's window holds many points
        face = norm.cdf((x - onset) / noise) / mass[i]
        loglik[i] = max(float(np.log((1.0 - e) * face + e / (hi - lo)).sum()) for e in _STRAY_SHARES)
    return onsets, loglik
