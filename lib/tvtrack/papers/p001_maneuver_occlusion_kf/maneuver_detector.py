"""Two-window manoeuvre detector on filter-output velocities (Fisenko et al. 2008, eqs. (3)-(14)).

The data are ``2n`` consecutive velocity estimates: an older window ``v_1`` and a newer one
``v_2``. The shift group ``g v = (v_1 - D, v_2 - D)`` (eq. 8) leaves the hypotheses
"no manoeuvre" ``v̄_1 = v̄_2`` and "manoeuvre" invariant; its maximal invariant is
``z = v_1 - v_2`` (eq. 10). For a common offset of the true velocities between the windows the
likelihood ratio of ``z`` is monotone in ``sum z_k``, so the invariant test is (eq. 14)::

    |S| > c(alpha),   S = sum_{k=1}^n (v_1k - v_2k).

Under no manoeuvre ``S ~ N(0, sigma_S^2)`` and ``c(alpha) = sigma_S Phi^{-1}(1 - alpha/2)``
(derived here from eq. 14). ``sigma_S`` is computed

* as the paper assumes, from independent samples: ``sigma_S^2 = 2 n sigma_v^2`` (eq. 12 with
  the factor 2 it misses: ``var z_k = 2 sigma_v^2``), :func:`variance_independent`;
* correctly, from the autocovariance ``r(m)`` of the stationary velocity error,
  :func:`variance_stationary` (``r`` from :func:`tvtrack.filters.alphabeta.lagged_covariances`);
* exactly for a time-varying gain schedule by a state-space recursion on the filter's error
  augmented with the two window sums (memory linear in the run length),
  :func:`scheduled_statistic_std` (checked against a simulation under no manoeuvre in the tests).
"""

from __future__ import annotations

import functools

import numpy as np
from scipy import stats

from ...filters.alphabeta import (
    error_covariance_sequence,
    gain_schedule,
    lagged_covariances,
    observation_row,
)
from ...filters.polynomial import taylor_transition
from ...estimate import Estimate
from ...montecarlo import mean_ci, quantile_ci
from ...counts import proportion_ci, zero_events_bound

__all__ = [
    "window_statistic",
    "window_sum_of_squares",
    "threshold_from_std",
    "variance_independent",
    "variance_stationary",
    "velocity_autocovariance",
    "statistic_std",
    "scheduled_statistic_std",
    "false_alarm_rates",
    "detection_time_summary",
    "null_quantile_threshold",
    "first_alarm_within",
    "track2_thresholds",
]


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
    (derived here), for comparison with :func:`window_statistic`, which
    is optimal only against a common offset. NaN for ``t < 2n-1``.
    """
    n = _check_window(n)
    v = np.asarray(v, dtype=float)
    T = v.shape[-1]
    Q = np.full(v.shape, np.nan)
    if T >= 2 * n:
        d2 = (v[..., n:] - v[..., :-n]) ** 2  # d2[j] = (v[j+n] - v[j])^2
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
    """``var S`` for a stationary sequence with autocovariance ``r(m)``, m = 0..2n-1 (derived here)::

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
    frozen filter with gains ``K`` (its Lyapunov equation). Shape (max_lag+1,)."""
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

    The noise part of the filter's error obeys ``e_k = A_k e_{k-1} + K_k eps_k`` with
    ``A_k = (I - K_k h) F``, and ``P_k = cov(e_k)`` follows the covariance recursion
    (:func:`tvtrack.filters.alphabeta.error_covariance_sequence`). For each window end ``t`` the
    state is augmented with the two running window sums of the output velocity,
    ``y = (e, s_old, s_new)``; starting from ``cov(y) = blockdiag(P_{t-2n}, 0, 0)`` the ``2n``
    frames of the windows propagate ``cov(y) <- M cov(y) M^T + sigma_eps^2 L L^T`` (``M`` adds
    the new velocity ``[A e]_v`` to the sum whose window the frame belongs to), and then
    ``sigma_S(t)^2 = var(s_old - s_new)``. All window ends are
    propagated together, so memory is linear in the run length (``T (d+2)^2`` numbers) and the
    work is ``2n`` batched steps.

    Parameters
    ----------
    gains : array_like, shape (T, order+1)
    n : int
    sigma_eps : float

    Returns
    -------
    ndarray, shape (T,)
        NaN for ``t < 2n-1``.

    Notes
    -----
    The result is a function of the gains, ``n`` and ``sigma_eps`` alone and is kept for the last 128 of them: an
    exploration asks for the same schedule at every replicate and condition of a configuration.
    """
    n = _check_window(n)
    G = np.ascontiguousarray(gains, dtype=float)
    if G.ndim != 2 or G.shape[1] < 2:
        raise ValueError(f"parameter 'gains' has shape {G.shape}; it must be (T, order+1) with order >= 1")
    return _scheduled_std(G.tobytes(), G.shape, n, float(sigma_eps)).copy()


