"""The Rerun layout of paper 000: one trial's scans (samples against scan phase with the true and predicted pulse,
the micro-raster gate, truth and estimate) and its time series (coordinate, noise intensity, error)."""

from __future__ import annotations

import numpy as np

from ...recordings import Recorder, image_and_series_blueprint
from .ekf import run_variant2, variant2_filter
from .model import DissectorScan, samples_from_pulse
from .study import D11_0, MESSAGE

__all__ = ["blueprint", "record_trial", "to_view"]


def blueprint():
    """The scan view on the left; the coordinate, the noise intensity and the error on the right."""
    return image_and_series_blueprint(
        "scan",
        ("track", "noise", "errors"),
        image_name="Scan: samples vs phase",
        series_names=("Coordinate (T)", "Noise intensity N/N0", "Error (T)"),
    )


def to_view(phase, value):
    """Scan-view coordinates of (scan phase, current) pairs: ``x = 100 tau``, ``y = 100 (1.3 - Y)`` (y points down)."""
    return np.stack([100 * np.asarray(phase), 100 * (1.3 - np.asarray(value))], axis=-1)


def record_trial(output_dir, mode: str, scan: DissectorScan, x, pulse, xi, n_scans: int, every: int = 1):
    """Record trial 0 of a run: ``x`` (n_trials, K + 1) truth, ``pulse``, ``xi`` (n_trials, K) its mean pulses and
    noise draws; variant 2 filters it. Returns the recording's file name, or None when ``mode`` is "off"."""
    y = samples_from_pulse(scan, pulse[:1], xi[:1])
    est, var = run_variant2(variant2_filter(scan, MESSAGE), y, D11_0)
    x, est, var, y = x[0], est[0], var[0], y[0]
    rec = Recorder(
        output_dir,
        mode,
        "tvtrack-000_dissector_ekf",
        blueprint=blueprint,
        frame_interval_s=scan.dt,
    )
    n_rec = min(n_scans * int(round(1.0 / scan.dt)), x.size - 1)
    phase_axis = np.linspace(0.0, 1.0, 101)
    x_pred = np.concatenate([[0.0], MESSAGE.euler(scan.dt)[0] * est[:-1]])
    for k in range(1, n_rec + 1, every):
        rec.set_frame(k)
        ks = np.arange(max(k - int(np.floor(scan.phase(k) / scan.dt)), 1), k + 1)
        rec.points(
            "scan/samples",
            to_view(scan.phase(ks), y[ks]),
            radii=0.8,
            colors=[255, 255, 255],
            image_space=False,
            labels=False,
        )
        for name, centre, colour in (("true_pulse", x[k], [0, 200, 0]), ("predicted_pulse", x_pred[k], [255, 140, 0])):
            shape = np.exp(-0.5 * ((phase_axis - scan.pulse_centre - centre) / scan.pulse_sigma) ** 2)
            rec.lines(f"scan/{name}", to_view(phase_axis, shape), colors=colour, image_space=False)
        rec.boxes(
            "scan/gate",
            to_view([0.5], [0.5]),
            [[50.0, 80.0]],
            colors=[120, 120, 255],
            labels=["micro-raster"],
            image_space=False,
        )
        rec.lines("scan/truth", to_view([0.5 + x[k]] * 2, [-0.2, 1.25]), colors=[0, 200, 0], image_space=False)
        rec.boxes(
            "scan/estimate",
            to_view([0.5 + est[k]], [0.5]),
            [[100 * np.sqrt(var[k]), 75.0]],
            colors=[255, 60, 60],
            labels=["estimate ±σ"],
            image_space=False,
        )
    kr = np.arange(n_rec + 1)
    series = {
        "track/truth": (x[kr], "truth X1", [0, 200, 0]),
        "track/estimate": (est[kr], "variant 2", [255, 60, 60]),
        "track/plus_sigma": (est[kr] + np.sqrt(var[kr]), "+σ", [255, 160, 160]),
        "track/minus_sigma": (est[kr] - np.sqrt(var[kr]), "-σ", [255, 160, 160]),
        "noise/intensity": (scan.noise_intensity(x[kr], kr) / scan.n0, "N / N0", [200, 200, 80]),
        "errors/x": (x[kr] - est[kr], "X1 - estimate", [255, 60, 60]),
    }
    for path, (values, name, colour) in series.items():
        rec.series(path, values)
        rec.series_style(path, name=name, color=colour)
    return rec.close() and "recording.rrd"


#: The viewer check's deviations from its default expectation (``tvtrack.contract.VIEWER_KEYS``): an image
#: dissector delivers a 1-D scan, so the 2-D view plots samples and pulses against phase, with no image.
VIEWER_EXPECTATIONS = {"image": False}
