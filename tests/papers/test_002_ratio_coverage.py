"""The coverage 002's variance-ratio interval states (``ratio_coverage.RATIO_COVERAGE``), re-measured, and its square
root (a ratio of standard deviations) where the numerator never varies.

The table holds 2000 experiments a cell; the test re-runs the first :data:`EXPERIMENTS` of them at the paper
profile's 80 trials (the same draws and resamples: each experiment has its own seed), so the two differ only by the
binomial spread of a subset of the table's experiments; a stated value that drifts by more than
:data:`SPREADS` of those standard errors fails."""

import warnings

import numpy as np
import pytest

from tvtrack.coverage import COVERAGE_FLOOR, coverage_reached, stated_coverage
from tvtrack.measured import calibrated
from tvtrack.papers.p002_unified_location_em import ratio_coverage as rc
from tvtrack.papers.p002_unified_location_em.summaries import ratio_interval_coverage, variance_ratio_ci

EXPERIMENTS = 150  # about 2 s a case at 80 trials
SPREADS = 4.0


def _tolerance(p: float, m: int = EXPERIMENTS, n: int = rc.N_EXPERIMENTS) -> float:
    """SPREADS binomial standard errors of the share over the first m of n experiments minus the share over all n."""
    return SPREADS * np.sqrt(p * (1.0 - p) * (1.0 / m - 1.0 / n))


@pytest.mark.parametrize("case", rc.CASES)
def test_the_stated_coverage_at_80_trials_is_what_the_interval_reaches(case):
    stated = rc.RATIO_COVERAGE[80][rc.CASES.index(case)]
    measured = ratio_interval_coverage(case, 80, EXPERIMENTS)
    assert abs(measured - stated) <= _tolerance(stated), (case, measured, stated)


def test_gross_errors_cost_coverage_and_the_note_states_the_worst():
    normal, heavy, gross = rc.RATIO_COVERAGE[80]
    assert gross < COVERAGE_FLOOR <= min(normal, heavy)  # a few gross errors are what falls short at 80 trials
    assert min(rc.RATIO_COVERAGE[80]) == gross
    note = rc.ratio_coverage_note(95)  # between sizes: the next smaller tabulated one
    assert note.startswith(f"coverage {min(rc.RATIO_COVERAGE[80]):.3f} at n = 95 (the worst of normal errors")
    assert "unmeasured" in rc.ratio_coverage_note(3)


@pytest.mark.parametrize("paired, sqrt", [(True, False), (False, False), (True, True)])
def test_the_interval_states_its_coverage_and_calibrated_widens_it(paired, sqrt):
    """Before, the method stated no coverage, so a rule read the interval as a 95 % one and never widened it."""
    num, den = rc.draw(rc.CASES[2], 80, 0)
    e = variance_ratio_ci(num, den, np.random.default_rng(1), 2000, paired=paired, sqrt=sqrt)
    assert f"coverage {min(rc.RATIO_COVERAGE[80]):.3f} at n = 80" in e.method
    assert stated_coverage(e) == min(rc.RATIO_COVERAGE[80]) and not coverage_reached(e)
    w = calibrated(e)
    assert w.ci_low < e.ci_low < e.value < e.ci_high < w.ci_high and "widened" in w.method


def test_robust_spreads_state_no_coverage_they_were_not_measured_for():
    num, den = rc.draw(rc.CASES[0], 80, 0)
    e = variance_ratio_ci(num, den, np.random.default_rng(1), 2000, spread="trimmed_variance")
    assert "coverage" not in e.method and calibrated(e) == e


def test_sd_ratio_of_a_numerator_that_never_varies_is_zero_without_a_warning():
    """A two-stage that keeps a designated velocity given exactly has velocity errors that are all 0: the ratio of
    variances is 0 in every resample, and its square root (C002-11 read as a ratio of SDs) must not divide 0 by 0
    (the notebook printed a RuntimeWarning and the record held a standard error of NaN)."""
    den = np.random.default_rng(2).normal(size=(80, 4))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        e = variance_ratio_ci(np.zeros((80, 4)), den, np.random.default_rng(1), 2000, sqrt=True)
    assert (e.value, e.stderr, e.ci_low, e.ci_high) == (0.0, 0.0, 0.0, 0.0)
    var = variance_ratio_ci(np.ones((80, 4)), den, np.random.default_rng(1), 2000)
    assert var.value == 0.0 and var.stderr == 0.0
