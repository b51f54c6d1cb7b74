"""Tests of tvtrack.track_modes (notebook 001): mode logic against hand-built runs."""

import numpy as np
import pytest

from tvtrack.detect.maneuver import scheduled_statistic_std, threshold_from_std
from tvtrack.filters.alphabeta import error_covariance_sequence, gain_schedule, scheduled_filter
from tvtrack.filters.polynomial import polynomial_observation_row, taylor_transition
from tvtrack.track_modes import COAST, TRACK2, TRACK3, TrackModeConfig, run_track_modes

T = 400


def _z(n, seed=0, accel=0.2, onset=125):
    f = np.arange(T)
    truth = 10.0 * f + 0.5 * accel * np.clip(f - onset, 0, None) ** 2
    return truth, truth + np.random.default_rng(seed).standard_normal((n, T))


def test_no_detection_is_the_second_order_filter_and_coasts():
    _, z = _z(5)
    vis = np.ones(T, bool)
    vis[200:260] = False
    out = run_track_modes(z, vis, TrackModeConfig(k_bound2=50), 1.0)
    ref = scheduled_filter(np.where(vis, z, np.nan), np.c_[gain_schedule(1, 50, T)])
    np.testing.assert_allclose(out.x[..., :2][:, :200], ref[:, :200], atol=1e-9)
    assert np.all(out.x[..., 2] == 0)
    assert np.all(out.mode[:, 200:260] == COAST) and np.all(out.mode[:, :200] == TRACK2)
    F = taylor_transition(2)
    np.testing.assert_allclose(out.x[:, 259], out.x[:, 199] @ np.linalg.matrix_power(F, 60).T, rtol=1e-12)
    assert np.all(out.gains[:, 200:260] == 0)
    assert np.all(out.detection_frame == -1)


def test_forced_switch_restart_a_equals_hand_built_run():
    _, z = _z(3)
    ks = 138
    out = run_track_modes(z, np.ones(T, bool), TrackModeConfig(k_bound2=50, k_bound3=80, force_switch_k=ks), 1.0)
    assert np.all(out.detection_frame == ks - 1)
    x2 = scheduled_filter(z[:, :ks], gain_schedule(1, 50, ks))[:, -1]
    x0 = np.c_[x2, np.zeros(3)]
    G3 = gain_schedule(2, 80, 3 + T - ks)[3:]                      # k = 4, 5, ...
    ref = scheduled_filter(z[:, ks:], G3, x0)
    np.testing.assert_allclose(out.x[:, ks:], ref, atol=1e-8)
    assert np.all(out.mode[:, ks:] == TRACK3)
    # the noise covariance equals the recursion over the same gains
    P = error_covariance_sequence(out.gains[0], 1.0)
    np.testing.assert_allclose(out.var[0], np.diagonal(P, axis1=-2, axis2=-1), rtol=1e-9, atol=1e-15)


def test_restart_b_is_the_window_least_squares_fit():
    _, z = _z(2)
    ks, n = 150, 20
    out = run_track_modes(z, np.ones(T, bool), TrackModeConfig(window=n, restart="B", force_switch_k=ks), 1.0)
    t = ks - 1
    H = polynomial_observation_row(2, np.arange(n - 1, -1, -1))
    fit = np.linalg.lstsq(H, z[:, t - n + 1:t + 1].T, rcond=None)[0].T
    np.testing.assert_allclose(out.x[:, t], fit, atol=1e-8)


def test_noise_variance_matches_monte_carlo_in_forced_mode():
    truth, z = _z(4000, seed=7)
    vis = np.ones(T, bool)
    vis[300:360] = False
    out = run_track_modes(z, vis, TrackModeConfig(k_bound3=60, force_switch_k=140), 1.0)
    e = out.x[..., 0] - truth
    for t in (200, 299, 359):
        assert np.var(e[:, t]) == pytest.approx(out.var[0, t, 0], rel=0.08)


def test_detector_fires_after_onset_with_correlated_threshold():
    _, z = _z(400, seed=9)
    c = threshold_from_std(1e-3, scheduled_statistic_std(gain_schedule(1, 50, T), 25, 1.0))
    out = run_track_modes(z, np.ones(T, bool), TrackModeConfig(threshold=np.where(np.isfinite(c), c, np.inf)), 1.0)
    d = out.detection_frame
    assert np.mean((d >= 125) & (d < 150)) > 0.95
    S, th = out.statistic, out.threshold
    assert np.all(np.isnan(S[:, :99]))                             # armed at k = kb2 + 2n = 100
    first = np.nanargmax(np.abs(S) > th, axis=1)
    np.testing.assert_array_equal(first[d >= 0], d[d >= 0])


def test_bad_config():
    with pytest.raises(ValueError, match="restart"):
        TrackModeConfig(restart="C")
    with pytest.raises(ValueError, match="k_bound3"):
        TrackModeConfig(k_bound3=2)
    with pytest.raises(ValueError, match="threshold"):
        TrackModeConfig(threshold=-1.0)
    with pytest.raises(ValueError, match="sigma_eps"):
        run_track_modes(np.zeros((1, 10)), np.ones(10, bool), TrackModeConfig(), 0.0)
