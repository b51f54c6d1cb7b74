"""Speed of notebook 002 (issues 6, 30): ratios measured in one run, never absolute wall times.

Where the time goes (profile of one claims replicate at the paper profile, ``n_trials = 80``, ``n_iter_trials = 40``,
87 simulation jobs, 15.7 s of CPU on this 2-core machine under load; one process):

* about half is Delta = 5 sigma (Fig 6b, C002-10's "coarser pixels"): the per-frame marks and the ULA. With two
  objects inside one or two coarse pixels a single frame hardly constrains their separation, so the per-frame EM
  converges linearly with a rate near 1 and a quarter to a half of the trials reach the 5000-step cap in some frame;
  that tail costs a fixed ~1 s per point whatever the number of trials;
* the T = 50 points (Fig 5b, C002-11): two-stage ~12 %, ULA ~11 %, MAP-ULA ~3 %;
* the plain-EM iteration counts (Fig 7, C002-13/14) ~5 %; all T = 5 and T = 10 ULA-only points ~15 %.

Since this session the E-step is compiled (numba, :mod:`tvtrack.papers.p002_unified_location_em._kernels`; its
NumPy twin is tested against it and used with ``TVTRACK_NO_JIT=1``): a replicate at the paper profile takes 9.4 s of
CPU instead of 14.0 (x1.5). The E-step is arithmetic-bound, not overhead-bound: 42 000 E-steps per replicate on
4 x 4 to 9 x 9 windows, each evaluating the Gaussian tail mass (erfc) and density at every pixel edge of every
(trial, frame, object); the compiled kernel still spends about 70 % of the replicate there, and the number of
E-steps (SQUAREM with a 1e-6 sigma tolerance; the capped Delta = 5 sigma tail) is what remains to cut.

Measured increments over a replicate (before the compiled E-step): a faster velocity (0.5, 0.25 sigma/frame) reruns every job (15.4 s); Delta =
sigma for Figs 4, 5, 7 reruns 26 jobs (6.0 s); a statistic or a reading reruns nothing (the job cache keys each
algorithm's job by the settings it reads).

An exploration at the paper profile (measured 2026-11-28 in CPU seconds, one process, ``nice -n 10`` at a
load of 2): replicates 21.7 (3), sizing 9.8 (5 more, each measuring only the claims still undecided), one at a time
104.3 (52 values, each measuring only the claims that read it, at full size reusing the first replicate's jobs),
joint 439.2 (32 configurations, 13.7 each), pinned 26.8 (2), combinations 17.2 (8); about 620 in all, against about
1,070 the run before (the bounds drawn in every algorithm's job, the MAP-ULA run under every reading, every claim
measured in every run, and a screen whose confirmations cost as much as it spared: at 8 joint configurations 68 + 123
screened against 180 unscreened). A default replicate costs 6.5-9.5 s of CPU, of which C002-10's points (the
8-separation gain curve and Fig 6b's coarse pixels) are about 60 %.

The compiled trial loop (measured 2026-12-04, CPU seconds per measurement call at the paper profile, best of 3,
``n_workers = 1``, ``nice -n 10`` at a load of 2-5; before is the vectorised NumPy loop with the compiled E-step): the
maximum-likelihood EM with fixed weights and widths (the ULA, the plain-EM counts, the per-frame marks, the
multi-start and one-track fits) runs one trial at a time compiled (``_kernels.em_trials``), with the same arithmetic
element by element, so the same numbers bit for bit (``tests/papers/test_002_em_trials.py``; 3 configurations x 2
seeds of the whole measurement compared equal, every job output and every claim value); the E-step tabulates only the
pixel range each frame's photons fall in and skips stopped trials. A default replicate takes 8.0-8.7 s instead of
14.1-17.4 (x1.6-2.0); a faster velocity (every job reruns) 9.6-11.6 instead of 16.0-17.9 (x1.5-1.9); Delta = 5 sigma
for Figs 4, 5, 7 after the default (its capped tails) 18.7-20.1 instead of 35.6 (x1.8-1.9); plain EM capped at 100
after the default 9.3-10.4 instead of 16.3-17.9 (x1.6-1.9); the designation-free two-stage after the default 4.1-4.9
instead of 6.7-7.7 (x1.4-1.9) (ranges: three runs of each at loads 2-5, one pair side by side). The coarse-pixel marks
alone (the benchmark below) run about 4 times faster. What remains is mostly arithmetic: about two thirds of a
replicate is the compiled loop, whose work is the erfc and exp at each pixel edge (about 28 ns an edge measured alone;
about 110 million edges a default replicate), the rest mostly the claims' bootstrap (1.3 s at the default, from 2.6:
its variance sums now run compiled in NumPy's summation order, the same bits, ``_spread_kernel``; the resampling
itself is :mod:`tvtrack.resampling`'s). The MAP-ULA (a prior) and the weight- and width-estimating fits still run the
vectorised loop. Compiling the loop takes about 15-20 s of CPU once per source digest (kept on disk under
``TVTRACK_JIT_CACHE``; about 1 s to load).
"""

