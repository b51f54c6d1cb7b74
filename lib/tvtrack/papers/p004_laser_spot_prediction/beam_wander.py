"""Synthetic beam-wander trajectories of a laser spot on a camera sensor.

Model (per image axis, x and y independent and alike)::

    c(t) = c0 + v_d (t - t_mid) + sum_k s_k(t)

- ``s_k``: stationary, critically damped 2nd-order Gauss-Markov processes
  ``s'' + 2 w_k s' + w_k^2 s = q_k xi(t)`` with white ``xi`` and ``q_k = 2 sigma_k w_k^(3/2)``,
  so that ``Var s_k = sigma_k^2`` and ``PSD_k(f) ~ 1/(1 + (f/f_k)^2)^2`` (corner ``f_k = w_k/2pi``).
  Paths are smooth (differentiable), as atmospheric beam wander is after aperture averaging.
- The component variances follow a power law, ``sigma_k^2 ~ f_k^(1 - alpha)``: the summed
  spectrum then has the envelope ``PSD(f) ~ f^(-alpha)`` between the corners and falls as
  ``f^-4`` above the highest one. The default ``alpha = 2/3`` is the low-frequency slope of the
  Kolmogorov tilt spectrum (Tyler 1994); above the tilt corner real spectra fall as
  ``f^(-11/3)``..``f^(-17/3)``, bracketing the model's ``f^-4``.
- Or (``rolloff="G-tilt"``) Tyler's G-tilt spectrum of a centroid through Kolmogorov turbulence in frozen
  flow (:func:`gtilt_shape`): ``f^(-2/3)`` below the corner ``~ v/D`` and ``f^(-11/3)`` above it, drawn by
  spectral synthesis with the frame's exposure applied exactly (``sinc^2(pi f tau)``, :func:`.gtilt.exposure_gain`)
  and folded at the frame rate.
- ``v_d``: a slow linear drift (mount or alignment), uniform direction, speed uniform in
  ``[0, drift_max]``, centred on the middle of the trace.
- Total intensity (scintillation): i.i.d. log-normal per frame, ``ln I ~ N(-s^2/2, s^2)`` (mean 1,
  scintillation index ``exp(s^2) - 1``): the whole spot fades, its shape kept (no speckle inside it).

Each path draws its own total wander RMS per axis, log-uniform in ``[rms_min, rms_max]`` (the
paper's 15 "laser paths" were different recordings), split over the components as above.
The processes are sampled exactly at the frame interval (matrix exponential and Van Loan's
integral for the discrete process noise), so no discretisation error depends on the frame rate.

The camera that images the paths (:class:`SpotCamera`, :func:`track_spot`) is :mod:`.camera`.

Command line (writes the data set shipped in ``data/laser_traces``)::

    python -m tvtrack.papers.p004_laser_spot_prediction.beam_wander --out data/laser_traces --seed 20050110
"""

from __future__ import annotations

import argparse
import json
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np
from scipy.linalg import block_diag, expm
from scipy.signal import lfilter

from .kalman_baselines import kalman_forecast
from .traces import TraceSet, save_traces, sha256_file
from .gtilt import GTILT, gtilt_wander, gtilt_frame_step_rms

__all__ = [
    "BeamWanderConfig",
    "scaled_config",
    "component_sigmas",
    "component_table",
    "one_frame_motion_rms",
    "gauss_markov_discrete",
    "GTILT",
    "generate_traces",
    "wander_state_space",
    "optimal_wander_forecast",
]

#: The generator's name as the shipped data set records it (``metadata["generator"]``). The module has
#: since moved into the paper package; the recorded name stays so that regenerating the data set with
#: ``python -m tvtrack.papers.p004_laser_spot_prediction.beam_wander`` writes the same metadata (the
#: arrays agree to the last bits the machine's floating point allows; ``tests/papers/test_004_traces.py``).
GENERATOR_RECORDED_NAME = "tvtrack.scenes.beam_wander.generate_traces"

#: The smooth side of the tilt range: the critically damped sum through one more real pole at the fastest corner.
SMOOTH = "f^-6"
#: The wander spectra the generator draws.
ROLLOFFS = ("f^-4", "f^-2", SMOOTH, GTILT)


