"""The Rerun recording of notebook 002: one trial fitted by the ULA (plain EM, with its history) and by the
two-stage iterative marks.

Layout: the count image of each frame (log scale) with the truth, the designation, the ULA estimate (points and
fitted trajectories) and the marks; the posterior share lambda of object 1 at the first and the last EM step; the
per-frame position errors (frame time line); the per-iteration log-likelihood and parameters (``iteration`` time
line).
"""

from __future__ import annotations

import numpy as np

from tvtrack.plotting import colour, rgb
from tvtrack.recordings import Recorder, image_and_series_blueprint
from .em import match_labels, responsibility_maps, unified_location_em
from .em_steps import pixel_entries
from .model import designate, draw_truth, frame_times, mixture_weights, noise_per_pixel, scene_geometry, simulate_counts
from .two_stage import em_marks, fit_lines, propagate

__all__ = ["blueprint", "count_image", "record_trial"]


def blueprint():
    """The viewer's layout: the count image with truth, designation and estimates; the errors and the EM's trace;
    the responsibilities of the first and the converged EM step."""
    return image_and_series_blueprint(
        "camera",
        ("errors", ("em/loglik", "em/theta")),
        image_name="Counts (log), truth, designation, estimates",
        series_names=(
            "position error per frame (px)",
            ("EM log-likelihood (time line 'iteration')", "EM parameters, px (time line 'iteration')"),
        ),
        image_share=0.6,
        more_images=(
            ("responsibility/first_iteration", "lambda_1, first EM step"),
            ("responsibility/last_iteration", "lambda_1, converged"),
        ),
    )


def count_image(frame) -> np.ndarray:
    """A count frame as uint8, ``log(1 + n)`` scaled to the frame's maximum, so that a few photons show."""
    return (255 * np.log1p(frame) / max(np.log1p(frame.max()), 1e-12)).astype(np.uint8)


def record_trial(
    output_dir,
    mode: str,
    rng: np.random.Generator,
    *,
    separation: float,
    pixel: float,
    photons: int,
    frames: int,
    velocity=(0.2, 0.1),
    noise_density: float = 0.01,
    designation_sd: float = 0.3,
    every: int = 1,
    max_iter: int = 5000,
) -> dict:
    """Simulate one two-object trial, fit it, and write the recording. Returns a summary: ``path`` of the
    recording (None when off), ``n_iter`` of the ULA, and the per-frame errors (px) ``err_ula`` and ``err_marks``
    (T, 2), each object's labels matched to the truth first."""
    g = scene_geometry(2, frames, separation, pixel, velocity, 6.0)
    times, s = frame_times(frames), g.sigma_px
    noise = noise_per_pixel(noise_density, s)
    p, p0 = mixture_weights(photons, noise, g.n_pixels, 2)
    truth = draw_truth(rng, 1, g)
    desig = designate(rng, truth, designation_sd * s)
    counts = simulate_counts(rng, truth, times, g.shape, s, photons, noise)
    res = unified_location_em(pixel_entries(counts), desig, s, p, p0, tol_px=1e-6 * s, max_iter=max_iter, history=True)
    marks = em_marks(counts, desig, times, s, p, p0, tol_px=1e-6 * s, max_iter=max_iter)
    lam = [responsibility_maps(th, times, g.shape, s, p, p0)[0] for th in (desig[0], res.theta[0])]
    truth_xy, est_xy, des_xy = (propagate(th, times)[0] for th in (truth, res.theta, desig))
    perm_u = match_labels(res.theta, truth, times)[0][0]
    perm_m = match_labels(fit_lines(marks, times, desig).theta, truth, times)[0][0]
    err_u = np.linalg.norm(est_xy[:, perm_u] - truth_xy, axis=-1)
    err_m = np.linalg.norm(marks.xy[0][:, perm_m] - truth_xy, axis=-1)
    rec = Recorder(output_dir, mode, "tvtrack-002_unified_location_em", blueprint=blueprint)
    c_t, c_e, c_d, c_m = (rgb(colour(r)) for r in ("truth", "estimate", "prediction", "measurement"))
    rec.lines("camera/ula_trajectory", [est_xy[:, j] for j in range(2)], colors=[c_e], radii=0.03)
    rec.lines("camera/true_trajectory", [truth_xy[:, j] for j in range(2)], colors=[c_t], radii=0.02)
    for ell in range(0, frames, every):
        rec.set_frame(ell)
        rec.image("camera/image", count_image(counts[0, ell]))
        rec.points("camera/truth", truth_xy[ell], colors=c_t, radii=0.12)
        rec.points("camera/designation", des_xy[ell], colors=c_d, radii=0.12)
        rec.points("camera/estimate", est_xy[ell], colors=c_e, radii=0.12)
        rec.points("camera/marks", marks.xy[0, ell], colors=c_m, radii=0.1)
        rec.image("responsibility/first_iteration/lambda_1", lam[0][ell].astype(np.float32))
        rec.image("responsibility/last_iteration/lambda_1", lam[1][ell].astype(np.float32))
    for j in range(2):
        rec.series(f"errors/ula/object_{j + 1}", err_u[:, j])
        rec.series(f"errors/marks/object_{j + 1}", err_m[:, j])
    rec.series("em/loglik/value", np.array([h[0] for h in res.history_loglik]), timeline="iteration")
    hist = np.array([h[0] for h in res.history_theta])
    for j in range(2):
        for k, name in enumerate(("x0", "y0", "vx", "vy")):
            rec.series(f"em/theta/{name}_{j + 1}", hist[:, j, k], timeline="iteration")
    path = rec.close()
    return {"path": path, "n_iter": int(res.n_iter[0]), "err_ula": err_u, "err_marks": err_m}


#: The viewer check's deviations from its default expectation (``tvtrack.contract.VIEWER_KEYS``): batch EM
#: location draws no gate (per-frame errors under errors/); the EM history is on the "iteration" timeline, shown
#: when the user picks it (the recording opens on "frame", where the image and the errors are).
VIEWER_EXPECTATIONS = {"overlays": ("truth", "estimate"), "other_timelines": ("iteration",)}
