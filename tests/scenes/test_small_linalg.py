"""scenes.small_linalg: numpy.linalg's results to the bit, numpy's errors on singular input."""

import numpy as np
import pytest

from scenes import small_linalg


@pytest.mark.parametrize("n", [3, 4, 6])
def test_same_bits_as_numpy_linalg(n):
    rng = np.random.default_rng(n)
    for _ in range(200):
        a = rng.normal(size=(n, n))
        spd = a @ a.T + 0.01 * np.eye(n)
        b = rng.normal(size=n)
        assert np.array_equal(small_linalg.solve(spd, b), np.linalg.solve(spd, b))
        assert np.array_equal(small_linalg.solve(a, b[:, None]), np.linalg.solve(a, b[:, None]))
        assert np.array_equal(small_linalg.inv(a), np.linalg.inv(a))
        w, v = small_linalg.eigh(spd)
        assert np.array_equal(w, np.linalg.eigh(spd)[0]) and np.array_equal(v, np.linalg.eigh(spd)[1])
    view = rng.normal(size=(6, 7))[:, 1:]          # strided input, as Jacobian column slices are
    assert np.array_equal(small_linalg.inv(view), np.linalg.inv(view))


def test_vector_norm_same_bits_as_numpy():
    rng = np.random.default_rng(1)
    for scale in (1e-300, 1e-12, 1.0, 1e6, 1e150):
        for n in (1, 3, 6):
            for _ in range(200):
                x = rng.normal(size=n) * scale
                assert small_linalg.norm(x) == float(np.linalg.norm(x))
    assert small_linalg.norm(np.zeros(3)) == 0.0
    assert np.isnan(small_linalg.norm(np.array([1.0, np.nan, 0.0])))
    assert small_linalg.norm(np.array([np.inf, 0.0, 1.0])) == np.inf


def test_singular_matrix_raises_numpys_error():
    with pytest.raises(np.linalg.LinAlgError):
        small_linalg.solve(np.zeros((3, 3)), np.ones(3))
    with pytest.raises(np.linalg.LinAlgError):
        small_linalg.inv(np.zeros((3, 3)))
