"""Seeded generators and Monte Carlo summaries.

Convention: Monte Carlo arrays carry trials on the leading axis, ``(n_trials, ...)``, and every
random draw comes from a :class:`numpy.random.Generator` made from the run's ``seed``.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
from scipy import stats

__all__ = ["make_rng", "spawn_rngs", "Estimate", "mean_ci", "bootstrap_ci", "mean_square_ci", "variance_ci",
           "rms_ci", "ratio_ci", "paired_difference", "paired_test", "robust_summary", "proportion_ci",
           "zero_events_bound", "events_statement", "quantile_ci", "N_BOOTSTRAP", "BOOTSTRAP_SEED"]

#: Bootstrap resamples by default (intervals at the 2.5 % / 97.5 % tails need thousands).
N_BOOTSTRAP = 2000
#: Seed of the default resampling stream: a summary is a pure function of its data.
BOOTSTRAP_SEED = 20261124


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
    method : str
        How the interval was made (e.g. ``"BCa bootstrap (2000 resamples)"``, ``"Clopper-Pearson"``).
    extrapolated : bool
        The value comes from extrapolating a fit beyond the data (e.g. a logistic tail): it is shown
        but never decides a verdict (:func:`tvtrack.verdicts.is_undecided`).
    """

    value: float
    stderr: float
    ci_low: float
    ci_high: float
    n: int
    confidence: float = 0.95
    method: str = ""
    extrapolated: bool = False

    def to_dict(self) -> dict:
        return {k: (float(v) if isinstance(v, (float, np.floating)) else v) for k, v in asdict(self).items()}

    @classmethod
    def exact(cls, value: float, method: str = "exact") -> "Estimate":
        """A number with no Monte Carlo uncertainty (a deterministic computation)."""
        v = float(value)
        return cls(v, 0.0, v, v, 1, 0.95, method)

    def _repr_markdown_(self) -> str:
        return f"{self:.4g}" + (f" ({self.method})" if self.method else "")

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
    return Estimate(mean, se, mean - half, mean + half, n, confidence, "Student t")


def bootstrap_ci(samples, statistic, *, paired: bool = True, n_resamples: int = N_BOOTSTRAP,
                 confidence: float = 0.95, rng: np.random.Generator | None = None,
                 method: str = "BCa") -> Estimate:
    """A statistic of independent trials with a bootstrap interval (:func:`scipy.stats.bootstrap`).

    Parameters
    ----------
    samples : sequence of array_like, each shape (n_trials,)
        One value per independent trial in each sample.
    statistic : callable
        ``statistic(*samples, axis=-1)``, vectorised like NumPy reductions.
    paired : bool
        Resample trials jointly across the samples (common random numbers), or each sample apart.
    n_resamples : int
        At least 2000 by default (:data:`N_BOOTSTRAP`).
    rng : numpy.random.Generator, optional
        The resampling stream; by default a fixed one (:data:`BOOTSTRAP_SEED`), so a summary is a
        pure function of its data.
    method : {"BCa", "percentile"}
        ``"BCa"`` (bias-corrected and accelerated) corrects the skew of ratios and mean squares.

    Returns
    -------
    Estimate
        ``value`` the statistic on all trials, ``stderr`` the bootstrap standard error,
        ``method`` names the interval.
    """
    data = tuple(np.asarray(x, dtype=float).ravel() for x in samples)
    n = min(x.size for x in data)
    value = float(statistic(*data, axis=-1))
    if n < 2 or not np.isfinite(value):
        return Estimate(value, float("nan"), float("nan"), float("nan"), n, confidence, "none (n < 2)")
    if all(np.ptp(x) == 0 for x in data):             # constant samples: BCa is undefined, nothing varies
        return Estimate(value, 0.0, value, value, n, confidence, "exact (constant sample)")
    rng = np.random.default_rng(BOOTSTRAP_SEED) if rng is None else rng
    res = stats.bootstrap(data, statistic, paired=paired, vectorized=True, axis=-1, n_resamples=n_resamples,
                          confidence_level=confidence, method=method, rng=rng)
    lo, hi = float(res.confidence_interval.low), float(res.confidence_interval.high)
    return Estimate(value, float(res.standard_error), lo, hi, n, confidence,
                    f"{method} bootstrap ({n_resamples} resamples)")


