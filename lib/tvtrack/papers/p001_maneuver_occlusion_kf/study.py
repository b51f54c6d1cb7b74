"""Study drivers of paper 001 (Fisenko et al. 2008): the scenario, the measurement functions the explorer calls,
the tuned comparators and the deterministic curves of Fig. 4 and the loss-time sweep.

A measurement function is ``measure(config, seed, sizes) -> {claim id: measured}``: one full-size run of the
study at ``config`` (a dict with every register entry of :mod:`.register`), every random draw from
``np.random.default_rng(seed)``, the same noise streams whatever the configuration (common random numbers).
``sizes`` holds the notebook's sample sizes and, under ``"defaults"``, the register's default configuration, which
completes a configuration that names only the entries of one exploration (bind ``sizes`` with
``functools.partial``, which stays picklable).

Units: positions in raster elements, velocities in elements/frame, accelerations in elements/frame²; the motion is
fixed in elements/s (the paper's values at 25 Hz), so another frame rate rescales the per-frame values.
"""

from __future__ import annotations

import functools
import itertools
from dataclasses import dataclass

import numpy as np
from scipy import signal, stats

from ...filters.alphabeta import gain_schedule, scheduled_filter
from ...filters.imm import cv_ca_models, imm_run
from ...filters.polynomial import predict_ahead
from ...filters.vdf import vd_filter_run
from ...montecarlo import Estimate, mean_ci, paired_difference
from .curves import optimum_location, resolved  # noqa: F401 (optimum_location: the notebook reads it here)
from .false_alarm import closed_form_check, closed_form_rate, statistic_impulse_response
from .maneuver_detector import (
    detection_time_summary,
    false_alarm_rates,
    first_alarm_within,
    null_quantile_threshold,
    scheduled_statistic_std,
    statistic_std,
    threshold_from_std,
    track2_thresholds,
    window_statistic,
    window_sum_of_squares,
)
from .track_modes import TrackModeConfig, manoeuvre_truth, run_track_modes

#: The paper's motion is stated per frame; it is read at this frame rate (Hz) and kept fixed in elements/s.
FPS_REF = 25.0
#: (initial velocity el/frame, acceleration el/frame²) at 25 Hz of the channels x (the paper's) and y (not stated).
MOTION = ((10.0, 0.2), (-6.0, -0.2))
NOISE_MODELS = ("white Gaussian", "quantised", "AR(1), rho = 0.5", "Student t, 3 dof")
THRESHOLD_READINGS = ("exact", "stationary", "independent", "raw increments")
ARMING_RULES = ("gains at bound", "windows full")
RMS_SPANS = ("4 s to loss", "onset to loss", "visible after 4 s", "end of the loss")
#: The spans the comparators are tuned for: the register's, and the last frame before the loss (the card's
#: "|bias| + RMS at 12 s" reading of C001-4).
TUNING_SPANS = RMS_SPANS + ("last frame before the loss",)
#: How long the acceleration lasts (s; None: to the end of the run). The paper gives the onset and the value only.
MANOEUVRES = {"constant acceleration": None, "2 s acceleration": 2.0}
#: The second channel's (initial velocity el/frame, acceleration el/frame²) at 25 Hz: not stated (one channel was
#: simulated); the paper's magnitude, or a turn mostly in x that gives y a quarter of it.
CHANNEL_Y = {"v -6, a -0.2": (-6.0, -0.2), "v -6, a -0.05": (-6.0, -0.05)}
#: The unit of the paper's "acceleration 0.2 raster elements per frame": el/frame² (the card), or a velocity change of
#: 0.2 el/frame per second (the paper's times are in seconds): the factor on the accelerations of ``MOTION``.
ACCEL_UNITS = {"el/frame²": 1.0, "el/frame per s": 1.0 / FPS_REF}
#: C001-4's "faster compensation" comparator: the scheme's TRACK2 filter never switching (the default), or the same
#: filter whose 2nd-order gains are raised at the scheme's own detection (restart at k = 3, decaying to a bound tuned
#: on the training runs over ``RAISED2_GRID``; 3 is the physical floor, restart A's k): the order switch isolated.
COMPENSATION_COMPARATORS = ("2nd order without the switch", "2nd order, gains raised at the detection")
RAISED2_GRID = (3, 5, 10, 20, 50)
#: C001-2's "UMP" comparator, another invariant rule on the same 2n velocities: the sum of squares Q (the GLR for an
#: arbitrary offset vector), or the GLS-weighted sum w·z, w = C_z⁻¹ 1 (the most powerful invariant test against a
#: common offset when the samples correlate as the filter's outputs do).
UMP_COMPARATORS = ("Q (sum of squares)", "GLS-weighted sum")
#: C001-9's extrapolation horizon, s: the scenario's 10 s loss, or the 3rd-order filter's memory (k_b3 = 100 frames).
HORIZONS = {"10 s loss": 10.0, "4 s filter memory": 4.0}
COMPARATORS = ("fixed 2nd order", "fixed 3rd order", "IMM", "VD filter")
#: Tuning grids (elements, frames); the first value of the fixed filters' grids is the physical floor of the
#: growing-memory law (the gains of a 2- or 3-point fit), not a grid edge; likewise q_CV = 0 for the IMM's CV model.
FIXED2_GRID = (2, 5, 10, 20, 50, 100, 200, 400)
FIXED3_GRID = (3, 5, 10, 20, 30, 50, 100, 200, 400)
IMM_Q_CA_GRID = (1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2)
IMM_P_STAY_GRID = (0.9, 0.99, 0.999, 0.9999, 0.99999)
VDF_Q_CA_GRID = (1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2)
VDF_WINDOWS = (2, 5, 10, 25)
#: grid values that are physical floors (an optimum there is not an edge effect)
FLOORS = {"fixed 2nd order": (2,), "fixed 3rd order": (3,), "IMM": (), "VD filter": (2,)}


@dataclass(frozen=True)
class Scenario:
    """The paper's scenario at one frame rate.

    Attributes
    ----------
    fps : float                 frame rate, Hz
    T, onset, f_loss, f_back : int   frames: length, manoeuvre onset, first lost frame, first frame back
    visible : ndarray of bool, shape (T,)
    truth : ndarray, shape (2, T, 3)  true (x, v, a) of the two channels
    """

    fps: float
    T: int
    onset: int
    f_loss: int
    f_back: int
    visible: np.ndarray
    truth: np.ndarray

    @property
    def frames(self) -> np.ndarray:
        return np.arange(self.T)


