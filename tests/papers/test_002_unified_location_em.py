"""Tests for notebook 002: the photon-counting scene, the unified location EM, the two-stage
baseline and the Poisson CRB (Savanevich 1999)."""

import numpy as np
import pytest
from scipy import stats

from tvtrack.bounds.poisson_crb import crb_linear_motion, fisher_linear_motion, position_crb_sum
from tvtrack.papers.p002_unified_location_em.em import (
    log_likelihood,
    match_labels,
    responsibility_maps,
    unified_location_em,
)
from tvtrack.papers.p002_unified_location_em.em_steps import pixel_entries
from tvtrack.papers.p002_unified_location_em.two_stage import (
    Marks,
    associate,
    associate_by_lines,
    centre_of_region_marks,
    em_marks,
    fit_lines,
    moment_starts,
    propagate,
)
from tvtrack.papers.p002_unified_location_em.model import (
    draw_truth,
    frame_times,
    mixture_weights,
    pixel_probabilities,
    scene_batches,
    scene_geometry,
    simulate_counts,
)


def expected_counts(theta, times, shape, sigma_px, photons: float, noise_per_pixel: float) -> np.ndarray:
    """Expected photon counts ``m sum_j F_j + b`` per pixel, shape (..., T, rows, cols): the mean the simulated
    counts must reach."""
    return photons * pixel_probabilities(theta, times, shape, sigma_px).sum(axis=-4) + noise_per_pixel


def _batch(seed, n, q=2, T=5, d=3.0, pix=1.0, m=20, rho=0.01, dsd=0.3, model="fixed"):
    rng = np.random.default_rng(seed)
    g = scene_geometry(q, T, d, pix)
    noise = rho / g.sigma_px**2  # photons per sigma^2 -> per pixel
    b = next(scene_batches(rng, g, n, T, m, noise, dsd * g.sigma_px, photon_model=model, batch_size=n))
    p, p0 = mixture_weights(m, noise, g.n_pixels, q)
    return g, b, p, p0, noise


# -- scene -------------------------------------------------------------------------------------


def test_pixel_probabilities_sum_to_in_frame_psf_mass():
    theta = np.array([[[3.2, 4.7, 0.5, -0.3], [-1.0, 2.0, 0.4, 0.9]]])  # object 2 starts outside
    times = frame_times(6)
    shape, s = (9, 11), 1.3
    F = pixel_probabilities(theta, times, shape, s)  # (1, Q, T, R, C)
    mux = theta[0, :, None, 0] + theta[0, :, None, 2] * times
    muy = theta[0, :, None, 1] + theta[0, :, None, 3] * times
    mass = (stats.norm.cdf(shape[1] - 0.5, mux, s) - stats.norm.cdf(-0.5, mux, s)) * (
        stats.norm.cdf(shape[0] - 0.5, muy, s) - stats.norm.cdf(-0.5, muy, s)
    )
    np.testing.assert_allclose(F.sum(axis=(-1, -2))[0], mass, rtol=1e-12, atol=1e-14)
    assert mass.min() < 0.9  # the case is non-trivial


def test_counts_match_expectation_and_seed_reproduces():
    g = scene_geometry(2, 4, 2.0, 1.0)
    rng = np.random.default_rng(3)
    truth = draw_truth(rng, 4000, g)
    truth[:] = truth[0]
    times = frame_times(4)
    for model in ("fixed", "poisson"):
        c = simulate_counts(np.random.default_rng(5), truth, times, g.shape, g.sigma_px, 20, 0.05, model)
        lam = expected_counts(truth[0], times, g.shape, g.sigma_px, 20, 0.05)
        se = np.sqrt(lam / len(truth)) + 1e-3
        assert np.all(np.abs(c.mean(axis=0) - lam) < 5 * se)
        c2 = simulate_counts(np.random.default_rng(5), truth, times, g.shape, g.sigma_px, 20, 0.05, model)
        np.testing.assert_array_equal(c, c2)
    # fixed photon numbers: each frame holds exactly Q m target photons when noise is off
    c = simulate_counts(rng, truth[:10], times, g.shape, g.sigma_px, 20, 0.0, "fixed")
    assert np.all(c.sum(axis=(-1, -2)) == 40)


