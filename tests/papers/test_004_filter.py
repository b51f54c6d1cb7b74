"""Notebook 004: the growing-memory polynomial filter against independent least squares (C004-4,
C004-5, C004-7) and the gain floors."""

from math import factorial

import numpy as np
import pytest

from tvtrack.filters.polynomial import growing_memory_filter, growing_memory_gains, predict_ahead, taylor_transition
from tvtrack.papers.p004_laser_spot_prediction.predictors import (
    g1_floor_filter,
    g1_floor_gains,
    growing_memory_forecast,
)
from tvtrack.papers.p004_laser_spot_prediction.predictors import batch_least_squares_states as pr_batch


def _batch_ls(z_present, t_present, t_now, order):
    """Independent batch LS (eq. (4)) of the Taylor state at t_now from samples at t_present."""
    lag = t_now - np.asarray(t_present, dtype=float)
    H = np.stack([(-lag) ** k / factorial(k) for k in range(order + 1)], axis=1)
    return np.linalg.lstsq(H, z_present, rcond=None)[0]


@pytest.mark.parametrize("order", [1, 2, 3])
def test_recursion_equals_batch_least_squares(order):
    rng = np.random.default_rng(order)
    T = 120
    z = 40 + np.cumsum(rng.normal(0, 1, T)) + rng.normal(0, 0.3, T)
    states = growing_memory_filter(z, order, None)
    for n in range(order, T):
        ref = _batch_ls(z[: n + 1], np.arange(n + 1), n, order)
        rel = np.abs(states[n] - ref) / np.maximum(np.abs(ref), 1.0)
        assert rel.max() <= 1e-9, (n, rel.max())


def test_first_estimate_at_three_samples_and_exact_quadratic():
    """C004-7: the first estimate is the quadratic through the first three samples."""
    z = np.array([1.0, 4.0, 9.0, 16.0, 25.0])  # (t+1)^2
    s = growing_memory_filter(z, 2, None)
    assert np.all(np.isnan(s[:2])) and np.all(np.isfinite(s[2:]))
    np.testing.assert_allclose(s[2], [9.0, 6.0, 2.0], atol=1e-12)  # x, x', x'' at t = 2
    np.testing.assert_allclose(predict_ahead(s[2], 2), 25.0, atol=1e-12)


def test_closed_form_gains_and_nine_over_n():
    """C004-5: g_N closed form, monotone, g_N1 -> 9/N."""
    N = np.arange(1, 401, dtype=float)
    closed = (
        np.stack([3 * (3 * N**2 - 3 * N + 2), 18 * (2 * N - 1), 60 + 0 * N], axis=1) / (N * (N + 1) * (N + 2))[:, None]
    )
    g = growing_memory_gains(2, 400)
    np.testing.assert_allclose(g[2:], closed[2:], rtol=1e-10)
    assert np.all(np.diff(g[2:, 0]) < 0)
    assert abs(g[-1, 0] * 400 / 9 - 1) < 0.01


def test_filtered_variance_equals_sigma2_g1():
    """C004-5: on an exact quadratic plus white noise, Var(x_est at N) = sigma^2 g_N1."""
    rng = np.random.default_rng(11)
    n_mc, T, sigma = 4000, 40, 0.7
    t = np.arange(T)
    quad = 3 - 0.2 * t + 0.05 * t**2
    est = growing_memory_filter(quad + sigma * rng.standard_normal((n_mc, T)), 2, None)[..., 0]
    g1 = growing_memory_gains(2, T)[:, 0]
    for N in (3, 10, 40):
        v = np.mean((est[:, N - 1] - quad[N - 1]) ** 2)
        # the mean of n_mc squared normals has relative sd sqrt(2/n_mc) = 0.022
        assert abs(v / (sigma**2 * g1[N - 1]) - 1) < 5 * np.sqrt(2 / n_mc)


