"""The scenario of paper 001 (Fisenko et al. 2008) and what every study reads: the motion, the measurement-error
models, the detector's thresholds and arming, the spans and the scheme run under a configuration of the register.

Units: positions in raster elements, velocities in elements/frame, accelerations in elements/frame². The paper
states its motion per frame (10 elements per frame, 0.2 elements per frame²) and its times in seconds (the onset at
5 s, the loss from 12 to 22 s); its frame rate is never printed. So the motion is kept per frame at every frame rate
and only the times are converted to frames.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import signal

from ...filters.alphabeta import gain_schedule
from .maneuver_detector import (
    statistic_std,
    threshold_from_std,
    track2_thresholds,
)
from .track_modes import TrackModeConfig, manoeuvre_truth, run_track_modes

__all__ = [
    "with_defaults",
    "FPS_REF",
    "MOTION",
    "NOISE_MODELS",
    "THRESHOLD_READINGS",
    "ARMING_RULES",
    "RMS_SPANS",
    "TUNING_SPANS",
    "MANOEUVRES",
    "CHANNEL_Y",
    "ACCEL_UNITS",
    "accel_factor",
    "uniform_truth",
    "COMPENSATION_COMPARATORS",
    "RAISED2_GRID",
    "UMP_COMPARATORS",
    "COMPARATORS",
    "FIXED2_GRID",
    "FIXED3_GRID",
    "IMM_Q_CA_GRID",
    "IMM_P_STAY_GRID",
    "VDF_Q_CA_GRID",
    "VDF_WINDOWS",
    "FLOORS",
    "Scenario",
    "scenario",
    "config_scenario",
    "measurements",
    "detector_threshold",
    "arming_count",
    "TEST_CADENCES",
    "cadence_threshold",
    "span_mask",
    "run_scheme",
]


#: The register's default frame rate (Hz), a TV frame rate; the paper's is never printed. It sets no motion: the
#: paper's motion is per frame at every frame rate.
FPS_REF = 25.0


#: (initial velocity el/frame, acceleration el/frame²) of the channels x (the paper's) and y (not stated), at every
#: frame rate.
MOTION = ((10.0, 0.2), (-6.0, -0.2))


NOISE_MODELS = ("white Gaussian", "quantised", "AR(1), rho = 0.5", "Student t, 3 dof")


THRESHOLD_READINGS = ("exact", "stationary", "independent", "raw increments")


ARMING_RULES = ("gains at bound", "windows full")


#: How often the armed detector takes decision (14): every frame (sliding windows), every n frames (windows
#: overlapping by half) or every 2n frames (disjoint intervals 2T), from the first armed frame on.
TEST_CADENCES = ("every frame", "every n frames", "every 2n frames")


RMS_SPANS = ("4 s to loss", "onset to loss", "visible after 4 s", "end of the loss")


#: The spans the comparators are tuned for: the register's, and the last frame before the loss (the
#: "|bias| + RMS at 12 s" reading of C001-4, the acceptance first set here).
TUNING_SPANS = RMS_SPANS + ("last frame before the loss",)


#: How long the acceleration lasts (s; None: to the end of the run). The paper gives the onset and the value only.
MANOEUVRES = {"constant acceleration": None, "2 s acceleration": 2.0}


#: The second channel's (initial velocity el/frame, acceleration el/frame²) at every frame rate: not stated (one channel was
#: simulated); the paper's magnitude, or a turn mostly in x that gives y a quarter of it.
CHANNEL_Y = {"v -6, a -0.2": (-6.0, -0.2), "v -6, a -0.05": (-6.0, -0.05)}


#: The unit of the paper's "acceleration 0.2 raster elements per frame": el/frame² (this project's default), or a
#: velocity change of 0.2 el/frame per second (the paper's times are in seconds): the power of the frame interval
#: 1/f (s) on the accelerations of ``MOTION`` (:func:`accel_factor`; 1/25 at 25 Hz, 1/50 at 50 Hz).
ACCEL_UNITS = {"el/frame²": 0, "el/frame per s": 1}


def accel_factor(unit: str, frame_rate_hz: float) -> float:
    """The factor on the paper's 0.2 that gives the acceleration in el/frame² under the reading ``unit`` of
    :data:`ACCEL_UNITS` at ``frame_rate_hz``: 1 for el/frame², 1/f for 0.2 el/frame gained per second."""
    if unit not in ACCEL_UNITS:
        raise ValueError(f"acceleration unit {unit!r}; it must be one of {tuple(ACCEL_UNITS)}")
    return float(frame_rate_hz) ** -ACCEL_UNITS[unit]


def uniform_truth(T: int) -> np.ndarray:
    """The positions (T,) of the paper's uniform motion before the manoeuvre, 10 elements per frame from 0 (the
    no-manoeuvre runs), at every frame rate."""
    return MOTION[0][0] * np.arange(T, dtype=float)


#: C001-4's "faster compensation" comparator: the scheme's TRACK2 filter never switching (the default), or the same
#: filter whose 2nd-order gains are raised at the scheme's own detection (restart at k = 3, decaying to a bound tuned
#: on the training runs over ``RAISED2_GRID``; 3 is the physical floor, restart A's k): the order switch isolated.
COMPENSATION_COMPARATORS = ("2nd order without the switch", "2nd order, gains raised at the detection")


RAISED2_GRID = (3, 5, 10, 20, 50)


#: C001-2's "UMP" comparator, another invariant rule on the same 2n velocities: the sum of squares Q (the GLR for an
#: arbitrary offset vector), or the GLS-weighted sum w·z, w = C_z⁻¹ 1 (the most powerful invariant test against a
#: common offset when the samples correlate as the filter's outputs do).
UMP_COMPARATORS = ("Q (sum of squares)", "GLS-weighted sum")


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
    again; None: to the end), lost from ``loss_s`` to ``reappear_s``. ``motion`` is per frame (el/frame, el/frame²)
    at every frame rate; the times in seconds are converted to frames at ``frame_rate_hz``."""
    fps = float(frame_rate_hz)
    T = int(round(duration_s * fps))
    onset = int(round(maneuver_s * fps))
    f_loss, f_back = int(round(loss_s * fps)), int(round(reappear_s * fps))
    f = np.arange(T)
    truth = np.stack([manoeuvre_truth(v0, a, onset, T) for v0, a in motion])
    if accel_duration_s is not None:  # the acceleration stops after D frames: x, v continue uniformly
        D = int(round(accel_duration_s * fps))
        d = np.clip(f - onset, 0, None)
        dc = np.minimum(d, D)
        acc = np.array([a for _, a in motion])[:, None]
        truth[..., 0] = truth[..., 0] - 0.5 * acc * d**2 + acc * (0.5 * dc**2 + D * (d - dc))
        truth[..., 1] = truth[..., 1] - acc * d + acc * dc
        truth[..., 2] = np.where((f >= onset) & (d < D), acc, 0.0)
    return Scenario(fps, T, onset, f_loss, f_back, (f < f_loss) | (f >= f_back), truth)


