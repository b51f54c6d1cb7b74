"""Per-scan errors, acquisition times and the robust error ratio of Monte Carlo filter runs (batched over trials).

A filter started from a pessimistic prior has a transient; a run has acquired the object once its per-scan mean
squared error stays within an in-lock bound. Errors come in arrays of shape (n_trials, K) with one row per
independent Monte Carlo run.
"""

from __future__ import annotations

import numpy as np

from ...estimate import Estimate
from ...montecarlo import bootstrap_ci

__all__ = ["scan_averages", "acquisition_times_from_scans", "median_ratio_ci"]


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


def acquisition_times_from_scans(per_scan_ms, threshold_ms: float, scan_duration: float):
    """Time each trial acquires the object for good, from the per-trial mean squared error of every scan: the end of
    its last scan whose mean squared error exceeds ``threshold_ms`` (the end of the first scan if none does: lock is
    known only once a scan has been seen; ``inf`` if the last scan of the run is out of lock).

    A run that re-acquires late and a run in a false lock (its filter confident, its error tens of
    sigma) both show here, unlike in the ensemble mean where they are averaged away or dominate.

    Parameters
    ----------
    per_scan_ms : ndarray, shape (n_trials, n_scans)   from :func:`scan_averages`
    threshold_ms : float                               in-lock bound on a scan's mean squared error
    scan_duration : float                              duration of one scan (time units of the result)

    Returns
    -------
    ndarray, shape (n_trials,)   acquisition time (time units of ``scan_duration``); ``inf``: not acquired by the end
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
