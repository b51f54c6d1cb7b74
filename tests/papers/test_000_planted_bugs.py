"""Tests of paper 000 that a planted bug in its core algorithm must fail.

Each test names the mutation it kills; each was seen failing with the mutation planted.
"""

import numpy as np
from scipy import special, stats

from tvtrack.papers.p000_dissector_ekf.ekf import run_variant2, variant2_filter
from tvtrack.papers.p000_dissector_ekf.model import (
    GaussMarkovMessage,
    draw_noises,
    scan_at_snr,
    simulate_integrated,
    simulate_two_rates,
)
from tvtrack.papers.p000_dissector_ekf.reference import grid_filter

MSG = GaussMarkovMessage(0.1, 0.15)


def _scan(contrast, psi=20.0, dt=0.05):
    return scan_at_snr(psi, contrast, dt)


def test_grid_likelihood_is_the_gaussian_log_density_up_to_a_constant():
    """Kills: the grid likelihood without its -1/2 log R term. With a signal-dependent R (P = 0.9) the
    log-likelihood over the nodes must differ from the exact Gaussian log density by one constant."""
    scan = _scan(0.9)
    gf = grid_filter(scan, MSG, 0.5, 201)
    z = np.array([0.3, 1.1, -0.2])
    for k in (3, 10, 14):
        mine = gf.log_likelihood(z, k)  # (n_trials, n_points)
        exact = stats.norm.logpdf(
            z[:, None], scan.amplitude * scan.shape(gf.nodes, k), np.sqrt(scan.sample_variance(gf.nodes, k))
        )
        diff = mine - exact
        np.testing.assert_allclose(diff - diff[:, :1], 0.0, atol=1e-9)


def test_grid_prediction_keeps_the_stationary_variance_of_the_message():
    """Kills: a doubled (or otherwise wrong) grid transition variance. Without measurements, the grid filter
    started from the stationary prior N(0, sigma_1^2) must keep it: the exact transition preserves it."""
    scan = _scan(0.5)
    gf = grid_filter(scan, MSG, 0.6, 601)
    out = gf.run(np.full((2, 400), np.nan), 0.0, MSG.sigma**2)
    np.testing.assert_allclose(out.var[:, [0, 100, 399]], MSG.sigma**2, rtol=0.01)
    np.testing.assert_allclose(out.mean, 0.0, atol=1e-9)


def test_updated_noise_reevaluation_redoes_the_update_with_the_noise_at_the_updated_estimate():
    """Kills: the "updated" variant-2 noise (noise_iterations = 1) doing nothing. One update by hand: the
    first pass with R at the prediction, the second from the same prior with R at the first pass's estimate."""
    scan = _scan(0.9)
    d0, x0, z = 0.2, np.array([0.05, -0.1]), np.array([[np.nan, 0.8], [np.nan, 0.1]])
    f1, q1 = MSG.euler(scan.dt)
    xp, dp = f1 * x0, f1**2 * d0 + q1
    h, H = scan.amplitude * scan.shape(xp, 1), scan.amplitude * scan.shape_derivative(xp, 1)

    def update(r):
        gain = dp * H / (H**2 * dp + r)
        return xp + gain * (z[:, 1] - h), dp * r / (H**2 * dp + r)

    first, _ = update(scan.sample_variance(xp, 1))
    second, var2 = update(scan.sample_variance(first, 1))
    est0, _ = run_variant2(variant2_filter(scan, MSG, noise_iterations=0), z, d0, init=x0)
    est1, var1 = run_variant2(variant2_filter(scan, MSG, noise_iterations=1), z, d0, init=x0)
    np.testing.assert_allclose(est0[:, 1], first, rtol=1e-12)
    np.testing.assert_allclose(est1[:, 1], second, rtol=1e-12)
    np.testing.assert_allclose(var1[:, 1], var2, rtol=1e-12)
    assert np.all(np.abs(second - first) > 1e-4)  # the two readings differ here


