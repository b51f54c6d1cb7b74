"""Innovation-based detectors of notebook 001's benchmark against direct (brute-force) computations."""

import numpy as np
import pytest

from tvtrack.detect.innovation import (
    chi2_window,
    cusum,
    delay_false_alarm_curve,
    glr_velocity_jump,
    normalised_innovations,
    velocity_jump_signature,
)
from tvtrack.filters.alphabeta import gain_schedule, scheduled_filter


def test_normalised_innovations_are_unit_variance_under_no_manoeuvre():
    G = gain_schedule(1, 30, 200)
    rng = np.random.default_rng(0)
    z = 5.0 * np.arange(200) + 2.0 * rng.standard_normal((20000, 200))
    u = normalised_innovations(z, scheduled_filter(z, G), G, 2.0)
    for t in (3, 50, 199):
        assert np.var(u[:, t]) == pytest.approx(1.0, rel=0.04)
        assert abs(np.mean(u[:, t])) < 0.03


def test_chi2_and_cusum_match_direct_loops():
    rng = np.random.default_rng(1)
    u = rng.standard_normal((3, 40))
    c = chi2_window(u, 5)
    assert np.all(np.isnan(c[:, :4]))
    np.testing.assert_allclose(c[:, 10], np.sum(u[:, 6:11] ** 2, axis=1))
    g = cusum(u, 0.5, start=4)
    gp = gm = np.zeros(3)
    for t in range(4, 40):
        gp = np.maximum(0, gp + u[:, t] - 0.5)
        gm = np.maximum(0, gm - u[:, t] - 0.5)
        np.testing.assert_allclose(g[:, t], np.maximum(gp, gm))
    assert np.all(np.isnan(g[:, :4]))


def test_glr_is_the_brute_force_maximum_over_jump_times():
    rng = np.random.default_rng(2)
    rho = rng.standard_normal(6)
    u = rng.standard_normal((2, 30))
    g = glr_velocity_jump(u, rho)
    for t in range(5, 30):
        best = np.zeros(2)
        for d in range(6):
            seg = u[:, t - d : t + 1]
            best = np.maximum(best, (seg @ rho[: d + 1]) ** 2 / np.sum(rho[: d + 1] ** 2))
        np.testing.assert_allclose(g[:, t], best, rtol=1e-12)


def test_signature_is_the_filter_response_to_a_velocity_jump():
    K = gain_schedule(1, 40)[-1]
    rho = velocity_jump_signature(K, 1.0, 10)
    # a long constant-velocity run (steady state, no noise) then a jump of 1 element/frame
    T = 400
    z = np.where(np.arange(T) < 300, 2.0 * np.arange(T), 2.0 * np.arange(T) + (np.arange(T) - 299))
    x = scheduled_filter(z, gain_schedule(1, 40, T))
    u = normalised_innovations(z, x, gain_schedule(1, 40, T), 1.0)
    np.testing.assert_allclose(u[300:310] - u[290:300].mean(), rho, atol=1e-6)
    assert rho[0] > 0 and np.all(np.diff(rho[:3]) > 0)


def test_delay_false_alarm_curve_on_a_known_case():
    rng = np.random.default_rng(3)
    null = rng.standard_normal((4000, 50))
    alt = rng.standard_normal((3000, 60))
    alt[:, 30:] += 4.0  # a large step at the onset 30
    armed = np.ones(50, bool)
    out = delay_false_alarm_curve(alt, null, np.ones(60, bool), armed, 30, [0.05, 0.5], 10.0, 0.5)
    np.testing.assert_allclose(out["per_run_false_alarm"], [0.05, 0.5], atol=0.01)
    assert out["median_delay_s"][0] == 0.0 and out["p_detect_within"][0] > 0.8
    assert out["early_alarm"][1] > out["early_alarm"][0]
    fixed = delay_false_alarm_curve(
        alt, null, np.ones(60, bool), armed, 30, None, 10.0, 0.5, thresholds=out["threshold"]
    )
    np.testing.assert_allclose(fixed["per_run_false_alarm"], out["per_run_false_alarm"])
    with pytest.raises(ValueError, match="targets"):
        delay_false_alarm_curve(alt, null, np.ones(60, bool), armed, 30, [1.5], 10.0, 0.5)
