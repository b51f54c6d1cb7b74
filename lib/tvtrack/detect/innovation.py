"""Innovation-based manoeuvre detectors for notebook 001's benchmark (this project's addition).

The TRACK2 filter's innovation ``nu_t = Z_t - h F x_{t-1}`` is, under no manoeuvre, zero-mean with
variance ``s_t^2 = [F P_{t-1} F^T]_00 + sigma_eps^2`` (noise covariance recursion); a manoeuvre
adds a deterministic signature. Three classical tests on the normalised innovation
``u_t = nu_t / s_t``:

* the chi-square test over a sliding window, ``sum_{j=t-L+1}^t u_j^2`` (Bar-Shalom, Li &
  Kirubarajan 2001, §11.2);
* the two-sided CUSUM (Page 1954), the larger of ``g^+_t = max(0, g^+_{t-1} + u_t - k)`` and
  ``g^-_t = max(0, g^-_{t-1} - u_t - k)``;
* the Willsky-Jones GLR for a jump of unknown size in the velocity at an unknown time ``theta``
  within the last ``L`` frames: with ``rho(d)`` the innovation response ``d`` frames after a unit
  velocity jump, ``max_theta (sum_d rho(d) u_{theta+d})^2 / sum_d rho(d)^2`` (Willsky & Jones 1976,
  with the innovations treated as white).

The fixed-gain filter is not the optimal filter of the noise, so the innovations are slightly
correlated and the nominal chi-square levels do not hold: the benchmark sets every threshold
from simulated no-manoeuvre runs (:func:`delay_false_alarm_curve`).
"""

from __future__ import annotations

import numpy as np

from ..filters.alphabeta import error_covariance_sequence, scheduled_filter
from ..filters.polynomial import taylor_transition

__all__ = [
    "normalised_innovations",
    "chi2_window",
    "cusum",
    "velocity_jump_signature",
    "glr_velocity_jump",
    "delay_false_alarm_curve",
]


def _check_length(L, name="L") -> int:
    if not (isinstance(L, (int, np.integer)) and L >= 1):
        raise ValueError(f"parameter '{name}' = {L!r}; it must be an integer >= 1")
    return int(L)


def normalised_innovations(z, states, gains, sigma_eps: float) -> np.ndarray:
    """``u_t = (Z_t - h F x_{t-1}) / s_t`` of a filter run.

    Parameters
    ----------
    z : array_like, shape (..., T)
        Measurements, elements.
    states : array_like, shape (..., T, d)
        The filter's states after each frame (``x_{-1} = 0``).
    gains : array_like, shape (T, d)
        The gains used (for the innovation variance from the noise covariance recursion).
    sigma_eps : float

    Returns
    -------
    ndarray, shape (..., T)
    """
    z = np.asarray(z, dtype=float)
    x = np.asarray(states, dtype=float)
    d = x.shape[-1]
    F = taylor_transition(d - 1)
    prev = np.concatenate([np.zeros(x.shape[:-2] + (1, d)), x[..., :-1, :]], axis=-2)
    pred = prev @ F[0]  # h F x_{t-1}
    P = error_covariance_sequence(np.asarray(gains, dtype=float), sigma_eps)
    P_prev = np.concatenate([np.zeros((1, d, d)), P[:-1]])
    s2 = (F @ P_prev @ F.T)[:, 0, 0] + sigma_eps**2
    return (z - pred) / np.sqrt(s2)


def chi2_window(u, L: int) -> np.ndarray:
    """``sum_{j=t-L+1}^t u_j^2`` along the last axis; NaN for ``t < L-1``."""
    L = _check_length(L)
    u = np.asarray(u, dtype=float)
    c = np.concatenate([np.zeros(u.shape[:-1] + (1,)), np.cumsum(u**2, axis=-1)], axis=-1)
    out = np.full(u.shape, np.nan)
    if u.shape[-1] >= L:
        out[..., L - 1 :] = c[..., L:] - c[..., :-L]
    return out


def cusum(u, drift: float, start: int = 0) -> np.ndarray:
    """Two-sided CUSUM ``max(g^+_t, g^-_t)`` of ``u`` along the last axis, restarted at 0 at ``start``
    (NaN before it).

    Parameters
    ----------
    u : array_like, shape (..., T)
    drift : float
        The reference value ``k`` (half the normalised shift the test is tuned to), >= 0.
    start : int
        First frame of the recursion (e.g. the arming frame).
    """
    if not drift >= 0:
        raise ValueError(f"parameter 'drift' = {drift!r}; it must be >= 0")
    u = np.asarray(u, dtype=float)
    g_up = np.zeros(u.shape[:-1])
    g_dn = np.zeros(u.shape[:-1])
    out = np.full(u.shape, np.nan)
    for t in range(start, u.shape[-1]):
        g_up = np.maximum(0.0, g_up + u[..., t] - drift)
        g_dn = np.maximum(0.0, g_dn - u[..., t] - drift)
        out[..., t] = np.maximum(g_up, g_dn)
    return out


