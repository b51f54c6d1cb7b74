"""The coverage 002's log-gain ratios and C002-6's frame-dependence contrast state (``gain_coverage.COVERAGE``),
re-measured on a cell, and stated in the intervals so that :func:`tvtrack.measured.calibrated` widens them.

The table holds 2000 experiments a cell; the test re-runs the first :data:`EXPERIMENTS` of them (the same draws and
resamples: each experiment has its own seed), so the two differ only by the binomial spread of a subset of the
table's experiments; a stated value that drifts by more than :data:`SPREADS` of those standard errors fails."""

import numpy as np
import pytest

from tvtrack.coverage import coverage_reached, stated_coverage
from tvtrack.measured import calibrated
from tvtrack.papers.p002_unified_location_em import gain_coverage as gc
from tvtrack.papers.p002_unified_location_em import ratio_coverage as rc
from tvtrack.papers.p002_unified_location_em.claim_values import (
    frame_dependence,
    gain_interval_coverage,
    mean_log_gain,
)

EXPERIMENTS = 200  # about 2 s at 80 trials, one group a side
SPREADS = 4.0


def _tolerance(p: float, m: int = EXPERIMENTS, n: int = gc.N_EXPERIMENTS) -> float:
    """SPREADS binomial standard errors of the share over the first m of n experiments minus the share over all n."""
    return SPREADS * np.sqrt(p * (1.0 - p) * (1.0 / m - 1.0 / n))


@pytest.mark.parametrize("statistic", list(gc.STATISTICS))
def test_the_stated_coverage_of_gross_errors_at_80_trials_is_what_the_interval_reaches(statistic):
    stated = gc.COVERAGE[statistic][(80, 1)][2]
    measured = gain_interval_coverage(statistic, rc.CASES[2], 80, 1, EXPERIMENTS)
    assert abs(measured - stated) <= _tolerance(stated), (statistic, measured, stated)


def test_the_note_states_the_worst_at_the_next_smaller_size_and_number_of_groups():
    worst = min(gc.COVERAGE["log gain"][(80, 1)])
    assert gc.coverage_note("log gain", 95, 3).startswith(f"coverage {worst:.3f} at n = 95, 3 groups a side (the worst")
    assert "unmeasured" in gc.coverage_note("log gain", 3, 1)
    assert gc.coverage_at("frame dependence", 80, 8) == gc.COVERAGE["frame dependence"][(80, 4)]


def _layout(groups: int, r: int = 0):
    return gc.draw_groups(rc.CASES[2], 80, r, groups, 0.0)


@pytest.mark.parametrize(
    "statistic, fn, groups", [("log gain", mean_log_gain, 1), ("frame dependence", frame_dependence, 4)]
)
def test_the_intervals_state_their_coverage_and_calibrated_reads_it(statistic, fn, groups):
    """Before, the method stated no coverage, so a rule read the interval as a 95 % one and never widened it."""
    e = fn(*_layout(groups), np.random.default_rng(1), 2000)
    worst = min(gc.coverage_at(statistic, 80, groups))
    assert f"coverage {worst:.3f} at n = 80, {groups} group" in e.method
    assert stated_coverage(e) == worst
    w = calibrated(e)
    if coverage_reached(e):
        assert w == e
    else:
        assert w.ci_low < e.ci_low < e.ci_high < w.ci_high and "widened" in w.method


def test_the_log_gain_of_one_group_a_side_is_widened_at_the_paper_profile():
    e = mean_log_gain(*_layout(1), np.random.default_rng(1), 2000)
    assert not coverage_reached(e) and "widened" in calibrated(e).method


def test_unmeasured_forms_state_nothing():
    hi, lo = _layout(1)
    trimmed = mean_log_gain(hi, lo, np.random.default_rng(1), 500, spread="trimmed_variance")
    gap = frame_dependence(hi, lo, np.random.default_rng(1), 500, gap=True)
    for e in (trimmed, gap):
        assert "coverage" not in e.method and calibrated(e) == e
