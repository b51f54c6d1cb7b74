"""Paper 004: every baseline gets the same tuning effort.

- a window search starts at the baseline's degree + 1 (a line from 2 samples);
- the constant-acceleration Kalman filter's noise grid reaches past its optimum;
- the learned models never see a test path.
"""

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import prediction_study as ps
from tvtrack.papers.p004_laser_spot_prediction import kalman_baselines
from tvtrack.papers.p004_laser_spot_prediction import learned

SETUP = ps.ComparisonSetup(
    floor_grid=(3, 10),
    window_grid=(4, 8, 16),
    start=30,
    learned_kw=dict(hidden_units=4, rbf_centres=20, max_samples=600),
    jerk_grid=(1e-6, 1e-2),
    meas_var_grid=(1e-4, 1e-2),
    singer_tau_grid=(1.0, 10.0),
    singer_ratio_grid=(1e-2, 1e2),
)


def test_window_candidates_start_at_degree_plus_one():
    assert ps.window_candidates(2, (4, 6, 8)) == (2, 3, 4, 6, 8)
    assert ps.window_candidates(3, (4, 6, 8)) == (3, 4, 6, 8)
    assert ps.window_candidates(4, (2, 6)) == (4, 6)
    assert ps.MIN_WINDOW == {"cubic spline": 4, "linear regression deg 1": 2, "linear regression deg 2": 3}


def test_a_line_on_a_fast_clean_random_walk_chooses_two_samples():
    """A noiseless integrated random walk (white acceleration) is best extrapolated from the last two
    samples by a line, a noiseless triply integrated one (white jerk) from the last three by a quadratic:
    the cross-validated windows must be 2 and 3. A search that starts at 4 (the old grid) cannot find them."""
    rng = np.random.default_rng(4)
    w = rng.standard_normal((1, 6, 2, 300))
    z = 60 + np.cumsum(np.cumsum(w, axis=-1), axis=-1) * 0.05
    c = ps.compare_methods(z, z, learned.path_folds(6, 3), SETUP, np.random.default_rng(1), learned=False)
    assert set(c.chosen["linear regression deg 1"]) == {2}
    np.testing.assert_array_equal(c.mse["linear regression deg 1"], c.mse["finite differences, 2 points"])
    z3 = 60 + np.cumsum(np.cumsum(np.cumsum(w, axis=-1), axis=-1), axis=-1) * 1e-3
    c3 = ps.compare_methods(z3, z3, learned.path_folds(6, 3), SETUP, np.random.default_rng(1), learned=False)
    assert set(c3.chosen["linear regression deg 2"]) == {3}


def test_grid_edges():
    np.testing.assert_array_equal(ps.grid_edges([1e-4, 1e-2, 1.0], (1e-4, 1e-2, 1.0)), [-1, 0, 1])


def test_ca_kalman_noise_fit_is_inside_the_default_grid_at_large_jitter():
    """White measurement noise of 2 px RMS (4 px^2, the size of 4x jitter): the maximum-likelihood
    measurement variance must be found near 4 px^2, not at a grid edge (the old grid stopped at 1)."""
    rng = np.random.default_rng(5)
    t = np.arange(400)
    truth = 60 + 5 * np.sin(2 * np.pi * t / 300)[None] + np.zeros((6, 1))
    z = truth + 2.0 * rng.standard_normal(truth.shape)
    s = ps.ComparisonSetup()
    (q, r), _ = kalman_baselines.fit_constant_acceleration(z, s.jerk_grid, s.meas_var_grid)
    assert ps.grid_edges([r], s.meas_var_grid)[0] == 0
    assert 1.0 < r < 20.0


