"""Tests for the per-scan, acquisition and ratio helpers of paper 000 (tvtrack.papers.p000_dissector_ekf.settling)."""

import numpy as np
import pytest

from tvtrack.papers.p000_dissector_ekf.settling import acquisition_times_from_scans, median_ratio_ci, scan_averages


def test_scan_averages_drop_the_start_and_the_incomplete_scan():
    sq = np.arange(12.0)[None, :].repeat(2, axis=0)  # columns 1..11: two full scans of 4, one partial
    np.testing.assert_allclose(scan_averages(sq, 4), [[2.5, 6.5]] * 2)
    with pytest.raises(ValueError, match="steps_per_scan"):
        scan_averages(sq, 0)


def test_acquisition_time_is_the_end_of_the_last_scan_out_of_lock():
    sps, dt = 4, 0.25  # scans of 1 time unit
    sq = np.full((4, 1 + 5 * sps), 0.01)
    sq[1, 1:9] = 1.0  # out for two scans, then in lock
    sq[2, 1:5] = 1.0
    sq[2, 13:17] = 1.0  # re-acquires, loses lock in scan 4, back in scan 5
    sq[3, 9:] = 1.0  # lost from scan 3 to the end
    per_scan = scan_averages(sq, sps)
    np.testing.assert_allclose(acquisition_times_from_scans(per_scan, 0.1, sps * dt), [1.0, 2.0, 4.0, np.inf])
    with pytest.raises(ValueError, match="threshold_ms"):
        acquisition_times_from_scans(per_scan, 0.0, sps * dt)


def test_median_ratio_ignores_a_few_diverged_runs():
    rng = np.random.default_rng(3)
    b = rng.exponential(size=400)
    a = 2.0 * b
    a[:8] = 1e4  # 2 % diverged runs
    r = median_ratio_ci(a, b)
    assert a.mean() / b.mean() > 100  # the mean ratio is dominated by the 8 runs
    assert 0 < r.ci_low < 2.0 * 1.05 and 2.0 < r.ci_high < 2.4  # the median ratio is about 2 (1.03 x 2 expected)
