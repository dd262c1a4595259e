"""Grasps on the edge of a front without a handle: the fingers pinch the panel across its thickness (pure numpy).

A parallel gripper can open a handleless door or drawer by pinching an edge of its front panel, if the
panel is thin enough to fit between the open fingers and a finger can reach behind the panel there. The
candidates: each edge of the panel (the largest geometry of the part seen along its outward direction) that
moves when the joint opens, pinched ``EDGE_DEPTH`` in from the edge at the point of the edge that moves most
(a door's free edge at its middle; its top and bottom edges ``CORNER_INSET`` from the free corner; a drawer's
edges at their middles), approached in the panel's plane from beyond the edge, the fingers closing across
the panel. Whether a finger fits behind the edge is left to the collision checks of the stand-pose search:
a closed overlay front usually has its carcass or a touching sibling there, and the search then names what
the grasp collides with.
"""

from __future__ import annotations

import numpy as np

from planners.errors import HandleNotFoundError

__all__ = ["EdgeGrasps", "edge_grasps", "EDGE_DEPTH", "CORNER_INSET", "FINGER_ROOM"]

EDGE_DEPTH = 0.015
"""Metres from the panel's edge to the tool frame: the fingertip pads overlap the panel by about this much."""

CORNER_INSET = 0.05
"""Metres from a door's free corner to the pinch on its top or bottom edge."""

FINGER_ROOM = 0.005
"""Metres each open finger must clear the panel's face by as it slides over it: a panel thicker than the
gripper's opening minus twice this cannot be pinched."""


class EdgeGrasps:
    """The pinch candidates of one front: ``frames`` tuple of (4, 4) tool frames in the moving link's frame, best
    first; ``geom`` (link, collision index) of the panel; ``thickness`` m; ``facing`` (3,) unit outward direction
    of the part at the first pinch (world; the robot stands on that side)."""

    def __init__(self, frames, geom, thickness, facing):
        self.frames, self.geom, self.thickness, self.facing = frames, geom, thickness, facing


def edge_grasps(cands: list, speed, outward_link: np.ndarray, grip_width: float, where: str) -> EdgeGrasps:
    """Pinch candidates on the panel of a handleless front.

    Args:
        cands: the part's geometries, ``(link, Shape, T_moving_geom (4, 4), index)`` each.
        speed: ``p_link (3,) -> (3,)`` world velocity of a point of the moving link per unit of opening.
        outward_link: (3,) the part's outward direction (where it opens toward), moving-link frame.
        grip_width: the gripper's largest opening, m.
        where: "file: joint 'name'" for messages.

    Raises:
        HandleNotFoundError: the part has no panel, or its panel is too thick for the gripper (the message
            says so).
    """
    from planners.handle import _bar, _box_extent
    n = outward_link / max(float(np.linalg.norm(outward_link)), 1e-12)
    best, best_area = None, -1.0
    for c in cands:
        e = _box_extent(c[1])
        m = np.abs(c[2][:3, :3].T @ n)
        area = float(e[0] * e[1] * m[2] + e[1] * e[2] * m[0] + e[0] * e[2] * m[1])
        if area > best_area:
            best, best_area = c, area
    if best is None or best_area <= 0:
        raise HandleNotFoundError(f"{where}: no handle and no front panel to pinch (the moving link has no "
                                  f"collision geometry facing outward); give OpenTask.grasp_point or grasp_link")
    e = _box_extent(best[1])
    R = best[2][:3, :3]
    centre = (best[2] @ np.append(_bar(best[1])[1], 1.0))[:3]
    face = int(np.argmax(np.abs(R.T @ n)))
    thickness = float(e[face])
    normal = R[:, face] * np.sign(R[:, face] @ n)
    if thickness > grip_width - 2 * FINGER_ROOM:
        raise HandleNotFoundError(
            f"{where}: no handle, and the front panel is {thickness * 1000:.0f} mm thick: more than the gripper "
            f"opens ({grip_width * 1000:.0f} mm) less {FINGER_ROOM * 1000:.0f} mm a side, so its edge cannot be "
            f"pinched either; give OpenTask.grasp_point or grasp_link")
    scored = []
    for i in (k for k in range(3) if k != face):
        k_along = 3 - face - i
        for sigma in (1.0, -1.0):
            u, along = R[:, i] * sigma, R[:, k_along]
            inset = max(0.0, e[k_along] / 2 - CORNER_INSET)
            points = [centre + (e[i] / 2 - EDGE_DEPTH) * u + t * along for t in (0.0, inset, -inset)]
            v = [float(np.linalg.norm(speed(p))) for p in points]
            j = int(np.argmax(np.round(v, 6)))        # ties (a drawer): the middle of the edge
            scored.append((v[j], points[j], u))
    top = max(s[0] for s in scored)
    frames = []
    for v, p, u in sorted(scored, key=lambda s: -s[0]):
        if v < 0.25 * top:                     # the hinge edge, or a door's edge that hardly moves
            continue
        z = -u
        y = normal
        x = np.cross(y, z)
        for flip in (False, True):
            T = np.eye(4)
            T[:3, :3] = np.column_stack([-x, -y, z]) if flip else np.column_stack([x, y, z])
            T[:3, 3] = p
            frames.append(T)
    return EdgeGrasps(tuple(frames), (best[0], best[3]), thickness, normal)
