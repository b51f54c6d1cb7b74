"""004's run of the methods on one scene (``study._methods``): what each comparator is handed.

The methods run on the measured series at the configuration's horizon: the paper's growing-memory filter and its
variant at the fixed floor, the classical baselines and the other readings of "spline extrapolation" at the fixed
window and tuned over windows from four samples (a cubic's degree + 1), the optimal predictor of the generator's
own model with the measurement noise of the scene (centroid error and frame jitter are independent, so their
variances add), and the networks on their own random stream. Each part's numbers are the same whichever other
parts run beside it.
"""

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import learned as lm
from tvtrack.papers.p004_laser_spot_prediction import predictors as pr
from tvtrack.papers.p004_laser_spot_prediction import study
from tvtrack.papers.p004_laser_spot_prediction.beam_wander import optimal_wander_forecast
from tvtrack.papers.p004_laser_spot_prediction.prediction_study import (
    PAPER,
    VARIANT,
    compare_methods,
    comparison_setup,
    window_candidates,
)
from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT

SIZE = study.StudySize(
    n_paths=6,
    n_frames=200,
    n_folds=3,
    floor_grid=(3, 5, 10),
    window_grid=(6, 8, 10),
    fixed_floor=7,
    fixed_window=9,
    mlp_hidden_units=3,
    rbf_centres=6,
    train_samples=120,
    lag_grid=(1, 2),
    lag_tuning_samples=60,
)
CONFIG = {**DEFAULT, "horizon": 3, "jitter": 1.0}  # jitter: both noise terms present
SEED = 11
CHEAP = frozenset({"optimal", "variant", "classical"})


@pytest.fixture(scope="module")
def scene():
    return study.study_run(dict(CONFIG), SEED, SIZE)


@pytest.fixture
def cheap(scene):  # per test (0.1 s): a mutation run attributes a module fixture's calls to its first test only
    return study._methods(scene, dict(CONFIG), SEED, parts=CHEAP)


def test_the_horizon_is_the_configurations_and_the_setup_the_sizes():
    s = comparison_setup(CONFIG, SIZE)
    assert (s.steps, s.fixed_floor, s.fixed_window) == (3, 7, 9)
    assert s.steps != comparison_setup(DEFAULT, SIZE).steps  # the configuration moved it


def test_the_paper_s_filter_and_its_variant_run_at_the_fixed_floor_and_the_horizon(scene, cheap):
    s = comparison_setup(CONFIG, SIZE)
    np.testing.assert_array_equal(cheap.fixed_forecasts[PAPER], pr.growing_memory_forecast(scene.z, 3, s.order, 7))
    np.testing.assert_array_equal(cheap.fixed_forecasts[VARIANT], pr.g1_floor_forecast(scene.z, 7, 3, s.order))
    # the floor and the horizon are not interchangeable: the other order gives another forecast
    assert not np.array_equal(cheap.fixed_forecasts[PAPER], pr.growing_memory_forecast(scene.z, 7, s.order, 3))


def test_the_classical_baselines_run_at_the_fixed_window(scene, cheap):
    f = cheap.fixed_forecasts
    np.testing.assert_array_equal(f["cubic spline"], pr.spline_forecast(scene.z, 9, 3))
    np.testing.assert_array_equal(f["linear regression deg 1"], pr.sliding_regression_forecast(scene.z, 9, 1, 3))
    np.testing.assert_array_equal(f["linear regression deg 2"], pr.sliding_regression_forecast(scene.z, 9, 2, 3))
    np.testing.assert_array_equal(f[study.LSQ_CUBIC], pr.sliding_regression_forecast(scene.z, 9, 3, 3))
    np.testing.assert_array_equal(f[study.NATURAL_SPLINE], pr.natural_spline_forecast(scene.z, 9, 3))


@pytest.mark.parametrize("name", ["LSQ_CUBIC", "NATURAL_SPLINE"])
def test_the_spline_readings_are_tuned_over_windows_from_four_samples(scene, cheap, name):
    """Each path's forecast is the one at the window its fold chose, among the windows from 4 (a cubic's degree
    + 1) up to the grid and beyond it while a fold picks the largest."""
    key = getattr(study, name)
    make = {
        "LSQ_CUBIC": lambda L: pr.sliding_regression_forecast(scene.z, L, 3, 3),
        "NATURAL_SPLINE": lambda L: pr.natural_spline_forecast(scene.z, L, 3),
    }[name]
    chosen = np.asarray(cheap.comparison.chosen[key])
    assert chosen.shape == (SIZE.n_paths,)
    tried = set(window_candidates(4, SIZE.window_grid))
    assert tried == {4, 5, 6, 8, 10}
    assert set(chosen.tolist()) <= tried | set(study.WINDOW_EXTENSION)
    for p, w in enumerate(chosen):
        np.testing.assert_array_equal(cheap.forecasts[key][..., p, :, :], make(int(w))[..., p, :, :])


