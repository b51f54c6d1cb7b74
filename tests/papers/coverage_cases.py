"""Coverage of notebook 003's threshold estimators at six runs a replicate, and of a t interval over three replicate
values (C004-4, C004-8), at the sizes the records use (``docs/interval_coverage.md``).

``PYTHONPATH=lib python tests/papers/coverage_cases.py`` prints the rows: the geometric-mean threshold and the paired
threshold ratio on the notebook's SIR grid, per-run log thresholds scattered normally, skewed (exponential) or with
Student-t(3) tails, the place in the grid at random (seeded, 4,000 experiments a row; experiments with a run broken
outside the grid are left out, and with them the bounds censoring certifies); the paired share difference's exact
coverage over every outcome of six (and eighteen) runs whose difference is -1, 0 or +1, its lowest over a grid of
probabilities 0.01 apart; the t interval over three values of four laws (100,000 experiments each); and a pooled
fold distance from 1 (C002-13, C003-11's ``bandwidth``) of replicates of a log-normal ratio, folded before or after
the pool (2,000 experiments a row).
``tests/papers/test_003_estimators.py`` re-measures the ratio's rows that failed before its allowance was a step.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import stats

from tvtrack.estimate import Estimate
from tvtrack.measured import fold_about
from tvtrack.montecarlo import ratio_ci
from tvtrack.pooling import pool
from tvtrack.verdicts import InBand
from tvtrack.papers.p003_rotating_marker_tracker.curves import SIR_GRID
from tvtrack.papers.p003_rotating_marker_tracker.estimators import share_difference, threshold, threshold_ratio

GRID = np.array(SIR_GRID)
LOG = np.log(GRID)


def scatter(rng: np.random.Generator, kind: str, n: int, s: float) -> np.ndarray:
    """``n`` log-threshold deviations of spread ``s`` (standard deviation) with mean 0."""
    z = {"normal": rng.standard_normal, "skewed": lambda k: rng.exponential(1.0, k) - 1.0}.get(kind)
    return s * (z(n) if z else rng.standard_t(3, n) / math.sqrt(3))


def lost(log_thresholds: np.ndarray) -> np.ndarray:
    """Loss of lock on :data:`GRID` for runs breaking at ``exp(log_thresholds)`` (lost below, kept from it on)."""
    return GRID[:, None] < np.exp(log_thresholds)[None, :]


def threshold_coverage(kind: str, s: float, n: int = 6, r: int = 4000, seed: int = 0) -> tuple[float, int]:
    """Share of experiments whose interval holds the true geometric mean, of those not extrapolated; their count."""
    rng = np.random.default_rng(seed)
    hits = done = 0
    for _ in range(r):
        mu = rng.uniform(LOG[2], LOG[-3])
        e = threshold(lost(mu + scatter(rng, kind, n, s)), GRID)
        if not e.extrapolated:
            done += 1
            hits += e.ci_low <= math.exp(mu) <= e.ci_high
    return hits / done, done


def ratio_coverage(kind: str, s: float, rho: float, n: int = 6, r: int = 4000, seed: int = 1) -> tuple[float, int]:
    """The same for the paired ratio, true log ratio uniform in [-0.3, 0.3], the curves' scatters correlated by
    ``rho`` (experiments with a censored run left out)."""
    rng = np.random.default_rng(seed)
    hits = done = 0
    for _ in range(r):
        mu, d = rng.uniform(LOG[2], LOG[-3]), rng.uniform(-0.3, 0.3)
        za = scatter(rng, kind, n, s)
        zb = rho * za + math.sqrt(1 - rho**2) * scatter(rng, kind, n, s)
        e = threshold_ratio(lost(mu + d / 2 + za), lost(mu - d / 2 + zb), GRID)
        if not (e.extrapolated or e.ci_low == 0.0 or math.isinf(e.ci_high)):
            done += 1
            hits += e.ci_low <= math.exp(d) <= e.ci_high
    return hits / done, done


def share_coverage(p_minus: float, p_plus: float, n: int = 6) -> float:
    """Exact coverage of :func:`share_difference` over every outcome of ``n`` runs differing by -1, 0, +1."""
    total = 0.0
    p_zero = 1.0 - p_minus - p_plus
    for km in range(n + 1):
        for kp in range(n + 1 - km):
            k0 = n - km - kp
            prob = math.comb(n, km) * math.comb(n - km, kp) * p_minus**km * p_zero**k0 * p_plus**kp
            if prob > 0:
                d = np.array([-1.0] * km + [0.0] * k0 + [1.0] * kp)
                e = share_difference((d > 0).astype(float), (d < 0).astype(float))
                total += prob * (e.ci_low <= p_plus - p_minus <= e.ci_high)
    return total


def t_over_three(law: str, r: int = 100_000, seed: int = 0) -> float:
    """Coverage of the 95 % Student-t interval over three values of ``law`` (its mean the truth)."""
    rng = np.random.default_rng(seed)
    draw, mean = {
        "normal": (lambda: rng.standard_normal((r, 3)), 0.0),
        "maximum of 15 normals": (lambda: rng.standard_normal((r, 3, 15)).max(-1), 1.7359),  # E max of 15
        "log-normal sigma 0.5": (lambda: rng.lognormal(0.0, 0.5, (r, 3)), math.exp(0.125)),
        "exponential": (lambda: rng.exponential(1.0, (r, 3)), 1.0),
    }[law]
    x = draw()
    m, se = x.mean(1), x.std(1, ddof=1) / math.sqrt(3)
    t = 4.302652729749464  # Student t, 2 degrees of freedom, 0.975
    return float(np.mean((m - t * se <= mean) & (mean <= m + t * se)))


def worst_share(n: int, step: float) -> tuple[float, float, float]:
    """The lowest exact coverage of :func:`share_coverage` over a grid of (P(-1), P(+1)) and where it is."""
    grid = np.round(np.arange(0.0, 1.0 + 1e-9, step), 10)
    return min((share_coverage(pm, pp, n), pm, pp) for pm in grid for pp in grid if pm + pp <= 1.0 + 1e-12)


def _tally(hits: dict, folded: list, truth: float, rule) -> None:
    """Add one experiment to ``hits``: the replicates' fold distances pooled with their signed ratios dropped (folded
    before the pool) and as they are (the pool folded after), each pool's interval holding ``truth`` and its verdict."""
    before = pool([Estimate(*(getattr(f, k) for k in ("value", "stderr", "ci_low", "ci_high", "n"))) for f in folded])
    for key, e in (("before", before), ("after", pool(folded))):
        hits[key][0] += e.ci_low <= truth <= e.ci_high
        hits[key][1] += rule.decide(e) == "reproduced"


