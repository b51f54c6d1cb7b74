"""Paper 004: the study functions the verdicts rest on (measurement function, batching, readings)."""

import numpy as np
import pytest

from tvtrack.filters.polynomial import growing_memory_gains
from tvtrack.montecarlo import Estimate
from tvtrack.papers.p004_laser_spot_prediction import findings as fd
from tvtrack.papers.p004_laser_spot_prediction import predictors as pr
from tvtrack.papers.p004_laser_spot_prediction import recording, study
from tvtrack.papers.p004_laser_spot_prediction import side_studies as side
from tvtrack.papers.p004_laser_spot_prediction.beam_wander import one_frame_motion_rms
from tvtrack.papers.p004_laser_spot_prediction.intervals import root_mean_ci
from tvtrack.papers.p004_laser_spot_prediction.prediction_study import CLASSICAL, PAPER, per_trial_path_mse
from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT, DEPENDS, NAMES, ROWS, build, explored
from tvtrack.papers.p004_laser_spot_prediction import derivation
from tvtrack.papers.p004_laser_spot_prediction import learned
from tvtrack.papers.p004_laser_spot_prediction import prediction_study
from tvtrack.papers.p004_laser_spot_prediction import world

SIZE = study.StudySize(
    n_paths=6,
    n_frames=200,
    floor_grid=(3, 5, 10, 30),
    window_grid=(4, 10),
    mlp_hidden_units=8,
    rbf_centres=20,
    train_samples=300,
    n_mc_variance=1000,
    timing_frames=20,
)
# The batching and claims= tests: what they check (a batch or a subset of claims gives the values of one full run
# bit for bit) does not depend on how many lag counts the networks' tuning tries. Two candidates still tune,
# choose and train per fold, with 9 of the 18 network fits of a scene at the default grid's five.
TWO_LAGS = study.replace(SIZE, lag_grid=(2, 4))


@pytest.fixture(scope="module")
def run():
    return study.run_study(dict(DEFAULT), 7, SIZE)


def _same(a, b):
    if isinstance(a, dict):
        assert a.keys() == b.keys()
        for k in a:
            _same(a[k], b[k])
    elif isinstance(a, Estimate):
        assert (a.value, a.ci_low, a.ci_high) == (b.value, b.ci_low, b.ci_high)
    else:
        assert a == b


def test_register_rows_are_complete_and_the_study_reads_every_entry():
    reg = build()
    assert tuple(reg.names) == NAMES == study.ENTRIES
    assert all(set(d) <= set(NAMES) for d in DEPENDS.values())
    assert {o for *_, o in ROWS} <= {"author", "adversarial"}
    small, dep = explored(["jitter", "horizon"])
    assert small.names == ["jitter", "horizon"] and dep["C004-5"] == [] and dep["C004-2"] == ["jitter", "horizon"]


def test_measure_is_a_function_of_config_and_seed_and_batching_changes_nothing():
    """The batched form shares scenes and runs between configurations; the claim values must be those
    of one run per configuration (C004-8, a CPU time, aside)."""
    configs = [
        dict(DEFAULT),
        dict(DEFAULT, tuning="fixed"),
        dict(DEFAULT, reference="true centre"),
        dict(DEFAULT, horizon=3),
        dict(DEFAULT, jitter=1.0),
    ]
    study.clear_cache()
    batch = study.measure_batch(configs, [7] * len(configs), TWO_LAGS)
    for cfg, got in zip(configs, batch):
        one = study.measure(cfg, 7, TWO_LAGS)
        assert set(one) == {
            "C004-1",
            "C004-2",
            "C004-3",
            "C004-3b",
            "C004-4",
            "C004-5",
            "C004-6",
            "C004-8",
            study.CENTROID,
        }
        for cid in one:
            if cid != "C004-8":
                _same(one[cid], got[cid])
    study.clear_cache()
    assert batch[0]["C004-2"].value != batch[3]["C004-2"].value  # the horizon is another run
    # another seed: C004-2 alone (claims=, whose values are the full run's bit for bit, the next test), not the networks
    other_seed = study.measure(dict(DEFAULT), 8, TWO_LAGS, claims=frozenset({"C004-2"}))
    assert batch[0]["C004-2"].value != other_seed["C004-2"].value


