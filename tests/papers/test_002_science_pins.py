"""Pins of paper 002's science that earlier tests let through.

Each test names the planted bug ("mutation") it kills; each was seen failing with the bug planted:

* the MAP prior without its sigma^2 factor (``prior = (theta0, 1 / sd_x^2, 1 / sd_v^2)`` in
  ``em.unified_location_em``): invisible where sigma_px = 1, so the test runs at sigma_px = 2.5;
* the centre-of-region gate shrunk from 3 x 3 to 1 x 1 pixels (``study.centre_gate_half_px`` 1.5 -> 0.5, or
  ``two_stage.centre_of_region_marks`` rounding the gate down);
* marks that are not the per-frame maximum-likelihood positions (e.g. the per-frame EM stopped after one step,
  or fed with all frames at once);
* the MAP comparison's information: the MAP-ULA must not be given the velocity its two-stage twin lacks.
"""

from dataclasses import replace

import numpy as np
import pytest

from tvtrack.papers.p002_unified_location_em.em import log_likelihood, unified_location_em
from tvtrack.papers.p002_unified_location_em.em_steps import pixel_entries
from tvtrack.papers.p002_unified_location_em.model import frame_times, mixture_weights, scene_batches, scene_geometry
from tvtrack.papers.p002_unified_location_em.simulation import Config, centre_gate_half_px, map_prior_sd, run_config
from tvtrack.papers.p002_unified_location_em.sim_config import CANONICAL_SETTINGS
from tvtrack.papers.p002_unified_location_em.two_stage import centre_of_region_marks, em_marks, propagate


def _scene(seed, n, q=2, T=5, d=2.0, pix=0.4, m=40, rho=0.01, dsd=0.5, vsd=0.0):
    rng = np.random.default_rng(seed)
    g = scene_geometry(q, T, d, pix)
    noise = rho / g.sigma_px**2
    b = next(scene_batches(rng, g, n, T, m, noise, dsd * g.sigma_px, vsd * g.sigma_px, batch_size=n))
    p, p0 = mixture_weights(m, noise, g.n_pixels, q)
    return g, b, p, p0


def _numeric_gradient(f, theta, h=1e-4):
    grad = np.zeros_like(theta)
    for idx in np.ndindex(theta.shape[1:]):
        e = np.zeros_like(theta)
        e[(slice(None),) + idx] = h
        grad[(slice(None),) + idx] = (f(theta + e) - f(theta - e)) / (2 * h)
    return grad


def test_map_ula_is_a_stationary_point_of_the_log_posterior_at_sigma_px_not_one():
    """Kills: the MAP prior without its sigma^2 factor. The fixed point of MAP-EM must zero the gradient of
    log L + log prior, the prior written here independently: -sum (x - x_d)^2 / (2 sd_x^2) - sum (V - V_d)^2 /
    (2 sd_v^2). Without the factor the prior weighs sigma_px^2 = 6.25 times too much or too little."""
    g, b, p, p0 = _scene(3, 4, pix=0.4)  # sigma_px = 2.5
    assert g.sigma_px == pytest.approx(2.5)
    times = frame_times(5)
    sd_x, sd_v = 0.3 * g.sigma_px, 0.05 * g.sigma_px
    res = unified_location_em(
        pixel_entries(b.counts), b.designation, g.sigma_px, p, p0, tol_px=1e-11, max_iter=20000, prior_sd=(sd_x, sd_v)
    )
    assert res.converged.all()

    def log_post(th):
        lp = -0.5 * (((th[..., :2] - b.designation[..., :2]) / sd_x) ** 2).sum(axis=(1, 2))
        lp -= 0.5 * (((th[..., 2:] - b.designation[..., 2:]) / sd_v) ** 2).sum(axis=(1, 2))
        return log_likelihood(b.counts, th, times, g.sigma_px, p, p0) + lp

    grad = _numeric_gradient(log_post, res.theta)
    prior_grad = np.concatenate(
        [
            (res.theta[..., :2] - b.designation[..., :2]) / sd_x**2,
            (res.theta[..., 2:] - b.designation[..., 2:]) / sd_v**2,
        ],
        axis=-1,
    )
    # the prior pulls with a force of order 1 or more; at the MAP the likelihood balances it exactly
    assert np.abs(prior_grad).max() > 1.0
    assert np.abs(grad).max() < 1e-3 * np.abs(prior_grad).max()


