"""Paper 004: coverage of the intervals its verdicts use, at the 15 paths they use them at (issue 28, item 4).

The per-path mean squared errors of the study spread over a factor of ~7 (wander RMS 3-8 px, drawn
log-uniformly) and a baseline's are strongly paired with the filter's; the model below has that shape."""

import numpy as np
import pytest

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
    ratio_true, ms_true = truth
    reps = 600
    b, p = _paths(np.random.default_rng(1), reps, N_PATHS)
    rng = np.random.default_rng(2)
    hit_r = hit_m = 0
    for i in range(reps):
        r = ratio_of_means_ci(b[i], p[i], n_resamples=999, rng=rng)
        m = root_mean_ci(p[i], n_resamples=999, rng=rng)
        hit_r += r.ci_low < ratio_true < r.ci_high
        hit_m += m.ci_low < np.sqrt(ms_true) < m.ci_high
    # 600 replications: Monte Carlo sd of the coverage is 0.01. Measured with 1500 replications: ratio
    # 0.935, RMS 0.96 (the ratio's shortfall is stated in the module and the notebook; BCa gives 0.92 here)
    assert hit_r / reps > 0.915
    assert hit_m / reps > 0.925


def test_values_and_degenerate_cases():
    a = np.array([2.0, 4.0, 6.0, 8.0])
    b = np.array([1.0, 2.0, 3.0, 4.0])
    r = ratio_of_means_ci(a, b)
    assert r.value == 2.0 and r.ci_low == r.ci_high == 2.0  # an exact ratio: nothing varies
    m = mean_ci_t([1.0, 2.0, 3.0, 4.0, 5.0])
    assert m.value == 3.0 and m.ci_low < 3.0 < m.ci_high
    assert root_mean_ci([4.0, 4.0, 4.0]).value == 2.0
    with pytest.raises(ValueError, match="numerator"):
        ratio_of_means_ci([1.0, np.nan, 2.0], [1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="sizes"):
        ratio_of_means_ci([1.0, 2.0, 3.0], [1.0, 1.0, 1.0, 1.0])


def test_interval_is_a_pure_function_of_the_data():
    x = np.random.default_rng(3).exponential(size=15)
    assert mean_ci_t(x) == mean_ci_t(x)
