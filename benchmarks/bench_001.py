"""Speed of notebook 001's full scenario: the batched mode logic vs a per-trial filterpy loop.

Work: 1000 runs x 2 channels x 625 frames (25 s at 25 Hz) of the paper's scheme: TRACK2
alpha-beta filter with the bounded growing-memory gains, the two-window detector with the exact
correlated threshold, the switch to the alpha-beta-gamma law and coasting through the loss.
The reference runs the same logic one trial-channel at a time with ``filterpy.gh.GHKFilter``
(gain overrides per update; its ``k`` is kappa3/2). It is timed on a subset of trial-channels in
the same benchmark run and scaled linearly (a per-trial loop's cost is linear in the number of
trials); the subset's detections and states must equal the batched ones.
Targets: >= 100x (issue 4, asserted); >= 400x (issue 30, reported as ``target_400x_met``). Where the time
goes (profiled 2026-11-25): the batched run is one Python loop over the 625 frames of about 25 in-place NumPy
operations on (2000,) arrays (filter update, running window sums, the per-channel gain gathers after the switch),
i.e. about 100 us per frame, which is NumPy's per-call overhead, not arithmetic. On this shared 2-core machine the
ratio measures 140-240x (it moves with the load of the other jobs). Two specialised paths, both tested equal to the
general loop and then dropped, were not measurably faster under that load: TRACK2 for every channel first and
TRACK3 shifted by each channel's detection frame (the (T, 3, B) assembly cost what the loops saved), and a lockstep
loop with the state as one (3, B) array (45-80 ms against the general loop's 55-70 ms). Reaching 400x needs the frame loop compiled (numba,
not in environment.txt) or the fixed-gain segments as ``scipy.signal.lfilter`` calls; see the 001 report.
"""

import time

import numpy as np
from filterpy.gh import GHKFilter

from tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector import scheduled_statistic_std, threshold_from_std
from tvtrack.filters.alphabeta import gain_schedule
from tvtrack.papers.p001_maneuver_occlusion_kf.track_modes import TrackModeConfig, run_track_modes

N_TRIALS, N_CH, FPS, T = 1000, 2, 25.0, 625
KB2, KB3, N_WIN, ALPHA = 50, 100, 25, 1e-3
N_REF = 20  # trial-channels timed with the per-trial reference


def scenario(seed=0):
    f = np.arange(T)
    truth = 10.0 * f + 0.1 * np.clip(f - 125, 0, None) ** 2
    z = truth + np.random.default_rng(seed).standard_normal((N_TRIALS, N_CH, T))
    visible = (f < 300) | (f >= 550)
    c = threshold_from_std(ALPHA, scheduled_statistic_std(gain_schedule(1, KB2, T), N_WIN, 1.0))
    return z, visible, np.where(np.isfinite(c), c, np.inf)


def reference_one(z, visible, thr):
    """The paper's per-channel logic for one sequence with filterpy's g-h-k filter."""
    K2, K3 = gain_schedule(1, KB2), gain_schedule(2, KB3)
    flt = GHKFilter(0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)
    k, mode, since, det = 0, 2, 0, -1
    v = np.full(T, np.nan)
    xs = np.empty((T, 3))
    for t in range(T):
        if visible[t]:
            k += 1
            since += 1
            g = K3[min(k, KB3) - 1] if mode == 3 else np.r_[K2[min(k, KB2) - 1], 0.0]
            flt.update(z[t], g=g[0], h=g[1], k=g[2] / 2)
        else:
            since = 0
            flt.update(0.0, g=0.0, h=0.0, k=0.0)
        v[t] = flt.dx
        if mode == 2 and visible[t] and k >= KB2 + 2 * N_WIN and since >= 2 * N_WIN:
            S = v[t - 2 * N_WIN + 1 : t - N_WIN + 1].sum() - v[t - N_WIN + 1 : t + 1].sum()
            if abs(S) > thr[min(k, thr.size) - 1]:
                det, mode, k, flt.ddx = t, 3, 3, 0.0
        xs[t] = flt.x, flt.dx, flt.ddx
    return xs, det


def test_full_scenario_speedup(benchmark, figure):
    z, visible, thr = scenario()
    cfg = TrackModeConfig(k_bound2=KB2, k_bound3=KB3, window=N_WIN, threshold=thr)
    out = benchmark.pedantic(run_track_modes, args=(z, visible, cfg, 1.0, False), rounds=5, iterations=1)
    t_batched = benchmark.stats.stats.min

    flat = z.reshape(-1, T)
    t0 = time.perf_counter()
    ref = [reference_one(flat[i], visible, thr) for i in range(N_REF)]
    t_ref = (time.perf_counter() - t0) / N_REF * N_TRIALS * N_CH
    det = out.detection_frame.reshape(-1)[:N_REF]
    np.testing.assert_array_equal(det, [d for _, d in ref])
    np.testing.assert_allclose(out.x.reshape(-1, T, 3)[:N_REF], np.stack([x for x, _ in ref]), rtol=1e-9, atol=1e-6)
    speedup = t_ref / t_batched
    benchmark.extra_info.update(
        batched_s=t_batched, filterpy_loop_s_extrapolated=t_ref, speedup=speedup, target_400x_met=bool(speedup >= 400)
    )
    print(
        f"\nbatched {t_batched:.2f} s; filterpy per-trial loop {t_ref:.1f} s (from {N_REF} trial-channels); "
        f"speed-up {speedup:.0f}x"
    )
    fig = figure("001 batched scenario over per-trial filterpy loop (same run)", speedup, 100, at_least=True, unit="x")
    assert fig.passed, fig.message()