def test_bad_scene_input_raises():
    with pytest.raises(ValueError, match="separation_sigma"):
        scene_geometry(2, 5, -1.0, 1.0)
    with pytest.raises(ValueError, match="photon_model"):
        simulate_counts(np.random.default_rng(0), np.zeros((1, 1, 4)), frame_times(2), (5, 5), 1.0, 5, 0.0, "gauss")


# -- ULA -----------------------------------------------------------------------------------------


def test_single_object_no_noise_fine_pixels_equals_photon_least_squares():
    """Q = 1, no noise, pixels 1/40 of sigma: the ULA is the LS line through the photons."""
    rng = np.random.default_rng(11)
    n, T, m, s = 20, 6, 30, 40.0
    times = frame_times(T)
    truth = np.zeros((n, 1, 4))
    truth[..., 0] = 260 + rng.uniform(0, 1, (n, 1))
    truth[..., 1] = 250 + rng.uniform(0, 1, (n, 1))
    truth[..., 2:] = [3.0, -2.0]
    shape = (500, 540)
    pos = truth[:, None, 0, :2] + times[None, :, None] * truth[:, None, 0, 2:]  # (n, T, 2)
    photons = pos[:, :, None] + s * rng.normal(size=(n, T, m, 2))
    u = np.floor(photons + 0.5).astype(int)
    counts = np.zeros((n, T) + shape, dtype=np.int32)
    ni, li, _ = np.indices((n, T, m))
    np.add.at(counts, (ni, li, u[..., 1], u[..., 0]), 1)
    # independent LS fit of the true photon positions (same design for both axes)
    X = np.column_stack([np.ones(T * m), np.repeat(times, m)])
    coef = np.linalg.lstsq(X, photons.reshape(n, T * m, 2).transpose(1, 0, 2).reshape(T * m, -1), rcond=None)[
        0
    ].reshape(2, n, 2)  # (x0/V, n, axis)
    ls = np.concatenate([coef[0], coef[1]], axis=-1)  # (n, 4)
    res = unified_location_em(pixel_entries(counts), truth + [1.0, -1.0, 0.1, 0.1], s, [1.0], 0.0, tol_px=1e-9)
    assert res.converged.all() and not res.failed.any()
    # pixel quantisation moves each photon by at most 1/2 px: the fits agree to ~0.2 px = 0.005 sigma
    assert np.abs(res.theta[:, 0, :2] - ls[:, :2]).max() < 0.01 * s
    assert np.abs(res.theta[:, 0, 2:] - ls[:, 2:]).max() < 0.01 * s / T
    # at the fixed point the estimate is exactly the count-weighted LS line through the local
    # means (truncated-normal means from scipy, an independent implementation of (U6))
    th = res.theta[0, 0]
    nz = np.nonzero(counts[0])
    w = counts[0][nz]
    mu_x = th[0] + th[2] * times[nz[0]]
    mhat = stats.truncnorm.mean((nz[2] - 0.5 - mu_x) / s, (nz[2] + 0.5 - mu_x) / s, loc=mu_x, scale=s)
    Xw = np.column_stack([np.ones(len(w)), times[nz[0]]]) * np.sqrt(w)[:, None]
    x0v = np.linalg.lstsq(Xw, mhat * np.sqrt(w), rcond=None)[0]
    np.testing.assert_allclose(x0v, th[[0, 2]], atol=1e-6)


