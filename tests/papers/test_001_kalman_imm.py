"""Kalman filter and IMM (notebook 001) against filterpy (test-only reference); SPD covariances."""

import numpy as np
import pytest
from filterpy.kalman import IMMEstimator
from filterpy.kalman import KalmanFilter as FKalman

from tvtrack.filters.imm import cv_ca_models, imm_run
from tvtrack.filters.kalman import KalmanFilter, kf_predict, kf_update
from tvtrack.filters.polynomial import taylor_transition


def _data(rng, T=300):
    f = np.arange(T)
    truth = 10 * f + 0.1 * np.clip(f - 120, 0, None) ** 2
    return truth + rng.standard_normal(T)


def test_kalman_matches_filterpy():
    rng = np.random.default_rng(0)
    F = taylor_transition(2)
    H = np.array([[1.0, 0, 0]])
    Q = 1e-3 * np.outer([0.5, 1, 1], [0.5, 1, 1])
    R = np.array([[2.0]])
    x0, P0 = np.array([0.0, 9.0, 0.0]), np.diag([100.0, 10.0, 1.0])
    zs = np.stack([_data(rng) for _ in range(3)])  # (3, T)
    ours = KalmanFilter(F, H, Q, R).run(zs[..., None], x0, P0)
    for i in range(3):
        kf = FKalman(dim_x=3, dim_z=1)
        kf.F, kf.H, kf.Q, kf.R, kf.x, kf.P = F, H, Q, R, x0.copy(), P0.copy()
        for t, z in enumerate(zs[i]):
            if t > 0:
                kf.predict()
            kf.update(np.array([z]))
            np.testing.assert_allclose(ours.x[i, t], kf.x, rtol=0, atol=1e-9 * max(1.0, np.abs(kf.x).max()))
            np.testing.assert_allclose(ours.P[i, t], kf.P, rtol=0, atol=1e-9)


def test_imm_matches_filterpy():
    rng = np.random.default_rng(1)
    Fs, Qs = cv_ca_models(1e-4, 1e-3)
    H, R = np.array([[1.0, 0, 0]]), np.array([[1.0]])
    M = np.array([[0.97, 0.03], [0.05, 0.95]])
    x0, P0, mu0 = np.array([0.0, 10.0, 0.0]), np.diag([10.0, 4.0, 1.0]), np.array([0.6, 0.4])
    z = _data(rng)
    ours = imm_run(z[:, None], Fs, Qs, H, R, M, x0, P0, mu0)
    filters = []
    for F, Q in zip(Fs, Qs):
        kf = FKalman(dim_x=3, dim_z=1)
        kf.F, kf.Q, kf.H, kf.R, kf.x, kf.P = F.copy(), Q.copy(), H.copy(), R.copy(), x0.copy(), P0.copy()
        filters.append(kf)
    ref = IMMEstimator(filters, mu0.copy(), M)
    for t in range(z.size):
        ref.predict()
        # filterpy combines the priors with the last posterior mu; we use the predicted mode
        # probabilities cbar (textbook), so compare with its mode-matched priors weighted by cbar
        prior = sum(w * f.x for w, f in zip(ref.cbar, ref.filters))
        np.testing.assert_allclose(ours.x_prior[t], prior, rtol=0, atol=1e-9 * max(1.0, np.abs(prior).max()))
        ref.update(np.array([z[t]]))
        np.testing.assert_allclose(ours.x[t], ref.x, rtol=0, atol=1e-9 * max(1.0, np.abs(ref.x).max()))
        np.testing.assert_allclose(ours.P[t], ref.P, rtol=0, atol=1e-9)
        np.testing.assert_allclose(ours.mu[t], ref.mu, rtol=0, atol=1e-9)


def test_imm_coasts_on_missing_measurements():
    rng = np.random.default_rng(2)
    Fs, Qs = cv_ca_models(1e-4, 1e-3)
    M = np.array([[0.9, 0.1], [0.1, 0.9]])
    z = _data(rng, 100)
    z[50:60] = np.nan
    out = imm_run(z[:, None], Fs, Qs, np.array([[1.0, 0, 0]]), np.eye(1), M, np.zeros(3), np.eye(3) * 100, [0.5, 0.5])
    np.testing.assert_allclose(out.mu[55], out.mu[54] @ M)  # mode probabilities only predicted
    np.testing.assert_allclose(out.x[55], out.x_prior[55])
    assert np.all(np.isfinite(out.x))


def _assert_spd(P):
    np.testing.assert_array_equal(P, np.swapaxes(P, -1, -2))
    assert np.linalg.eigvalsh(P).min() > 0