def test_claims_asked_are_computed_alone_bit_for_bit():
    """measure(..., claims=S) gives exactly measure(...)'s values on S (the explorer's claims=), running only the
    methods S reads; a batch that asks the prediction claims one by one on one scene (the cached run grows by the
    parts asked) gives the values of one full run."""
    cfg = dict(DEFAULT, horizon=3)
    full = study.measure(cfg, 7, TWO_LAGS)
    for subset in ({"C004-3"}, {"C004-3b"}, {"C004-1", "C004-6"}, {"C004-4", "C004-5"}, {"C004-2", "C004-3b"}):
        got = study.measure(cfg, 7, TWO_LAGS, claims=frozenset(subset))
        assert subset <= set(got) and "C004-8" not in got
        for cid in subset:
            _same(full[cid], got[cid])
    study.clear_cache()
    asked = [frozenset({"C004-3"}), frozenset({"C004-3b", "C004-2"}), None, frozenset({"C004-5"})]
    batch = study.measure_batch([cfg] * 4, [7] * 4, TWO_LAGS, claims=asked)
    for claims, got in zip(asked, batch):
        for cid in claims or set(full) - {"C004-8"}:
            _same(full[cid], got[cid])
    runs = [r for k, r in study._CACHE.items() if k[0] == "scene" and r.parts]
    assert len(runs) == 1 and runs[0].parts == {"classical", "learned"}  # no Kalman filter: no claim reads it
    assert "MLP back-prop" in runs[0].forecasts and prediction_study.SINGER not in runs[0].forecasts
    study.clear_cache()
    assert study.parts_for({"C004-5", "C004-8"}) is None and study.parts_for({"C004-3"}) == {"classical"}


def test_the_cached_variance_check_is_the_uncached_one():
    """C004-5 is computed once per (seed, series, noise law) and shared by every configuration: the cached value is
    bit for bit a fresh run from the seed's own stream, for each noise law and seed."""
    study.clear_cache()
    for seed, noise in ((7, "Gaussian"), (7, "Student t3"), (8, "Gaussian"), (7, "Gaussian")):
        fresh = study.variance_ratios(np.random.default_rng(study.run_streams(seed)[4]), 1000, noise=noise)
        _same(fresh, study._variance_check(seed, 1000, noise))
    assert len(study._VARIANCE) == 3
    study.clear_cache()
    assert not study._VARIANCE


def test_readings_of_one_run(run):
    """tuning = fixed is the floor N_f = fixed_floor; reference = true centre scores against the truth."""
    m, s = 1, SIZE.eval_start
    fixed = study.claim_values(study.replace(run, config=dict(DEFAULT, tuning="fixed")))
    mse = per_trial_path_mse(pr.growing_memory_forecast(run.z, m, 2, SIZE.fixed_floor), run.z_meas, m, s)[0]
    assert fixed["C004-2"].value == pytest.approx(np.sqrt(mse.mean()))
    truth = study.claim_values(study.replace(run, config=dict(DEFAULT, reference="true centre")))
    mse_t = per_trial_path_mse(run.forecasts[PAPER], run.truth, m, s)[0]
    assert truth["C004-2"].value == pytest.approx(np.sqrt(mse_t.mean()))
    lsq = study.claim_values(study.replace(run, config=dict(DEFAULT, spline="least-squares cubic")))
    r_lsq = (
        per_trial_path_mse(run.forecasts[study.LSQ_CUBIC], run.z_meas, m, s)[0].mean()
        / per_trial_path_mse(run.forecasts[PAPER], run.z_meas, m, s)[0].mean()
    )
    assert lsq["C004-3"]["cubic spline"].value == pytest.approx(r_lsq)
    base = study.claim_values(run)
    assert base["C004-3"]["cubic spline"].value != pytest.approx(r_lsq)
    for b in CLASSICAL:
        ratio = (
            per_trial_path_mse(run.forecasts[b], run.z_meas, m, s)[0].mean()
            / per_trial_path_mse(run.forecasts[PAPER], run.z_meas, m, s)[0].mean()
        )
        assert base["C004-3"][b].value == pytest.approx(ratio)