def scenario(
    frame_rate_hz: float = 25.0,
    duration_s: float = 25.0,
    maneuver_s: float = 5.0,
    loss_s: float = 12.0,
    reappear_s: float = 22.0,
    motion=MOTION,
    accel_duration_s: float | None = None,
) -> Scenario:
    """Uniform motion, constant acceleration from ``maneuver_s`` (for ``accel_duration_s``, then uniform motion
    again; None: to the end), lost from ``loss_s`` to ``reappear_s``."""
    fps = float(frame_rate_hz)
    T = int(round(duration_s * fps))
    onset = int(round(maneuver_s * fps))
    f_loss, f_back = int(round(loss_s * fps)), int(round(reappear_s * fps))
    f = np.arange(T)
    scale = FPS_REF / fps
    truth = np.stack([manoeuvre_truth(v0 * scale, a * scale**2, onset, T) for v0, a in motion])
    if accel_duration_s is not None:  # the acceleration stops after D frames: x, v continue uniformly
        D = int(round(accel_duration_s * fps))
        d = np.clip(f - onset, 0, None)
        dc = np.minimum(d, D)
        acc = np.array([a * scale**2 for _, a in motion])[:, None]
        truth[..., 0] = truth[..., 0] - 0.5 * acc * d**2 + acc * (0.5 * dc**2 + D * (d - dc))
        truth[..., 1] = truth[..., 1] - acc * d + acc * dc
        truth[..., 2] = np.where((f >= onset) & (d < D), acc, 0.0)
    return Scenario(fps, T, onset, f_loss, f_back, (f < f_loss) | (f >= f_back), truth)


def config_scenario(config: dict) -> Scenario:
    """The scenario of a configuration: its frame rate, its manoeuvre (``MANOEUVRES``; default constant) and the
    second channel's motion (``CHANNEL_Y``; default the card's) and the acceleration's unit (``ACCEL_UNITS``)."""
    u = ACCEL_UNITS[config.get("accel_unit", "el/frame²")]
    return scenario(
        config["frame_rate_hz"],
        motion=tuple((v0, u * a) for v0, a in (MOTION[0], CHANNEL_Y[config.get("channel_y", "v -6, a -0.2")])),
        accel_duration_s=MANOEUVRES[config.get("manoeuvre", "constant acceleration")],
    )


def measurements(truth_pos, model: str, n: int, rng: np.random.Generator, sigma_eps: float = 1.0) -> np.ndarray:
    """``n`` noisy copies of ``truth_pos`` (..., T) -> (n, ..., T) under a measurement-error model of RMS sigma.

    The standard normal draws come first and have the same shape for every model (common random numbers):
    white Gaussian; quantised to whole elements (Gaussian part of variance sigma² - 1/12); AR(1) with lag-1
    correlation 0.5 (stationary from the first frame); Student t with 3 degrees of freedom (scaled to RMS sigma).
    """
    truth_pos = np.asarray(truth_pos, dtype=float)
    e = rng.standard_normal((n,) + truth_pos.shape)
    if model == "white Gaussian":
        return truth_pos + sigma_eps * e
    if model == "quantised":
        return np.round(truth_pos + np.sqrt(max(sigma_eps**2 - 1 / 12, 0.0)) * e)
    if model == "AR(1), rho = 0.5":
        x = np.sqrt(0.75) * e
        x[..., 0] = e[..., 0]
        return truth_pos + sigma_eps * signal.lfilter([1.0], [1.0, -0.5], x, axis=-1)
    if model == "Student t, 3 dof":
        chi2 = rng.chisquare(3, e.shape)
        return truth_pos + sigma_eps * np.sqrt(1 / 3) * e / np.sqrt(chi2 / 3)
    raise ValueError(f"measurement-error model {model!r}; it must be one of {NOISE_MODELS}")


def detector_threshold(reading: str, visible, k_bound2: int, n: int, alpha: float, sigma_eps: float = 1.0):
    """``c(alpha)`` per frame (T,) under one reading of the paper's sigma_S (card §4.3).

    ``"exact"``: time-varying gains including any coast (:func:`track2_thresholds`); ``"stationary"``: the
    correlated Lyapunov value; ``"independent"``: the paper's independence with the filter-output velocity RMS;
    ``"raw increments"``: independence with the RMS of the raw coordinate increments, ``sigma_v² = 2 sigma²``.
    """
    visible = np.asarray(visible, dtype=bool)
    if reading == "exact":
        return track2_thresholds(visible, k_bound2, n, alpha, sigma_eps)
    K2 = gain_schedule(1, k_bound2)[-1]
    sig = {
        "stationary": lambda: statistic_std(K2, sigma_eps, n, "correlated"),
        "independent": lambda: statistic_std(K2, sigma_eps, n, "independent"),
        "raw increments": lambda: np.sqrt(4 * n) * sigma_eps,
    }
    if reading not in sig:
        raise ValueError(f"threshold reading {reading!r}; it must be one of {THRESHOLD_READINGS}")
    return np.full(visible.size, float(threshold_from_std(alpha, sig[reading]())))


def arming_count(rule: str, k_bound2: int, n: int, onset: int) -> tuple[int, str]:
    """The TRACK2 count at which the detector starts testing, and the rule applied.

    ``"gains at bound"``: ``k_b2 + 2n`` (both windows at the frozen gains: sigma "known and equal for all
    samples", the paper's premise); ``"windows full"``: ``2n + 1``, the first count at which both windows hold
    least-squares velocities (the first measurement's velocity carries none). The paper's detector is running
    when the manoeuvre begins (Fig. 2), so where a rule would first test at or after the onset frame it arms when
    its windows are full instead (the rule applied is returned).
    """
    if rule not in ARMING_RULES:
        raise ValueError(f"arming rule {rule!r}; it must be one of {ARMING_RULES}")
    arm = k_bound2 + 2 * n if rule == "gains at bound" else 2 * n + 1
    if arm - 1 >= onset:
        return 2 * n + 1, "windows full (the stated rule would first test after the onset)"
    return arm, rule


def gls_window_taps(K2, n: int, sigma_eps: float = 1.0) -> np.ndarray:
    """Taps (2n,) over ``v[t-2n+1 .. t]`` of the GLS-weighted window difference: ``+w`` on the older window, ``-w``
    on the newer, ``w = C_z⁻¹ 1`` with ``C_z`` the stationary covariance of ``z_k = v_k - v_{k+n}`` of the frozen
    filter with gains ``K2`` (``cov(z_i, z_j) = 2 r(i-j) - r(i-j-n) - r(i-j+n)``); with independent samples
    ``w`` is constant and the statistic is (14)'s S up to scale."""
    from ...filters.alphabeta import lagged_covariances

    r = lagged_covariances(np.asarray(K2, float), sigma_eps, 2 * n)[:, 1, 1]
    d = np.subtract.outer(np.arange(n), np.arange(n))
    Cz = 2 * r[np.abs(d)] - r[np.abs(d - n)] - r[np.abs(d + n)]
    w = np.linalg.solve(Cz, np.ones(n))
    return np.concatenate([w, -w]) / np.abs(w).sum()


def tapped_window_statistic(v, taps) -> np.ndarray:
    """``sum_j taps[j] v[t-2n+1+j]`` along the last axis, NaN before the window is full (shape of v)."""
    taps = np.asarray(taps, float)
    v = np.asarray(v, float)
    out = signal.lfilter(taps[::-1], [1.0], np.nan_to_num(v), axis=-1)
    out[..., : taps.size - 1] = np.nan
    return out