import time

import numpy as np
import pytest

from tvtrack import jit
from tvtrack.papers.p002_unified_location_em import _kernels, study
from tvtrack.papers.p002_unified_location_em.em_steps import per_frame_entries, pixel_entries
from tvtrack.papers.p002_unified_location_em.em import unified_location_em
from tvtrack.papers.p002_unified_location_em.model import (
    designate,
    draw_truth,
    frame_times,
    mixture_weights,
    scene_geometry,
    simulate_counts,
)
from tvtrack.papers.p002_unified_location_em.register import REGISTER

N = 100


def _scene():
    rng = np.random.default_rng(0)
    g = scene_geometry(2, 10, 2.0, 1.0)
    truth = draw_truth(rng, N, g)
    counts = simulate_counts(rng, truth, frame_times(10), g.shape, g.sigma_px, 20, 0.01)
    p, p0 = mixture_weights(20, 0.01, g.n_pixels, 2)
    return g, counts, designate(rng, truth, 0.3 * g.sigma_px), p, p0


def test_em_batched_across_trials_vs_one_trial_at_a_time(benchmark, figure):
    """Target: the batched EM at least 2 times faster (measured 3.0-3.4 under load) than a per-trial loop of the same function, same estimates."""
    g, counts, desig, p, p0 = _scene()

    def batched():
        return unified_location_em(pixel_entries(counts), desig, g.sigma_px, p, p0, max_iter=200)

    res = benchmark.pedantic(batched, rounds=3, iterations=1)
    t_batch = benchmark.stats.stats.min
    t0 = time.perf_counter()
    loop = [
        unified_location_em(pixel_entries(counts[i : i + 1]), desig[i : i + 1], g.sigma_px, p, p0, max_iter=200)
        for i in range(N)
    ]
    t_loop = time.perf_counter() - t0
    np.testing.assert_allclose(np.concatenate([r.theta for r in loop]), res.theta, atol=1e-8)
    fig = figure("002 batched EM / per-trial loop (same estimates)", t_loop / t_batch, 2.0, at_least=True)
    assert fig.passed, fig.message()


def test_a_statistic_value_reuses_the_replicate(benchmark, figure):
    """Target: measuring a register value that changes only the statistic costs under 20 % of the replicate."""
    scale = study.Scale(
        n_trials=8,
        n_iter_trials=4,
        separations=(1.0, 2.0, 3.0, 4.0, 6.0, 8.0),
        fig3_frames=(5, 10, 50),
        crb_phases=2,
        max_iter=100,
    )
    default = REGISTER.default()
    study.clear_cache()
    t0 = time.perf_counter()
    study.measure(default, 1, scale)
    t_rep = time.perf_counter() - t0
    benchmark.pedantic(lambda: study.measure({**default, "statistic": "MSE"}, 1, scale), rounds=1, iterations=1)
    fig = figure(
        "002 statistic-only register value / replicate (wall)", benchmark.stats.stats.min / t_rep, 0.2, at_least=False
    )
    assert fig.passed, fig.message()


