"""Rerun layout of notebook 001: run 0 of the scenario, both channels: a rendered crop around the object with the
predicted gate, truth, measurement and estimate (the prediction while lost); the trajectory; series of errors,
velocity, acceleration, detector statistic and threshold, kappa1 and the mode."""

from __future__ import annotations

import numpy as np

from ...filters.polynomial import predict_ahead
from ...plotting import ROLE_COLOURS, rgb
from ...recordings import Recorder, ellipse_outline, image_and_series_blueprint
from ...render import gate_origin, gaussian_spot

__all__ = ["blueprint", "record_run"]


def blueprint():
    """Crop and trajectory on the left, the time series stacked on the right."""
    return image_and_series_blueprint(
        "camera",
        ("errors", "velocity", "acceleration", "detector", "gain", "mode"),
        image_name="Crop around the object (elements)",
        series_names=(
            "Coordinate error (elements)",
            "Velocity x (elements/frame)",
            "Acceleration x (elements/frame²)",
            "Detector x: S and ±c",
            "κ1",
            "Mode (0 coast, 2, 3)",
        ),
        image_share=0.45,
        more_images=(("trajectory", "Trajectory (elements)"),),
    )


def record_run(
    rec: Recorder,
    out,
    z,
    truth,
    visible,
    rng: np.random.Generator,
    *,
    gate_sigma: float = 3.0,
    every: int = 2,
    crop_px: int = 64,
    spot_sigma_px: float = 1.5,
) -> None:
    """Log run 0 of a :class:`~.track_modes.TrackModeOutput` ``out`` (batch axes (runs, 2)).

    Parameters
    ----------
    z : ndarray, shape (2, T)    measurements of run 0, elements
    truth : ndarray, shape (2, T, 3)
    visible : ndarray of bool, shape (T,)
    rng : numpy.random.Generator   the crop's pixel noise
    every : int                  log every ``every``-th frame's crop
    """
    if not rec.enabled:
        return
    T = truth.shape[1]
    true_xy, meas_xy, est_xy = truth[:, :, 0].T, z.T, out.x[0, :, :, 0].T
    gate_sd = np.sqrt(out.gate_var[0]).T
    prev = np.concatenate([np.zeros((2, 1, 3)), out.x[0, :, :-1]], axis=1)
    pred_xy = predict_ahead(prev, 1).T
    size = (crop_px, crop_px)
    origins = gate_origin(true_xy, size)
    for f in range(0, T, every):
        rec.set_frame(f)
        o = origins[f]
        rec.image("camera/image", _crop_image(true_xy[f], o, visible[f], size, spot_sigma_px, rng))
        rec.boxes("camera/gate", pred_xy[f] - o, gate_sigma * gate_sd[f], colors=[rgb(ROLE_COLOURS["gate"])])
        _log_crop_points(rec, true_xy[f] - o, meas_xy[f] - o, est_xy[f] - o, visible[f])
    rec.set_frame(0)
    _log_trajectory(rec, true_xy, est_xy)
    _log_series(rec, out, truth)


def _crop_image(xy, origin, visible: bool, size, spot_sigma_px: float, rng: np.random.Generator) -> np.ndarray:
    """One frame's rendered crop (uint8, shape ``size``): the object's Gaussian spot at ``xy`` (elements) on a dark
    background, or the uniform cloud while it is not visible, plus pixel noise (RMS 3 grey levels)."""
    if visible:
        img = 20 + gaussian_spot(xy, size, spot_sigma_px, 2 * np.pi * spot_sigma_px**2 * 200, origin=origin)
    else:
        img = np.full(size, 90.0)  # the cloud: object not visible
    return np.clip(img + rng.normal(0, 3, size), 0, 255).astype(np.uint8)


def _log_crop_points(rec: Recorder, true_xy, meas_xy, est_xy, visible: bool) -> None:
    """One frame's truth ring, estimate and, while visible, the measurement (else the prediction), each (2,) in
    crop coordinates (elements)."""
    none = np.zeros((0, 2))
    rec.lines(
        "camera/truth", ellipse_outline(true_xy, 4.0 * np.eye(2)), colors=[rgb(ROLE_COLOURS["truth"])], radii=-1.5
    )
    rec.points("camera/estimate", est_xy, colors=[rgb(ROLE_COLOURS["estimate"])], radii=-4.0)
    rec.points("camera/measured", meas_xy if visible else none, colors=[rgb(ROLE_COLOURS["measurement"])], radii=-3.0)
    rec.points("camera/predicted", none if visible else est_xy, colors=[rgb(ROLE_COLOURS["prediction"])], radii=-4.0)


def _log_trajectory(rec: Recorder, true_xy, est_xy) -> None:
    """The true and estimated trajectories, (T, 2) elements, every 5th frame."""
    # the estimate follows the truth closely: the truth is drawn wider and below, so both stay visible
    rec.lines(
        "trajectory/truth",
        true_xy[::5],
        colors=[rgb(ROLE_COLOURS["truth"])],
        radii=-3.0,
        image_space=False,
        draw_order=10.0,
    )
    rec.lines(
        "trajectory/estimate",
        est_xy[::5],
        colors=[rgb(ROLE_COLOURS["estimate"])],
        radii=-1.0,
        image_space=False,
        draw_order=20.0,
    )


def _log_series(rec: Recorder, out, truth) -> None:
    """Run 0's time series: errors, kappa1 and mode of both channels; velocity, acceleration and the detector of
    channel x; a text entry at each mode change of channel x."""
    for c, nm in enumerate(("x", "y")):
        rec.series(f"errors/{nm}", out.x[0, c, :, 0] - truth[c, :, 0])
        rec.series(f"gain/kappa1_{nm}", out.gains[0, c, :, 0])
        rec.series(f"mode/{nm}", out.mode[0, c].astype(float))
    rec.series("velocity/true", truth[0, :, 1])
    rec.series("velocity/estimate", out.x[0, 0, :, 1])
    rec.series("acceleration/true", truth[0, :, 2])
    rec.series("acceleration/estimate", out.x[0, 0, :, 2])
    rec.series("detector/S", out.statistic[0, 0])
    rec.series("detector/threshold_plus", out.threshold[0, 0])
    rec.series("detector/threshold_minus", -out.threshold[0, 0])
    for f in np.where(np.diff(out.mode[0, 0].astype(int)) != 0)[0] + 1:
        rec.set_frame(int(f))
        rec.text("log/mode_x", f"channel x: mode {out.mode[0, 0, f - 1]} -> {out.mode[0, 0, f]}")


#: The viewer check's deviations from its default expectation (``tvtrack.contract.VIEWER_KEYS``): the truth ring
#: and estimate dot are sized in screen points, and each must stay clearly visible (was 9-35 px).
VIEWER_EXPECTATIONS = {"min_overlay_px": 30}