def _full(config: dict, sizes: dict) -> dict:
    """``config`` completed with the register's defaults (``sizes["defaults"]``)."""
    return {**sizes.get("defaults", {}), **config}


def _missing(what: str) -> Estimate:
    return Estimate(float("nan"), float("nan"), float("nan"), float("nan"), 0, 0.95, what)


def _frame_resolution(e: Estimate, fps: float) -> Estimate:
    """A detection-time quantile with its order-statistic interval widened by half a frame each side: a detection
    at frame f means the statistic crossed the threshold within the frame interval, so time is known to a frame
    (the interval of a quantile of frame-quantised times is otherwise often one frame wide, i.e. degenerate)."""
    h = 0.5 / fps
    return Estimate(
        e.value,
        e.stderr,
        e.ci_low - h,
        e.ci_high + h,
        e.n,
        e.confidence,
        f"{e.method}, widened by half a frame each side (time resolution)",
    )


def _per_alpha(e: Estimate, alpha: float) -> Estimate:
    """A per-test rate in units of alpha (so one rule serves every alpha of the register)."""
    return Estimate(
        e.value / alpha,
        e.stderr / alpha,
        e.ci_low / alpha,
        e.ci_high / alpha,
        e.n,
        e.confidence,
        "exact" if e.method == "exact" else f"{e.method}, divided by alpha",  # a closed-form number stays exact
    )


def measure_detection(config: dict, seed: int, sizes: dict) -> dict:
    """C001-1 (detection time), C001-2 (size, invariance, unbiasedness, optimality) and C001-3 (the paper's
    independence threshold) from one full-size run. Per-test rates are in units of the configuration's alpha.

    Config entries read: ``frame_rate_hz``, ``window_n``, ``k_bound2``, ``alpha``, ``arming``, ``threshold``,
    ``paper_sigma``, ``noise``, ``alternative``, ``roc_delay_s``, ``step_dv``, ``ump_comparator``. Sizes:
    ``n_trials`` (scenario runs, both channels), ``n_fa_runs`` (no-manoeuvre runs), ``fa_duration_s``,
    ``sigma_eps``.
    """
    config = _full(config, sizes)
    sc = config_scenario(config)
    n, kb2, alpha, sigma = int(config["window_n"]), int(config["k_bound2"]), float(config["alpha"]), sizes["sigma_eps"]
    arm_k, _ = arming_count(config["arming"], kb2, n, sc.onset)
    rng = np.random.default_rng(seed)
    scale = FPS_REF / sc.fps
    # the scenario runs up to the loss, both channels
    Tl = sc.f_loss
    z = measurements(sc.truth[:, :Tl, 0], config["noise"], sizes["n_trials"], rng, sigma)  # (runs, 2, Tl)
    # no-manoeuvre runs: uniform motion of channel x
    d_roc = int(round(float(config["roc_delay_s"]) * sc.fps))
    Tr = sc.onset + d_roc + 1
    T0 = max(int(round(sizes["fa_duration_s"] * sc.fps)), Tr, arm_k + 1)
    z0 = measurements(MOTION[0][0] * scale * np.arange(T0), config["noise"], sizes["n_fa_runs"], rng, sigma)
    G0 = gain_schedule(1, kb2, T0)
    v0_hat = scheduled_filter(z0, G0)[..., 1]
    S0 = window_statistic(v0_hat, n)
    f0 = np.arange(T0)
    armed0 = f0 >= arm_k - 1
    pre0 = armed0 & (f0 < sc.onset)
    # C001-1: the scheme with the reading's threshold
    c1 = detector_threshold(config["threshold"], np.ones(Tl, bool), kb2, n, alpha, sigma)
    cfg = TrackModeConfig(k_bound2=kb2, window=n, threshold=c1, threshold_index="frame", arm_k=arm_k)
    det = run_track_modes(z, np.ones(Tl, bool), cfg, sigma, covariance=False).detection_frame
    s = detection_time_summary(det, sc.onset, Tl, sc.fps)
    c001_1 = {
        "median": _frame_resolution(s["median_s"], sc.fps) if s["median_s"] else _missing("fewer than two detections"),
        "early": s["false_alarm_before_onset"],
        "missed": s["missed_by_loss"],
    }
    # C001-2: size with the exact sigma_S; unbiasedness and power against Q on the TRACK2 filter (no switch)
    c_exact0 = detector_threshold("exact", np.ones(T0, bool), kb2, n, alpha, sigma)
    size = false_alarm_rates(S0, c_exact0, armed0, pre0, T0 - 1, arm_k - 1)["per_test_pooled"]
    if config["alternative"] == "ramp":
        za = z[..., :Tr]
    else:  # a velocity step of step_dv at the onset, both channels
        t = np.arange(Tr)
        steps = np.stack(
            [
                v0 * scale * t + np.sign(a) * float(config["step_dv"]) * scale * np.clip(t - sc.onset, 0, None)
                for v0, a in MOTION
            ]
        )
        za = measurements(steps, config["noise"], sizes["n_trials"], rng, sigma)
    va = scheduled_filter(za, G0[:Tr])[..., 1]
    sig_t = scheduled_statistic_std(G0[:Tr], n, sigma)
    sig_t = np.where(np.isfinite(sig_t), sig_t, np.inf)
    arm_r = np.arange(Tr) >= arm_k - 1
    if config.get("ump_comparator", UMP_COMPARATORS[0]) == UMP_COMPARATORS[0]:
        Q0, Qa = window_sum_of_squares(v0_hat[:, :Tr], n), window_sum_of_squares(va, n)
    else:  # |w·z| with the GLS taps of the frozen TRACK2 filter
        taps = gls_window_taps(G0[-1], n, sigma)
        Q0, Qa = np.abs(tapped_window_statistic(v0_hat[:, :Tr], taps)), np.abs(tapped_window_statistic(va, taps))
    q_scale = np.full(Tr, np.inf)
    q_scale[arm_r] = Q0[:, arm_r].mean(axis=0)
    stat_S, stat_S0 = np.abs(window_statistic(va, n)) / sig_t, np.abs(S0[:, :Tr]) / sig_t
    stat_Q, stat_Q0 = Qa / q_scale, Q0 / q_scale
    hits_S = first_alarm_within(stat_S, null_quantile_threshold(stat_S0, arm_r, alpha), arm_r, sc.onset)
    hits_Q = first_alarm_within(stat_Q, null_quantile_threshold(stat_Q0, arm_r, alpha), arm_r, sc.onset)
    post = arm_r & (np.arange(Tr) >= sc.onset)
    unbiased = mean_ci((stat_S[..., post] > stats.norm.isf(alpha / 2)).mean(axis=-1).reshape(-1))
    shift = 50 * rng.standard_normal((5, n))
    v_test = v0_hat[:5, -2 * n :]
    invariance = float(
        np.max(
            np.abs(
                window_statistic(v_test + np.concatenate([shift, shift], axis=1), n)[:, -1]
                - window_statistic(v_test, n)[:, -1]
            )
        )
    )
    c001_2 = {
        "size": _per_alpha(size, alpha),
        "invariance": invariance,
        "unbiased": _per_alpha(unbiased, alpha),
        "UMP": paired_difference(hits_S.reshape(-1).astype(float), hits_Q.reshape(-1).astype(float)),
    }
    # C001-3: the paper's independence threshold, sigma read as the filter-output or the raw-increment RMS
    reading = "independent" if config["paper_sigma"] == "filter-output velocity" else "raw increments"
    c_paper = detector_threshold(reading, np.ones(T0, bool), kb2, n, alpha, sigma)
    mc3 = false_alarm_rates(S0, c_paper, armed0, pre0, T0 - 1, arm_k - 1)["per_test_pooled"]
    cf3 = closed_form_rate(
        statistic_impulse_response(G0, n), c_paper, armed0, config["noise"], sigma, rng=rng, runs=2000, mc=mc3
    )
    c001_3 = _per_alpha(cf3, alpha)
    return {"C001-1": c001_1, "C001-2": c001_2, "C001-3": c001_3}


