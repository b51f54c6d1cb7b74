"""Notebook 004: baseline predictors (exactness on polynomials, Kalman equivalences, learned models)."""

import pickle

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import predictors as pr
from tvtrack.filters.polynomial import growing_memory_filter, predict_ahead
from tvtrack.papers.p004_laser_spot_prediction import kalman_baselines
from tvtrack.papers.p004_laser_spot_prediction import learned


def test_forecast_errors_alignment():
    f = np.arange(10.0)
    e = pr.forecast_errors(f, np.arange(10.0) + 100, 2)
    assert np.all(np.isnan(e[:2]))
    np.testing.assert_allclose(e[2:], f[:-2] - (np.arange(2, 10) + 100))


@pytest.mark.parametrize("degree, window", [(1, 2), (2, 3), (2, 8), (3, 9)])
def test_sliding_regression_exact_on_polynomials(degree, window):
    t = np.arange(60.0)
    z = 1 + 0.3 * t - 0.02 * t**2 * (degree >= 2) + 1e-4 * t**3 * (degree >= 3)
    for steps in (1, 4):
        f = pr.sliding_regression_forecast(z, window, degree, steps)
        # exact from the first degree + 1 samples on: before its window's worth a fit uses all there are
        np.testing.assert_allclose(f[degree:-steps], z[degree + steps :], atol=1e-8)
        assert np.all(np.isnan(f[:degree]))


def test_finite_difference_formula():
    z = np.array([0.0, 1.0, 4.0, 2.0])
    np.testing.assert_allclose(pr.sliding_regression_forecast(z, 2, 1, 1)[1:], 2 * z[1:] - z[:-1], atol=1e-12)
    np.testing.assert_allclose(
        pr.sliding_regression_forecast(z, 3, 2, 1)[2:], 3 * z[2:] - 3 * z[1:-1] + z[:-2], atol=1e-12
    )


def test_spline_extrapolation_exact_on_cubics_and_batched():
    t = np.arange(40.0)
    z = np.stack([2 - t + 0.01 * t**3, 5 + 0.5 * t])
    f = pr.spline_forecast(z, 6, 2)
    np.testing.assert_allclose(f[:, 5:-2], z[:, 7:], rtol=1e-9)


def test_ca_kalman_without_process_noise_equals_growing_memory():
    """Equivalent form (derived here): zero process noise + diffuse prior = growing-memory LS."""
    rng = np.random.default_rng(0)
    z = np.cumsum(rng.normal(0, 1, (2, 60)), axis=-1)
    F, Q, H, R = kalman_baselines.constant_acceleration_model(0.0, 1.0)
    # prior 1e10: diffuse enough that its weight is negligible, small enough that the Joseph update
    # (core, any gain) does not lose the digits a 1e12 prior costs it (2.8e-5 px there, 4e-8 px here)
    f_kf, _ = kalman_baselines.kalman_forecast(z, F, Q, H, R, np.zeros(3), np.diag([1e10, 1e8, 1e6]), 1)
    f_gm = predict_ahead(growing_memory_filter(z, 2, None), 1)
    np.testing.assert_allclose(f_kf[:, 5:], f_gm[:, 5:], atol=1e-6)