@dataclass(frozen=True)
class BeamWanderConfig:
    """Parameters of the beam-wander generator (units in the names).

    Attributes
    ----------
    n_paths : int
        Number of independent traces (default 15, as the paper's data base).
    n_frames : int
        Frames per trace (default 1000).
    frame_rate_hz : float
        Camera frame rate, frames/s (default 25, the paper's).
    image_size_px : int
        Side of the square sensor, px (default 128, the paper's).
    corner_frequencies_hz : tuple of float
        Corner frequency ``f_k`` of each Gauss-Markov component, Hz (default 0.02, 0.1, 0.5:
        0.5 Hz (this project's choice) as the fastest, with slower wander a factor 5 and 25 below it; the
        trace length, 40 s, is about one period of the slowest).
    spectral_index : float
        ``alpha`` of the spectral envelope ``PSD ~ f^-alpha`` between the corners (default 2/3).
    rms_min_px, rms_max_px : float
        Range of the per-path total wander RMS per axis, px, drawn log-uniformly
        (default 3..8 px around 5 px, this project's choice).
    drift_max_px_per_frame : float
        Largest drift speed, px/frame (default 0.02, i.e. <= 20 px over 1000 frames).
    scintillation_sigma_ln : float
        Standard deviation of ln(total intensity) (default 0.3, this project's choice).
    aliased_corners : bool
        Allow corners at or above the Nyquist frequency ``frame_rate_hz / 2`` (default False). The
        exact discretisation holds for any corner; such a component is nearly uncorrelated from
        frame to frame (aliased fast tilt). Recorded in the metadata only when True, so data sets
        made before the option existed regenerate byte for byte.
    rolloff : {"f^-4", "f^-2", "f^-6", "G-tilt"}
        Spectrum of each component above its corner (default ``"f^-4"``): a critically damped
        second-order Gauss-Markov process (smooth paths with a velocity), or a first-order one
        (Ornstein-Uhlenbeck, PSD ``~ 1 / (1 + (f/f_k)^2)``: continuous paths without a velocity).
        ``"f^-6"``: the critically damped sum passed through one more real pole at the fastest corner
        (the discrete one-pole low-pass ``y_t = b y_(t-1) + (1 - b) x_t``, ``b = exp(-2 pi f_max / fs)``,
        started at the first sample), so the spectrum falls as ``f^-6`` above it: the smooth side of the
        tilt range (Tyler's G-tilt falls as ``f^-17/3``; proposed in ``docs/validity/004.md``). The
        low-pass takes some variance from the fastest component; the generator's state-space model
        (:func:`wander_state_space`) omits the pole, so the "optimal" forecast is model-based, no bound.
        ``"G-tilt"`` replaces the whole sum by Tyler's G-tilt spectrum (:func:`gtilt_psd`): its
        asymptotes cross at the highest corner, ``spectral_index`` and the other corners are unused.
        Recorded in the metadata only when not the default, like ``aliased_corners``.
    exposure_s, field_offset_s : float
        Exposure of each frame, s, used by the ``"G-tilt"`` spectrum only (default 0: instant): the
        frame's centre is the path's mean over ``exposure_s`` (the spectrum times
        ``sinc^2(pi f exposure_s)``), and, with ``field_offset_s > 0``, the mean of two such fields
        ``field_offset_s`` apart (an interlaced camera; times ``cos^2(pi f field_offset_s)``).
        Recorded in the metadata only when not 0.
    """

    n_paths: int = 15
    n_frames: int = 1000
    frame_rate_hz: float = 25.0
    image_size_px: int = 128
    corner_frequencies_hz: tuple = (0.02, 0.1, 0.5)
    spectral_index: float = 2.0 / 3.0
    rms_min_px: float = 3.0
    rms_max_px: float = 8.0
    drift_max_px_per_frame: float = 0.02
    scintillation_sigma_ln: float = 0.3
    aliased_corners: bool = False
    rolloff: str = "f^-4"
    exposure_s: float = 0.0
    field_offset_s: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "corner_frequencies_hz", tuple(float(f) for f in self.corner_frequencies_hz))
        checks = [
            ("n_paths", self.n_paths, self.n_paths >= 1, ">= 1"),
            ("n_frames", self.n_frames, self.n_frames >= 2, ">= 2"),
            ("frame_rate_hz", self.frame_rate_hz, self.frame_rate_hz > 0, "> 0"),
            ("image_size_px", self.image_size_px, self.image_size_px >= 8, ">= 8"),
            (
                "corner_frequencies_hz",
                self.corner_frequencies_hz,
                len(self.corner_frequencies_hz) >= 1
                and all(
                    0 < f and (self.aliased_corners or f < self.frame_rate_hz / 2) for f in self.corner_frequencies_hz
                ),
                "a non-empty list of values in (0, frame_rate_hz/2) (any value > 0 with aliased_corners=True)",
            ),
            ("spectral_index", self.spectral_index, -2.0 <= self.spectral_index <= 4.0, "in [-2, 4]"),
            ("rms_min_px", self.rms_min_px, 0 <= self.rms_min_px <= self.rms_max_px, "in [0, rms_max_px]"),
            (
                "rms_max_px",
                self.rms_max_px,
                self.rms_max_px <= self.image_size_px / 6,
                f"<= image_size_px/6 = {self.image_size_px / 6:g}",
            ),
            (
                "drift_max_px_per_frame",
                self.drift_max_px_per_frame,
                0 <= self.drift_max_px_per_frame * self.n_frames <= self.image_size_px / 4,
                f"in [0, image_size_px/(4 n_frames)] = [0, {self.image_size_px / 4 / self.n_frames:g}]",
            ),
            ("scintillation_sigma_ln", self.scintillation_sigma_ln, 0 <= self.scintillation_sigma_ln <= 2, "in [0, 2]"),
            ("rolloff", self.rolloff, self.rolloff in ROLLOFFS, f"one of {ROLLOFFS}"),
            ("exposure_s", self.exposure_s, self.exposure_s >= 0, ">= 0"),
            ("field_offset_s", self.field_offset_s, self.field_offset_s >= 0, ">= 0"),
        ]
        for name, value, ok, allowed in checks:
            if not ok:
                raise ValueError(f"parameter {name!r} = {value!r}; it must be {allowed}")