def test_log_likelihood_never_decreases():
    g, b, p, p0, noise = _batch(2, 30, d=1.0, pix=1.0, m=15, rho=0.05, dsd=1.0)
    ent = pixel_entries(b.counts)
    res = unified_location_em(ent, b.designation, g.sigma_px, p, p0, tol_px=1e-7, max_iter=400, history=True)
    L = np.array(res.history_loglik)  # (iters, N)
    steps = np.diff(L, axis=0)
    assert steps.min() > -1e-9 * np.abs(L).max()
    # the sparse log-likelihood equals the dense eq. (3) objective
    dense = log_likelihood(b.counts, res.theta, frame_times(5), g.sigma_px, p, p0)
    np.testing.assert_allclose(res.loglik, dense, rtol=1e-10)
    # with p and sigma estimated too (ECM): still monotone
    res2 = unified_location_em(
        ent,
        b.designation,
        g.sigma_px * 1.3,
        p,
        p0,
        tol_px=1e-7,
        max_iter=300,
        history=True,
        estimate_weights=True,
        estimate_sigma=True,
    )
    L2 = np.array(res2.history_loglik)
    assert np.diff(L2, axis=0).min() > -1e-9 * np.abs(L2).max()


def test_squarem_reaches_the_same_fixed_point_in_fewer_steps():
    g, b, p, p0, _ = _batch(4, 60, d=1.5, pix=1.0, m=20)
    ent = pixel_entries(b.counts)
    plain = unified_location_em(ent, b.designation, g.sigma_px, p, p0, tol_px=1e-8)
    fast = unified_location_em(ent, b.designation, g.sigma_px, p, p0, tol_px=1e-8, accelerate="squarem")
    ok = plain.converged & fast.converged
    assert ok.mean() > 0.9
    np.testing.assert_allclose(fast.theta[ok], plain.theta[ok], atol=1e-4)
    # trial by trial: the same likelihood at the end, in fewer EM steps on average
    np.testing.assert_allclose(fast.loglik[ok], plain.loglik[ok], rtol=0, atol=1e-6)
    assert fast.n_iter.mean() < plain.n_iter.mean()


def test_ula_ends_at_least_at_the_likelihood_of_the_truth_in_every_trial():
    """The ML estimate's likelihood is at least the truth's; EM started at the designation reaches
    it in each trial (resolved objects, d = 2 sigma, and coarse pixels, d = 3 sigma at Delta = 3 sigma)."""
    for d, pix in ((2.0, 1.0), (3.0, 3.0)):
        g, b, p, p0, _ = _batch(12, 40, T=8, d=d, pix=pix, m=20)
        res = unified_location_em(
            pixel_entries(b.counts), b.designation, g.sigma_px, p, p0, tol_px=1e-7, accelerate="squarem"
        )
        at_truth = log_likelihood(b.counts, b.truth, frame_times(8), g.sigma_px, p, p0)
        assert res.converged.all()
        assert np.all(res.loglik >= at_truth - 1e-9 * np.abs(at_truth)), (d, pix, (res.loglik - at_truth).min())


@pytest.mark.slow
def test_variance_approaches_crb_when_well_separated():
    """d = 6 sigma, 200 Poisson photons per object, Delta = sigma, T = 5: Var ~ CRB."""
    n, T = 400, 5
    g, b, p, p0, noise = _batch(7, n, T=T, d=6.0, pix=1.0, m=200, rho=0.01, model="poisson")
    res = unified_location_em(
        pixel_entries(b.counts), b.designation, g.sigma_px, p, p0, tol_px=1e-7, accelerate="squarem"
    )
    assert not res.failed.any()
    err = res.theta - b.truth
    crb = crb_linear_motion(b.truth, frame_times(T), g.shape, g.sigma_px, 200, noise)  # per trial
    bound = np.diagonal(crb, axis1=-2, axis2=-1).mean(axis=0).reshape(2, 4)
    ratio = (err**2).mean(axis=0) / bound  # (Q, 4)
    # each ratio is a chi^2_n / n variable: 3 standard errors = 3 sqrt(2/n) = 0.21
    assert np.all(np.abs(ratio - 1) < 3 * np.sqrt(2 / n)), ratio


