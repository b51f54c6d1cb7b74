"""004's method comparison (prediction_study.py): every comparator tuned and scored the same way.

Each tuned method's setting is chosen per fold on the fold's training paths only (trials pooled), over its stated
grid (a windowed baseline from its degree + 1), the grid extended while a fold picks its top value; every method is
scored against the same reference, at the same horizon, from the same first frame; the networks' lag counts are
chosen on training paths only and the networks are trained on training paths only; the Kalman filters are fitted on
the first trial of the training paths; and each part's numbers are the same whichever other parts run.

The series are tiny synthetic ones; where an inner fit is expensive it is replaced by a recorder, and the expected
choices and scores are computed here, independently of the module.
"""

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import kalman_baselines as kb
from tvtrack.papers.p004_laser_spot_prediction import learned as lm
from tvtrack.papers.p004_laser_spot_prediction import predictors as pr
from tvtrack.papers.p004_laser_spot_prediction import prediction_study as ps

FOLDS = lm.path_folds(6, 3)  # test groups {0, 1}, {2, 3}, {4, 5}
BIG = 1e3  # forecast value on frames that must not be scored


def mse_here(forecast, reference, steps, start):
    """Mean square of ``forecast[n] - reference[n + steps]`` over frames ``n + steps >= start``, both axes."""
    f = np.asarray(forecast, dtype=float)
    r = np.broadcast_to(np.asarray(reference, dtype=float), f.shape)
    e = f[..., start - steps : f.shape[-1] - steps] - r[..., start:]
    return np.nanmean(e.reshape(e.shape[0], e.shape[1], -1) ** 2, axis=-1)


def planted(reference, amp, steps, start, seed):
    """A forecast whose score against ``reference`` is exactly ``amp**2`` per (trial, path) at ``steps`` and
    ``start``: the reference ``steps`` ahead plus ``+-amp``, and ``BIG`` on every frame that must not be scored."""
    r = np.asarray(reference, dtype=float)
    T = r.shape[-1]
    u = np.random.default_rng(seed).choice([-1.0, 1.0], size=r.shape)
    f = np.full(r.shape, BIG)
    f[..., start - steps : T - steps] = r[..., start:] + np.asarray(amp)[..., None, None] * u[..., start:]
    return f


def pick_here(loss, folds):
    """Index of each fold's choice: the smallest mean loss over its training paths; ``loss`` (C, P)."""
    return np.array([int(np.argmin(loss[:, train].mean(axis=1))) for train, _ in folds])


def per_path(fold_choice, folds, P):
    out = np.empty(P, dtype=np.asarray(fold_choice).dtype)
    for value, (_, test) in zip(fold_choice, folds):
        out[test] = value
    return out


# -- window_candidates, grid_edges --------------------------------------------------------------------------------
def test_window_candidates_run_from_the_degree_plus_one_through_the_grid():
    assert ps.window_candidates(2, (4, 6, 8)) == (2, 3, 4, 6, 8)
    assert ps.window_candidates(4, (8, 6)) == (4, 5, 6, 8)  # an unsorted grid: its smallest value counts
    assert ps.window_candidates(4, (4, 6)) == (4, 6)
    assert ps.window_candidates(5, (3, 4, 8, 6)) == (5, 6, 8)  # values below the degree + 1 dropped
    assert ps.window_candidates(3, (3,)) == (3,)
    got = ps.window_candidates(2.0, (4.0, 7.0))
    assert got == (2, 3, 4, 7) and all(type(w) is int for w in got)


def test_grid_edges_mark_the_lowest_and_highest_values():
    np.testing.assert_array_equal(ps.grid_edges([1, 5, 3, 2, 1 + 1e-12, 5 - 1e-12], (5, 1, 3)), [-1, 1, 0, 0, -1, 1])
    np.testing.assert_array_equal(ps.grid_edges([[0.1, 0.2], [10.0, 1.0]], (0.1, 1.0, 10.0)), [[-1, 0], [1, 0]])
    np.testing.assert_array_equal(ps.grid_edges([1.5, 4.0], (1.0, 2.0, 4.0)), [0, 1])


# -- tuned_forecast -----------------------------------------------------------------------------------------------
TARGET = np.array([5.0, 5.0, -1.0, -1.0, 3.0, 3.0])  # training means per fold: 1, 4, 2


def loss_of(c, target=TARGET):
    """Trial-pooled loss of setting ``c`` on each path: smallest where ``c`` is the path's target."""
    return (c - target) ** 2 + 1.0