def test_kalman_covariance_stays_spd_over_a_million_steps():
    """2000 independent, deliberately ill-conditioned filters x 500 steps = 10^6 filter steps."""
    rng = np.random.default_rng(3)
    B, T = 2000, 500
    F = taylor_transition(2) * rng.uniform(0.98, 1.02, (B, 1, 1))
    H = np.array([[1.0, 0, 0]])
    q = 10.0 ** rng.uniform(-12, -2, B)
    Q = q[:, None, None] * np.outer([1 / 6, 0.5, 1], [1 / 6, 0.5, 1]) + 1e-14 * np.eye(3)
    R = (10.0 ** rng.uniform(-6, 3, B))[:, None, None]
    x = np.zeros((B, 3))
    P = np.broadcast_to(np.diag([1e8, 1e4, 1.0]), (B, 3, 3)).copy()
    for t in range(T):
        x, P = kf_predict(x, P, F, Q)
        present = rng.random(B) > 0.1
        x, P, _, _ = kf_update(x, P, rng.standard_normal((B, 1)), H, R, present)
        if t % 50 == 0 or t == T - 1:
            _assert_spd(P)


def test_imm_covariance_stays_spd():
    rng = np.random.default_rng(4)
    Fs, Qs = cv_ca_models(1e-8, 1e-6)
    M = np.array([[0.99, 0.01], [0.01, 0.99]])
    z = np.stack([_data(rng, 400) for _ in range(200)])
    z[:, 200:260] = np.nan
    out = imm_run(
        z[..., None],
        Fs,
        Qs,
        np.array([[1.0, 0, 0]]),
        np.array([[1e-4]]),
        M,
        np.zeros(3),
        np.diag([1e6, 1e4, 1.0]),
        [0.5, 0.5],
    )
    # the CV mode pins a = 0, so its covariance is singular in a by construction: the combined
    # covariance is symmetric positive semi-definite, and positive definite on (x, v)
    np.testing.assert_array_equal(out.P, np.swapaxes(out.P, -1, -2))
    scale = np.abs(out.P).max(axis=(-1, -2))
    assert np.all(np.linalg.eigvalsh(out.P).min(axis=-1) >= -1e-12 * scale)
    _assert_spd(out.P[..., :2, :2])


def test_imm_bad_input():
    Fs, Qs = cv_ca_models(1e-4, 1e-3)
    with pytest.raises(ValueError, match="transition"):
        imm_run(
            np.zeros((5, 1)),
            Fs,
            Qs,
            np.array([[1.0, 0, 0]]),
            np.eye(1),
            np.eye(2) * 0.5,
            np.zeros(3),
            np.eye(3),
            [0.5, 0.5],
        )
    with pytest.raises(ValueError, match="q_cv"):
        cv_ca_models(-1.0, 0.0)


def test_imm_loglik_of_one_mode_is_the_kalman_innovation_likelihood():
    rng = np.random.default_rng(3)
    F = taylor_transition(2)
    H, R = np.array([[1.0, 0, 0]]), np.array([[1.5]])
    Q = 1e-4 * np.outer([0.5, 1, 1], [0.5, 1, 1])
    zs = _data(rng, 120)
    zs[50:60] = np.nan
    x0, P0 = np.zeros(3), np.diag([1e4, 1e2, 1.0])
    imm = imm_run(zs[:, None], F[None], Q[None], H, R, np.eye(1), x0, P0, [1.0])
    kf = FKalman(dim_x=3, dim_z=1)
    kf.F, kf.H, kf.Q, kf.R, kf.x, kf.P = F, H, Q, R, x0.copy(), P0.copy()
    ll = 0.0
    for z in zs:
        kf.predict()
        if np.isfinite(z):
            kf.update(z)
            ll += kf.log_likelihood
    assert float(imm.loglik) == pytest.approx(ll, rel=1e-9)


def test_imm_frozen_coast_keeps_mode_probabilities_and_the_ca_acceleration():
    rng = np.random.default_rng(4)
    zs = _data(rng, 300)
    zs[200:] = np.nan
    Fs, Qs = cv_ca_models(1e-6, 1e-5)
    M = np.array([[0.98, 0.02], [0.02, 0.98]])
    args = (Fs, Qs, np.array([[1.0, 0, 0]]), np.array([[1.0]]), M, np.zeros(3), np.diag([1e6, 1e4, 1.0]), [0.5, 0.5])
    frozen = imm_run(zs[:, None], *args, coast="frozen")
    mixed = imm_run(zs[:, None], *args)
    np.testing.assert_allclose(frozen.mu[200:], np.broadcast_to(frozen.mu[199], (100, 2)), rtol=1e-12)
    assert abs(frozen.x[-1, 2] - 0.2) < 0.05 < abs(mixed.x[-1, 2] - 0.2)  # true acceleration 0.2
    mode = imm_run(zs[:, None], *args, coast="mode")  # the CA mode is the most probable at the loss
    assert mode.mu[199, 1] > 0.5
    np.testing.assert_allclose(mode.mu[200:], np.broadcast_to([0.0, 1.0], (100, 2)))
    assert abs(mode.x[-1, 2] - 0.2) < 0.05
    with pytest.raises(ValueError, match="coast"):
        imm_run(zs[:, None], *args, coast="bogus")
