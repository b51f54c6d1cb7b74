"""Tests for the steady-state, settling and acquisition helpers of paper 000 (tvtrack.papers.p000_dissector_ekf.settling)."""

import numpy as np
import pytest

from tvtrack.papers.p000_dissector_ekf.settling import (
    acquisition_times,
    median_ratio_ci,
    per_trial_mse,
    scan_averages,
    settle_time,
    settle_time_ci,
)


def test_per_trial_mse_uses_the_window_only():
    x = np.zeros((2, 5))
    e = np.array([[9.0, 1.0, 1.0, 2.0, 2.0], [9.0, 0.0, 0.0, 0.0, 3.0]])
    np.testing.assert_allclose(per_trial_mse(x, e, np.array([False, True, True, True, True])), [2.5, 2.25])


def test_scan_averages_drop_the_start_and_the_incomplete_scan():
    sq = np.arange(12.0)[None, :].repeat(2, axis=0)  # columns 1..11: two full scans of 4, one partial
    np.testing.assert_allclose(scan_averages(sq, 4), [[2.5, 6.5]] * 2)
    with pytest.raises(ValueError, match="steps_per_scan"):
        scan_averages(sq, 0)


def test_settle_time_is_the_end_of_the_first_scan_within_tolerance():
    per_scan = np.array([1.0, 0.5, 0.115, 0.105, 0.12, 0.1])
    assert settle_time(per_scan, 0.1, 2.0) == 8.0  # 4th scan (0.105 <= 0.11) ends at 4 x 2
    assert settle_time(per_scan, 0.1, 2.0, tolerance=0.2) == 6.0
    assert settle_time(per_scan, 0.01, 2.0) == np.inf


def test_settle_time_ci_on_an_exponential_decay():
    """Every trial decays as exp(-t/tau) to a floor: the settling time is where the decay falls below
    10 % of the floor, rounded up to the end of a scan; identical trials give a degenerate interval."""
    dt, sps, tau, floor = 0.05, 20, 1.5, 1e-3
    t = np.arange(601) * dt
    sq = np.repeat((0.2 * np.exp(-t / tau) + floor)[None, :], 50, axis=0)
    exact = np.ceil(tau * np.log(0.2 / (0.1 * floor)))  # first scan end with decay <= 0.1 floor (approx.)
    est = settle_time_ci(sq, t > 20.0, sps, dt, np.random.default_rng(0), n_boot=50)
    assert abs(est.value - exact) <= 1.0
    assert est.ci_low == est.ci_high == est.value and est.stderr == 0.0


def test_settle_time_ci_interval_covers_the_value_and_reproduces_with_the_seed():
    rng = np.random.default_rng(1)
    t = np.arange(301) * 0.05
    sq = (0.2 * np.exp(-t / 0.8) + 4e-4) * rng.exponential(size=(200, t.size))
    a = settle_time_ci(sq, t > 10.0, 20, 0.05, np.random.default_rng(2), n_boot=200)
    b = settle_time_ci(sq, t > 10.0, 20, 0.05, np.random.default_rng(2), n_boot=200)
    assert a == b
    assert a.ci_low <= a.value <= a.ci_high and np.isfinite(a.stderr)


def test_acquisition_time_is_the_end_of_the_last_scan_out_of_lock():
    sps, dt = 4, 0.25  # scans of 1 time unit
    sq = np.full((4, 1 + 5 * sps), 0.01)
    sq[1, 1:9] = 1.0  # out for two scans, then in lock
    sq[2, 1:5] = 1.0
    sq[2, 13:17] = 1.0  # re-acquires, loses lock in scan 4, back in scan 5
    sq[3, 9:] = 1.0  # lost from scan 3 to the end
    np.testing.assert_allclose(acquisition_times(sq, 0.1, sps, dt), [1.0, 2.0, 4.0, np.inf])
    with pytest.raises(ValueError, match="threshold_ms"):
        acquisition_times(sq, 0.0, sps, dt)


def test_median_ratio_ignores_a_few_diverged_runs():
    rng = np.random.default_rng(3)
    b = rng.exponential(size=400)
    a = 2.0 * b
    a[:8] = 1e4  # 2 % diverged runs
    r = median_ratio_ci(a, b)
    assert a.mean() / b.mean() > 100  # the mean ratio is dominated by the 8 runs
    assert 0 < r.ci_low < 2.0 * 1.05 and 2.0 < r.ci_high < 2.4  # the median ratio is about 2 (1.03 x 2 expected)