def c3_closed_form_check(config: dict, seed: int, sizes: dict) -> dict:
    """C001-3's closed form against a Monte Carlo of the same per-test rate (in units of alpha) on
    ``n_fa_runs`` fresh no-manoeuvre runs of ``fa_duration_s``: :func:`.false_alarm.closed_form_check`."""
    config = _full(config, sizes)
    sc = config_scenario(config)
    n, kb2, alpha, sigma = int(config["window_n"]), int(config["k_bound2"]), float(config["alpha"]), sizes["sigma_eps"]
    arm_k, _ = arming_count(config["arming"], kb2, n, sc.onset)
    rng = np.random.default_rng(seed)
    T0 = max(int(round(sizes["fa_duration_s"] * sc.fps)), arm_k + 1)
    z0 = measurements(MOTION[0][0] * FPS_REF / sc.fps * np.arange(T0), config["noise"], sizes["n_fa_runs"], rng, sigma)
    G0 = gain_schedule(1, kb2, T0)
    S0 = window_statistic(scheduled_filter(z0, G0)[..., 1], n)
    f0 = np.arange(T0)
    armed0 = f0 >= arm_k - 1
    reading = "independent" if config["paper_sigma"] == "filter-output velocity" else "raw increments"
    c = detector_threshold(reading, np.ones(T0, bool), kb2, n, alpha, sigma)
    mc = false_alarm_rates(S0, c, armed0, armed0 & (f0 < sc.onset), T0 - 1, arm_k - 1)["per_test_pooled"]
    cf = closed_form_rate(statistic_impulse_response(G0, n), c, armed0, config["noise"], sigma, rng=rng, mc=mc)
    return closed_form_check(_per_alpha(cf, alpha), _per_alpha(mc, alpha))


def span_mask(span: str, sc: Scenario) -> np.ndarray:
    """Frames over which a position RMS is taken: ``"4 s to loss"`` (tracking, after the TRACK2 gains and the
    detector have settled), ``"onset to loss"``, ``"visible after 4 s"`` (reacquisition included) and ``"end of the
    loss"`` (the last lost frame, where the estimate is the pure prediction through the loss)."""
    f = sc.frames
    settled = f >= int(round(4.0 * sc.fps))
    masks = {
        "visible after 4 s": sc.visible & settled,
        "onset to loss": (f >= sc.onset) & (f < sc.f_loss),
        "4 s to loss": settled & (f < sc.f_loss),
        "end of the loss": f == sc.f_back - 1,
        "last frame before the loss": f == sc.f_loss - 1,
    }
    if span not in masks:
        raise ValueError(f"RMS span {span!r}; it must be one of {TUNING_SPANS}")
    return masks[span]


def _scheme_config(config: dict, sc: Scenario, sizes: dict, **over) -> TrackModeConfig:
    n, kb2 = int(config["window_n"]), int(config["k_bound2"])
    arm_k, _ = arming_count(config["arming"], kb2, n, sc.onset)
    thr = detector_threshold(config["threshold"], sc.visible, kb2, n, float(config["alpha"]), sizes["sigma_eps"])
    kw = dict(
        k_bound2=kb2,
        k_bound3=int(config["k_bound3"]),
        window=n,
        threshold=thr,
        threshold_index="frame",
        arm_k=arm_k,
        restart=config["restart"],
        restart_accel_var=float(config["restart_accel_var"]),
    )
    return TrackModeConfig(**(kw | over))


def run_scheme(z, sc: Scenario, config: dict, sizes: dict, covariance: bool = True):
    """The paper's scheme (mode logic with the register's threshold, arming and restart) on measurements z."""
    cfg = _scheme_config(config, sc, sizes)
    return run_track_modes(z, sc.visible, cfg, sizes["sigma_eps"], covariance=covariance or cfg.restart == "C")


def _imm(z, sc, q_ca, p_stay, coast, sigma):
    Fs, Qs = cv_ca_models(0.0, q_ca)
    M = np.array([[p_stay, 1 - p_stay], [1 - p_stay, p_stay]])
    zz = np.where(sc.visible, z, np.nan)[..., None]
    return imm_run(
        zz,
        Fs,
        Qs,
        np.array([[1.0, 0, 0]]),
        np.array([[sigma**2]]),
        M,
        np.zeros(3),
        np.diag([1e6, 1e4, 1.0]),
        [0.5, 0.5],
        coast=coast,
    )


def comparator_positions(name: str, setting: tuple, z, sc: Scenario, sigma: float) -> np.ndarray:
    """Position estimates (..., T) of one comparator at one setting (its tuned parameters).

    ``"fixed 2nd order"`` / ``"fixed 3rd order"``: ``(k_b,)``, the growing-memory law frozen at ``k_b``, coasting
    while lost; ``"IMM"``: ``(q_ca, p_stay, coast)``, CV/CA with ``q_CV = 0`` (the CV model has no process noise,
    like the paper's TRACK2; 0 is its physical floor, not a grid edge); ``"VD filter"``: ``(q_ca, window,
    threshold)``.
    """
    if name in ("fixed 2nd order", "fixed 3rd order"):
        order = 1 if name == "fixed 2nd order" else 2
        return scheduled_filter(np.where(sc.visible, z, np.nan), gain_schedule(order, int(setting[0]), sc.T))[..., 0]
    if name == "IMM":
        return _imm(z, sc, setting[0], setting[1], setting[2], sigma).x[..., 0]
    if name == "VD filter":
        return vd_filter_run(z, sc.visible, 0.0, setting[0], sigma, int(setting[1]), setting[2]).x[..., 0]
    raise ValueError(f"comparator {name!r}; it must be one of {COMPARATORS}")


def _span_ms(xhat, sc: Scenario, channel_truth) -> dict:
    e2 = (xhat - channel_truth) ** 2
    return {span: e2[..., span_mask(span, sc)].mean(axis=(-1, -2)) for span in TUNING_SPANS}