def scaled_config(
    config: BeamWanderConfig, wander_scale: float = 1.0, bandwidth_scale: float = 1.0
) -> BeamWanderConfig:
    """``config`` with the wander RMS range multiplied by ``wander_scale`` and every corner
    frequency by ``bandwidth_scale`` (with the same seed, the same paths, louder or faster)."""
    if not (wander_scale > 0 and bandwidth_scale > 0):
        raise ValueError(
            f"parameters 'wander_scale' = {wander_scale!r} and 'bandwidth_scale' = "
            f"{bandwidth_scale!r}; both must be > 0"
        )
    return replace(
        config,
        rms_min_px=config.rms_min_px * wander_scale,
        rms_max_px=config.rms_max_px * wander_scale,
        corner_frequencies_hz=tuple(f * bandwidth_scale for f in config.corner_frequencies_hz),
    )


def component_sigmas(config: BeamWanderConfig, rms_px) -> np.ndarray:
    """RMS of each Gauss-Markov component for a total RMS ``rms_px`` (per axis).

    ``sigma_k^2 = rms^2 w_k / sum w``, ``w_k = f_k^(1-alpha)`` (envelope ``PSD ~ f^-alpha``).

    Returns
    -------
    ndarray, shape (..., K), px
    """
    f = np.asarray(config.corner_frequencies_hz)
    w = f ** (1.0 - config.spectral_index)
    return np.asarray(rms_px, dtype=float)[..., None] * np.sqrt(w / w.sum())


def component_table(config: BeamWanderConfig) -> list[dict]:
    """Spectrum and variance share of each wander component, for data sheets.

    Component ``k`` has the one-sided PSD ``S_k(f) = (4 sigma_k^2 / (pi f_k)) / (1 + (f/f_k)^2)^2``
    (px^2/Hz; it integrates to ``sigma_k^2``) and the autocorrelation
    ``rho_k(tau) = (1 + w_k tau) exp(-w_k tau)``.

    Returns
    -------
    list of dict
        Per component: ``corner_hz``, ``variance_share`` (of the total wander variance),
        ``frame_correlation`` (``rho_k`` at one frame).
    """
    f = np.asarray(config.corner_frequencies_hz)
    share = component_sigmas(config, 1.0) ** 2
    wt = 2 * np.pi * f / config.frame_rate_hz
    rho = np.exp(-wt) if config.rolloff == "f^-2" else (1 + wt) * np.exp(-wt)
    return [
        {"corner_hz": float(fk), "variance_share": float(sk), "frame_correlation": float(rk)}
        for fk, sk, rk in zip(f, share, rho)
    ]


