"""The no-manoeuvre runs that C001-2 and C001-3 share: C001-3 reads their first frames only, and those frames'
errors do not depend on how long C001-2 needs the runs to be."""

import numpy as np
import pytest

from tvtrack.papers.p001_maneuver_occlusion_kf.scenario import NOISE_MODELS, prefix_stable_measurements


@pytest.mark.parametrize("model", NOISE_MODELS)
def test_the_first_frames_are_the_same_numbers_whatever_the_length(model):
    truth = 0.3 * np.arange(400.0)
    short = prefix_stable_measurements(truth[:300], model, 50, np.random.default_rng(5), 1.0)
    long = prefix_stable_measurements(truth, model, 50, np.random.default_rng(5), 1.0)
    assert short.shape == (50, 300) and long.shape == (50, 400)
    np.testing.assert_array_equal(long[:, :300], short)


@pytest.mark.parametrize("model", NOISE_MODELS)
def test_the_errors_have_the_models_rms_and_no_common_part(model):
    truth = np.zeros(2000)
    z = prefix_stable_measurements(truth, model, 400, np.random.default_rng(6), 1.5)
    rms = np.sqrt(np.mean(z**2))
    # every model is scaled to an RMS of sigma = 1.5 elements (the Student t's heavy tail: a looser bound)
    assert rms == pytest.approx(1.5, rel=0.08 if model.startswith("Student") else 0.01)
    # runs are independent of each other: the mean over runs at each frame has variance sigma^2 / runs
    assert np.var(z.mean(axis=0)) == pytest.approx(1.5**2 / 400, rel=0.2 if model.startswith("Student") else 0.1)


def test_lag_one_correlation_of_the_ar1_model_is_one_half_and_zero_otherwise():
    z = prefix_stable_measurements(np.zeros(3000), "AR(1), rho = 0.5", 200, np.random.default_rng(7), 1.0)
    r1 = np.mean(z[:, 1:] * z[:, :-1]) / np.mean(z**2)
    assert r1 == pytest.approx(0.5, abs=0.01)
    w = prefix_stable_measurements(np.zeros(3000), "white Gaussian", 200, np.random.default_rng(7), 1.0)
    assert abs(np.mean(w[:, 1:] * w[:, :-1])) < 0.01
