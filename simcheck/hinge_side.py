"""The other hinge of a door whose hinge side the scan leaves undecided.

recon flags a handleless door whose two edges lie as near its body's edges ``side_undecided`` in
graph.json (:class:`recon.model.JointUncertainty`): nothing in the scan says which edge is free, the one
it hinged is a guess. A robust certificate samples both sides (:mod:`simcheck.perturbations`); the other
side's hinge is the estimated hinge line mirrored across the door's middle, along the door's width
(:func:`scenes.hinge_mirror.other_edge_origin`), with its axis reversed so that a positive angle still
swings the door outward.

Frames: world at q = 0, metres.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from planners.scene_urdf import read_scene_urdf
from scenes.description import ShapeKind
from scenes.hinge_mirror import other_edge_origin
from simcheck.errors import SimcheckInputError

__all__ = ["other_hinge_origin"]


def other_hinge_origin(scene_urdf: str | Path, joint: str, axis, origin) -> np.ndarray:
    """(3,) a point on the hinge line of ``joint``'s door at its other edge (the line parallel to ``axis``;
    hinged there, the door opens about the reversed axis).

    axis (3,), origin (3,) : the estimated hinge (world, q = 0). The door is the joint's child link's
    largest collision box; its thickness is the box's smallest extent across the axis. Raises
    :class:`SimcheckInputError` naming the file, joint and link when the joint or a box is missing.
    """
    model = read_scene_urdf(scene_urdf)
    j = model.joints.get(joint)
    if j is None:
        raise SimcheckInputError(f"{scene_urdf}: joint {joint!r}: not in the scene")
    boxes = [s for s in model.links[j.child].collisions if s.kind is ShapeKind.BOX]
    if not boxes:
        raise SimcheckInputError(f"{scene_urdf}: joint {joint!r}: its hinge side is undecided (graph.json) but its "
                                 f"door link {j.child!r} has no collision box to find its other edge from; add one "
                                 f"or drop side_undecided")
    door = max(boxes, key=lambda s: float(np.prod(s.size)))
    return other_edge_origin(origin, axis, model.T_world_link(j.child) @ door.T_link_shape, door.size)
