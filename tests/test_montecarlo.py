import numpy as np
import pytest
from scipy import stats

from tvtrack.montecarlo import make_rng, mean_ci, proportion_ci, quantile_ci, ratio_ci, rms_ci, spawn_rngs


def test_mean_ci_matches_scipy_t_interval():
    x = make_rng(0).normal(3.0, 2.0, size=50)
    est = mean_ci(x, 0.9)
    lo, hi = stats.t.interval(0.9, 49, loc=x.mean(), scale=stats.sem(x))
    assert est.value == pytest.approx(x.mean())
    assert (est.ci_low, est.ci_high) == pytest.approx((lo, hi), rel=1e-12)


def test_mean_ci_covers_truth_at_nominal_rate():
    # 2000 experiments of 20 samples: coverage of the 95% interval within its binomial spread
    x = make_rng(1).normal(1.0, 1.0, size=(2000, 20))
    covered = sum(mean_ci(row).ci_low <= 1.0 <= mean_ci(row).ci_high for row in x)
    assert abs(covered / 2000 - 0.95) < 3 * np.sqrt(0.95 * 0.05 / 2000)


def test_rms_ci_uses_trials_as_independent_samples():
    e = make_rng(2).normal(0, 0.5, size=(400, 30))
    est = rms_ci(e)
    assert est.n == 400
    assert est.ci_low < 0.5 < est.ci_high
    assert est.value == pytest.approx(np.sqrt(np.mean(e**2)))


def test_proportion_ci_is_clopper_pearson():
    est = proportion_ci(0, 20)
    assert est.value == 0 and est.ci_low == 0
    assert est.ci_high == pytest.approx(1 - 0.025 ** (1 / 20), rel=1e-9)  # exact upper bound for k=0
    with pytest.raises(ValueError, match="n >= 1"):
        proportion_ci(0, 0)


def test_quantile_ci_brackets_the_quantile():
    x = make_rng(3).exponential(size=4000)
    est = quantile_ci(x, 0.95)
    assert est.ci_low <= est.value <= est.ci_high
    assert est.ci_low < -np.log(0.05) < est.ci_high


def test_seeds_reproduce_and_spawned_streams_differ():
    assert np.array_equal(make_rng(7).normal(size=5), make_rng(7).normal(size=5))
    a, b = spawn_rngs(7, 2)
    assert not np.array_equal(a.normal(size=5), b.normal(size=5))
    assert np.array_equal(spawn_rngs(7, 2)[1].normal(size=5), spawn_rngs(7, 2)[1].normal(size=5))


def test_ratio_ci_uses_the_pairing():
    rng = make_rng(4)
    common = rng.chisquare(3, size=2000)
    a, b = 2.0 * common + 0.1 * rng.normal(size=2000), common
    paired = ratio_ci(a, b)
    assert paired.value == pytest.approx(a.mean() / b.mean())
    assert paired.ci_low < 2.0 < paired.ci_high
    # the same marginals without the pairing give a much wider interval
    unpaired = ratio_ci(rng.permutation(a), b)
    assert (paired.ci_high - paired.ci_low) < 0.2 * (unpaired.ci_high - unpaired.ci_low)
    with pytest.raises(ValueError, match="paired samples"):
        ratio_ci([1.0], [1.0])
