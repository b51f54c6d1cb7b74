"""Two-window manoeuvre detector on filter-output velocities (Fisenko et al. 2008, eqs. (3)-(14)).

The data are ``2n`` consecutive velocity estimates: an older window ``v_1`` and a newer one
``v_2``. The shift group ``g v = (v_1 - D, v_2 - D)`` (eq. 8) leaves the hypotheses
"no manoeuvre" ``v̄_1 = v̄_2`` and "manoeuvre" invariant; its maximal invariant is
``z = v_1 - v_2`` (eq. 10). For a common offset of the true velocities between the windows the
likelihood ratio of ``z`` is monotone in ``sum z_k``, so the invariant test is (eq. 14)::

    |S| > c(alpha),   S = sum_{k=1}^n (v_1k - v_2k).

Under no manoeuvre ``S ~ N(0, sigma_S^2)`` and ``c(alpha) = sigma_S Phi^{-1}(1 - alpha/2)``
(card §4.3). ``sigma_S`` is computed

* as the paper assumes, from independent samples: ``sigma_S^2 = 2 n sigma_v^2`` (eq. 12 with
  the card's factor-2 correction), :func:`variance_independent`;
* correctly, from the autocovariance ``r(m)`` of the stationary velocity error,
  :func:`variance_stationary` (``r`` from :func:`tvtrack.filters.alphabeta.lagged_covariances`);
* exactly for a time-varying gain schedule from the filter's impulse responses,
  :func:`scheduled_statistic_std`;
* or by simulation under no manoeuvre, :func:`calibrate_threshold`.
"""

from __future__ import annotations

import numpy as np
from scipy import stats

from ..filters.alphabeta import lagged_covariances, scheduled_filter
from ..montecarlo import Estimate, quantile_ci

__all__ = ["window_statistic", "window_sum_of_squares", "threshold_from_std", "variance_independent", "variance_stationary",
           "velocity_autocovariance", "statistic_std", "scheduled_statistic_std", "calibrate_threshold"]


def _check_window(n) -> int:
    if not (isinstance(n, (int, np.integer)) and n >= 1):
        raise ValueError(f"parameter 'n' (window length) = {n!r}; it must be an integer >= 1")
    return int(n)


def _check_alpha(alpha) -> float:
    if not (0 < alpha < 1):
        raise ValueError(f"parameter 'alpha' = {alpha!r}; it must be in (0, 1)")
    return float(alpha)


def window_statistic(v, n: int) -> np.ndarray:
    """``S_t = sum(v[t-2n+1 .. t-n]) - sum(v[t-n+1 .. t])`` along the last axis (eq. 14).

    Parameters
    ----------
    v : array_like, shape (..., T)
        Velocity estimates, elements/frame.
    n : int
        Half-window length, frames.

    Returns
    -------
    ndarray, shape (..., T)
        NaN for ``t < 2n-1`` (window not full) or where a window holds a NaN.
    """
    n = _check_window(n)
    v = np.asarray(v, dtype=float)
    T = v.shape[-1]
    c = np.concatenate([np.zeros(v.shape[:-1] + (1,)), np.cumsum(v, axis=-1)], axis=-1)
    S = np.full(v.shape, np.nan)
    if T >= 2 * n:
        t = np.arange(2 * n - 1, T)
        older = c[..., t - n + 1] - c[..., t - 2 * n + 1]
        newer = c[..., t + 1] - c[..., t - n + 1]
        S[..., t] = older - newer
    return S


def window_sum_of_squares(v, n: int) -> np.ndarray:
    """``Q_t = sum_k (v_1k - v_2k)^2`` over the two windows ending at ``t`` (last axis).

    The invariant GLR statistic against an *arbitrary* offset vector between the windows
    (card §3, "gap in the derivation"), for comparison with :func:`window_statistic`, which
    is optimal only against a common offset. NaN for ``t < 2n-1``.
    """
    n = _check_window(n)
    v = np.asarray(v, dtype=float)
    T = v.shape[-1]
    Q = np.full(v.shape, np.nan)
    if T >= 2 * n:
        d2 = (v[..., n:] - v[..., :-n]) ** 2                      # d2[j] = (v[j+n] - v[j])^2
        c = np.concatenate([np.zeros(v.shape[:-1] + (1,)), np.cumsum(d2, axis=-1)], axis=-1)
        t = np.arange(2 * n - 1, T)
        Q[..., t] = c[..., t - n + 1] - c[..., t - 2 * n + 1]
    return Q


def threshold_from_std(alpha: float, sigma_S) -> np.ndarray:
    """``c(alpha) = sigma_S Phi^{-1}(1 - alpha/2)``: two-sided Gaussian threshold (eq. 13-14)."""
    _check_alpha(alpha)
    return np.asarray(sigma_S, dtype=float) * stats.norm.isf(alpha / 2)


def variance_independent(n: int, sigma_v: float) -> float:
    """``var S = 2 n sigma_v^2`` under the paper's independence assumption, with the factor 2
    of ``var(v_1k - v_2k)`` that eq. (12) omits."""
    n = _check_window(n)
    return 2.0 * n * float(sigma_v) ** 2


