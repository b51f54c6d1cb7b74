"""Compiled summed column variance of bootstrap resamples (numba), the twin of ``e.var(axis=1, ddof=1).sum(axis=-1)``.

The claims' bootstrap evaluates the gain's variance sums on every resample (arrays of 2000 x n_trials x k errors); NumPy
does it in four passes with temporaries. This kernel does the same arithmetic in NumPy's order: each column's sum
over the trials one after the other (NumPy reduces a non-innermost axis row by row), divided by n; the squared
deviations summed the same way and divided by n - 1; the k column variances summed as NumPy sums a contiguous last
axis (pairwise: one after the other below 8 terms, from 8 eight running sums added in pairs), so the same bits
(``tests/papers/test_002_em_trials.py`` compares the two on the shapes the claims use).
"""

from __future__ import annotations

import numpy as np

from tvtrack import jit
from tvtrack.jit import njit

__all__ = ["variance_sum_rows"]


@njit
def _pairwise(a):  # pragma: no cover - compiled
    """``a.sum()`` of a contiguous 1-D array in NumPy's pairwise order (up to 128 terms)."""
    n = a.size
    if n < 8:
        res = 0.0
        for i in range(n):
            res += a[i]
        return res
    r = a[:8].copy()
    i = 8
    while i < n - (n % 8):
        for j in range(8):
            r[j] += a[i + j]
        i += 8
    res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]))
    while i < n:
        res += a[i]
        i += 1
    return res


@njit
def _variance_sum_rows(e):  # pragma: no cover - compiled
    n_rows, n, k = e.shape
    out = np.empty(n_rows)
    mean = np.empty(k)
    acc = np.empty(k)
    for b in range(n_rows):
        mean[:] = 0.0
        for i in range(n):
            for j in range(k):
                mean[j] += e[b, i, j]
        for j in range(k):
            mean[j] = mean[j] / n
        acc[:] = 0.0
        for i in range(n):
            for j in range(k):
                d = e[b, i, j] - mean[j]
                acc[j] += d * d
        for j in range(k):
            acc[j] = acc[j] / (n - 1)
        out[b] = _pairwise(acc)
    return out


def variance_sum_rows(e) -> np.ndarray:
    """``e.var(axis=1, ddof=1).sum(axis=-1)`` of errors ``e`` (B, n, k) (any unit; the result in its square),
    shape (B,): compiled where numba is used, the same bits as NumPy's (which it falls back to otherwise, and for
    anything but a float64 array (B, n, k) with n >= 2, 2 <= k <= 128 and k its innermost axis: with one column,
    or the trials innermost, NumPy sums over the trials pairwise instead)."""
    e = np.asarray(e)
    if not jit.enabled() or e.ndim != 3 or e.dtype != np.float64 or not _rows_outer(e):
        return e.var(axis=1, ddof=1).sum(axis=-1)
    return _variance_sum_rows(np.ascontiguousarray(e))  # one compiled layout (the same sums: it reads by index)


def _rows_outer(e) -> bool:
    """Whether NumPy reduces ``e`` (B, n, k) over the trials row by row: k in [2, 128] columns contiguous, the
    trial axis outside them and the resamples outside that."""
    n_rows, n, k = e.shape
    s0, s1, s2 = e.strides
    return n >= 2 and 2 <= k <= 128 and s2 == e.itemsize and s1 >= k * s2 and (n_rows == 1 or s0 >= n * s1)
