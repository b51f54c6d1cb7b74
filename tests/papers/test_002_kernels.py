"""The compiled E-step of notebook 002's unified location EM against its NumPy twin.

The NumPy path is always tested (``TVTRACK_NO_JIT=1``); the compiled path only where numba is importable.
"""

import numpy as np
import pytest

from tvtrack import jit
from tvtrack.papers.p002_unified_location_em import _kernels, em_steps
from tvtrack.papers.p002_unified_location_em.em_steps import pixel_entries
from tvtrack.papers.p002_unified_location_em.em import unified_location_em
from tvtrack.papers.p002_unified_location_em.model import (
    designate,
    draw_truth,
    frame_times,
    mixture_weights,
    scene_geometry,
    simulate_counts,
)

needs_numba = pytest.mark.skipif(jit._numba is None, reason="numba is not installed: the NumPy path is the one used")


def _scene(q=2, T=10, d=2.0, pix=1.0, m=20, noise=0.01, n=12, seed=0):
    rng = np.random.default_rng(seed)
    g = scene_geometry(q, T, d, pix)
    truth = draw_truth(rng, n, g)
    counts = simulate_counts(rng, truth, frame_times(T), g.shape, g.sigma_px, m, noise)
    p, p0 = mixture_weights(m, noise, g.n_pixels, q)
    return g, counts, designate(rng, truth, 0.3 * g.sigma_px), p, p0


@needs_numba
@pytest.mark.parametrize("q, pix, second", [(1, 1.0, False), (2, 1.0, True), (2, 5.0, False), (3, 2.5, True)])
def test_compiled_e_step_equals_the_numpy_e_step(q, pix, second):
    g, counts, desig, p, p0 = _scene(q=q, pix=pix)
    entries = pixel_entries(counts)
    n = counts.shape[0]
    work = em_steps.ActiveEntries(entries, np.arange(n))
    rng = np.random.default_rng(3)
    theta = desig + 0.3 * rng.standard_normal(desig.shape)  # off the designation: every term non-trivial
    pw = np.broadcast_to(p, (n, q)).copy()
    p0v = np.full(n, p0)
    sigma = np.full((n, q), g.sigma_px) * (1 + 0.1 * rng.random((n, q)))
    times = frame_times(counts.shape[1])
    ref_sums, ref_ll = em_steps.expectation_step_numpy(work, theta, pw, p0v, sigma, times, entries.shape, second)
    sums, ll = _kernels.e_step(work, theta, pw, p0v, sigma, times, entries.shape, second)
    assert sums.shape == ref_sums.shape == (n, q, 9 if second else 7)
    np.testing.assert_allclose(sums, ref_sums, rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(ll, ref_ll, rtol=1e-12)


@needs_numba
@pytest.mark.parametrize("accelerate", [None, "squarem"])
def test_the_em_gives_the_same_estimates_compiled_or_not(monkeypatch, accelerate):
    g, counts, desig, p, p0 = _scene(pix=2.5, n=16, seed=4)
    run = dict(times=frame_times(counts.shape[1]), tol_px=1e-8, accelerate=accelerate)
    fast = unified_location_em(pixel_entries(counts), desig, g.sigma_px, p, p0, **run)
    monkeypatch.setenv("TVTRACK_NO_JIT", "1")
    assert not jit.enabled()
    slow = unified_location_em(pixel_entries(counts), desig, g.sigma_px, p, p0, **run)
    np.testing.assert_allclose(fast.theta, slow.theta, atol=1e-6)  # both stop within 1e-8 px of the fixed point
    np.testing.assert_allclose(fast.loglik, slow.loglik, rtol=1e-10)
    assert np.abs(fast.n_iter - slow.n_iter).max() <= 2


def test_the_numpy_path_is_used_when_jit_is_off(monkeypatch):
    monkeypatch.setenv("TVTRACK_NO_JIT", "1")
    called = []
    monkeypatch.setattr(_kernels, "e_step", lambda *a: called.append(1))
    g, counts, desig, p, p0 = _scene(n=4)
    res = unified_location_em(pixel_entries(counts), desig, g.sigma_px, p, p0, times=frame_times(counts.shape[1]))
    assert not called and res.converged.all()


@pytest.mark.parametrize("static", [False, True])
def test_compiled_m_step_is_the_numpy_m_step_bit_for_bit(static):
    """The compiled M-step (no prior) gives the NumPy one's new states and degenerate flags exactly, including rows
    with no weight (A = 0), a singular line fit (all weight in one frame: det = 0) and a non-finite sum."""
    if not jit.available():
        pytest.skip("numba not installed")
    rng = np.random.default_rng(3)
    sums = rng.uniform(0.5, 50.0, size=(40, 2, 7))
    sums[..., 1] = sums[..., 0] * rng.uniform(0, 5, size=(40, 2))  # B = A * mean t
    sums[..., 2] = sums[..., 1] ** 2 / sums[..., 0] * rng.uniform(1.0, 2.0, size=(40, 2))  # C >= B^2 / A
    sums[0, 0, 0] = 0.0  # no weight
    sums[1, 1, 2] = sums[1, 1, 1] ** 2 / sums[1, 1, 0]  # singular
    sums[2, 0, 3] = np.inf
    theta = rng.normal(size=(40, 2, 4))
    ref_new, ref_bad = em_steps.maximisation_step(sums, theta, static)
    new, bad = _kernels.m_step(sums, theta, static)
    assert ref_bad[:3].any() and ref_bad.tolist() == bad.tolist()
    assert np.array_equal(ref_new, new)


@needs_numba
@pytest.mark.parametrize("limited", [False, True])
def test_compiled_photon_histogram_is_the_numpy_one(limited):
    """The scene's photon counts, compiled and in NumPy, from the same draws: photons near pixel edges (offsets
    that land on x.5 before rounding), outside the window on every side, and (``limited``) only the first k of
    the m drawn per object and frame (the Poisson photon model)."""
    from tvtrack.papers.p002_unified_location_em._photon_kernel import add_photons, add_photons_numpy

    rng = np.random.default_rng(4)
    n, t, q, m, rows, cols = 30, 6, 2, 25, 5, 7
    pos = rng.uniform(-3, 10, (n, t, q, 2))
    pos[0, 0, 0] = (2.5, 1.5)  # on a pixel edge: z = 0 rounds up
    z = rng.standard_normal((n, t, q, m, 2))
    z[0, 0, 0, :3] = 0.0
    k = rng.integers(0, m + 1, (n, t, q)) if limited else None
    if limited:
        k[0, 0, 0] = m
    noise = rng.poisson(0.3, (n, t, rows, cols)).astype(np.int32)
    fast, slow = noise.copy(), noise.copy()
    add_photons(fast, pos, z, 1.3, k)
    add_photons_numpy(slow, pos, z, 1.3, k)
    assert np.array_equal(fast, slow) and fast.dtype == np.int32
    kept = (fast - noise).sum()
    assert 0 < kept < (k.sum() if limited else n * t * q * m)  # some photons left the window
    assert fast[0, 0, 2, 3] - noise[0, 0, 2, 3] >= 3  # the three photons on the corner, in the pixel beyond it
