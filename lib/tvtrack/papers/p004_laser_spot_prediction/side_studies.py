"""The studies of notebook 004 beyond the claims' values (Kokryatska and Hrynchyshyn 2005), on the shipped run:
the methods' scores and the tuned settings on a grid edge, the measurement budget against the Cramer-Rao bound,
which model order wins, the horizon study, and a claim's value along one register entry of an exploration.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...render import gaussian_spot, sensor_readout
from .camera import SpotCamera
from .beam_wander import optimal_wander_forecast
from .prediction_study import (
    CA_KALMAN,
    FADING,
    PAPER,
    PARTS,
    SINGER,
    Comparison,
    ComparisonSetup,
    compare_methods,
    per_trial_path_mse,
)
from .world import BASE_CAMERA
from .prediction_study import comparison_setup
from .study import LSQ_CUBIC, NATURAL_SPLINE, NETWORKS, OPTIMAL, StudyRun
from .intervals import ratio_of_means_ci, root_mean_ci

__all__ = [
    "scores",
    "grid_edge_report",
    "own_minimum_report",
    "single_values",
    "spot_position_crb",
    "measurement_budget",
    "model_order_summary",
    "horizon_study",
]


def scores(run: StudyRun) -> tuple[dict, dict]:
    """Per method: RMS error against the measured centre (px, :func:`root_mean_ci`), and the paired
    ratio of its per-path MSE to the paper filter's (:func:`ratio_of_means_ci`)."""
    m = int(run.config["horizon"])
    mse = {n: per_trial_path_mse(f, run.z_meas, m, run.size.eval_start)[0] for n, f in run.forecasts.items()}
    rms = {n: root_mean_ci(v) for n, v in mse.items()}
    return rms, {n: ratio_of_means_ci(v, mse[PAPER]) for n, v in mse.items() if n != PAPER}


def grid_edge_report(run: StudyRun) -> dict:
    """Share of the tuned settings that sit on an edge of their grid, per method and setting (a fit on
    an edge may be the grid's limit rather than the method's optimum)."""
    return _edge_shares(run.comparison.chosen, comparison_setup(run.config, run.size))


def _edge_shares(ch: dict, s: ComparisonSetup) -> dict:
    """:func:`grid_edge_report` of the tuned settings ``ch`` (``compare_methods``' ``chosen``) on the grids of
    ``s``; the networks' lags only where they were tuned."""
    from .prediction_study import FLOOR_EXTENSION, MIN_WINDOW, WINDOW_EXTENSION, grid_edges, window_candidates

    floors = (*s.floor_grid, *FLOOR_EXTENSION)  # the grids as the tuning extends them while a fold picks the top
    out = {
        PAPER: float(np.mean(grid_edges(ch[PAPER], floors) == 1)),  # N_f = 3 (order + 1) is a true limit
        FADING: float(np.mean(grid_edges(ch[FADING], s.theta_grid) != 0)),
    }
    for name, lo in MIN_WINDOW.items():
        out[name] = float(
            np.mean(grid_edges(ch[name], (*window_candidates(lo, s.window_grid), *WINDOW_EXTENSION)) == 1)
        )  # degree+1 is a true limit
    for name in (LSQ_CUBIC, NATURAL_SPLINE):  # the spline's other readings, tuned in _methods (not at every horizon)
        if name in ch:
            out[name] = float(
                np.mean(grid_edges(ch[name], (*window_candidates(4, s.window_grid), *WINDOW_EXTENSION)) == 1)
            )
    ca = np.asarray(ch["CA Kalman, ML noise"])
    out["CA Kalman jerk density"] = float(np.mean(grid_edges(ca[:, 0], s.jerk_grid) != 0))
    out["CA Kalman measurement variance"] = float(np.mean(grid_edges(ca[:, 1], s.meas_var_grid) != 0))
    for name in NETWORKS:
        if name in ch:  # lag counts chosen by cross-validation (1 lag, the lowest, is a true limit)
            out[f"{name} lags"] = float(np.mean(grid_edges(ch[name], s.lag_grid) == 1))
    sg = np.asarray(ch[SINGER])
    out["Singer tau"] = float(np.mean(grid_edges(sg[:, 0], s.singer_tau_grid) == 1))  # 0.01 frames: white acceleration
    return out


