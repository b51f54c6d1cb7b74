"""The compiled E-step of notebook 002's unified location EM against its NumPy twin.

The NumPy path is always tested (``TVTRACK_NO_JIT=1``); the compiled path only where numba is importable.
"""

from dataclasses import replace

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


def _broken_entries(entries, case):
    """``entries`` with one defect: an index outside its table, an order or a value the steps cannot read."""
    one = np.arange(entries.trial.size) == 3
    rows, cols = entries.shape
    last = np.arange(entries.trial.size) == entries.trial.size - 1
    flip = {f: getattr(entries, f)[::-1] for f in ("trial", "frame", "row", "col", "count")}
    return {
        "col at cols": lambda: replace(entries, col=np.where(one, float(cols), entries.col)),
        "col far": lambda: replace(entries, col=np.where(one, 1e6, entries.col)),
        "row negative": lambda: replace(entries, row=np.where(one, -2.0, entries.row)),
        "row not whole": lambda: replace(entries, row=np.where(one, 0.5, entries.row)),
        "frame at T": lambda: replace(entries, frame=np.where(one, entries.n_frames, entries.frame)),
        "frame far": lambda: replace(entries, frame=np.where(one, 10**7, entries.frame)),
        "frame float": lambda: replace(entries, frame=entries.frame.astype(float)),
        "trial at N": lambda: replace(entries, trial=np.where(last, entries.n_trials, entries.trial)),
        "unsorted": lambda: replace(entries, **flip),
        "negative count": lambda: replace(entries, count=np.where(one, -1.0, entries.count)),
        "col short": lambda: replace(entries, col=entries.col[:-1]),
    }[case]()


@pytest.mark.parametrize("no_jit", ["0", "1"])
@pytest.mark.parametrize(
    "case",
    [
        "col at cols",
        "col far",
        "row negative",
        "row not whole",
        "frame at T",
        "frame far",
        "frame float",
        "trial at N",
        "unsorted",
        "negative count",
        "col short",
    ],
)
def test_hand_built_entries_the_steps_cannot_index_are_refused(monkeypatch, case, no_jit):
    """A hand-built :class:`PixelEntries` is checked once, before either path reads it: the compiled steps index their
    tables with it unchecked (a column or frame far outside crashed the process, one just past the table or a
    negative row gave each path another wrong answer, unsorted trials ran compiled but not in NumPy)."""
    monkeypatch.setenv("TVTRACK_NO_JIT", no_jit)
    g, counts, desig, p, p0 = _scene(n=4, T=4)
    entries = _broken_entries(pixel_entries(counts), case)
    with pytest.raises(ValueError, match="^parameter 'entries' "):
        unified_location_em(entries, desig, g.sigma_px, p, p0, max_iter=20)


@pytest.mark.parametrize("no_jit", ["0", "1"])
@pytest.mark.parametrize("name", ["theta", "p", "p_noise", "sigma", "times", "shape", "live"])
def test_the_e_step_refuses_arrays_that_do_not_fit_the_working_set(monkeypatch, name, no_jit):
    """:func:`em_steps.expectation_step` checks its per-trial arrays, frame times and window against the working
    set (the compiled step read past them: fewer trials than the entries crashed the process)."""
    monkeypatch.setenv("TVTRACK_NO_JIT", no_jit)
    g, counts, desig, p, p0 = _scene(n=6, T=4)
    entries = pixel_entries(counts)
    n, q = desig.shape[:2]
    args = dict(
        theta=desig,
        p=np.tile(p, (n, 1)),
        p_noise=np.full(n, p0),
        sigma=np.full((n, q), g.sigma_px),
        times=frame_times(4),
        shape=entries.shape,
        live=np.ones(n, dtype=bool),
    )
    wrong = {
        "theta": desig[:1],
        "p": args["p"][:, :1],
        "p_noise": args["p_noise"][:2],
        "sigma": args["sigma"][:1],
        "times": frame_times(2),
        "shape": (entries.shape[0] - 2, entries.shape[1]),
        "live": np.ones(1, dtype=bool),
    }
    work = em_steps.ActiveEntries(entries, np.arange(n))
    sums, ll = em_steps.expectation_step(work, **args, second=False)  # the right arrays
    assert sums.shape == (n, q, 7) and np.isfinite(ll).all()
    with pytest.raises(ValueError, match=f"^parameter '{name}' "):
        em_steps.expectation_step(work, **{**args, name: wrong[name]}, second=False)


def _photon_inputs():
    from tvtrack.papers.p002_unified_location_em._photon_kernel import add_photons, add_photons_numpy

    rng = np.random.default_rng(5)
    n, t, q, m = 3, 4, 2, 30
    pos = rng.uniform(0, 8, (n, t, q, 2))
    return add_photons, add_photons_numpy, pos, rng.standard_normal((n, t, q, m, 2)), rng.integers(0, m, (n, t, q))


@pytest.mark.parametrize("which", ["k per trial and frame", "one k", "one position per object"])
def test_add_photons_broadcasts_positions_and_counts_as_numpy_does(which):
    """``pos`` and ``k`` are broadcast to the shapes the kernel indexes, as NumPy broadcasts them (the kernel read
    past them and counted other photons than the NumPy histogram)."""
    add_photons, add_photons_numpy, pos, z, k = _photon_inputs()
    small = {
        "k per trial and frame": (pos, k[..., :1]),
        "one k": (pos, k[:1, :1, :1]),
        "one position per object": (pos[:1, :1], k),
    }
    pos_s, k_s = small[which]
    fast, ref = np.zeros((3, 4, 7, 9), np.int32), np.zeros((3, 4, 7, 9), np.int32)
    add_photons(fast, pos_s, z, 1.3, k_s)
    add_photons_numpy(ref, np.broadcast_to(pos_s, pos.shape), z, 1.3, np.broadcast_to(k_s, k.shape))
    assert ref.sum() > 0 and np.array_equal(fast, ref)


@pytest.mark.parametrize("which", ["z of one trial", "z with three coordinates", "k not integers", "pos of 3 objects"])
def test_add_photons_refuses_inputs_the_kernel_cannot_index(which):
    """One photon draw per photon of every trial and frame (``z``), integer photon numbers (``k``: NumPy compared
    ``j < 3.7`` where the kernel truncated), positions that broadcast: else a one-line ``ValueError``."""
    add_photons, _, pos, z, k = _photon_inputs()
    bad = {
        "z of one trial": ("z", pos, z[:1], k),
        "z with three coordinates": ("z", pos, np.concatenate([z, z[..., :1]], axis=-1), k),
        "k not integers": ("k", pos, z, k + 0.7),
        "pos of 3 objects": ("pos", np.concatenate([pos, pos[:, :, :1]], axis=2), z, k),
    }
    name, pos_b, z_b, k_b = bad[which]
    counts = np.zeros((3, 4, 7, 9), np.int32)
    with pytest.raises(ValueError, match=f"^parameter '{name}' "):
        add_photons(counts, pos_b, z_b, 1.3, k_b)