def test_the_spline_readings_are_tuned_on_the_measured_centres_with_the_window_extension(scene, monkeypatch):
    seen = []
    real = study.tuned_forecast

    def spy(candidates, make, z, ref, folds, s, more=()):
        seen.append((candidates, z, ref, folds, s, more))
        return real(candidates, make, z, ref, folds, s, more=more)

    monkeypatch.setattr(study, "tuned_forecast", spy)
    study._methods(scene, dict(CONFIG), SEED, parts={"classical"})
    assert len(seen) == 2  # the least-squares cubic and the natural spline
    for candidates, z, ref, folds, s, more in seen:
        assert candidates == (4, 5, 6, 8, 10) and more == [min(w, scene.z.shape[-1]) for w in study.WINDOW_EXTENSION]
        assert z is scene.z and ref is scene.z_meas and s == comparison_setup(CONFIG, SIZE)
        assert [list(b) for _, b in folds] == [[0, 1], [2, 3], [4, 5]]


def test_the_optimal_predictor_reads_the_sum_of_the_centroid_and_jitter_variances(scene, cheap):
    s = comparison_setup(CONFIG, SIZE)
    noise = scene.centroid_rms**2 + scene.jitter_rms**2
    want = optimal_wander_forecast(scene.z, scene.scene, scene.path_rms, noise, s.steps)
    np.testing.assert_array_equal(cheap.forecasts[study.OPTIMAL], want)
    assert np.all(np.asarray(scene.jitter_rms) > 0) and np.all(np.asarray(scene.centroid_rms) > 0)
    for wrong in (scene.centroid_rms**2, scene.centroid_rms**2 - scene.jitter_rms**2):
        other = optimal_wander_forecast(scene.z, scene.scene, scene.path_rms, np.abs(wrong), s.steps)
        assert not np.array_equal(cheap.forecasts[study.OPTIMAL], other)


def test_each_part_runs_only_when_asked_and_keeps_its_numbers_beside_the_others(scene, cheap):
    alone = study._methods(scene, dict(CONFIG), SEED, parts={"optimal"})
    assert alone.parts == {"optimal"} and cheap.parts == CHEAP
    assert VARIANT not in alone.fixed_forecasts and "cubic spline" not in alone.fixed_forecasts
    assert study.LSQ_CUBIC not in alone.forecasts
    np.testing.assert_array_equal(alone.forecasts[study.OPTIMAL], cheap.forecasts[study.OPTIMAL])
    np.testing.assert_array_equal(alone.fixed_forecasts[PAPER], cheap.fixed_forecasts[PAPER])
    none = study._methods(scene, dict(CONFIG), SEED, parts={"classical"})
    assert study.OPTIMAL not in none.forecasts and VARIANT not in none.fixed_forecasts
    np.testing.assert_array_equal(none.forecasts[study.LSQ_CUBIC], cheap.forecasts[study.LSQ_CUBIC])
    assert none.config == CONFIG and none.config is not CONFIG
    other = {**CONFIG, "horizon": 1}  # the methods' configuration is the run's, not the scene's
    assert study._methods(scene, other, SEED, parts={"optimal"}).config == other and scene.config == CONFIG
    assert [(list(a), list(b)) for a, b in none.folds] == [
        (list(a), list(b)) for a, b in lm.path_folds(SIZE.n_paths, SIZE.n_folds)
    ]


def test_the_networks_draw_from_the_runs_fourth_stream_only(scene):
    """The models' stream (the fourth of :func:`study.run_streams`: traces, jitter, sensor, models, ...): the same
    networks as a comparison handed that stream, others from any other."""
    got = study._methods(scene, dict(CONFIG), SEED, parts={"learned"})
    s = comparison_setup(CONFIG, SIZE)
    folds = lm.path_folds(SIZE.n_paths, SIZE.n_folds)
    streams = study.run_streams(SEED)

    def nets(i):
        cmp = compare_methods(scene.z, scene.z_meas, folds, s, np.random.default_rng(streams[i]), parts={"learned"})
        return {k: v for k, v in cmp.forecasts.items() if k not in (PAPER,)}

    want = nets(3)
    assert set(want) and set(want) <= set(got.forecasts)
    for k, v in want.items():
        np.testing.assert_array_equal(got.forecasts[k], v)
    other = nets(2)
    assert any(not np.array_equal(got.forecasts[k], other[k]) for k in want)


def test_a_series_the_spot_was_never_measured_on_is_refused(scene):
    z = scene.z.copy()
    z[..., 0, 0, 5] = np.nan
    with pytest.raises(ValueError, match="never measured"):
        study._methods(study.replace(scene, z=z), dict(CONFIG), SEED, parts={"optimal"})


def test_a_scene_rendered_in_a_worker_is_the_one_rendered_here():
    from tvtrack.papers.p004_laser_spot_prediction import shipping

    here = study.study_run(dict(CONFIG), SEED, SIZE)
    there = shipping.loads(study._scene_shipped(dict(CONFIG), SEED, SIZE))
    np.testing.assert_array_equal(there.z, here.z)
    np.testing.assert_array_equal(there.z_meas, here.z_meas)
    assert there.config == CONFIG and there.size == SIZE
    other = shipping.loads(study._scene_shipped(dict(CONFIG), SEED + 1, SIZE))
    assert not np.array_equal(other.z, here.z)
