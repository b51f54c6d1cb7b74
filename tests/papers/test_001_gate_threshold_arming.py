"""Tests of paper 001's gate, threshold index, arming and coast guards, and of the detection summaries at the
onset frame. Each test names the planted bug it kills."""

import numpy as np
import pytest

from tvtrack.filters.alphabeta import gain_schedule, observation_row
from tvtrack.filters.polynomial import taylor_transition
from tvtrack.montecarlo import zero_events_bound
from tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector import (
    detection_time_summary,
    false_alarm_rates,
    first_alarm_within,
    scheduled_statistic_std,
    threshold_from_std,
    track2_thresholds,
)
from tvtrack.papers.p001_maneuver_occlusion_kf.track_modes import TrackModeConfig, run_track_modes

T = 400


def _z(n, seed=0, accel=0.2, onset=125, T=T):
    f = np.arange(T)
    truth = 10.0 * f + 0.5 * accel * np.clip(f - onset, 0, None) ** 2
    return truth, truth + np.random.default_rng(seed).standard_normal((n, T))


def _gate_by_hand(gains, sigma_eps):
    """Independent recursion: gate_t = [F P_{t-1} F^T]_00 + sigma^2, then the Joseph update with the gains used."""
    F, h = taylor_transition(2), observation_row(2)
    P = np.zeros((3, 3))
    gate = np.empty(len(gains))
    for t, K in enumerate(gains):
        Pp = F @ P @ F.T
        gate[t] = Pp[0, 0] + sigma_eps**2
        IKh = np.eye(3) - np.outer(K, h)
        P = IKh @ Pp @ IKh.T + sigma_eps**2 * np.outer(K, K)
    return gate


def test_gate_is_the_predicted_innovation_variance_with_the_measurement_noise():
    """Kills: gate variance without the measurement noise; gate from the filtered instead of the predicted
    covariance. The gate must equal [F P F^T]_00 + sigma^2 of an independent recursion over the gains used
    (restart A keeps the TRACK2 covariance, so the recursion over the gains is the whole story)."""
    _, z = _z(2, seed=4)
    vis = np.ones(T, bool)
    vis[250:330] = False
    sigma = 1.7
    out = run_track_modes(z * sigma, vis, TrackModeConfig(k_bound3=60, force_switch_k=140), sigma)
    ref = _gate_by_hand(out.gains[0], sigma)
    np.testing.assert_allclose(out.gate_var[0], ref, rtol=1e-9)


@pytest.mark.parametrize("restart", ["A", "B", "C"])
def test_gate_matches_the_empirical_innovation_variance_at_reappearance(restart):
    """Kills the same two gate bugs by Monte Carlo, with no recursion in the test: the innovation at the
    reappearance frame (after an 80-frame coast) has the variance the gate states."""
    truth, z = _z(4000, seed=7)
    vis = np.ones(T, bool)
    vis[250:330] = False
    out = run_track_modes(z, vis, TrackModeConfig(k_bound3=60, force_switch_k=140, restart=restart), 1.0)
    for t in (330, 331, 360):  # the first frames back: filtered != predicted
        innov = z[:, t] - (taylor_transition(2) @ out.x[:, t - 1].T)[0]
        assert np.var(innov) == pytest.approx(out.gate_var[0, t], rel=0.07)


def test_threshold_array_is_read_at_the_current_count():
    """Kills: the threshold read one count late (or early). Only count k0 has a finite (tiny) threshold, so every
    run must alarm exactly at the frame where the TRACK2 count is k0 (frame k0 - 1 with all frames visible)."""
    _, z = _z(5, seed=2)
    k0 = 80
    thr = np.full(T, np.inf)
    thr[k0 - 1] = 1e-12
    out = run_track_modes(z, np.ones(T, bool), TrackModeConfig(threshold=thr, arm_k=60), 1.0, covariance=False)
    np.testing.assert_array_equal(out.detection_frame, k0 - 1)
    assert out.threshold[0, k0 - 1] == 1e-12 and np.isinf(out.threshold[0, k0 - 2])


def test_frame_indexed_threshold_is_read_at_the_current_frame():
    _, z = _z(3, seed=2)
    vis = np.ones(T, bool)
    vis[100:120] = False  # count and frame differ after the gap
    f0 = 230
    thr = np.full(T, np.inf)
    thr[f0] = 1e-12
    cfg = TrackModeConfig(threshold=thr, threshold_index="frame", arm_k=60)
    out = run_track_modes(z, vis, cfg, 1.0, covariance=False)
    np.testing.assert_array_equal(out.detection_frame, f0)


