"""C004-8's timing of paper 004 (Kokryatska and Hrynchyshyn 2005): the time per frame of the energy centre, one step
of the recursion and the prediction, batched or frame by frame as the frames arrive (the register's C004-8
readings). :mod:`.study` reads it in its claim values; ``run`` is a :class:`.study.StudyRun`."""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from ...filters.polynomial import (
    growing_memory_filter,
    growing_memory_gains,
    polynomial_observation_row,
    predict_ahead,
    taylor_transition,
)
from ...measure import centroid
from ...render import gate_origin, gaussian_spot, sensor_readout

# ``run`` below is a :class:`.study.StudyRun` (not imported: study imports this module)
StudyRun = Any

__all__ = ["CLOCKS", "streaming_frame_times", "frame_time_ms"]


#: The clocks of the "C004-8 clock" reading: CPU time of the process, or wall-clock time.
CLOCKS = {"CPU": time.process_time, "wall": time.perf_counter}


def frame_time_ms(run: StudyRun, rng: np.random.Generator, config: dict) -> float:
    """Time per frame, ms, at the C004-8 readings: the batched plain centroid's mean (default), or the
    streaming pipeline's mean or 99th percentile over frames after the first (warm-up); the streaming
    pipeline measures in the gate or (``C004-8 frame`` = "whole frame") over the whole frame, and
    ``C004-8 clock`` reads CPU or wall-clock time."""
    pipeline = config.get("C004-8 pipeline", "batched plain centroid")
    statistic = config.get("C004-8 statistic", "mean")
    whole = config.get("C004-8 frame", "gate") == "whole frame"
    clock = CLOCKS[config.get("C004-8 clock", "CPU")]
    if pipeline == "batched plain centroid" and statistic == "mean" and not whole:
        return _time_per_frame(run, rng, clock)
    # per-frame times exist only for the streaming pipeline (the 99th percentile and the whole-frame reading);
    # on the wall clock the frames another process preempted are left out (a dedicated core, as the paper's PC)
    wall = clock is CLOCKS["wall"]
    t = streaming_frame_times(run, rng, whole_frame=whole, clock=clock, drop_preempted=wall)[0][1:] * 1e3
    return float(np.nanmean(t) if statistic == "mean" else np.nanquantile(t, 0.99))


def _time_per_frame(run: StudyRun, rng: np.random.Generator, clock=time.process_time) -> float:
    """ms per full 128 x 128 frame (``clock``: CPU by default): centroid, filter update and one-step
    prediction, batched over the frames."""
    nt = min(run.size.timing_frames, run.truth.shape[-1])
    cam = run.camera
    xy = np.moveaxis(run.truth[0, 0, :, :nt], 0, -1)
    frames = sensor_readout(
        gaussian_spot(xy, (run.scene.image_size_px,) * 2, cam.spot_sigma_px, cam.flux_e),
        rng,
        background=cam.background_dn,
        read_noise=cam.read_noise_dn,
        bit_depth=cam.bit_depth,
    )
    t0 = clock()
    cm = centroid(frames, background="border", threshold_sigma=cam.threshold_sigma)
    predict_ahead(growing_memory_filter(np.moveaxis(cm.xy, -1, 0), 2, run.size.fixed_floor), 1)
    return (clock() - t0) / nt * 1e3


def _involuntary_switches() -> int:
    """Involuntary context switches of this process so far (another process took the core)."""
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_nivcsw


def streaming_frame_times(
    run: StudyRun,
    rng: np.random.Generator,
    whole_frame: bool = False,
    clock=time.process_time,
    drop_preempted: bool = False,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each frame processed as it arrives (the "streaming" reading of C004-8): from the full 128 x 128
    frame, crop the gate around the one-step prediction, measure the study's energy centre in it (the
    camera's ``centroid_mode``), run one step of the recursion (5)-(6) with the fixed floor's precomputed
    gains and predict one frame ahead. ``whole_frame``: no gate, the energy centre runs over the whole
    frame (the windowed one started at the prediction). ``drop_preempted``: a frame during which the process
    was preempted (an involuntary context switch: another process took the core) gets a NaN time, so a
    wall clock measures the pipeline on a dedicated core, not the other tenants of a shared machine.

    Returns
    -------
    times : ndarray, shape (n,)
        Seconds of each frame on ``clock`` (CPU time, ``time.process_time``, by default).
    states : ndarray, shape (n, 2, 3)
        The recursion's state after each frame (per axis; NaN before the first three), for tests.
    measured : ndarray, shape (n, 2)
        The centres the recursion was fed, px (a frame with nothing above threshold: the prediction).
    """
    from .spot_centre import windowed_centroid

    nt = min(run.size.timing_frames, run.truth.shape[-1])
    cam, size = run.camera, run.scene.image_size_px
    xy = np.moveaxis(run.truth[0, 0, :, :nt], 0, -1)
    frames = sensor_readout(
        gaussian_spot(xy, (size, size), cam.spot_sigma_px, cam.flux_e),
        rng,
        background=cam.background_dn,
        read_noise=cam.read_noise_dn,
        bit_depth=cam.bit_depth,
    )
    g, nf = cam.gate_size_px, run.size.fixed_floor
    F = taylor_transition(2)
    gains = growing_memory_gains(2, nf)
    H0 = polynomial_observation_row(2, np.arange(3)[::-1])  # the first three samples, oldest first
    times, states, measured = np.empty(nt), np.full((nt, 2, 3), np.nan), np.empty((nt, 2))
    aim, first, x = xy[0], [], None
    for t in range(nt):
        n0 = _involuntary_switches() if drop_preempted else 0
        t0 = clock()
        if whole_frame:
            o, gate = np.zeros(2, int), frames[t]
        else:
            o = np.clip(gate_origin(aim, (g, g)), 0, size - g)
            gate = frames[t, o[1] : o[1] + g, o[0] : o[0] + g]
        if cam.centroid_mode == "windowed":
            start = aim if whole_frame else None  # in a gate the window starts at its centre, the prediction
            m = windowed_centroid(gate, o, window_px=cam.window_px, threshold_sigma=cam.threshold_sigma, start=start)
        else:
            m = centroid(gate, o, background="border", threshold_sigma=cam.threshold_sigma)
        z = m.xy if m.valid else aim
        if x is None:
            first.append(z)
            if len(first) == 3:
                x = np.linalg.solve(H0, np.asarray(first))  # (3 states, 2 axes): eq. (4) on 3 samples
        else:
            x = F @ x
            x = x + gains[min(t + 1, nf) - 1][:, None] * (z - x[0])[None, :]
        if x is not None:
            aim = (F @ x)[0]  # the one-step prediction centres the next gate
            states[t] = x.T
        times[t] = clock() - t0
        if drop_preempted and _involuntary_switches() != n0:
            times[t] = np.nan
        measured[t] = z
    return times, states, measured
