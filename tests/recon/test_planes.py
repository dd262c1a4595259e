"""recon.planes: RANSAC planes are the seen faces with outward normals."""

import numpy as np
import trimesh

from recon.config import ReconConfig
from recon.planes import ransac_planes

CFG = ReconConfig()


def at(x, y, z):
    T = np.eye(4)
    T[:3, 3] = [x, y, z]
    return T


def test_ransac_planes_are_the_seen_faces_with_outward_normals():
    mesh = trimesh.creation.box([0.4, 0.6, 0.8], transform=at(1, 0, 0.4))
    pts, _ = trimesh.sample.sample_surface(mesh, 6000, seed=0)
    planes = ransac_planes(pts, CFG.contacts, seed=0)
    assert len(planes) == 6
    for pl in planes:
        assert pl.normal @ np.array([1, 0, 0.4]) + pl.d < 0                # centre behind the face
        k = int(np.argmax(np.abs(pl.normal)))
        assert abs(pl.normal[k]) > 0.999
        assert abs(abs(pl.d + pl.normal[k] * [1, 0, 0.4][k]) - [0.2, 0.3, 0.4][k]) < 0.005