@pytest.mark.skipif(not jit.enabled(), reason="numba absent or TVTRACK_NO_JIT=1: the NumPy E-step is the one used")
def test_compiled_e_step_vs_numpy_e_step_on_a_replicate(benchmark, figure, monkeypatch):
    """Target: one claims replicate (half the paper profile's trials) at least 1.3 times faster in CPU with the
    compiled E-step than with the NumPy one, the same verdict numbers to 1e-6 relative (the EM stops within its
    tolerance either way). Measured 1.5 (14.0 -> 9.4 s at the paper profile, one process, under load)."""
    scale = study.Scale(n_trials=40, n_iter_trials=20, n_workers=1)
    default = REGISTER.default()
    study.clear_cache()
    study.measure(default, 1, study.Scale(n_trials=8, n_iter_trials=4, n_workers=1))  # compile outside the clock
    study.clear_cache()
    fast = benchmark.pedantic(lambda: study.measure(default, 3, scale), rounds=1, iterations=1)
    t_fast = benchmark.stats.stats.min
    study.clear_cache()
    monkeypatch.setenv("TVTRACK_NO_JIT", "1")
    t0 = time.perf_counter()
    slow = study.measure(default, 3, scale)
    t_slow = time.perf_counter() - t0
    study.clear_cache()
    a, b = fast["C002-12"]["Delta = 1 sigma"], slow["C002-12"]["Delta = 1 sigma"]
    assert a.value == pytest.approx(b.value, rel=1e-6)
    fig = figure(
        "002 replicate: NumPy E-step / compiled E-step (wall, same numbers)", t_slow / t_fast, 1.3, at_least=True
    )
    assert fig.passed, fig.message()


@pytest.mark.skipif(not jit.enabled(), reason="numba absent or TVTRACK_NO_JIT=1: no compiled loop")
def test_compiled_trial_loop_vs_vectorised_loop_on_coarse_pixel_marks(benchmark, figure, monkeypatch):
    """Target: the per-frame marks at Delta = 5 sigma (40 trials x 10 frames, static EM, SQUAREM to 1e-6 sigma,
    many frames reaching the 5000-step cap) at least 2 times faster in CPU through the compiled one-trial-at-a-time
    loop than through the vectorised NumPy loop with the compiled E-step, the same estimates and step counts bit
    for bit."""
    rng = np.random.default_rng(1)
    g = scene_geometry(2, 10, 1.0, 5.0)
    truth = draw_truth(rng, 40, g)
    counts = simulate_counts(rng, truth, frame_times(10), g.shape, g.sigma_px, 20, 0.01 / g.sigma_px**2)
    p, p0 = mixture_weights(20, 0.01 / g.sigma_px**2, g.n_pixels, 2)
    ent = per_frame_entries(pixel_entries(counts))
    start = np.repeat(designate(rng, truth, 0.3 * g.sigma_px), 10, axis=0)
    run = dict(motion="static", tol_px=1e-6 * g.sigma_px, accelerate="squarem")
    unified_location_em(per_frame_entries(pixel_entries(counts[:1])), start[:10], g.sigma_px, p, p0, **run)  # compile
    cpu = []

    def compiled():
        t0 = time.process_time()
        out = unified_location_em(ent, start, g.sigma_px, p, p0, **run)
        cpu.append(time.process_time() - t0)
        return out

    fast = benchmark.pedantic(compiled, rounds=1, iterations=1)
    t_fast = min(cpu)
    monkeypatch.setattr(_kernels, "em_trials", lambda *a, **k: False)
    t0 = time.process_time()
    slow = unified_location_em(ent, start, g.sigma_px, p, p0, **run)
    t_slow = time.process_time() - t0
    assert np.array_equal(fast.theta, slow.theta) and np.array_equal(fast.n_iter, slow.n_iter)
    fig = figure(
        "002 per-frame marks: vectorised loop / compiled trial loop (same bits)", t_slow / t_fast, 2.0, at_least=True
    )
    assert fig.passed, fig.message()
