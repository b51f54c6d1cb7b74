"""Growing-memory polynomial filters (recursive least squares on a Taylor model).

The state of an order-``r`` filter is ``X_n = (x_n, x'_n, ..., x^(r)_n)``, derivatives per
sample (unit time step). An observation ``j`` samples back is ``Z_{n-j} = h_j X_n + noise`` with
``h_j = ((-j)^k / k!)_{k=0..r}`` (Kokryatska & Hrynchyshyn 2005, eqs. (2)-(3) as corrected
here: the entry printed ``i^2/i`` is ``i^2/2``, and the rows run over the lags ``j = 0..k-1``
where the printed matrix starts at lag ``k``). With no process noise the least-squares estimate
over all ``N`` observations, eq. (4), obeys the recursion (5)-(6)::

    X^- = F_{+1} X            (eq. 5, with the forward matrix F_{+1} = F_{-1}^{-1})
    X   = X^- + g_N (Z - x^-) (eq. 6, g_N = M_N^{-1} h_0^T,  M_N = sum_{j<N} h_j^T h_j)

so the gains depend only on ``N`` and are computed once. For ``r = 2``,
``g_N = (3(3N^2-3N+2), 18(2N-1), 60) / (N(N+1)(N+2))``. A *gain floor* ``N_f`` stops the
gains decreasing after ``N_f`` samples (``g_N = g_{N_f}`` for ``N > N_f``), which turns the
filter into a fixed-gain alpha-beta(-gamma) filter with a finite bandwidth.
"""

from __future__ import annotations

from math import factorial

import numpy as np

__all__ = [
    "taylor_transition",
    "polynomial_observation_row",
    "growing_memory_gains",
    "growing_memory_filter",
    "predict_ahead",
]

_MAX_ORDER = 3


def _check_order(order: int) -> None:
    if not (isinstance(order, (int, np.integer)) and 0 <= order <= _MAX_ORDER):
        raise ValueError(f"parameter 'order' = {order!r}; it must be an integer in [0, {_MAX_ORDER}]")


def taylor_transition(order: int, steps: float = 1.0) -> np.ndarray:
    """``F`` (order+1, order+1) moving a Taylor state ``steps`` samples forward
    (``F[i, j] = steps^(j-i)/(j-i)!``; ``steps = -i`` gives the paper's ``F_{-i}``)."""
    _check_order(order)
    n = order + 1
    F = np.zeros((n, n))
    for i in range(n):
        for j in range(i, n):
            F[i, j] = steps ** (j - i) / factorial(j - i)
    return F


def polynomial_observation_row(order: int, lag) -> np.ndarray:
    """``h_j = ((-j)^k / k!)``: how the observation ``lag = j`` samples back sees ``X_n``.

    Returns shape (..., order+1) for ``lag`` of shape (...)."""
    _check_order(order)
    j = np.asarray(lag, dtype=float)[..., None]
    k = np.arange(order + 1)
    return (-j) ** k / np.array([factorial(int(i)) for i in k])


def growing_memory_gains(order: int, n_max: int) -> np.ndarray:
    """Gains ``g_N = M_N^{-1} h_0^T`` for ``N = 1..n_max`` samples.

    ``g_N`` is defined from ``N = order+1`` on; earlier rows are NaN (the estimate does not
    exist yet). Computed in the scaled basis ``(-j/N)^k`` so that the normal equations stay
    well conditioned for large ``N``.

    Returns
    -------
    ndarray, shape (n_max, order+1)
    """
    _check_order(order)
    if n_max < 1:
        raise ValueError(f"n_max = {n_max} must be >= 1")
    n = order + 1
    N = np.arange(1, n_max + 1, dtype=float)
    j = np.arange(n_max, dtype=float)
    p = np.arange(2 * order + 1)
    # power sums S_p(N) = sum_{j<N} j^p, scaled by N^p
    S = np.cumsum(j[:, None] ** p, axis=0) / N[:, None] ** p
    a = np.arange(n)
    A = S[:, a[:, None] + a[None, :]] * (-1.0) ** (a[:, None] + a[None, :])
    g = np.full((n_max, n), np.nan)
    ok = N >= n
    e0 = np.zeros(n)
    e0[0] = 1.0
    scaled = np.linalg.solve(A[ok], np.broadcast_to(e0, (ok.sum(), n))[..., None])[..., 0]
    fact = np.array([factorial(int(k)) for k in a], dtype=float)
    g[ok] = scaled * fact / N[ok, None] ** a
    return g


