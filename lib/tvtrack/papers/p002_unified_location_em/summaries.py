"""Summaries of the per-trial errors of one configuration (paper 002): errors at an epoch, variance and MSE sums with
bootstrap intervals, ratios of variance sums (the gain rho), bootstrap over independent groups of trials, and failure
rates. Units: the errors' (sigma and sigma/frame after :func:`.simulation.errors_vs_truth`); ratios are unit-free.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from scipy import stats

from tvtrack.montecarlo import N_BOOTSTRAP, bootstrap_ci, mean_square_ci
from tvtrack.estimate import Estimate
from ._spread_kernel import variance_sum_rows
from . import ratio_coverage as _rc
from .ratio_coverage import ratio_coverage_note

__all__ = [
    "FLAG_NAMES",
    "SPREADS",
    "position_errors",
    "centred_squares",
    "variance_sum",
    "mse_sum",
    "bootstrap_groups",
    "variance_ratio_ci",
    "gross_errors",
    "ratio_interval_coverage",
]

#: Columns of the per-trial flag arrays ``ula_flags``, ``em_flags`` and ``cr_flags``.
FLAG_NAMES = {
    "ula": ("swap", "merge", "cap_hit", "degenerate", "left_frame"),
    "em": ("swap", "line_fit_invalid", "cap_hit", "missing_marks"),
    "cr": ("swap", "line_fit_invalid"),
}


def position_errors(result: dict, alg: str, epoch: str = "first", trials=None) -> np.ndarray:
    """Errors of one algorithm at one epoch, shape (n, 2Q), sigma (sigma/frame for velocity).

    Parameters
    ----------
    result : dict
        A :func:`run_config` result.
    alg : str
        ``"ula"``, ``"plain"``, ``"em"``, ``"cr"`` or another error array of ``result``.
    epoch : {"first", "mid", "last", "velocity"}
        Position error at the first frame ``t = 0`` (the paper's "initial position", an
        extrapolated end of the fitted line), at the middle ``t = (T-1)/2`` (where a line fit is
        most accurate), at the last frame ``t = T-1``, or the velocity error.
    trials : array of bool or int, optional
        The trials to keep.
    """
    e = result[alg] if trials is None else result[alg][trials]
    t_last = result["T"] - 1
    t = {"first": 0.0, "mid": t_last / 2, "last": float(t_last), "velocity": None}
    if epoch not in t:
        raise ValueError(f"epoch = {epoch!r} must be one of {list(t)}")
    out = e[..., 2:4] if epoch == "velocity" else e[..., :2] + t[epoch] * e[..., 2:4]
    return out.reshape(len(e), -1)


def centred_squares(e) -> np.ndarray:
    """Per-trial summed squared deviations from the column means, ``n/(n-1)`` corrected, shape (n,):
    their mean is the sum of the column variances of ``e`` (n, k)."""
    e = np.asarray(e, dtype=float)
    return ((e - e.mean(axis=0)) ** 2).sum(axis=1) * len(e) / (len(e) - 1)


def variance_sum(e) -> Estimate:
    """Sum of the variances of the columns of ``e`` (n, k) with a BCa bootstrap interval of the
    per-trial centred squares (never below zero; the mean's own uncertainty is second order)."""
    return mean_square_ci(centred_squares(e))


def mse_sum(e) -> Estimate:
    """Sum of the mean squared values of the columns of ``e`` (n, k), with a BCa bootstrap interval."""
    return mean_square_ci((np.asarray(e, dtype=float) ** 2).sum(axis=1))


def bootstrap_groups(
    groups, statistic, rng: np.random.Generator, n_bootstrap: int = N_BOOTSTRAP, confidence: float = 0.95
) -> Estimate:
    """A statistic of several independent groups of trials with a percentile bootstrap interval
    (:func:`tvtrack.montecarlo.bootstrap_ci` with trials as clusters of their ``k_g`` values).

    The rows (trials) of each group are resampled jointly (a group holds the paired errors of
    several algorithms on the same scenes); different groups (different configurations, drawn
    from different seeds) are resampled independently.

    Parameters
    ----------
    groups : sequence of ndarray, each shape (n_g, k_g)
        Per-trial values, one row per trial.
    statistic : callable
        ``statistic(*arrays)`` with arrays of shape (B, n_g, k_g) returns shape (B,).
    rng : numpy.random.Generator
        Draws the resample indices.
    n_bootstrap : int
        Resamples (at least 2000 for 95 % tails).

    Returns
    -------
    Estimate
        The statistic on the data, the bootstrap standard deviation, the percentile interval,
        ``n`` the smallest group size. Resamples whose statistic is not finite (a resample of a
        few trials that repeats one trial has zero variance) are left out.
    """
    groups = [np.asarray(g, dtype=float).reshape(len(g), -1) for g in groups]
    ks = [g.shape[1] for g in groups]
    labels = [np.repeat(np.arange(len(g)), k) for g, k in zip(groups, ks)]

    def stat(*flat, axis=-1):  # the one bootstrap hands over rows flattened: reshape to (B, n_g, k_g)
        arrs = [np.asarray(x).reshape(*np.shape(x)[:-1], -1, k) for x, k in zip(flat, ks)]
        with np.errstate(divide="ignore", invalid="ignore"):  # a resample of few trials can repeat one trial
            out = statistic(*[a if a.ndim == 3 else a[None] for a in arrs])
        return out if np.ndim(flat[0]) > 1 else float(np.ravel(out)[0])

    paired = len(groups) == 1
    return bootstrap_ci(
        [g.ravel() for g in groups],
        stat,
        paired=paired,
        groups=labels[0] if paired else labels,
        rng=rng,
        n_resamples=n_bootstrap,
        confidence=confidence,
        method="percentile",
    )


def _var_sum(e):
    """Summed column variances of resampled errors (B, n, k) -> (B,) (compiled, NumPy's bits)."""
    return variance_sum_rows(e)


def _mean_square_sum(e):
    return (e**2).mean(axis=1).sum(axis=-1)


def _trimmed_var_sum(e, trim: float = 0.1):
    """10 %-trimmed mean of the per-trial centred squares (B, n, k) -> (B,): a variance sum that a few
    gross errors cannot dominate."""
    c = ((e - np.median(e, axis=1, keepdims=True)) ** 2).sum(axis=-1)
    return stats.trim_mean(c, trim, axis=1)


def _median_square(e):
    """Median of the per-trial summed squared errors (B, n, k) -> (B,)."""
    return np.median((e**2).sum(axis=-1), axis=1)


#: Spread statistics of :func:`variance_ratio_ci`: a sum over coordinates of (B, n, k) -> (B,).
SPREADS = {
    "variance": _var_sum,
    "mse": _mean_square_sum,
    "trimmed_variance": _trimmed_var_sum,
    "median_square": _median_square,
}


def variance_ratio_ci(
    e_num,
    e_den,
    rng: np.random.Generator,
    n_bootstrap: int = N_BOOTSTRAP,
    paired: bool = True,
    mse: bool = False,
    sqrt: bool = False,
    spread: str = "variance",
) -> Estimate:
    """Ratio of summed column variances (or another spread) of two error samples, with a
    percentile bootstrap CI.

    Unlike :func:`tvtrack.montecarlo.ratio_ci` (a ratio of means), this is a ratio of variance
    *sums*, e.g. the gain ``rho = Sigma^2_traj / Sigma^2_ULA``.

    Parameters
    ----------
    e_num, e_den : ndarray, shape (n1, k) and (n2, k)
        Per-trial errors (any unit; the ratio is unit-free).
    rng : numpy.random.Generator
        Draws the resample indices.
    n_bootstrap : int
        Number of resamples.
    paired : bool
        Resample trials jointly (same samples for both, requires ``n1 == n2``; otherwise
        independent resamples).
    mse : bool
        Shorthand for ``spread="mse"`` (summed mean squares instead of variances).
    sqrt : bool
        Report the square root (ratio of RMS / standard deviations).
    spread : {"variance", "mse", "trimmed_variance", "median_square"}
        The spread statistic (:data:`SPREADS`): the last two are robust to a few gross errors.

    Returns
    -------
    Estimate
        Point ratio, bootstrap standard deviation, 2.5 % and 97.5 % quantiles, ``min(n1, n2)``. For the variance
        and MSE spreads the ``method`` states the interval's coverage measured at ``n`` (the worst of normal,
        Student t5 and 2 % gross errors, :mod:`.ratio_coverage`), which :func:`tvtrack.measured.calibrated` reads
        to widen an interval short of 95 %; the robust spreads' coverage is not measured and not stated.
    """
    f = SPREADS["mse" if mse else spread]
    e_num, e_den = np.asarray(e_num, float), np.asarray(e_den, float)
    k = e_num.shape[1]
    if paired:
        if len(e_num) != len(e_den):
            raise ValueError(f"paired ratio needs equal sample sizes, got {len(e_num)} and {len(e_den)}")
        r = bootstrap_groups([np.hstack([e_num, e_den])], lambda e: f(e[..., :k]) / f(e[..., k:]), rng, n_bootstrap)
    else:
        r = bootstrap_groups([e_num, e_den], lambda a, b: f(a) / f(b), rng, n_bootstrap)
    if f in (_var_sum, _mean_square_sum):  # the spreads whose coverage was measured (ratio_coverage.py)
        r = replace(r, method=f"{r.method}; {ratio_coverage_note(r.n)}")
    return _square_root(r) if sqrt else r


def _square_root(r: Estimate) -> Estimate:
    """The square root of a ratio estimate (a ratio of standard deviations): the interval maps end by end, the
    standard error by the delta method; a ratio of 0 (a numerator that never varies, such as a velocity given
    exactly) keeps a zero standard error where every resample was 0, else it is undefined (NaN), not a number."""
    if r.value > 0:
        se = r.stderr / (2 * np.sqrt(r.value))
    else:
        se = 0.0 if r.stderr == 0 and r.value == 0 else float("nan")
    root = np.sqrt(np.maximum([r.value, r.ci_low, r.ci_high], 0.0))
    return Estimate(float(root[0]), float(se), float(root[1]), float(root[2]), r.n, r.confidence, r.method)


def gross_errors(result: dict, alg: str, limit_sigma: float = 2.0) -> np.ndarray:
    """Trials (n,) in which some position error exceeds ``limit_sigma``."""
    return (np.abs(result[alg][..., :2]) > limit_sigma).any(axis=(1, 2))


def ratio_interval_coverage(case: str, n: int, experiments: int = _rc.N_EXPERIMENTS) -> float:
    """The share of the first ``experiments`` simulated experiments of ``case`` at ``n`` trials
    (:func:`.ratio_coverage.draw`) whose :func:`variance_ratio_ci` (paired, 2000 resamples, as the claims compute it)
    holds the true ratio: what :data:`.ratio_coverage.RATIO_COVERAGE` tabulates."""
    hits = 0
    for r in range(experiments):
        e = variance_ratio_ci(*_rc.draw(case, n, r), np.random.default_rng([_rc.SEED, n, r]), 2000)
        hits += e.ci_low <= _rc.TRUE_RATIO <= e.ci_high
    return hits / experiments


if __name__ == "__main__":  # prints ratio_coverage.RATIO_COVERAGE (a few minutes)
    for size in _rc.RATIO_COVERAGE:
        print(f"    {size}: ({', '.join(f'{ratio_interval_coverage(c, size):.3f}' for c in _rc.CASES)}),", flush=True)
