"""Notebook 004: the networks' lag count cross-validated on the training paths only."""

from dataclasses import replace

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction.beam_wander import BeamWanderConfig, generate_traces
from tvtrack.papers.p004_laser_spot_prediction.prediction_study import (
    ComparisonSetup,
    compare_methods,
    tune_learned_lags,
)
from tvtrack.papers.p004_laser_spot_prediction import learned

SETUP = ComparisonSetup(
    start=30,
    learned_lags=None,
    lag_grid=(1, 2, 4, 8),
    lag_tuning_samples=300,
    learned_kw=dict(hidden_units=4, rbf_centres=20, max_samples=300),
    floor_grid=(3, 10),
    window_grid=(4, 8),
    jerk_grid=(1e-4, 1e-2),
    meas_var_grid=(1e-2, 1.0),
    singer_tau_grid=(1.0, 10.0),
    singer_ratio_grid=(1e-2, 1e2),
)


def _z(seed, n_paths=6, T=300):
    tr = generate_traces(BeamWanderConfig(n_paths=n_paths, n_frames=T), seed)
    z = np.moveaxis(tr.centres_px, -1, -2)[None]
    return z + 0.1 * np.random.default_rng(seed).standard_normal(z.shape)


# The back-propagation network tries two lag counts, not four: a leak shows in every candidate's loss, so the
# check has the same power with two, at half the 48 network trainings (the cheap RBF network keeps the four).
@pytest.mark.parametrize("kind, grid", [("mlp", (2, 4)), ("rbf", (1, 2, 4, 8))])
def test_tuning_of_a_fold_never_sees_its_test_paths(kind, grid):
    """Replace fold i's test paths by other paths: fold i's tuning losses (and its chosen lag count) stay
    identical to the last bit, while the other folds' losses change (they do use those paths). A leak (a
    model trained on, or a score taken on, the fold's test paths) fails."""
    z = _z(1)
    folds = learned.path_folds(z.shape[1], 3)
    setup = replace(SETUP, lag_grid=grid)
    lags, loss = tune_learned_lags(kind, z, z, folds, setup, np.random.default_rng(7))
    assert loss.shape == (3, len(grid)) and np.all(np.isfinite(loss)) and set(lags) <= set(grid)
    other = _z(2)
    for i, (_, test) in enumerate(folds):
        z2 = z.copy()
        z2[:, test] = other[:, test] * 1.5
        lags2, loss2 = tune_learned_lags(kind, z2, z2, folds, setup, np.random.default_rng(7))
        np.testing.assert_array_equal(loss2[i], loss[i])
        assert lags2[i] == lags[i]
        assert not np.allclose(np.delete(loss2, i, axis=0), np.delete(loss, i, axis=0))


def test_lag_tuning_needs_three_folds_and_reaches_the_comparison():
    z = _z(3)
    with pytest.raises(ValueError, match="3 folds"):
        tune_learned_lags("rbf", z, z, learned.path_folds(6, 2), SETUP, np.random.default_rng(0))
    folds = learned.path_folds(6, 3)
    cmp = compare_methods(z, z, folds, SETUP, np.random.default_rng(0))
    for name in ("MLP back-prop", "RBF network"):
        assert cmp.chosen[name].shape == (3,) and set(cmp.chosen[name]) <= set(SETUP.lag_grid)
        assert [m.n_lags_ for m in cmp.learned_models["mlp" if name.startswith("MLP") else "rbf"]] == list(
            cmp.chosen[name]
        )
    fixed = compare_methods(z, z, folds, replace(SETUP, learned_lags=4), np.random.default_rng(0))
    assert "MLP back-prop" not in fixed.chosen and all(m.n_lags_ == 4 for m in fixed.learned_models["mlp"])