def growing_memory_filter(z, order: int = 2, floor_memory: int | None = None) -> np.ndarray:
    """Run the growing-memory filter along the last axis of ``z``.

    Parameters
    ----------
    z : array_like, shape (..., T)
        Measurements, one per sample; NaN marks a missing sample (the filter coasts: it
        predicts, and the memory count does not grow). After a gap the gains are those of
        consecutive samples, so the estimate is then close to, but not exactly, the least-squares
        fit over the samples present; without gaps after the start it is exact.
    order : int
        Polynomial order ``r`` in [0, 3] (2 = the paper's constant-acceleration model).
    floor_memory : int, optional
        ``N_f``: the memory after which the gains stop decreasing (``>= order+1``);
        ``None`` = no floor (pure growing memory).

    Returns
    -------
    ndarray, shape (..., T, order+1)
        Filtered states (value, derivatives per sample) after each sample; NaN until
        ``order+1`` samples have arrived. The first defined state is the exact polynomial
        through the first ``order+1`` samples, as eq. (4) prescribes.
    """
    _check_order(order)
    z = np.asarray(z, dtype=float)
    n = order + 1
    if floor_memory is not None and floor_memory < n:
        raise ValueError(f"parameter 'floor_memory' = {floor_memory}; it must be >= order+1 = {n} or None")
    T = z.shape[-1]
    n_max = T if floor_memory is None else min(T, floor_memory)
    gains = growing_memory_gains(order, max(n_max, n))
    F = taylor_transition(order)
    batch = z.shape[:-1]
    present = np.isfinite(z)
    count_after = np.cumsum(present, axis=-1)  # samples received up to and including t
    # (eq. 4) the first estimate: the exact polynomial through the first order+1 samples
    first_times = np.stack([np.argmax(present & (count_after == k + 1), axis=-1) for k in range(n)], -1)
    start = first_times[..., -1]
    ready = count_after[..., -1] >= n
    lags = start[..., None] - first_times
    H0 = polynomial_observation_row(order, np.where(ready[..., None], lags, np.arange(n)[::-1]))
    z0 = np.where(ready[..., None], np.take_along_axis(z, first_times, axis=-1), 0.0)
    x = np.linalg.solve(H0, z0[..., None])[..., 0]
    states = np.full(batch + (T, n), np.nan)
    for t in range(T):
        running = ready & (t > start)
        x = np.where(running[..., None], x @ F.T, x)  # (eq. 5) predict
        # (eq. 6) correct with the gain for N = samples so far, frozen at the floor
        g = gains[np.minimum(count_after[..., t], gains.shape[0]) - 1]
        upd = running & present[..., t]
        innovation = np.where(upd, z[..., t] - x[..., 0], 0.0)
        x = x + np.where(upd[..., None], g, 0.0) * innovation[..., None]
        states[..., t, :] = np.where((ready & (t >= start))[..., None], x, np.nan)
    return states


def predict_ahead(states, steps: int | np.ndarray = 1) -> np.ndarray:
    """Value ``steps`` samples ahead of each Taylor state: ``sum_k steps^k/k! x^(k)``.

    Parameters
    ----------
    states : ndarray, shape (..., order+1)
    steps : int or ndarray broadcastable to ``states.shape[:-1]``

    Returns
    -------
    ndarray, shape (...)
    """
    s = np.asarray(states, dtype=float)
    order = s.shape[-1] - 1
    m = np.asarray(steps, dtype=float)[..., None]
    k = np.arange(order + 1)
    coeff = m**k / np.array([factorial(int(i)) for i in k])
    return np.sum(s * coeff, axis=-1)
