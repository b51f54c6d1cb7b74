"""Seeded generators and Monte Carlo summaries.

Convention: Monte Carlo arrays carry trials on the leading axis, ``(n_trials, ...)``, and every
random draw comes from a :class:`numpy.random.Generator` made from the run's ``seed``.

This module is the one import path for the interval helpers: it holds the intervals of means, mean
squares, ratios, paired differences and quantiles, and re-exports the measured coverage of those
intervals (:mod:`tvtrack.coverage`) and the probabilities from event counts (:mod:`tvtrack.counts`).
"""

from __future__ import annotations

import functools

import numpy as np
import scipy  # scipy.stats is imported at its first use (scipy loads submodules lazily)

# re-exported: tvtrack.montecarlo.Estimate, the coverage table and the counts helpers keep their import paths
from .counts import events_statement, mark_extrapolated, proportion_ci, rate_from_counts, zero_events_bound
from .coverage import (
    COVERAGE,
    COVERAGE_FLOOR,
    coverage_note,
    coverage_at,
    coverage_reached,
    stated_coverage,
    widen_to_nominal,
)
from .estimate import Estimate
from .resampling import (
    expanded_alpha,
    expanded_percentile_ratio,
    bca_levels,
    grouped_bootstrap,
    means_replicates,
    order_quantiles,
    studentized_mean_interval,
)

__all__ = [
    "make_rng",
    "spawn_rngs",
    "Estimate",
    "mean_ci",
    "bootstrap_ci",
    "mean_square_ci",
    "variance_ci",
    "rms_ci",
    "ratio_ci",
    "means_bootstrap",
    "paired_difference",
    "paired_test",
    "robust_summary",
    "proportion_ci",
    "zero_events_bound",
    "events_statement",
    "quantile_ci",
    "N_BOOTSTRAP",
    "BOOTSTRAP_SEED",
    "COVERAGE",
    "COVERAGE_FLOOR",
    "coverage_at",
    "stated_coverage",
    "coverage_reached",
    "rate_from_counts",
    "mark_extrapolated",
    "widen_to_nominal",
]

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


def mean_ci(samples, confidence: float = 0.95, method: str = "t", rng: np.random.Generator | None = None) -> Estimate:
    """Mean of independent samples with a Student-t (or bootstrap-t) confidence interval.

    The Student-t interval is exact for normal samples; on skewed samples it under-covers at small
    n (measured coverage in :data:`COVERAGE`, stated in ``method`` below 100 samples), where
    ``method="bootstrap-t"`` (studentised bootstrap, :data:`N_BOOTSTRAP` resamples) follows the skew.

    Parameters
    ----------
    samples : array_like, shape (n,)
        One value per independent trial (flattened).
    method : {"t", "bootstrap-t"}
    rng : numpy.random.Generator, optional
        Resampling stream of ``"bootstrap-t"`` (default :data:`BOOTSTRAP_SEED`).
    """
    x = np.asarray(samples, dtype=float).ravel()
    n = x.size
    if n == 0:
        raise ValueError("mean_ci needs at least one sample")
    if method not in ("t", "bootstrap-t"):
        raise ValueError(f"mean_ci: method {method!r} must be 't' or 'bootstrap-t'")
    mean = float(x.mean())
    if n < 2:
        return Estimate(mean, float("nan"), float("nan"), float("nan"), n, confidence)
    se = float(x.std(ddof=1) / np.sqrt(n))
    if se == 0:
        return Estimate(mean, 0.0, mean, mean, n, confidence, "degenerate (all samples equal)")
    if method == "bootstrap-t":
        rng = np.random.default_rng(BOOTSTRAP_SEED) if rng is None else rng
        lo, hi, _ = studentized_mean_interval(x[None], confidence, N_BOOTSTRAP, rng)
        return Estimate(
            mean,
            se,
            float(lo[0]),
            float(hi[0]),
            n,
            confidence,
            f"bootstrap-t ({N_BOOTSTRAP} resamples); " + coverage_note("mean bootstrap-t", n),
        )
    # scipy.stats.t.ppf's own function (special.stdtrit), without the per-call checks: the same number, n >= 2 here
    half = float(scipy.special.stdtrit(n - 1, 0.5 + confidence / 2) * se)
    text = "Student t" + (f"; {coverage_note('mean t', n)}" if n < 100 else "")
    return Estimate(mean, se, mean - half, mean + half, n, confidence, text)


