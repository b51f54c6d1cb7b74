"""The deterministic curves of C001-7 and C001-8 (Fisenko et al. 2008, Fig. 4 and the text before Fig. 1) as
measured values, tagged with the register's ``curve_tolerance`` (the claims' Monotone rules count a smaller step as
flat), and Fig. 4's optimum reported with what it rests on (where the signed dynamic error crosses zero).
"""

from __future__ import annotations


import numpy as np
from scipy import stats

from ...filters.polynomial import predict_ahead
from ...projection import as_declared
from ...verdicts import ByReading
from .track_modes import TrackModeConfig, run_track_modes
from .sizes import declared
from .scenario import (
    FPS_REF,
    Scenario,
    config_scenario,
    measurements,
    with_defaults,
)

__all__ = [
    "kb3_grid",
    "optimum_location",
    "forced_output",
    "prediction_error",
    "occlusion_frames",
    "fig4_curves",
    "loss_sweep",
    "c7_parts",
    "c8_parts",
    "measure_curves",
    "fig4_monte_carlo",
    "curve_agreement",
    "agreement_word",
    "chi2_words",
    "smallest_rms_words",
    "C8_UNITS",
    "unbiased_prediction_bound",
]


def optimum_location(cur: dict) -> dict:
    """Where curve 3 (|dynamic| + RMS) is smallest and what puts it there.

    Returns
    -------
    dict
        ``kb3`` (the grid point of the minimum), ``sum``, ``dyn``, ``rms`` there; ``crossings``: the k_b3 values
        (linear interpolation between grid points) where the signed dynamic error changes sign; ``nearest_crossing``
        (None without a crossing); ``at_crossing``: whether the minimum is the grid point next to a crossing on
        either side (the optimum then sits where the dynamic error passes through zero, not where a trade-off
        of two monotone errors balances); ``rms_share``: RMS / sum at the minimum.
    """
    kb = np.asarray(cur["kb3"], float)
    dyn, rms, s = (np.asarray(cur[k], float) for k in ("dyn", "rms", "sum"))
    i = int(np.argmin(s))
    a, b = dyn[:-1], dyn[1:]
    j = np.nonzero(a * b < 0)[0]  # strict sign changes (exact zeros of a rounded curve are not crossings)
    cross = [float(kb[k] + (kb[k + 1] - kb[k]) * a[k] / (a[k] - b[k])) for k in j]
    near = min(cross, key=lambda c: abs(c - kb[i])) if cross else None
    adjacent = near is not None and (
        (i > 0 and kb[i - 1] <= near <= kb[i]) or (i < len(kb) - 1 and kb[i] <= near <= kb[i + 1])
    )
    return {
        "kb3": int(kb[i]),
        "sum": float(s[i]),
        "dyn": float(dyn[i]),
        "rms": float(rms[i]),
        "crossings": cross,
        "nearest_crossing": near,
        "at_crossing": bool(adjacent),
        "rms_share": float(rms[i] / s[i]),
    }


def forced_output(sc: Scenario, config: dict, sizes: dict, kb3: int, visible, z=None, covariance=True):
    """The scheme with the switch forced at ``switch_s`` (the filter is then linear; this project's Fig. 4
    computation), on the noise-free truth of channel x (``z=None``) or on measurements ``z``."""
    k_switch = int(round(float(config["switch_s"]) * sc.fps)) + 1
    cfg = TrackModeConfig(
        k_bound2=int(config["k_bound2"]),
        k_bound3=int(kb3),
        window=int(config["window_n"]),
        restart=config["restart"],
        restart_accel_var=float(config["restart_accel_var"]),
        force_switch_k=k_switch,
    )
    zz = sc.truth[0, :, 0] if z is None else z
    return run_track_modes(zz, visible, cfg, sizes["sigma_eps"], covariance=covariance or cfg.restart == "C")


def prediction_error(sc: Scenario, config: dict, sizes: dict, kb3: int, f_loss: int, f_back: int):
    """Noise-free dynamic error and RMS (elements) of the prediction at ``f_back`` after a loss ``[f_loss, f_back)``
    (this project's Fig. 4 computation). The RMS is the covariance recursion's for white errors (also the RMS of the
    quantised and Student-t models, white with the same variance); for ``config["noise"]`` = AR(1) it is exact for
    the correlated errors: the forced filter is linear, so the prediction error is ``w @ e`` with ``w`` its response
    to unit impulses and variance ``sigma² w R w``, ``R_ij = 0.5^|i-j|``."""
    vis = (sc.frames < f_loss) | (sc.frames >= f_back)
    o = forced_output(sc, config, sizes, kb3, vis)
    dyn = float(predict_ahead(o.x[f_back - 1], 1) - sc.truth[0, f_back, 0])
    rms = float(np.sqrt(o.gate_var[f_back] - sizes["sigma_eps"] ** 2))
    if config.get("noise", "white Gaussian") == "AR(1), rho = 0.5":
        imp = np.eye(f_loss, sc.T)
        w = predict_ahead(forced_output(sc, config, sizes, kb3, vis, z=imp, covariance=False).x[:, f_back - 1], 1)
        lag = np.abs(np.subtract.outer(np.arange(f_loss), np.arange(f_loss)))
        rms = float(sizes["sigma_eps"] * np.sqrt(w @ (0.5**lag) @ w))
    return round(dyn, 6), round(rms, 6)  # float noise off the deterministic curves