@functools.lru_cache(maxsize=4)
def tuned_comparators(
    frame_rate_hz: float,
    n_train: int,
    train_seed: int,
    alpha: float,
    sigma_eps: float = 1.0,
    grids: tuple = (),
    manoeuvre: str = "constant acceleration",
) -> dict:
    """Each comparator tuned on ``n_train`` training runs of the scenario with white Gaussian errors (their own
    seed, never the test runs) for the lowest position RMS over each span:
    ``{span: {comparator: (setting, training RMS, on_edge)}}``.

    The same effort for every comparator: a grid over its parameters (``FIXED2_GRID``, ``FIXED3_GRID``,
    ``IMM_Q_CA_GRID`` x ``IMM_P_STAY_GRID`` and the best of three ways to coast, ``VDF_Q_CA_GRID`` x
    ``VDF_WINDOWS``; ``grids`` overrides them: pairs (name, values) with names ``fixed2``, ``fixed3``,
    ``imm_q_ca``, ``imm_p_stay``, ``vdf_q_ca``, ``vdf_windows``); ``on_edge`` flags an optimum on a grid edge that is not a physical floor (``FLOORS``).
    Like the paper's scheme, whose thresholds assume white Gaussian errors, the comparators are tuned once for
    white Gaussian errors and then face every measurement-error model untuned. The VD filter's threshold is the
    ``1 - alpha`` quantile of its statistic before the onset (per-test rate alpha, as the paper's detector).
    """
    g = {
        "fixed2": FIXED2_GRID,
        "fixed3": FIXED3_GRID,
        "imm_q_ca": IMM_Q_CA_GRID,
        "imm_p_stay": IMM_P_STAY_GRID,
        "vdf_q_ca": VDF_Q_CA_GRID,
        "vdf_windows": VDF_WINDOWS,
    } | dict(grids)
    sc = config_scenario({"frame_rate_hz": frame_rate_hz, "manoeuvre": manoeuvre})
    rng = np.random.default_rng(train_seed)
    z = measurements(sc.truth[:, :, 0], "white Gaussian", n_train, rng, sigma_eps)
    truth = sc.truth[None, :, :, 0]
    cand = {"fixed 2nd order": [(kb,) for kb in g["fixed2"]], "fixed 3rd order": [(kb,) for kb in g["fixed3"]]}
    cand["IMM"] = [(q, p, "mix") for q, p in itertools.product(g["imm_q_ca"], g["imm_p_stay"])]
    vd_thr = {}
    for w in g["vdf_windows"]:  # CV only (no detection): rho does not depend on q_CA
        rho = vd_filter_run(z, sc.visible, 0.0, g["vdf_q_ca"][0], sigma_eps, w, np.inf).rho[..., w + 1 : sc.onset]
        vd_thr[w] = float(np.quantile(rho, 1 - alpha))
    cand["VD filter"] = [(q, w, vd_thr[w]) for q, w in itertools.product(g["vdf_q_ca"], g["vdf_windows"])]

    def score(name, setting):
        return {
            k: float(v.mean())
            for k, v in _span_ms(comparator_positions(name, setting, z, sc, sigma_eps), sc, truth).items()
        }

    scores = {name: {st: score(name, st) for st in settings} for name, settings in cand.items()}
    for q, p, _ in {min(scores["IMM"], key=lambda st: scores["IMM"][st][span]) for span in TUNING_SPANS}:
        for coast in ("frozen", "mode"):  # three ways to coast at each best process noise
            scores["IMM"][(q, p, coast)] = score("IMM", (q, p, coast))
    out = {}
    for span in TUNING_SPANS:
        out[span] = {}
        for name, sc_ in scores.items():
            best = min(sc_, key=lambda st: sc_[st][span])
            out[span][name] = (best, float(np.sqrt(sc_[best][span])), _on_edge(name, best, g))
    return out


def _on_edge(name: str, best: tuple, g: dict) -> bool:
    grids = {
        "fixed 2nd order": (g["fixed2"],),
        "fixed 3rd order": (g["fixed3"],),
        "IMM": (g["imm_q_ca"], g["imm_p_stay"]),
        "VD filter": (g["vdf_q_ca"], g["vdf_windows"]),
    }[name]
    return any(len(v_) > 1 and v in (min(v_), max(v_)) and v not in FLOORS[name] for v_, v in zip(grids, best))


def _tuning(config: dict, sizes: dict) -> dict:
    grids = tuple((k, tuple(v)) for k, v in sizes.get("grids", {}).items())
    return tuned_comparators(
        float(config["frame_rate_hz"]),
        sizes["n_train"],
        sizes["train_seed"],
        float(config["alpha"]),
        sizes["sigma_eps"],
        grids,
        config.get("manoeuvre", "constant acceleration"),
    )


def tradeoff_runs(config: dict, seed: int, sizes: dict) -> dict:
    """The scheme and every tuned comparator on the same test runs (channel x and y).

    Returns
    -------
    dict
        ``scenario``; ``positions`` ``{name: (runs, 2, T)}`` for ``"adaptive"``, ``"2nd order without the
        switch"`` (the scheme's own TRACK2 filter, never switching) and each comparator tuned for the config's
        ``rms_span``; ``tuning`` (settings, training RMS, on-edge flags); ``z`` the measurements.
    """
    config = _full(config, sizes)
    sc = config_scenario(config)
    sigma = sizes["sigma_eps"]
    rng = np.random.default_rng(seed)
    z = measurements(sc.truth[:, :, 0], config["noise"], sizes["n_tradeoff_trials"], rng, sigma)
    tuning = _tuning(config, sizes)[config["rms_span"]]
    pos = {
        "adaptive": run_scheme(z, sc, config, sizes, covariance=False).x[..., 0],
        "2nd order without the switch": comparator_positions(
            "fixed 2nd order", (int(config["k_bound2"]),), z, sc, sigma
        ),
    }
    for name, (setting, _, _) in tuning.items():
        pos[name] = comparator_positions(name, setting, z, sc, sigma)
    return {"scenario": sc, "positions": pos, "tuning": tuning, "z": z}


def scenario_runs(config: dict, seed: int, sizes: dict, restarts=("A", "B", "C")) -> dict:
    """The paper's scenario (both channels, ``sizes["n_trials"]`` runs) through the scheme under each restart rule,
    with the covariance (gate): ``{"scenario", "z", "outs": {restart: TrackModeOutput}}``."""
    config = _full(config, sizes)
    sc = config_scenario(config)
    z = measurements(
        sc.truth[:, :, 0], config["noise"], sizes["n_trials"], np.random.default_rng(seed), sizes["sigma_eps"]
    )
    return {"scenario": sc, "z": z, "outs": {r: run_scheme(z, sc, config | {"restart": r}, sizes) for r in restarts}}


