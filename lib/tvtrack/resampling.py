"""The bootstrap machinery behind :mod:`tvtrack.montecarlo`'s intervals: resample weights in memory-bounded
blocks, the studentised (bootstrap-t) interval of a mean, the expanded percentile interval of a ratio
(Hesterberg 2015) and the cluster bootstrap. A notebook uses the interval functions of :mod:`tvtrack.montecarlo`,
which call these."""

from __future__ import annotations

import numpy as np
import scipy  # scipy.stats is imported at its first use (scipy loads submodules lazily)

from .estimate import Estimate

__all__ = [
    "expanded_alpha",
    "studentized_mean_interval",
    "expanded_percentile_ratio",
    "means_replicates",
    "order_quantiles",
    "bca_levels",
    "grouped_bootstrap",
]


def expanded_alpha(alpha: float, n: int) -> float:
    """Tail probability of the expanded percentile bootstrap (Hesterberg 2015, "What teachers should
    know about the bootstrap", sec. 5.4): ``2 Phi(-sqrt(n/(n-1)) t_{alpha/2, n-1})``, which widens
    the percentile interval by the t and ``n/(n-1)`` factors its narrowness at small n lacks.

    Parameters
    ----------
    alpha : float
        The nominal two-sided tail probability (``1 - confidence``).
    n : int
        The sample size (at least 2).

    Returns
    -------
    float
        The smaller tail probability whose percentile interval the expanded method reads.
    """
    return float(2 * scipy.stats.norm.cdf(np.sqrt(n / (n - 1)) * scipy.stats.t.ppf(alpha / 2, n - 1)))


def _quantiles(boot: np.ndarray, probs) -> np.ndarray:
    """Quantiles over the last axis ignoring NaN (``boot`` (..., B)), shape (len(probs), ...).

    Rows without NaN go through ``numpy.quantile`` in one vectorised call (the same numbers as ``nanquantile``,
    which works row by row and took most of an interval's time at 2000 rows); only rows holding a NaN are
    read by ``nanquantile``."""
    boot = np.asarray(boot)
    nan_rows = np.isnan(boot).any(axis=-1)
    with np.errstate(invalid="ignore"):  # infinite replicates: inf - inf between two of them, as in nanquantile
        if boot.ndim < 2 or nan_rows.all():
            return np.nanquantile(boot, probs, axis=-1)
        out = np.quantile(boot, probs, axis=-1)
        if nan_rows.any():
            out[:, nan_rows] = np.nanquantile(boot[nan_rows], probs, axis=-1)
    return out


def _resample_weights(idx: np.ndarray, n: int) -> np.ndarray:
    """Resample counts ``W`` (B, n) from resample indices ``idx`` (B, n): ``W @ x / n`` is the mean of a resample."""
    B = idx.shape[0]
    return np.bincount((idx + n * np.arange(B)[:, None]).ravel(), minlength=B * n).reshape(B, n).astype(float)


