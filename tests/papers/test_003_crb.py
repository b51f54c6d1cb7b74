"""Tests of paper 003's posterior CRB and the velocity-state EKF (beyond the paper)."""

import numpy as np
import pytest
from scipy.linalg import expm

from tvtrack.papers.p003_rotating_marker_tracker import crb
from tvtrack.papers.p003_rotating_marker_tracker.ekf import VelocityEKFTracker, velocity_model


def _overlap(lo, hi, n):
    """Overlap of [lo, hi] with each unit pixel centred on 0..n-1 (interval arithmetic, no renderer)."""
    p = np.arange(n)
    return np.clip(np.minimum(p + 0.5, hi) - np.maximum(p - 0.5, lo), 0.0, None)


def test_square_spot_information_has_its_closed_form():
    """A square spot of side D moved along x changes only the two edge columns, by d per px each row it covers:
    G_xx = 2 d^2 sum_rows overlap_y^2 / sigma^2 (averaged over the sub-pixel positions used)."""
    D, d, sigma, k = 8.0, 1.0, 0.02, 7
    size = int(np.ceil(D)) + 6
    ref = np.mean([2 * d**2 * np.sum(_overlap(c - D / 2, c + D / 2, size) ** 2) for c in size / 2 + np.arange(k) / k])
    G = crb.spot_position_information("square", D, d, sigma, offsets=k)
    assert G[0, 0] == pytest.approx(ref / sigma**2, rel=1e-6)
    assert G[1, 1] == pytest.approx(G[0, 0], rel=1e-9) and abs(G[0, 1]) < 1e-6 * G[0, 0]
    # supersampling the square's box render changes nothing (it already integrates pixel areas exactly)
    assert crb.spot_position_information("square", D, d, sigma, supersample=4, offsets=k)[0, 0] == pytest.approx(
        G[0, 0], rel=1e-6
    )


def test_disc_information_converges_with_supersampling_to_the_rim_integral():
    """Supersampled renders tend to exact pixel areas: the information converges (within 5 % from s = 4 to 16,
    the resolution dependence of a sharp-edged spot) to the order of the rim's, d^2 (pi D) <n_x^2> / sigma^2 per unit
    rim length crossing a pixel: between a half and twice pi D / 2 for d = sigma = 1."""
    vals = [crb.spot_position_information("disc", 8.0, 1.0, 1.0, supersample=s)[0, 0] for s in (4, 8, 16)]
    assert max(vals) / min(vals) < 1.05
    assert 0.5 * np.pi * 8.0 / 2 < vals[-1] < 2 * np.pi * 8.0 / 2


def test_marker_information_closed_form_for_an_isotropic_spot():
    g, r = 3.0e4, 12.0
    J = crb.marker_information(g * np.eye(2), r)
    np.testing.assert_allclose(J, np.diag([g, g, g, g * r**2, 0, 0, 0]), atol=1e-6 * g)


def test_prediction_bound_static_limit_is_the_information_sum():
    """No dynamics (F = I, Q -> 0): after k frames the bound on x_r is 1 / (1/p0 + k g)."""
    g, r, p0, T = 50.0, 12.0, 4.0, 40
    F, Q = np.eye(7), 1e-12 * np.eye(7)
    P0 = p0 * np.eye(7)
    B = crb.prediction_bound(F, Q, P0, crb.marker_information(g * np.eye(2), r), T)
    k = np.arange(T)
    np.testing.assert_allclose(B[:, 0, 0], 1 / (1 / p0 + k * g), rtol=1e-6)
    np.testing.assert_allclose(B[:, 3, 3], 1 / (1 / p0 + k * g * r**2), rtol=1e-5)


def test_velocity_model_is_the_exact_discretisation():
    """Van Loan: Q = int_0^dt e^{A s} L q L^T e^{A^T s} ds for the continuous model x' = A x + L w."""
    dt, qa, qr, qo = 0.01, 100.0, 0.05, 1.0
    A = np.zeros((7, 7))
    A[0, 5] = A[1, 6] = A[3, 4] = 1.0
    W = np.diag([0, 0, qr, 0, qo, qa, qa])
    M = expm(np.block([[-A, W], [np.zeros((7, 7)), A.T]]) * dt)
    F_ref = M[7:, 7:].T
    Q_ref = F_ref @ M[:7, 7:]
    F, Q = velocity_model(dt, qa, qr, qo)
    np.testing.assert_allclose(F, F_ref, atol=1e-12)
    np.testing.assert_allclose(Q, Q_ref, rtol=1e-9, atol=1e-15)


def test_velocity_ekf_step_matches_filterpy():
    from filterpy.kalman import ExtendedKalmanFilter

    x0 = np.array([[100.0, 90.0, 12.0, 0.7, 50.0, 15.0, -8.0]])
    P0 = np.diag([4.0, 3.0, 2.0, 0.05, 1.0, 100.0, 90.0])
    mv, S, dt, q = 0.002, 16.0, 0.002, (100.0, 0.05, 1.0)
    ekf = VelocityEKFTracker(x0, P0, *q, mv, S)
    dx, dy = np.array([8.0]), np.array([-5.0])
    ekf.update(dx, dy, dt)
    ref = ExtendedKalmanFilter(dim_x=7, dim_z=2)
    ref.x, ref.P, ref.R = x0[0].copy(), P0.copy(), mv * np.eye(2)
    th, r = x0[0, 3], x0[0, 2]
    H = np.zeros((2, 7))
    H[0, :4] = [1, 0, np.cos(th), -r * np.sin(th)]
    H[1, :4] = [0, 1, np.sin(th), r * np.cos(th)]
    ref.update(np.array([8.0, -5.0]) / S, HJacobian=lambda x: H, Hx=lambda x: np.zeros(2))
    ref.F, ref.Q = velocity_model(dt, *q)
    ref.predict()
    np.testing.assert_allclose(ekf.lam[0], ref.x, rtol=1e-10)
    np.testing.assert_allclose(ekf.P[0], ref.P, rtol=1e-8, atol=1e-12)
    np.testing.assert_allclose(ekf.state[0], ref.x[:5], rtol=1e-10)


def test_every_tracker_respects_the_bound_and_the_velocity_ekf_beats_the_loops():
    out = crb.compare_with_bound(5, 5, 2.0, 0.8, bxy_grid=(10.0,), supersample=(1,))
    b = out["bound"][1]
    assert 0 < b < 0.05  # the pixels pin the position to hundredths of a pixel
    for name, e in out["rms"].items():
        assert e.value > b, name
    assert out["rms"]["EKF (velocity)"].ci_high < out["rms"]["loops 10 Hz"].ci_low
    assert out["lost"]["EKF (velocity)"] == 0
