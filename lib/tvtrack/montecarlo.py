"""Seeded generators and Monte Carlo summaries.

Convention: Monte Carlo arrays carry trials on the leading axis, ``(n_trials, ...)``, and every
random draw comes from a :class:`numpy.random.Generator` made from the run's ``seed``.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
from scipy import stats

__all__ = ["make_rng", "spawn_rngs", "Estimate", "mean_ci", "rms_ci", "ratio_ci", "proportion_ci", "quantile_ci"]


def make_rng(seed: int) -> np.random.Generator:
    """The run's generator (PCG64 seeded by ``seed``)."""
    return np.random.default_rng(seed)


def spawn_rngs(seed: int, n: int) -> list[np.random.Generator]:
    """``n`` independent generators derived from ``seed`` (for independent sub-experiments
    whose results must not change when another sub-experiment draws more numbers)."""
    return [np.random.default_rng(s) for s in np.random.SeedSequence(seed).spawn(n)]


@dataclass(frozen=True)
class Estimate:
    """A Monte Carlo estimate with its uncertainty.

    Attributes
    ----------
    value : float
        Point estimate.
    stderr : float
        Standard error of ``value`` (NaN where not defined).
    ci_low, ci_high : float
        Confidence interval at level ``confidence``.
    n : int
        Number of independent samples behind the estimate.
    confidence : float
        Confidence level of the interval, e.g. 0.95.
    """

    value: float
    stderr: float
    ci_low: float
    ci_high: float
    n: int
    confidence: float = 0.95

    def to_dict(self) -> dict:
        return {k: (float(v) if isinstance(v, (float, np.floating)) else v) for k, v in asdict(self).items()}

    def __format__(self, spec: str) -> str:
        spec = spec or ".3g"
        return (f"{self.value:{spec}} [{self.ci_low:{spec}}, {self.ci_high:{spec}}] "
                f"({self.confidence:.0%} CI, n={self.n})")


def mean_ci(samples, confidence: float = 0.95) -> Estimate:
    """Mean of independent samples with a Student-t confidence interval.

    Parameters
    ----------
    samples : array_like, shape (n,)
        One value per independent trial (flattened).
    """
    x = np.asarray(samples, dtype=float).ravel()
    n = x.size
    if n == 0:
        raise ValueError("mean_ci needs at least one sample")
    mean = float(x.mean())
    if n < 2:
        return Estimate(mean, float("nan"), float("nan"), float("nan"), n, confidence)
    se = float(x.std(ddof=1) / np.sqrt(n))
    half = float(stats.t.ppf(0.5 + confidence / 2, n - 1) * se)
    return Estimate(mean, se, mean - half, mean + half, n, confidence)


def rms_ci(errors, axis_trials: int = 0, confidence: float = 0.95) -> Estimate:
    """Root-mean-square of errors, with the interval from per-trial mean squares.

    The errors within one trial are correlated (a filter's errors over time), so the
    interval treats each trial's mean square as one independent sample and maps the
    t-interval of the mean square through the square root.

    Parameters
    ----------
    errors : array_like, shape (n_trials, ...)
        Errors with trials on ``axis_trials``.
    """
    e = np.moveaxis(np.asarray(errors, dtype=float), axis_trials, 0)
    per_trial = np.nanmean(e.reshape(e.shape[0], -1) ** 2, axis=1)
    ms = mean_ci(per_trial, confidence)
    root = lambda v: float(np.sqrt(max(v, 0.0))) if np.isfinite(v) else float("nan")
    value = root(ms.value)
    se = ms.stderr / (2 * value) if value > 0 else float("nan")
    return Estimate(value, se, root(ms.ci_low), root(ms.ci_high), ms.n, confidence)


def ratio_ci(numerator, denominator, confidence: float = 0.95) -> Estimate:
    """``mean(numerator) / mean(denominator)`` with a delta-method normal interval.

    The samples are paired per trial (e.g. the squared errors of two filters on the same
    runs, common random numbers), so their covariance narrows the interval.

    Parameters
    ----------
    numerator, denominator : array_like, shape (n,)
        One value per independent trial each; ``mean(denominator)`` must not be 0.
    """
    a = np.asarray(numerator, dtype=float).ravel()
    b = np.asarray(denominator, dtype=float).ravel()
    if a.size != b.size or a.size < 2:
        raise ValueError(f"ratio_ci needs paired samples of equal size >= 2, got {a.size} and {b.size}")
    ma, mb = a.mean(), b.mean()
    if mb == 0:
        raise ValueError("ratio_ci: the denominator's mean is 0")
    r = ma / mb
    (va, cab), (_, vb) = np.cov(a, b)
    # delta method: Var(r) ~ (Var a - 2 r Cov(a, b) + r^2 Var b) / (n mb^2)
    se = float(np.sqrt(max(va - 2 * r * cab + r**2 * vb, 0.0) / a.size) / abs(mb))
    z = float(stats.norm.ppf(0.5 + confidence / 2))
    return Estimate(float(r), se, float(r - z * se), float(r + z * se), int(a.size), confidence)


def proportion_ci(successes: int, n: int, confidence: float = 0.95) -> Estimate:
    """A probability from ``successes`` out of ``n`` Bernoulli trials, with the exact
    Clopper-Pearson interval (scipy.stats.binomtest)."""
    if n <= 0:
        raise ValueError(f"proportion_ci needs n >= 1, got n={n}")
    k = int(successes)
    p = k / n
    ci = stats.binomtest(k, n).proportion_ci(confidence_level=confidence, method="exact")
    return Estimate(p, float(np.sqrt(p * (1 - p) / n)), float(ci.low), float(ci.high), n, confidence)


def quantile_ci(samples, q: float, confidence: float = 0.95) -> Estimate:
    """The ``q`` quantile of independent samples with a distribution-free (order-statistic)
    confidence interval."""
    x = np.sort(np.asarray(samples, dtype=float).ravel())
    n = x.size
    if n == 0:
        raise ValueError("quantile_ci needs at least one sample")
    value = float(np.quantile(x, q))
    lo_rank = int(stats.binom.ppf((1 - confidence) / 2, n, q))
    hi_rank = int(stats.binom.ppf(0.5 + confidence / 2, n, q))
    lo = float(x[max(lo_rank - 1, 0)])
    hi = float(x[min(hi_rank, n - 1)])
    return Estimate(value, float("nan"), lo, hi, n, confidence)
