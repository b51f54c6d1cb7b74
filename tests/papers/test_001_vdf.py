"""Tests of tvtrack.filters.vdf (notebook 001's variable-dimension filter comparator)."""

import numpy as np
import pytest

from tvtrack.filters.imm import cv_ca_models
from tvtrack.filters.kalman import KalmanFilter
from tvtrack.filters.vdf import vd_filter_run, vd_restart_covariance

T = 300


def _scenario(n, seed, onset=120, accel=0.2):
    f = np.arange(T)
    truth = 10.0 * f + 0.5 * accel * np.clip(f - onset, 0, None) ** 2
    return truth, truth + np.random.default_rng(seed).standard_normal((n, T))


def test_without_detection_it_is_the_cv_kalman_filter():
    _, z = _scenario(4, 0)
    vis = np.ones(T, bool)
    vis[150:200] = False
    q_cv = 1e-4
    out = vd_filter_run(z, vis, q_cv, 1e-3, 1.0, 10, np.inf)
    Fs, Qs = cv_ca_models(q_cv, 1e-3)
    P0 = np.diag([1e6, 1e4, 0.0])
    kf = KalmanFilter(Fs[0], np.array([[1.0, 0.0, 0.0]]), Qs[0], np.array([[1.0]]))
    ref = kf.run(
        np.where(vis, z, np.nan)[..., None], np.zeros(3), Fs[0] @ P0 @ Fs[0].T + Qs[0]
    )  # VD predicts at frame 0 too
    np.testing.assert_allclose(out.x, ref.x, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(out.var_prior[:, 1:], ref.P_prior[:, 1:, 0, 0], rtol=1e-9)
    assert np.all(out.detection_frame == -1) and not out.ca.any()
    # rho is the fading-memory sum of the normalised innovations squared
    lam = 1 - 1 / 10
    rho, expect = out.rho[0], 0.0
    for t in range(T):
        if vis[t]:
            expect = lam * expect + ref.nis[0, t]
        assert rho[t] == pytest.approx(expect, rel=1e-9)


def test_restart_covariance_matches_monte_carlo():
    rng = np.random.default_rng(1)
    P_xv = np.array([[0.3, 0.05], [0.05, 0.02]])
    n = 400_000
    e = rng.multivariate_normal(np.zeros(2), P_xv, n)  # CV posterior errors at t0 - 1
    ez = 1.5 * rng.standard_normal(n)  # measurement error at t0
    x_true, v_true = 100.0, 10.0  # no manoeuvre: the re-initialised truth is (x+v, v, 0)
    x_hat, v_hat, z = x_true + e[:, 0], v_true + e[:, 1], x_true + v_true + ez
    a = 2.0 * (z - (x_hat + v_hat))
    errs = np.stack([z - (x_true + v_true), v_hat + a - v_true, a], axis=1)
    np.testing.assert_allclose(np.cov(errs.T), vd_restart_covariance(P_xv, 1.5), rtol=0.02, atol=2e-3)


def test_batched_equals_one_trial_at_a_time_and_detects_after_the_onset():
    truth, z = _scenario(8, 2)
    vis = np.ones((8, T), bool)
    vis[::2, 200:240] = False
    out = vd_filter_run(z, vis, 0.0, 1e-6, 1.0, 10, 30.0)
    d = out.detection_frame
    assert np.all((d > 120) & (d < 140))
    for i in range(8):
        one = vd_filter_run(z[i], vis[i], 0.0, 1e-6, 1.0, 10, 30.0)
        assert one.detection_frame == d[i]
        np.testing.assert_allclose(one.x, out.x[i], rtol=1e-12, atol=1e-9)
    # after the restart the estimate follows the acceleration
    assert np.all(np.abs(out.x[:, 199, 2] - 0.2) < 0.05)


def test_bad_parameters():
    with pytest.raises(ValueError, match="window"):
        vd_filter_run(np.zeros((1, 10)), np.ones(10, bool), 0.0, 0.0, 1.0, 1, 5.0)
    with pytest.raises(ValueError, match="sigma_eps"):
        vd_filter_run(np.zeros((1, 10)), np.ones(10, bool), 0.0, 0.0, 0.0, 5, 5.0)


def test_detection_restarts_back_in_time_and_reruns_the_ca_filter():
    """At a detection at t the state is the CA Kalman filter started at t0 = t - window from the
    re-initialisation (z_t0, v + a, a = 2 (z_t0 - x - v)) and run over t0+1 .. t."""
    _, z = _scenario(1, 3)
    vis = np.ones(T, bool)
    win, q_ca = 10, 1e-6
    out = vd_filter_run(z, vis, 0.0, q_ca, 1.0, win, 30.0)
    t = int(out.detection_frame[0])
    t0 = t - win
    Fs, Qs = cv_ca_models(0.0, q_ca)
    P0 = np.diag([1e6, 1e4, 0.0])
    cv = KalmanFilter(Fs[0], np.array([[1.0, 0.0, 0.0]]), Qs[0], np.array([[1.0]])).run(
        z[0, :t0][:, None], np.zeros(3), Fs[0] @ P0 @ Fs[0].T + Qs[0]
    )
    x_prev, P_prev = cv.x[t0 - 1], cv.P[t0 - 1]
    np.testing.assert_allclose(out.x[0, t0 - 1], x_prev, rtol=1e-9)
    a = 2.0 * (z[0, t0] - x_prev[0] - x_prev[1])
    ca = KalmanFilter(Fs[1], np.array([[1.0, 0.0, 0.0]]), Qs[1], np.array([[1.0]]))
    x_r, P_r = np.array([z[0, t0], x_prev[1] + a, a]), vd_restart_covariance(P_prev[:2, :2], 1.0)
    ref = ca.run(z[0, t0 + 1 : t + 1][:, None], Fs[1] @ x_r, Fs[1] @ P_r @ Fs[1].T + Qs[1])
    np.testing.assert_allclose(out.x[0, t], ref.x[-1], rtol=1e-9, atol=1e-9)
    assert out.ca[0, t] and not out.ca[0, t - 1]