def gain_checks(out, sc: Scenario, k_bound3: int) -> dict:
    """C001-5's implementation checks: increases of kappa1 on consecutive visible frames outside the order switches,
    and the runs x channels that switched at least ``k_bound3`` frames before the loss and sit at the 3rd-order
    bound's kappa1 at the last frame before it."""
    k1 = out.gains[..., 0]
    both = sc.visible[1:] & sc.visible[:-1]
    dk = np.diff(k1, axis=-1)
    det = out.detection_frame
    switch = np.zeros(dk.shape, bool)
    hit = det >= 0
    idx = np.nonzero(hit)
    switch[idx + (np.clip(det[hit], 0, sc.T - 2),)] = True
    increases = int(np.sum((dk > 1e-15) & both & ~switch))
    long_enough = hit & (sc.f_loss - 1 - det >= k_bound3)
    at_bound = np.isclose(k1[..., sc.f_loss - 1], gain_schedule(2, k_bound3)[-1, 0])
    return {
        "increases_outside_switches": increases,
        "long_enough": int(long_enough.sum()),
        "at_bound": int((at_bound & long_enough).sum()),
    }


def coast_check(out, sc: Scenario) -> dict:
    """C001-6: the largest difference between the actual error while lost and ``F^m`` times the error at the last
    seen frame (E2), and the size of the errors, elements."""
    from ...filters.polynomial import taylor_transition

    err = out.x - sc.truth[None]
    m = np.arange(1, sc.f_back - sc.f_loss + 1)
    Fm = np.stack([np.linalg.matrix_power(taylor_transition(2), int(k)) for k in m])
    pred = np.einsum("mij,...j->...mi", Fm, err[..., sc.f_loss - 1, :])
    actual = err[..., sc.f_loss : sc.f_back, :]
    return {"max_abs_deviation": float(np.max(np.abs(pred - actual))), "error_scale": float(np.max(np.abs(actual)))}


def sigma_s_readings(config: dict, sizes: dict) -> dict:
    """sigma_S (elements/frame) at the detector's arming under each threshold reading, the lag-1 correlation of the
    frozen TRACK2 filter's output velocity, and the per-test rate the paper's independence threshold gives at
    stationarity (Gaussian: 2 Phi(-c_ind / sigma_S))."""
    from ...filters.alphabeta import lagged_covariances

    config = _full(config, sizes)
    n, kb2, alpha = int(config["window_n"]), int(config["k_bound2"]), float(config["alpha"])
    K2 = gain_schedule(1, kb2)[-1]
    C = lagged_covariances(K2, sizes["sigma_eps"], 2)
    z_a = stats.norm.isf(alpha / 2)
    sig = {
        r: float(detector_threshold(r, np.ones(kb2 + 2 * n + 1, bool), kb2, n, alpha, sizes["sigma_eps"])[-1] / z_a)
        for r in THRESHOLD_READINGS
    }
    return {
        "sigma_S": sig,
        "rho_v1": float(C[1, 1, 1] / C[0, 1, 1]),
        "pfa_independent": float(2 * stats.norm.sf(sig["independent"] / sig["stationary"] * z_a)),
    }


def compensation_ms(xhat, sc: Scenario, end_s: float) -> np.ndarray:
    """Per-run mean-square position error from the onset to ``end_s`` (channels pooled), elements²."""
    f = sc.frames
    m = (f >= sc.onset) & (f < int(round(end_s * sc.fps)))
    return ((xhat - sc.truth[None, :, :, 0]) ** 2)[..., m].mean(axis=(-1, -2))


def raised_second_order(z, sc: Scenario, detection_frame, k_bound2: int, k_bound: int) -> np.ndarray:
    """Positions (..., T) of the scheme's TRACK2 filter whose gains are raised, not its order, at
    ``detection_frame`` (..., -1: none): the growing-memory 2nd-order law bounded at ``k_bound2`` up to the detection,
    then restarted at k = 3 and bounded at ``k_bound`` (>= 3); coasting while lost."""
    t = np.arange(sc.T)
    d = np.where(np.asarray(detection_frame) >= 0, detection_frame, sc.T)[..., None]
    k = np.where(t <= d, np.minimum(t + 1, k_bound2), np.minimum(3 + (t - d - 1), k_bound))
    G = gain_schedule(1, max(int(k_bound), int(k_bound2)), sc.T + 3)
    return scheduled_filter(np.where(sc.visible, z, np.nan), G[k - 1])[..., 0]


def compensation_comparator(name: str, z, sc: Scenario, config: dict, sizes: dict, detection_frame) -> np.ndarray:
    """Positions (..., T) of C001-4's compensation comparator ``name`` (``COMPENSATION_COMPARATORS``). The raised
    2nd-order filter's bound is tuned on ``sizes["n_train"]`` training runs (seed ``train_seed + 1``, white Gaussian)
    for the lowest mean-square error from the onset to ``compensation_end_s``, the measure it is judged on."""
    k2, sigma = int(config["k_bound2"]), sizes["sigma_eps"]
    if name == COMPENSATION_COMPARATORS[0]:
        return comparator_positions("fixed 2nd order", (k2,), z, sc, sigma)
    if name != COMPENSATION_COMPARATORS[1]:
        raise ValueError(f"compensation comparator {name!r}; it must be one of {COMPENSATION_COMPARATORS}")
    rng = np.random.default_rng(sizes["train_seed"] + 1)
    zt = measurements(sc.truth[:, :, 0], "white Gaussian", sizes["n_train"], rng, sigma)
    dt = run_scheme(zt, sc, config, sizes, covariance=False).detection_frame
    end = float(config["compensation_end_s"])
    kb = min(RAISED2_GRID, key=lambda b: compensation_ms(raised_second_order(zt, sc, dt, k2, b), sc, end).mean())
    return raised_second_order(z, sc, detection_frame, k2, kb)


def measure_tradeoff(config: dict, seed: int, sizes: dict) -> dict:
    """C001-4's measurement: :func:`.tradeoff.measure_tradeoff` (the dynamic error's transient and the RMS the
    register's ``rms_statistic`` reads, as separate parts)."""
    from .tradeoff import measure_tradeoff as measure

    return measure(config, seed, sizes)