def test_kalman_forecast_matches_filterpy():
    filterpy = pytest.importorskip("filterpy.kalman")
    rng = np.random.default_rng(1)
    z = np.cumsum(rng.normal(0, 1, 40))
    F, Q, H, R = kalman_baselines.constant_acceleration_model(0.05, 0.3)
    x0, P0 = np.zeros(3), np.diag([100.0, 10.0, 1.0])
    ours, ll = kalman_baselines.kalman_forecast(z, F, Q, H, R, x0, P0, 2)
    kf = filterpy.KalmanFilter(dim_x=3, dim_z=1)
    kf.x, kf.P, kf.F, kf.Q, kf.H, kf.R = x0.copy(), P0.copy(), F, Q, H, R
    ref, ll_ref = [], 0.0
    for t, zt in enumerate(z):
        if t > 0:
            kf.predict()
        kf.update(np.array([zt]))
        ll_ref += kf.log_likelihood
        ref.append((H @ np.linalg.matrix_power(F, 2) @ kf.x)[0])
    np.testing.assert_allclose(ours, ref, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(ll, ll_ref, rtol=1e-9)


def test_ml_fit_recovers_noise_levels_roughly():
    """White-jerk data with known q, r: the grid maximum lands on the true cell or a neighbour."""
    rng = np.random.default_rng(3)
    q_true, r_true, T = 1e-2, 0.25, 600
    F, Q, H, R = kalman_baselines.constant_acceleration_model(q_true, r_true)
    L = np.linalg.cholesky(Q)
    x = np.zeros((6, 3))
    zs = []
    for _ in range(T):
        x = x @ F.T + rng.standard_normal((6, 3)) @ L.T
        zs.append(x[:, 0] + np.sqrt(r_true) * rng.standard_normal(6))
    z = np.stack(zs, axis=-1)
    grid_q, grid_r = np.logspace(-4, 0, 9), np.logspace(-2, 0, 5)
    (q, r), ll = kalman_baselines.fit_constant_acceleration(z, grid_q, grid_r)
    assert ll.shape == (9, 5)
    assert abs(np.log10(q / q_true)) <= 0.51 and abs(np.log10(r / r_true)) <= 0.51


@pytest.mark.parametrize("kind", ["mlp", "rbf"])
def test_learned_predictors_beat_last_value_on_smooth_series(kind):
    rng = np.random.default_rng(4)
    t = np.arange(400)
    phases = rng.uniform(0, 2 * np.pi, (6, 1))
    z = 10 * np.sin(2 * np.pi * t / 60 + phases) + rng.normal(0, 0.01, (6, 400))
    model = learned.fit_learned_predictor(kind, z[:4], 5, 1, hidden_units=8, rbf_centres=50, seed=0)
    f = learned.learned_forecast(model, z[4:])
    e = pr.forecast_errors(f, z[4:], 1)[:, 10:]
    naive = np.diff(z[4:], axis=-1)[:, 9:]
    assert np.sqrt(np.nanmean(e**2)) < 0.3 * np.sqrt(np.mean(naive**2))


def test_lag_features_and_folds():
    z = np.arange(10.0) ** 2
    X, y = learned.lag_features(z, 3, 2)
    np.testing.assert_allclose(X[5], [16 - 25, 9 - 25, 4 - 25])
    assert y[5] == 49 - 25 and np.isnan(y[-1]) and np.all(np.isnan(X[:3]))
    folds = learned.path_folds(15, 3)
    assert sorted(np.concatenate([te for _, te in folds]).tolist()) == list(range(15))
    assert all(np.intersect1d(tr, te).size == 0 for tr, te in folds)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: pr.sliding_regression_forecast(np.arange(10.0), 2, 2), "window"),
        (lambda: pr.spline_forecast(np.arange(10.0), 3), "window"),
        (lambda: pr.growing_memory_forecast(np.arange(10.0), 0), "steps"),
        (lambda: learned.fit_learned_predictor("svm", np.zeros((2, 50)), 3), "kind"),
        (lambda: learned.path_folds(3, 5), "n_folds"),
    ],
)
def test_bad_arguments_name_the_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_hold_last_fills_gaps_forward_and_leading_gaps_backward():
    z = np.array([[np.nan, 1.0, np.nan, np.nan, 4.0, np.nan], [np.nan] * 6])
    out = pr.hold_last(z)
    np.testing.assert_array_equal(out[0], [1.0, 1.0, 1.0, 1.0, 4.0, 4.0])
    assert np.all(np.isnan(out[1]))


