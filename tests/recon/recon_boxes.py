"""Box primitives for the recon unit tests (a module beside the tests; tests/recon/conftest.py makes it
importable, prefixed ``recon_`` so it cannot shadow another package's test helpers)."""

import numpy as np
from scipy.spatial.transform import Rotation

from recon.config import ReconConfig
from recon.primitive import Primitive

CFG = ReconConfig()


def box(lo, hi, rotvec=(0, 0, 0)) -> Primitive:
    """A box spanning ``lo``..``hi`` (3,) metres in its own frame, rotated by ``rotvec`` (rad) about its centre."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec(rotvec).as_matrix()
    T[:3, 3] = (lo + hi) / 2
    return Primitive("box", hi - lo, T)


def planes(p: Primitive):
    """The surface planes of ``p`` as the contact stage sees them (default config)."""
    return p.planes(CFG.contacts.cylinder_side_faces)


def carcass_points(rng: np.random.Generator, m: int = 1500) -> tuple[np.ndarray, np.ndarray]:
    """(points (2m, 3), normals (2m, 3)) of a 0.5 x 0.52 x 0.8 m carcass (x from 0 to its front at 0.5) seen on
    its two sides (y = -+0.26) and its top (z = 0.8), m points each, noise-free."""
    side = np.c_[rng.uniform(0.0, 0.5, m), np.where(rng.random(m) < 0.5, -0.26, 0.26), rng.uniform(0.0, 0.8, m)]
    side_n = np.c_[np.zeros(m), np.sign(side[:, 1]), np.zeros(m)]
    top = np.c_[rng.uniform(0.0, 0.5, m), rng.uniform(-0.26, 0.26, m), np.full(m, 0.8)]
    return np.concatenate([side, top]), np.concatenate([side_n, np.tile([0.0, 0.0, 1.0], (m, 1))])