def velocity_jump_signature(gain, sigma_eps: float, L: int) -> np.ndarray:
    """``rho(d)``, d = 0..L-1: the normalised innovation ``d`` frames after a unit velocity jump,
    for the frozen filter with gain vector ``gain`` in steady state.

    A measurement ramp ``Z_t = t + 1`` for ``t = 0..L-1`` (the offset the jump adds ``d`` frames after
    it is ``d + 1``) is run through the frozen filter from a zero state (steady state of a constant
    position).
    """
    L = _check_length(L)
    K = np.asarray(gain, dtype=float)
    G = np.broadcast_to(K, (L, K.size))
    ramp = np.arange(1, L + 1, dtype=float)
    x = scheduled_filter(ramp, G)
    prev = np.concatenate([np.zeros((1, K.size)), x[:-1]])
    nu = ramp - prev @ taylor_transition(K.size - 1)[0]
    P = error_covariance_sequence(np.broadcast_to(K, (2000, K.size)), sigma_eps)[-1]  # steady state
    F = taylor_transition(K.size - 1)
    return nu / np.sqrt((F @ P @ F.T)[0, 0] + sigma_eps**2)


def glr_velocity_jump(u, signature) -> np.ndarray:
    """Willsky-Jones GLR for a velocity jump within the last ``L = len(signature)`` frames.

    ``max_{d=0..L-1} (sum_{i=0}^{d} rho(i) u_{t-d+i})^2 / sum_{i=0}^{d} rho(i)^2``, along the last
    axis; NaN for ``t < L-1``.
    """
    rho = np.asarray(signature, dtype=float)
    L = rho.size
    u = np.asarray(u, dtype=float)
    T = u.shape[-1]
    out = np.full(u.shape, np.nan)
    if T < L:
        return out
    best = np.zeros(u.shape[:-1] + (T - L + 1,))
    energy = np.cumsum(rho**2)
    for d in range(L):
        num = np.zeros_like(best)
        for i in range(d + 1):  # u_{t-d+i} for t = L-1 .. T-1
            num += rho[i] * u[..., L - 1 - d + i : T - d + i]
        best = np.maximum(best, num**2 / energy[d])
    out[..., L - 1 :] = best
    return out


def delay_false_alarm_curve(
    stat_alt,
    stat_null,
    armed_alt,
    armed_null,
    onset: int,
    targets,
    frame_rate_hz: float,
    delay_limit_s: float,
    thresholds=None,
) -> dict:
    """Detection delay against the per-run false-alarm probability, thresholds set on null runs.

    For each target per-run false-alarm probability ``p`` the threshold is the ``1 - p`` quantile
    of each null run's largest statistic over its armed frames. On the manoeuvre runs the delay is
    the first alarm at or after the onset (runs that alarm before the onset are false alarms and
    count as not detected; runs that never alarm have infinite delay).

    Parameters
    ----------
    stat_alt : array_like, shape (..., T_alt)
        Statistic on manoeuvre runs (NaN = not tested).
    stat_null : array_like, shape (runs, T_null)
        Statistic on independent no-manoeuvre runs.
    armed_alt, armed_null : array_like of bool, shapes (T_alt,), (T_null,)
    onset : int
    targets : array_like, shape (m,)
        Per-run false-alarm probabilities in (0, 1).
    frame_rate_hz, delay_limit_s : float
        For the delay in seconds and the detection-within-limit probability.
    thresholds : array_like, shape (m,), optional
        Fixed thresholds instead of the null quantiles (e.g. a rule's nominal threshold); the
        targets are then ignored.

    Returns
    -------
    dict of ndarray, shape (m,)
        ``threshold``, ``per_run_false_alarm`` (empirical on the null runs), ``median_delay_s``
        (inf if fewer than half the runs detect), ``p_detect_within`` (first alarm within
        ``delay_limit_s`` of the onset, none before) and ``early_alarm`` (alarm before the onset).
    """
    targets = np.asarray(targets if thresholds is None else np.full(np.size(thresholds), 0.5), dtype=float)
    if np.any((targets <= 0) | (targets >= 1)):
        raise ValueError("parameter 'targets' must hold probabilities in (0, 1)")
    null = np.where(np.asarray(armed_null, bool), np.nan_to_num(np.asarray(stat_null, float), nan=-np.inf), -np.inf)
    alt = np.where(np.asarray(armed_alt, bool), np.nan_to_num(np.asarray(stat_alt, float), nan=-np.inf), -np.inf)
    alt = alt.reshape(-1, alt.shape[-1])
    null_max = null.max(axis=-1)
    thr = np.quantile(null_max, 1 - targets) if thresholds is None else np.asarray(thresholds, dtype=float)
    out = {
        k: np.empty(targets.size)
        for k in ("threshold", "per_run_false_alarm", "median_delay_s", "p_detect_within", "early_alarm")
    }
    limit = int(round(delay_limit_s * frame_rate_hz))
    for i, c in enumerate(thr):
        hit = alt > c
        first = np.where(hit.any(axis=-1), hit.argmax(axis=-1), np.iinfo(np.int64).max)
        early = first < onset
        delay = np.where(early, np.inf, (first - onset) / frame_rate_hz)
        delay = np.where(first == np.iinfo(np.int64).max, np.inf, delay)
        out["threshold"][i] = c
        out["per_run_false_alarm"][i] = np.mean(null_max > c)
        out["median_delay_s"][i] = np.median(delay)
        out["p_detect_within"][i] = np.mean(~early & (first <= onset + limit))
        out["early_alarm"][i] = np.mean(early)
    return out
