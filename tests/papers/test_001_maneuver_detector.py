"""Tests of tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector (notebook 001): statistic, thresholds, false-alarm rate."""

import numpy as np
import pytest
from scipy import stats

from tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector import (
    scheduled_statistic_std,
    statistic_std,
    threshold_from_std,
    variance_independent,
    variance_stationary,
    window_statistic,
    window_sum_of_squares,
)
from tvtrack.filters.alphabeta import gain_schedule, scheduled_filter
from tvtrack.montecarlo import quantile_ci


def test_window_statistic_matches_direct_sums_and_is_invariant():
    rng = np.random.default_rng(0)
    v = rng.standard_normal((3, 40))
    n = 6
    S = window_statistic(v, n)
    assert np.all(np.isnan(S[:, : 2 * n - 1]))
    for t in range(2 * n - 1, 40):
        np.testing.assert_allclose(S[:, t], v[:, t - 2 * n + 1 : t - n + 1].sum(1) - v[:, t - n + 1 : t + 1].sum(1))
    delta = 100 * rng.standard_normal((3, n))
    shifted = v.copy()
    shifted[:, -2 * n :] += np.concatenate([delta, delta], axis=1)
    np.testing.assert_allclose(window_statistic(shifted, n)[:, -1], S[:, -1], atol=1e-11)


def test_raw_differences_telescope_to_six_sigma2():
    # r(0) = 2, r(1) = -1 for first differences of unit white noise: var S = 6 for every n
    for n in (1, 3, 25):
        r = np.zeros(2 * n)
        r[0] = 2.0
        if 2 * n > 1:
            r[1] = -1.0
        assert variance_stationary(r, n) == pytest.approx(6.0)
        assert variance_independent(n, np.sqrt(2.0)) == pytest.approx(4.0 * n)


def test_correlated_variance_ratio_and_exact_limit():
    K = gain_schedule(1, 50)[-1]
    s_c, s_i = statistic_std(K, 1.0, 25), statistic_std(K, 1.0, 25, "independent")
    assert (s_c / s_i) ** 2 == pytest.approx(12.35, abs=0.01)
    exact = scheduled_statistic_std(gain_schedule(1, 50, 600), 25, 1.0)
    assert exact[-1] == pytest.approx(s_c, rel=1e-6)


def test_exact_std_matches_simulation_in_transient():
    G = gain_schedule(1, 50, 130)
    exact = scheduled_statistic_std(G, 25, 2.0)
    rng = np.random.default_rng(8)
    S = window_statistic(scheduled_filter(2.0 * rng.standard_normal((20000, 130)), G)[..., 1], 25)
    for t in (49, 99, 129):
        assert np.std(S[:, t]) == pytest.approx(exact[t], rel=0.03)


@pytest.mark.parametrize("alpha", [1e-2, 1e-3])
def test_correlated_threshold_gives_nominal_false_alarm_rate(alpha):
    """One test per run (independent Bernoulli trials), >= 20,000 runs, at the stationary and at the
    arming frame; the rate must lie in the two-sided 99.9 % binomial interval of alpha."""
    n_runs, n, kb = 40000, 25, 50
    T = 2 * kb + 2 * n
    G = gain_schedule(1, kb, T)
    rng = np.random.default_rng(2024)
    S = window_statistic(scheduled_filter(rng.standard_normal((n_runs, T)), G)[..., 1], n)
    c = threshold_from_std(alpha, scheduled_statistic_std(G, n, 1.0))
    lo, hi = stats.binom.ppf([0.0005, 0.9995], n_runs, alpha)
    for t in (kb + 2 * n - 1, T - 1):
        k = int(np.sum(np.abs(S[:, t]) > c[t]))
        assert lo <= k <= hi, (t, k, lo, hi)
    # the paper's independence threshold is far too low at the stationary frame
    c_ind = threshold_from_std(alpha, statistic_std(G[-1], 1.0, n, "independent"))
    assert np.mean(np.abs(S[:, -1]) > c_ind) > 20 * alpha


def test_calibration_by_simulation_brackets_exact_threshold():
    """The 95 % quantile of |S| at frame 199 over 20,000 simulated runs under no manoeuvre (white noise on a
    zero truth, to which the filter is invariant) brackets the exact threshold."""
    G = gain_schedule(1, 30, 200)
    eps = np.random.default_rng(1).standard_normal((20000, 200))
    S = window_statistic(scheduled_filter(eps, G)[..., 1], 10)[:, 199]
    est = quantile_ci(np.abs(S), 0.95)
    exact = threshold_from_std(0.05, scheduled_statistic_std(G, 10, 1.0)[199])
    assert est.ci_low <= exact <= est.ci_high


