"""recon.primitive: volume and inertia against trimesh, surface samples on the surface, planes pointing
outward."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from recon.primitive import Primitive


def pose(rotvec=(0, 0, 0), t=(0, 0, 0)):
    T = np.eye(4)
    T[:3, :3] = Rotation.from_rotvec(rotvec).as_matrix()
    T[:3, 3] = t
    return T


@pytest.mark.parametrize("kind, size", [("box", [0.3, 0.5, 0.7]), ("cylinder", [0.2, 0.2, 0.9]),
                                        ("sphere", [0.4, 0.4, 0.4])])
def test_volume_and_inertia_match_trimesh(kind, size):
    prim = Primitive(kind, size, pose((0.3, -0.2, 0.5), (1, 2, 3)))
    mesh = prim.to_trimesh()
    # a 32-gon cylinder / icosphere are slightly smaller than the true shapes: 1.5 % covers both
    assert prim.volume == pytest.approx(mesh.volume, rel=0.015)
    mass = 7.0
    mesh.density = mass / mesh.volume
    I_world = prim.T_world_part[:3, :3] @ prim.inertia(mass) @ prim.T_world_part[:3, :3].T
    np.testing.assert_allclose(I_world, mesh.moment_inertia, rtol=0.03, atol=1e-4)


def test_surface_samples_lie_on_the_surface_and_planes_point_outward():
    rng = np.random.default_rng(0)
    for kind, size in [("box", [0.3, 0.5, 0.7]), ("cylinder", [0.2, 0.2, 0.9]), ("sphere", [0.4] * 3)]:
        prim = Primitive(kind, size, pose((0.1, 0.2, 0.3), (0.5, 0, 1)))
        pts, face = prim.sample_surface(500, rng)
        assert np.max(prim.surface_distance(pts)) < 1e-9
        assert face.min() >= 0 and len(np.unique(face)) >= 6
        for pl in prim.planes():
            assert pl.normal @ prim.center + pl.d < 0            # centre is behind every face
            assert np.allclose(pl.polygon @ pl.normal + pl.d, 0, atol=1e-9)
    with pytest.raises(ValueError, match="positive and finite"):
        Primitive("box", [0.1, -0.2, 0.3], np.eye(4))
    with pytest.raises(ValueError, match=r"\(4, 4\) pose"):
        Primitive("box", [0.1, 0.2, 0.3], np.eye(3))
