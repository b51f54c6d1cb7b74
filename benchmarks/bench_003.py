"""Speed targets of notebook 003 (issues 7 and 27).

- Gate-crop tracking throughput: rendering + quadrant discriminator + five-state loops, batched
  over trials (200 runs of 1 s, five interferers, static scene set-up included), >= 20,000
  frames/s on one core.
- The paper profile's interference exploration under 4 CPU minutes: per configuration of the register
  (``study.measure_interference``) 378 runs of 5 s at 500 frames/s (rotating and static markers with one
  and five interferers, two gate sizes and the decoy on 8 SIRs x 6 runs, 5 x 6 runs without compensation,
  2 x 6 runs for the loop bandwidths), and about 31 configurations (3-4 replicates, 26 one-at-a-time values
  in run-time equivalents, 1 joint sample): about 29 M gate frames. Projected from the marginal CPU cost per
  frame of a 225-run batch (3 seeds x 15 SIRs x 5 runs, common random numbers), from runs of 0.5 s and 1 s.

Where the time goes (cProfile of ``run_scenario`` with five interferers, 1 s at 500 frames/s, 2026-11-25, load ~3):
240 trials take 2.1 s (8.6 us per trial-frame): the correlated static background (``correlated_background``,
``scipy.ndimage.correlate1d`` 0.55 s of its 0.99 s) and ``static_residual`` are ~50 %, the closed loop over frames
(``run_closed_loop``: ``gate_crops`` with its ``take`` gathers 0.43 s, ``disc_spot`` 0.16 s, the discriminator and
the five-state loop update) ~37 %, the scene set-up ~10 %. At 30 trials the loop costs ~370 us per frame step, most
of it NumPy call overhead; at 240 trials ~1.5 ms per step, mostly the gathers. A compiled frame loop would save the
per-step overhead (~0.15-0.2 s per 500-frame batch, ~10-20 % of a 240-trial run) and little of the gathers; the
background generation, the larger share, gains nothing from a JIT (it is already one scipy call) but could be drawn
once per scene and shared across the configurations that do not change it (common random numbers).

Per configuration, 2026-11-28 (CPU s of one process, paper sizes, main and this tree side by side at a
load of 2): ``measure_interference`` at the default 3.6 s (4.8 s before), a joint-like configuration (integrated
exposure at 250 frames/s, centroid static baseline, 2D interferers, random motion) 4.3 s (5.4 s); the rotating pair
with the decoy riding as a third block, the static pair, two gate sizes, the uncompensated runs and the bandwidth pair
are six frame loops; a frame step costs ~130 us of NumPy calls plus ~3 us per run. ``measure_tracking`` 2.35 s (3.0 s):
six batches of 6-30 runs, ~125 us per frame step of call overhead (edge form with pixel noise ~190 us). The cuts,
all bit for bit: gathers through a window view, spots rendered over their 9 x 9 px box, one-pass quadrant weights,
the decoy in the rotating batch, an integrated exposure's sub-steps in one render. Across configurations the study
memo (``.memo``) reruns only the parts a register change touches (static gate, decoy brightness, static form: one
batch; compensation reading: none; Fig. 2 law: Fig. 2; edge normalisation: the two edge runs), and ``claims=``
skips the parts no asked claim reads. CPU seconds grow ~30 % under load (the same default configuration: 6.3 s at a
load of 8, 4.8 s at 2).

Per measurement call, 2026-12-04 (process CPU s, one process, paper sizes, seed 3, the memo empty, best of 2-5 runs of
main and this tree alternately at a load of 2.5-6: single runs varied by up to 50 %, the absolute numbers run high):
``measure_interference`` at the default 8.0 s (11.3 s before, 1.40x), fps 1000 18.1 s (24.3 s, 1.34x), integrated
exposure 16.3 s (21.1 s, 1.29x), horizon 2T 15.6 s (24.7 s, 1.58x); ``measure_tracking`` at the default 5.1 s (6.9 s,
1.36x), fps 1000 10.1 s (16.3 s, 1.61x), integrated exposure 7.8 s (8.4 s, 1.08x). The cuts, all bit for bit (every
output of both measurements at 3 configurations x 2 seeds, a memo sequence and the paper-size default compared): a
measurement's batches run side by side in one frame loop (``lockstep.run_together``: one tracker with per-run gains,
one scene and one set of discriminator calls per crop size and form; the interference study's six loops become one
with three crop groups, the tracking study's five one with four; Fig. 2, longer, runs alone), a loss curve's runs
leave the loop once lost (nothing it reads comes after a run's first loss: ~30 % of the curves' run-frames at the
default), the spot boxes of the marker and the lit decoys rendered 64 frames at a time (an integrated exposure's
sub-frame boxes 16; dark decoys not at all), the noise drawn 25 frames at a time. Peak memory of
``measure_interference`` 420 MB (234 MB before: the batches' images are held together).
"""

import time

import numpy as np

from tvtrack.papers.p003_rotating_marker_tracker.scene import Scenario, run_scenario

SIRS = np.array([0.5, 0.625, 0.75, 0.875, 1.0, 1.125, 1.25, 1.375, 1.5, 1.625, 1.75, 1.875, 2.0, 2.5, 3.0])
PAPER_LOSS_FRAMES = 500 * 5 * 378 * 31


def _batch(n_trials: int, duration_s: float, n_interferers: int = 5):
    sc = Scenario(duration_s=duration_s, n_interferers=n_interferers)
    sir = np.resize(SIRS, n_trials)
    run_scenario(np.random.default_rng(0), n_trials, sc, sir, keep_full=False)
    return n_trials * sc.n_frames


def test_gate_crop_frames_per_second(benchmark, figure):
    frames = 200 * 500
    cpu = []

    def batch():
        t0 = time.process_time()
        out = _batch(200, 1.0)
        cpu.append(time.process_time() - t0)
        return out

    result = benchmark.pedantic(batch, rounds=3, iterations=1)
    assert result == frames
    benchmark.extra_info["frames_per_wall_s"] = frames / benchmark.stats.stats.min
    fig = figure("003 gate-crop frames per CPU s", frames / min(cpu), 20_000, at_least=True)
    assert fig.passed, fig.message()


def _loss_batch_cpu(duration_s: float) -> float:
    sc = Scenario(duration_s=duration_s, n_interferers=5)
    sir = np.tile(np.repeat(SIRS, 5), 3)
    rngs = [np.random.default_rng([10, s]) for s in (3, 4, 5)]
    t0 = time.process_time()
    run_scenario(rngs, sir.size, sc, sir, keep_full=False, n_common=5)
    return time.process_time() - t0


def test_interference_exploration_paper_profile_under_4_minutes(benchmark, figure):
    short, long_ = benchmark.pedantic(lambda: (_loss_batch_cpu(0.5), _loss_batch_cpu(1.0)), rounds=1, iterations=1)
    per_frame = (long_ - short) / (3 * len(SIRS) * 5 * 0.5 * 500)
    projected = per_frame * PAPER_LOSS_FRAMES
    benchmark.extra_info["projected_loss_studies_cpu_s"] = projected
    fig = figure("003 interference exploration, projected CPU s", projected, 240, at_least=False, unit="s")
    assert fig.passed, fig.message()