@functools.lru_cache(maxsize=128)
def _scheduled_std(buf: bytes, shape: tuple, n: int, sigma_eps: float) -> np.ndarray:
    """:func:`scheduled_statistic_std` of the gains held in ``buf`` (float64, ``shape``)."""
    G = np.frombuffer(buf, dtype=float).reshape(shape)
    T, d = G.shape
    out = np.full(T, np.nan)
    if T < 2 * n:
        return out
    P = error_covariance_sequence(G, sigma_eps)  # (T, d, d) after each frame
    ends = np.arange(2 * n - 1, T)
    starts = ends - 2 * n + 1  # first frame of the older window
    m = d + 2
    Y = np.zeros((ends.size, m, m))
    Y[starts > 0, :d, :d] = P[starts[starts > 0] - 1]
    F = taylor_transition(d - 1)
    h = observation_row(d - 1)
    M = np.broadcast_to(np.eye(m), Y.shape).copy()
    L = np.zeros((ends.size, m))
    for s in range(2 * n):
        K = G[starts + s]  # (B, d)
        A = (np.eye(d) - K[:, :, None] * h) @ F  # (B, d, d)
        col, other = (d, d + 1) if s < n else (d + 1, d)
        M[:, :d, :d] = A
        M[:, col, :d] = A[:, 1, :]  # the sum gains the new velocity error
        M[:, other, :d] = 0.0
        L[:, :d] = K
        L[:, col] = K[:, 1]
        L[:, other] = 0.0
        Y = M @ Y @ np.swapaxes(M, -1, -2) + sigma_eps**2 * L[:, :, None] * L[:, None, :]
    var = Y[:, d, d] + Y[:, d + 1, d + 1] - 2 * Y[:, d, d + 1]
    out[ends] = np.sqrt(np.maximum(var, 0.0))
    return out


def track2_thresholds(visible, k_bound2: int, n: int, alpha: float, sigma_eps: float = 1.0) -> np.ndarray:
    """Exact ``c(alpha)`` per *frame* for the TRACK2 filter of a run with losses (derived here for time-varying gains).

    While lost the filter coasts (zero gains, (E1)) and its error grows; after re-arming the window sums carry
    that error for many frames, so a threshold computed for a run without loss (indexed by the measurement count)
    is far too low there (after a 10 s loss at alpha = 1e-3 the per-test rate is tens of times alpha). Here the
    gain sequence of the run itself, ``K_2(min(k_t, k_b2))`` on visible frames and 0 on lost ones, goes through
    :func:`scheduled_statistic_std`, so ``sigma_S(t)`` includes the coast.

    Parameters
    ----------
    visible : array_like of bool, shape (T,)
        Visibility shared by every run (the TRACK2 filter is then the same in every run).
    k_bound2, n : int
        TRACK2 gain bound and detector half-window, frames.
    alpha : float
        Per-test false-alarm probability.
    sigma_eps : float
        Measurement noise RMS, elements.

    Returns
    -------
    ndarray, shape (T,)
        Threshold per frame (elements/frame); inf where the windows are not full or hold only predicted
        velocities (sigma_S = 0: no test is possible there).
    """
    _check_alpha(alpha)
    vis = np.asarray(visible, dtype=bool)
    if vis.ndim != 1:
        raise ValueError(f"parameter 'visible' has shape {vis.shape}; it must be (T,)")
    k = np.cumsum(vis)
    G = gain_schedule(1, k_bound2, max(int(k[-1]), 1))[np.maximum(k, 1) - 1] * vis[:, None]
    sig = scheduled_statistic_std(G, n, sigma_eps)
    # from the (2n - 1)-th lost frame on both windows hold the one held velocity: S = 0, sigma_S = 0 in arithmetic
    # (computed, a few 1e-9 of rounding may be left), and no test is possible
    t = np.arange(vis.size)
    coasting = t - np.maximum.accumulate(np.where(vis, t, -1)) >= 2 * n - 1
    c = threshold_from_std(alpha, np.where(np.isfinite(sig) & (sig > 0) & ~coasting, sig, np.inf))
    return np.where(np.isfinite(c), c, np.inf)