def bootstrap_ci(
    samples,
    statistic,
    *,
    paired: bool = True,
    n_resamples: int = N_BOOTSTRAP,
    confidence: float = 0.95,
    rng: np.random.Generator | None = None,
    method: str = "BCa",
    groups=None,
) -> Estimate:
    """A statistic of independent trials (or of independent clusters of trials) with a bootstrap interval.

    Parameters
    ----------
    samples : sequence of array_like, each shape (n_trials,)
        One value per trial in each sample.
    statistic : callable
        ``statistic(*samples, axis=-1)``, vectorised like NumPy reductions.
    paired : bool
        Resample trials jointly across the samples (common random numbers), or each sample apart.
    n_resamples : int
        At least 2000 by default (:data:`N_BOOTSTRAP`).
    rng : numpy.random.Generator, optional
        The resampling stream; by default a fixed one (:data:`BOOTSTRAP_SEED`), so a summary is a
        pure function of its data.
    method : {"BCa", "percentile", "expanded percentile"}
        ``"BCa"`` (bias-corrected and accelerated) corrects the skew of ratios and mean squares;
        ``"expanded percentile"`` widens the percentile interval for small n (Hesterberg 2015),
        which covers better than BCa below about 50 trials or clusters (``tests/test_intervals.py``).
    groups : array_like, shape (n_trials,), or a sequence of them (one per sample), optional
        Cluster label of each trial (e.g. the seed, path or scene it was drawn with). Whole clusters are
        resampled with replacement (cluster bootstrap), so trials that share a cluster are not treated
        as independent; ``n`` is then the (smallest) number of clusters. Paired: one label array shared
        by all samples, clusters resampled jointly. Not paired: each sample's clusters resampled
        independently (one label array per sample, or one for all). BCa (paired only) takes its
        acceleration from the leave-one-cluster-out jackknife; ``"expanded percentile"`` covers better
        with few clusters (``tests/test_intervals.py``: 0.95 at 15 clusters where BCa gives 0.92).
        Equal cluster sizes are vectorised and keep the trial order, so a statistic of per-trial
        vectors can reshape: flatten rows ``e`` (n, k) with ``groups=np.repeat(np.arange(n), k)`` and
        reshape ``x.reshape(*x.shape[:-1], -1, k)`` inside the statistic (a row bootstrap). Unequal
        sizes evaluate the statistic once per resample.

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
    if all(np.ptp(x) == 0 for x in data):  # constant samples: BCa is undefined, nothing varies
        return Estimate(value, 0.0, value, value, n, confidence, "exact (constant sample)")
    rng = np.random.default_rng(BOOTSTRAP_SEED) if rng is None else rng
    if groups is not None:
        return grouped_bootstrap(data, statistic, value, groups, paired, n_resamples, confidence, rng, method)
    level = confidence
    if method == "expanded percentile":
        level = 1 - expanded_alpha(1 - confidence, n)
    elif method not in ("BCa", "percentile"):
        raise ValueError(f"bootstrap_ci: method {method!r} must be 'BCa', 'percentile' or 'expanded percentile'")
    res = scipy.stats.bootstrap(
        data,
        statistic,
        paired=paired,
        vectorized=True,
        axis=-1,
        n_resamples=n_resamples,
        confidence_level=level,
        method="BCa" if method == "BCa" else "percentile",
        rng=rng,
    )
    lo, hi = float(res.confidence_interval.low), float(res.confidence_interval.high)
    return Estimate(
        value, float(res.standard_error), lo, hi, n, confidence, f"{method} bootstrap ({n_resamples} resamples)"
    )


def mean_square_ci(
    per_trial, confidence: float = 0.95, rng: np.random.Generator | None = None, method: str = "bootstrap-t"
) -> Estimate:
    """Mean of non-negative per-trial values (mean squares, variances) with a bootstrap interval.

    The default is the studentised bootstrap (bootstrap-t, :data:`N_BOOTSTRAP` resamples) with the
    lower end clipped at 0: it follows the right skew of squared errors and, unlike BCa, keeps its
    coverage at the 10-50 trials or paths the notebooks use (measured coverage at 15 per-trial values:
    BCa 0.86-0.93, bootstrap-t 0.94-0.96 on skewed samples; :data:`COVERAGE`, stated in ``method``).
    Heavy tails (log-normal sigma 1, squared Student-t(3)) stay below 95 % at any method and n; report
    :func:`robust_summary` beside it.

    Parameters
    ----------
    per_trial : array_like, shape (n_trials,)
        One non-negative value per independent trial (e.g. a trial's time-averaged squared error).
    method : {"bootstrap-t", "BCa"}
        ``"BCa"``: the earlier interval (:func:`bootstrap_ci`), kept for comparison.
    """
    x = np.asarray(per_trial, dtype=float).ravel()
    if np.any(x < 0):
        raise ValueError("mean_square_ci needs non-negative values (squared errors, variances)")
    if method == "BCa":
        return bootstrap_ci((x,), np.mean, confidence=confidence, rng=rng)
    if method != "bootstrap-t":
        raise ValueError(f"mean_square_ci: method {method!r} must be 'bootstrap-t' or 'BCa'")
    n = x.size
    value = float(x.mean()) if n else float("nan")
    if n < 2 or not np.isfinite(value):
        return Estimate(value, float("nan"), float("nan"), float("nan"), n, confidence, "none (n < 2)")
    if np.ptp(x) == 0:
        return Estimate(value, 0.0, value, value, n, confidence, "exact (constant sample)")
    rng = np.random.default_rng(BOOTSTRAP_SEED) if rng is None else rng
    lo, hi, sd = studentized_mean_interval(x[None], confidence, N_BOOTSTRAP, rng)
    return Estimate(
        value,
        float(sd[0]),
        float(max(lo[0], 0.0)),
        float(hi[0]),
        n,
        confidence,
        f"bootstrap-t ({N_BOOTSTRAP} resamples); {coverage_note('mean_square', n)}",
    )


def variance_ci(
    samples, confidence: float = 0.95, method: str = "bootstrap", rng: np.random.Generator | None = None
) -> Estimate:
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
        lo = (n - 1) * s2 / scipy.stats.chi2.ppf(1 - a / 2, n - 1)
        hi = (n - 1) * s2 / scipy.stats.chi2.ppf(a / 2, n - 1)
        return Estimate(
            s2, float(s2 * np.sqrt(2 / (n - 1))), float(lo), float(hi), n, confidence, "chi-square (normal)"
        )
    if method != "bootstrap":
        raise ValueError(f"variance_ci: method {method!r} must be 'bootstrap' or 'chi2'")
    return bootstrap_ci((x,), lambda v, axis: np.var(v, axis=axis, ddof=1), confidence=confidence, rng=rng)


def rms_ci(errors, axis_trials: int = 0, confidence: float = 0.95, rng: np.random.Generator | None = None) -> Estimate:
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
    return Estimate(
        value,
        se,
        float(np.sqrt(ms.ci_low)),
        float(np.sqrt(ms.ci_high)),
        ms.n,
        confidence,
        f"square root of {ms.method} of per-trial mean squares",
    )


def ratio_ci(
    numerator,
    denominator,
    confidence: float = 0.95,
    paired: bool = True,
    rng: np.random.Generator | None = None,
    method: str = "expanded percentile",
) -> Estimate:
    """``mean(numerator) / mean(denominator)`` with a bootstrap interval.

    Paired samples (e.g. the squared errors of two filters on the same runs or paths, common random
    numbers) are resampled jointly, which narrows the interval by their correlation; a ratio of
    positive means has a positive interval. The default expanded percentile interval (Hesterberg
    2015) keeps its coverage at the 10-50 paths or trials the notebooks use, where BCa covered 0.86-0.92
    (``tests/test_intervals.py``); the measured coverage at ``n`` is stated in ``method``
    (:data:`COVERAGE`, :func:`coverage_reached`).

    Parameters
    ----------
    numerator, denominator : array_like, shape (n,)
        One value per independent trial each; ``mean(denominator)`` must not be 0.
    method : {"expanded percentile", "BCa"}
        ``"BCa"``: the earlier interval (:func:`bootstrap_ci`), kept for comparison.
    """
    a = np.asarray(numerator, dtype=float).ravel()
    b = np.asarray(denominator, dtype=float).ravel()
    if (paired and a.size != b.size) or min(a.size, b.size) < 2:
        raise ValueError(f"ratio_ci needs {'paired ' if paired else ''}samples of size >= 2, got {a.size} and {b.size}")
    if b.mean() == 0:
        raise ValueError("ratio_ci: the denominator's mean is 0")
    if method == "BCa":
        return bootstrap_ci(
            (a, b),
            lambda x, y, axis: x.mean(axis=axis) / y.mean(axis=axis),
            paired=paired,
            confidence=confidence,
            rng=rng,
        )
    if method != "expanded percentile":
        raise ValueError(f"ratio_ci: method {method!r} must be 'expanded percentile' or 'BCa'")
    value = float(a.mean() / b.mean())
    n = min(a.size, b.size)
    if not np.isfinite(value):
        return Estimate(value, float("nan"), float("nan"), float("nan"), n, confidence, "none (ratio not finite)")
    if np.ptp(a) == 0 and np.ptp(b) == 0:
        return Estimate(value, 0.0, value, value, n, confidence, "exact (constant samples)")
    rng = np.random.default_rng(BOOTSTRAP_SEED) if rng is None else rng
    lo, hi, sd = expanded_percentile_ratio(a[None], b[None], confidence, paired, N_BOOTSTRAP, rng)
    return Estimate(
        value,
        float(sd[0]),
        float(lo[0]),
        float(hi[0]),
        n,
        confidence,
        f"expanded percentile bootstrap ({N_BOOTSTRAP} resamples{', paired' if paired else ''}); "
        + coverage_note("ratio", n),
    )


def means_bootstrap(
    samples,
    statistic,
    confidence: float = 0.95,
    rng: np.random.Generator | None = None,
    n_resamples: int = N_BOOTSTRAP,
    method: str = "expanded percentile",
) -> Estimate:
    """A smooth statistic of column means over paired runs, with a bootstrap interval over the runs: the expanded
    percentile interval (Hesterberg 2015; :func:`tvtrack.resampling.expanded_alpha`) or BCa, its acceleration from
    the leave-one-run-out means (Efron & Tibshirani 1993, ch. 14).

    Where :func:`ratio_ci` takes one value per run, this takes a row per run (a run's errors at every frame judged):
    e.g. the mean over frames of the variance over runs, ``mean(m2 - m1**2)`` from the column means ``m1`` of the
    errors and ``m2`` of their squares, of one filter over another's on the same runs. The rows are resampled
    jointly across the samples (:func:`tvtrack.resampling.means_replicates`).

    Parameters
    ----------
    samples : sequence of array_like
        Each (n, k_i): one row per independent run, the same n runs in every sample, in any unit.
    statistic : callable
        ``statistic(*means)``: each mean (..., k_i) the column means of a sample; returns (...), in the result's unit.
    confidence : float
        The nominal coverage.
    rng : numpy.random.Generator, optional
        The resampling stream; by default a fixed one (:data:`BOOTSTRAP_SEED`).
    n_resamples : int
        Bootstrap resamples (default :data:`N_BOOTSTRAP`).
    method : {"expanded percentile", "BCa"}
        The interval. Ratios of 001's functionals (mean squares of the bias, variances, their sums) of errors
        correlated over 200 frames, 300 runs and 400 resamples: 0.944-0.951 expanded percentile, 0.941-0.944 BCa
        (1,000 experiments each, ± 0.007; ``tests/test_intervals.py`` re-measures the bias's at 400).

    Returns
    -------
    Estimate
        ``statistic`` of the samples' column means, with the bootstrap standard error and interval.
    """
    if method not in ("expanded percentile", "BCa"):
        raise ValueError(f"means_bootstrap: method {method!r} must be 'expanded percentile' or 'BCa'")
    data = [np.asarray(x, dtype=float).reshape(len(x), -1) for x in samples]
    n = data[0].shape[0]
    if n < 2 or any(x.shape[0] != n for x in data):
        raise ValueError(f"means_bootstrap needs paired samples of at least 2 runs, got {[x.shape[0] for x in data]}")
    with np.errstate(divide="ignore", invalid="ignore"):
        value = float(statistic(*(x.mean(axis=0) for x in data)))
    if not np.isfinite(value):
        return Estimate(value, float("nan"), float("nan"), float("nan"), n, confidence, "none (statistic not finite)")
    rng = np.random.default_rng(BOOTSTRAP_SEED) if rng is None else rng
    boot = means_replicates(data, statistic, n_resamples, rng)
    defined = boot[~np.isnan(boot)]  # an unbounded replicate (x / 0) is kept: it may make an end infinite
    levels = [expanded_alpha(1 - confidence, n) / 2, 1 - expanded_alpha(1 - confidence, n) / 2]
    if method == "BCa":
        with np.errstate(divide="ignore", invalid="ignore"):  # each run left out: (sum - row) / (n - 1)
            jack = statistic(*((x.sum(axis=0) - x) / (n - 1) for x in data))
        levels = bca_levels(defined, value, jack, confidence) if np.isfinite(jack).all() else [np.nan, np.nan]
    # a statistic undefined on many resamples (0 / 0 often) has no interval, as in the cluster bootstrap; nor has BCa
    # where a run left out leaves it undefined or unbounded
    if defined.size >= 0.9 * n_resamples and np.isfinite(levels).all():
        lo, hi = order_quantiles(defined, levels)
    else:
        lo, hi = np.nan, np.nan
    finite = defined[np.isfinite(defined)]
    return Estimate(
        value,
        float(np.std(finite, ddof=1)) if finite.size > 1 else float("nan"),
        float(lo),
        float(hi),
        n,
        confidence,
        f"{method} bootstrap over {n} runs ({n_resamples} resamples, paired)",
    )


def paired_difference(a, b, confidence: float = 0.95) -> Estimate:
    """Mean of the paired differences ``a - b`` (common random numbers) with a Student-t interval.

    Differences of errors are roughly symmetric even where the errors are not, so the t interval
    is used; :func:`paired_test` gives the matching two-sided tests. Paired 0/1 outcomes (e.g. lost
    lock or not) that never differ give the bound zero discordant pairs certify, ``|p_a - p_b| <=
    P(discordant) < 1 - 0.05^(1/n)`` (:func:`zero_events_bound`); other equal differences give a
    zero-width interval that says ``degenerate``: it certifies nothing, and a rule must not decide on it.
    Coverage of 0/1 differences (``tests/test_intervals.py``): 0.93-0.95 where pairs differ at 10-48
    trials; the t interval alone covered 0.40-0.78 at 10-30 trials with rare discordance (all-zero
    differences).

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
    if d.method.startswith("degenerate"):
        if d.value == 0 and np.all(np.isin(a, (0.0, 1.0))) and np.all(np.isin(b, (0.0, 1.0))):
            bound = zero_events_bound(d.n, confidence)  # no discordant pair: |p_a - p_b| <= P(discordant)
            return Estimate(
                0.0,
                float("nan"),
                -bound,
                bound,
                d.n,
                confidence,
                f"paired 0/1 outcomes, no discordant pair in {d.n}: |difference| < {bound:.3g} "
                "(zero-events bound on the discordant share)",
            )
        return Estimate(
            d.value, d.stderr, d.ci_low, d.ci_high, d.n, confidence, "paired t, degenerate (all differences equal)"
        )
    return Estimate(d.value, d.stderr, d.ci_low, d.ci_high, d.n, confidence, "paired t" + d.method[len("Student t") :])


def paired_test(a, b) -> dict:
    """Two-sided paired tests of ``a`` against ``b``: ``{"t_p": ..., "wilcoxon_p": ..., "n": ...}``
    (Student t on the differences; Wilcoxon signed-rank, robust to heavy tails)."""
    a = np.asarray(a, dtype=float).ravel()
    b = np.asarray(b, dtype=float).ravel()
    d = a - b
    if d.size < 2 or np.all(d == 0):
        return {"t_p": 1.0, "wilcoxon_p": 1.0, "n": int(d.size)}
    return {
        "t_p": float(scipy.stats.ttest_rel(a, b).pvalue),
        "wilcoxon_p": float(scipy.stats.wilcoxon(a, b).pvalue),
        "n": int(d.size),
    }


def robust_summary(
    per_trial,
    divergence_threshold: float,
    *,
    trim: float = 0.1,
    confidence: float = 0.95,
    rng: np.random.Generator | None = None,
    what: str = "per-trial mean square",
) -> dict:
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
    diverged = ~(x <= divergence_threshold)  # NaN counts as diverged
    kept = x[~diverged]
    return {
        "median": quantile_ci(x[np.isfinite(x)], 0.5, confidence) if np.isfinite(x).any() else None,
        "trimmed_mean": bootstrap_ci(
            (x[np.isfinite(x)],),
            lambda v, axis: scipy.stats.trim_mean(v, trim, axis=axis),
            confidence=confidence,
            rng=rng,
            method="percentile",
        ),
        "divergence_rate": proportion_ci(int(diverged.sum()), x.size, confidence),
        "divergence_rule": f"{what} > {divergence_threshold:.4g} (or not finite)",
        "mean_without_diverged": mean_square_ci(kept, confidence, rng)
        if kept.size >= 2 and np.all(kept >= 0)
        else (mean_ci(kept, confidence) if kept.size >= 2 else None),
    }


def quantile_ci(samples, q: float, confidence: float = 0.95) -> Estimate:
    """The ``q`` quantile of independent samples with a distribution-free (order-statistic)
    confidence interval ``[x_(l), x_(u)]``.

    The ranks are chosen from Binomial(n, q) so that each tail holds at most ``(1 - confidence)/2``;
    the interval's coverage is then exact for continuous samples, ``P(l <= K < u)`` with
    ``K ~ Binomial(n, q)``, and stated in ``method``. Where n is too small for the ranks to exist
    (e.g. the 95 % quantile from 10 samples needs a rank beyond the largest), the nearest order
    statistic is used and the stated coverage is below ``confidence`` (:func:`coverage_reached`).
    """
    x = np.sort(np.asarray(samples, dtype=float).ravel())
    n = x.size
    if n == 0:
        raise ValueError("quantile_ci needs at least one sample")
    value = float(np.quantile(x, q))
    l, u, coverage = _order_ranks(n, q, confidence)
    lo = float(x[l - 1])
    hi = float(x[u - 1])
    note = "" if coverage >= confidence else ", too few samples for both ranks"
    return Estimate(
        value,
        float("nan"),
        lo,
        hi,
        n,
        confidence,
        f"order statistics (coverage {coverage:.3f} at n = {n}, exact for continuous samples{note})",
    )


@functools.lru_cache(maxsize=1024)
def _order_ranks(n: int, q: float, confidence: float) -> tuple[int, int, float]:
    """:func:`quantile_ci`'s 1-based ranks ``(l, u)`` and their exact coverage ``P(l <= K < u)``, ``K ~
    Binomial(n, q)``: a function of the sizes alone, kept for the next call with the same ones."""
    lo_rank = int(scipy.stats.binom.ppf((1 - confidence) / 2, n, q))  # l: P(K < l) <= a/2
    hi_rank = int(scipy.stats.binom.ppf(0.5 + confidence / 2, n, q))  # u - 1: P(K >= u) <= a/2
    l, u = max(lo_rank, 1), min(hi_rank + 1, n)  # 1-based ranks that exist
    return l, u, float(scipy.stats.binom.cdf(u - 1, n, q) - scipy.stats.binom.cdf(l - 1, n, q))
