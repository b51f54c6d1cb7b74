import numpy as np
import pytest
from filterpy.kalman import KalmanFilter as FPKalman

from tvtrack.filters import (
    KalmanFilter,
    growing_memory_filter,
    growing_memory_gains,
    polynomial_observation_row,
    predict_ahead,
    taylor_transition,
)
from tvtrack.montecarlo import make_rng


def cv_model(q=0.01, r=0.5):
    F = np.array([[1.0, 1.0], [0.0, 1.0]])
    H = np.array([[1.0, 0.0]])
    Q = q * np.array([[1 / 3, 1 / 2], [1 / 2, 1.0]])
    return F, H, Q, np.array([[r]])


def test_kalman_matches_filterpy():
    F, H, Q, R = cv_model()
    rng = make_rng(0)
    zs = np.cumsum(rng.normal(size=(3, 60, 1)), axis=1)
    zs[1, 20:25] = np.nan
    out = KalmanFilter(F, H, Q, R).run(zs, x0=[0.0, 0.0], P0=10 * np.eye(2))
    for trial in range(3):
        ref = FPKalman(dim_x=2, dim_z=1)
        ref.F, ref.H, ref.Q, ref.R, ref.P, ref.x = F, H, Q, R, 10 * np.eye(2), np.zeros(2)
        for t in range(60):
            if t > 0:
                ref.predict()
            z = zs[trial, t]
            if np.all(np.isfinite(z)):
                ref.update(z)
            assert np.allclose(out.x[trial, t], ref.x, atol=1e-9, rtol=1e-9)
            assert np.allclose(out.P[trial, t], ref.P, atol=1e-9, rtol=1e-9)


def test_kalman_covariance_stays_symmetric_positive_definite():
    F, H, Q, R = cv_model(q=1e-8, r=1e-6)
    zs = make_rng(1).normal(size=(2, 500, 1))
    out = KalmanFilter(F, H, Q, R).run(zs, x0=[0.0, 0.0], P0=1e6 * np.eye(2))
    assert np.array_equal(out.P, np.swapaxes(out.P, -1, -2))
    assert np.all(np.linalg.eigvalsh(out.P) > 0)


def test_nis_is_chi2_on_a_matched_model():
    F, H, Q, R = cv_model(q=0.05, r=1.0)
    rng = make_rng(2)
    n, T = 400, 100
    x = np.zeros((n, 2))
    zs = np.empty((n, T, 1))
    L = np.linalg.cholesky(Q)
    for t in range(T):
        if t:
            x = x @ F.T + rng.normal(size=(n, 2)) @ L.T
        zs[:, t, 0] = x[:, 0] + rng.normal(size=n)
    out = KalmanFilter(F, H, Q, R).run(zs, x0=[0.0, 0.0], P0=1e-12 * np.eye(2) + 0 * Q)
    nis = out.nis[:, 20:].mean()
    assert nis == pytest.approx(1.0, abs=4 * np.sqrt(2 / (n * 80)) * 3)


@pytest.mark.parametrize("order", [0, 1, 2, 3])
def test_growing_memory_recursion_equals_batch_least_squares(order):
    rng = make_rng(3)
    T = 120
    z = rng.normal(size=(4, T)) + 0.01 * np.arange(T) ** 2
    states = growing_memory_filter(z, order)
    assert np.isnan(states[:, :order]).all()
    for t in range(order, T):
        H = polynomial_observation_row(order, t - np.arange(t + 1))
        batch = np.linalg.lstsq(H, z[:, : t + 1].T, rcond=None)[0].T
        assert np.allclose(states[:, t], batch, rtol=1e-9, atol=1e-9 * np.abs(batch).max())


def test_second_order_gains_have_the_closed_form():
    N = np.arange(3, 2001, dtype=float)
    g = growing_memory_gains(2, 2000)[2:]
    closed = (
        np.stack([3 * (3 * N**2 - 3 * N + 2), 18 * (2 * N - 1), 60 * np.ones_like(N)], 1)
        / (N * (N + 1) * (N + 2))[:, None]
    )
    assert np.allclose(g, closed, rtol=1e-9)


def test_floor_freezes_the_gain_and_missing_samples_coast():
    z = np.arange(40.0) ** 2 / 2  # exact quadratic: any gain reproduces it
    z_missing = z.copy()
    z_missing[10:15] = np.nan
    for zz in (z, z_missing):
        s = growing_memory_filter(zz, 2, floor_memory=6)
        assert np.allclose(s[-1], [z[-1], 39.0, 1.0])
    with pytest.raises(ValueError, match="floor_memory"):
        growing_memory_filter(z, 2, floor_memory=2)


def test_prediction_and_transition_agree():
    x = np.array([1.0, 2.0, 0.5, 0.1])
    F3 = np.linalg.matrix_power(taylor_transition(3), 3)
    assert predict_ahead(x, 3) == pytest.approx((F3 @ x)[0])
    assert np.allclose(taylor_transition(2, -1), np.linalg.inv(taylor_transition(2, 1)))
    with pytest.raises(ValueError, match="order"):
        taylor_transition(4)


def test_first_estimate_skips_missing_samples():
    # with a gap before the filter starts, the first estimate is the exact quadratic through
    # the first three *present* samples (eq. 4), placed at the time of the third
    t = np.arange(10.0)
    z = 2.0 - 0.5 * t + 0.25 * t**2
    z[1] = np.nan
    s = growing_memory_filter(z[None], 2)[0]
    assert np.isnan(s[:3]).all()
    assert np.allclose(s[3], [z[3], -0.5 + 0.5 * 3, 0.5])


def test_one_joseph_update_for_any_gain_matches_the_textbook_form():
    """joseph_covariance: the scalar outer-product path and the matrix path agree with
    (I - K H) P (I - K H)^T + K R K^T for a suboptimal gain, and reduce to (I - K H) P for the
    Kalman gain."""
    import numpy as np

    from tvtrack.filters.kalman import joseph_covariance

    rng = np.random.default_rng(0)
    A = rng.normal(size=(5, 3, 3))
    P = A @ np.swapaxes(A, -1, -2) + np.eye(3)
    for m in (1, 2):
        H = rng.normal(size=(m, 3))
        R = np.eye(m) * 0.7
        K = rng.normal(size=(5, 3, m))  # any gain
        IKH = np.eye(3) - K @ H
        want = IKH @ P @ np.swapaxes(IKH, -1, -2) + K @ R @ np.swapaxes(K, -1, -2)
        np.testing.assert_allclose(joseph_covariance(P, K, H, R), want, rtol=1e-12, atol=1e-12)
        S = H @ P @ H.T + R
        K_opt = P @ H.T @ np.linalg.inv(S)
        np.testing.assert_allclose(joseph_covariance(P, K_opt, H, R), (np.eye(3) - K_opt @ H) @ P, atol=1e-10)


def test_joseph_update_keeps_its_digits_under_a_diffuse_prior():
    """A 1e12 prior measured with 1e-6 noise: the posterior variance is the measurement's, 1e-6. The
    expanded (outer-product) Joseph form cancels to 0 here; the factored form keeps it."""
    import numpy as np

    from tvtrack.filters.kalman import joseph_covariance

    P = np.diag([1e12, 1e12])[None]
    H = np.array([[1.0, 0.0]])
    K = (P[:, :, 0] / (P[:, 0, 0, None] + 1e-6))[..., None]
    out = joseph_covariance(P, K, H, 1e-6)[0]
    np.testing.assert_allclose(out, np.diag([1e-6, 1e12]), rtol=1e-6)