def mean_square_ci(per_trial, confidence: float = 0.95, rng: np.random.Generator | None = None) -> Estimate:
    """Mean of non-negative per-trial values (mean squares, variances) with a BCa bootstrap interval.

    The bootstrap distribution of a mean of non-negative values is non-negative, so unlike a
    Student-t interval the interval never goes below zero, and BCa follows the right skew of
    heavy-tailed squared errors. Coverage 93-97 % at n >= 300 trials for squared normal, squared
    Student-t(10), log-normal and exponential values (``tests/test_intervals.py``); fewer trials
    under-cover heavy tails, so report :func:`robust_summary` beside it.

    Parameters
    ----------
    per_trial : array_like, shape (n_trials,)
        One non-negative value per independent trial (e.g. a trial's time-averaged squared error).
    """
    x = np.asarray(per_trial, dtype=float).ravel()
    if np.any(x < 0):
        raise ValueError("mean_square_ci needs non-negative values (squared errors, variances)")
    return bootstrap_ci((x,), np.mean, confidence=confidence, rng=rng)


def variance_ci(samples, confidence: float = 0.95, method: str = "bootstrap",
                rng: np.random.Generator | None = None) -> Estimate:
    """Variance (``ddof=1``) of independent samples with an interval that stays above zero.

    Parameters
    ----------
    samples : array_like, shape (n,)
    method : {"bootstrap", "chi2"}
        ``"chi2"``: the exact interval ``(n-1) s^2 / chi^2_{n-1}`` for normal samples (wrong for
        heavy tails); ``"bootstrap"``: BCa, no distributional assumption.
    """
    x = np.asarray(samples, dtype=float).ravel()
    n = x.size
    if n < 2:
        raise ValueError(f"variance_ci needs at least 2 samples, got {n}")
    s2 = float(x.var(ddof=1))
    if method == "chi2":
        a = 1 - confidence
        lo = (n - 1) * s2 / stats.chi2.ppf(1 - a / 2, n - 1)
        hi = (n - 1) * s2 / stats.chi2.ppf(a / 2, n - 1)
        return Estimate(s2, float(s2 * np.sqrt(2 / (n - 1))), float(lo), float(hi), n, confidence, "chi-square (normal)")
    if method != "bootstrap":
        raise ValueError(f"variance_ci: method {method!r} must be 'bootstrap' or 'chi2'")
    return bootstrap_ci((x,), lambda v, axis: np.var(v, axis=axis, ddof=1), confidence=confidence, rng=rng)


def rms_ci(errors, axis_trials: int = 0, confidence: float = 0.95,
           rng: np.random.Generator | None = None) -> Estimate:
    """Root-mean-square of errors: the square root of :func:`mean_square_ci` of per-trial mean squares.

    The errors within one trial are correlated (a filter's errors over time), so each trial's
    mean square is one independent sample; NaNs (no estimate yet) are skipped within a trial.

    Parameters
    ----------
    errors : array_like, shape (n_trials, ...)
        Errors with trials on ``axis_trials``.
    """
    e = np.moveaxis(np.asarray(errors, dtype=float), axis_trials, 0)
    per_trial = np.nanmean(e.reshape(e.shape[0], -1) ** 2, axis=1)
    ms = mean_square_ci(per_trial, confidence, rng)
    value = float(np.sqrt(ms.value))
    se = ms.stderr / (2 * value) if value > 0 else float("nan")
    return Estimate(value, se, float(np.sqrt(ms.ci_low)), float(np.sqrt(ms.ci_high)), ms.n, confidence,
                    f"square root of {ms.method} of per-trial mean squares")


def ratio_ci(numerator, denominator, confidence: float = 0.95, paired: bool = True,
             rng: np.random.Generator | None = None) -> Estimate:
    """``mean(numerator) / mean(denominator)`` with a BCa bootstrap interval.

    Paired samples (e.g. the squared errors of two filters on the same runs, common random
    numbers) are resampled jointly, which narrows the interval by their correlation; a ratio of
    positive means has a positive interval.

    Parameters
    ----------
    numerator, denominator : array_like, shape (n,)
        One value per independent trial each; ``mean(denominator)`` must not be 0.
    """
    a = np.asarray(numerator, dtype=float).ravel()
    b = np.asarray(denominator, dtype=float).ravel()
    if (paired and a.size != b.size) or min(a.size, b.size) < 2:
        raise ValueError(f"ratio_ci needs {'paired ' if paired else ''}samples of size >= 2, "
                         f"got {a.size} and {b.size}")
    if b.mean() == 0:
        raise ValueError("ratio_ci: the denominator's mean is 0")
    return bootstrap_ci((a, b), lambda x, y, axis: x.mean(axis=axis) / y.mean(axis=axis), paired=paired,
                        confidence=confidence, rng=rng)


def paired_difference(a, b, confidence: float = 0.95) -> Estimate:
    """Mean of the paired differences ``a - b`` (common random numbers) with a Student-t interval.

    Differences of errors are roughly symmetric even where the errors are not, so the t interval
    is used; :func:`paired_test` gives the matching two-sided tests.

    Parameters
    ----------
    a, b : array_like, shape (n,)
        The same trials under two methods or conditions.
    """
    a = np.asarray(a, dtype=float).ravel()
    b = np.asarray(b, dtype=float).ravel()
    if a.size != b.size:
        raise ValueError(f"paired_difference needs samples of equal size, got {a.size} and {b.size}")
    d = mean_ci(a - b, confidence)
    return Estimate(d.value, d.stderr, d.ci_low, d.ci_high, d.n, confidence, "paired t")