def test_constant_acceleration_forecast_uses_each_folds_fit_on_its_test_paths():
    rng = np.random.default_rng(3)
    z = np.cumsum(np.cumsum(rng.normal(0, 0.05, (2, 6, 80)), -1), -1) + rng.normal(0, 0.1, (2, 6, 80))
    folds = learned.path_folds(6, 2)
    fits = [(1e-3, 1e-2), (1e-1, 1e-3)]
    out = kalman_baselines.constant_acceleration_forecast(z, fits, folds, 2)
    for (q, r), (_, test) in zip(fits, folds):
        F, Q, H, R = kalman_baselines.constant_acceleration_model(q, r)
        ref = kalman_baselines.kalman_forecast(z[:, test], F, Q, H, R, np.zeros(3), np.diag([1e4, 1e2, 1e1]), 2)[0]
        np.testing.assert_array_equal(out[:, test], ref)
    fitted = kalman_baselines.fit_constant_acceleration_folds(z[0], folds, [1e-4, 1e-2], [1e-2, 1e-1])
    assert len(fitted) == 2 and all(q in (1e-4, 1e-2) and r in (1e-2, 1e-1) for q, r in fitted)


def test_cross_validated_pick_never_uses_the_test_path():
    from tvtrack.papers.p004_laser_spot_prediction.learned import cross_validated_pick, path_folds

    # candidate 1 is best on paths 0-3, candidate 0 on paths 4-5; a fold picks from its training paths only,
    # so paths 0-3 get candidate 0 (their training sets include 4-5) and paths 4-5 get candidate 1
    loss = np.array([[2.0, 2, 2, 2, 0, 0], [1.0, 1, 1, 1, 9, 9]])
    folds = path_folds(6, 3)  # tests {0,1}, {2,3}, {4,5}
    np.testing.assert_array_equal(cross_validated_pick(loss, folds), [0, 0, 0, 0, 1, 1])


def test_fading_memory_filter_is_the_discounted_least_squares_quadratic():
    """Morrison's gains give, after the start-up has faded, the quadratic that minimises
    sum_j theta^j (z_{n-j} - h_j X)^2 (checked against numpy lstsq on the last 400 samples)."""
    from tvtrack.papers.p004_laser_spot_prediction.predictors import fading_memory_forecast

    theta, T = 0.8, 600
    z = np.cumsum(np.random.default_rng(4).standard_normal(T))
    fc = fading_memory_forecast(z, theta, 1)
    lags = np.arange(400.0)
    H = np.stack([np.ones_like(lags), -lags, lags**2 / 2], axis=1)
    w = np.sqrt(theta**lags)
    X = np.linalg.lstsq(H * w[:, None], z[::-1][:400] * w, rcond=None)[0]
    np.testing.assert_allclose(fc[-1], X[0] + X[1] + X[2] / 2, rtol=1e-9)