def _blocks(n_resamples: int, width: int):
    """Slices of the resamples, at most about 4e6 weights each (memory stays small at any n)."""
    step = max(1, int(4e6 // max(width, 1)))
    return [slice(j, min(j + step, n_resamples)) for j in range(0, n_resamples, step)]


def studentized_mean_interval(
    x: np.ndarray, confidence: float, n_resamples: int, rng: np.random.Generator
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bootstrap-t (studentised) interval of the mean of each row of ``x`` (R, n).

    ``T* = (mean* - mean) / (sd* / sqrt(n))`` over resamples; the interval is
    ``[mean - q_{1-a/2}(T*) se, mean - q_{a/2}(T*) se]`` with ``se = sd / sqrt(n)`` (Efron and
    Tibshirani 1993, sec. 12.5). Returns ``lo, hi, sd_boot`` (R,), ``sd_boot`` the bootstrap standard
    deviation of the mean. The resample indices are shared by the rows (independent experiments).
    """
    R, n = x.shape
    m = x.mean(axis=1)
    xc = x - m[:, None]  # centred: no cancellation in the moments
    se = xc.std(axis=1, ddof=1) / np.sqrt(n)
    idx = rng.integers(0, n, size=(n_resamples, n))
    t = np.empty((R, n_resamples))
    mb = np.empty((R, n_resamples))
    for sl in _blocks(n_resamples, n):
        W = _resample_weights(idx[sl], n) / n  # (b, n)
        m1 = xc @ W.T  # (R, b) resample mean minus the mean
        m2 = (xc**2) @ W.T
        sd = np.sqrt(np.maximum(m2 - m1**2, 0.0) * n / (n - 1)) / np.sqrt(n)
        with np.errstate(divide="ignore", invalid="ignore"):
            t[:, sl] = m1 / sd
        mb[:, sl] = m1
    t[np.isnan(t)] = 0.0  # a resample of one repeated value at the mean
    a = 1 - confidence
    q_lo, q_hi = _quantiles(t, [a / 2, 1 - a / 2])
    return m - q_hi * se, m - q_lo * se, mb.std(axis=1, ddof=1)


def _ratio_replicates(
    a: np.ndarray, b: np.ndarray, paired: bool, n_resamples: int, rng: np.random.Generator
) -> np.ndarray:
    """Bootstrap replicates of ``mean(a) / mean(b)`` per row, ``a`` (R, n_a), ``b`` (R, n_b) -> (R, B);
    paired: the same trial indices for both (``n_a == n_b``). Not finite replicates are NaN."""
    na, nb = a.shape[1], b.shape[1]
    ia = rng.integers(0, na, size=(n_resamples, na))
    ib = ia if paired else rng.integers(0, nb, size=(n_resamples, nb))
    out = np.empty((a.shape[0], n_resamples))
    for sl in _blocks(n_resamples, max(na, nb)):
        Wa = _resample_weights(ia[sl], na)
        Wb = Wa if paired else _resample_weights(ib[sl], nb)
        with np.errstate(divide="ignore", invalid="ignore"):
            out[:, sl] = (a @ Wa.T / na) / (b @ Wb.T / nb)
    out[~np.isfinite(out)] = np.nan
    return out


def expanded_percentile_ratio(
    a: np.ndarray, b: np.ndarray, confidence: float, paired: bool, n_resamples: int, rng: np.random.Generator
):
    """Expanded percentile interval of ``mean(a) / mean(b)`` per row (Hesterberg 2015; :func:`expanded_alpha`).

    Parameters
    ----------
    a, b : numpy.ndarray
        Samples (R, n) of numerator and denominator, in any one unit each.
    confidence : float
        The nominal coverage (e.g. 0.95).
    paired : bool
        Resample ``a`` and ``b`` jointly (common random numbers) or independently.
    n_resamples : int
        Bootstrap resamples.
    rng : numpy.random.Generator
        The seeded generator the resamples are drawn from.

    Returns
    -------
    tuple of numpy.ndarray
        ``lo, hi, se_boot``, each (R,), in the unit of the ratio.
    """
    n = min(a.shape[1], b.shape[1])
    a2 = expanded_alpha(1 - confidence, n) / 2
    boot = _ratio_replicates(a, b, paired, n_resamples, rng)
    lo, hi = _quantiles(boot, [a2, 1 - a2])
    with np.errstate(invalid="ignore"):
        return lo, hi, np.nanstd(boot, axis=1, ddof=1)


def bca_levels(boot: np.ndarray, value: float, jack: np.ndarray, confidence: float) -> np.ndarray:
    """The two quantile levels of the BCa interval (Efron & Tibshirani 1993, eqs. 14.9-14.15): the bias correction
    ``z0`` from the share of finite replicates ``boot`` below ``value``, the acceleration from the leave-one-out
    (or leave-one-cluster-out) values ``jack``."""
    z0 = scipy.stats.norm.ppf(
        np.clip((np.sum(boot < value) + 0.5 * np.sum(boot == value)) / boot.size, 1 / boot.size, 1 - 1 / boot.size)
    )
    d = jack.mean() - jack
    acc = np.sum(d**3) / (6 * np.sum(d**2) ** 1.5) if np.sum(d**2) > 0 else 0.0
    a = 1 - confidence
    z = scipy.stats.norm.ppf([a / 2, 1 - a / 2])
    return scipy.stats.norm.cdf(z0 + (z0 + z) / (1 - acc * (z0 + z)))


def means_replicates(samples, statistic, n_resamples: int, rng: np.random.Generator) -> np.ndarray:
    """Bootstrap replicates (B,) of ``statistic(*means)`` (NaN where it is undefined, ``inf`` where it is unbounded), where each mean is a sample's column means (..., k) over
    one resample of its rows: the rows (runs) are resampled jointly across the samples (paired), and a resample's
    means are its counts ``W`` (B, n) times the sample, ``W @ x / n``, so no resampled copy of the rows is made.

    Parameters
    ----------
    samples : sequence of numpy.ndarray
        Each (n, k_i): one row per independent run, the same runs in every sample.
    statistic : callable
        ``statistic(*means)``, each mean (b, k_i), returns (b,).
    n_resamples : int
        Bootstrap resamples B.
    rng : numpy.random.Generator
        The seeded generator the resamples are drawn from.
    """
    n = samples[0].shape[0]
    idx = rng.integers(0, n, size=(n_resamples, n))
    out = np.empty(n_resamples)
    for sl in _blocks(n_resamples, n + sum(x.shape[1] for x in samples)):  # W and every W @ x of a block
        W = _resample_weights(idx[sl], n) / n
        with np.errstate(divide="ignore", invalid="ignore"):
            out[sl] = statistic(*(W @ x for x in samples))
    return out


def order_quantiles(values: np.ndarray, levels) -> np.ndarray:
    """Quantiles at ``levels`` of ``values`` that may hold ``-inf`` or ``inf`` (no NaN), read between order statistics
    as ``numpy.quantile``'s linear rule does: a level whose neighbouring order statistics reach an infinite value is
    that infinity (a ratio whose denominator is 0 in some resamples has an unbounded end there)."""
    v = np.sort(np.asarray(values, dtype=float))
    pos = np.asarray(levels, dtype=float) * (v.size - 1)
    lo, hi = v[np.floor(pos).astype(int)], v[np.ceil(pos).astype(int)]
    with np.errstate(invalid="ignore"):
        out = np.quantile(v, levels)  # finite neighbours: numpy's own numbers, bit for bit
    out = np.where(hi == np.inf, np.inf, out)
    return np.where(lo == -np.inf, -np.inf, out)


def _cluster_members(groups: np.ndarray) -> list[np.ndarray]:
    """Indices of the trials of each cluster (in order of first appearance of the labels)."""
    _, first, inverse = np.unique(groups, return_index=True, return_inverse=True)
    order = np.argsort(first)
    return [np.flatnonzero(inverse == k) for k in order]


def _cluster_indices(members: list[np.ndarray], picks: np.ndarray) -> np.ndarray | list[np.ndarray]:
    """Trial indices of the clusters picked in each row of ``picks`` (B, c): an array (B, c * m) for
    clusters of equal size m (cluster order and trial order kept), else a list of B index arrays."""
    if len({len(m) for m in members}) == 1:
        return np.stack(members)[picks].reshape(len(picks), -1)
    return [np.concatenate([members[k] for k in row]) for row in picks]


def _picked_rows(x: np.ndarray, members: list[np.ndarray], picks: np.ndarray) -> np.ndarray:
    """``x[_cluster_indices(members, picks)]`` for clusters of equal size m, shape (B, c * m): where the clusters are
    the consecutive blocks of m trials in order (a row bootstrap: trial i the values ``x[i m : (i + 1) m]``), whole
    blocks are copied, the same values in the same order without an index per value."""
    stacked = np.stack(members)
    if x.size == stacked.size and np.array_equal(stacked.ravel(), np.arange(x.size)):
        return x.reshape(stacked.shape)[picks].reshape(len(picks), -1)
    return x[stacked[picks].reshape(len(picks), -1)]


def _cluster_statistics(data, statistic, members, picks) -> np.ndarray:
    """``statistic`` on the picked clusters of each sample (B,): ``members`` and ``picks`` hold one
    entry per sample (the same entry for paired samples). Equal cluster sizes are evaluated in one
    vectorised call, unequal sizes resample by resample."""
    if all(len({len(k) for k in m}) == 1 for m in members):
        with np.errstate(divide="ignore", invalid="ignore"):
            rows = (_picked_rows(x, m, p) for x, m, p in zip(data, members, picks))
            return np.asarray(statistic(*rows, axis=-1), dtype=float)
    idx = [_cluster_indices(m, p) for m, p in zip(members, picks)]
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.array(
            [float(statistic(*(x[i[j]] for x, i in zip(data, idx)), axis=-1)) for j in range(len(picks[0]))]
        )


def grouped_bootstrap(
    data,
    statistic,
    value: float,
    groups,
    paired: bool,
    n_resamples: int,
    confidence: float,
    rng: np.random.Generator,
    method: str,
) -> Estimate:
    """Cluster bootstrap of :func:`tvtrack.montecarlo.bootstrap_ci`: whole clusters resampled with replacement,
    jointly across paired samples (one label array) or independently per sample (one label array each).

    Parameters
    ----------
    data : sequence of array_like
        The samples ``statistic`` reads (one per argument).
    statistic : callable
        ``statistic(*samples) -> float``, in the unit of the result.
    value : float
        The statistic on the data as they are.
    groups : array_like or sequence of array_like
        Cluster labels of the trials: one array for all samples, or one per sample.
    paired : bool
        Resample the samples' clusters jointly.
    n_resamples : int
        Bootstrap resamples.
    confidence : float
        The nominal coverage.
    rng : numpy.random.Generator
        The seeded generator the resamples are drawn from.
    method : str
        The interval method, ``"percentile"`` or ``"expanded"`` (as :func:`tvtrack.montecarlo.bootstrap_ci`).

    Returns
    -------
    Estimate
        The value with its cluster-bootstrap interval.
    """
    labels = (
        [np.asarray(groups).ravel()] * len(data)
        if paired or np.ndim(groups[0]) == 0
        else [np.asarray(g).ravel() for g in groups]
    )
    if len(labels) != len(data) or any(x.size != g.size for x, g in zip(data, labels)):
        raise ValueError(
            f"bootstrap_ci: 'groups' has {[g.size for g in labels]} labels, the samples {[x.size for x in data]} trials"
        )
    members = [_cluster_members(g) for g in labels]
    sizes = [len(m) for m in members]
    C = min(sizes)
    if C < 2:
        return Estimate(value, float("nan"), float("nan"), float("nan"), C, confidence, "none (fewer than 2 clusters)")
    if paired:
        picks = [rng.integers(0, C, size=(n_resamples, C))] * len(data)
    else:
        picks = [rng.integers(0, c, size=(n_resamples, c)) for c in sizes]
    boot = _cluster_statistics(data, statistic, members, picks)
    boot = boot[np.isfinite(boot)]
    a = 1 - confidence
    if method == "percentile":
        probs = [a / 2, 1 - a / 2]
    elif method == "expanded percentile":
        a2 = expanded_alpha(a, C) / 2
        probs = [a2, 1 - a2]
    elif method == "BCa":
        if not paired:
            raise ValueError("bootstrap_ci: BCa with clusters needs paired samples; use 'expanded percentile'")
        leave_one_out = np.array([[k for k in range(C) if k != i] for i in range(C)])
        jack = _cluster_statistics(data, statistic, members, [leave_one_out] * len(data))
        probs = bca_levels(boot, value, jack, confidence)
    else:
        raise ValueError(f"bootstrap_ci: method {method!r} must be 'BCa', 'percentile' or 'expanded percentile'")
    lo, hi = np.quantile(boot, probs) if boot.size >= 0.9 * n_resamples else (np.nan, np.nan)
    what = f"{C} clusters" if paired or len(set(sizes)) == 1 else f"{'/'.join(map(str, sizes))} clusters"
    return Estimate(
        value,
        float(boot.std(ddof=1)) if boot.size > 1 else float("nan"),
        float(lo),
        float(hi),
        C,
        confidence,
        f"cluster {method} bootstrap ({n_resamples} resamples of {what})",
    )