def test_integrated_truth_is_scored_at_the_interval_centre():
    """Kills: scoring the truth at another time in the sample interval. With no process noise the message decays
    as x0 exp(-alpha t): the truth of sample k must be its value at (k - 1/2) dt (the time the filters' model of
    the sample refers to), or at k dt when asked for the interval end."""
    scan, m, n = _scan(0.5), 5, 30
    noises = draw_noises(np.random.default_rng(3), 4, n, substeps=m)
    noises["w_sub"][:] = 0.0
    k = np.arange(1, n + 1)
    x0 = MSG.sigma * noises["x0"][:, None]
    x, _ = simulate_integrated(scan, MSG, noises)
    np.testing.assert_allclose(x[:, 1:], x0 * np.exp(-MSG.alpha * (k - 0.5) * scan.dt), rtol=1e-12)
    x_end, _ = simulate_integrated(scan, MSG, noises, score_at="interval_end")
    np.testing.assert_allclose(x_end[:, 1:], x0 * np.exp(-MSG.alpha * k * scan.dt), rtol=1e-12)


def test_two_rate_truths_are_scored_at_their_interval_centres():
    """Kills the same mutation in the discretisation check: coarse and fine truths at their own interval centres."""
    scan, factor = _scan(0.5), 4
    d = simulate_two_rates(scan, MSG, factor, np.random.default_rng(5), 3, 6)
    np.testing.assert_allclose(d["t_coarse"][1:], (np.arange(1, 7) - 0.5) * scan.dt)
    np.testing.assert_allclose(d["t_fine"], (np.arange(24) + 0.5) * scan.dt / factor)
    np.testing.assert_array_equal(d["x_fine"], d["x_mid"])
    e = simulate_two_rates(scan, MSG, factor, np.random.default_rng(5), 3, 6, score_at="interval_end")
    np.testing.assert_allclose(e["x_fine"][:, factor - 1 :: factor], e["x_coarse"][:, 1:])
    # the same path: the coarse centre (k - 1/2) dt is the end of fine sample (k - 1) factor + factor/2 - 1
    np.testing.assert_array_equal(d["x_coarse"][:, 1:], e["x_fine"][:, factor // 2 - 1 :: factor])
    assert np.abs(d["x_coarse"][:, 1:] - e["x_coarse"][:, 1:]).min() > 0


def test_integrated_sample_mean_of_a_still_object_is_the_pulse_integral_over_the_interval():
    """Pins an integrated-model number to its closed form: with the object still at x = 0 the mean of sample k is
    (1/dt) int exp(-(t - 1/2)^2 / (2 s^2)) dt over ((k-1) dt, k dt] = s sqrt(pi/2) / dt [erf(b) - erf(a)]."""
    scan, m, n_steps = _scan(0.5), 50, 20
    still = GaussMarkovMessage(1e-12, 0.15)
    noises = draw_noises(np.random.default_rng(1), 1, n_steps, substeps=m)
    noises["xi"][:] = 0.0
    _, y = simulate_integrated(scan, still, noises)
    edges = np.arange(n_steps + 1) * scan.dt - 0.5
    c = 1.0 / (np.sqrt(2.0) * scan.pulse_sigma)
    closed = scan.pulse_sigma * np.sqrt(np.pi / 2) / scan.dt * np.diff(special.erf(c * edges))
    np.testing.assert_allclose(y[0, 1:], closed, rtol=2e-5)
    assert abs(y[0, 10] - 0.9933738) < 1e-6  # interval (0.45, 0.5], ending at the peak


def test_a_seed_reproduces_a_run_and_another_seed_does_not():
    """The seed-reproduction test able to fail: the same seed gives the same run whatever the global NumPy state,
    another seed a different one (a generator ignored, or the global state used, fails here)."""
    scan = _scan(0.5)

    def run(seed):
        noises = draw_noises(np.random.default_rng(seed), 5, 60, substeps=3)
        return run_variant2(variant2_filter(scan, MSG), simulate_integrated(scan, MSG, noises)[1])[0]

    np.random.seed(1)
    a = run(12)
    np.random.seed(2)
    b = run(12)
    np.testing.assert_array_equal(a, b)
    assert np.abs(run(13) - a).max() > 1e-3