def test_bad_input():
    with pytest.raises(ValueError, match="window"):
        window_statistic(np.zeros(10), 0)
    with pytest.raises(ValueError, match="alpha"):
        threshold_from_std(1.5, 1.0)
    with pytest.raises(ValueError, match="method"):
        statistic_std([0.1, 0.01], 1.0, 5, "bogus")
    with pytest.raises(ValueError, match="lags"):
        variance_stationary(np.ones(3), 5)


def test_sum_of_squares_statistic_matches_direct_sums_and_is_invariant():
    rng = np.random.default_rng(4)
    v = rng.standard_normal((2, 30))
    n = 5
    Q = window_sum_of_squares(v, n)
    assert np.all(np.isnan(Q[:, : 2 * n - 1]))
    for t in range(2 * n - 1, 30):
        z = v[:, t - 2 * n + 1 : t - n + 1] - v[:, t - n + 1 : t + 1]
        np.testing.assert_allclose(Q[:, t], np.sum(z**2, axis=1), rtol=1e-12)
    delta = 10 * rng.standard_normal((2, n))
    shifted = v.copy()
    shifted[:, -2 * n :] += np.concatenate([delta, delta], axis=1)
    np.testing.assert_allclose(window_sum_of_squares(shifted, n)[:, -1], Q[:, -1], rtol=1e-10)


def _impulse_response_std(G, n, sigma_eps):
    """Reference: sigma_S(t) from the filter's responses to unit impulses (quadratic memory; small T only)."""
    T = G.shape[0]
    responses = scheduled_filter(np.eye(T), G)[..., 1]  # (j, t): velocity at t from an impulse at j
    W = window_statistic(responses, n)  # (j, t): weight of eps_j in S_t
    return sigma_eps * np.sqrt(np.sum(W**2, axis=0))


@pytest.mark.parametrize("order, kb, n, T", [(1, 50, 25, 300), (2, 30, 10, 200), (1, 5, 3, 40)])
def test_exact_std_recursion_equals_impulse_responses(order, kb, n, T):
    G = gain_schedule(order, kb, T)
    np.testing.assert_allclose(scheduled_statistic_std(G, n, 1.7), _impulse_response_std(G, n, 1.7), rtol=1e-10)


def _peak_bytes(T, n):
    import tracemalloc

    G = gain_schedule(1, 50, T)
    tracemalloc.start()
    scheduled_statistic_std(G, n, 1.0)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak


def test_exact_std_memory_is_linear_in_run_length():
    """B3: the exact threshold once built an identity of the run length (memory ~ T^2: gigabytes at
    200 Hz x 60 s). Doubling T must at most about double the peak, and the 200 Hz x 60 s run with the
    largest window the notebook allows must stay under 200 MB."""
    small, large = _peak_bytes(1500, 25), _peak_bytes(3000, 25)
    assert large / small < 2.5, (small, large)
    assert _peak_bytes(200 * 60, 200) < 200e6


@pytest.mark.parametrize("k_bound2,n", [(50, 25), (100, 25), (50, 10), (30, 25)])
def test_windows_of_predicted_velocities_only_get_no_threshold(k_bound2, n):
    """While lost the filter coasts: from the 2n - 1-th lost frame on, both windows hold one held velocity, S is 0
    and no test is possible, so the threshold is infinite there at every bound (the exact sigma_S is 0 in
    arithmetic; computed, it may leave a few 1e-9 of rounding, which must not become a threshold of 1e-8)."""
    from tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector import track2_thresholds

    vis = np.ones(625, bool)
    vis[300:550] = False  # the scenario's loss, 12 s to 22 s at 25 frames/s
    c = track2_thresholds(vis, k_bound2, n, 1e-3)
    coasting = np.zeros(625, bool)
    coasting[300 + 2 * n - 2 : 550] = True
    assert np.all(np.isinf(c[coasting]))
    assert np.all(np.isfinite(c[2 * n - 1 :][~coasting[2 * n - 1 :]]))  # every other full window is tested
    assert c[~coasting & np.isfinite(c)].min() > 1e-3