def test_singer_model_is_the_exact_discretisation_and_batches():
    """F = expm(A) and Q = 2 accel_var / tau * int_0^1 e^{As} G G^T e^{A^T s} ds (adaptive quadrature,
    independent of the library's closed form and Van Loan branches) over short to long tau."""
    from scipy.integrate import quad_vec
    from scipy.linalg import expm

    taus, s2 = np.array([0.01, 0.3, 3.0, 10.0, 30.0, 1000.0, 1e5]), 0.2
    F, Q, H, R = kalman_baselines.singer_model(taus, s2, 0.01)
    assert F.shape == Q.shape == (7, 3, 3) and R.shape == (1, 1)
    for i, tau in enumerate(taus):
        A = np.array([[0, 1, 0], [0, 0, 1], [0, 0, -1 / tau]])
        Q_ref = quad_vec(lambda s, A=A: np.outer(*(2 * [expm(A * s)[:, 2]])), 0, 1, epsabs=0, epsrel=1e-12)[0]
        np.testing.assert_allclose(F[i], expm(A), rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(Q[i], 2 * s2 / tau * Q_ref, rtol=1e-9)
    np.testing.assert_allclose(Q[:, 2, 2], s2 * -np.expm1(-2 / taus), rtol=1e-12)  # stationary acceleration variance


def test_singer_model_tends_to_white_jerk_for_long_correlation_times():
    """tau -> inf with 2 accel_var / tau = q fixed: the constant-acceleration white-jerk model."""
    q, tau = 0.03, 1e5
    F, Q, _, _ = kalman_baselines.singer_model(tau, q * tau / 2, 1.0)
    F_ca, Q_ca, _, _ = kalman_baselines.constant_acceleration_model(q, 1.0)
    np.testing.assert_allclose(F, F_ca, atol=1e-4)
    np.testing.assert_allclose(Q, Q_ca, rtol=1e-4)


def _simulate_singer(tau, accel_var, meas_var, n_series, T, rng):
    F, Q, _, _ = kalman_baselines.singer_model(tau, accel_var, meas_var)
    L = np.linalg.cholesky(Q)
    x = np.zeros((n_series, 3))
    x[:, 2] = np.sqrt(accel_var) * rng.standard_normal(n_series)
    zs = []
    for _ in range(T):
        x = x @ F.T + rng.standard_normal((n_series, 3)) @ L.T
        zs.append(x[:, 0] + np.sqrt(meas_var) * rng.standard_normal(n_series))
    return np.stack(zs, axis=-1)


def test_singer_ml_fit_recovers_parameters_and_its_likelihood_is_the_full_one():
    """Simulated Singer data: the grid maximum is the true tau (or a neighbour), the variances
    within 30 %; the concentrated log-likelihood at the maximum equals the full likelihood of
    :func:`kalman_forecast` with the fitted (tau, accel_var, meas_var) and the scaled prior."""
    rng = np.random.default_rng(11)
    tau, s2, r = 5.0, 0.01, 0.04
    z = _simulate_singer(tau, s2, r, 8, 800, rng)
    tau_grid, ratio_grid = np.array([1.0, 2.5, 5.0, 10.0, 20.0]), np.logspace(-2, 1, 13)
    (tau_f, s2_f, r_f), ll = kalman_baselines.fit_singer(z, tau_grid, ratio_grid)
    assert ll.shape == (5, 13)
    assert tau_f in (2.5, 5.0, 10.0)
    assert abs(s2_f / s2 - 1) < 0.3 and abs(r_f / r - 1) < 0.3
    F, Q, H, R = kalman_baselines.singer_model(tau_f, s2_f, r_f)
    _, ll_full = kalman_baselines.kalman_forecast(
        z, F, Q, H, R, np.zeros(3), r_f * np.diag([1e4, 1e2, 1e1]), burn_in=10
    )
    assert ll_full.sum() == pytest.approx(ll.max(), rel=1e-10)


def test_singer_forecast_uses_each_folds_fit_and_beats_constant_acceleration_on_singer_data():
    rng = np.random.default_rng(12)
    z = _simulate_singer(2.0, 0.05, 0.01, 12, 500, rng).reshape(2, 6, 500)
    folds = learned.path_folds(6, 2)
    fits = kalman_baselines.fit_singer_folds(z[0], folds, [0.5, 2.0, 8.0], np.logspace(-1, 2, 7))
    out = kalman_baselines.singer_forecast(z, fits, folds, 1)
    for (tau, s2, r), (_, test) in zip(fits, folds):
        F, Q, H, R = kalman_baselines.singer_model(tau, s2, r)
        ref = kalman_baselines.kalman_forecast(z[:, test], F, Q, H, R, np.zeros(3), r * np.diag([1e4, 1e2, 1e1]), 1)[0]
        np.testing.assert_array_equal(out[:, test], ref)
    ca = kalman_baselines.constant_acceleration_forecast(
        z,
        kalman_baselines.fit_constant_acceleration_folds(z[0], folds, np.logspace(-5, 0, 11), np.logspace(-3, 0, 7)),
        folds,
        1,
    )
    mse = lambda f: np.mean(pr.forecast_errors(f, z, 1)[..., 20:-1] ** 2)
    assert mse(out) < mse(ca)


def test_absolute_centre_inputs_are_the_last_centres_and_the_target_the_next():
    # the third adversarial pass's reading of what the networks are fed ("network inputs" = absolute centres)
    from tvtrack.papers.p004_laser_spot_prediction.learned import fit_learned_predictor, lag_features, learned_forecast

    z = np.arange(10.0)
    X, y = lag_features(z, 3, inputs="absolute centres")
    assert np.isnan(X[1]).all() and X[2].tolist() == [2.0, 1.0, 0.0] and X[9].tolist() == [9.0, 8.0, 7.0]
    assert y[2] == 3.0 and np.isnan(y[9])
    with pytest.raises(ValueError, match="inputs"):
        lag_features(z, 3, inputs="pixels")
    rng = np.random.default_rng(0)
    paths = np.cumsum(rng.normal(0, 0.2, (4, 400)), axis=1) + 60.0  # a slow walk about the field's middle
    model = fit_learned_predictor("rbf", paths, 4, inputs="absolute centres", max_samples=1500)
    f = learned_forecast(model, paths[:1])
    err = (f[0, 3:-1] - paths[0, 4:]).std()
    assert model.inputs_ == "absolute centres" and err < 0.4  # the next centre, not an increment (~60 px off)


@pytest.mark.parametrize("inputs", ["increments", "absolute centres"])
def test_the_early_stopped_network_is_scikit_learns_bit_for_bit(inputs, monkeypatch):
    """The network's early-stopping score skips scikit-learn's input checks and its training loop indexes the
    arrays directly (``learned._adam_epochs``): every epoch's validation score, the epoch it stops at and the
    weights it keeps are those of ``MLPRegressor`` itself, to the last bit (300 pairs: two mini-batches an epoch)."""
    from sklearn.metrics import r2_score
    from sklearn.neural_network import MLPRegressor

    from tvtrack.papers.p004_laser_spot_prediction import learned

    epochs_run = []
    plain_loop = learned._adam_epochs
    monkeypatch.setattr(learned, "_adam_epochs", lambda *a: epochs_run.append(1) or plain_loop(*a))
    z = np.cumsum(np.random.default_rng(3).standard_normal((4, 2, 300)), axis=-1)
    for seed in range(3):
        fast = learned.fit_learned_predictor("mlp", z, 3, seed=seed, hidden_units=4, max_samples=300, inputs=inputs)
        assert len(epochs_run) == seed + 1  # the lean loop trained it
        with monkeypatch.context() as m:
            m.setattr(learned, "_mlp_regressor", lambda: MLPRegressor)
            stock = learned.fit_learned_predictor(
                "mlp", z, 3, seed=seed, hidden_units=4, max_samples=300, inputs=inputs
            )
        a, b = (getattr(p, "regressor_", p)[-1] for p in (fast, stock))
        assert type(a) is not MLPRegressor and type(b) is MLPRegressor
        assert a.n_iter_ == b.n_iter_ > 10 and a.validation_scores_ == b.validation_scores_
        for u, v in zip(a.coefs_ + a.intercepts_, b.coefs_ + b.intercepts_):
            assert np.array_equal(u, v)
    rng = np.random.default_rng(4)
    for y, p in (
        (rng.standard_normal(37), rng.standard_normal(37)),
        (np.full(5, 2.0), np.full(5, 2.0)),  # a perfect forecast of a constant: 1
        (np.full(5, 2.0), np.full(5, 2.5)),  # a constant missed: 0, not -inf
        (np.arange(4.0), np.arange(4.0)),
    ):
        assert learned._r2(y[:, None], p) == r2_score(y[:, None], p)
    assert np.isnan(learned._r2(np.ones(1), np.ones(1)))
    back = pickle.loads(pickle.dumps(fast))  # a model pickled in one process is read in another by the class's name
    assert type(getattr(back, "regressor_", back)[-1]) is type(a)


@pytest.mark.parametrize("name", ["regression 1", "regression 2", "spline", "natural spline"])
def test_a_window_longer_than_the_samples_so_far_fits_all_of_them(name):
    """Before ``window`` samples a windowed baseline fits every sample there is (its shortest window first): at
    frame t < window - 1 it is the same fit on t + 1 samples; from window - 1 on, the sliding fit, unchanged."""
    from tvtrack.papers.p004_laser_spot_prediction import predictors as pr

    make = {
        "regression 1": (lambda z, L: pr.sliding_regression_forecast(z, L, 1, 2), 2),
        "regression 2": (lambda z, L: pr.sliding_regression_forecast(z, L, 2, 2), 3),
        "spline": (lambda z, L: pr.spline_forecast(z, L, 2), 4),
        "natural spline": (lambda z, L: pr.natural_spline_forecast(z, L, 2), 4),
    }
    f, shortest = make[name]
    z = np.random.default_rng(8).normal(size=(2, 3, 2, 60)).cumsum(axis=-1)
    long_ = f(z, 30)
    assert np.isnan(long_[..., : shortest - 1]).all() and np.isfinite(long_[..., shortest - 1 :]).all()
    for t in (shortest - 1, 10, 28):
        np.testing.assert_allclose(long_[..., t], f(z[..., : t + 1], t + 1)[..., t], rtol=1e-10, atol=1e-10)
    tail = f(z, 30)[..., 29:]
    np.testing.assert_allclose(tail, f(z[..., :], 30)[..., 29:], rtol=0, atol=0)
    # a straight line (regression) or a cubic (splines) through the samples so far is extrapolated exactly
    t = np.arange(60, dtype=float)
    exact = {"regression 1": 3 + 0.5 * t, "regression 2": 1 + 0.1 * t**2}.get(name, 2 - t + 0.01 * t**3)
    got = f(np.broadcast_to(exact, (1, 1, 1, 60)).copy(), 30)[0, 0, 0]
    want = {"regression 1": 3 + 0.5 * (t + 2), "regression 2": 1 + 0.1 * (t + 2) ** 2}.get(
        name, 2 - (t + 2) + 0.01 * (t + 2) ** 3
    )
    if name != "natural spline":  # the natural spline is not exact for a cubic (zero curvature at its ends)
        np.testing.assert_allclose(got[shortest - 1 : 58], want[shortest - 1 : 58], rtol=1e-8, atol=1e-8)


@pytest.mark.parametrize("theta", [0.3, 0.8, 0.95])
def test_the_fading_memory_is_started_by_the_expanding_memory_until_its_gains_fall_to_the_fading_ones(theta):
    """Morrison's start: the growing (expanding) memory, whose position gain for order 2 is
    3 (3N^2 - 3N + 2) / (N (N + 1) (N + 2)), runs until that gain is at most the fading one, 1 - theta^3; the
    forecasts up to there are the growing memory's, and the fixed fading gains run from there on."""
    from tvtrack.filters.polynomial import growing_memory_filter

    g1 = [3 * (3 * N * N - 3 * N + 2) / (N * (N + 1) * (N + 2)) for N in range(3, 400)]
    want = next(N for N, g in zip(range(3, 400), g1) if g <= 1 - theta**3)
    assert pr.fading_switch(theta, 400) == want
    assert want == {0.3: 4, 0.8: 15, 0.95: 60}[theta]
    assert pr.fading_switch(0.999, 50) == 50  # never reached: the growing memory throughout
    z = np.random.default_rng(2).normal(size=(3, 200)).cumsum(axis=-1)
    f = pr.fading_memory_forecast(z, theta, 2)
    grow = pr.predict_ahead(growing_memory_filter(z, 2, None), 2)
    np.testing.assert_allclose(f[..., 2:want], grow[..., 2:want], rtol=1e-12, atol=1e-12)
    assert not np.allclose(f[..., want + 5 :], grow[..., want + 5 :])
    # from the switch on: x <- F x; x <- x + g (z - x), g the fading gains, from the growing memory's state
    x = growing_memory_filter(z[..., :want], 2, None)[..., -1, :]
    F = np.array([[1.0, 1.0, 0.5], [0.0, 1.0, 1.0], [0.0, 0.0, 1.0]])
    g = pr.fading_memory_gains(theta)
    for t in range(want, want + 30):
        x = x @ F.T
        x = x + g * (z[..., t] - x[..., 0])[..., None]
        np.testing.assert_allclose(f[..., t], x[..., 0] + 2 * x[..., 1] + 2 * x[..., 2], rtol=1e-9, atol=1e-9)
