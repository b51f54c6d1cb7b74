"""Notebook 004: the floor N_f as a fixed-gain alpha-beta-gamma filter (gains, noise reduction, bandwidth)."""

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import predictors as pr
from tvtrack.filters.alphabeta import (
    abg_variance_reduction,
    closed_form_gains,
    floor_bandwidth_map,
    floor_variance_reduction,
    steady_state_covariance,
)
from tvtrack.filters.polynomial import growing_memory_filter, taylor_transition

FLOORS = [3, 4, 5, 7, 10, 15, 30, 100, 200]


@pytest.mark.parametrize("floor", [4, 10, 30])
def test_floored_filter_is_filterpys_ghk_filter_with_the_mapped_gains(floor):
    """After N_f samples the floored growing-memory filter runs exactly as filterpy's GHKFilter with
    g = alpha, h = beta, k = gamma of floor_bandwidth_map, started from the floored state."""
    gh = pytest.importorskip("filterpy.gh")
    rng = np.random.default_rng(floor)
    z = np.cumsum(np.cumsum(rng.normal(0, 0.05, 300))) + rng.normal(0, 0.3, 300)
    states = growing_memory_filter(z, 2, floor)
    m = floor_bandwidth_map([floor], 25.0)
    x0 = states[floor - 1]
    f = gh.GHKFilter(x0[0], x0[1], x0[2], 1.0, m["alpha"][0], m["beta"][0], m["gamma"][0])
    ref = np.array([f.update(zt)[0] for zt in z[floor:]])
    np.testing.assert_allclose(states[floor:, 0], ref, rtol=1e-10, atol=1e-9)
    np.testing.assert_allclose(
        pr.growing_memory_forecast(z, 1, 2, floor)[floor:],
        states[floor:, 0] + states[floor:, 1] + states[floor:, 2] / 2,
        rtol=1e-9,
    )


def test_variance_reduction_closed_forms_equal_the_lyapunov_solution():
    F = taylor_transition(2)
    gains = np.vstack(
        [closed_form_gains(2, np.array(FLOORS)), pr.fading_memory_gains(0.5), pr.fading_memory_gains(0.9)]
    )
    filtered, predicted = abg_variance_reduction(gains)
    for K, vf, vp in zip(gains, filtered, predicted):
        P = steady_state_covariance(K, 1.0)
        assert vf == pytest.approx(P[0, 0], rel=1e-10)
        assert vp == pytest.approx((F @ P @ F.T)[0, 0], rel=1e-10)
    assert filtered[0] == pytest.approx(1.0) and predicted[0] == pytest.approx(19.0)  # N_f = 3: z_n itself; FD3: 1+9+9


def test_rational_functions_of_the_floor_and_their_limit():
    N = np.arange(3, 400)
    np.testing.assert_allclose(
        np.stack(floor_variance_reduction(N)), np.stack(abg_variance_reduction(closed_form_gains(2, N))), rtol=1e-10
    )
    big = floor_variance_reduction(1e6)
    np.testing.assert_allclose(np.array(big) * 1e6, 153 / 22, rtol=1e-5)


def test_equivalent_memory_and_bandwidth():
    m = floor_bandwidth_map(FLOORS, 25.0)
    np.testing.assert_allclose(closed_form_gains(2, m["equivalent_memory"])[:, 0], m["vrr_filtered"], rtol=1e-9)
    assert m["equivalent_memory"][0] == pytest.approx(3.0)
    assert m["equivalent_memory"][-1] / FLOORS[-1] == pytest.approx(9 * 22 / 153, rel=0.02)
    np.testing.assert_allclose(m["noise_bandwidth_hz"], m["vrr_filtered"] * 12.5)
    assert m["noise_bandwidth_hz"][0] == pytest.approx(12.5)  # alpha = 1 passes everything up to Nyquist
    assert np.all(np.diff(m["noise_bandwidth_hz"]) < 0)


@pytest.mark.parametrize("floor", [5, 20])
def test_monte_carlo_variance_of_the_floored_forecast(floor):
    """Unit white noise through the floored filter: the variance of its one-step forecast at a late
    frame is vrr_predicted (20000 series; 5 % is > 7 standard errors)."""
    rng = np.random.default_rng(100 + floor)
    z = rng.standard_normal((20000, 40 * floor))
    fc = pr.growing_memory_forecast(z, 1, 2, floor)[:, -1]
    _, vp = floor_variance_reduction(floor)
    assert np.var(fc) == pytest.approx(vp, rel=0.05)
