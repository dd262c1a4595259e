"""The grasp attachment's spring law (pure numpy): a force-capped spring-damper between the robot's tool
frame origin and the held point of a scene link, world frame, N and metres.

The adapter (:meth:`simcheck.world.World.attach`) reads the two points' states every step, applies the
force returned here as equal and opposite external forces, and moves the held point when it slides.
The spring's stiffness is a (3, 3) matrix: the arm's Cartesian stiffness at the tool under its joint
impedance (:func:`cartesian_stiffness`), or an isotropic one; it is capped where the explicit, once per
step integration of the spring stays stable (:func:`stable_stiffness`), and so is its damping
(:func:`stable_damping`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from scenes.small_linalg import eigh, inv, norm as vector_norm

__all__ = ["GraspSpring", "spring_force", "cartesian_stiffness", "stable_stiffness", "stable_damping"]


@dataclass
class GraspSpring:
    """A grasp attachment's state.

    body, index : the held scene link (PyBullet body id and link index)
    p_local : (3,) the held point in the link's frame, m (moves when the handle slides)
    stiffness : (3, 3) N/m, or one number (isotropic); the adapter updates it when it follows the arm's
        configuration; damping :
        N*s/m; cap : the largest force the grasp transmits, N
    max_stiffness : stiffness eigenvalues above this, N/m, are lowered to it (``inf``: none)
    max_damping : damping above this, N*s/m, is lowered to it (``inf``: none)
    p_local0 : (3,) the held point in the link's frame when the grasp was made, m (default: ``p_local``)
    force : the norm of the force holding the point took in the last step, before the cap, N
    slid : the force has reached the cap since the grasp was made
    steps : the physics steps the spring has acted (its adapter counts them)

    ``stiffness`` is replaced, never changed in place: :func:`spring_force` keeps the capped matrix of the
    stiffness object it last saw.
    """

    body: int
    index: int
    p_local: np.ndarray
    stiffness: np.ndarray | float
    damping: float
    cap: float
    max_stiffness: float = float("inf")
    max_damping: float = float("inf")
    p_local0: np.ndarray | None = None
    force: float = 0.0
    slid: bool = False
    steps: int = 0
    _capped: tuple = field(default=(None, None), init=False, repr=False, compare=False)  # (stiffness, capped)

    def __post_init__(self) -> None:
        if self.p_local0 is None:
            self.p_local0 = np.array(self.p_local, dtype=float)

    def capped_stiffness(self) -> np.ndarray:
        """(3, 3) N/m: ``stiffness`` as a matrix with its eigenvalues lowered to ``max_stiffness``; computed once
        per stiffness object."""
        of, K = self._capped
        if of is self.stiffness:
            return K
        K = np.asarray(self.stiffness, dtype=float)
        if K.ndim == 0:
            K = float(K) * np.eye(3)
        # else no eigenvalue is above it (Gershgorin; the rows' sums as numpy's sum(axis=1) adds them)
        if max(abs(a) + abs(b) + abs(c) for a, b, c in K.tolist()) > self.max_stiffness:
            w, V = eigh(K)
            if w.max() > self.max_stiffness:
                K = (V * np.minimum(w, self.max_stiffness)) @ V.T
        self._capped = (self.stiffness, K)
        return K

    @property
    def slide(self) -> float:
        """How far, m, the held point has slid on the link since the grasp was made (above the cap)."""
        return vector_norm(np.asarray(self.p_local, dtype=float) - self.p_local0)


def cartesian_stiffness(J: np.ndarray, joint_stiffness: np.ndarray) -> np.ndarray:
    """(3, 3) translational stiffness, N/m, at a point whose (3, n) linear Jacobian over n joints is ``J``
    (m per rad or m) when each joint is held by a spring of ``joint_stiffness`` (n,) N*m/rad (N/m):
    ``(J C_q J^T)^-1`` with ``C_q`` the diagonal joint compliance. Joints left out of ``J`` are rigid."""
    J = np.asarray(J, dtype=float)
    return inv((J / np.asarray(joint_stiffness, dtype=float)) @ J.T)


def _smallest_effective_mass(J: np.ndarray, M: np.ndarray) -> float:
    """kg: ``1 / max eig(J M^-1 J^T)`` of a point with (3, n) linear Jacobian ``J`` on a body of (n, n) mass
    matrix ``M``; ``inf`` when the point cannot move."""
    J = np.asarray(J, dtype=float)
    if not J.size:
        return float("inf")
    top = float(np.linalg.eigvalsh(J @ np.linalg.solve(np.asarray(M, dtype=float), J.T)).max())
    return float("inf") if top <= 1e-12 else 1.0 / top


def stable_damping(J: np.ndarray, M: np.ndarray, time_step: float) -> float:
    """Largest damping, N*s/m, of a damper integrated explicitly once per ``time_step`` s on the point of
    :func:`stable_stiffness`: its smallest effective mass over the time step (one step then takes away at most
    the relative velocity, never reverses it; above twice that it diverges; docs/decisions.md has the part
    that needed it). ``inf`` when the point cannot move."""
    return _smallest_effective_mass(J, M) / time_step


def stable_stiffness(J: np.ndarray, M: np.ndarray, time_step: float) -> float:
    """Largest stiffness, N/m, of a spring integrated explicitly once per ``time_step`` s on a point of a
    body whose (3, n) linear Jacobian over its n joints is ``J`` and (n, n) mass matrix is ``M``: the
    point's smallest effective mass ``1 / max eig(J M^-1 J^T)``, kg, over ``2 * time_step**2`` (natural
    frequency x time step = 0.71, well inside the bound of 2 of an undamped oscillator: the held link,
    the hand under its position motors and the solver couple; at 1.0 a third-party microwave door's
    grasp still diverged). ``inf`` when the point cannot move."""
    return _smallest_effective_mass(J, M) / (2.0 * time_step ** 2)


def spring_force(spring: GraspSpring, p_held: np.ndarray, v_held: np.ndarray, p_tool: np.ndarray,
                 v_tool: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
    """(force (3,) N on the held point (its opposite acts on the tool), the point the held point slides
    to (3,) world m, or None when it holds), from the held point's and the tool's positions (3,) m and
    velocities (3,) m/s. Records the uncapped force and the slide in ``spring``.

    The force is ``K @ stretch + damping * relative velocity`` (``K``: ``spring.stiffness`` with its
    eigenvalues capped at ``spring.max_stiffness``, the damping at ``spring.max_damping``), capped at ``spring.cap``; when the spring force
    alone exceeds the cap, the held point slides toward the tool so that the spring stays at the cap."""
    K = spring.capped_stiffness()
    stretch = p_tool - p_held
    f_spring = K @ stretch
    f = f_spring + min(spring.damping, spring.max_damping) * (v_tool - v_held)
    norm = vector_norm(f)
    spring.force = norm
    slide_to = None
    if norm > spring.cap:
        f *= spring.cap / norm
        spring.slid = True
        pull = vector_norm(f_spring)
        if pull > spring.cap:
            slide_to = p_tool - stretch * (spring.cap / pull)
    return f, slide_to
