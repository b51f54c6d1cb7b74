"""Notebook 004: the floor N_f as a fixed-gain alpha-beta-gamma filter (gains, noise reduction)."""

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import predictors as pr
from tvtrack.filters.alphabeta import closed_form_gains, steady_state_covariance
from tvtrack.filters.polynomial import growing_memory_filter, taylor_transition

FLOORS = [3, 4, 5, 7, 10, 15, 30, 100, 200]


def floor_variance_reduction(floor_memory):
    """Variance reduction ratios (filtered, one-step predicted) of the growing-memory filter frozen at ``N_f``
    (order 2), as rational functions of ``N = N_f`` (Brookner 1998, Sect. 1.3, with the gains of
    :func:`closed_form_gains` substituted): ``3(51N^4 - 264N^3 + 478N^2 - 373N + 114) / D`` and
    ``3(51N^4 + 60N^3 - 8N^2 + 5N + 6) / D``, ``D = (2N - 1)(N^2 - N - 3)(11N^2 - 11N - 6)``; both
    ``-> 153 / (22 N)``."""
    N = np.asarray(floor_memory, dtype=float)
    D = (2 * N - 1) * (N**2 - N - 3) * (11 * N**2 - 11 * N - 6)
    return (
        3 * (51 * N**4 - 264 * N**3 + 478 * N**2 - 373 * N + 114) / D,
        3 * (51 * N**4 + 60 * N**3 - 8 * N**2 + 5 * N + 6) / D,
    )


@pytest.mark.parametrize("floor", [4, 10, 30])
def test_floored_filter_is_filterpys_ghk_filter_with_the_mapped_gains(floor):
    """After N_f samples the floored growing-memory filter runs exactly as filterpy's GHKFilter with
    g = g_1, h = g_2, k = g_3 / 2 of the frozen gains, started from the floored state."""
    gh = pytest.importorskip("filterpy.gh")
    rng = np.random.default_rng(floor)
    z = np.cumsum(np.cumsum(rng.normal(0, 0.05, 300))) + rng.normal(0, 0.3, 300)
    states = growing_memory_filter(z, 2, floor)
    K = closed_form_gains(2, np.array([floor]))[0]
    x0 = states[floor - 1]
    f = gh.GHKFilter(x0[0], x0[1], x0[2], 1.0, K[0], K[1], K[2] / 2)
    ref = np.array([f.update(zt)[0] for zt in z[floor:]])
    np.testing.assert_allclose(states[floor:, 0], ref, rtol=1e-10, atol=1e-9)
    np.testing.assert_allclose(
        pr.growing_memory_forecast(z, 1, 2, floor)[floor:],
        states[floor:, 0] + states[floor:, 1] + states[floor:, 2] / 2,
        rtol=1e-9,
    )


def test_variance_reduction_closed_forms_equal_the_lyapunov_solution():
    F = taylor_transition(2)
    filtered, predicted = floor_variance_reduction(FLOORS)
    for K, vf, vp in zip(closed_form_gains(2, np.array(FLOORS)), filtered, predicted):
        P = steady_state_covariance(K, 1.0)
        assert vf == pytest.approx(P[0, 0], rel=1e-10)
        assert vp == pytest.approx((F @ P @ F.T)[0, 0], rel=1e-10)
    assert filtered[0] == pytest.approx(1.0) and predicted[0] == pytest.approx(19.0)  # N_f = 3: z_n itself; FD3: 1+9+9
    np.testing.assert_allclose(np.array(floor_variance_reduction(1e6)) * 1e6, 153 / 22, rtol=1e-5)


@pytest.mark.parametrize("floor", [5, 20])
def test_monte_carlo_variance_of_the_floored_forecast(floor):
    """Unit white noise through the floored filter: the variance of its one-step forecast at a late
    frame is vrr_predicted (20000 series; 5 % is > 7 standard errors)."""
    rng = np.random.default_rng(100 + floor)
    z = rng.standard_normal((20000, 40 * floor))
    fc = pr.growing_memory_forecast(z, 1, 2, floor)[:, -1]
    _, vp = floor_variance_reduction(floor)
    assert np.var(fc) == pytest.approx(vp, rel=0.05)
