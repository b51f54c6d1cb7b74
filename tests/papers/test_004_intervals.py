"""Paper 004: coverage of the intervals its verdicts use, at the 15 paths they use them at.

004's intervals are the core's (``tvtrack.montecarlo``): the RMS through ``rms_ci`` (bootstrap-t of the mean
square), ratios through ``ratio_ci`` (paired expanded percentile bootstrap), means through ``mean_ci``
(bootstrap-t); each states its coverage measured on the core's reference samples in ``method``. Here the
coverage is measured again on 004's own shape: per-path mean squared errors spread over a factor of ~7 (wander
RMS 3-8 px, drawn log-uniformly), a baseline's strongly paired with the filter's."""

import numpy as np
import pytest

from tvtrack.montecarlo import coverage_at, coverage_reached, stated_coverage
from tvtrack.papers.p004_laser_spot_prediction.intervals import mean_ci_t, ratio_of_means_ci, root_mean_ci

N_PATHS = 15


def _paths(rng, reps, n):
    scale = np.exp(rng.uniform(np.log(9.0), np.log(64.0), (reps, n)))  # per-path wander variance
    spread = 0.3 * rng.standard_normal((reps, n))
    baseline = scale * 1.3 * np.exp(spread + 0.15 * rng.standard_normal((reps, n)))
    paper = scale * np.exp(0.15 * rng.standard_normal((reps, n)))
    return baseline, paper


@pytest.fixture(scope="module")
def truth():
    b, p = _paths(np.random.default_rng(0), 1, 2_000_000)
    return b.mean() / p.mean(), p.mean()


@pytest.mark.slow
def test_ratio_and_rms_intervals_cover_at_fifteen_paths(truth):
    """Measured with 1500 replications: ratio 0.930, RMS 0.965 (the ratio between the core's stated 0.940 on
    skewed and 0.927 on heavy-tailed samples; 004's own log-scale bootstrap-t, now removed, gave 0.941). At 600
    replications the coverage's sd is 0.010: the bounds are 2.5 sd below."""
    ratio_true, ms_true = truth
    reps = 600
    b, p = _paths(np.random.default_rng(1), reps, N_PATHS)
    hit_r = hit_m = 0
    for i in range(reps):
        r = ratio_of_means_ci(b[i], p[i])
        m = root_mean_ci(p[i])
        hit_r += r.ci_low < ratio_true < r.ci_high
        hit_m += m.ci_low < np.sqrt(ms_true) < m.ci_high
    assert hit_r / reps > 0.905
    assert hit_m / reps > 0.94


def test_the_intervals_state_the_core_coverage_at_fifteen_paths():
    b, p = _paths(np.random.default_rng(4), 1, N_PATHS)
    r, m, q = ratio_of_means_ci(b[0], p[0]), root_mean_ci(p[0]), mean_ci_t(np.sqrt(p[0]))
    assert stated_coverage(r) == coverage_at("ratio", N_PATHS)[0] and "paired" in r.method
    assert stated_coverage(m) == coverage_at("mean_square", N_PATHS)[0]
    assert stated_coverage(q) == coverage_at("mean bootstrap-t", N_PATHS)[0]
    assert all(coverage_reached(e) for e in (r, m, q))


def test_values_and_degenerate_cases():
    a = np.array([2.0, 4.0, 6.0, 8.0])
    b = np.array([1.0, 2.0, 3.0, 4.0])
    r = ratio_of_means_ci(a, b)
    assert r.value == 2.0 and r.ci_low == pytest.approx(2.0) and r.ci_high == pytest.approx(2.0)  # exact ratio
    m = mean_ci_t([1.0, 2.0, 3.0, 4.0, 5.0])
    assert m.value == 3.0 and m.ci_low < 3.0 < m.ci_high
    assert root_mean_ci([4.0, 4.0, 4.0]).value == 2.0
    assert root_mean_ci([1.0, 4.0, 9.0, 16.0]).value == pytest.approx(np.sqrt(7.5))
    assert np.isnan(ratio_of_means_ci([1.0, np.nan, 2.0], [1.0, 1.0, 1.0]).ci_low)  # undecided, never decides
    with pytest.raises(ValueError, match="paired"):
        ratio_of_means_ci([1.0, 2.0, 3.0], [1.0, 1.0, 1.0, 1.0])


def test_interval_is_a_pure_function_of_the_data():
    x = np.random.default_rng(3).exponential(size=15)
    assert mean_ci_t(x) == mean_ci_t(x) and root_mean_ci(x) == root_mean_ci(x)