def test_zero_photon_frames_all_empty_and_leaving_frame_are_flagged_not_nan():
    g, b, p, p0, _ = _batch(5, 6, T=6, d=3.0, m=20, rho=0.0)
    counts = b.counts.copy()
    counts[0, 2:4] = 0  # two empty frames: still a valid fit
    counts[1] = 0  # nothing at all: degenerate
    counts[2, 1:] = 0  # one frame only: velocity not identifiable
    res = unified_location_em(pixel_entries(counts), b.designation, g.sigma_px, p, p0)
    assert np.isfinite(res.theta).all() and np.isfinite(res.loglik).all()
    assert not res.failed[0] and res.converged[0]
    assert res.degenerate[1] and res.degenerate[2]
    np.testing.assert_array_equal(res.theta[1], b.designation[1])
    assert res.degenerate.sum() == 2
    # objects that leave the window: flagged
    theta = b.truth[:2].copy()
    theta[..., 2] = 2.0  # fast to the right: out of the window after a few frames
    times = frame_times(6)
    c = simulate_counts(np.random.default_rng(1), theta, times, g.shape, g.sigma_px, 50, 0.0)
    res = unified_location_em(pixel_entries(c), theta, g.sigma_px, p, p0)
    assert res.left_frame.all() and np.isfinite(res.theta).all()


def test_coincident_designations_flag_merge():
    g, b, p, p0, _ = _batch(6, 5, d=2.0)
    des = b.designation.copy()
    des[:, 1] = des[:, 0]
    res = unified_location_em(pixel_entries(b.counts), des, g.sigma_px, p, p0, max_iter=50)
    assert res.merged.all() and np.isfinite(res.theta).all()
    assert not res.swapped.any()


def test_bad_estimator_input_raises():
    g, b, p, p0, _ = _batch(6, 2)
    ent = pixel_entries(b.counts)
    with pytest.raises(ValueError, match="tol_px"):
        unified_location_em(ent, b.designation, g.sigma_px, p, p0, tol_px=0.0)
    with pytest.raises(ValueError, match="theta0"):
        unified_location_em(ent, b.designation[:1], g.sigma_px, p, p0)
    with pytest.raises(ValueError, match="p_noise"):
        unified_location_em(ent, b.designation, g.sigma_px, p, p0 + 0.1)
    with pytest.raises(ValueError, match="counts"):
        pixel_entries(-np.ones((1, 1, 2, 2)))


def test_weight_and_sigma_estimation_recover_truth():
    g, b, p, p0, _ = _batch(8, 40, T=10, d=5.0, pix=1.0, m=100, rho=0.01)
    res = unified_location_em(
        pixel_entries(b.counts),
        b.designation,
        g.sigma_px * 1.4,
        p * 0.7,
        1 - 0.7 * p.sum(),
        estimate_weights=True,
        estimate_sigma=True,
        tol_px=1e-6,
    )
    assert abs(np.median(res.sigma) / g.sigma_px - 1) < 0.03
    assert np.abs(np.median(res.p, axis=0) / p - 1).max() < 0.05


def test_match_labels_and_responsibilities():
    a = np.array([[[0, 0, 0, 0], [5, 0, 0, 0.0]], [[0, 0, 0, 0], [5, 0, 0, 0.0]]])
    b = a.copy()
    b[1] = b[1, ::-1]
    perm, same = match_labels(b, a)
    np.testing.assert_array_equal(same, [True, False])
    np.testing.assert_array_equal(np.take_along_axis(b, perm[..., None], 1), a)
    lam = responsibility_maps(np.array([[3, 3, 0, 0], [6, 3, 0, 0.0]]), frame_times(2), (7, 9), 1.0, [0.4, 0.4], 0.2)
    np.testing.assert_allclose(lam.sum(axis=0), 1.0)
    assert lam[0, 0, 3, 3] > 0.9 and lam[1, 0, 3, 6] > 0.9


# -- two-stage baseline -------------------------------------------------------------------------


def test_fit_lines_is_ols_and_skips_invalid_marks():
    rng = np.random.default_rng(0)
    times = frame_times(8)
    xy = rng.normal(size=(3, 8, 2, 2))
    valid = np.ones((3, 8, 2), dtype=bool)
    valid[1, :3, 0] = False
    valid[2, 1:, 1] = False  # a single mark: no line
    fb = np.full((3, 2, 4), 7.0)
    fit = fit_lines(Marks(xy, valid, np.zeros((3, 8), int), np.zeros((3, 8), bool)), times, fb)
    for n, j in [(0, 0), (1, 0), (1, 1)]:
        keep = valid[n, :, j]
        for ax in (0, 1):
            v, x0 = np.polyfit(times[keep], xy[n, keep, j, ax], 1)
            np.testing.assert_allclose(fit.theta[n, j, [ax, ax + 2]], [x0, v], atol=1e-10)
    assert not fit.valid[2, 1] and np.all(fit.theta[2, 1] == 7.0)


