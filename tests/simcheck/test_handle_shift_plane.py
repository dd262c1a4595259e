"""The perceived handle's error is kept in the plane of the part's front: it moves where the handle is seen,
not how far the bar stands out of its own front (recon's geometry)."""

import numpy as np
import pytest

from simcheck.perturbations import front_normal, in_front_plane


def test_a_doors_front_normal_is_across_its_hinge_and_lever():
    # vertical hinge at x = 0.45, y = 2.0; the door spans +x, its bar 1.8 cm proud toward -y (kitchen 5's microwave)
    n = front_normal("revolute", (0.0, 0.0, -1.0), (0.448, 1.995, 0.971), (0.729, 1.977, 0.971))
    assert abs(n @ (0.0, 1.0, 0.0)) == pytest.approx(1.0, abs=0.005)
    shift = in_front_plane((0.002, 0.009, -0.004), n)                      # 9 mm into the door: dropped
    assert abs(np.asarray(shift) @ n) < 1e-12
    assert shift[0] == pytest.approx(0.002, abs=1e-3) and shift[2] == pytest.approx(-0.004)


def test_a_drawers_front_normal_is_its_axis_and_undefined_cases_keep_the_shift():
    n = front_normal("prismatic", (2.0, 0.0, 0.0), (0.0, 0.0, 0.0), (0.3, 0.0, 0.7))
    assert np.allclose(n, (1.0, 0.0, 0.0))
    assert in_front_plane((0.005, 0.003, -0.002), n) == pytest.approx((0.0, 0.003, -0.002))
    assert front_normal("revolute", (0.0, 0.0, 1.0), (0.0, 0.0, 0.0), (0.0, 0.0, 0.5)) is None   # on the hinge line
    assert in_front_plane((0.001, 0.002, 0.003), None) == (0.001, 0.002, 0.003)
