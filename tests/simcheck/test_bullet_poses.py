"""simcheck.bullet_poses: PyBullet's (position, quaternion x y z w) <-> T (4, 4), checked against scipy."""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from simcheck.bullet_poses import T_from_pos_quat, quat_xyzw_from_R


def test_T_from_pos_quat_matches_scipy_and_round_trips():
    rng = np.random.default_rng(0)
    for R in Rotation.random(20, random_state=1):
        p = rng.normal(size=3)
        T = T_from_pos_quat(p, R.as_quat())
        assert T.shape == (4, 4) and T.dtype == np.float64
        assert np.allclose(T[:3, :3], R.as_matrix(), atol=1e-12) and np.allclose(T[:3, 3], p)
        assert np.array_equal(T[3], [0, 0, 0, 1])
        assert np.allclose(T_from_pos_quat(p, quat_xyzw_from_R(T[:3, :3])), T, atol=1e-12)


def test_quat_xyzw_from_R_puts_w_last():
    assert np.allclose(quat_xyzw_from_R(np.eye(3)), (0, 0, 0, 1))
    x, y, z, w = quat_xyzw_from_R(Rotation.from_rotvec([0, 0, np.pi / 2]).as_matrix())
    assert np.allclose((x, y, z, w), (0, 0, np.sqrt(0.5), np.sqrt(0.5)))
