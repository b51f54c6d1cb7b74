"""Notebook 003 beyond the paper (moved from :mod:`.study`): frame-rate smear and the static baseline at matched
exposure (:func:`exposure_study`), and one trial of the temporal-median compensation (:func:`median_example`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .scene import Scenario, scenario_truth
from .backdrop import median_residual, place_interferers
from .draws import stream_rng
from .study import Sizes, measure_interference, measure_tracking, scenario

__all__ = ["exposure_study", "median_example"]


def exposure_study(seed: int, sizes: Sizes, sizes_i: Sizes, fps: float) -> dict:
    """Frame-rate smear (beyond the paper) and the static baseline at matched exposure, at frame rate ``fps``.

    Both exposure models on the same draws: ``"instant"`` (the marker sampled at the frame time) and ``"integrated"``
    (the sensor integrates over the frame, so the rotating marker is smeared along the arc ``2 pi f_rot r / fps`` it
    turns in a frame, while the static baseline's emitter, held still, keeps its spot: the same spot energy per frame,
    sensor noise and exposure model for both markers, i.e. matched exposure).

    Returns
    -------
    dict
        ``{exposure: {"x_r_rms_px": Estimate (Fig. 1 RMS x_r error, px), "thresholds": {"rotating 1", "rotating 5",
        "static 1", "static 5"}: Estimate (the bound each threshold's grid censoring certifies, SIR)}}`` and
        ``"arc_px"``: the marker's arc per frame (px).
    """
    out = {}
    for e in ("instant", "integrated"):
        cfg = {"fps": float(fps), "exposure": e}
        out[e] = {
            "x_r_rms_px": measure_tracking(cfg, seed, sizes)["C003-1"]["x_r"],
            "thresholds": measure_interference(cfg, seed, sizes_i)["_map_bound"],
        }
    sc = scenario({"fps": float(fps)}, sizes)
    out["arc_px"] = float(sc.omega0 * sc.radius / sc.fps)
    return out


def median_example(seed: int, sc: Scenario) -> dict:
    """One trial of the temporal-median compensation (beyond the paper) for :func:`.plots.median_figure`: the truth, the
    interferers about its start and the residual the median of the first ``sc.median_revolutions`` revolutions leaves
    (:func:`.scene.median_residual`, the marker masked out: the background cancels; the interferers are added at
    ``d / SIR`` in the runs).

    Returns
    -------
    dict
        ``residual`` (rows, cols), ``truth`` (one trial), ``interferers`` (count, 2) px, ``n_frames``, ``noise_std``.
    """
    rng = stream_rng(50, seed)
    n_frames = int(np.ceil(sc.median_revolutions * sc.fps / sc.rotation_hz))
    truth = scenario_truth(rng, 1, replace(sc, duration_s=max(sc.duration_s, (n_frames + 1) / sc.fps)))
    q = place_interferers(rng, 1, sc.n_interferers, truth.center[:, 0], sc.radius)
    shape = (sc.image_size, sc.image_size)
    res = median_residual(rng, truth, n_frames, shape, sc.spot, sc.diameter, sc.brightness, sc.noise_std)
    return dict(residual=res[0], truth=truth, interferers=q[0], n_frames=n_frames, noise_std=sc.noise_std)