def test_learned_models_never_train_on_their_test_paths(monkeypatch):
    """Each fold's MLP/RBF network is trained on the training paths of its fold only (planted bug:
    the networks trained on the test paths too)."""
    seen = []
    real = learned.fit_learned_predictor

    def spy(kind, z_train, *args, **kw):
        seen.append(np.array(z_train, copy=True))
        return real(kind, z_train, *args, **kw)

    monkeypatch.setattr(learned, "fit_learned_predictor", spy)
    rng = np.random.default_rng(6)
    z = 60 + np.cumsum(rng.standard_normal((1, 6, 2, 120)), axis=-1) * 0.1
    z += np.arange(6)[None, :, None, None] * 1000.0  # every path identifiable by its level
    folds = learned.path_folds(6, 3)
    models = ps.fit_learned_folds("mlp", z, folds, SETUP, np.random.default_rng(0))
    assert len(models) == len(seen) == len(folds)
    for z_train, (train, test) in zip(seen, folds):
        levels = set(np.round(np.asarray(z_train)[..., 0].ravel() / 1000.0).astype(int))
        assert levels == set(train.tolist()) and not levels & set(test.tolist())


@pytest.mark.parametrize("n_paths, n_folds", [(6, 3), (9, 3), (15, 3), (15, 5)])
def test_folds_partition_the_paths(n_paths, n_folds):
    folds = learned.path_folds(n_paths, n_folds)
    tests = np.concatenate([t for _, t in folds])
    assert sorted(tests.tolist()) == list(range(n_paths))
    for train, test in folds:
        assert not set(train.tolist()) & set(test.tolist())
        assert sorted(np.concatenate([train, test]).tolist()) == list(range(n_paths))


def test_a_tuning_grid_is_extended_until_the_folds_leave_its_top():
    """The floor's grid reaches the paper filter's optimum (at horizon 10 the old grid's top, 200, was picked):
    while a fold picks the last candidate the next extension value is tried, and only then."""
    z = np.zeros((2, 6, 2, 60))
    folds = learned.path_folds(6, 3)
    made = []

    def make(c):  # a forecast whose error is |c - 5| everywhere: the optimum is 5
        made.append(c)
        return np.full(z.shape, abs(c - 5.0))

    _, _, chosen, _, _ = ps.tuned_forecast((1, 2, 3), make, z, z, folds, SETUP, more=(4, 5, 6, 7))
    assert np.all(chosen == 5) and made == [1, 2, 3, 4, 5, 6]  # 7 is never needed
    made.clear()
    _, _, chosen, _, _ = ps.tuned_forecast((4, 5, 6), make, z, z, folds, SETUP, more=(7,))
    assert np.all(chosen == 5) and made == [4, 5, 6]  # an interior optimum extends nothing
    _, _, chosen, _, _ = ps.tuned_forecast((1, 2, 3), make, z, z, folds, SETUP)
    assert np.all(chosen == 3)  # without an extension the top stays the grid's limit (reported as an edge)


def test_windowed_baselines_search_past_the_window_grid_like_the_filter(monkeypatch):
    """The card, C004-3: "Implement the baselines (§8) on identical data, horizon and metric" -- with the same tuning
    effort: the spline's and the regressions' windows, like the paper filter's floor, are searched past the grid
    (:data:`~.prediction_study.WINDOW_EXTENSION`) while a fold picks its top, so none stays at the grid's limit."""
    asked = []
    tuned = ps.tuned_forecast

    def spy(candidates, make, z, ref, folds, s, more=()):
        asked.append((tuple(candidates), tuple(more)))
        return tuned(candidates, make, z, ref, folds, s, more=more)

    monkeypatch.setattr(ps, "tuned_forecast", spy)
    rng = np.random.default_rng(1)
    t = np.arange(150)
    z = 50.0 + rng.uniform(-0.3, 0.3, (1, 4, 2, 1)) * t + rng.standard_normal((1, 4, 2, 150))  # noisy lines
    s = ps.ComparisonSetup(floor_grid=(3, 10), window_grid=(4,), start=30)
    cmp = ps.compare_methods(z, z, learned.path_folds(4, 4), s, rng, parts={"classical"})
    for name, lowest in ps.MIN_WINDOW.items():
        assert (ps.window_candidates(lowest, s.window_grid), ps.WINDOW_EXTENSION) in asked, name
    # a line through noisy samples errs least on the longest window: the search leaves the one-value grid
    assert np.all(cmp.chosen["linear regression deg 1"] > max(s.window_grid))
