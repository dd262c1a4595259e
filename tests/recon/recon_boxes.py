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
