"""The compiled one-trial-at-a-time EM of notebook 002 against the vectorised loop it replaces, bit for bit (and the
compiled variance sums of the claims' bootstrap against NumPy's).

The per-trial loop (:func:`tvtrack.papers.p002_unified_location_em._kernels.em_trials`) must give the vectorised
loop's (:func:`tvtrack.papers.p002_unified_location_em.em_loop.iterate`) estimates, log-likelihoods, step counts and
flags exactly: the explorer's numbers may not move. The range-restricted tables and the skipped stopped trials of the
compiled E-step are pinned against full tables and every trial computed.
"""

import numpy as np
import pytest

from tvtrack import jit
from tvtrack.papers.p002_unified_location_em import _kernels, em_steps
from tvtrack.papers.p002_unified_location_em._spread_kernel import variance_sum_rows
from tvtrack.papers.p002_unified_location_em.em import unified_location_em
from tvtrack.papers.p002_unified_location_em.em_steps import per_frame_entries, pixel_entries
from tvtrack.papers.p002_unified_location_em.model import (
    designate,
    draw_truth,
    frame_times,
    mixture_weights,
    scene_geometry,
    simulate_counts,
)

pytestmark = pytest.mark.skipif(not jit.enabled(), reason="numba absent or TVTRACK_NO_JIT=1: no compiled loop")


def _scene(q=2, T=6, d=1.5, pix=3.0, m=20, noise=0.01, n=24, seed=0):
    rng = np.random.default_rng(seed)
    g = scene_geometry(q, T, d, pix)
    truth = draw_truth(rng, n, g)
    counts = simulate_counts(rng, truth, frame_times(T), g.shape, g.sigma_px, m, noise)
    counts[0] = 0  # a trial without photons: degenerate from the start
    p, p0 = mixture_weights(m, noise, g.n_pixels, q)
    return g, counts, designate(rng, truth, 0.3 * g.sigma_px), p, p0


def _both(monkeypatch, *args, **kw):
    """The EM through the compiled per-trial loop and through the vectorised loop (the loop forced off)."""
    used = []
    real = _kernels.em_trials

    def spy(*a, **k):
        used.append(1)
        return real(*a, **k)

    monkeypatch.setattr(_kernels, "em_trials", spy)
    fast = unified_location_em(*args, **kw)
    assert used, "the compiled loop was not used"
    monkeypatch.setattr(_kernels, "em_trials", lambda *a, **k: False)
    slow = unified_location_em(*args, **kw)
    return fast, slow


@pytest.mark.parametrize(
    "q, accelerate, tol_loglik, max_iter",
    [
        (2, "squarem", None, 5000),
        (2, None, None, 8),
        (1, "squarem", None, 5000),
        (2, None, 0.1, 5000),
        (2, "squarem", 0.1, 6),
    ],
)
def test_the_trial_loop_is_the_vectorised_loop_bit_for_bit(monkeypatch, q, accelerate, tol_loglik, max_iter):
    g, counts, desig, p, p0 = _scene(q=q)
    run = dict(times=frame_times(counts.shape[1]), tol_px=1e-6 * g.sigma_px, max_iter=max_iter, accelerate=accelerate)
    fast, slow = _both(monkeypatch, pixel_entries(counts), desig, g.sigma_px, p, p0, tol_loglik=tol_loglik, **run)
    for name in ("theta", "loglik", "n_iter", "converged", "cap_hit", "degenerate", "merged", "swapped"):
        assert np.array_equal(getattr(fast, name), getattr(slow, name)), name
    assert fast.degenerate[0] and fast.n_iter.max() > 3
    # a low cap stops both loops at the same step; otherwise the stopping rule does
    assert fast.cap_hit.any() if max_iter < 100 else fast.converged[1:].all()


@pytest.mark.parametrize("accelerate", [None, "squarem"])
def test_the_trial_loop_gives_the_per_frame_marks_bit_for_bit(monkeypatch, accelerate):
    """The marks' EM: every (trial, frame) a one-frame trial, static model, coarse pixels (slow convergence)."""
    g, counts, desig, p, p0 = _scene(pix=5.0, d=1.0, n=10)
    ent = per_frame_entries(pixel_entries(counts))
    start = np.repeat(desig, counts.shape[1], axis=0)
    run = dict(motion="static", tol_px=1e-6 * g.sigma_px, max_iter=300, accelerate=accelerate)
    fast, slow = _both(monkeypatch, ent, start, g.sigma_px, p, p0, **run)
    for name in ("theta", "loglik", "n_iter", "converged", "cap_hit", "degenerate"):
        assert np.array_equal(getattr(fast, name), getattr(slow, name)), name
    assert np.all(fast.theta[..., 2:] == 0.0) and fast.cap_hit.any()


