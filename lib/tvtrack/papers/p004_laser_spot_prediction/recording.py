"""The Rerun recording of paper 004: the gate images, centres and errors of path 1 of a run."""

from __future__ import annotations

import numpy as np

from ...filters.polynomial import growing_memory_gains
from ...plotting import colour, rgb
from ...recordings import Recorder, image_and_series_blueprint
from . import predictors as pr
from .prediction_study import PAPER
from .spot_centre import centroid_mask

__all__ = ["blueprint", "gain_used", "record_run"]


def blueprint():
    """Camera on the left; errors, centres and the filter's position gain stacked on the right."""
    return image_and_series_blueprint(
        "camera",
        ("errors", "centre", "filter"),
        image_name="camera (gate, mask, truth, measured, predicted)",
        series_names=("prediction error (px)", "centre x and y (px)", "position gain g1 used"),
    )


def gain_used(floor: int, n_frames: int, order: int = 2) -> np.ndarray:
    """The position gain ``g_{min(N, N_f), 1}`` the floored filter applies at each frame (N = frame + 1)."""
    g = growing_memory_gains(order, floor)[:, 0]
    return g[np.minimum(np.arange(n_frames), floor - 1)]


def record_run(rec: Recorder, run, every: int = 1) -> None:
    """Log path 1 of ``run`` (its gates kept): gate image with the weighted pixels tinted, gate box,
    centroid window, trail, true / measured / predicted centre; the errors, the coordinates and the
    position gain of the floor the path's prediction actually used (its cross-validated N_f)."""
    trk, cam = run.track, run.camera
    m = int(run.config["horizon"])
    meas = np.moveaxis(run.z_meas[0, 0], 0, -1)
    truth = np.moveaxis(run.truth[0, 0], 0, -1)
    fc = run.forecasts[PAPER][0, 0]
    T = meas.shape[0]
    half = (cam.gate_size_px - 1) / 2
    full = 2**cam.bit_depth - 1
    masks = centroid_mask(
        trk.gates, trk.origin[0, 0], meas, window_px=cam.window_px, threshold_sigma=cam.threshold_sigma
    )
    for t in range(0, T, every):
        rec.set_frame(t)
        g8 = np.clip(trk.gates[t] * 255.0 / full, 0, 255).astype(np.uint8)
        img = np.stack([g8, g8, g8], axis=-1)
        img[masks[t], 0] //= 3  # weighted pixels tinted cyan
        rec.image("camera/gate", img, offset=trk.origin[0, 0, t])
        rec.boxes(
            "camera/gate_box", trk.origin[0, 0, t] + half, [cam.gate_size_px / 2] * 2, colors=[rgb(colour("gate"))]
        )
        if np.all(np.isfinite(meas[t])):
            rec.boxes("camera/centroid_window", meas[t], [cam.window_px / 2] * 2, colors=[[0, 255, 255]])
            rec.points("camera/measured", meas[t], colors=[rgb(colour("measurement"))], radii=0.9)
        rec.lines("camera/trail", meas[max(0, t - 25) : t + 1], colors=[rgb(colour("measurement"))], radii=0.08)
        rec.points("camera/truth", truth[t], colors=[rgb(colour("truth"))], radii=0.4, draw_order=40.0)
        if t >= m and np.all(np.isfinite(fc[:, t - m])):
            rec.points("camera/predicted", fc[:, t - m], colors=[rgb(colour("prediction"))], radii=0.6)
    err = pr.forecast_errors(run.forecasts[PAPER], run.z_meas, m)[0, 0]
    rec.series("errors/x", err[0])
    rec.series("errors/y", err[1])
    for a, axis in enumerate("xy"):
        rec.series(f"centre/{axis}_true", truth[:, a])
        rec.series(f"centre/{axis}_measured", meas[:, a])
        rec.series(f"centre/{axis}_predicted", np.concatenate([np.full(m, np.nan), fc[a, :-m]]))
    rec.series("filter/g1", gain_used(int(run.comparison.chosen[PAPER][0]), T))


#: The viewer check's deviations from its default expectation (``tvtrack.contract.VIEWER_KEYS``): the paper's
#: estimates are the measured spot centre and the centre predicted ahead.
VIEWER_EXPECTATIONS = {"overlays": ("gate", "truth", "measured", "predicted")}
