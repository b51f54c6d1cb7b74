"""The object's and the marker's truth: the Fig. 1 object paths
(eq. (7); an Ornstein-Uhlenbeck x and a sinusoidal y whose phase is drawn per run) and the marker on its circle
(eq. (8), exact phase integral).

Units: px, s, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.signal import lfilter


__all__ = ["ornstein_uhlenbeck", "MarkerTruth", "marker_truth", "MOTIONS", "object_motion"]


def ornstein_uhlenbeck(
    rng: np.random.Generator, n: int, n_frames: int, dt: float, std: float, tau: float
) -> np.ndarray:
    """Stationary Ornstein-Uhlenbeck paths (exact discretisation), shape (n, n_frames), zero mean."""
    if not tau > 0:
        raise ValueError(f"parameter 'tau' = {tau}; it must be > 0")
    a = np.exp(-dt / tau)
    w = rng.standard_normal((n, n_frames)) * std * np.sqrt(1 - a * a)
    w[:, 0] = rng.standard_normal(n) * std
    return lfilter([1.0], [1.0, -a], w, axis=1)


@dataclass
class MarkerTruth:
    """True state histories, each shape (n_trials, n_frames).

    Attributes
    ----------
    xr, yr : object centre (px); r : rotation radius (px); theta : marker phase (rad);
    omega : angular rate (rad/s); t : frame times (s), shape (n_frames,).
    """

    xr: np.ndarray
    yr: np.ndarray
    r: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    t: np.ndarray

    @property
    def marker(self) -> np.ndarray:
        """Marker positions ``(x_m, y_m)`` from eq. (8), shape (n_trials, n_frames, 2)."""
        return np.stack([self.xr + self.r * np.cos(self.theta), self.yr + self.r * np.sin(self.theta)], axis=-1)

    @property
    def center(self) -> np.ndarray:
        """Object centres, shape (n_trials, n_frames, 2)."""
        return np.stack([self.xr, self.yr], axis=-1)

    @property
    def n_frames(self) -> int:
        return self.t.size


def marker_truth(xr, yr, r, omega, phi, dt: float) -> MarkerTruth:
    """Assemble truth from state histories; the phase is the exact integral of ``omega``.

    Parameters
    ----------
    xr, yr, r, omega : array_like, shape (n, T) (or broadcastable)
        Object centre (px), radius (px), angular rate (rad/s) at the frame times ``k dt``.
    phi : array_like, shape (n,)
        Initial phase (rad).
    dt : float
        Frame interval (s).
    """
    xr, yr, r, omega = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (xr, yr, r, omega)))
    # theta_k = phi + sum_{j<k} omega_j dt (eq. (8) with the exact phase, not (U3))
    theta = np.asarray(phi, dtype=float)[:, None] + np.concatenate(
        [np.zeros_like(omega[:, :1]), np.cumsum(omega[:, :-1], axis=1) * dt], axis=1
    )
    t = np.arange(xr.shape[1]) * dt
    return MarkerTruth(xr.copy(), yr.copy(), r.copy(), theta, omega.copy(), t)


MOTIONS = ("card", "sinusoids", "random")


def object_motion(
    rng: np.random.Generator,
    n: int,
    n_frames: int,
    dt: float,
    *,
    center=(128.0, 128.0),
    x_std: float = 10.0,
    x_tau: float = 1.0,
    x_smooth: float = 0.05,
    y_amplitude: float = 20.0,
    y_freq: float = 0.5,
    kind: str = "card",
    y_phase: float | None = None,
):
    """Object centre paths of Fig. 1: ``x`` random, ``y`` a sinusoid of amplitude ``y_amplitude`` px
    at ``y_freq`` Hz and phase ``y_phase`` rad (``kind = "card"``, this project's default).

    ``y_phase = None`` (the default) draws the sinusoid's phase per run, uniformly on ``[0, 2 pi)``: the paper
    gives none, and a fixed phase puts every run's start (about which the interferers are placed) at the same
    point of the path, so the object always crosses the interferers at the same speed (at ``y_phase = 0``: its
    full speed), a geometry one comparator can be more sensitive to than another.

    ``x`` is an Ornstein-Uhlenbeck process (time constant ``x_tau`` s) passed through a first-order
    low-pass of time constant ``x_smooth`` s (so that the path has a finite velocity, as a real
    object's does) and scaled to the stationary standard deviation ``x_std`` px. Other kinds (the
    paper gives no amplitudes and no law for the interference runs): ``"sinusoids"``, ``x`` a
    sinusoid of amplitude ``sqrt 2 x_std`` (the same RMS) at ``0.7 y_freq`` Hz with a random phase;
    ``"random"``, ``y`` also such a smoothed OU process, of standard deviation ``y_amplitude / sqrt 2``
    (the sinusoid's RMS). Every kind first draws the default kind's ``x`` (common random numbers across kinds).

    Returns
    -------
    xr, yr : ndarray, shape (n, n_frames)
    """
    if kind not in MOTIONS:
        raise ValueError(f"parameter 'kind' = {kind!r}; it must be one of {MOTIONS}")
    t = np.arange(n_frames) * dt

    def smoothed_ou(std):
        ou = ornstein_uhlenbeck(rng, n, n_frames, dt, 1.0, x_tau)
        if x_smooth > 0:
            b = np.exp(-dt / x_smooth)
            ou = lfilter([1 - b], [1.0, -b], ou, axis=1, zi=b * ou[:, :1])[0]
            ou *= np.sqrt((x_tau + x_smooth) / x_tau)
        return std * ou

    ou_x = smoothed_ou(x_std) if x_std > 0 else np.zeros((n, n_frames))
    # the y phase is drawn right after the default kind's x in every kind (common random numbers across kinds)
    psi = rng.uniform(0, 2 * np.pi, size=(n, 1)) if y_phase is None else np.full((n, 1), float(y_phase))
    ou_y = smoothed_ou(y_amplitude / np.sqrt(2)) if kind == "random" and y_amplitude > 0 else None
    if kind == "sinusoids":
        xr = np.sqrt(2) * x_std * np.sin(2 * np.pi * 0.7 * y_freq * t + rng.uniform(0, 2 * np.pi, size=(n, 1)))
    else:
        xr = ou_x
    yr = ou_y if ou_y is not None else y_amplitude * np.sin(2 * np.pi * y_freq * t + psi)
    return center[0] + xr, center[1] + yr