def test_forward_transition_is_inverse_of_backward():
    """Sign correction of eq. (5), derived here: F_{+1} = F_{-1}^{-1}."""
    np.testing.assert_allclose(taylor_transition(2, 1.0) @ taylor_transition(2, -1.0), np.eye(3), atol=1e-15)


@pytest.mark.parametrize("nf", [3, 5, 10, 100])
def test_frozen_floor_closed_loop_is_stable(nf):
    g = growing_memory_gains(2, nf)[-1]
    F = taylor_transition(2)
    A = (np.eye(3) - np.outer(g, [1, 0, 0])) @ F
    assert np.max(np.abs(np.linalg.eigvals(A))) < 1


def test_floor_tracks_a_changing_quadratic_better_than_no_floor():
    """C004-6 in miniature: a sine is quadratic only locally."""
    t = np.arange(600)
    z = 20 * np.sin(2 * np.pi * t / 150)
    e = lambda f: np.sqrt(np.nanmean((f[300:-1] - z[301:]) ** 2))
    assert e(growing_memory_forecast(z, 1, 2, None)) > 10 * e(growing_memory_forecast(z, 1, 2, 10))


def test_variant_floor_matches_core_before_the_floor_and_keeps_g1():
    rng = np.random.default_rng(2)
    z = np.cumsum(rng.normal(0, 1, (3, 200)), axis=-1)
    g1min = growing_memory_gains(2, 20)[-1, 0]
    var = g1_floor_filter(z, g1min)
    core = growing_memory_filter(z, 2, None)
    np.testing.assert_allclose(var[:, :20], core[:, :20], rtol=1e-9, atol=1e-9)
    gains = g1_floor_gains(2, 200, g1min)
    assert np.all(gains[19:, 0] >= g1min - 1e-15)
    np.testing.assert_allclose(
        gains[50] / gains[50, 0], growing_memory_gains(2, 51)[-1] / growing_memory_gains(2, 51)[-1, 0]
    )


def test_variant_rejects_bad_input():
    with pytest.raises(ValueError, match="g1_min"):
        g1_floor_filter(np.arange(10.0), 1.5)
    with pytest.raises(ValueError, match="NaN"):
        g1_floor_filter(np.array([1.0, np.nan, 2, 3, 4]), 0.5)


@pytest.mark.parametrize("order, nf", [(1, 2), (2, 3), (2, 10), (3, 30)])
def test_fast_floored_forecast_equals_core_filter(order, nf):
    rng = np.random.default_rng(order * 100 + nf)
    z = np.cumsum(rng.normal(0, 1, (4, 2, 300)), axis=-1)
    for steps in (1, 4):
        fast = growing_memory_forecast(z, steps, order, nf)
        core = predict_ahead(growing_memory_filter(z, order, nf), steps)
        np.testing.assert_array_equal(np.isnan(fast), np.isnan(core))
        np.testing.assert_allclose(fast, core, rtol=1e-9, atol=1e-9)


def test_batch_least_squares_states_exact_on_a_quadratic():
    t = np.arange(12.0)
    z = 3.0 - 0.5 * t + 0.1 * t**2
    states = pr_batch(z, 2)
    assert np.all(np.isnan(states[:2]))
    np.testing.assert_allclose(states[2:, 0], z[2:], atol=1e-10)
    np.testing.assert_allclose(states[2:, 1], -0.5 + 0.2 * t[2:], atol=1e-10)  # px per sample
    np.testing.assert_allclose(states[2:, 2], 0.2, atol=1e-10)
    noisy = z + np.random.default_rng(1).normal(0, 0.5, z.size)
    np.testing.assert_allclose(pr_batch(noisy, 2)[2:], growing_memory_filter(noisy, 2, None)[2:], rtol=1e-9, atol=1e-9)
    with pytest.raises(ValueError, match="'z'"):
        pr_batch(np.array([1.0, np.inf, 3.0, 4.0]), 2)  # NaN is a lost sample (skipped); inf is an error