def own_minimum_report(run: StudyRun) -> dict:
    """The tuned settings that sit at the smallest value their search allows, the method's own limit (a floor of the
    grid's smallest number of samples, a window of degree + 1 samples), which :func:`grid_edge_report` rightly does
    not count as a grid edge: ``{method: (setting name, value, share of paths or folds)}`` for each method with a
    share above 0."""
    from .prediction_study import MIN_WINDOW, VARIANT

    ch, s = run.comparison.chosen, comparison_setup(run.config, run.size)
    lows = {PAPER: ("floor N_f", min(s.floor_grid)), VARIANT: ("floor N_f", min(s.floor_grid))}
    lows |= {name: ("window L", lo) for name, lo in MIN_WINDOW.items()}
    lows |= {
        name: ("window L", 4) for name in (LSQ_CUBIC, NATURAL_SPLINE)
    }  # the spline's other readings start at 4 too
    out = {}
    for name, (what, lo) in lows.items():
        if name in ch:
            share = float(np.mean(np.isclose(np.asarray(ch[name], float), lo)))
            if share > 0:
                out[name] = (what, int(lo), share)
    return out


def single_values(exploration, claim_id: str, entry: str) -> dict:
    """The claim's measured value at each value of ``entry`` (one at a time; the default pooled)."""
    from .register import DEFAULT

    out = {exploration.default.get(entry, DEFAULT[entry]): exploration.measured(claim_id)}
    for r in exploration.runs:
        if r.stage == "single" and list(r.changed(exploration.default)) == [entry] and claim_id in r.outputs:
            out[r.config[entry]] = r.outputs[claim_id]
    return dict(sorted(out.items()))


def spot_position_crb(camera: SpotCamera, read_noise_dn: float) -> float:
    """Per-axis Cramer-Rao bound of the spot position in one gate at intensity 1 (Poisson counts, read
    noise and quantisation as Poisson-equivalent variance per pixel), px."""
    from ...bounds.poisson_crb import fisher_linear_motion

    g = camera.gate_size_px
    theta = np.array([[(g - 1) / 2, (g - 1) / 2, 0.0, 0.0]])
    noise = camera.background_dn + read_noise_dn**2 + 1 / 12
    fim = fisher_linear_motion(theta, np.array([0.0]), (g, g), camera.spot_sigma_px, camera.flux_e, noise)[:2, :2]
    return float(np.sqrt(np.linalg.inv(fim)[0, 0]))  # one frame: only the position block is informative


def measurement_budget(
    read_noise_levels, n_gates: int, rng: np.random.Generator, camera: SpotCamera = BASE_CAMERA
) -> dict:
    """Error of the windowed centroid and of a Gaussian-fit MLE on static spots (random sub-pixel
    positions, intensity 1) against the Cramer-Rao bound, per read-noise level.

    Returns
    -------
    dict
        {read noise (DN): {"centroid", "mle", "crb"} per-axis RMS / bound, px}
    """
    from .spot_centre import gaussian_fit_centre, windowed_centroid

    g = camera.gate_size_px
    out = {}
    for rn in read_noise_levels:
        c_true = (g - 1) / 2 + rng.uniform(-2, 2, (n_gates, 2))
        img = sensor_readout(
            gaussian_spot(c_true, (g, g), camera.spot_sigma_px, camera.flux_e),
            rng,
            background=camera.background_dn,
            read_noise=rn,
            bit_depth=camera.bit_depth,
        )
        wc = windowed_centroid(img, (0, 0), window_px=camera.window_px, threshold_sigma=camera.threshold_sigma).xy
        ok = np.all(np.isfinite(wc), axis=-1)
        ml = gaussian_fit_centre(img[ok], np.zeros((ok.sum(), 2)), wc[ok], sigma_px=camera.spot_sigma_px, read_noise=rn)
        out[float(rn)] = {
            "centroid": float(np.sqrt(np.mean((wc[ok] - c_true[ok]) ** 2))),
            "mle": float(np.sqrt(np.mean((ml - c_true[ok]) ** 2))),
            "crb": spot_position_crb(camera, rn),
            "lost": float(np.mean(~ok)),
        }
    return out


