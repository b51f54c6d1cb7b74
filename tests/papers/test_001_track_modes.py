"""Tests of tvtrack.papers.p001_maneuver_occlusion_kf.track_modes (notebook 001): mode logic against hand-built runs,
with both engines (the NumPy frame loop and the compiled kernel)."""

import numpy as np
import pytest

from tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector import (
    scheduled_statistic_std,
    threshold_from_std,
    window_statistic,
)
from tvtrack.filters.alphabeta import error_covariance_sequence, gain_schedule, scheduled_filter
from tvtrack.filters.polynomial import polynomial_observation_row, taylor_transition
from tvtrack.papers.p001_maneuver_occlusion_kf.track_modes import (
    COAST,
    TRACK2,
    TRACK3,
    TrackModeConfig,
    run_track_modes,
)

T = 400


@pytest.fixture(autouse=True, params=["numpy", "jit"])
def engine(request, monkeypatch):
    """Every test here runs with the NumPy frame loop (``TVTRACK_NO_JIT=1``, the fallback) and with the
    compiled kernel (skipped when numba is not importable)."""
    if request.param == "jit":
        pytest.importorskip("numba")
    monkeypatch.setenv("TVTRACK_NO_JIT", "1" if request.param == "numpy" else "0")
    return request.param


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
    G3 = gain_schedule(2, 80, 3 + T - ks)[3:]  # k = 4, 5, ...
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
    fit = np.linalg.lstsq(H, z[:, t - n + 1 : t + 1].T, rcond=None)[0].T
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
    assert np.all(np.isnan(S[:, :99]))  # armed at k = kb2 + 2n = 100
    first = np.nanargmax(np.abs(S) > th, axis=1)
    np.testing.assert_array_equal(first[d >= 0], d[d >= 0])


def test_bad_config():
    with pytest.raises(ValueError, match="restart"):
        TrackModeConfig(restart="D")
    with pytest.raises(ValueError, match="k_bound3"):
        TrackModeConfig(k_bound3=2)
    with pytest.raises(ValueError, match="threshold"):
        TrackModeConfig(threshold=-1.0)
    with pytest.raises(ValueError, match="sigma_eps"):
        run_track_modes(np.zeros((1, 10)), np.ones(10, bool), TrackModeConfig(), 0.0)


def _low_threshold_run(restart, **cfg):
    """Detector kept on in TRACK3 with a low threshold, so that it restarts the 3rd-order law many times."""
    _, z = _z(6, seed=3)
    return run_track_modes(
        z,
        np.ones(T, bool),
        TrackModeConfig(threshold=1.0, detect_in_track3=True, arm_k=51, restart=restart, **cfg),
        1.0,
    )


@pytest.mark.parametrize("restart", ["A", "B", "C"])
def test_detector_statistic_is_the_window_statistic_of_the_output_velocities(restart):
    """B1: with the detector on in TRACK3, a restart that changes the velocity estimate must not leave
    the running window sums holding the pre-restart value (S drifted from the true window statistic)."""
    out = _low_threshold_run(restart)
    S, c = out.statistic, out.threshold
    ref = window_statistic(out.x[..., 1], 25)
    tested = np.isfinite(S) & ~(np.abs(S) > c)  # frames with a test and no restart at that frame
    assert tested.sum() > 20 and np.all((out.mode == TRACK3).sum(1) > 0)
    np.testing.assert_allclose(S[tested], ref[tested], atol=1e-8)


def test_track3_tests_use_the_track3_threshold():
    """B2: in TRACK3 the threshold in force comes from ``threshold_track3`` indexed by the TRACK3 count,
    not from the TRACK2 array indexed by the TRACK3 counter."""
    _, z = _z(4, seed=5)
    thr2 = np.linspace(50.0, 3.0, 400)  # a TRACK2 array that varies with k
    thr3 = np.linspace(2.0, 9.0, 300)
    out = run_track_modes(
        z,
        np.ones(T, bool),
        TrackModeConfig(threshold=thr2, threshold_track3=thr3, detect_in_track3=True, arm_k=60),
        1.0,
    )
    was3 = np.concatenate([np.zeros((4, 1), bool), out.mode[:, :-1] == TRACK3], axis=1)  # tested in TRACK3
    in3 = was3 & np.isfinite(out.threshold)
    in2 = ~was3 & np.isfinite(out.threshold)
    assert in3.sum() > 10 and in2.sum() > 10
    assert np.all(np.isin(out.threshold[in3], thr3)) and not np.any(np.isin(out.threshold[in3], thr2))
    assert np.all(np.isin(out.threshold[in2], thr2))
    with pytest.raises(ValueError, match="threshold_track3"):
        TrackModeConfig(threshold=thr2, detect_in_track3=True)