def forced_output(sc: Scenario, config: dict, sizes: dict, kb3: int, visible, z=None, covariance=True):
    """The scheme with the switch forced at ``switch_s`` (the filter is then linear, card §4.5), on the noise-free
    truth of channel x (``z=None``) or on measurements ``z``."""
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
    (card §4.5). The RMS is the covariance recursion's for white errors (also the RMS of the quantised and
    Student-t models, white with the same variance); for ``config["noise"]`` = AR(1) it is exact for the correlated
    errors: the forced filter is linear, so the prediction error is ``w @ e`` with ``w`` its response to unit
    impulses and variance ``sigma² w R w``, ``R_ij = 0.5^|i-j|``."""
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


def occlusion_frames(reading: str, sc: Scenario) -> tuple[int, int]:
    """Fig. 4's "disappearance at the 10th second": the scenario's loss (12-22 s) or a 10 s loss from 10 s."""
    if reading == "scenario 12-22 s":
        return sc.f_loss, sc.f_back
    if reading == "from 10 s":
        return int(round(10 * sc.fps)), int(round(20 * sc.fps))
    raise ValueError(f"occlusion reading {reading!r}")


def fig4_curves(config: dict, sizes: dict) -> dict:
    """Fig. 4: dynamic error, RMS and their sum at reappearance over ``sizes["kb3_grid"]`` (deterministic)."""
    config = _full(config, sizes)
    sc = config_scenario(config)
    fl, fb = occlusion_frames(config["occlusion"], sc)
    dyn, rms = np.array([prediction_error(sc, config, sizes, kb, fl, fb) for kb in sizes["kb3_grid"]]).T
    return {"kb3": np.asarray(sizes["kb3_grid"]), "dyn": dyn, "rms": rms, "sum": np.abs(dyn) + rms}


def loss_sweep(config: dict, sizes: dict) -> dict:
    """C001-7: a 10 s loss starting at each of ``sizes["loss_grid_s"]`` (deterministic)."""
    config = _full(config, sizes)
    sc = config_scenario(config)
    rows = [
        prediction_error(
            sc, config, sizes, int(config["k_bound3"]), int(round(s * sc.fps)), int(round((s + 10.0) * sc.fps))
        )
        for s in sizes["loss_grid_s"]
    ]
    dyn, rms = np.array(rows).T
    return {"loss_s": np.asarray(sizes["loss_grid_s"]), "dyn": dyn, "rms": rms}


def c7_parts(sweep: dict, tolerance: float = 0.01) -> dict:
    """C001-7's parts: |dynamic| decreasing with the loss time (each point ± ``tolerance``/2 elements,
    :func:`.curves.resolved`); |dynamic| / RMS for the earliest loss."""
    return {
        "decreasing": resolved(np.abs(sweep["dyn"]), tolerance),
        "dominates early": float(abs(sweep["dyn"][0]) / sweep["rms"][0]),
    }


def c8_parts(cur: dict, tolerance: float = 0.01) -> dict:
    """C001-8's parts: RMS decreasing in k_b3; an interior minimum of curve 3 (ends minus the inside minimum);
    |dynamic| increasing from the optimum on (curve points ± ``tolerance``/2 elements, :func:`.curves.resolved`)."""
    s = cur["sum"]
    ib = int(np.argmin(s))
    tail = [float(v) for v in np.abs(cur["dyn"])[ib:]]
    return {
        "RMS decreasing": resolved(cur["rms"], tolerance),
        "interior minimum": float(min(s[0], s[-1]) - s[1:-1].min()),
        "dynamic grows beyond the optimum": resolved(tail if len(tail) >= 2 else [tail[0], tail[0]], tolerance),
    }


def measure_curves(config: dict, seed: int, sizes: dict) -> dict:
    """C001-7 and C001-8 from the noise-free runs and the covariance recursion (``seed`` unused: no draw)."""
    config = _full(config, sizes)
    tol = float(config["curve_tolerance"])
    return {
        "C001-7": c7_parts(loss_sweep(config, sizes), tol),
        "C001-8": c8_parts(fig4_curves(config, sizes), tol),
    }


def fig4_monte_carlo(config: dict, sizes: dict, rng: np.random.Generator) -> dict:
    """Independent Monte Carlo check of Fig. 4: fresh runs per k_b3; mean, SD and SE of the prediction error."""
    config = _full(config, sizes)
    sc = config_scenario(config)
    fl, fb = occlusion_frames(config["occlusion"], sc)
    vis = (sc.frames < fl) | (sc.frames >= fb)
    out = {"mean": [], "sd": [], "se": []}
    for kb in sizes["kb3_grid"]:
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
    """The word a test at ``level`` allows: "agree with" when p >= level, "differ from" otherwise."""
    return "agree with" if p >= level else "differ from"


def unbiased_prediction_bound(sc: Scenario, f_first: int, f_last: int, f_pred: int, sigma_eps: float = 1.0) -> float:
    """SD bound for any *unbiased* predictor of the position at ``f_pred`` from the measurements ``f_first`` ..
    ``f_last`` of a quadratic in white noise (the least-squares fit is the MVU estimator, card §8.3), elements."""
    lags = np.arange(f_last - f_first, -1, -1, dtype=float)
    H = np.stack([np.ones_like(lags), -lags, 0.5 * lags**2], axis=-1)
    m = f_pred - f_last
    u = np.array([1.0, m, 0.5 * m**2])
    return float(sigma_eps * np.sqrt(u @ np.linalg.solve(H.T @ H, u)))


def spherical_deviations(
    ranges_m, speeds, headings_deg, elevations_deg, horizon_s: float = 10.0, deg_per_element: float = 6.0 / 712
) -> np.ndarray:
    """Targets in uniform Cartesian motion seen in azimuth/elevation: the largest deviation (elements) over
    ``horizon_s`` of a linear and of a quadratic extrapolation of the exact angular state at the start.

    Returns
    -------
    ndarray, shape (geometries, 7)
        range m, speed m/s, heading deg, initial elevation deg, stays within ±20° (1/0), linear, quadratic.
    """
    tt = np.linspace(0, horizon_s, 251)
    hd = 1e-3

    def angles(R, V, h, e0, t):
        p = R * np.array([np.cos(e0), 0.0, np.sin(e0)]) + V * np.asarray(t)[:, None] * np.array(
            [np.cos(h), np.sin(h), 0.0]
        )
        return np.degrees(np.arctan2(p[:, 1], p[:, 0])), np.degrees(np.arctan2(p[:, 2], np.hypot(p[:, 0], p[:, 1])))

    rows = []
    for R, V, h, e0 in itertools.product(ranges_m, speeds, np.deg2rad(headings_deg), np.deg2rad(elevations_deg)):
        az, el = angles(R, V, h, e0, tt)
        inside = np.all(np.abs(az) <= 20) and np.all(np.abs(el) <= 20)
        dev = []
        for order in (1, 2):
            worst = 0.0
            for ang, a3 in zip((az, el), angles(R, V, h, e0, [-hd, 0.0, hd])):
                v = (a3[2] - a3[0]) / (2 * hd)
                a = (a3[2] - 2 * a3[1] + a3[0]) / hd**2 if order == 2 else 0.0
                worst = max(worst, float(np.max(np.abs(a3[1] + v * tt + 0.5 * a * tt**2 - ang))) / deg_per_element)
            dev.append(worst)
        rows.append((R, V, np.degrees(h), np.degrees(e0), float(inside), *dev))
    return np.array(rows)


#: The target sets of C001-9: ranges m, speeds m/s, headings deg, initial elevations deg.
TARGET_SETS = {
    "2-20 km, 100-300 m/s": ((2e3, 5e3, 10e3, 20e3), (100.0, 300.0), (90.0, 45.0), (0.0, 10.0, 15.0)),
    "20-100 km, 50-250 m/s": ((20e3, 50e3, 100e3), (50.0, 250.0), (90.0, 45.0), (0.0, 10.0, 15.0)),
    "50-100 km, 100-300 m/s": ((50e3, 70e3, 100e3), (100.0, 300.0), (90.0, 45.0), (0.0, 10.0, 15.0)),
}


#: The paper's two angular rates, deg/s: 10 elements/frame and 0.02°/frame at 25 Hz (C001-10's two figures).
PAPER_RATES = {
    "2.107°/s (10 el/frame)": 10.0 * FPS_REF * 6.0 / 712,
    "0.5°/s (0.02°/frame)": 0.02 * FPS_REF,
}


def paper_rate_deviation(rate_deg_s: float, horizon_s: float = 10.0, extrapolation: str = "quadratic") -> dict:
    """C001-9 at one of the paper's angular rates: a target crossing at closest approach (azimuth 0, elevation 0,
    the rate ``rate_deg_s`` there), its angle extrapolated over ``horizon_s``; the largest deviation from the
    true angle, elements (closed form ``omega H - atan(omega H)`` at the crossing, where the angular acceleration
    is 0 so linear and quadratic coincide), and whether the angle stays within ±20°.
    """
    R = 10e3  # only the rate matters: the angle is atan(omega t)
    row = spherical_deviations([R], [np.deg2rad(rate_deg_s) * R], [90.0], [0.0], horizon_s=horizon_s)[0]
    return {
        "deviation_el": float(row[5] if extrapolation == "linear" else row[6]),
        "within_20deg": bool(row[4] > 0),
        "end_angle_deg": float(np.degrees(np.arctan(np.deg2rad(rate_deg_s) * horizon_s))),
    }


def measure_spherical(config: dict, seed: int, sizes: dict) -> dict:
    """C001-9 in parts: at each of the paper's two rates (:data:`PAPER_RATES`) the deviation in multiples of the
    tolerance (:func:`paper_rate_deviation`), then over the register's grid of geometries the fraction within
    ±20° whose extrapolation stays within the tolerance (``extrapolation``: quadratic/linear; ``tolerance``:
    "1 element" or "prediction RMS at k_b3"; ``targets``: a key of :data:`TARGET_SETS`; ``horizon``: a key of
    :data:`HORIZONS`; NaN when no geometry stays within ±20°)."""
    config = _full(config, sizes)
    H = HORIZONS[config.get("horizon", "10 s loss")]
    tol = 1.0 if config["tolerance"] == "1 element" else float(sizes["prediction_rms"])
    parts = {
        name: paper_rate_deviation(rate, H, config["extrapolation"])["deviation_el"] / tol
        for name, rate in PAPER_RATES.items()
    }
    rows = spherical_deviations(*TARGET_SETS[config["targets"]], horizon_s=H)
    inside = rows[rows[:, 4] > 0]
    col = 5 if config["extrapolation"] == "linear" else 6
    parts["geometries"] = float(np.mean(inside[:, col] < tol)) if inside.size else float("nan")
    return {"C001-9": parts}


def detector_benchmark(config: dict, seed: int, sizes: dict, windows=(10, 25, 50), fa_targets=None) -> dict:
    """Delay against per-run false alarms of the paper's |S| (several half-windows), Q and three innovation tests
    (chi-square over n frames, two-sided CUSUM with drift 0.5, the Willsky-Jones GLR for a velocity jump) on the
    TRACK2 filter: thresholds from no-manoeuvre runs of ``fa_duration_s`` for each per-run false-alarm target,
    median first-alarm delay after the onset on the scenario's runs up to the loss (card §8.1).

    Every detector is armed by the configuration's arming rule for its own window (:func:`arming_count`), so each
    tests before the onset; a detector first armed after the onset would "detect" at its first test in every run.

    Returns
    -------
    dict
        ``{name: curve}`` with the curves of :func:`tvtrack.detect.innovation.delay_false_alarm_curve`, and
        ``"arming_frame"``: ``{name: first tested frame}``.
    """
    from ...detect.innovation import (
        chi2_window,
        cusum,
        delay_false_alarm_curve,
        glr_velocity_jump,
        normalised_innovations,
        velocity_jump_signature,
    )

    config = _full(config, sizes)
    sc = config_scenario(config)
    n, kb2, sigma = int(config["window_n"]), int(config["k_bound2"]), sizes["sigma_eps"]
    targets = np.array([0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5]) if fa_targets is None else np.asarray(fa_targets)
    rng = np.random.default_rng(seed)
    Tl = sc.f_loss
    T0 = int(round(sizes["fa_duration_s"] * sc.fps))
    scale = FPS_REF / sc.fps
    z = measurements(sc.truth[:, :Tl, 0], config["noise"], sizes["n_trials"], rng, sigma)
    z0 = measurements(MOTION[0][0] * scale * np.arange(T0), config["noise"], sizes["n_fa_runs"], rng, sigma)
    G = gain_schedule(1, kb2, max(Tl, T0))
    s_alt, s_null = scheduled_filter(z, G[:Tl]), scheduled_filter(z0, G[:T0])
    u_alt = normalised_innovations(z, s_alt, G[:Tl], sigma)
    u_null = normalised_innovations(z0, s_null, G[:T0], sigma)
    stats_ = {}
    for w in sorted(set(windows) | {n}):
        a, _ = arming_count(config["arming"], kb2, w, sc.onset)
        sig = scheduled_statistic_std(G[:T0], w, sigma)
        sig = np.where(np.isfinite(sig) & (sig > 0), sig, np.inf)
        stats_[f"|S|, n={w}"] = (
            np.abs(window_statistic(s_alt[..., 1], w)) / sig[:Tl],
            np.abs(window_statistic(s_null[..., 1], w)) / sig,
            a,
        )
    a, _ = arming_count(config["arming"], kb2, n, sc.onset)
    q0 = window_sum_of_squares(s_null[..., 1], n)
    q_mean = np.full(T0, np.inf)
    q_mean[a - 1 :] = q0[:, a - 1 :].mean(axis=0)
    stats_[f"Q, n={n}"] = (window_sum_of_squares(s_alt[..., 1], n) / q_mean[:Tl], q0 / q_mean, a)
    stats_[f"chi-square, L={n}"] = (chi2_window(u_alt, n), chi2_window(u_null, n), a)
    stats_["CUSUM, k=0.5"] = (cusum(u_alt, 0.5, a - 1), cusum(u_null, 0.5, a - 1), a)
    sigj = velocity_jump_signature(gain_schedule(1, kb2)[-1], sigma, n)
    stats_[f"GLR velocity jump, L={n}"] = (glr_velocity_jump(u_alt, sigj), glr_velocity_jump(u_null, sigj), a)
    out = {"arming_frame": {}}
    for name, (alt, null, a) in stats_.items():
        out[name] = delay_false_alarm_curve(
            alt,
            null,
            np.arange(Tl) >= a - 1,
            np.arange(T0) >= a - 1,
            sc.onset,
            targets,
            sc.fps,
            float(config["roc_delay_s"]),
        )
        out["arming_frame"][name] = a - 1
    return out