@pytest.mark.parametrize("n_terms", [1, 4, 7, 8, 12, 16, 20, 28])
def test_the_squarem_norm_is_summed_in_numpys_order(n_terms):
    """``(r**2).sum(axis=(1, 2))`` of NumPy (pairwise from 8 terms) and the compiled sum agree bit for bit, on
    values spread over 40 orders of magnitude (where a different order changes the last bits)."""
    rng = np.random.default_rng(n_terms)
    shape = (500, n_terms // 4, 4) if n_terms % 4 == 0 else (500, 1, n_terms)
    x = rng.standard_normal(shape) * np.exp(rng.uniform(-46, 46, shape))
    ref = (x**2).sum(axis=(1, 2))
    got = np.array([_kernels._sum_squares(np.ascontiguousarray(row)) for row in x])
    assert np.array_equal(ref, got)


def test_a_table_over_a_pixel_range_is_the_full_table_there():
    rng = np.random.default_rng(5)
    for _ in range(200):
        n, mu, s = int(rng.integers(3, 30)), rng.uniform(-5, 35), rng.uniform(0.1, 3.0)
        lo = int(rng.integers(0, n))
        hi = int(rng.integers(lo, n))
        full = [np.full(n, np.nan) for _ in range(3)]
        part = [np.full(n, np.nan) for _ in range(3)]
        _kernels._axis_table(mu, s, 0, n - 1, True, *full)
        _kernels._axis_table(mu, s, lo, hi, True, *part)
        for a, b in zip(full, part):
            assert np.array_equal(a[lo : hi + 1], b[lo : hi + 1])
            assert np.isnan(b[:lo]).all() and np.isnan(b[hi + 1 :]).all()  # nothing outside the range written


def _full_table_e_step(work, theta, p, p_noise, sigma, times, shape):
    """The E-step with every pixel of every axis tabulated (the reference): the kernel's sums per entry, in order."""
    rows, cols = shape
    n, q = theta.shape[:2]
    tab = {}
    for r in range(n):
        for f, t in enumerate(times):
            for j in range(q):
                fx, mx, fy, my = np.empty(cols), np.empty(cols), np.empty(rows), np.empty(rows)
                _kernels._axis_table(theta[r, j, 0] + theta[r, j, 2] * t, sigma[r, j], 0, cols - 1, False, fx, mx, fx)
                _kernels._axis_table(theta[r, j, 1] + theta[r, j, 3] * t, sigma[r, j], 0, rows - 1, False, fy, my, fy)
                tab[r, f, j] = fx, mx, fy, my
    sums, loglik = np.zeros((n, q, 7)), np.zeros(n)
    for r, f, y, x, c in zip(work.loc, work.frame, work.row.astype(int), work.col.astype(int), work.count):
        t = times[f]
        pv = [p[r, j] * (tab[r, f, j][0][x] * tab[r, f, j][2][y]) for j in range(q)]
        v = max(p_noise[r] / (rows * cols) + sum(pv), 1e-300)
        loglik[r] += c * np.log(v)
        for j in range(q):
            w = pv[j] * (c / v)
            wt = w * t
            ex, ey = tab[r, f, j][1][x], tab[r, f, j][3][y]
            sums[r, j] += [w, wt, wt * t, w * ex, wt * ex, w * ey, wt * ey]
    return sums, loglik


def test_the_e_step_over_photon_ranges_and_live_trials_is_the_full_one():
    g, counts, desig, p, p0 = _scene(n=8, T=4)
    entries = pixel_entries(counts)
    n, q = desig.shape[:2]
    work = em_steps.ActiveEntries(entries, np.arange(1, n))  # trial 0 has no photons
    rng = np.random.default_rng(2)
    theta = desig[1:] + 0.3 * rng.standard_normal(desig[1:].shape)
    pw, p0v, sigma = np.broadcast_to(p, (n - 1, q)).copy(), np.full(n - 1, p0), np.full((n - 1, q), g.sigma_px)
    times = frame_times(counts.shape[1])
    ref_sums, ref_ll = _full_table_e_step(work, theta, pw, p0v, sigma, times, entries.shape)
    live = np.arange(n - 1) % 3 != 1
    sums, ll = _kernels.e_step(work, theta, pw, p0v, sigma, times, entries.shape, False, live)
    np.testing.assert_allclose(sums[live], ref_sums[live], rtol=1e-15, atol=0)
    np.testing.assert_allclose(ll[live], ref_ll[live], rtol=1e-15, atol=0)
    assert not sums[~live].any() and not ll[~live].any()  # the stopped trials are skipped
    all_sums, all_ll = _kernels.e_step(
        em_steps.ActiveEntries(entries, np.arange(1, n)), theta, pw, p0v, sigma, times, entries.shape, False
    )
    assert np.array_equal(all_sums[live], sums[live]) and np.array_equal(all_ll[live], ll[live])


@pytest.mark.parametrize("k", [1, 2, 3, 4, 8, 9])
def test_the_compiled_variance_sum_is_numpys_bit_for_bit(k):
    """The claims' resampled variance sums (B, n, k): paired halves side by side, fancy-indexed resamples, one row
    (the point estimate), values over 20 orders of magnitude; one column falls back to NumPy (which then sums the
    trials pairwise)."""
    rng = np.random.default_rng(k)
    data = rng.standard_normal((80, 2 * k)) * np.exp(rng.uniform(-23, 23, (80, 2 * k))) + 1.5
    res = data[rng.integers(0, 80, (300, 80))]  # (B, n, 2k) as the bootstrap hands it over
    for e in (res[..., :k], res[..., k:], np.ascontiguousarray(res[..., :k]), data[None], res[:, :2]):
        assert np.array_equal(variance_sum_rows(e), e.var(axis=1, ddof=1).sum(axis=-1))