def occlusion_frames(reading: str, sc: Scenario, length_s: float = 10.0) -> tuple[int, int]:
    """Fig. 4's "disappearance at the 10th second": the scenario's loss (from 12 s) or a loss from 10 s, lasting
    ``length_s`` seconds (the register's ``loss_length_s``; the paper's 10 s gives 12-22 s and 10-20 s)."""
    starts = {"scenario 12-22 s": sc.f_loss / sc.fps, "from 10 s": 10.0}
    if reading not in starts:
        raise ValueError(f"occlusion reading {reading!r}")
    start = starts[reading]
    return int(round(start * sc.fps)), int(round((start + float(length_s)) * sc.fps))


def fig4_curves(config: dict, sizes: dict) -> dict:
    """Fig. 4: dynamic error, RMS and their sum at reappearance over :func:`kb3_grid` (deterministic)."""
    config = with_defaults(config, sizes)
    sc = config_scenario(config)
    fl, fb = occlusion_frames(config["occlusion"], sc, config.get("loss_length_s", 10.0))
    grid = kb3_grid(config, sizes)
    dyn, rms = np.array([prediction_error(sc, config, sizes, kb, fl, fb) for kb in grid]).T
    return {"kb3": np.asarray(grid), "dyn": dyn, "rms": rms, "sum": np.abs(dyn) + rms}


def kb3_grid(config: dict, sizes: dict) -> list[int]:
    """Fig. 4's grid of the 3rd-order gain bound (frames) at the configuration's frame rate: ``sizes["kb3_grid"]``
    at the reference 25 frames/s, stretched with the frame rate so that it spans the same seconds of the scenario
    (at 50 frames/s the switch-to-loss gap is 325 frames, beyond the reference grid's 200: a minimum there would sit
    on the grid's edge for want of points, not for want of an optimum)."""
    f = float(config["frame_rate_hz"]) / FPS_REF
    return [int(round(k * f)) for k in sizes["kb3_grid"]]


def loss_sweep(config: dict, sizes: dict) -> dict:
    """C001-7: a loss of ``loss_length_s`` (default the paper's 10 s) starting at each of ``sizes["loss_grid_s"]``
    (deterministic)."""
    config = with_defaults(config, sizes)
    sc = config_scenario(config)
    length = float(config.get("loss_length_s", 10.0))
    rows = [
        prediction_error(
            sc, config, sizes, int(config["k_bound3"]), int(round(s * sc.fps)), int(round((s + length) * sc.fps))
        )
        for s in sizes["loss_grid_s"]
    ]
    dyn, rms = np.array(rows).T
    return {"loss_s": np.asarray(sizes["loss_grid_s"]), "dyn": dyn, "rms": rms}


def c7_parts(sweep: dict) -> dict:
    """C001-7's parts: |dynamic| along the loss times in multiples of the smallest random prediction error (RMS) of
    the sweep; |dynamic| / RMS for the earliest loss.

    The paper says dynamic errors "substantially affect the prediction" ("существенно влияют на прогноз") when the
    object is lost before they are worked off, and plots them beside the random error (Fig. 4, curves 1 and 2; the
    figure itself is not in the text). A change of the dynamic error smaller than the random error of the
    prediction is no substantial change of its effect, so the trend is read in units of the smallest random error
    along the sweep (7.6 el at the default, the gains at their bound) and C001-7's rule counts a step within one
    unit as flat: the tolerance the paper's curve allows.
    """
    dyn, rms = np.abs(np.asarray(sweep["dyn"], float)), np.asarray(sweep["rms"], float)
    return {
        "decreasing": [float(v) for v in dyn / rms.min()],
        "dominates early": float(dyn[0] / rms[0]),
    }


def c8_parts(cur: dict) -> dict:
    """C001-8's parts: the RMS (elements) along k_b3; an interior minimum of curve 3 (ends minus the inside
    minimum); |dynamic| from the optimum on."""
    s = cur["sum"]
    ib = int(np.argmin(s))
    tail = [float(v) for v in np.abs(cur["dyn"])[ib:]]
    return {
        "RMS decreasing": [float(v) for v in cur["rms"]],
        "interior minimum": float(min(s[0], s[-1]) - s[1:-1].min()),
        "dynamic grows beyond the optimum": tail if len(tail) >= 2 else [tail[0], tail[0]],
    }


