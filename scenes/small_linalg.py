"""``numpy.linalg.solve``, ``inv``, ``eigh`` and ``norm`` for the small float64 matrices and vectors of inner
loops (IK steps, the grasp spring of every physics step), without numpy's per-call argument checks.

Each calls the same LAPACK kernel as its ``numpy.linalg`` namesake (numpy's own ``_umath_linalg``
gufunc), so the result is the same to the bit; on 3x3 to 6x6 matrices a call costs ~8 us instead of
~30-40 us. A result that is not finite (a singular matrix, a NaN input) is computed again by the
``numpy.linalg`` function itself, which raises its ``LinAlgError`` or returns what it returns, so the
errors are numpy's too. Without ``_umath_linalg`` (a numpy that renames it) these are numpy's functions.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["solve", "inv", "eigh", "norm"]

try:
    from numpy.linalg import _umath_linalg as _kernels
except ImportError:  # pragma: no cover - numpy 2.x ships it; fall back to the checked functions
    _kernels = None

try:    # numpy's floating-point error state, set directly: ``np.errstate(all="ignore")`` costs ~2 us a use
    from numpy._core._ufunc_config import _extobj_contextvar as _fp_state, _make_extobj
    _FP_IGNORE = _make_extobj(all="ignore")
except ImportError:  # pragma: no cover - a numpy that moved them: np.errstate
    _fp_state = None


def _quiet(kernel, *args, **kwargs):
    """(``kernel(*args, **kwargs)``, True when every entry of its result (an array or a pair of arrays) is
    finite), computed with floating-point errors ignored (as inside ``np.errstate(all="ignore")``). The test
    is on the entries' sum (any NaN or infinity makes it non-finite; a sum of finite entries that overflows
    only sends the caller to numpy's own function, which returns the same result)."""
    if _fp_state is None:   # pragma: no cover
        with np.errstate(all="ignore"):
            out = kernel(*args, **kwargs)
            return out, all(np.isfinite(x).all() for x in (out if isinstance(out, tuple) else (out,)))
    token = _fp_state.set(_FP_IGNORE)
    try:
        out = kernel(*args, **kwargs)
        total = _sum(out[0], None) + _sum(out[1], None) if isinstance(out, tuple) else _sum(out, None)
        return out, math.isfinite(total)
    finally:
        _fp_state.reset(token)


_sum = np.add.reduce


def solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``numpy.linalg.solve(a, b)`` for a float64 ``a (n, n)`` and ``b (n,)`` or ``(n, k)``."""
    if _kernels is None:
        return np.linalg.solve(a, b)
    x, finite = _quiet(_kernels.solve1 if np.ndim(b) == 1 else _kernels.solve, a, b, signature="dd->d")
    return x if finite else np.linalg.solve(a, b)


def inv(a: np.ndarray) -> np.ndarray:
    """``numpy.linalg.inv(a)`` for a float64 ``a (n, n)``."""
    if _kernels is None:
        return np.linalg.inv(a)
    x, finite = _quiet(_kernels.inv, a, signature="d->d")
    return x if finite else np.linalg.inv(a)


def eigh(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``numpy.linalg.eigh(a)`` (lower triangle) for a float64 symmetric ``a (n, n)``: (eigenvalues (n,)
    ascending, eigenvectors (n, n) as columns)."""
    if _kernels is None:
        return tuple(np.linalg.eigh(a))
    (w, v), finite = _quiet(_kernels.eigh_lo, a, signature="d->dd")
    return (w, v) if finite else tuple(np.linalg.eigh(a))


def norm(x: np.ndarray) -> float:
    """``float(numpy.linalg.norm(x))`` for a float64 vector ``x (n,)``: the same ``sqrt(x.dot(x))`` numpy
    computes (both square roots are IEEE's, correctly rounded), without its argument handling (~0.8 us
    instead of ~2.3)."""
    return math.sqrt(x.dot(x))