def test_detection_in_the_onset_frame_is_a_hit():
    """Kills: detections in the onset frame dropped (counted as early, or not at all)."""
    onset = 10
    s = detection_time_summary(np.array([onset, onset, onset + 1, -1]), onset=onset, loss_frame=20, frame_rate_hz=10.0)
    assert s["false_alarm_before_onset"].value == 0.0
    assert s["missed_by_loss"].value == 0.25
    assert s["median_s"].value == pytest.approx(1.0)
    stat = np.zeros((2, 15))
    stat[0, onset] = 5.0  # an alarm exactly at the onset frame
    stat[1, onset - 1] = 5.0  # an alarm one frame before it
    armed = np.ones(15, bool)
    np.testing.assert_array_equal(first_alarm_within(stat, 1.0, armed, onset), [True, False])


def test_arming_that_includes_the_first_frames_velocity_is_refused():
    """arm_k = 2n puts the velocity of the first measurement (3 Z_1, no velocity information) in the older
    window; it alarms in every run. The guard refuses arm_k < 2n + 1."""
    with pytest.raises(ValueError, match="arm_k"):
        TrackModeConfig(window=25, arm_k=50)
    TrackModeConfig(window=25, arm_k=51)


def test_earliest_valid_arming_has_the_nominal_false_alarm_rate():
    """At arm_k = 2n + 1 the windows hold least-squares velocities only: the exact threshold of the time-varying
    gains then gives the nominal per-test rate at the first test (without the guard, arm_k = 2n alarms always)."""
    n, alpha, Tn = 25, 0.05, 60
    z = 10.0 * np.arange(Tn) + np.random.default_rng(3).standard_normal((4000, Tn))
    c = threshold_from_std(alpha, scheduled_statistic_std(gain_schedule(1, 50, Tn), n, 1.0))
    c = np.where(np.isfinite(c), c, np.inf)
    out = run_track_modes(z, np.ones(Tn, bool), TrackModeConfig(threshold=c, arm_k=2 * n + 1), 1.0, covariance=False)
    first = 2 * n  # frame of count 2n + 1
    rate = np.mean(out.detection_frame == first)
    assert alpha / 1.4 < rate < alpha * 1.4


def test_exact_threshold_after_a_coast_keeps_the_nominal_rate():
    """After a 10 s loss without a manoeuvre the count-indexed exact threshold (computed for a run without loss)
    alarms far above alpha on re-arming; the frame-indexed threshold of the actual gain sequence, zero gains while
    lost (track2_thresholds), keeps the nominal per-test rate."""
    Tn, alpha = 625, 0.01
    vis = np.ones(Tn, bool)
    vis[300:550] = False
    z = np.random.default_rng(1).standard_normal((3000, Tn))
    out = run_track_modes(z, vis, TrackModeConfig(threshold=np.inf), 1.0, covariance=False)  # never switches
    S = out.statistic
    after = np.isfinite(S[0]) & (np.arange(Tn) >= 550)
    assert after.sum() >= 20
    c_count = threshold_from_std(alpha, scheduled_statistic_std(gain_schedule(1, 50, Tn), 25, 1.0))
    k = np.cumsum(vis)
    rate_count = np.mean(np.abs(S[:, after]) > c_count[k - 1][after])
    c_frame = track2_thresholds(vis, 50, 25, alpha, 1.0)
    rate_frame = np.mean(np.abs(S[:, after]) > c_frame[after])
    assert rate_count > 5 * alpha  # the bug this guards against
    assert alpha / 1.4 < rate_frame < alpha * 1.4
    before = np.isfinite(S[0]) & (np.arange(Tn) < 300)  # and the same thresholds before the loss
    np.testing.assert_allclose(c_frame[before], c_count[before], rtol=1e-12)


def test_frame_threshold_in_the_scheme_keeps_runs_in_track2_after_a_coast():
    Tn, alpha = 625, 1e-3
    vis = np.ones(Tn, bool)
    vis[300:550] = False
    z = np.random.default_rng(5).standard_normal((1500, Tn))
    cfg = TrackModeConfig(threshold=track2_thresholds(vis, 50, 25, alpha, 1.0), threshold_index="frame")
    d = run_track_modes(z, vis, cfg, 1.0, covariance=False).detection_frame
    switched_after = np.mean(d >= 550)
    assert switched_after < 0.05  # about 30 % with the count-indexed threshold


def test_pooled_false_alarm_rate_with_zero_events_gives_the_zero_events_bound():
    S = np.zeros((40, 6))
    armed = np.array([False, True, True, True, True, True])
    r = false_alarm_rates(S, 1.0, armed, armed, test_frame=5, arming_frame=1)
    pooled = r["per_test_pooled"]
    assert pooled.value == 0.0
    assert pooled.ci_low == 0.0 and pooled.ci_high == pytest.approx(zero_events_bound(40))
    assert "zero" in pooled.method
