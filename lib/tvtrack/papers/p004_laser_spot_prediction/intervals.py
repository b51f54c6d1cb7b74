"""Intervals over a few paths that cover: studentised (bootstrap-t) intervals for paper 004.

The verdicts of paper 004 rest on statistics over 15 paths whose mean squared errors spread over a
factor of about 7 (the wander RMS is drawn from 3 to 8 px). At that size the BCa bootstrap of
:func:`tvtrack.montecarlo.ratio_ci` covers about 0.90-0.92 instead of 0.95, and a Student-t interval
about 0.93 (issue 28, item 4; both measured on the model of ``tests/papers/test_004_intervals.py``). The bootstrap-t
interval resamples the studentised statistic ``(theta* - theta) / se*`` and corrects part of the skew
that both miss. Measured at 15 paths (1500 replications of the test's model): the RMS interval covers
0.96, the ratio interval 0.93 (a t interval or BCa does not do better; the log scale keeps the bounds
positive at any size). So a single
15-path interval of a ratio under-covers by about 1.5 points: the notebook says so, and a claim's
verdict at the default reading pools the independent replicates (45 paths or more).

Candidate for the core's one bootstrap (``tvtrack.montecarlo.bootstrap_ci``, a ``method="studentized"``);
kept here until the core has it.
"""

from __future__ import annotations

import numpy as np

from ...montecarlo import Estimate

__all__ = ["N_RESAMPLES", "RESAMPLE_SEED", "mean_ci_t", "ratio_of_means_ci", "root_mean_ci"]

#: Bootstrap resamples of every interval.
N_RESAMPLES = 1999
#: Seed of the resampling stream: an interval is a pure function of its data.
RESAMPLE_SEED = 20050110


def _bootstrap_t(stat, samples, confidence: float, n_resamples: int, rng) -> tuple[float, float, float, float]:
    """Bootstrap-t interval of ``stat(*samples) -> (value, se)`` (vectorised over a leading axis)."""
    n = samples[0].shape[-1]
    rng = np.random.default_rng(RESAMPLE_SEED) if rng is None else rng
    value, se = stat(*(s[None] for s in samples))
    value, se = float(value[0]), float(se[0])
    if not np.isfinite(value):
        return value, float("nan"), float("nan"), float("nan")
    if not se > 1e-12 * max(1.0, abs(value)):  # constant data (or an exact ratio): nothing varies
        return value, 0.0, value, value
    idx = rng.integers(0, n, (n_resamples, n))
    v_star, se_star = stat(*(s[idx] for s in samples))
    ok = np.isfinite(v_star) & (se_star > 0)
    t = (v_star[ok] - value) / se_star[ok]
    a = 1 - confidence
    q_hi, q_lo = np.quantile(t, [1 - a / 2, a / 2])
    return value, se, value - q_hi * se, value - q_lo * se


def _mean_stat(x):
    return x.mean(axis=-1), x.std(axis=-1, ddof=1) / np.sqrt(x.shape[-1])


def _log_mean_stat(x):
    """log of a positive mean and its delta-method standard error."""
    m = x.mean(axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.log(m), x.std(axis=-1, ddof=1) / (np.sqrt(x.shape[-1]) * m)


def _log_ratio_stat(a, b):
    """log of a ratio of positive means and its linearised standard error."""
    r = a.mean(axis=-1) / b.mean(axis=-1)
    d = a - r[..., None] * b  # linearised residuals of the ratio of means
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.log(r), d.std(axis=-1, ddof=1) / (np.sqrt(a.shape[-1]) * b.mean(axis=-1) * r)


def _check(x, name: str) -> np.ndarray:
    x = np.asarray(x, dtype=float).ravel()
    if x.size < 3 or not np.all(np.isfinite(x)):
        raise ValueError(f"parameter {name!r} needs >= 3 finite values (one per independent path), got {x.size}")
    return x


def mean_ci_t(samples, confidence: float = 0.95, n_resamples: int = N_RESAMPLES, rng=None) -> Estimate:
    """Mean of independent values (e.g. one per path) with a bootstrap-t interval.

    Parameters
    ----------
    samples : array_like, shape (n,)
        One value per independent path or run.

    Returns
    -------
    Estimate
    """
    x = _check(samples, "samples")
    v, se, lo, hi = _bootstrap_t(_mean_stat, (x,), confidence, n_resamples, rng)
    return Estimate(v, se, lo, hi, x.size, confidence, f"bootstrap-t ({n_resamples} resamples)")


def root_mean_ci(mean_squares, confidence: float = 0.95, n_resamples: int = N_RESAMPLES, rng=None) -> Estimate:
    """RMS ``sqrt(mean(m))`` of per-path mean squares ``m`` (px^2): bootstrap-t interval of the log of
    the mean (positive bounds at any sample size), mapped through the square root (px).

    Parameters
    ----------
    mean_squares : array_like, shape (n,)
        Mean squared error of each independent path (positive).
    """
    m = _check(mean_squares, "mean_squares")
    if np.any(m <= 0):
        raise ValueError("parameter 'mean_squares' must be positive")
    v, se, lo, hi = _bootstrap_t(_log_mean_stat, (m,), confidence, n_resamples, rng)
    root = lambda x: float(np.exp(x / 2))
    return Estimate(
        root(v),
        se * root(v) / 2,
        root(lo),
        root(hi),
        m.size,
        confidence,
        f"square root of the bootstrap-t interval (log scale) of the mean square ({n_resamples} resamples)",
    )


def ratio_of_means_ci(
    numerator, denominator, confidence: float = 0.95, n_resamples: int = N_RESAMPLES, rng=None
) -> Estimate:
    """``mean(numerator) / mean(denominator)`` of paired positive values (the same paths under two
    methods): bootstrap-t interval of the log ratio on the linearised standard error (positive bounds).

    Parameters
    ----------
    numerator, denominator : array_like, shape (n,)
        Paired per-path values (e.g. mean squared errors of a baseline and of the filter), positive.
    """
    a, b = _check(numerator, "numerator"), _check(denominator, "denominator")
    if a.size != b.size:
        raise ValueError(f"paired samples of sizes {a.size} and {b.size}")
    if np.any(a <= 0) or np.any(b <= 0):
        raise ValueError("ratio_of_means_ci needs positive values")
    v, se, lo, hi = _bootstrap_t(_log_ratio_stat, (a, b), confidence, n_resamples, rng)
    r = float(np.exp(v))
    return Estimate(
        r,
        se * r,
        float(np.exp(lo)),
        float(np.exp(hi)),
        a.size,
        confidence,
        f"paired bootstrap-t, log scale ({n_resamples} resamples)",
    )
