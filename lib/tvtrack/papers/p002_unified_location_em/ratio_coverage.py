"""The measured coverage of :func:`.summaries.variance_ratio_ci`'s 95 % interval at the sizes paper 002 uses it at.

The interval is a cluster percentile bootstrap of a ratio of summed variances (trials resampled as whole rows). Its
coverage was measured by simulation (:func:`.summaries.ratio_interval_coverage`, :data:`N_EXPERIMENTS` experiments a
cell; ``python -m tvtrack.papers.p002_unified_location_em.summaries`` prints the table) for three kinds of per-trial
errors: normal errors, heavy tails (Student t5) and 2 % gross errors (a trial of either algorithm whose errors are 5
times as large: a swap or a lost object, which 002's runs have). The
layout is the gain rho's: two algorithms' errors on the same scenes (correlation 0.7), four coordinates each, true
ratio 0.5. The interval states the worst of the three in its ``method`` ("coverage 0.9xx at n = N (...)", the words
:func:`tvtrack.coverage.stated_coverage` reads), so :func:`tvtrack.measured.calibrated` widens it to 95 % where it
falls short of the floor; ``tests/papers/test_002_ratio_coverage.py`` re-measures the table.
"""

from __future__ import annotations

import numpy as np

__all__ = ["RATIO_COVERAGE", "CASES", "N_EXPERIMENTS", "ratio_coverage_at", "ratio_coverage_note", "draw"]

#: Experiments per cell of :data:`RATIO_COVERAGE`.
N_EXPERIMENTS = 2000
#: The error kinds, in the order of :data:`RATIO_COVERAGE`'s tuples.
CASES = ("normal errors", "Student t5 errors", "2 % gross errors")
#: Coverage of the 95 % interval measured by :func:`.summaries.ratio_interval_coverage` (2000 experiments a cell):
#: trials (the smaller sample where unpaired) -> (normal errors, Student t5 errors, 2 % gross errors). 002 uses 80
#: trials a replicate (240 in C002-5's ratios), 8 and 24 at the smoke profile; the package tests use 4.
#: Between tabulated sizes the next smaller size counts.
RATIO_COVERAGE = {
    4: (0.888, 0.869, 0.892),
    8: (0.909, 0.894, 0.893),
    20: (0.926, 0.920, 0.908),
    40: (0.930, 0.931, 0.903),
    80: (0.933, 0.938, 0.895),
    240: (0.950, 0.948, 0.926),
}
#: The true ratio, the correlation of the two algorithms' errors, coordinates, gross share and scale of the draws.
TRUE_RATIO, CORRELATION, COORDINATES, GROSS_SHARE, GROSS_SCALE = 0.5, 0.7, 4, 0.02, 5.0
SEED = 20261205


def ratio_coverage_at(n: int) -> tuple:
    """The measured coverage ``(normal, t5, gross)`` at ``n`` trials (the next smaller tabulated size; NaN below)."""
    below = [m for m in sorted(RATIO_COVERAGE) if m <= n]
    return RATIO_COVERAGE[below[-1]] if below else (float("nan"),) * 3


def ratio_coverage_note(n: int) -> str:
    """The words :func:`.summaries.variance_ratio_ci` adds to its ``method``: the worst coverage of the three kinds
    of errors first (the number :func:`tvtrack.coverage.stated_coverage` reads), then each."""
    cov = ratio_coverage_at(n)
    if np.isnan(cov[0]):
        return f"coverage unmeasured at n = {n} (below n = {min(RATIO_COVERAGE)}, the smallest size measured)"
    each = ", ".join(f"{name} {c:.3f}" for name, c in zip(CASES, cov))
    return f"coverage {min(cov):.3f} at n = {n} (the worst of {each})"


def _unit(rng: np.random.Generator, heavy: bool, shape) -> np.ndarray:
    return rng.standard_t(5, shape) / np.sqrt(5.0 / 3.0) if heavy else rng.normal(size=shape)


def draw(case: str, n: int, r: int, group: int = 0, correlation: float = CORRELATION) -> tuple:
    """Experiment ``r`` of ``case`` at ``n`` trials: the numerator and denominator errors (n, 4), each unit variance
    per coordinate up to the true ratio (its own seed, so an experiment is the same however many are run).

    ``group`` and ``correlation`` give the independent groups of a statistic over several of them
    (:mod:`.gain_coverage`: group ``g`` of experiment ``r`` has its own seed) and the correlation of the numerator's
    and denominator's errors (0: two configurations run on their own scenes); the defaults are the gain rho's draws.
    """
    own = group == 0 and correlation == CORRELATION
    key = [SEED, CASES.index(case), n, r] + ([] if own else [group, int(round(100 * correlation))])
    rng = np.random.default_rng(key)
    heavy = case == CASES[1]
    z1, z2 = _unit(rng, heavy, (n, COORDINATES)), _unit(rng, heavy, (n, COORDINATES))
    den = z1
    num = np.sqrt(TRUE_RATIO) * (correlation * z1 + np.sqrt(1.0 - correlation**2) * z2)
    if case == CASES[2]:  # each algorithm's gross errors on their own trials: scale-contaminated, mean still 0
        num = num * np.where(rng.random(n) < GROSS_SHARE, GROSS_SCALE, 1.0)[:, None]
        den = den * np.where(rng.random(n) < GROSS_SHARE, GROSS_SCALE, 1.0)[:, None]
    return num, den