def fold_rates(true: float, runs: int, replicates: int, r: int = 2000, seed: int = 2) -> dict:
    """Pooled fold distances of ``replicates`` log-normal ratios about ``true`` (``runs`` each, log spread 0.5, t
    interval on the log scale), folded before the pool (each replicate's signed ratio dropped) and after it: the
    share of pooled intervals holding the true fold, and of pools a rule "at least 1.1" reads as reproduced."""
    rng, t = np.random.default_rng(seed), stats.t.ppf(0.975, runs - 1)
    rule, truth = InBand("fold", low=1.1), max(true, 1.0 / true)
    hits = {"before": [0, 0], "after": [0, 0]}
    for _ in range(r):
        x = rng.normal(math.log(true), 0.5, (replicates, runs))
        m, h = x.mean(axis=1), t * x.std(axis=1, ddof=1) / math.sqrt(runs)
        folded = [
            fold_about(Estimate(math.exp(a), math.nan, math.exp(a - b), math.exp(a + b), runs)) for a, b in zip(m, h)
        ]
        _tally(hits, folded, truth, rule)
    return {k: (c / r, y / r) for k, (c, y) in hits.items()}


def fold_rates_unpaired(true: float, replicates: int, runs: int = 10, r: int = 1000, seed: int = 7) -> dict:
    """:func:`fold_rates` with C002-13's interval: the unpaired ratio of two means of ``runs`` exponential runs
    each (:func:`tvtrack.montecarlo.ratio_ci`, skewed), folded before or after the pool."""
    rng, rule, truth = np.random.default_rng(seed), InBand("fold", low=1.1), max(true, 1.0 / true)
    hits = {"before": [0, 0], "after": [0, 0]}
    for _ in range(r):
        folded = [
            fold_about(ratio_ci(rng.exponential(true, runs), rng.exponential(1.0, runs), paired=False, rng=rng))
            for _ in range(replicates)
        ]
        _tally(hits, folded, truth, rule)
    return {k: (c / r, y / r) for k, (c, y) in hits.items()}


if __name__ == "__main__":
    for kind in ("normal", "skewed", "t3"):
        for s in (0.02, 0.1, 0.2, 0.4):
            print(f"threshold, {kind}, spread {s}: %.3f of %d" % threshold_coverage(kind, s))
    for kind in ("normal", "skewed"):
        for s in (0.0, 0.02, 0.05, 0.2, 0.4):
            for rho in (0.0, 0.8):
                print(f"ratio, {kind}, spread {s}, correlation {rho}: %.3f of %d" % ratio_coverage(kind, s, rho))
    for n, step in ((6, 0.01), (18, 0.01)):
        print(
            f"share difference, {n} runs: lowest exact coverage %.3f at P(-1) = %.2f, P(+1) = %.2f"
            % worst_share(n, step)
        )
    for true, runs in ((1.0, 40), (1.1, 6)):
        for k in (3, 5):
            got = fold_rates(true, runs, k)
            print(
                f"fold distance, true ratio {true}, {runs} runs, {k} replicates: covers %.3f / %.3f, "
                "reads >= 1.1 %.1f %% / %.1f %% (folded before / after the pool)"
                % (got["before"][0], got["after"][0], 100 * got["before"][1], 100 * got["after"][1])
            )
    for k in (3, 5):
        got = fold_rates_unpaired(1.0, k)
        print(
            f"fold distance, unpaired exponential runs (10 a side, true ratio 1), {k} replicates: covers %.3f / %.3f, "
            "reads >= 1.1 %.1f %% / %.1f %% (folded before / after the pool)"
            % (got["before"][0], got["after"][0], 100 * got["before"][1], 100 * got["after"][1])
        )
