"""Notebook 004: the symmetric (cross-validated) comparison of the paper's filter and its baselines."""

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import predictors as pr
from tvtrack.papers.p004_laser_spot_prediction.prediction_study import (
    CLASSICAL,
    FADING,
    FITTED,
    PAPER,
    VARIANT,
    ComparisonSetup,
    compare_methods,
    per_trial_path_mse,
)
from tvtrack.papers.p004_laser_spot_prediction import learned

SETUP = ComparisonSetup(
    floor_grid=(3, 5, 10, 30),
    window_grid=(4, 8, 16),
    start=30,
    learned_kw=dict(hidden_units=4, rbf_centres=20, max_samples=600),
    jerk_grid=(1e-6, 1e-4, 1e-2),
    meas_var_grid=(1e-4, 1e-2),
    singer_tau_grid=(1.0, 10.0),
    singer_ratio_grid=(1e-2, 1e2),
)


def _series(n_paths=6, T=200, noise=0.0, seed=0):
    rng = np.random.default_rng(seed)
    t = np.arange(T)
    a = rng.uniform(-1e-3, 1e-3, (n_paths, 2, 1))
    v = rng.uniform(-0.3, 0.3, (n_paths, 2, 1))
    z = (60.0 + v * t + a * t**2)[None]
    return z + noise * rng.standard_normal(z.shape)


def test_polynomial_methods_are_exact_on_noiseless_quadratics():
    """Exact quadratics: the growing-memory filter (any floor), 3-point differences and degree-2
    regression predict without error; the MSE helper agrees with a direct computation."""
    z = _series()
    c = compare_methods(z, z, learned.path_folds(6, 3), SETUP, np.random.default_rng(1), learned=False)
    for name in (PAPER, FADING, "finite differences, 3 points", "linear regression deg 2"):
        assert np.max(c.mse[name]) < 1e-16, name
        assert np.max(c.mse_fixed[name]) < 1e-16, name
    assert np.min(c.mse["finite differences, 2 points"]) > 0  # a line misses the curvature
    fc = pr.sliding_regression_forecast(z, 2, 1, 1)
    e = fc[..., 30:-1] - z[..., 31:]
    np.testing.assert_allclose(per_trial_path_mse(fc, z, 1, 31), np.mean(e**2, axis=(-1, -2)), rtol=1e-12)


def test_a_path_never_tunes_its_own_setting():
    """Changing one path's data changes the settings chosen for the *other* folds' paths only."""
    z = _series(noise=0.05, seed=3)
    folds = learned.path_folds(6, 3)
    a = compare_methods(z, z, folds, SETUP, np.random.default_rng(1), learned=False)
    z2 = z.copy()
    z2[:, 0] += 3.0 * np.random.default_rng(9).standard_normal(z2[:, 0].shape)  # path 0 becomes very noisy
    b = compare_methods(z2, z2, folds, SETUP, np.random.default_rng(1), learned=False)
    for name in (PAPER, "cubic spline", "linear regression deg 1", "linear regression deg 2"):
        np.testing.assert_array_equal(a.chosen[name][:2], b.chosen[name][:2])  # path 0's own fold is {0, 1}
    assert b.chosen[PAPER][2:].max() >= a.chosen[PAPER][2:].max()  # a noisy training path asks for a longer floor


@pytest.mark.slow
def test_learned_models_train_on_other_paths_and_can_be_reused():
    z = _series(noise=0.02, seed=5)
    folds = learned.path_folds(6, 3)
    c = compare_methods(z, z, folds, SETUP, np.random.default_rng(2))
    assert set(c.mse) == {PAPER, VARIANT, FADING, *CLASSICAL, *FITTED}
    again = compare_methods(z, z, folds, SETUP, np.random.default_rng(7), learned_models=c.learned_models)
    for name in ("MLP back-prop", "RBF network"):
        np.testing.assert_array_equal(again.mse[name], c.mse[name])  # the given models, not retrained
        assert np.all(np.isfinite(c.mse[name]))