def config_scenario(config: dict) -> Scenario:
    """The scenario of a configuration: its frame rate, its manoeuvre (``MANOEUVRES``; default constant) and the
    second channel's motion (``CHANNEL_Y``; default this project's) and the acceleration's unit (``ACCEL_UNITS``)."""
    u = accel_factor(config.get("accel_unit", "el/frame²"), config["frame_rate_hz"])
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
    chi2 = rng.chisquare(3, e.shape) if model == "Student t, 3 dof" else None
    return _with_errors(truth_pos, model, e, chi2, sigma_eps)


def prefix_stable_measurements(truth_pos, model: str, n: int, rng: np.random.Generator, sigma_eps: float = 1.0):
    """:func:`measurements` of one track ``truth_pos`` (T,) -> (n, T), drawn frame by frame so that the first
    frames' errors do not depend on the length T: the standard normals are drawn frame-major from one child of
    ``rng`` and the Student-t chi-squares from another. A claim that reads only the first frames of a longer run
    therefore reads the same numbers whatever sets the run's length."""
    truth_pos = np.asarray(truth_pos, dtype=float)
    normals, scales = rng.spawn(2)
    e = normals.standard_normal(truth_pos.shape[::-1] + (n,)).T
    chi2 = scales.chisquare(3, truth_pos.shape[::-1] + (n,)).T if model == "Student t, 3 dof" else None
    return _with_errors(truth_pos, model, e, chi2, sigma_eps)


