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


# ----------------------------------------------------------------------------- the one filter interface


def _filterpy_history(F, H, Q, R, zs, x0, P0):
    """filterpy's KalmanFilter over one sequence (T, m), with our convention: prior of time 0, update first."""
    ref = FPKalman(dim_x=F.shape[0], dim_z=H.shape[0])
    ref.F, ref.H, ref.Q, ref.R, ref.P, ref.x = F, H, Q, R, np.array(P0, float), np.array(x0, float)
    out = {"x_prior": [], "P_prior": [], "x": [], "P": []}
    for t, z in enumerate(zs):
        if t > 0:
            ref.predict()
        out["x_prior"].append(ref.x.copy())
        out["P_prior"].append(ref.P.copy())
        if np.all(np.isfinite(z)):
            ref.update(z)
        out["x"].append(ref.x.copy())
        out["P"].append(ref.P.copy())
    return {k: np.array(v) for k, v in out.items()}


def test_batched_run_over_two_trial_axes_matches_filterpy_sequence_by_sequence():
    from tvtrack.filters import SequentialFilter

    F = np.array([[1.0, 1.0, 0.5], [0.0, 1.0, 1.0], [0.0, 0.0, 1.0]])
    H = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    Q, R = 0.02 * np.eye(3), np.array([[0.5, 0.1], [0.1, 0.8]])
    rng = make_rng(5)
    zs = np.cumsum(rng.normal(size=(2, 3, 40, 2)), axis=2)
    zs[0, 1, 10:13] = np.nan  # a coasting stretch in one sequence
    zs[1, 2, 30, 1] = np.nan  # one component missing: the whole row is absent
    x0, P0 = np.array([0.0, 1.0, 0.0]), 5.0 * np.eye(3)
    filt = KalmanFilter(F, H, Q, R)
    assert isinstance(filt, SequentialFilter)
    out = filt.run(zs, x0, P0)
    assert out.x.shape == (2, 3, 40, 3) and out.P.shape == (2, 3, 40, 3, 3) and out.nis.shape == (2, 3, 40)
    for i in range(2):
        for j in range(3):
            ref = _filterpy_history(F, H, Q, R, zs[i, j], x0, P0)
            for key, value in ref.items():
                assert np.allclose(getattr(out, key)[i, j], value, rtol=1e-9, atol=1e-9), (i, j, key)
    assert np.isnan(out.innovation[0, 1, 10:13]).all() and np.isnan(out.nis[1, 2, 30])
    assert np.array_equal(out.x[0, 1, 11], out.x_prior[0, 1, 11])  # absent: the prior is kept


def test_the_ekf_with_a_linear_observation_is_the_kalman_filter_of_filterpy():
    from tvtrack.filters.ekf import ExtendedKalmanFilter

    F, H, Q, R = cv_model(q=0.03, r=0.7)
    zs = np.cumsum(make_rng(6).normal(size=(4, 50, 1)), axis=1)
    zs[2, 5:9] = np.nan
    ekf = ExtendedKalmanFilter(
        F, Q, lambda x, k: x[..., :1], lambda x, k: np.broadcast_to(H, x.shape[:-1] + H.shape), R
    )
    out = ekf.run(zs, [0.0, 0.0], 10 * np.eye(2))
    for trial in range(4):
        ref = _filterpy_history(F, H, Q, R, zs[trial], [0.0, 0.0], 10 * np.eye(2))
        assert np.allclose(out.x[trial], ref["x"], rtol=1e-9, atol=1e-9)
        assert np.allclose(out.P_prior[trial], ref["P_prior"], rtol=1e-9, atol=1e-9)


def test_a_gain_schedule_in_the_interface_is_the_scheduled_filter_and_its_covariance():
    from tvtrack.filters.alphabeta import (
        GainScheduleFilter,
        error_covariance_sequence,
        gain_schedule,
        scheduled_filter,
    )

    T = 60
    gains = gain_schedule(2, 12, T)
    gains[30:35] = 0.0  # a coasting stretch (zero gains)
    z = np.cumsum(make_rng(7).normal(size=(2, 5, T)), axis=-1)
    x_before = np.array([1.0, 0.5, 0.0])
    filt = GainScheduleFilter(gains, sigma_eps=0.7)
    out = filt.run(z[..., None], filt.F @ x_before, np.zeros((3, 3)))
    assert np.allclose(out.x, scheduled_filter(z, gains, x0=x_before), rtol=1e-12, atol=1e-12)
    assert np.allclose(out.P[0, 0], error_covariance_sequence(gains, sigma_eps=0.7), rtol=1e-12, atol=1e-12)
    # the growing-memory start fits the first three samples exactly: position equals the third sample
    assert np.allclose(out.x[..., 2, 0], z[..., 2])


def test_a_filter_that_writes_only_its_two_steps_gets_the_batched_run():
    from tvtrack.filters import SequentialFilter

    class RandomWalk(SequentialFilter):
        """Scalar random walk, written as its textbook steps (independent of the library's update)."""

        def predict(self, x, P, k):
            return x, P + 0.1

        def update(self, x, P, z, k, mask=None):
            S = P + 1.0  # (..., 1, 1)
            K = P[..., 0] / S[..., 0]  # (..., 1)
            nu = z - x
            x_new, P_new = x + K * nu, ((1 - K) * P[..., 0])[..., None]
            if mask is not None:
                x_new = np.where(mask[..., None], x_new, x)
                P_new = np.where(mask[..., None, None], P_new, P)
            return x_new, P_new, nu, S

    zs = make_rng(8).normal(size=(3, 30, 1))
    zs[1, 4] = np.nan
    out = RandomWalk().run(zs, [0.0], [[2.0]])
    ref = KalmanFilter([[1.0]], [[1.0]], [[0.1]], [[1.0]]).run(zs, [0.0], [[2.0]])
    for key in ("x", "P", "x_prior", "P_prior", "nis"):
        assert np.allclose(getattr(out, key), getattr(ref, key), equal_nan=True, rtol=1e-12), key