def table_make(reference, steps, start, calls, target=TARGET):
    """``make(c)``: a forecast scoring ``loss_of(c) * (1 +- 0.9)`` on trials 0 and 1 (their mean the pooled loss)."""
    tilt = np.where(np.random.default_rng(99).random((20, 6)) < 0.5, 0.9, -0.9)

    def make(c):
        calls.append(c)
        L = loss_of(c, target)
        t = tilt[int(round(c * 2))]
        amp = np.sqrt(np.stack([L * (1 + t), L * (1 - t)]))
        return planted(reference, amp, steps, start, seed=int(round(c * 10)))

    return make


def reference_series(trials=2, T=30):
    return np.random.default_rng(7).normal(size=(trials, 6, 2, T)) * 3.0 + 50.0


def test_each_fold_picks_on_its_training_paths_pooled_over_trials_and_extends_past_the_top():
    s = ps.ComparisonSetup(steps=2, start=5)
    ref = reference_series()
    calls = []
    make = table_make(ref, 2, 5, calls)
    fc, mse, chosen, fcs, every = ps.tuned_forecast([1, 2, 3], make, ref, ref, FOLDS, s, more=(0.5, 3, 4, 5, 6))
    # fold 0 trains on targets -1, 3 (mean 1), fold 1 on 5, 3 (mean 4: the grid's top, then 4, then 5 tried), fold 2
    # on 5, -1 (mean 2); 0.5 and 3 are not above the grid and never tried, 6 is never needed
    assert calls == [1, 2, 3, 4, 5]
    np.testing.assert_array_equal(chosen, [1, 1, 4, 4, 2, 2])
    assert len(fcs) == 5 and every.shape == (5, 2, 6)
    for k, c in enumerate([1, 2, 3, 4, 5]):
        np.testing.assert_allclose(every[k].mean(axis=0), loss_of(c))
        np.testing.assert_array_equal(fcs[k], make(c))
    pooled = np.stack([loss_of(c) for c in (1, 2, 3, 4, 5)])
    assert [[1, 2, 3, 4, 5][i] for i in pick_here(pooled, FOLDS)] == [1, 4, 2]
    # trial 0 alone would choose otherwise: the trials are pooled
    assert [[1, 2, 3, 4, 5][i] for i in pick_here(every[:, 0], FOLDS)] != [1, 4, 2]
    # each path gets its fold's forecast and score
    index = {1: 0, 2: 1, 4: 3}
    for p in range(6):
        k = index[int(chosen[p])]
        np.testing.assert_array_equal(fc[:, p], fcs[k][:, p])
        np.testing.assert_allclose(mse[:, p], every[k][:, p])
        np.testing.assert_allclose(mse[:, p], mse_here(fcs[k], ref, 2, 5)[:, p])
    assert fc.shape == ref.shape and mse.shape == (2, 6)


def test_the_score_reads_the_horizon_and_the_first_frame_of_the_setup():
    ref = reference_series()
    amp = np.full((2, 6), 2.0)
    for steps, start in ((1, 4), (3, 7)):
        s = ps.ComparisonSetup(steps=steps, start=start)
        _, mse, _, _, every = ps.tuned_forecast(
            [1, 2], lambda c, steps=steps, start=start: planted(ref, amp * c, steps, start, seed=c), ref, ref, FOLDS, s
        )
        np.testing.assert_allclose(every, np.stack([np.full((2, 6), 4.0), np.full((2, 6), 16.0)]))
        np.testing.assert_allclose(mse, 4.0)


def test_a_grid_whose_top_is_not_picked_is_not_extended():
    ref = reference_series()
    calls = []
    target = np.array([1.0, 1.0, 2.0, 2.0, 1.0, 2.0])
    _, _, chosen, fcs, _ = ps.tuned_forecast(
        [1, 2, 3],
        table_make(ref, 1, 3, calls, target),
        ref,
        ref,
        FOLDS,
        ps.ComparisonSetup(steps=1, start=3),
        more=(4,),
    )
    assert calls == [1, 2, 3] and len(fcs) == 3
    assert set(np.asarray(chosen).tolist()) <= {1, 2}


def test_a_test_path_never_moves_its_own_folds_choice():
    ref = reference_series()
    s = ps.ComparisonSetup(steps=2, start=5)
    base = ps.tuned_forecast([1, 2, 3], table_make(ref, 2, 5, []), ref, ref, FOLDS, s, more=(4, 5, 6))[2]
    for _, test in FOLDS:
        target = TARGET.copy()
        target[test] = [-50.0, -40.0][: len(test)]  # the fold's own test paths now want something else entirely
        got = ps.tuned_forecast([1, 2, 3], table_make(ref, 2, 5, [], target), ref, ref, FOLDS, s, more=(4, 5, 6))[2]
        np.testing.assert_array_equal(got[test], base[test])
        assert not np.array_equal(got, base)  # the other folds train on them and move


