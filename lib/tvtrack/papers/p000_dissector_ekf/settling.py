"""Steady-state error and settling time of Monte Carlo filter runs (batched over trials).

A filter started from a pessimistic prior has a transient; its steady-state accuracy is the
per-trial mean squared error over a final window, and its settling time is when the ensemble
error first comes within a tolerance of that steady value. Errors come in arrays of shape
(n_trials, K) with one row per independent Monte Carlo run.
"""

from __future__ import annotations

import numpy as np

from ...estimate import Estimate
from ...montecarlo import bootstrap_ci

__all__ = [
    "lock_lost",
    "per_trial_mse",
    "scan_averages",
    "settle_time",
    "settle_time_ci",
    "acquisition_times",
    "acquisition_times_from_scans",
    "median_ratio_ci",
]


def per_trial_mse(truth, estimate, mask):
    """Mean squared error of every trial over the steps selected by ``mask``.

    Parameters
    ----------
    truth, estimate : ndarray, shape (n_trials, K)
    mask : ndarray of bool, shape (K,)   steps to average (e.g. the steady-state window)

    Returns
    -------
    ndarray, shape (n_trials,)   one independent sample per trial (units of the state squared)
    """
    return ((truth - estimate)[:, mask] ** 2).mean(axis=1)


def scan_averages(sq_error, steps_per_scan: int):
    """Average of ``sq_error[:, 1:]`` over consecutive blocks of ``steps_per_scan`` steps.

    Parameters
    ----------
    sq_error : ndarray, shape (n_trials, K + 1)   column 0 is the start (no sample), dropped
    steps_per_scan : int                           steps per block (>= 1)

    Returns
    -------
    ndarray, shape (n_trials, K // steps_per_scan)   incomplete last block dropped
    """
    if steps_per_scan < 1:
        raise ValueError(f"parameter 'steps_per_scan' = {steps_per_scan}; it must be >= 1")
    n_trials = sq_error.shape[0]
    n_scans = (sq_error.shape[1] - 1) // steps_per_scan
    return sq_error[:, 1 : 1 + n_scans * steps_per_scan].reshape(n_trials, n_scans, steps_per_scan).mean(axis=2)


def settle_time(per_scan, steady, scan_duration: float, tolerance: float = 0.10) -> float:
    """End of the first scan whose mean squared error is within ``tolerance`` of ``steady`` (or below).

    First entry rather than "stays inside": a decay from a large prior is monotone, and later
    excursions of a scan average are Monte Carlo noise.

    Parameters
    ----------
    per_scan : ndarray, shape (n_scans,)   ensemble MSE averaged over each scan
    steady : float                          steady-state MSE
    scan_duration : float                   duration of one scan (time units of the result)
    tolerance : float                       relative tolerance (0.10: within 10 %)

    Returns
    -------
    float   settling time, or ``inf`` if no scan gets within the tolerance
    """
    inside = per_scan <= (1.0 + tolerance) * steady
    return (np.argmax(inside) + 1) * scan_duration if inside.any() else np.inf


def settle_time_ci(
    sq_error,
    steady_mask,
    steps_per_scan: int,
    dt: float,
    rng: np.random.Generator,
    n_boot: int = 2000,
    tolerance: float = 0.10,
    confidence: float = 0.95,
) -> Estimate:
    """Settling time (:func:`settle_time`) with a percentile bootstrap over trials.

    Trials are resampled with replacement (:func:`tvtrack.montecarlo.bootstrap_ci`, percentile); each resample recomputes the
    per-scan ensemble MSE and the steady value from the same trials.

    Parameters
    ----------
    sq_error : ndarray, shape (n_trials, K + 1)   squared errors, column 0 at the start
    steady_mask : ndarray of bool, shape (K + 1,) steady-state window
    steps_per_scan : int;  dt : float             steps per scan and step length (time units)
    rng : numpy.random.Generator                  drives the resampling
    n_boot : int                                  bootstrap resamples

    Returns
    -------
    Estimate  value, bootstrap standard deviation (NaN if some resample never settles), percentile CI
    """
    per_scan = scan_averages(sq_error, steps_per_scan)
    steady = sq_error[:, steady_mask].mean(axis=1)
    n_trials = per_scan.shape[0]
    scan_duration = steps_per_scan * dt

    def statistic(idx, axis=-1):
        idx = np.asarray(idx).astype(int)  # bootstrap_ci hands the trial indices over as floats
        rows = np.atleast_2d(idx)
        out = np.array(
            [settle_time(per_scan[i].mean(axis=0), steady[i].mean(), scan_duration, tolerance) for i in rows]
        )
        return out[0] if idx.ndim == 1 else out

    value = float(settle_time(per_scan.mean(axis=0), steady.mean(), scan_duration, tolerance))
    est = bootstrap_ci(
        (np.arange(n_trials),), statistic, n_resamples=n_boot, confidence=confidence, rng=rng, method="percentile"
    )
    return Estimate(value, est.stderr, est.ci_low, est.ci_high, n_trials, confidence, est.method)