def test_centre_of_region_gate_is_three_pixels_wide_with_coarse_pixels():
    """Kills: the gate shrunk from 3 x 3 to 1 x 1. At Delta = 5 sigma the gate half-size is 1.5 px, and a photon
    one pixel off the predicted pixel moves the centroid half a pixel; a 1 x 1 gate would return the pixel centre."""
    assert centre_gate_half_px(3.0, 0.2) == 1.5  # Delta = 5 sigma: 3 sigma = 0.6 px < 1.5 px
    assert centre_gate_half_px(3.0, 1.0) == 3.0  # Delta = sigma: 3 sigma = 3 px
    counts = np.zeros((1, 1, 11, 11))
    counts[0, 0, 5, 5] = 1.0
    counts[0, 0, 5, 6] = 1.0  # right neighbour: inside a 3 x 3 gate
    counts[0, 0, 5, 7] = 5.0  # two pixels right: outside it
    pred = np.array([[[[5.2, 4.9]]]])
    marks = centre_of_region_marks(counts, pred, centre_gate_half_px(3.0, 0.2))
    np.testing.assert_allclose(marks.xy[0, 0, 0], [5.5, 5.0])


def test_centre_of_region_marks_in_the_study_resolve_sub_pixel_motion_with_coarse_pixels():
    """Kills the same mutation where the study uses it: one object, Delta = 5 sigma, 200 photons. With a 3 x 3 gate
    the line fit's x0 error variance is about 0.3 sigma^2 (the centroid's pixel-centre bias); a 1 x 1 gate quantises
    every mark to the pixel centre, Var = Delta^2 / 12 = 2.1 sigma^2."""
    settings = replace(
        CANONICAL_SETTINGS,
        seed=5,
        noise_density=0.0,
        designation_sd_sigma=0.3,
        max_iter=500,
        bic_max_iter=10,
        crb_phases=2,
        n_trials=120,
    )
    cfg = Config(1, 0.0, 5.0, 200, 2, "c", 0.3, None, None, 120, "pin", 0.0)
    res = run_config(settings, cfg)
    var_x0 = res["cr"][:, 0, 0].var(ddof=1)
    assert var_x0 < 1.0, var_x0


def test_marks_are_the_per_frame_maximum_likelihood_positions():
    """Kills: marks that are not each frame's own MLE (one EM step only, all frames pooled, the designation
    returned). Each mark must zero the gradient of its frame's static log-likelihood and beat nearby points."""
    g, b, p, p0 = _scene(11, 3, T=4, d=3.0, pix=1.0, m=30)
    times = frame_times(4)
    mk = em_marks(b.counts, b.designation, times, g.sigma_px, p, p0, tol_px=1e-10, max_iter=20000)
    assert mk.valid.all()
    n, t, q = mk.xy.shape[:3]
    frames = b.counts.reshape(n * t, 1, *b.counts.shape[-2:])
    th = np.zeros((n * t, q, 4))
    th[..., :2] = mk.xy.reshape(n * t, q, 2)

    def ll(x):
        return log_likelihood(frames, x, np.zeros(1), g.sigma_px, p, p0)

    grad = _numeric_gradient(ll, th)[..., :2]
    assert np.abs(grad).max() < 1e-4
    rng = np.random.default_rng(0)
    for _ in range(5):
        step = np.zeros_like(th)
        step[..., :2] = rng.normal(scale=0.05, size=th[..., :2].shape)
        assert (ll(th + step) <= ll(th) + 1e-9).all()
    # and they are not the designation propagated to the frame
    assert np.abs(mk.xy - propagate(b.designation, times)).max() > 0.05


def test_map_comparison_gives_both_algorithms_the_same_velocity_knowledge():
    """The MAP-ULA's velocity prior is free by default (a zero sd pinned it to the true velocity while
    the two-stage fitted its own); with "designated" both get the designated velocity."""
    assert map_prior_sd("free", 0.3, 0.0, 2.0) == (0.6, np.inf)
    assert map_prior_sd("designated", 0.3, 0.05, 2.0) == (0.6, 0.1)
    with pytest.raises(ValueError):
        map_prior_sd("oracle", 0.3, 0.0, 1.0)
    base = replace(
        CANONICAL_SETTINGS, seed=8, designation_sd_sigma=0.3, max_iter=300, bic_max_iter=10, crb_phases=2, n_trials=12
    )
    cfg = Config(2, 2.0, 1.0, 20, 6, "uemk", 0.3, None, None, 12, "pin", 0.0)
    free = run_config(replace(base, velocity_knowledge="free"), cfg)
    known = run_config(replace(base, velocity_knowledge="designated"), cfg)
    # free: the MAP-ULA fits the velocity as the two-stage line does; designated (exact here): the MAP-ULA and the
    # line that keeps the designated velocity ("em_vd", its twin) both have no velocity error
    assert np.abs(free["map"][..., 2:]).max() > 1e-3 and np.abs(free["em"][..., 2:]).max() > 1e-3
    np.testing.assert_allclose(known["map"][..., 2:], 0.0, atol=1e-5)
    np.testing.assert_allclose(known["em_vd"][..., 2:], 0.0, atol=1e-12)
    # the ML ULA told the designated (here exact) velocity keeps it; its positions are then fitted freely
    np.testing.assert_allclose(known["ula_vd"][..., 2:], 0.0, atol=1e-5)
    assert np.abs(known["ula_vd"][..., :2] - known["ula"][..., :2]).max() > 1e-4