def variance_stationary(r, n: int) -> float:
    """``var S`` for a stationary sequence with autocovariance ``r(m)``, m = 0..2n-1 (card §4.3b)::

        var S = 2 [n r(0) + 2 sum_{m=1}^{n-1} (n-m) r(m)] - 2 sum_{L=1}^{2n-1} (n - |L-n|) r(L)

    Parameters
    ----------
    r : array_like, shape (>= 2n,)
    """
    n = _check_window(n)
    r = np.asarray(r, dtype=float)
    if r.shape[0] < 2 * n:
        raise ValueError(f"autocovariance has {r.shape[0]} lags; the window n={n} needs {2 * n}")
    m = np.arange(1, n)
    var_window = n * r[0] + 2 * np.sum((n - m) * r[m])
    L = np.arange(1, 2 * n)
    cross = np.sum((n - np.abs(L - n)) * r[L])
    return float(2 * var_window - 2 * cross)


def velocity_autocovariance(K, sigma_eps: float, max_lag: int) -> np.ndarray:
    """``r(m) = [A^m P]_{vv}``, m = 0..max_lag: autocovariance of the velocity error of the
    frozen filter with gains ``K`` (card §4.2). Shape (max_lag+1,)."""
    return lagged_covariances(K, sigma_eps, max_lag)[:, 1, 1]


def statistic_std(K, sigma_eps: float, n: int, method: str = "correlated") -> float:
    """``sigma_S`` for the frozen filter ``K``.

    Parameters
    ----------
    method : {"correlated", "independent"}
        ``"correlated"``: :func:`variance_stationary` with the Lyapunov autocovariance;
        ``"independent"``: the paper's assumption, :func:`variance_independent` with the
        stationary velocity RMS.
    """
    n = _check_window(n)
    r = velocity_autocovariance(K, sigma_eps, 2 * n)
    if method == "correlated":
        return float(np.sqrt(variance_stationary(r, n)))
    if method == "independent":
        return float(np.sqrt(variance_independent(n, np.sqrt(r[0]))))
    raise ValueError(f"parameter 'method' = {method!r}; it must be 'correlated' or 'independent'")


def scheduled_statistic_std(gains, n: int, sigma_eps: float) -> np.ndarray:
    """Exact ``sigma_S(t)`` for a filter with time-varying gains started at frame 0.

    The velocity noise is linear in the measurement noise, ``v_t = sum_j G[t, j] eps_j``; the
    columns of ``G`` are the filter's responses to unit impulses (run batched). Then
    ``S_t = u_t^T G eps`` and ``sigma_S(t)^2 = sigma_eps^2 |G^T u_t|^2`` (card §4.3,
    "time-varying gains").

    Parameters
    ----------
    gains : array_like, shape (T, order+1)
    n : int
    sigma_eps : float

    Returns
    -------
    ndarray, shape (T,)
        NaN for ``t < 2n-1``.
    """
    n = _check_window(n)
    G = np.asarray(gains, dtype=float)
    T = G.shape[0]
    responses = scheduled_filter(np.eye(T), G)[..., 1]     # (j, t): velocity at t from impulse at j
    W = window_statistic(responses, n)                      # (j, t): weight of eps_j in S_t
    return sigma_eps * np.sqrt(np.sum(W**2, axis=0))


def calibrate_threshold(gains, n: int, alpha: float, frames, n_sims: int, rng: np.random.Generator,
                        sigma_eps: float = 1.0, confidence: float = 0.95) -> Estimate:
    """Threshold by simulation under no manoeuvre: the ``1 - alpha`` quantile of ``|S_t|``.

    White Gaussian noise of RMS ``sigma_eps`` on a constant-velocity truth (the filter is
    invariant to it, so zero truth is used) runs through the filter with ``gains``; ``|S_t|`` is
    pooled over ``frames`` (marginal quantile), one value per simulation and frame.

    Parameters
    ----------
    gains : array_like, shape (T, order+1)
    frames : array_like of int
        Frames at which the test is made (each >= 2n-1).
    n_sims : int
        Independent simulated runs.

    Returns
    -------
    Estimate
        The quantile with its order-statistic confidence interval (over simulations x frames;
        the interval assumes independent values, so it is optimistic when several correlated
        frames are pooled).
    """
    n = _check_window(n)
    _check_alpha(alpha)
    frames = np.atleast_1d(np.asarray(frames, dtype=int))
    if np.any(frames < 2 * n - 1) or np.any(frames >= np.asarray(gains).shape[0]):
        raise ValueError(f"parameter 'frames' must lie in [{2 * n - 1}, {np.asarray(gains).shape[0] - 1}]")
    if n_sims < 1:
        raise ValueError(f"parameter 'n_sims' = {n_sims}; it must be >= 1")
    T = int(frames.max()) + 1
    eps = sigma_eps * rng.standard_normal((n_sims, T))
    v = scheduled_filter(eps, np.asarray(gains, dtype=float)[:T])[..., 1]
    S = window_statistic(v, n)[:, frames]
    return quantile_ci(np.abs(S), 1 - alpha, confidence)