def acquisition_times(sq_error, threshold_ms: float, steps_per_scan: int, dt: float):
    """Time each trial acquires the object for good: the end of its last scan whose mean squared
    error exceeds ``threshold_ms`` (the end of the first scan if none does: lock is known only once a
    scan has been seen; ``inf`` if the last scan of the run is out of lock).

    A run that re-acquires late and a run in a false lock (its filter confident, its error tens of
    sigma) both show here, unlike in the ensemble mean where they are averaged away or dominate.

    Parameters
    ----------
    sq_error : ndarray, shape (n_trials, K + 1)   squared errors, column 0 at the start (dropped)
    threshold_ms : float                          in-lock bound on a scan's mean squared error
    steps_per_scan : int;  dt : float             steps per scan and step length (time units)

    Returns
    -------
    ndarray, shape (n_trials,)   acquisition time (time units of ``dt``); ``inf``: not acquired by the end
    """
    return acquisition_times_from_scans(scan_averages(sq_error, steps_per_scan), threshold_ms, steps_per_scan * dt)


def acquisition_times_from_scans(per_scan_ms, threshold_ms: float, scan_duration: float):
    """:func:`acquisition_times` from the per-trial mean squared error of every scan.

    Parameters
    ----------
    per_scan_ms : ndarray, shape (n_trials, n_scans)   from :func:`scan_averages`
    threshold_ms : float                               in-lock bound on a scan's mean squared error
    scan_duration : float                              duration of one scan (time units of the result)
    """
    if not threshold_ms > 0:
        raise ValueError(f"parameter 'threshold_ms' = {threshold_ms}; it must be > 0")
    out = np.asarray(per_scan_ms) > threshold_ms  # (n_trials, n_scans)
    n_scans = out.shape[1]
    last_out = n_scans - 1 - np.argmax(out[:, ::-1], axis=1)  # index of the last scan out of lock
    t = np.where(out.any(axis=1), last_out + 1, 1) * scan_duration
    return np.where(out[:, -1], np.inf, t)


def median_ratio_ci(numerator, denominator, confidence: float = 0.95) -> Estimate:
    """``median(numerator) / median(denominator)`` of paired per-trial values with a BCa bootstrap
    interval (trials resampled jointly): the robust companion of a variance ratio whose mean a few
    diverged runs can dominate.

    Parameters
    ----------
    numerator, denominator : array_like, shape (n_trials,)
        Per-trial steady-state mean squared errors of two filters on the same runs.
    """
    return bootstrap_ci(
        (numerator, denominator),
        lambda a, b, axis: np.median(a, axis=axis) / np.median(b, axis=axis),
        confidence=confidence,
    )


def lock_lost(error, threshold: float, min_steps: int):
    """Trials whose ``|error|`` exceeds ``threshold`` for at least ``min_steps`` consecutive steps.

    Parameters
    ----------
    error : ndarray, shape (n_trials, K)
    Returns
    -------
    ndarray of bool, shape (n_trials,)
    """
    if min_steps < 1:
        raise ValueError(f"parameter 'min_steps' = {min_steps}; it must be >= 1")
    big = (np.abs(error) > threshold).astype(np.int32)
    run = np.zeros(big.shape[0], dtype=np.int32)
    longest = np.zeros_like(run)
    for k in range(big.shape[1]):
        run = (run + 1) * big[:, k]
        longest = np.maximum(longest, run)
    return longest >= min_steps