def test_the_bound_gets_the_measurement_variance_not_its_square_root(monkeypatch):
    """The optimal predictor is given the centroid variance plus the jitter variance (planted bug: the
    standard deviations where the variances belong)."""
    seen = {}
    real = study.optimal_wander_forecast

    def spy(z, scene, rms, meas_var, steps):
        seen["meas_var"] = np.asarray(meas_var)
        return real(z, scene, rms, meas_var, steps)

    monkeypatch.setattr(study, "optimal_wander_forecast", spy)
    cfg = dict(DEFAULT, jitter=1.0)
    r = study._methods(study.study_run(cfg, 3, SIZE), cfg, 3, {"optimal"})  # the bound alone: what the spy watches
    np.testing.assert_allclose(seen["meas_var"], r.centroid_rms**2 + r.jitter_rms**2)


def test_scene_jitter_and_saturation():
    r = study.study_run(dict(DEFAULT, jitter=2.0), 5, SIZE)
    np.testing.assert_allclose(r.jitter_rms, 2.0 * one_frame_motion_rms(r.scene, r.path_rms))
    assert 0.05 < study.study_run(dict(DEFAULT), 5, SIZE).clipped_share < 0.6  # 200 DN peak x scintillation, 8 bits
    assert study.study_run(dict(DEFAULT, saturation="none"), 5, SIZE).clipped_share == 0.0
    assert study.scene_config(dict(DEFAULT, **{"frame rate": 200.0}), SIZE).drift_max_px_per_frame == pytest.approx(
        0.02 * 25 / 200
    )


def test_horizon_study_retunes_the_floor_at_every_horizon(run):
    """The floor reported at each horizon is the one cross-validation picks for that horizon (the old
    study kept the one-frame floor at every horizon)."""
    from tvtrack.papers.p004_laser_spot_prediction.prediction_study import FLOOR_EXTENSION

    hz = side.horizon_study(run, (1, 10), seed=0)
    T = run.z.shape[-1]
    for h in (1, 10):
        grid, more = list(SIZE.floor_grid), sorted({min(v, T) for v in FLOOR_EXTENSION})

        def loss_of(nf, h=h):
            f = pr.growing_memory_forecast(run.z, h, 2, nf)
            return per_trial_path_mse(f, run.z_meas, h, SIZE.eval_start).mean(axis=0)

        loss = [loss_of(nf) for nf in grid]
        pick = learned.cross_validated_pick(np.stack(loss), run.folds)
        while more and np.any(pick == len(grid) - 1):  # the grid extended while a fold picks its top
            grid.append(more.pop(0))
            loss.append(loss_of(grid[-1]))
            pick = learned.cross_validated_pick(np.stack(loss), run.folds)
        pick = np.asarray(grid)[pick]
        assert hz["floor"][h] == float(np.median(pick))
        top = max((*SIZE.floor_grid, *FLOOR_EXTENSION))
        assert hz["edges"][h][PAPER] == float(np.mean(pick == top))  # the extended grid's upper edge
    assert hz["rms"][PAPER][10].value > hz["rms"][PAPER][1].value
    assert set(hz["slopes"]) == set(hz["rms"])
    text = fd.horizon_sentence(hz)
    on_edge = any(v > 0 for e in hz["edges"].values() for v in e.values())
    assert ("on an edge of their grid" in text) == on_edge
    assert ("inside its grid at every horizon" in text) == (not on_edge)


