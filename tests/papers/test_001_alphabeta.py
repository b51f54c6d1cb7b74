"""Tests of tvtrack.filters.alphabeta (notebook 001): gain law, batch least squares, Lyapunov statistics."""

import numpy as np
import pytest

from tvtrack.filters.alphabeta import (
    closed_form_gains,
    closed_loop_matrix,
    error_covariance_sequence,
    gain_schedule,
    lagged_covariances,
    scheduled_filter,
    steady_state_covariance,
)
from tvtrack.filters.polynomial import growing_memory_gains, polynomial_observation_row


@pytest.mark.parametrize("order", [1, 2])
def test_schedule_reproduces_batch_least_squares(order):
    rng = np.random.default_rng(11)
    T = 120
    t = np.arange(T)
    z = 5.0 + 3.0 * t - 0.01 * t**2 + 2.0 * rng.standard_normal((4, T))
    states = scheduled_filter(z, gain_schedule(order, 10**6, T), x0=rng.normal(0, 100, (4, order + 1)))
    for k in range(order, T):
        H = polynomial_observation_row(order, k - np.arange(k + 1))  # lags back from sample k
        ls = np.linalg.lstsq(H, z[:, : k + 1].T, rcond=None)[0].T
        np.testing.assert_allclose(states[:, k], ls, rtol=0, atol=1e-9 * max(1.0, np.abs(ls).max()))


@pytest.mark.parametrize("order", [1, 2])
def test_closed_forms_match_core_gains(order):
    n = 500
    core = growing_memory_gains(order, n)[order:]
    np.testing.assert_allclose(closed_form_gains(order, np.arange(order + 1, n + 1)), core, rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(
        closed_form_gains(2, [1, 2, 3, 4]), [[1, 3, 10], [1, 2.25, 2.5], [1, 1.5, 1], [0.95, 1.05, 0.5]], atol=1e-12
    )


def test_schedule_lower_bound_is_a_plateau():
    g = gain_schedule(2, 40, 100)
    assert np.all(np.diff(g[2:40, 0]) < 0)
    np.testing.assert_array_equal(g[40:], np.broadcast_to(g[39], (60, 3)))


def test_lyapunov_matches_kalata_closed_form():
    for kb in (10, 50, 200):
        a, b = gain_schedule(1, kb)[-1]
        P = steady_state_covariance([a, b], 2.0)
        d = a * (4 - 2 * a - b)
        np.testing.assert_allclose(P[0, 0], 4.0 * (2 * a * a + 2 * b - 3 * a * b) / d, rtol=1e-10)
        np.testing.assert_allclose(P[1, 1], 4.0 * 2 * b * b / d, rtol=1e-10)


@pytest.mark.parametrize("order,kb", [(1, 50), (2, 40)])
def test_lyapunov_statistics_match_long_simulation(order, kb):
    K = gain_schedule(order, kb)[-1]
    C = lagged_covariances(K, 1.0, 3)
    rng = np.random.default_rng(5)
    n_runs, burn, T = 400, 30 * kb, 3000
    e = scheduled_filter(rng.standard_normal((n_runs, burn + T)), np.broadcast_to(K, (burn + T, order + 1)))[:, burn:]
    for lag in (0, 1, 3):
        prod = np.einsum("rti,rtj->rij", e[:, lag:], e[:, : T - lag]) / (T - lag)  # per-run estimate of C(lag)
        mean, se = prod.mean(0), prod.std(0, ddof=1) / np.sqrt(n_runs)
        assert np.all(np.abs(mean - C[lag]) <= 4.5 * se + 1e-15), (lag, mean, C[lag], se)


def test_covariance_recursion_matches_monte_carlo_with_switching_and_coast():
    T = 300
    G = np.zeros((T, 3))
    G[:100, :2] = gain_schedule(1, 50, 100)
    G[100:200] = gain_schedule(2, 60, 100)
    # frames 200..299: coast (zero gains)
    P = error_covariance_sequence(G, 1.5)
    rng = np.random.default_rng(3)
    e = scheduled_filter(1.5 * rng.standard_normal((20000, T)), G)
    for t in (99, 150, 299):
        emp = np.cov(e[:, t].T)
        np.testing.assert_allclose(emp, P[t], rtol=0.06, atol=1e-12)


def test_stability_and_bad_input():
    for kb in (3, 10, 100, 1000):
        assert np.max(np.abs(np.linalg.eigvals(closed_loop_matrix(gain_schedule(2, kb)[-1])))) < 1
    with pytest.raises(ValueError, match="order"):
        gain_schedule(3, 10)
    with pytest.raises(ValueError, match="k_bound"):
        gain_schedule(1, 0)
    with pytest.raises(ValueError, match="sigma_eps"):
        steady_state_covariance([0.5, 0.1], 0.0)
    with pytest.raises(ValueError, match="unstable"):
        steady_state_covariance([0.5, 3.0])
