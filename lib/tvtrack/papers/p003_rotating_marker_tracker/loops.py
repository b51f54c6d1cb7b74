"""Closed-loop trackers of Yukhno 2025: the five-state rotating-marker tracker, its discrete EKF
form, and the 1-D two-emitter tracker.

Five-state tracker (eq. (16) with diagonal gains, "chosen by classical automatic-control
methods"; the gain rule is this project's choice). With normalised discriminator outputs
``eps_x = Delta_x / S``, ``eps_y = Delta_y / S``, ``eps_r = e_r / S``, ``eps_th = e_th / (S r_hat)``
(``S`` = discriminator slope, e.g. ``2 d D`` for the quadrant form), per frame of length ``dt``::

    x_r += dt K_xy eps_x          y_r += dt K_xy eps_y          r += dt K_r eps_r
    variant "S" (phase state, type-2 PLL):   th += dt (om + K1 eps_th),   om += dt K2 eps_th
    variant "P" (literal (16), (27), (28)):  phi += dt K_phi eps_th,  om += dt K_om tau eps_th,
                                             th = om tau + phi, tau re-referenced every revolution

``K = 2 pi B`` for the first-order loops (closed-loop -3 dB bandwidth ``B``); the PLL has
``K1 = 2 zeta w_n``, ``K2 = w_n^2``, ``w_n = 2 pi B_om / sqrt(1 + 2 zeta^2 + sqrt((1 + 2 zeta^2)^2 + 1))``.
Everything is batched over a leading trials axis.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from .discriminators import (
    centroid_discriminator,
    edge_discriminator,
    polar_errors,
    quadrant_noise,
    quadrant_weights,
    two_emitter_discriminator,
)
from ...measure import gate_crop_size
from ...render import pixel_fractions_box

__all__ = [
    "LoopGains",
    "loop_gains",
    "RotatingGateTracker",
    "TrackHistory",
    "run_closed_loop",
    "discriminate",
    "loop_poles",
    "phase_response",
    "realised_phase_bandwidth",
    "gains_realising",
    "stack_gains",
    "simulate_two_emitter_1d",
    "phase_locked_amplitude",
    "omega_response",
    "omega_bandwidth",
]

VARIANTS = ("S", "P")


@dataclass(frozen=True)
class LoopGains:
    """Loop gains (1/s): ``k_xy``, ``k_r``; PLL ``k1``, ``k2`` (variant S); ``k_phi``, ``k_om``
    (variant P, ``k_om`` in 1/s^3)."""

    k_xy: float
    k_r: float
    k1: float
    k2: float
    k_phi: float
    k_om: float


def stack_gains(gains, n_each: int) -> LoopGains:
    """Per-trial gains: each of ``gains`` repeated for ``n_each`` consecutive trials (fields of shape (k n_each,))."""
    return LoopGains(
        *(
            np.repeat([getattr(g, f) for g in gains], n_each).astype(float)
            for f in ("k_xy", "k_r", "k1", "k2", "k_phi", "k_om")
        )
    )


def loop_gains(
    b_xy: float = 10.0, b_r: float = 0.2, b_omega: float = 6.0, zeta: float = 0.707, rotation_hz: float = 8.0
) -> LoopGains:
    """Gains from closed-loop -3 dB bandwidths (Hz): 10 / 0.2 / 6 Hz in the paper.

    Variant P uses ``k_phi = 2 pi B_om`` and ``k_om = k_phi / T_rot^2`` (this project's choice; not from the paper).
    """
    for name, v in (("b_xy", b_xy), ("b_r", b_r), ("b_omega", b_omega), ("zeta", zeta), ("rotation_hz", rotation_hz)):
        if not v > 0:
            raise ValueError(f"parameter '{name}' = {v}; it must be > 0")
    z2 = 1 + 2 * zeta**2
    wn = 2 * np.pi * b_omega / np.sqrt(z2 + np.sqrt(z2**2 + 1))
    k_phi = 2 * np.pi * b_omega
    return LoopGains(2 * np.pi * b_xy, 2 * np.pi * b_r, 2 * zeta * wn, wn**2, k_phi, k_phi * rotation_hz**2)


class RotatingGateTracker:
    """Batched five-state loop tracker ``(x_r, y_r, r, theta/phi, omega)``.

    Parameters
    ----------
    x0 : ndarray, shape (n, 5)
        Initial estimates ``(x_r, y_r, r, theta_0, omega)`` (px, px, px, rad, rad/s).
    gains : LoopGains
    slope : float
        Discriminator slope ``S`` (output per px of marker offset).
    variant : {"S", "P"}
    rotating : bool
        False: static (non-modulated) marker baseline; the gate sits on ``(x_r, y_r)`` and only
        the coordinate loops run.
    """

    def __init__(self, x0, gains: LoopGains, slope: float, variant: str = "S", rotating: bool = True):
        if variant not in VARIANTS:
            raise ValueError(f"parameter 'variant' = {variant!r}; it must be one of {VARIANTS}")
        if not slope > 0:
            raise ValueError(f"parameter 'slope' = {slope}; it must be > 0")
        self.state = np.array(x0, dtype=float, copy=True)
        if self.state.ndim != 2 or self.state.shape[1] != 5:
            raise ValueError(f"parameter 'x0' has shape {self.state.shape}; it must be (n, 5)")
        self.g, self.slope, self.variant, self.rotating = gains, float(slope), variant, rotating
        self.phi = self.state[:, 3].copy()  # variant P: phase at the reference time
        self.tau = 0.0  # variant P: time since the reference

    def gate_center(self) -> np.ndarray:
        """Predicted marker position (eq. (8) with the estimates), shape (n, 2)."""
        s = self.state
        if not self.rotating:
            return s[:, :2].copy()
        return np.stack([s[:, 0] + s[:, 2] * np.cos(s[:, 3]), s[:, 1] + s[:, 2] * np.sin(s[:, 3])], axis=1)

    def update(self, dx, dy, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """One frame of the loops from the Cartesian discriminator outputs; returns ``(e_r, e_th)``."""
        s, g, S = self.state, self.g, self.slope
        s[:, 0] += dt * g.k_xy * dx / S
        s[:, 1] += dt * g.k_xy * dy / S
        if not self.rotating:
            return np.zeros_like(dx), np.zeros_like(dx)
        e_r, e_th = polar_errors(dx, dy, s[:, 3])  # corrected (26)-(28)
        eps_th = e_th / (S * np.maximum(s[:, 2], 1.0))
        s[:, 2] += dt * g.k_r * e_r / S
        if self.variant == "S":
            s[:, 3] += dt * (s[:, 4] + g.k1 * eps_th)
            s[:, 4] += dt * g.k2 * eps_th
        else:
            self.phi += dt * g.k_phi * eps_th  # (28): dPi/dphi = r e_th
            s[:, 4] += dt * g.k_om * self.tau * eps_th  # (27): dPi/domega = r t e_th
            self.tau += dt
            period = 2 * np.pi / max(float(np.mean(np.abs(s[:, 4]))), 1e-9)
            if self.tau >= period:  # re-reference the time origin
                self.phi += s[:, 4] * self.tau
                self.tau = 0.0
            s[:, 3] = self.phi + s[:, 4] * self.tau
        return e_r, e_th


@dataclass
class TrackHistory:
    """Per-frame histories of a closed-loop run (trials first).

    Attributes
    ----------
    estimate : (n, T, 5) float32 or None, state estimates used for frame k's gate.
    gate : (n, T, 2) float32, gate centres.
    disc : (n, T, 4) float32 or None, ``(Delta_x, Delta_y, e_r, e_th)`` normalised by ``S`` (px).
    miss : (n, T) float32, marker miss distance ``|gate - marker|`` (px).
    inside : (n, T) bool, gate centre inside the image.
    omega : (n, T) float32, the angular-velocity estimate used for frame k (rad/s); kept even
        without ``keep_full``, since it is what a tracker can watch for its own loss of lock.
    """

    estimate: np.ndarray | None
    gate: np.ndarray
    disc: np.ndarray | None
    miss: np.ndarray
    inside: np.ndarray
    omega: np.ndarray


def run_closed_loop(
    scene,
    tracker: RotatingGateTracker,
    rng: np.random.Generator | None,
    *,
    gate_half: float,
    form: str = "quadrant",
    edge_a: float | None = None,
    noise: str = "pixel",
    keep_full: bool = True,
    crop_callback=None,
) -> TrackHistory:
    """Render gate crops, discriminate and update the loops frame by frame (batched over trials).

    Parameters
    ----------
    scene : tvtrack.papers.p003_rotating_marker_tracker.scene.RotatingMarkerScene
    tracker : RotatingGateTracker or EKFTracker
        Anything with ``state`` (n, 5), ``slope``, ``gate_center()`` and ``update(dx, dy, dt)``.
    rng : numpy.random.Generator or None
        Sensor-noise generator (None: noise-free).
    gate_half : float
        Gate half-size ``A`` (px).
    form : {"quadrant", "edge", "centroid"}
    edge_a : float, optional
        Edge-form half-width (spot half-size).
    noise : {"pixel", "projected"}
        ``"pixel"`` adds white noise to every crop pixel; ``"projected"`` (quadrant form only)
        draws its exact effect on ``(Delta_x, Delta_y)`` instead (:func:`quadrant_noise`), two
        draws per gate: the same distribution of discriminator outputs, much faster. The crops
        passed to ``crop_callback`` are then noise-free.
    keep_full : bool
        Keep estimates and discriminator outputs (memory ``n T 9`` floats); else only gate, miss.
    crop_callback : callable, optional
        ``f(k, crops, origin)`` called each frame (e.g. to record trial 0's gate crop).
    """
    if form not in ("quadrant", "edge", "centroid"):
        raise ValueError(f"parameter 'form' = {form!r}; it must be 'quadrant', 'edge' or 'centroid'")
    if noise not in ("pixel", "projected") or (noise == "projected" and form != "quadrant"):
        raise ValueError(f"parameter 'noise' = {noise!r}; it must be 'pixel', or 'projected' with the quadrant form")
    n, T = scene.n, scene.truth.n_frames
    dt = float(scene.truth.t[1] - scene.truth.t[0]) if T > 1 else 1.0
    size = gate_crop_size(max(edge_a or 0.0, gate_half) if form == "edge" else gate_half)
    est = np.empty((n, T, 5), np.float32) if keep_full else None
    disc = np.empty((n, T, 4), np.float32) if keep_full else None
    gate = np.empty((n, T, 2), np.float32)
    inside = np.empty((n, T), bool)
    omega = np.empty((n, T), np.float32)
    for k in range(T):
        c = tracker.gate_center()
        omega[:, k] = tracker.state[:, 4]
        if keep_full:
            est[:, k] = tracker.state
        dx, dy, inside[:, k] = discriminate(scene, k, c, size, gate_half, form, edge_a, noise, rng, crop_callback)
        e_r, e_th = tracker.update(dx, dy, dt)
        gate[:, k] = c
        if keep_full:
            disc[:, k] = np.stack([dx, dy, e_r, e_th], axis=1) / tracker.slope
    miss = np.linalg.norm(gate - scene.truth.marker, axis=-1).astype(np.float32)
    return TrackHistory(est, gate, disc, miss, inside, omega)


def discriminate(
    scene, k: int, c, size: int, gate_half: float, form: str, edge_a, noise: str, rng, crop_callback=None, trials=None
):
    """One frame of :func:`run_closed_loop` before the loop update: the gate crops of frame ``k`` at the gate centres
    ``c`` (n, 2) px (of the scene's ``trials``, default all), read by the discriminator ``form``, with the sensor noise
    of ``noise`` drawn from ``rng``.

    Returns
    -------
    dx, dy : ndarray, shape (n,)
        Cartesian discriminator outputs.
    inside : ndarray of bool, shape (n,)
        Whether each gate centre is inside the image.
    """
    crops, origin, inside = scene.gate_crops(k, c, size, rng if noise == "pixel" else None, trials)
    if crop_callback is not None:
        crop_callback(k, crops, origin)
    if form == "quadrant":
        wy, wx = quadrant_weights(origin, c, gate_half, (size, size), np.float32)
        m = wy @ (crops @ wx)
        dx, dy = m[:, 0, 1].astype(float), m[:, 1, 0].astype(float)
        if noise == "projected" and rng is not None and scene.noise_std > 0:
            w = quadrant_noise(wy, wx, scene.noise_std, rng)
            dx, dy = dx + w[:, 0], dy + w[:, 1]
    elif form == "centroid":
        dx, dy = centroid_discriminator(crops, origin, c, gate_half)
    else:
        dx, dy = edge_discriminator(crops, origin, c, edge_a)
    return dx, dy, inside


def loop_poles(gains: LoopGains, omega: float, r: float) -> np.ndarray:
    """Closed-loop poles (1/s) of the linearised variant-S loop for a uniform rotation.

    In the frame rotating with the marker the error dynamics are time-invariant. With
    ``q = R(-theta) (x_r err, y_r err)`` and marker error ``e = q + (dr, r dtheta)`` (radial,
    tangential), the linear discriminator gives ``eps = -e``; the states
    ``(q_rad, q_tan, dr, dtheta, domega)`` obey ``d/dt = A (...)`` with the rotation ``-omega J``
    acting on ``q``.

    Returns
    -------
    ndarray of complex, shape (5,)
    """
    A = _loop_matrix(gains, omega, r)
    return np.linalg.eigvals(A)


def _loop_matrix(gains: LoopGains, omega: float, r: float) -> np.ndarray:
    """State matrix of :func:`loop_poles` (errors ``q_rad, q_tan, dr, dtheta, domega``)."""
    g = gains
    A = np.zeros((5, 5))
    A[0, :] = [-g.k_xy, omega, -g.k_xy, 0, 0]
    A[1, :] = [-omega, -g.k_xy, 0, -g.k_xy * r, 0]
    A[2, :] = [-g.k_r, 0, -g.k_r, 0, 0]
    A[3, :] = [0, -g.k1 / r, 0, -g.k1, 1]
    A[4, :] = [0, -g.k2 / r, 0, -g.k2, 0]
    return A


def phase_response(gains: LoopGains, omega: float, r: float, freqs_hz) -> np.ndarray:
    """Frequency response of the coupled variant-S loop from the true marker phase to its estimate.

    With a phase perturbation ``p(t)`` of the uniform rotation (true phase ``theta_0 + omega t + p``),
    the error state of :func:`loop_poles` obeys ``x' = A x + b p'`` with ``b = -e_dtheta``, so
    ``theta_hat - theta_0 - omega t = p + dtheta`` and

    ``H(s) = 1 + s e_dtheta^T (s I - A)^{-1} b``  (derived here; the loops of eq. (16) linearised).

    Uncoupled (``K_xy = 0``) this is the type-2 PLL ``(K1 s + K2) / (s^2 + K1 s + K2)`` with its
    design -3 dB bandwidth; the coordinate loops also correct the tangential error and lower it.

    Parameters
    ----------
    gains : LoopGains
    omega : float
        Rotation rate (rad/s).
    r : float
        Rotation radius (px).
    freqs_hz : array_like, shape (m,)

    Returns
    -------
    ndarray of complex, shape (m,)
    """
    s, x = _phase_resolvent(gains, omega, r, freqs_hz)
    return 1 + s * x[:, 3]


def realised_phase_bandwidth(gains: LoopGains, omega: float, r: float, f_max: float = 100.0) -> dict:
    """-3 dB bandwidth (Hz) and peak gain of :func:`phase_response` (coupled loop), on a 0.01 Hz grid.

    Returns
    -------
    dict
        ``bandwidth_hz`` (first frequency where ``|H|`` falls below ``1/sqrt 2``; NaN if none below
        ``f_max``), ``peak_gain`` (max ``|H|``), ``peak_hz``.
    """
    f = np.arange(0.01, f_max, 0.01)
    mag = np.abs(phase_response(gains, omega, r, f))
    below = np.flatnonzero(mag < 1 / np.sqrt(2))
    return dict(
        bandwidth_hz=float(f[below[0]]) if below.size else float("nan"),
        peak_gain=float(mag.max()),
        peak_hz=float(f[np.argmax(mag)]),
    )


def omega_response(gains: LoopGains, omega: float, r: float, freqs_hz) -> np.ndarray:
    """Frequency response of the coupled variant-S loop from the true rotation rate to its estimate ``omega_hat``.

    With the phase perturbation ``p`` of :func:`phase_response` the true rate deviates by ``p'`` and the state
    ``domega`` of :func:`loop_poles` is ``omega_hat - omega_0``, so ``H_omega(s) = e_domega^T (s I - A)^{-1} b``
    per unit ``p'``. Uncoupled (``K_xy = 0``) it is the PLL's ``K2 / (s^2 + K1 s + K2)``: the rate estimate is
    low-passed at the loop's natural frequency, well below the phase loop's -3 dB bandwidth.

    Parameters
    ----------
    gains : LoopGains
    omega : float
        Rotation rate (rad/s).
    r : float
        Rotation radius (px).
    freqs_hz : array_like, shape (m,)

    Returns
    -------
    ndarray of complex, shape (m,)
    """
    return _phase_resolvent(gains, omega, r, freqs_hz)[1][:, 4]


def _phase_resolvent(gains: LoopGains, omega: float, r: float, freqs_hz) -> tuple[np.ndarray, np.ndarray]:
    """``s = 2 pi i f`` (shape (m,)) and ``(s I - A)^{-1} b`` (shape (m, 5)) for a unit phase perturbation
    ``b = -e_dtheta`` of the coupled loop: the common part of :func:`phase_response` and :func:`omega_response`."""
    A = _loop_matrix(gains, omega, r)
    b = np.zeros(5)
    b[3] = -1.0
    s = 2j * np.pi * np.atleast_1d(np.asarray(freqs_hz, dtype=float))
    return s, np.linalg.solve(s[:, None, None] * np.eye(5) - A, np.broadcast_to(b, (s.size, 5))[..., None])[..., 0]


def omega_bandwidth(gains: LoopGains, omega: float, r: float, at_hz: float = 6.0, f_max: float = 100.0) -> dict:
    """-3 dB bandwidth (Hz) of :func:`omega_response` and its gain at ``at_hz`` (the paper's "6 Hz for omega").

    Returns
    -------
    dict
        ``bandwidth_hz`` (first frequency on a 0.01 Hz grid where ``|H_omega| < 1/sqrt 2``; NaN if none below
        ``f_max``) and ``gain_at`` (``|H_omega(at_hz)|``, dimensionless).
    """
    f = np.arange(0.01, f_max, 0.01)
    below = np.flatnonzero(np.abs(omega_response(gains, omega, r, f)) < 1 / np.sqrt(2))
    return dict(
        bandwidth_hz=float(f[below[0]]) if below.size else float("nan"),
        gain_at=float(np.abs(omega_response(gains, omega, r, [at_hz])[0])),
    )


@functools.lru_cache(maxsize=64)
def gains_realising(
    b_xy: float, b_r: float, b_omega: float, zeta: float = 0.707, rotation_hz: float = 8.0, r: float = 12.0
) -> LoopGains:
    """Loop gains whose *coupled* phase loop realises the -3 dB bandwidth ``b_omega`` (Hz).

    :func:`loop_gains` designs the PLL alone; the coordinate loops take up part of the tangential error,
    so the coupled loop realises less. Here the PLL's design bandwidth is raised (bisection on the
    realised bandwidth, monotone in it) until the coupled loop realises ``b_omega``; ``k_xy``, ``k_r`` unchanged.
    """
    from scipy.optimize import brentq

    omega = 2 * np.pi * rotation_hz

    def gap(b):
        return realised_phase_bandwidth(loop_gains(b_xy, b_r, b, zeta, rotation_hz), omega, r)["bandwidth_hz"] - b_omega

    hi = b_omega
    while gap(hi) < 0:
        hi *= 2
        if hi > 1e3:
            raise ValueError(f"no PLL design realises {b_omega} Hz with b_xy = {b_xy} Hz")
    b = brentq(gap, b_omega / 4, hi, xtol=1e-3)
    return loop_gains(b_xy, b_r, b, zeta, rotation_hz)


def simulate_two_emitter_1d(
    rng: np.random.Generator,
    lam,
    *,
    dt: float,
    beta: float,
    a: float,
    f_c: float,
    noise_std: float,
    form: str,
    bandwidth: float,
    unit_slope: float,
    half_gate: float | None = None,
    line_length: int = 256,
    lam0=None,
) -> np.ndarray:
    """1-D two-emitter tracker, eqs. (1)-(6) with the corrected (6), batched over trials.

    Emitters of half-width ``a`` at ``lambda -+ beta`` with anti-phase laws
    ``c1 = (1 + cos 2 pi f_c t) / 2``, ``c2 = (1 - cos 2 pi f_c t) / 2``; the loop is
    ``lam_hat += dt K e / (S1 (c1^2 + c2^2))``, ``K = 2 pi B`` (eq. (5), ``g = 0``).

    Parameters
    ----------
    lam : ndarray, shape (n, T)
        True object coordinate (px).
    unit_slope : float
        Discriminator slope per px for ``c1^2 + c2^2 = 1`` (2 for the integral form).
    lam0 : ndarray, shape (n,), optional
        Initial estimate (default: the truth).

    Returns
    -------
    ndarray, shape (n, T)
        Estimates ``lam_hat`` used at each frame.
    """
    lam = np.asarray(lam, dtype=float)
    n, T = lam.shape
    est = np.empty_like(lam)
    lh = lam[:, 0].copy() if lam0 is None else np.array(lam0, dtype=float)
    K = 2 * np.pi * bandwidth
    for k in range(T):
        t = k * dt
        c1 = 0.5 * (1 + np.cos(2 * np.pi * f_c * t))
        c2 = 1.0 - c1
        line = (
            (
                c1 * pixel_fractions_box(lam[:, k] - beta, a, line_length)
                + c2 * pixel_fractions_box(lam[:, k] + beta, a, line_length)
            )
            * 2
            * a
        )  # (2), (3)
        line += noise_std * rng.standard_normal(line.shape)  # (4)
        est[:, k] = lh
        e = two_emitter_discriminator(line, 0, lh, beta=beta, a=a, c1=c1, c2=c2, form=form, half_gate=half_gate)
        lh = lh + dt * K * e / (unit_slope * (c1**2 + c2**2))  # (5)
    return est


def phase_locked_amplitude(err, phase) -> np.ndarray:
    """Amplitude of the component of an error locked to a phase (synchronous demodulation).

    Per trial, least squares ``err ~ c0 + a cos(phase) + b sin(phase)``; the amplitude is
    ``sqrt(a^2 + b^2)``. With the marker's true phase it measures the error that varies "in step
    with the rotation"; with an unrelated phase (a control frequency) it measures how much a
    broadband error leaks into such a fit.

    Parameters
    ----------
    err : ndarray, shape (n, T)
        Error series per trial (e.g. px).
    phase : ndarray, shape (n, T) or (T,)
        Reference phase (rad).

    Returns
    -------
    ndarray, shape (n,)
        Amplitudes, units of ``err``.
    """
    e = np.asarray(err, float)
    ph = np.broadcast_to(np.asarray(phase, float), e.shape)
    X = np.stack([np.ones_like(ph), np.cos(ph), np.sin(ph)], axis=-1)  # (n, T, 3)
    coef = np.linalg.solve(np.einsum("ntk,ntl->nkl", X, X), np.einsum("ntk,nt->nk", X, e)[..., None])[..., 0]
    return np.hypot(coef[:, 1], coef[:, 2])