def paired_test(a, b) -> dict:
    """Two-sided paired tests of ``a`` against ``b``: ``{"t_p": ..., "wilcoxon_p": ..., "n": ...}``
    (Student t on the differences; Wilcoxon signed-rank, robust to heavy tails)."""
    a = np.asarray(a, dtype=float).ravel()
    b = np.asarray(b, dtype=float).ravel()
    d = a - b
    if d.size < 2 or np.all(d == 0):
        return {"t_p": 1.0, "wilcoxon_p": 1.0, "n": int(d.size)}
    return {"t_p": float(stats.ttest_rel(a, b).pvalue), "wilcoxon_p": float(stats.wilcoxon(a, b).pvalue),
            "n": int(d.size)}


def robust_summary(per_trial, divergence_threshold: float, *, trim: float = 0.1, confidence: float = 0.95,
                   rng: np.random.Generator | None = None, what: str = "per-trial mean square") -> dict:
    """Robust companions of a heavy-tailed mean: median, trimmed mean and divergence rate.

    Parameters
    ----------
    per_trial : array_like, shape (n_trials,)
        One value per trial (e.g. steady-state mean squared error).
    divergence_threshold : float
        A trial whose value exceeds it counts as diverged (the rule is returned as text).
    trim : float
        Fraction cut from each end for the trimmed mean (:func:`scipy.stats.trim_mean`).

    Returns
    -------
    dict
        ``median`` (:func:`quantile_ci`), ``trimmed_mean`` (BCa bootstrap), ``divergence_rate``
        (:func:`proportion_ci`), ``divergence_rule`` (text), ``mean_without_diverged``
        (:func:`mean_square_ci` of the trials that did not diverge, or None).
    """
    x = np.asarray(per_trial, dtype=float).ravel()
    diverged = ~(x <= divergence_threshold)            # NaN counts as diverged
    kept = x[~diverged]
    return {
        "median": quantile_ci(x[np.isfinite(x)], 0.5, confidence) if np.isfinite(x).any() else None,
        "trimmed_mean": bootstrap_ci((x[np.isfinite(x)],),
                                     lambda v, axis: stats.trim_mean(v, trim, axis=axis),
                                     confidence=confidence, rng=rng, method="percentile"),
        "divergence_rate": proportion_ci(int(diverged.sum()), x.size, confidence),
        "divergence_rule": f"{what} > {divergence_threshold:.4g} (or not finite)",
        "mean_without_diverged": mean_square_ci(kept, confidence, rng) if kept.size >= 2 and np.all(kept >= 0)
        else (mean_ci(kept, confidence) if kept.size >= 2 else None),
    }


def proportion_ci(successes: int, n: int, confidence: float = 0.95) -> Estimate:
    """A probability from ``successes`` out of ``n`` Bernoulli trials, with the exact
    Clopper-Pearson interval (scipy.stats.binomtest)."""
    if n <= 0:
        raise ValueError(f"proportion_ci needs n >= 1, got n={n}")
    k = int(successes)
    p = k / n
    ci = stats.binomtest(k, n).proportion_ci(confidence_level=confidence, method="exact")
    return Estimate(p, float(np.sqrt(p * (1 - p) / n)), float(ci.low), float(ci.high), n, confidence,
                    "Clopper-Pearson")


def zero_events_bound(n: int, confidence: float = 0.95) -> float:
    """The upper bound on a probability that zero events in ``n`` independent runs certify:
    ``1 - (1 - confidence)^(1/n)`` (one-sided Clopper-Pearson; about ``3/n`` at 95 %)."""
    if n <= 0:
        raise ValueError(f"zero_events_bound needs n >= 1, got n={n}")
    return float(1 - (1 - confidence) ** (1 / n))


def events_statement(k: int, n: int, confidence: float = 0.95) -> str:
    """What ``k`` events in ``n`` runs say, in words: for ``k = 0`` the bound it certifies,
    otherwise the rate with its Clopper-Pearson interval."""
    if k == 0:
        return f"0 of {n} runs: rate < {zero_events_bound(n, confidence):.3g} ({confidence:.0%} one-sided)"
    e = proportion_ci(k, n, confidence)
    return f"{k} of {n} runs: rate {e.value:.3g} [{e.ci_low:.3g}, {e.ci_high:.3g}] ({confidence:.0%} Clopper-Pearson)"


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
    return Estimate(value, float("nan"), lo, hi, n, confidence, "order statistics")
