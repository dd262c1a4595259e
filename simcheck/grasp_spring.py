"""The grasp attachment's spring law (pure numpy): a force-capped spring-damper between the robot's tool
frame origin and the held point of a scene link, world frame, N and metres.

The adapter (:meth:`simcheck.world.World.attach`) reads the two points' states every step, applies the
force returned here as equal and opposite external forces, and moves the held point when it slides.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["GraspSpring", "spring_force"]


@dataclass
class GraspSpring:
    """A grasp attachment's state.

    body, index : the held scene link (PyBullet body id and link index)
    p_local : (3,) the held point in the link's frame, m (moves when the handle slides)
    stiffness : N/m; damping : N*s/m; cap : the largest force the grasp transmits, N
    force : the norm of the force holding the point took in the last step, before the cap, N
    slid : the force has reached the cap since the grasp was made
    """

    body: int
    index: int
    p_local: np.ndarray
    stiffness: float
    damping: float
    cap: float
    force: float = 0.0
    slid: bool = False


def spring_force(spring: GraspSpring, p_held: np.ndarray, v_held: np.ndarray, p_tool: np.ndarray,
                 v_tool: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
    """(force (3,) N on the held point (its opposite acts on the tool), the point the held point slides
    to (3,) world m, or None when it holds), from the held point's and the tool's positions (3,) m and
    velocities (3,) m/s. Records the uncapped force and the slide in ``spring``.

    The force is ``stiffness * stretch + damping * relative velocity`` capped at ``spring.cap``; when the
    stretch alone exceeds ``cap / stiffness`` the held point slides toward the tool so that the spring
    stays at the cap."""
    stretch = p_tool - p_held
    f = spring.stiffness * stretch + spring.damping * (v_tool - v_held)
    norm = float(np.linalg.norm(f))
    spring.force = norm
    slide_to = None
    if norm > spring.cap:
        f *= spring.cap / norm
        spring.slid = True
        s = float(np.linalg.norm(stretch))
        if s > spring.cap / spring.stiffness:
            slide_to = p_tool - stretch * (spring.cap / spring.stiffness / s)
    return f, slide_to