def test_restart_c_is_a_kalman_reset_from_the_track2_covariance():
    """Restart C: at the switch keep (x, v) and their TRACK2 noise covariance, set a = 0 with a diffuse
    variance, run Kalman gains (no process noise) until kappa1 reaches the bound, then the bound."""
    _, z = _z(3, seed=11)
    ks, kb3, var_a = 138, 60, 1e4
    out = run_track_modes(
        z,
        np.ones(T, bool),
        TrackModeConfig(k_bound2=50, k_bound3=kb3, force_switch_k=ks, restart="C", restart_accel_var=var_a),
        1.0,
    )
    G2 = gain_schedule(1, 50, ks)
    x = np.c_[scheduled_filter(z[:, :ks], G2)[:, -1], np.zeros(3)]
    P2 = error_covariance_sequence(G2, 1.0)[-1]
    P = np.zeros((3, 3))
    P[:2, :2] = P2
    P[2, 2] = var_a
    F, h = taylor_transition(2), np.array([1.0, 0, 0])
    bound = gain_schedule(2, kb3)[-1]
    kalman = True
    for t in range(ks, T):
        Pp = F @ P @ F.T
        K = Pp @ h / (h @ Pp @ h + 1.0) if kalman else bound
        if kalman and K[0] <= bound[0]:
            kalman, K = False, bound
        x = x @ F.T + (z[:, t] - x @ F.T @ h)[:, None] * K
        IKh = np.eye(3) - np.outer(K, h)
        P = IKh @ Pp @ IKh.T + np.outer(K, K)
        np.testing.assert_allclose(out.x[:, t], x, rtol=1e-9, atol=1e-7)
        np.testing.assert_allclose(out.gains[0, t], K, rtol=1e-9, atol=1e-12)
    assert not kalman  # reached the bound in the run


def _per_trial_reference(z, vis, thr, kb2, kb3, n, restart):
    """The mode logic written the straightforward way: one sequence at a time, filterpy's g-h-k
    filter (its ``k`` is kappa3/2) with the gains overridden per update, the detector statistic
    summed afresh over both windows at every test, restart A (k = 3, a = 0) or B (window LS fit)."""
    from filterpy.gh import GHKFilter

    T = z.size
    G2, G3 = gain_schedule(1, kb2), gain_schedule(2, kb3)
    flt = GHKFilter(0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)
    k, in3, since, had_gap, det = 0, False, 0, False, -1
    xs, gains = np.empty((T, 3)), np.zeros((T, 3))
    S, mode = np.full(T, np.nan), np.zeros(T, int)
    for t in range(T):
        if vis[t]:
            k += 1
            since += 1
            gains[t] = G3[min(k, kb3) - 1] if in3 else np.r_[G2[min(k, kb2) - 1], 0.0]
            flt.update(z[t], g=gains[t, 0], h=gains[t, 1], k=gains[t, 2] / 2)
            mode[t] = TRACK3 if in3 else TRACK2
        else:
            since, had_gap = 0, True
            flt.update(0.0, g=0.0, h=0.0, k=0.0)
        xs[t] = flt.x, flt.dx, flt.ddx
        if not in3 and vis[t] and k >= kb2 + 2 * n and (since >= 2 * n or not had_gap):
            S[t] = xs[t - 2 * n + 1 : t - n + 1, 1].sum() - xs[t - n + 1 : t + 1, 1].sum()
            if abs(S[t]) > thr[min(k, thr.size) - 1]:
                det, in3, mode[t] = t, True, TRACK3  # the switch frame counts as TRACK3
                if restart == "A":
                    k, flt.ddx = 3, 0.0
                else:
                    H = polynomial_observation_row(2, np.arange(n - 1, -1, -1))
                    k, (flt.x, flt.dx, flt.ddx) = n, np.linalg.lstsq(H, z[t - n + 1 : t + 1], rcond=None)[0]
                xs[t] = flt.x, flt.dx, flt.ddx
    return xs, S, gains, mode, det


@pytest.mark.parametrize("restart", ["A", "B"])
def test_batched_run_equals_the_per_trial_filterpy_loop(restart):
    """The batched, in-place implementation (frame-by-frame output buffers, counters shared while
    the trials run in lockstep) against the straightforward per-trial loop, with per-trial gaps,
    trials without a manoeuvre and the exact time-varying threshold."""
    kb2, kb3, n, n_trials = 20, 40, 10, 12
    _, z = _z(n_trials, seed=13, onset=150)
    z[::3] = 10.0 * np.arange(T) + np.random.default_rng(14).standard_normal((4, T))  # no manoeuvre
    vis = np.ones((n_trials, T), bool)
    for i in range(n_trials):
        vis[i, 190 + 7 * i : 230 + 9 * i] = False  # gaps differ per trial
    z = np.where(vis, z, np.nan)
    c = threshold_from_std(1e-2, scheduled_statistic_std(gain_schedule(1, kb2, T), n, 1.0))
    thr = np.where(np.isfinite(c), c, np.inf)
    cfg = TrackModeConfig(k_bound2=kb2, k_bound3=kb3, window=n, threshold=thr, restart=restart)
    out = run_track_modes(z.reshape(3, 4, T), vis.reshape(3, 4, T), cfg, 1.0, covariance=False)
    refs = [_per_trial_reference(z[i], vis[i], thr, kb2, kb3, n, restart) for i in range(n_trials)]
    xs, S, gains, mode, det = (np.stack(r) for r in zip(*refs))
    assert 0 < np.sum(det >= 0) < n_trials  # both kinds of trial
    np.testing.assert_array_equal(out.detection_frame.reshape(-1), det)
    np.testing.assert_array_equal(out.mode.reshape(n_trials, T), mode)
    np.testing.assert_array_equal(out.gains.reshape(n_trials, T, 3), gains)
    x = out.x.reshape(n_trials, T, 3)
    for i in range(3):  # 1e-12 of each component's scale (a's is set by its restart)
        np.testing.assert_allclose(x[..., i], xs[..., i], rtol=0, atol=1e-12 * np.abs(xs[..., i]).max())
    # running window sums vs sums taken afresh: agreement to 1e-12 of the sums' magnitude
    np.testing.assert_array_equal(np.isnan(out.statistic.reshape(n_trials, T)), np.isnan(S))
    np.testing.assert_allclose(
        out.statistic.reshape(n_trials, T), S, rtol=0, atol=1e-12 * n * np.abs(xs[..., 1]).max(), equal_nan=True
    )
