"""Speed of notebook 004: measurement + filter + prediction on gate crops, and one full-size measurement.

Work: 15 paths x 1000 frames of 31 x 31 gate crops (rendered and read out beforehand,
not timed): energy centre with border-median background and 3-sigma threshold
(:func:`tvtrack.measure.centroid`), the growing-memory filter with floor N_f = 10 on x and y and
its one-frame prediction (:func:`tvtrack.papers.p004_laser_spot_prediction.predictors.growing_memory_forecast`: the core filter for
the first N_f frames, then the fixed-gain filter as an IIR filter).
Targets: >= 50,000 gate-crop frames/s on one core; one full-size measurement of the explorer
(:func:`tvtrack.papers.p004_laser_spot_prediction.study.measure`: 15 paths x 1000 frames rendered and
measured, 1.3 CPU s, then predicted by the paper's filter and every baseline a claim reads, each tuned; the two
networks with their lag counts cross-validated are most of it) < 10 s CPU. Measured on one core: 6.2
CPU s before the measurement ran only what its claims read (the ML Kalman filters, the variant floor and the fading
memory are the notebook's figures, no claim's value) and the networks were fitted without scikit-learn's per-call
validation, 4.8 s after. Measured again on the shared two-core machine (one BLAS thread, as ``make reproduce`` gives each
kernel; ``measure_batch`` of one configuration at seed 1, process CPU, the old and the new code run alternately, best
of 3): 6.89 CPU s at the default before the networks' training loop indexed its arrays directly and back-propagated
without scikit-learn's per-call dispatch (:func:`.learned._adam_epochs`: ``_safe_indexing`` asked for every
mini-batch whether the array was a data frame; the same networks bit for bit), 5.80 after; absolute centres fed to the
networks 9.57 -> 7.30; 200 frames/s at horizon 10 9.04 -> 8.11 (a network fit: 0.45 -> 0.29 CPU s at 500 pairs,
1.65 -> 1.0 at 4000). With ``n_workers`` > 1 the scenes
and runs a worker process computed used to end with the call's process pool, so the subset search rendered and fitted
again what the one-at-a-time and joint stages had measured; a worker now sends them back to the parent's cache, and a
scene is keyed by what it reads (a bandwidth set by hand makes the band position no input): four pairs reusing three
singles' scenes (9 paths x 300 frames, 2 workers, CPU of the process and its workers) took 11.3 CPU s before, 1.7
after. Where the notebook's paper-profile time goes (one run, n_workers=1, nice 10, CPU s): the
exploration 214 (replicates 12, one at a time 89 over 40 configurations, joint 112 over 32, pinned 0.1,
combinations 1.5: the combinations' scenes and methods are already cached in the one process), the studies beyond it
about 19 (calibration 7.8, the shipped run with every method 5.3, horizon study 1.9, measurement budget 1.6,
recording 1.0, figures 1.2). The notebook's paper-profile CPU time is
the row ``004 paper-profile CPU s (last reproduce)`` of ``bench_runner`` (from the last ``make reproduce``; the
budget is the total, 15 minutes wall on 2 cores): a second paper-profile run here would only repeat it.

The frame rate is asserted on process CPU time (best of 5; numpy here runs on one core), because
the development machine is shared and wall time there measures the other users; the wall-clock
rate is reported beside it (``extra_info``).
"""

import time

import numpy as np

from tvtrack.papers.p004_laser_spot_prediction.spot_centre import windowed_centroid
from tvtrack.papers.p004_laser_spot_prediction.predictors import growing_memory_forecast
from tvtrack.papers.p004_laser_spot_prediction.traces import DATA_DIR
from tvtrack.render import gate_origin, gaussian_spot, sensor_readout
from tvtrack.papers.p004_laser_spot_prediction.camera import SpotCamera
from tvtrack.papers.p004_laser_spot_prediction.traces import load_traces

TARGET_FRAMES_PER_S = 50_000
TARGET_MEASURE_CPU_S = 10.0


def gate_crops():
    tr = load_traces(DATA_DIR / "laser_traces" / "traces.npz")
    cam = SpotCamera()
    g = cam.gate_size_px
    aim = np.concatenate([tr.centres_px[:, :1], tr.centres_px[:, :-1]], axis=1)  # previous frame
    origin = gate_origin(aim, (g, g))
    signal = gaussian_spot(tr.centres_px, (g, g), cam.spot_sigma_px, cam.flux_e * tr.intensity, origin=origin)
    crops = sensor_readout(
        signal,
        np.random.default_rng(0),
        background=cam.background_dn,
        read_noise=cam.read_noise_dn,
        bit_depth=cam.bit_depth,
    )
    return crops, origin, tr.centres_px


def measure_filter_predict(crops, origin):
    c = windowed_centroid(crops, origin, window_px=SpotCamera().window_px, threshold_sigma=3.0)
    z = np.moveaxis(c.xy, -1, -2)  # (paths, axis, T)
    return growing_memory_forecast(z, 1, 2, 10)


def test_gate_crop_pipeline_frames_per_s(benchmark, figure):
    crops, origin, truth = gate_crops()
    n_frames = crops.shape[0] * crops.shape[1]
    pred = benchmark.pedantic(measure_filter_predict, args=(crops, origin), rounds=5, iterations=1, warmup_rounds=1)
    e = pred[..., :-1] - np.moveaxis(truth, -1, -2)[..., 1:]
    assert np.sqrt(np.nanmean(e**2)) < 2.0  # sane output, not only fast
    cpu = []
    for _ in range(5):
        t0 = time.process_time()
        measure_filter_predict(crops, origin)
        cpu.append(time.process_time() - t0)
    rate = n_frames / min(cpu)
    benchmark.extra_info["frames_per_cpu_s"] = rate
    benchmark.extra_info["frames_per_wall_s"] = n_frames / benchmark.stats.stats.min
    fig = figure("004 gate-crop frames per CPU s", rate, TARGET_FRAMES_PER_S, at_least=True)
    assert fig.passed, fig.message()


def test_one_full_size_measurement_cpu_s(benchmark, figure):
    """CPU time of one full-size run of the study at the default reading (the explorer's unit of work)."""
    from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT
    from tvtrack.papers.p004_laser_spot_prediction.study import measure

    t0 = time.process_time()
    out = benchmark.pedantic(measure, args=(dict(DEFAULT), 1), rounds=1, iterations=1)
    cpu = time.process_time() - t0
    benchmark.extra_info["measure_cpu_s"] = cpu
    assert 0.1 < out["C004-2"].value < 2.0  # sane output, not only fast
    fig = figure("004 one full-size measurement CPU s", cpu, TARGET_MEASURE_CPU_S, at_least=False, unit="s")
    assert fig.passed, fig.message()
