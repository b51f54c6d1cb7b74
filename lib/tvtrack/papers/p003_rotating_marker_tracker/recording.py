"""Rerun layout of notebook 003's showcase run: the camera zoomed on the object with the gate, the marker and the
estimated circle, and the state errors, discriminator outputs and lock flag as time series."""

from __future__ import annotations

import numpy as np

from ...recordings import Recorder, image_and_series_blueprint
from .scene import state_errors

__all__ = ["blueprint", "record_showcase"]


def blueprint():
    """Camera on the left; errors, discriminator outputs and lock on the right (frame timeline)."""
    return image_and_series_blueprint(
        "camera",
        ("errors", "discriminator", "lock"),
        image_name="Camera (zoomed on the object)",
        series_names=(
            "state errors (px, rad, rad/s)",
            "discriminator outputs / S (px)",
            "lock flag and miss distance (px)",
        ),
    )


def _to8(img):
    return np.clip((img + 0.25) * 180, 0, 255).astype(np.uint8)


def record_showcase(
    rec: Recorder,
    truth,
    scene,
    hist,
    crops,
    origins,
    *,
    gate_half: float,
    n_frames: int,
    full_every: int,
    rev_frames: int,
    loss_frame: int,
    rng,
) -> None:
    """Log one run (trial 0) frame by frame.

    Parameters
    ----------
    rec : Recorder
    truth, scene, hist
        From :func:`.scene.run_scenario` (``keep_full=True``).
    crops, origins : list of ndarray
        Trial 0's gate crop and its origin at every frame (what the discriminator read).
    gate_half : float
        Gate half-size (px).
    n_frames : int
        Frames to log.
    full_every : int
        Log the full frame every ``full_every`` frames (the gate crop every frame).
    rev_frames : int
        Frames per revolution (length of the logged gate path).
    loss_frame : int
        First loss frame of trial 0 (-1: kept lock).
    """
    rec.set_frame(0)
    rec.points("camera/interferers", scene.interferers[0], colors=[255, 60, 60], radii=1.5)
    circle = np.stack([np.cos(np.linspace(0, 2 * np.pi, 49)), np.sin(np.linspace(0, 2 * np.pi, 49))], axis=1)
    A = gate_half
    for k in range(n_frames):
        rec.set_frame(k)
        if k % full_every == 0:
            rec.image("camera/image", _to8(scene.frame(0, k, rng)), jpeg_quality=80, draw_order=0.0)
        rec.image("camera/frame_in_gate", _to8(crops[k]), offset=origins[k], draw_order=1.0)
        g, est = hist.gate[0, k], hist.estimate[0, k]
        rec.boxes("camera/gate", g, [A, A], colors=[0, 200, 255])
        rec.lines(
            "camera/gate_quadrants",
            [np.array([[g[0] - A, g[1]], [g[0] + A, g[1]]]), np.array([[g[0], g[1] - A], [g[0], g[1] + A]])],
            colors=[0, 200, 255],
        )
        rec.points("camera/marker/truth", truth.marker[0, k], colors=[0, 255, 0], radii=1.2)
        rec.points("camera/marker/estimate", g, colors=[255, 0, 255], radii=1.2)
        rec.points("camera/center/truth", truth.center[0, k], colors=[0, 255, 0], radii=1.0)
        rec.points("camera/center/estimate", est[:2], colors=[255, 0, 255], radii=1.0)
        rec.lines("camera/circle/estimate", est[:2] + est[2] * circle, colors=[255, 0, 255])
        rec.lines("camera/gate_path", hist.gate[0, max(0, k - rev_frames) : k + 1], colors=[0, 200, 255])
    e = state_errors(truth, hist)
    locked = np.ones(n_frames)
    if loss_frame >= 0:
        locked[loss_frame:] = 0
    for i, name in enumerate(["x_r_px", "y_r_px", "r_px", "theta_rad", "omega_rad_s"]):
        rec.series(f"errors/{name}", e[0, :n_frames, i])
    for i, name in enumerate(["delta_x", "delta_y", "e_r", "e_theta"]):
        rec.series(f"discriminator/{name}", hist.disc[0, :n_frames, i])
    rec.series("lock/locked", locked)
    rec.series("lock/miss_px", hist.miss[0, :n_frames])
    if 0 <= loss_frame < n_frames:
        rec.set_frame(int(loss_frame))
        rec.text("lock/events", "loss of lock", level="WARN")


#: The viewer check's deviations from its default expectation (``tvtrack.contract.VIEWER_KEYS``): none.
VIEWER_EXPECTATIONS: dict = {}
