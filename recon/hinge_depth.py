"""How deep behind a door's front face its hinge line lies, from the scan points at the hinge edge.

A scanner sees a door's front face; a front is then given an 18 mm board behind it
(``FittingConfig.front_thickness``) and the hinge put on that board's back face. Real doors are often
thicker (a microwave's or a refrigerator's door 3-6 cm), and where the pivot lies across a thick door
is decided by the door and its carcass, which the scan shows at the hinge edge:

- **Overlay door** (it stands in front of its carcass and, closed, rests on it): at the hinge edge the
  door's edge strip and the carcass's side face meet where the door's back face rests on the carcass's
  front. The labels change there, along the depth: door points in front, carcass points behind. That
  depth is the door's thickness. Any pivot between the door's front and back faces lets the door
  swing without sweeping through its carcass (every point behind the pivot moves forward and across
  the carcass's front edge), so one static scan cannot tell where in the thickness the pivot is: the
  estimate keeps the usual place, the back face at the carcass's front (where a hinge's leaf is screwed
  on the carcass), and reports the thickness beyond a board as *undecided* (the joint's uncertainty
  widens by it: :mod:`recon.joint_uncertainty`).
- **Inset door** (it closes inside its carcass's opening: the carcass's front face stands beside the hinge
  edge, level with the door's front), or a door with another front level with it just beyond its hinge
  edge (an oven door above its drawer): a door pivoting behind its front face would sweep its front
  corner at the hinge edge across that edge, into the face beside it; it can only pivot at its front face.
- Neither shown (the carcass's side is hidden, e.g. by a neighbour, and nothing stands beside the hinge
  edge): the board rule stays.

All depths are measured along the opening's outward normal, from the door box's front face, in metres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from recon.config import JointConfig

__all__ = ["SeenPoints", "HingeDepth", "hinge_depth"]


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
    (overlay door resting on its carcass) or "front face" (inset door)."""

    depth: float
    undecided: float
    how: str


def hinge_depth(front: float, board: float, normal: np.ndarray, out: np.ndarray, edge: float,
                axis: np.ndarray, span: tuple[float, float], seen: SeenPoints | None,
                config: JointConfig, noise: float = 0.0) -> HingeDepth:
    """The hinge line's depth behind the door's front face (see the module docstring).

    front : the door's front face along ``normal`` (3,) (unit, outward), m; board : the depth the door
    box's back face has (the board rule); out : (3,) unit, in the door's plane, pointing out of the door
    across its hinge edge, which lies at ``edge`` (m) along it; axis : (3,) the hinge's direction, the
    door spanning ``span`` (lo, hi) m along it; seen : the points (None: the board rule); noise : m, the
    depth noise of the door's points across its face (:mod:`recon.depth_noise`).
    """
    board_rule = HingeDepth(board, 0.0, "board")
    if seen is None:
        return board_rule
    band, trim, n_min = config.hinge_edge_band, config.hinge_edge_trim, config.hinge_edge_min_points

    def window(p):
        depth = front - p @ normal
        across = p @ out - edge
        along = p @ axis
        keep = ((np.abs(across) <= band) & (along >= span[0] + trim) & (along <= span[1] - trim)
                & (depth >= -band) & (depth <= config.door_max_thickness + band))
        return keep, depth, across

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
    # overlay: the depth where the labels change from door (in front) to carcass (behind)
    d_door, d_body = np.sort(dd[kd]), np.sort(db[kb])
    if len(d_door) < n_min or len(d_body) < n_min:
        return board_rule
    cuts = np.unique(np.concatenate([d_door, d_body]))
    wrong = (len(d_door) - np.searchsorted(d_door, cuts, side="left")) + np.searchsorted(d_body, cuts, side="left")
    cut = float(np.median(cuts[wrong == wrong.min()]))          # the middle of the cuts that split them best
    behind = int(np.sum((d_body >= cut) & (d_body <= cut + config.hinge_edge_band)))
    # a thickness the scan's own depth noise could make up is no thickness
    if cut <= board + max(config.hinge_depth_tolerance, config.hinge_depth_noise_sigmas * noise) or behind < n_min:
        return board_rule
    return HingeDepth(cut, cut - board, "carcass front")