def one_frame_motion_rms(config: BeamWanderConfig, rms_px) -> np.ndarray:
    """RMS per axis of the wander's change over one frame, ``sqrt(sum_k 2 sigma_k^2 (1 - rho_k(dt)))``
    (stationary part; the drift adds at most ``drift_max_px_per_frame``), px.

    Parameters
    ----------
    rms_px : array_like, shape (...)
        Total wander RMS per axis.

    Returns
    -------
    ndarray, shape (...)
    """
    if config.rolloff == GTILT:
        return gtilt_frame_step_rms(config) * np.asarray(rms_px, dtype=float)
    sig = component_sigmas(config, rms_px)
    rho = np.array([c["frame_correlation"] for c in component_table(config)])
    return np.sqrt(np.sum(2 * sig**2 * (1 - rho), axis=-1))


def gauss_markov_discrete(omega, sigma, dt: float, order: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """Exact discrete model of critically damped Gauss-Markov processes.

    State ``(s, s')``; continuous ``A = [[0, 1], [-w^2, -2w]]``, noise input ``(0, q)``,
    ``q = 2 sigma w^(3/2)``.

    Parameters
    ----------
    omega : array_like, shape (K,)
        Angular corner frequencies, rad/s.
    sigma : array_like, shape (..., K)
        Stationary RMS of ``s``, px.
    dt : float
        Sampling interval, s.
    order : {2, 1}
        2: critically damped (PSD ``~ f^-4`` above the corner); 1: Ornstein-Uhlenbeck in ``s``
        (``s' = -w s + noise``, PSD ``~ f^-2``), the second state held at 0.

    Returns
    -------
    Phi : ndarray, shape (K, 2, 2)
        Transition over ``dt``.
    Qd : ndarray, shape (..., K, 2, 2)
        Discrete process-noise covariance, px^2 and (px/s)^2 (Van Loan 1978).
    """
    omega = np.asarray(omega, dtype=float)
    sigma = np.asarray(sigma, dtype=float)
    if order == 1:  # Ornstein-Uhlenbeck in the first state; the second state stays 0
        a = np.exp(-omega * dt)
        Phi = np.zeros(omega.shape + (2, 2))
        Phi[:, 0, 0] = a
        Qd = np.zeros(sigma.shape + (2, 2))
        Qd[..., 0, 0] = sigma**2 * (1 - a**2)
        return Phi, Qd
    Phi = np.empty(omega.shape + (2, 2))
    Q1 = np.empty(omega.shape + (2, 2))  # for q = 1
    for k, w in enumerate(omega):
        A = np.array([[0.0, 1.0], [-w * w, -2.0 * w]])
        G = np.array([[0.0, 0.0], [0.0, 1.0]])
        vl = expm(np.block([[-A, G], [np.zeros((2, 2)), A.T]]) * dt)  # Van Loan
        Phi[k] = vl[2:, 2:].T
        Q1[k] = Phi[k] @ vl[:2, 2:]
        Q1[k] = 0.5 * (Q1[k] + Q1[k].T)
    q2 = (2.0 * sigma * omega**1.5) ** 2
    return Phi, q2[..., None, None] * Q1


def _stationary_cov(omega, sigma, order: int = 2) -> np.ndarray:
    """Stationary covariance ``diag(sigma^2, sigma^2 w^2)`` of ``(s, s')``, shape (..., K, 2, 2)."""
    omega = np.asarray(omega, dtype=float)
    sigma = np.asarray(sigma, dtype=float)
    P = np.zeros(sigma.shape + (2, 2))
    P[..., 0, 0] = sigma**2
    P[..., 1, 1] = 0.0 if order == 1 else (sigma * omega) ** 2
    return P


def generate_traces(config: BeamWanderConfig = BeamWanderConfig(), seed: int = 0) -> TraceSet:
    """Draw ``config.n_paths`` beam-wander traces.

    The draws come from ``numpy.random.default_rng(seed)`` in a fixed order (per-path RMS,
    drift, initial states, process noise, scintillation), so a seed gives the same traces on
    every machine.

    Returns
    -------
    TraceSet
        ``centres_px`` (n_paths, n_frames, 2) and ``intensity`` (n_paths, n_frames); metadata
        holds the config, the seed and the per-path draws (``wander_rms_px`` (n_paths,),
        ``drift_px_per_frame`` (n_paths, 2)).
    """
    if not (isinstance(seed, (int, np.integer)) and seed >= 0):
        raise ValueError(f"parameter 'seed' = {seed!r}; it must be an integer >= 0")
    c = config
    rng = np.random.default_rng(seed)
    P, T = c.n_paths, c.n_frames
    dt = 1.0 / c.frame_rate_hz
    omega = 2 * np.pi * np.asarray(c.corner_frequencies_hz)
    K = omega.size
    rms = np.exp(rng.uniform(np.log(max(c.rms_min_px, 1e-12)), np.log(max(c.rms_max_px, 1e-12)), size=P))
    if c.rms_max_px == 0:
        rms[:] = 0.0
    speed = c.drift_max_px_per_frame * rng.uniform(0.0, 1.0, size=P)
    angle = rng.uniform(0.0, 2 * np.pi, size=P)
    drift = speed[:, None] * np.stack([np.cos(angle), np.sin(angle)], axis=-1)  # (P, 2) px/frame
    if c.rolloff == GTILT:
        wander = gtilt_wander(c, rms, rng)
    else:
        sig = component_sigmas(c, rms)  # (P, K)
        order = 1 if c.rolloff == "f^-2" else 2
        Phi, Qd = gauss_markov_discrete(omega, sig, dt, order)  # (K,2,2), (P,K,2,2)
        L0 = np.linalg.cholesky(_stationary_cov(omega, sig, order) + 1e-300 * np.eye(2))  # (P,K,2,2)
        Lq = np.linalg.cholesky(Qd + 1e-300 * np.eye(2))
        s = np.einsum("pkij,pakj->pakj", L0, rng.standard_normal((P, 2, K, 2)))  # (P, axis, K, 2)
        noise = rng.standard_normal((T, P, 2, K, 2))
        wander = np.empty((P, T, 2))
        for t in range(T):
            if t > 0:
                s = np.einsum("kij,pakj->paki", Phi, s) + np.einsum("pkij,pakj->paki", Lq, noise[t])
            wander[:, t, :] = s[..., 0].sum(axis=-1)
        if c.rolloff == SMOOTH:  # one more pole at the fastest corner (no draw: common random numbers)
            b = float(np.exp(-omega.max() * dt))
            wander = lfilter([1.0 - b], [1.0, -b], wander, axis=1, zi=b * wander[:, :1])[0]
    centre = (c.image_size_px - 1) / 2.0
    t_rel = np.arange(T) - (T - 1) / 2.0
    centres = centre + drift[:, None, :] * t_rel[None, :, None] + wander
    sl = c.scintillation_sigma_ln
    intensity = np.exp(rng.normal(-0.5 * sl * sl, sl, size=(P, T)))
    cfg = asdict(c)
    cfg["corner_frequencies_hz"] = list(c.corner_frequencies_hz)
    if not c.aliased_corners:
        del cfg["aliased_corners"]
    if c.rolloff == "f^-4":
        del cfg["rolloff"]
    for name in ("exposure_s", "field_offset_s"):
        if cfg[name] == 0:
            del cfg[name]
    metadata = {
        "generator": GENERATOR_RECORDED_NAME,
        "config": cfg,
        "seed": int(seed),
        "wander_rms_px": rms.tolist(),
        "drift_px_per_frame": drift.tolist(),
        "units": {
            "centres_px": "px (pixel centres at integers; x = column, y = row)",
            "intensity": "dimensionless total-intensity factor, mean 1",
        },
    }
    return TraceSet(centres, intensity, c.frame_rate_hz, c.image_size_px, metadata)


def wander_state_space(config: BeamWanderConfig, rms_px, drift_prior_px_per_frame: float | None = None):
    """Per-axis linear-Gaussian model of the generator, for the optimal (Kalman) predictor.

    The ``"G-tilt"`` spectrum has no finite state: there the model is the default (``f^-4``) sum of
    components at the same corners, a mismatched model, so its forecast is no bound.

    State ``(s_1, s_1', ..., s_K, s_K', offset, drift)``; ``offset`` = centre of the path at the
    current frame without wander (``c0 + v_d (t - t_mid)``), ``drift`` in px/frame. Time step =
    one frame; derivatives ``s_k'`` in px/s.

    Parameters
    ----------
    config : BeamWanderConfig
    rms_px : array_like, shape (P,)
        Total wander RMS of each path (the generator's per-path draws).
    drift_prior_px_per_frame : float, optional
        Prior RMS of the drift speed per axis (default ``drift_max/sqrt(3)``).

    Returns
    -------
    F : ndarray, shape (n, n)
    Q : ndarray, shape (P, n, n)
    H : ndarray, shape (1, n)
    P0 : ndarray, shape (P, n, n)
        Stationary prior of the wander, diffuse (100^2 px^2) offset, drift prior.
    """
    c = config
    dt = 1.0 / c.frame_rate_hz
    omega = 2 * np.pi * np.asarray(c.corner_frequencies_hz)
    sig = component_sigmas(c, rms_px)
    order = 1 if c.rolloff == "f^-2" else 2
    Phi, Qd = gauss_markov_discrete(omega, sig, dt, order)
    Pst = _stationary_cov(omega, sig, order)
    K = omega.size
    n = 2 * K + 2
    F = block_diag(*Phi, np.array([[1.0, 1.0], [0.0, 1.0]]))
    npath = sig.shape[0]
    Q = np.zeros((npath, n, n))
    P0 = np.zeros((npath, n, n))
    for k in range(K):
        Q[:, 2 * k : 2 * k + 2, 2 * k : 2 * k + 2] = Qd[:, k]
        P0[:, 2 * k : 2 * k + 2, 2 * k : 2 * k + 2] = Pst[:, k]
    d = c.drift_max_px_per_frame / np.sqrt(3.0) if drift_prior_px_per_frame is None else drift_prior_px_per_frame
    P0[:, -2, -2] = 100.0**2
    P0[:, -1, -1] = max(d, 1e-9) ** 2
    H = np.zeros((1, n))
    H[0, 0 : 2 * K : 2] = 1.0
    H[0, -2] = 1.0
    return F, Q, H, P0


def optimal_wander_forecast(z, config: BeamWanderConfig, rms_px, meas_var: float, steps: int = 1) -> np.ndarray:
    """Kalman ``steps``-ahead forecast with the generator's own model (:func:`wander_state_space`,
    known per-path RMS) and white measurement noise: the optimal linear predictor, a lower bound
    for every method on these traces.

    Parameters
    ----------
    z : ndarray, shape (..., P, A, T)
        Complete measured series of ``P`` paths, ``A`` axes each, px.
    rms_px : array_like, shape (P,)
        Wander RMS of each path, px.
    meas_var : float or array_like, shape (P,)
        White measurement noise variance per axis, px^2 (per path: e.g. centroid noise plus a
        path's frame jitter).

    Returns
    -------
    ndarray, shape like ``z``
    """
    F, Q, H, P0 = wander_state_space(config, rms_px)
    x0 = np.zeros(F.shape[0])
    x0[-2] = (config.image_size_px - 1) / 2.0
    R = np.broadcast_to(np.asarray(meas_var, dtype=float), (Q.shape[0],))[:, None, None, None]
    return kalman_forecast(z, F, Q[:, None], H, R, x0, P0[:, None], steps)[0]


def main(argv=None) -> int:
    """Write a trace data set: ``traces.npz`` plus ``checksums.sha256``."""
    ap = argparse.ArgumentParser(
        prog="python -m tvtrack.papers.p004_laser_spot_prediction.beam_wander",
        description="Generate synthetic laser beam-wander traces (true centres).",
    )
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--seed", type=int, required=True, help="random seed (integer >= 0)")
    d = BeamWanderConfig()
    ap.add_argument("--n-paths", type=int, default=d.n_paths)
    ap.add_argument("--n-frames", type=int, default=d.n_frames)
    ap.add_argument("--frame-rate-hz", type=float, default=d.frame_rate_hz)
    ap.add_argument("--image-size-px", type=int, default=d.image_size_px)
    ap.add_argument("--corner-frequencies-hz", type=float, nargs="+", default=list(d.corner_frequencies_hz))
    ap.add_argument("--spectral-index", type=float, default=d.spectral_index)
    ap.add_argument("--rms-min-px", type=float, default=d.rms_min_px)
    ap.add_argument("--rms-max-px", type=float, default=d.rms_max_px)
    ap.add_argument("--drift-max-px-per-frame", type=float, default=d.drift_max_px_per_frame)
    ap.add_argument("--scintillation-sigma-ln", type=float, default=d.scintillation_sigma_ln)
    a = ap.parse_args(argv)
    cfg = BeamWanderConfig(
        a.n_paths,
        a.n_frames,
        a.frame_rate_hz,
        a.image_size_px,
        tuple(a.corner_frequencies_hz),
        a.spectral_index,
        a.rms_min_px,
        a.rms_max_px,
        a.drift_max_px_per_frame,
        a.scintillation_sigma_ln,
    )
    traces = generate_traces(cfg, a.seed)
    out = Path(a.out)
    path = save_traces(out / "traces.npz", traces)
    (out / "checksums.sha256").write_text(f"{sha256_file(path)}  {path.name}\n")
    print(
        json.dumps(
            {"file": str(path), "sha256": sha256_file(path), "n_paths": cfg.n_paths, "n_frames": cfg.n_frames}, indent=1
        )
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