def measure_curves(config: dict, seed: int, sizes: dict, claims=None) -> dict:
    """C001-7 and C001-8 from the noise-free runs and the covariance recursion (``seed`` unused: no draw), C001-8
    tagged with the register's ``curve_tolerance`` (:class:`~tvtrack.verdicts.ByReading`: the claims' Monotone
    rules count a step below it as flat, :mod:`.claims`); only the claims in ``claims`` (None: both)."""
    config = with_defaults(config, sizes)
    out = {}
    if claims is None or "C001-7" in claims:
        out["C001-7"] = c7_parts(loss_sweep(config, sizes))
    if claims is None or "C001-8" in claims:
        out["C001-8"] = ByReading.tag(float(config["curve_tolerance"]), c8_parts(fig4_curves(config, sizes)))
    return out


# each claim at its configuration projected onto its DEPENDS; as_declared applied here, not as a decorator:
# mutmut 3 mutates no decorated function (docs/mutation.md)
measure_curves = as_declared(("C001-7", "C001-8"), declared)(measure_curves)


def fig4_monte_carlo(config: dict, sizes: dict, rng: np.random.Generator) -> dict:
    """Independent Monte Carlo check of Fig. 4: fresh runs per k_b3 of :func:`kb3_grid` (the curves' own grid at
    the configuration's frame rate); mean, SD and SE of the prediction error."""
    config = with_defaults(config, sizes)
    sc = config_scenario(config)
    fl, fb = occlusion_frames(config["occlusion"], sc, config.get("loss_length_s", 10.0))
    vis = (sc.frames < fl) | (sc.frames >= fb)
    out = {"mean": [], "sd": [], "se": []}
    for kb in kb3_grid(config, sizes):
        z = measurements(sc.truth[0, :, 0], "white Gaussian", sizes["n_fig4_trials"], rng, sizes["sigma_eps"])
        o = forced_output(sc, config, sizes, kb, vis, z=z, covariance=False)
        e = predict_ahead(o.x[:, fb - 1], 1) - sc.truth[0, fb, 0]
        out["mean"].append(e.mean())
        out["sd"].append(e.std(ddof=1))
        out["se"].append(e.std(ddof=1) / np.sqrt(e.size))
    return {k: np.array(v) for k, v in out.items()}


def curve_agreement(curves: dict, mc: dict, n: int) -> dict:
    """Chi-square tests of the Monte Carlo against the noise-free dynamic error (means) and the covariance RMS
    (variances): ``{"p_mean", "p_var"}``, two-sided for the variance."""
    p_mean = float(stats.chi2.sf(np.sum(((mc["mean"] - curves["dyn"]) / mc["se"]) ** 2), len(curves["dyn"])))
    chi2 = float(np.sum((n - 1) * mc["sd"] ** 2 / curves["rms"] ** 2))
    dof = len(curves["rms"]) * (n - 1)
    return {"p_mean": p_mean, "p_var": float(2 * min(stats.chi2.sf(chi2, dof), stats.chi2.cdf(chi2, dof)))}


def agreement_word(p: float, level: float = 0.05) -> str:
    """The words a test at ``level`` allows: "differ from" when it rejects (p < level); otherwise only "are not
    shown to differ from", since a test that does not reject is no evidence of agreement."""
    return "are not shown to differ from" if p >= level else "differ from"


def chi2_words(p: float, level: float = 0.05) -> str:
    """What a chi-square test at ``level`` shows, from its p-value: ``"χ² p = 0.06 ≥ 0.05: not rejected at the 5 %
    level, which is not evidence of agreement"`` or ``"χ² p = 0.01 < 0.05: rejected at the 5 % level"``."""
    head = f"χ² p = {p:.2g}"
    if p < level:
        return f"{head} < {level:g}: rejected at the {100 * level:g} % level"
    return f"{head} ≥ {level:g}: not rejected at the {100 * level:g} % level, which is not evidence of agreement"


def unbiased_prediction_bound(sc: Scenario, f_first: int, f_last: int, f_pred: int, sigma_eps: float = 1.0) -> float:
    """SD bound for any *unbiased* predictor of the position at ``f_pred`` from the measurements ``f_first`` ..
    ``f_last`` of a quadratic in white noise (the least-squares fit is the MVU estimator), elements."""
    lags = np.arange(f_last - f_first, -1, -1, dtype=float)
    H = np.stack([np.ones_like(lags), -lags, 0.5 * lags**2], axis=-1)
    m = f_pred - f_last
    u = np.array([1.0, m, 0.5 * m**2])
    return float(sigma_eps * np.sqrt(u @ np.linalg.solve(H.T @ H, u)))


def smallest_rms_words(sweep: dict) -> str:
    """C001-7's caveat: the unit its values are counted in, the smallest random prediction error (RMS) of the loss
    sweep (:func:`loss_sweep`), in elements."""
    return (
        f"Its unit, the smallest random prediction error (RMS) of the sweep, is "
        f"{float(np.min(sweep['rms'])):.3g} elements"
    )


#: C001-8's caveat: the unit of its parts (:func:`c8_parts`), which the conclusions' part decisions do not print.
C8_UNITS = (
    "Its parts are in raster elements: the RMS prediction error at reappearance, the interior minimum of "
    "|dynamic error| + RMS (the smallest at the grid's ends less the smallest inside it) and the |dynamic error| "
    "from the optimum on"
)