def test_centre_of_region_marks_equal_centroid_inside_gate():
    g, b, p, p0, _ = _batch(9, 8, q=1, T=4, d=0.0, pix=1.0, m=30, rho=0.0)
    times = frame_times(4)
    pred = propagate(b.truth, times)
    marks = centre_of_region_marks(b.counts, pred, half_gate_px=50)  # the whole window
    r, c = np.indices(g.shape)
    tot = b.counts.sum(axis=(-1, -2))
    cx = (b.counts * c).sum(axis=(-1, -2)) / tot
    cy = (b.counts * r).sum(axis=(-1, -2)) / tot
    np.testing.assert_allclose(marks.xy[..., 0, 0], cx)
    np.testing.assert_allclose(marks.xy[..., 0, 1], cy)


def test_em_marks_empty_frames_and_association():
    g, b, p, p0, _ = _batch(10, 10, T=6, d=4.0, pix=1.0, m=30, rho=0.0)
    counts = b.counts.copy()
    counts[:, 3] = 0
    times = frame_times(6)
    for init in ("designation", "previous"):
        mk = em_marks(counts, b.designation, times, g.sigma_px, p, p0, init=init, association="assignment")
        assert np.isfinite(mk.xy).all() and not mk.valid[:, 3].any() and mk.valid[:, [0, 1, 2, 4, 5]].all()
        fit = fit_lines(mk, times, b.designation)
        assert fit.valid.all()
        assert np.abs(fit.theta[..., :2] - b.truth[..., :2]).max() < 1.0
    swapped = Marks(mk.xy[:, :, ::-1], mk.valid, mk.n_iter, mk.cap_hit)
    back = associate(swapped, propagate(b.designation, times))
    np.testing.assert_allclose(back.xy, mk.xy)


def test_moment_starts_find_resolved_and_overlapping_pairs_without_the_designation():
    times = frame_times(4)
    for d in (6.0, 1.0):  # resolved: two regions; overlapping: principal-axis split
        g, b, p, p0, _ = _batch(13, 30, T=4, d=d, pix=1.0, m=400, rho=0.0)
        starts = moment_starts(b.counts, g.sigma_px, 2)  # (N, T, 2, 2)
        truth = propagate(b.truth, times)
        # each start near a different object (best of the two orders), to a fraction of the separation
        direct = np.linalg.norm(starts - truth, axis=-1).max(axis=-1)
        crossed = np.linalg.norm(starts[..., ::-1, :] - truth, axis=-1).max(axis=-1)
        assert np.median(np.minimum(direct, crossed)) < 0.35 * max(d, 1.5) * g.sigma_px
        # the split is along the separation (y): the two starts differ mostly in y
        gap = np.abs(starts[..., 0, :] - starts[..., 1, :])
        assert np.median(gap[..., 1] / np.maximum(gap[..., 0], 1e-9)) > 2


def test_line_association_undoes_per_frame_label_shuffles():
    rng = np.random.default_rng(14)
    times = frame_times(12)
    truth = np.array([[[10.0, 10.0, 0.3, 0.1], [10.0, 12.0, 0.3, 0.1]]]).repeat(5, axis=0)  # 2 px apart
    xy = propagate(truth, times) + rng.normal(0, 0.2, (5, 12, 2, 2))
    flip = rng.random((5, 12)) < 0.5
    shuffled = np.where(flip[..., None, None], xy[:, :, ::-1], xy)
    ones = np.ones((5, 12, 2), dtype=bool)
    out = associate_by_lines(Marks(shuffled, ones, np.zeros((5, 12), int), np.zeros((5, 12), bool)), times)
    same = np.all(out.xy == xy, axis=(1, 2, 3))
    swapped = np.all(out.xy == xy[:, :, ::-1], axis=(1, 2, 3))
    assert np.all(same | swapped)  # consistent labels in every frame