def test_horizon_study_reuses_the_runs_comparison_bit_for_bit(run):
    """At the run's own horizon the horizon study takes the run's comparison instead of a fresh one: the same
    numbers (RMS, floors, edge shares) as a fresh comparison, which a run without its parts forces."""
    reused = side.horizon_study(run, (1, 2), seed=0)
    fresh = side.horizon_study(study.replace(run, parts=frozenset()), (1, 2), seed=0)
    assert side._run_comparison_at(run, 1) is not None and side._run_comparison_at(run, 2) is None
    assert reused["floor"] == fresh["floor"] and reused["edges"] == fresh["edges"]
    assert list(reused["rms"]) == list(fresh["rms"])
    for name, per_h in fresh["rms"].items():
        _same(per_h, reused["rms"][name])
    # the Kalman fits made once are those a fresh comparison at horizon 2 makes
    from tvtrack.papers.p004_laser_spot_prediction.prediction_study import CA_KALMAN, compare_methods

    s2 = study.replace(prediction_study.comparison_setup(dict(run.config, horizon=2), SIZE), learned_kw={})
    direct = compare_methods(run.z, run.z_meas, run.folds, s2, np.random.default_rng(0), learned=False)
    for name in (CA_KALMAN, prediction_study.SINGER, PAPER):
        mse = per_trial_path_mse(direct.forecasts[name], run.z_meas, 2, SIZE.eval_start)[0]
        _same(root_mean_ci(mse), reused["rms"][name][2])


def test_horizon_sentence_names_the_settings_on_a_grid_edge():
    """A floor on the grid's top at a long horizon is named with its horizon and share (the curve there is
    the grid's limit); a horizon with nothing on an edge is not listed."""
    text = fd._horizon_edges({1: {PAPER: 0.0, "Singer tau": 0.0}, 10: {PAPER: 0.6, "Singer tau": 0.0}})
    assert "horizon 10: growing memory (paper) 60%" in text and "horizon 1:" not in text
    assert "inside its grid" in fd._horizon_edges({1: {PAPER: 0.0}})
    assert fd._horizon_edges({}) == ""


def test_late_rms_ratio_is_the_root_of_the_mean_square_ratio():
    rng = np.random.default_rng(1)
    ref = np.zeros((1, 5, 2, 100))
    a = 3.0 * rng.standard_normal(ref.shape)
    b = 1.0 * rng.standard_normal(ref.shape)
    e = prediction_study.late_rms_ratio(a, b, ref, 1, 50)
    ma = per_trial_path_mse(a, ref, 1, 50)[0].mean()
    mb = per_trial_path_mse(b, ref, 1, 50)[0].mean()
    assert e.value == pytest.approx(np.sqrt(ma / mb)) and e.ci_low < e.value < e.ci_high


def test_variance_ratios_are_one_for_the_model_and_the_gain_falls():
    v = study.variance_ratios(np.random.default_rng(2), 20000)
    assert v["g1 decreasing"] < 0
    for k, e in v.items():
        if k.startswith("variance"):
            assert e.ci_low < 1.0 < e.ci_high and abs(e.value - 1) < 0.05


def test_recursion_vs_batch_is_exact_and_starts_at_three():
    dev, first = derivation.recursion_vs_batch(np.cumsum(np.random.default_rng(3).standard_normal(80)))
    assert dev < 1e-9 and first == 3


def test_gain_used_is_the_floored_gain():
    g = growing_memory_gains(2, 7)[:, 0]
    np.testing.assert_array_equal(recording.gain_used(7, 12), np.r_[g, [g[-1]] * 5])