def false_alarm_rates(S, threshold, armed, before_onset, test_frame: int, arming_frame: int) -> dict:
    """False-alarm rates of ``|S| > c`` on no-manoeuvre runs, per test and per run.

    Parameters
    ----------
    S : array_like, shape (runs, T)
        Detector statistic of independent no-manoeuvre runs.
    threshold : array_like, shape (T,) or scalar
        ``c(alpha)`` per frame.
    armed, before_onset : array_like of bool, shape (T,)
        Frames at which the detector tests, and the armed frames before the manoeuvre onset.
    test_frame, arming_frame : int
        A fixed frame for a per-test rate independent across runs (exact binomial interval), and
        the first armed frame.

    Returns
    -------
    dict of Estimate (or None)
        ``per_test_fixed_frame``, ``per_test_at_arming``, ``per_test_pooled`` (mean over the armed
        frames of each run, interval from the per-run rates; with no alarm at all, 0 with the zero-events
        bound over the independent runs as its upper limit), ``per_run_before_onset`` (at least one
        alarm before the onset; None when no frame is armed before it) and ``per_run_whole``.
    """
    S = np.asarray(S, dtype=float)
    armed, before_onset = np.asarray(armed, bool), np.asarray(before_onset, bool)
    if S.ndim != 2 or armed.shape != (S.shape[1],) or before_onset.shape != armed.shape:
        raise ValueError(f"parameter 'S' has shape {S.shape}; it must be (runs, T) with 'armed' of shape (T,)")
    runs = S.shape[0]
    alarm = np.abs(S) > threshold
    return {
        "per_test_fixed_frame": proportion_ci(int(alarm[:, test_frame].sum()), runs),
        "per_test_at_arming": proportion_ci(int(alarm[:, arming_frame].sum()), runs),
        "per_test_pooled": _pooled_rate(alarm[:, armed]),
        "per_run_before_onset": (
            proportion_ci(int(alarm[:, before_onset].any(axis=1).sum()), runs) if before_onset.any() else None
        ),
        "per_run_whole": proportion_ci(int(alarm[:, armed].any(axis=1).sum()), runs),
    }


def _pooled_rate(alarm) -> Estimate:
    """Per-test rate pooled over the tested frames of independent runs, ``alarm`` (runs, tests)."""
    runs = alarm.shape[0]
    if not alarm.any():  # zero events: the bound they certify, never [0, 0]
        return Estimate(
            0.0,
            float("nan"),
            0.0,
            zero_events_bound(runs),
            runs,
            0.95,
            f"zero-events bound over {runs} independent runs",
        )
    return mean_ci(alarm.mean(axis=1))


def detection_time_summary(detection_frames, onset: int, loss_frame: int, frame_rate_hz: float) -> dict:
    """Distribution of the first detection time over runs (and channels).

    Parameters
    ----------
    detection_frames : array_like of int, any shape
        First detection frame per run and channel; negative = never detected.
    onset, loss_frame : int
        Manoeuvre onset frame and the frame at which the object is lost.
    frame_rate_hz : float

    Returns
    -------
    dict
        ``median_s``, ``q05_s``, ``q95_s`` (quantiles of the detection time in s, detections at or
        after the onset; None with fewer than two), ``mean_s``, ``false_alarm_before_onset``
        (fraction of runs first detecting before the onset) and ``missed_by_loss`` (no detection
        before the loss).
    """
    d = np.asarray(detection_frames).ravel()
    hit = d >= onset
    early = (d >= 0) & (d < onset)
    missed = d < 0
    t_det = d[hit] / frame_rate_hz
    enough = hit.sum() > 1
    return {
        "median_s": quantile_ci(t_det, 0.5) if enough else None,
        "q05_s": quantile_ci(t_det, 0.05) if enough else None,
        "q95_s": quantile_ci(t_det, 0.95) if enough else None,
        "mean_s": mean_ci(t_det) if enough else None,
        "false_alarm_before_onset": proportion_ci(int(early.sum()), d.size),
        "missed_by_loss": proportion_ci(int((missed | (d >= loss_frame)).sum()), d.size),
    }


def null_quantile_threshold(stat_null, armed, pfa: float) -> float:
    """The threshold whose per-test false-alarm rate is ``pfa``: the ``1 - pfa`` quantile of a
    normalised null statistic pooled over the armed frames.

    Parameters
    ----------
    stat_null : array_like, shape (runs, T)
    armed : array_like of bool, shape (T,)
    pfa : float
        Per-test false-alarm probability, in (0, 1).
    """
    _check_alpha(pfa)
    null = np.asarray(stat_null, dtype=float)[:, np.asarray(armed, bool)]
    return float(np.quantile(null[np.isfinite(null)], 1 - pfa))


def first_alarm_within(stat, threshold: float, armed, onset: int) -> np.ndarray:
    """Per run: the first alarm of ``stat > threshold`` on the armed frames falls in ``[onset, T)``
    (no alarm before the onset, one after it).

    Parameters
    ----------
    stat : array_like, shape (..., T)
        Normalised statistic; NaN = not tested.
    threshold : float
    armed : array_like of bool, shape (T,)
    onset : int

    Returns
    -------
    ndarray of bool, shape (...)
    """
    armed = np.asarray(armed, bool)
    m = np.where(armed, np.nan_to_num(np.asarray(stat, dtype=float), nan=-np.inf), -np.inf)
    return (m[..., :onset].max(axis=-1, initial=-np.inf) <= threshold) & (m.max(axis=-1) > threshold)