def test_designation_free_marks_fit_the_tracks():
    g, b, p, p0, _ = _batch(15, 20, T=8, d=4.0, pix=1.0, m=60)
    times = frame_times(8)
    mk = em_marks(b.counts, b.designation * np.nan, times, g.sigma_px, p, p0, init="moments", association="lines")
    fit = fit_lines(mk, times, np.zeros_like(b.truth))
    perm, _ = match_labels(fit.theta, b.truth, times)
    est = np.take_along_axis(fit.theta, perm[..., None], axis=1)
    assert np.abs(est[..., :2] - b.truth[..., :2]).max() < 0.5 * g.sigma_px
    with pytest.raises(ValueError, match="init"):
        em_marks(b.counts, b.designation, times, g.sigma_px, p, p0, init="peaks")


# -- CRB ----------------------------------------------------------------------------------------


def test_crb_single_object_fine_pixels_matches_continuous_bound():
    T, m, s = 6, 50.0, 12.0
    times = frame_times(T)
    theta = np.array([[60.3, 58.8, 0.7, -0.4]])
    crb = crb_linear_motion(theta, times, (120, 124), s, m, 0.0)
    A, B, C = T, times.sum(), (times**2).sum()
    var_x0 = s**2 / m * C / (A * C - B**2)
    var_v = s**2 / m * A / (A * C - B**2)
    d = np.diag(crb)
    np.testing.assert_allclose(d[[0, 1]], var_x0, rtol=0.005)  # pixel = sigma/12
    np.testing.assert_allclose(d[[2, 3]], var_v, rtol=0.005)
    assert position_crb_sum(crb[None])[0] == pytest.approx(d[0] + d[1])
    # the Fisher matrix is symmetric and the coincident-object case is infinite, not NaN
    fim = fisher_linear_motion(np.array([[[5.0, 5, 0, 0], [5, 5, 0, 0]]]), times, (11, 11), 1.0, 10.0, 0.01)
    np.testing.assert_allclose(fim, np.swapaxes(fim, -1, -2))
    bad = crb_linear_motion(np.array([[5.0, 5, 0, 0], [5, 5, 0, 0]]), times, (11, 11), 1.0, 10.0, 0.01)
    assert np.isinf(np.diag(bad)).all()


def test_map_ula_limits_and_monotone_posterior():
    g, b, p, p0, _ = _batch(16, 20, T=6, d=1.5, pix=1.0, m=20, dsd=0.3)
    ent = pixel_entries(b.counts)
    ml = unified_location_em(ent, b.designation, g.sigma_px, p, p0, tol_px=1e-9)
    flat = unified_location_em(ent, b.designation, g.sigma_px, p, p0, tol_px=1e-9, prior_sd=(1e6, 1e6))
    np.testing.assert_allclose(flat.theta, ml.theta, atol=1e-5)  # a flat prior is ML
    tight = unified_location_em(ent, b.designation, g.sigma_px, p, p0, tol_px=1e-9, prior_sd=(1e-6, 0.0))
    np.testing.assert_allclose(tight.theta, b.designation, atol=1e-6)  # a sharp prior keeps the designation
    # velocity sd 0 fixes the velocity; the log posterior never decreases over the EM steps
    mp = unified_location_em(
        ent, b.designation, g.sigma_px, p, p0, tol_px=1e-9, prior_sd=(0.3 * g.sigma_px, 0.0), history=True
    )
    np.testing.assert_allclose(mp.theta[..., 2:], b.designation[..., 2:], atol=1e-6)
    post = np.array(mp.history_loglik)
    assert np.diff(post, axis=0).min() > -1e-9 * np.abs(post).max()
    # the MAP estimate lies between the designation and the ML estimate in the summed sense
    assert np.abs(mp.theta - b.designation).sum() < np.abs(ml.theta - b.designation).sum()
    with pytest.raises(ValueError, match="prior_sd"):
        unified_location_em(ent, b.designation, g.sigma_px, p, p0, prior_sd=(0.0, 0.0))