# -- tune_learned_lags --------------------------------------------------------------------------------------------
def coded_series(trials=2, T=40):
    """Series whose first sample names its trial and path (100 t + p), slowly rising after."""
    t = np.arange(trials)[:, None, None, None]
    p = np.arange(6)[None, :, None, None]
    return 100.0 * t + p + 1e-3 * np.arange(T) + np.zeros((trials, 6, 2, T))


def ids(z):
    return [int(round(v)) % 100 for v in z[0, :, 0, 0]], [int(round(v)) // 100 for v in z[:, 0, 0, 0]]


def amp_of(L, train, p):
    """Score (root) of a model with ``L`` lags trained on paths ``train``, on path ``p``."""
    return 1.0 + ((7 * L + 3 * sum(train) + 5 * p + L * p) % 11) / 3.0


class FakeNetworks:
    """Recorders for the network fit and forecast: a model remembers what it was trained on; its forecast on a
    path scores exactly ``score(L, train paths, path) ** 2`` against ``reference``."""

    def __init__(self, monkeypatch, reference, steps, start, score=amp_of):
        self.fits, self.forecasts = [], []
        self.reference, self.steps, self.start, self.score = reference, steps, start, score
        monkeypatch.setattr(lm, "fit_learned_predictor", self.fit)
        monkeypatch.setattr(lm, "learned_forecast", self.forecast)

    def fit(self, kind, z_train, n_lags, steps=1, **kw):
        paths = [int(round(v)) % 100 for v in z_train[:, 0, 0]]
        assert z_train.ndim == 3 and all(v < 100 for v in z_train[:, 0, 0])  # trial 0 only
        assert kind in ("mlp", "rbf")
        model = SimpleNamespace(kind=kind, train=tuple(paths), L=n_lags, steps=steps, kw=kw)
        self.fits.append(model)
        return model

    def forecast(self, model, z):
        paths, trials = ids(z)
        self.forecasts.append((model, tuple(paths), tuple(trials)))
        amp = np.array([[self.score(model.L, model.train, p) for p in paths]] * len(trials))
        ref = np.take(np.asarray(self.reference), trials, axis=0)[:, paths]
        return planted(ref, amp, self.steps, self.start, seed=model.L)


def expected_lags(grid, score=amp_of, folds=FOLDS, P=6):
    groups = [list(test) for _, test in folds]
    K = len(groups)
    loss = np.empty((K, len(grid)))
    for i in range(K):
        for c, L in enumerate(grid):
            vals = [
                score(L, tuple(groups[g]), p) ** 2
                for g in range(K)
                if g != i
                for p in range(P)
                if p not in groups[g] and p not in groups[i]
            ]
            loss[i, c] = np.mean(vals)
    return np.asarray(grid)[np.argmin(loss, axis=1)], loss


@pytest.mark.parametrize("kind", ["mlp", "rbf"])
def test_lag_counts_are_chosen_per_fold_on_models_and_scores_that_never_touch_its_test_paths(monkeypatch, kind):
    z = coded_series()
    ref = z + 0.25  # not the series itself: the reference handed in is what is scored against
    s = ps.ComparisonSetup(
        steps=2, start=6, lag_grid=(1.0, 3, 2), lag_tuning_samples=77, learned_kw={"hidden_units": 3, "max_samples": 9}
    )
    net = FakeNetworks(monkeypatch, ref, 2, 6)
    lags, loss = ps.tune_learned_lags(kind, z, ref, FOLDS, s, np.random.default_rng(5))
    want, want_loss = expected_lags((1, 3, 2))
    np.testing.assert_array_equal(lags, want)
    np.testing.assert_allclose(loss, want_loss)
    assert lags.dtype.kind == "i" and loss.shape == (3, 3)
    seeds = np.random.default_rng(5).integers(2**31, size=(3, 3))
    groups = [tuple(test) for _, test in FOLDS]
    assert [(m.kind, m.train, m.L, m.steps) for m in net.fits] == [(kind, g, L, 2) for L in (1, 3, 2) for g in groups]
    assert [m.kw for m in net.fits] == [
        {"hidden_units": 3, "max_samples": 77, "seed": int(seeds[c, g])} for c in range(3) for g in range(3)
    ]
    # each model forecasts the first trial of every path outside the group it was trained on
    for model, paths, trials in net.forecasts:
        assert trials == (0,) and paths == tuple(p for p in range(6) if p not in model.train)
    assert len(net.forecasts) == 9


def test_perturbing_a_folds_test_paths_leaves_its_lag_count(monkeypatch):
    z = coded_series()
    s = ps.ComparisonSetup(steps=1, start=4, lag_grid=(1, 2, 4, 8), lag_tuning_samples=50)
    FakeNetworks(monkeypatch, z, 1, 4)
    base, _ = ps.tune_learned_lags("mlp", z, z, FOLDS, s, np.random.default_rng(0))
    for i, (_, test) in enumerate(FOLDS):
        test = set(test.tolist())

        def bent(L, train, p, test=test, best=base[i]):  # the fold's test paths scored and trained on otherwise
            if p in test or set(train) == test:
                return 30.0 if L == best else 0.1 + 0.01 * L
            return amp_of(L, train, p)

        FakeNetworks(monkeypatch, z, 1, 4, score=bent)
        got, _ = ps.tune_learned_lags("mlp", z, z, FOLDS, s, np.random.default_rng(0))
        assert got[i] == base[i]
        np.testing.assert_array_equal(got, expected_lags((1, 2, 4, 8), bent)[0])


def test_lag_tuning_needs_three_folds(monkeypatch):
    z = coded_series()
    FakeNetworks(monkeypatch, z, 1, 4)
    s = ps.ComparisonSetup(steps=1, start=4, lag_grid=(1, 2))
    with pytest.raises(ValueError, match="2 folds"):
        ps.tune_learned_lags("mlp", z, z, lm.path_folds(6, 2), s, np.random.default_rng(0))
    ps.tune_learned_lags("mlp", z, z, FOLDS, s, np.random.default_rng(0))  # three are enough


# -- fit_learned_folds, apply_learned_folds -----------------------------------------------------------------------
def test_each_folds_network_trains_on_the_first_trial_of_its_training_paths(monkeypatch):
    z = coded_series()
    net = FakeNetworks(monkeypatch, z, 1, 4)
    s = ps.ComparisonSetup(steps=3, learned_lags=5, learned_kw={"hidden_units": 2, "max_samples": 11})
    models = ps.fit_learned_folds("rbf", z, FOLDS, s, np.random.default_rng(8))
    draw = np.random.default_rng(8)
    seeds = [int(draw.integers(2**31)) for _ in FOLDS]
    assert models == net.fits
    assert [(m.kind, m.train, m.L, m.steps) for m in models] == [("rbf", tuple(tr), 5, 3) for tr, _ in FOLDS]
    assert [m.kw for m in models] == [{"hidden_units": 2, "max_samples": 11, "seed": sd} for sd in seeds]
    tuned = ps.fit_learned_folds("mlp", z, FOLDS, s, np.random.default_rng(8), lags=np.array([2.0, 4.0, 1.0]))
    assert [m.L for m in tuned] == [2, 4, 1] and all(type(m.L) is int for m in tuned)
    assert [m.kw["seed"] for m in tuned] == seeds


def test_each_folds_network_forecasts_its_test_paths_on_every_trial(monkeypatch):
    z = coded_series(trials=3)
    seen = []

    def forecast(model, zz):
        seen.append((model, ids(zz)))
        return zz + 1000.0 * model

    monkeypatch.setattr(lm, "learned_forecast", forecast)
    out = ps.apply_learned_folds([1, 2, 3], z, FOLDS)
    assert seen == [(k + 1, ([int(p) for p in test], [0, 1, 2])) for k, (_, test) in enumerate(FOLDS)]
    for k, (_, test) in enumerate(FOLDS):
        np.testing.assert_array_equal(out[:, test], z[:, test] + 1000.0 * (k + 1))
    partial = ps.apply_learned_folds([1, 2], z, FOLDS)  # a path no fold tests is left unforecast
    assert np.all(np.isnan(partial[:, 4:])) and np.all(np.isfinite(partial[:, :4]))


# -- compare_methods ----------------------------------------------------------------------------------------------
def moving_series(T=120, trials=2):
    """Sinusoids of different speeds and noise levels per path pair (so the folds choose differently)."""
    rng = np.random.default_rng(21)
    n = np.arange(T)
    freq = np.array([0.002, 0.002, 0.05, 0.05, 0.02, 0.02])[None, :, None, None]
    amp = np.array([5, 5, 20, 20, 10, 10])[None, :, None, None]
    phase = rng.uniform(0, 6.3, size=(1, 6, 2, 1))
    sd = np.array([1.0, 1.0, 0.05, 0.05, 0.3, 0.3])[None, :, None, None]
    return 50 + amp * np.sin(2 * np.pi * freq * n + phase) + rng.normal(size=(trials, 6, 2, T)) * sd


SETUP = ps.ComparisonSetup(
    steps=2,
    start=12,
    order=2,
    floor_grid=(3, 5, 10),
    window_grid=(6, 8),
    theta_grid=(0.3, 0.6, 0.9),
    fixed_floor=7,
    fixed_window=9,
    learned_lags=3,
    learned_kw={"hidden_units": 2},
    jerk_grid=(1e-3, 1e-1),
    meas_var_grid=(0.1, 1.0),
    singer_tau_grid=(1.0, 10.0),
    singer_ratio_grid=(1.0, 100.0),
)


class FakeKalman:
    """Recorders for the Kalman fits and forecasts (fits per fold, a forecast shifted by the fold's fit)."""

    def __init__(self, monkeypatch):
        self.calls = []
        monkeypatch.setattr(kb, "fit_constant_acceleration_folds", self.fit_ca)
        monkeypatch.setattr(kb, "fit_singer_folds", self.fit_singer)
        monkeypatch.setattr(kb, "constant_acceleration_forecast", self.ca)
        monkeypatch.setattr(kb, "singer_forecast", self.singer)

    def fit_ca(self, z0, folds, jerk_grid, meas_var_grid):
        self.calls.append(("fit ca", z0.copy(), folds, jerk_grid, meas_var_grid))
        return [(0.01 * (k + 1), 0.5 * (k + 1)) for k in range(len(folds))]

    def fit_singer(self, z0, folds, tau_grid, ratio_grid):
        self.calls.append(("fit singer", z0.copy(), folds, tau_grid, ratio_grid))
        return [(2.0 * (k + 1), 0.3, 0.7 * (k + 1)) for k in range(len(folds))]

    @staticmethod
    def shifted(z, fits, folds, steps):
        out = np.full(z.shape, np.nan)
        for k, (_, test) in enumerate(folds):
            out[:, test, :, :-steps] = (
                z[:, test, :, steps:] + sum(fits[k]) * (k + 1) + 0.1 * np.arange(z.shape[-1] - steps)
            )
        return out

    def ca(self, z, fits, folds, steps):
        self.calls.append(("ca", z, list(fits), folds, steps))
        return self.shifted(z, fits, folds, steps)

    def singer(self, z, fits, folds, steps):
        self.calls.append(("singer", z, list(fits), folds, steps))
        return -self.shifted(z, fits, folds, steps)


def tuned_here(candidates, make, ref, s, more=()):
    """The cross-validated forecast and score of a method, computed here: per fold, the candidate (the grid, then
    ``more`` in turn while a fold picks the last) with the least mean score over its training paths."""
    candidates, more = list(candidates), [c for c in more if c > max(candidates)]
    fcs = [make(c) for c in candidates]
    while True:
        loss = np.stack([mse_here(f, ref, s.steps, s.start).mean(axis=0) for f in fcs])
        pick = per_path(pick_here(loss, FOLDS), FOLDS, 6)
        if not (more and np.any(pick == len(candidates) - 1)):
            break
        candidates.append(more.pop(0))
        fcs.append(make(candidates[-1]))
    fc = np.stack([fcs[pick[p]][:, p] for p in range(6)], axis=1)
    return fc, mse_here(fc, ref, s.steps, s.start), np.asarray(candidates)[pick]


def check_tuned(cmp, name, candidates, make, ref, s, more=()):
    fc, mse, chosen = tuned_here(candidates, make, ref, s, more)
    np.testing.assert_array_equal(cmp.forecasts[name], fc)
    np.testing.assert_allclose(cmp.mse[name], mse, rtol=1e-12)
    np.testing.assert_array_equal(cmp.chosen[name], chosen)
    return chosen


def test_the_paper_s_filter_its_variant_and_the_fading_memory_are_tuned_on_the_same_folds_and_scores(monkeypatch):
    z = moving_series()
    ref = z + np.random.default_rng(3).normal(size=z.shape) * 0.2  # a reference other than the series
    s = replace(SETUP, steps=3, order=1)  # a horizon other than the order, an order other than the default
    cmp = ps.compare_methods(z, ref, FOLDS, s, np.random.default_rng(0), parts={"variant", "fading"})
    more = (120,)  # the floor extension, clipped to the series' length
    chosen = check_tuned(cmp, ps.PAPER, (3, 5, 10), lambda nf: pr.growing_memory_forecast(z, 3, 1, nf), ref, s, more)
    check_tuned(cmp, ps.VARIANT, (3, 5, 10), lambda nf: pr.g1_floor_forecast(z, nf, 3, 1), ref, s, more)
    check_tuned(cmp, ps.FADING, (0.3, 0.6, 0.9), lambda th: pr.fading_memory_forecast(z, th, 3), ref, s)
    assert len(set(chosen.tolist())) > 1  # the folds choose differently here
    np.testing.assert_allclose(
        cmp.mse_fixed[ps.PAPER], mse_here(pr.growing_memory_forecast(z, 3, 1, 7), ref, 3, 12), rtol=1e-12
    )
    np.testing.assert_allclose(
        cmp.mse_fixed[ps.VARIANT], mse_here(pr.g1_floor_forecast(z, 7, 3, 1), ref, 3, 12), rtol=1e-12
    )
    np.testing.assert_array_equal(cmp.mse_fixed[ps.FADING], cmp.mse[ps.FADING])
    assert set(cmp.mse) == {ps.PAPER, ps.VARIANT, ps.FADING} and cmp.learned_models == {}
    assert set(cmp.mse_fixed) == set(cmp.mse) and set(cmp.forecasts) == set(cmp.mse)


def test_a_still_spot_takes_the_floor_and_the_windows_past_their_grids():
    rng = np.random.default_rng(4)
    z = 40.0 + rng.normal(size=(1, 6, 2, 160))  # no motion: the longest memory wins everywhere
    s = ps.ComparisonSetup(steps=1, start=110, floor_grid=(3, 5, 10), window_grid=(6, 8), fixed_window=9)
    cmp = ps.compare_methods(z, z, FOLDS, s, rng, parts={"classical", "variant"})
    np.testing.assert_array_equal(cmp.chosen[ps.PAPER], [160] * 6)  # 350, 600, 1000 clipped to the 160 frames
    np.testing.assert_array_equal(cmp.chosen[ps.VARIANT], [160] * 6)
    np.testing.assert_array_equal(cmp.chosen["linear regression deg 1"], [100] * 6)  # 45, 70, 100 tried in turn
    check_tuned(cmp, ps.PAPER, (3, 5, 10), lambda nf: pr.growing_memory_forecast(z, 1, 2, nf), z, s, (160,))


def test_on_a_short_series_the_windows_past_the_grid_stop_at_its_length():
    """The window extension (45, 70, 100) is clipped to the series' frames, as the floors are: on 80 frames a still
    spot's longest memory is a window of all 80 samples, never a reported window of 100 frames."""
    rng = np.random.default_rng(7)
    z = 40.0 + rng.normal(size=(1, 6, 2, 80))
    s = ps.ComparisonSetup(steps=1, start=60, floor_grid=(3, 5, 10), window_grid=(6, 8), fixed_window=9)
    cmp = ps.compare_methods(z, z, FOLDS, s, rng, parts={"classical"})
    np.testing.assert_array_equal(cmp.chosen[ps.PAPER], [80] * 6)
    chosen = np.concatenate([cmp.chosen[n] for n in ("linear regression deg 1", "linear regression deg 2")])
    assert set(chosen.tolist()) <= {70, 80} and 80 in chosen  # the extension ran to the series' end, not past it
    assert ps.clipped_extension(ps.WINDOW_EXTENSION, 80) == [45, 70, 80]
    assert ps.clipped_extension(ps.FLOOR_EXTENSION, 80) == [80]
    assert ps.clipped_extension(ps.WINDOW_EXTENSION, 1000) == [45, 70, 100]


def test_the_classical_baselines_search_windows_from_their_degree_plus_one_on_the_same_folds():
    z = moving_series()
    ref = z + np.random.default_rng(5).normal(size=z.shape) * 0.2
    s = SETUP
    cmp = ps.compare_methods(z, ref, FOLDS, s, np.random.default_rng(0), parts={"classical"})
    ext = (45, 70, 100)
    windows = {
        "cubic spline": ((4, 5, 6, 8), lambda L: pr.spline_forecast(z, L, 2)),
        "linear regression deg 1": ((2, 3, 4, 5, 6, 8), lambda L: pr.sliding_regression_forecast(z, L, 1, 2)),
        "linear regression deg 2": ((3, 4, 5, 6, 8), lambda L: pr.sliding_regression_forecast(z, L, 2, 2)),
    }
    picked = set()
    for name, (candidates, make) in windows.items():
        picked |= set(check_tuned(cmp, name, candidates, make, ref, s, ext).tolist())
        np.testing.assert_allclose(cmp.mse_fixed[name], mse_here(make(9), ref, 2, 12), rtol=1e-12)
    assert {2, 3} & picked  # the short windows below the grid are reached
    for name, (window, degree) in {
        "finite differences, 2 points": (2, 1),
        "finite differences, 3 points": (3, 2),
    }.items():
        f = pr.sliding_regression_forecast(z, window, degree, 2)
        np.testing.assert_array_equal(cmp.forecasts[name], f)
        np.testing.assert_allclose(cmp.mse[name], mse_here(f, ref, 2, 12), rtol=1e-12)
        np.testing.assert_array_equal(cmp.mse_fixed[name], cmp.mse[name])
        assert name not in cmp.chosen
    assert set(cmp.mse) == {ps.PAPER, *ps.CLASSICAL}


def test_the_networks_are_trained_and_scored_like_the_rest(monkeypatch):
    z = coded_series(T=60)
    ref = z + 0.5
    s = ps.ComparisonSetup(
        steps=2, start=12, floor_grid=(3, 5), learned_lags=None, lag_grid=(1, 2, 3), lag_tuning_samples=40
    )
    net = FakeNetworks(monkeypatch, ref, 2, 12)
    cmp = ps.compare_methods(z, ref, FOLDS, s, np.random.default_rng(6), parts={"learned"})
    draw = np.random.default_rng(6)
    for kind, name in (("mlp", "MLP back-prop"), ("rbf", "RBF network")):
        lags = ps.tune_learned_lags(kind, z, ref, FOLDS, s, draw)[0]  # the same draws, in the same order
        np.testing.assert_array_equal(cmp.chosen[name], lags)
        models = cmp.learned_models[kind]
        assert [(m.kind, m.train, m.L) for m in models] == [(kind, tuple(tr), L) for (tr, _), L in zip(FOLDS, lags)]
        assert [m.kw["seed"] for m in models] == [int(draw.integers(2**31)) for _ in FOLDS]
        want = np.full(z.shape, np.nan)
        for m, (_, test) in zip(models, FOLDS):
            want[:, test] = net.forecast(m, z[:, test])
        np.testing.assert_array_equal(cmp.forecasts[name], want)
        np.testing.assert_allclose(cmp.mse[name], mse_here(want, ref, 2, 12), rtol=1e-12)
        np.testing.assert_array_equal(cmp.mse_fixed[name], cmp.mse[name])
    # fixed lag counts: nothing tuned, the setup's count in every fold
    fixed = ps.compare_methods(
        z, ref, FOLDS, ps.ComparisonSetup(**{**s.__dict__, "learned_lags": 2}), draw, parts={"learned"}
    )
    assert "MLP back-prop" not in fixed.chosen and {m.L for m in fixed.learned_models["rbf"]} == {2}
    # pre-trained models are applied as given: nothing trained, tuned or drawn
    before = len(net.fits)
    given = ps.compare_methods(z, ref, FOLDS, s, draw, learned_models=cmp.learned_models, parts={"learned"})
    assert len(net.fits) == before and "RBF network" not in given.chosen
    assert given.learned_models == cmp.learned_models
    np.testing.assert_array_equal(given.forecasts["MLP back-prop"], cmp.forecasts["MLP back-prop"])
    assert "MLP back-prop" not in ps.compare_methods(z, ref, FOLDS, s, draw, learned=False).mse
    assert len(net.fits) == before


def test_the_kalman_filters_are_fitted_on_the_first_trial_and_scored_like_the_rest(monkeypatch):
    z = moving_series(T=60)
    ref = z + 0.3
    kal = FakeKalman(monkeypatch)
    s = SETUP
    cmp = ps.compare_methods(z, ref, FOLDS, s, np.random.default_rng(0), parts={"kalman"})
    (n1, z1, f1, g1, h1), (n2, z2, f2, g2, h2) = kal.calls[:2]
    assert (n1, n2) == ("fit ca", "fit singer")
    np.testing.assert_array_equal(z1, z[0])
    np.testing.assert_array_equal(z2, z[0])
    assert f1 is FOLDS and f2 is FOLDS
    assert (g1, h1, g2, h2) == (s.jerk_grid, s.meas_var_grid, s.singer_tau_grid, s.singer_ratio_grid)
    ca_fits, singer_fits = kal.fit_ca(z[0], FOLDS, 0, 0), kal.fit_singer(z[0], FOLDS, 0, 0)
    for name, fits, sign in ((ps.CA_KALMAN, ca_fits, 1), (ps.SINGER, singer_fits, -1)):
        f = sign * FakeKalman.shifted(z, fits, FOLDS, 2)
        np.testing.assert_array_equal(cmp.forecasts[name], f)
        np.testing.assert_allclose(cmp.mse[name], mse_here(f, ref, 2, 12), rtol=1e-12)
        np.testing.assert_array_equal(cmp.mse_fixed[name], cmp.mse[name])
        np.testing.assert_array_equal(cmp.chosen[name], np.array(fits))
    assert [c[0] for c in kal.calls[2:4]] == ["ca", "singer"] and all(c[1] is z and c[4] == 2 for c in kal.calls[2:4])
    # fits handed in are used as they are, nothing fitted
    kal.calls.clear()
    given = ([(1.0, 2.0)] * 3, [(3.0, 4.0, 5.0)] * 3)
    again = ps.compare_methods(z, ref, FOLDS, s, np.random.default_rng(0), parts={"kalman"}, kalman_fits=given)
    assert [c[0] for c in kal.calls] == ["ca", "singer"]
    np.testing.assert_array_equal(again.chosen[ps.SINGER], [[3.0, 4.0, 5.0]] * 3)
    np.testing.assert_array_equal(again.forecasts[ps.CA_KALMAN], FakeKalman.shifted(z, given[0], FOLDS, 2))


def test_each_part_keeps_its_numbers_whichever_others_run(monkeypatch):
    z = coded_series(T=110) + moving_series(T=110) * 0.001
    ref = z + 0.1
    FakeNetworks(monkeypatch, ref, 2, 12)
    FakeKalman(monkeypatch)
    s = ps.ComparisonSetup(
        steps=2, start=12, floor_grid=(3, 5), window_grid=(6,), theta_grid=(0.5, 0.8), learned_lags=None,
        lag_grid=(1, 2), lag_tuning_samples=40,
    )  # fmt: skip
    every = ps.compare_methods(z, ref, FOLDS, s, np.random.default_rng(2))
    assert set(every.mse) == {ps.PAPER, ps.VARIANT, ps.FADING, *ps.CLASSICAL, *ps.FITTED}
    for part in sorted(ps.PARTS):
        alone = ps.compare_methods(z, ref, FOLDS, s, np.random.default_rng(2), parts=[part])
        assert len(alone.mse) > 1
        for name in alone.mse:
            np.testing.assert_array_equal(alone.mse[name], every.mse[name])
            np.testing.assert_array_equal(alone.mse_fixed[name], every.mse_fixed[name])
            np.testing.assert_array_equal(alone.forecasts[name], every.forecasts[name])
        for name in alone.chosen:
            np.testing.assert_array_equal(alone.chosen[name], every.chosen[name])
    with pytest.raises(ValueError, match="'bogus'"):
        ps.compare_methods(z, ref, FOLDS, s, np.random.default_rng(2), parts={"classical", "bogus"})


def test_every_method_is_scored_from_the_same_first_frame():
    """A window longer than the first scored frame fits all the samples there are before it has its window's worth:
    every method has a forecast at every scored frame, so each is scored over the same frames."""
    rng = np.random.default_rng(4)
    z = 40.0 + rng.normal(size=(1, 6, 2, 160))  # no motion: the windows grow past the first scored frame
    s = ps.ComparisonSetup(steps=1, start=20, floor_grid=(3, 5, 10), window_grid=(6, 8), fixed_window=9)
    cmp = ps.compare_methods(z, z, FOLDS, s, rng, parts={"classical"})
    assert np.all(cmp.chosen["linear regression deg 1"] > s.start)
    for name, f in cmp.forecasts.items():
        e = pr.forecast_errors(f, z, s.steps)[..., s.start :]
        assert np.all(np.isfinite(e)), name


def test_the_fading_memory_takes_its_longest_memory_on_a_still_spot():
    rng = np.random.default_rng(4)
    z = 40.0 + rng.normal(size=(1, 6, 2, 600))  # no motion: the longest memory wins in the steady state
    s = ps.ComparisonSetup(steps=1, start=40, floor_grid=(3, 5, 10))  # the default theta grid, up to 0.95
    steady = [mse_here(pr.fading_memory_forecast(z, th, 1), z, 1, 400).mean() for th in s.theta_grid]
    assert np.argmin(steady) == len(s.theta_grid) - 1  # from frame 400 on, 0.95 is the best
    cmp = ps.compare_methods(z, z, FOLDS, s, rng, parts={"fading"})
    np.testing.assert_array_equal(cmp.chosen[ps.FADING], [0.95] * 6)