def _with_errors(truth_pos: np.ndarray, model: str, e: np.ndarray, chi2, sigma_eps: float) -> np.ndarray:
    """``truth_pos`` plus the errors of ``model`` made from standard normals ``e`` (n, ..., T) and, for the
    Student-t model, chi-square(3) draws ``chi2`` of the same shape."""
    if model == "white Gaussian":
        return truth_pos + sigma_eps * e
    if model == "quantised":
        return np.round(truth_pos + np.sqrt(max(sigma_eps**2 - 1 / 12, 0.0)) * e)
    if model == "AR(1), rho = 0.5":
        x = np.sqrt(0.75) * e
        x[..., 0] = e[..., 0]
        return truth_pos + sigma_eps * signal.lfilter([1.0], [1.0, -0.5], x, axis=-1)
    if model == "Student t, 3 dof":
        return truth_pos + sigma_eps * np.sqrt(1 / 3) * e / np.sqrt(chi2 / 3)
    raise ValueError(f"measurement-error model {model!r}; it must be one of {NOISE_MODELS}")


def detector_threshold(reading: str, visible, k_bound2: int, n: int, alpha: float, sigma_eps: float = 1.0):
    """``c(alpha)`` per frame (T,) under one reading of the paper's sigma_S (eq. 14's threshold).

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


def cadence_threshold(threshold, cadence: str, n: int, arm_k: int) -> np.ndarray:
    """The per-frame threshold (T,) with the frames the detector does not test set to infinity: ``cadence`` one of
    :data:`TEST_CADENCES`, the tests every 1, ``n`` or ``2n`` frames from the first armed frame ``arm_k - 1`` (the
    TRACK2 count ``arm_k``; frames before it are left as they are, the mode logic does not test them)."""
    if cadence not in TEST_CADENCES:
        raise ValueError(f"test cadence {cadence!r}; it must be one of {TEST_CADENCES}")
    out = np.array(threshold, dtype=float)
    step = {"every frame": 1, "every n frames": n, "every 2n frames": 2 * n}[cadence]
    f = np.arange(out.size)
    out[(f >= arm_k - 1) & ((f - (arm_k - 1)) % step != 0)] = np.inf
    return out


def with_defaults(config: dict, sizes: dict) -> dict:
    """A configuration completed with the register's defaults.

    Parameters
    ----------
    config : dict
        Register entry name -> value (the entries a run varies).
    sizes : dict
        The run's sizes; ``sizes["defaults"]`` holds every entry's default.

    Returns
    -------
    dict
        Every entry's value: ``config``'s where it names one, the default elsewhere.
    """
    return {**sizes.get("defaults", {}), **config}


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
    thr = cadence_threshold(thr, config["test_cadence"], n, arm_k)
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


def run_scheme(z, sc: Scenario, config: dict, sizes: dict, covariance: bool = True, **over):
    """The paper's scheme (mode logic with the register's threshold, arming and restart) on measurements z;
    ``over``: :class:`TrackModeConfig` fields that replace the register's (``force_switch_k``)."""
    cfg = _scheme_config(config, sc, sizes, **over)
    return run_track_modes(z, sc.visible, cfg, sizes["sigma_eps"], covariance=covariance or cfg.restart == "C")