def model_order_summary(run: StudyRun) -> dict:
    """Which model order predicts best, and the fitted Singer time constant that says why.

    Returns
    -------
    dict
        ``rms`` per method (px), ``best`` (name), ``best_order1`` / ``best_order2`` (names of the best
        first-order predictor: 2-point differences or degree-1 regression; and second-order: the paper's
        filter, 3-point differences, degree-2 regression, Morrison), ``ratio_2_over_1`` (paired MSE ratio,
        best second order over best first order; below 1: the acceleration term pays),
        ``singer_tau_frames`` (per fold), ``tau_over_horizon`` and ``frame_ms`` (the frame interval, ms).
    """
    c = run.config
    m = int(c["horizon"])
    mse = {n: per_trial_path_mse(f, run.z_meas, m, run.size.eval_start)[0] for n, f in run.forecasts.items()}
    rms = {n: float(np.sqrt(v.mean())) for n, v in mse.items()}
    order1 = ("finite differences, 2 points", "linear regression deg 1")
    order2 = (PAPER, "finite differences, 3 points", "linear regression deg 2", FADING)
    b1 = min(order1, key=rms.get)
    b2 = min(order2, key=rms.get)
    tau = np.asarray(run.comparison.chosen[SINGER])[:, 0]
    return {
        "rms": rms,
        "best": min((n for n in rms if n != OPTIMAL), key=rms.get),
        "best_order1": b1,
        "best_order2": b2,
        "ratio_2_over_1": ratio_of_means_ci(mse[b2], mse[b1]),
        "singer_tau_frames": tau,
        "tau_grid_min": float(min(comparison_setup(c, run.size).singer_tau_grid)),
        "tau_over_horizon": float(np.median(tau) / m),
        "frame_ms": 1e3 / float(run.scene.frame_rate_hz),
    }


def horizon_study(run: StudyRun, horizons, seed: int) -> dict:
    """RMS error versus horizon, every method re-tuned at each horizon (the floor and windows chosen
    by cross-validation for that horizon; the Kalman filters' ML fits, which read no horizon, made once and
    forecast at each; networks left out for cost),
    and the optimal predictor.

    Returns
    -------
    dict
        ``rms``: {method: {horizon: Estimate (px)}}; ``floor``: {horizon: median cross-validated N_f};
        ``floor_grid``: the floor's grid; ``edges``: {horizon: :func:`grid_edge_report` of that horizon's
        tuning}; ``slopes``: {method: log-log slope of RMS over the horizons}.
    """
    rms, floors, edges = {}, {}, {}
    fits = None  # the Kalman filters' ML fits read no horizon: fitted once, forecast at every horizon
    for h in horizons:
        s = replace(comparison_setup({**run.config, "horizon": h}, run.size), learned_kw={})
        cmp = _run_comparison_at(run, h)
        if cmp is None:
            rng = np.random.default_rng(0)
            cmp = compare_methods(run.z, run.z_meas, run.folds, s, rng, learned=False, kalman_fits=fits)
        fits = (cmp.chosen[CA_KALMAN], cmp.chosen[SINGER])
        fcs = dict(cmp.forecasts)
        fcs[OPTIMAL] = optimal_wander_forecast(
            run.z, run.scene, run.path_rms, run.centroid_rms**2 + run.jitter_rms**2, h
        )
        for name, f in fcs.items():
            rms.setdefault(name, {})[h] = root_mean_ci(per_trial_path_mse(f, run.z_meas, h, run.size.eval_start)[0])
        floors[h] = float(np.median(cmp.chosen[PAPER]))
        edges[h] = _edge_shares(cmp.chosen, s)
    hs = np.log(np.asarray(horizons, dtype=float))
    slopes = (
        {n: float(np.polyfit(hs, np.log([d[h].value for h in horizons]), 1)[0]) for n, d in rms.items()}
        if len(horizons) > 1
        else {}
    )
    return {"rms": rms, "floor": floors, "floor_grid": tuple(run.size.floor_grid), "edges": edges, "slopes": slopes}


def _run_comparison_at(run: StudyRun, horizon: int) -> Comparison | None:
    """``run``'s own comparison as :func:`horizon_study` would compute it at ``horizon`` (the networks and the
    spline's other readings left out), if ``run`` ran every non-learned method at that horizon; else None. The
    non-learned methods draw nothing, so the numbers are those of a fresh comparison."""
    if run.comparison is None or int(run.config["horizon"]) != int(horizon) or not PARTS - {"learned"} <= run.parts:
        return None
    skip = {*NETWORKS, LSQ_CUBIC, NATURAL_SPLINE}
    c = run.comparison
    keep = lambda d: {n: v for n, v in d.items() if n not in skip}  # noqa: E731
    return Comparison(keep(c.mse), keep(c.mse_fixed), keep(c.chosen), keep(c.forecasts), {})