def test_words_follow_the_interval():
    e = lambda lo, hi: Estimate(1.0, 0.1, lo, hi, 15)
    assert fd.compare_word(e(1.1, 1.5)) == "larger"
    assert fd.compare_word(e(0.5, 0.9)) == "smaller"
    assert fd.compare_word(e(0.9, 1.1)) == "indistinguishable from"
    assert fd.compare_word(Estimate(1.0, np.nan, np.nan, np.nan, 15)) == "indistinguishable from"


def test_model_order_summary_names_the_better_order(run):
    s = side.model_order_summary(run)
    ratio = s["ratio_2_over_1"]
    text = fd.model_order_sentence(s)
    if ratio.ci_low > 1:
        assert "first order (a line) wins" in text
    elif ratio.ci_high < 1:
        assert "second order (a quadratic) wins" in text
    assert s["rms"][s["best_order1"]] <= min(
        s["rms"][n] for n in ("finite differences, 2 points", "linear regression deg 1")
    )


def test_full_frame_exposure_is_the_mean_of_the_path_over_the_frame_interval():
    """'exposure = full frame': each frame is the mean of k sub-samples of one path drawn at k times the
    frame rate, the last sub-sample at the frame time; 'instant' is the generator itself."""
    from dataclasses import replace

    from tvtrack.papers.p004_laser_spot_prediction.beam_wander import generate_traces

    scene = study.scene_config(dict(DEFAULT), SIZE)
    k = world.EXPOSURE_SUBSAMPLES
    inst = world.exposed_traces(scene, 3, "instant")
    np.testing.assert_array_equal(inst.centres_px, generate_traces(scene, 3).centres_px)
    full = world.exposed_traces(scene, 3, "full frame")
    fine = generate_traces(
        replace(
            scene,
            frame_rate_hz=scene.frame_rate_hz * k,
            n_frames=scene.n_frames * k,
            drift_max_px_per_frame=scene.drift_max_px_per_frame / k,
        ),
        3,
    )
    t = 17
    np.testing.assert_allclose(full.centres_px[:, t], fine.centres_px[:, k * t : k * t + k].mean(axis=1))
    assert full.centres_px.shape == inst.centres_px.shape and full.frame_rate_hz == scene.frame_rate_hz
    # the boxcar smooths: the frame-to-frame second difference shrinks against the instant sampling
    d2 = lambda x: np.sqrt(np.mean(np.diff(x, 2, axis=1) ** 2))  # noqa: E731
    assert d2(full.centres_px) < d2(fine.centres_px[:, k - 1 :: k])
    with pytest.raises(ValueError, match="exposure"):
        world.exposed_traces(scene, 3, "half")
    # interlaced frame integration: two fields of one frame interval each, half a frame apart, averaged
    w = world.exposure_weights("interlaced, frame integration", 4)
    np.testing.assert_allclose(w, [0.125, 0.125, 0.25, 0.25, 0.125, 0.125])
    il = world.exposed_traces(scene, 3, "interlaced, frame integration")
    a = fine.centres_px[:, k * t : k * t + k].mean(axis=1)
    b = fine.centres_px[:, k * t - k // 2 : k * t + k // 2].mean(axis=1)
    np.testing.assert_allclose(il.centres_px[:, t], (a + b) / 2)


def test_spot_size_reaches_the_camera():
    assert study.camera_for(dict(DEFAULT, **{"spot size": 0.6})).spot_sigma_px == 0.6
    assert study.camera_for(dict(DEFAULT)).spot_sigma_px == 4.0


def test_statistic_readings_radial_and_tail(run):
    """C004-1 radial: the per-path 95th percentile of the distance |e| (both axes); C004-3 tail reading:
    the paired ratio of per-path 95th percentiles of the per-axis |e|."""
    m, s = 1, SIZE.eval_start
    rad = study.claim_values(study.replace(run, config=dict(DEFAULT, **{"C004-1 statistic": "radial 95th percentile"})))
    e = pr.forecast_errors(run.forecasts[PAPER], run.z_meas, m)[0, ..., s:]
    want = np.nanquantile(np.hypot(e[:, 0], e[:, 1]), 0.95, axis=1).mean()
    assert rad["C004-1"].value == pytest.approx(want)
    tail = study.claim_values(study.replace(run, config=dict(DEFAULT, **{"C004-3 statistic": "95th percentile"})))
    base = study.claim_values(run)
    assert tail["C004-2"].value == base["C004-2"].value  # the reading changes C004-3 only
    q = (
        lambda f: np.nanquantile(  # noqa: E731
            np.abs(pr.forecast_errors(f, run.z_meas, m)[0, ..., s:]).reshape(SIZE.n_paths, -1), 0.95, axis=1
        )
    )
    for b in CLASSICAL:
        assert tail["C004-3"][b].value == pytest.approx(q(run.forecasts[b]).mean() / q(run.forecasts[PAPER]).mean())


def test_natural_spline_reading(run):
    """The natural cubic spline extends linearly beyond its last knot: it extrapolates a line exactly,
    not a parabola, and matches scipy's natural spline value + slope at the last knot; the reading
    'spline = natural cubic' scores it as the spline part of C004-3."""
    from scipy.interpolate import CubicSpline

    t = np.arange(30.0)
    line = pr.natural_spline_forecast(2.0 + 0.5 * t, 6, 3)
    np.testing.assert_allclose(line[5:], 2.0 + 0.5 * (t[5:] + 3))
    parab = pr.natural_spline_forecast(0.1 * t**2, 6, 1)
    assert np.nanmax(np.abs(parab[5:] - 0.1 * (t[5:] + 1) ** 2)) > 0.05
    z = np.random.default_rng(1).standard_normal(12)
    cs = CubicSpline(np.arange(6.0), z[-6:], bc_type="natural")
    assert pr.natural_spline_forecast(z, 6, 2)[-1] == pytest.approx(cs(5.0) + 2 * cs.derivative()(5.0))
    m, s = 1, SIZE.eval_start
    nat = study.claim_values(study.replace(run, config=dict(DEFAULT, spline="natural cubic")))
    r = (
        per_trial_path_mse(run.forecasts[study.NATURAL_SPLINE], run.z_meas, m, s)[0].mean()
        / per_trial_path_mse(run.forecasts[PAPER], run.z_meas, m, s)[0].mean()
    )
    assert nat["C004-3"]["cubic spline"].value == pytest.approx(r)


def test_vibration_regime_adds_a_sinusoid_to_the_true_path():
    """'vibration' adds amplitude * sin(2 pi 8 Hz t + phase) per path and axis to the true centres; the
    other streams (paths, jitter, sensor) are untouched (common random numbers)."""
    v = study.vibration(1.5, 25.0, (3, 50, 2), np.random.default_rng(0))
    assert v.shape == (3, 50, 2) and np.max(np.abs(v)) <= 1.5 and np.max(np.abs(v)) > 1.4
    spec = np.abs(np.fft.rfft(v[0, :, 0]))
    assert np.argmax(spec) == round(world.VIBRATION_HZ / 25.0 * 50)  # 8 Hz on a 0.5 Hz grid
    small = study.replace(SIZE, n_paths=2, n_frames=100)
    a = study.study_run(dict(DEFAULT, bandwidth=3.0), 5, small)  # one bandwidth: the vibration world is re-calibrated
    b = study.study_run(dict(DEFAULT, bandwidth=3.0, vibration=1.0), 5, small)
    d = (b.truth - a.truth)[0]  # (P, 2, T)
    np.testing.assert_allclose(np.max(np.abs(d), axis=-1), 1.0, atol=0.02)
    k = -4 * np.sin(np.pi * world.VIBRATION_HZ / 25.0) ** 2  # a sampled sinusoid: d'' = k d exactly
    np.testing.assert_allclose(np.diff(d, 2, axis=-1), k * d[..., 1:-1], atol=1e-9)


def test_frame_loss_breaks_the_recursion_only_when_lost_frames_are_skipped():
    # third adversarial pass: with gaps the sample-counting recursion differs from eq. (4) at the true times
    from tvtrack.papers.p004_laser_spot_prediction.derivation import drop_frames, recursion_vs_batch

    t = np.arange(200.0)
    z = 3.0 + 0.2 * t - 0.001 * t**2 + np.random.default_rng(1).normal(0, 0.3, t.size)
    same = drop_frames(z, np.random.default_rng(2), 0.0, held=False)
    assert np.array_equal(same, z)
    held = drop_frames(z, np.random.default_rng(2), 0.05, held=True)
    skipped = drop_frames(z, np.random.default_rng(2), 0.05, held=False)
    assert np.isnan(skipped).any() and np.isfinite(held).all()
    assert recursion_vs_batch(held)[0] < 1e-9  # held: an even series again, exact
    assert recursion_vs_batch(skipped)[0] > 1e-6  # skipped: the recursion is not eq. (4) at the true times


def test_budget_and_regeneration_sentences_follow_their_tests():
    """The measurement's share is read at the study's read noise (or the nearest level, said so); the
    regenerated data set 'agrees' only within the stated tolerance."""
    budget = {2.0: {"centroid": 0.04, "crb": 0.03}, 32.0: {"centroid": 0.2, "crb": 0.14}}
    pred = Estimate(0.33, 0.01, 0.31, 0.35, 15)
    text = fd.budget_sentence(budget, 2.0, pred)
    assert "At the study's read noise the centroid errs 0.040 px" in text and "a small part" in text
    far = fd.budget_sentence(budget, 24.0, Estimate(0.3, 0.01, 0.28, 0.32, 15))
    assert "At 32 DN, the budget's level nearest the study's 24 DN," in far and "a large part" in far
    assert "2 DN 0.56" in text
    assert "agrees with" in fd.regeneration_sentence(3.8e-16)
    assert "differs from" in fd.regeneration_sentence(2e-12)


def test_ranking_figure_and_single_values_take_runs_measured_for_some_claims_only():
    """With the explorer's claims=, a condition measures only the claims reading what it changes (a change of the
    networks' lags: C004-3b alone); the ranking figure draws each condition's claims and single_values skips a run
    without the claim."""
    from types import SimpleNamespace

    from tvtrack.papers.p004_laser_spot_prediction import plots

    est = lambda v: Estimate(v, 0.1, v - 0.2, v + 0.2, 15)  # noqa: E731
    ranks = {"C004-3": {b: est(2.0) for b in CLASSICAL}, "C004-3b": {b: est(0.5) for b in study.NETWORKS}}

    def run(stage, changed, outputs):
        return SimpleNamespace(stage=stage, config=dict(DEFAULT, **changed), outputs=outputs, changed=lambda d: changed)

    runs = [
        run("single", {"network lags": 10}, {"C004-3b": ranks["C004-3b"]}),
        run("single", {"spline": "natural cubic"}, {"C004-3": ranks["C004-3"]}),
        run("single", {"amplitude": 2.0}, {**ranks, "C004-2": est(3.0)}),
        run("single", {"amplitude": 0.5}, {"C004-3": ranks["C004-3"]}),  # no C004-2: skipped
    ]
    ex = SimpleNamespace(runs=runs, default=dict(DEFAULT), measured=lambda c: ranks.get(c, est(1.5)))
    fig = plots.ranking_figure(ex)
    assert len(fig.axes[0].get_yticklabels()) == 5  # the default and the four conditions
    dots = {c.get_label(): len(c[0].get_xdata()) for c in fig.axes[0].containers}
    assert dots == {**{b: 4 for b in CLASSICAL}, **{b: 3 for b in study.NETWORKS}}  # rows measured for the claim
    assert side.single_values(ex, "C004-2", "amplitude") == {1.0: est(1.5), 2.0: est(3.0)}
