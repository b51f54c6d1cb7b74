"""TV scene of an object carrying a rotating-emitter marker, seen through interference.

Model (Yukhno 2025, eqs. (7)-(13), with the compensation model of the paper card, section 4.2)::

    u_d(x, y, t) = s(x - x_m(t), y - y_m(t)) + kappa * f(x, y) + sum_q (d / SIR) * spot(x - x_q, y - y_q) + n

- ``s``: the marker spot (uniform disc of diameter ``D`` or square of side ``D``), brightness ``d``
  per fully covered pixel, centred on the marker ``x_m = x_r + r cos(theta)``,
  ``y_m = y_r + r sin(theta)``, ``theta = phi + int omega dt`` (eq. (8), exact phase integral).
- ``f``: zero-mean Gaussian random background with a Gaussian correlation function
  ``exp(-(tau / l_c)^2)`` (``l_c`` = correlation length, px); after compensation only
  ``kappa * f`` remains (``kappa`` = compensation residual factor; 1 = no compensation).
- stationary interferers, same spot as the marker, *residual* brightness ``d / SIR`` after
  compensation (SIR is defined after compensation; before it the ratio is ``SIR_0 = kappa SIR``).
- ``n``: white Gaussian sensor noise, ``noise_std`` per pixel per frame (eq. (U4)).

The static part (background residual and interferers) is rendered once per trial as a full
image; each frame only the gate crop is read out and the moving marker rendered into it, so
the per-frame cost is that of the gate (about 26 x 26 px), batched over trials.

Coordinates follow :mod:`tvtrack.render`: pixel centres at integers, ``x`` = column, ``y`` = row.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage
from scipy.signal import lfilter

from .loops import (
    EKFTracker,
    RotatingGateTracker,
    ekf_noise_from_bandwidths,
    gains_realising,
    loop_gains,
    run_closed_loop,
)
from ...render import box_spot, disc_area, disc_spot

__all__ = [
    "render_spot",
    "correlated_background",
    "ornstein_uhlenbeck",
    "marker_truth",
    "MarkerTruth",
    "place_interferers",
    "add_spots",
    "object_motion",
    "MOTIONS",
    "build_scene",
    "Scenario",
    "scenario_truth",
    "run_scenario",
    "RotatingMarkerScene",
    "state_errors",
    "interference_runs",
    "CommonNormal",
    "PLACEMENTS",
    "EXPOSURES",
    "COMPENSATIONS",
    "median_residual",
]

SPOTS = ("disc", "square")


def _check_spot(spot: str) -> None:
    if spot not in SPOTS:
        raise ValueError(f"parameter 'spot' = {spot!r}; it must be one of {SPOTS}")


def render_spot(spot: str, centers, shape, diameter, brightness=1.0, origin=(0, 0)) -> np.ndarray:
    """A marker or interferer spot: ``"disc"`` (diameter ``D``) or ``"square"`` (side ``D``),
    ``brightness`` per fully covered pixel; shape ``(..., rows, cols)``."""
    _check_spot(spot)
    b = np.asarray(brightness, dtype=float)
    if spot == "disc":
        return disc_spot(centers, shape, diameter, b * disc_area(diameter), origin)
    return box_spot(centers, shape, diameter / 2, b * diameter**2, origin)


def correlated_background(rng: np.random.Generator, n: int, shape, corr_length, std) -> np.ndarray:
    """Zero-mean Gaussian random fields with correlation ``exp(-(tau / corr_length)^2)``.

    White noise is filtered by a Gaussian kernel of standard deviation ``corr_length / 2``
    (periodic boundary) and divided by the filter's exact output standard deviation (the root
    sum of squares of the discrete kernel), so every pixel has standard deviation ``std``.

    Returns
    -------
    ndarray, shape (n, rows, cols), float32
    """
    if not corr_length > 0:
        raise ValueError(f"parameter 'corr_length' = {corr_length}; it must be > 0")
    if std < 0:
        raise ValueError(f"parameter 'std' = {std}; it must be >= 0")
    sigma = corr_length / 2
    field = rng.standard_normal((n, *shape), dtype=np.float32)
    ndimage.gaussian_filter(field, sigma=(0, sigma, sigma), mode="wrap", output=field)
    impulse = np.zeros(2 * int(4 * sigma + 0.5) + 1)
    impulse[impulse.size // 2] = 1.0
    gain = np.sum(ndimage.gaussian_filter1d(impulse, sigma, mode="constant") ** 2)  # per axis
    field *= np.float32(std / gain)
    return field


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


def place_interferers(
    rng: np.random.Generator, n: int, count: int, center, radius: float, radial_jitter: float = 0.0
) -> np.ndarray:
    """Stationary interferers on a circle (the area swept by the marker).

    One interferer sits at a uniformly random angle; several are equally spaced with a common
    random angular offset. ``radial_jitter`` > 0 draws each radius uniformly in
    ``[radius - jitter, radius + jitter]``.

    Returns
    -------
    ndarray, shape (n, count, 2)
        Positions ``(x, y)`` in px.
    """
    if count < 0:
        raise ValueError(f"parameter 'count' = {count}; it must be >= 0")
    offset = rng.uniform(0, 2 * np.pi, size=(n, 1))
    ang = offset + 2 * np.pi * np.arange(count) / max(count, 1)
    rad = radius + rng.uniform(-radial_jitter, radial_jitter, size=(n, count))
    c = np.broadcast_to(np.asarray(center, dtype=float), (n, 2))
    return np.stack([c[:, None, 0] + rad * np.cos(ang), c[:, None, 1] + rad * np.sin(ang)], axis=-1)


def add_spots(images, centers, brightness, spot: str, diameter: float) -> None:
    """Add spots to images in place, each rendered only in a small patch around it.

    Parameters
    ----------
    images : ndarray, shape (n, rows, cols)
    centers : ndarray, shape (n, q, 2)
        Spot centres (px); parts falling outside the image are dropped.
    brightness : ndarray, shape (n, q)
    """
    n, rows, cols = images.shape
    size = int(np.ceil(diameter)) + 4
    trial = np.arange(n)[:, None, None]
    ar = np.arange(size)
    for j in range(np.asarray(centers).shape[1]):
        c = centers[:, j]
        origin = np.floor(c - (size - 1) / 2).astype(np.int64)
        patch = render_spot(spot, c, (size, size), diameter, brightness[:, j], origin)
        ys = origin[:, 1, None] + ar
        xs = origin[:, 0, None] + ar
        ok = ((ys >= 0) & (ys < rows))[:, :, None] & ((xs >= 0) & (xs < cols))[:, None, :]
        yi = np.clip(ys, 0, rows - 1)[:, :, None]
        xi = np.clip(xs, 0, cols - 1)[:, None, :]
        images[trial, yi, xi] += np.where(ok, patch, 0.0).astype(images.dtype)


class RotatingMarkerScene:
    """Static compensated scene per trial plus the moving marker, read out as gate crops.

    Parameters
    ----------
    truth : MarkerTruth
        Marker and object truth, shape (n, T) per state.
    image_shape : (int, int)
        Sensor size ``(rows, cols)``.
    spot : {"disc", "square"}
        Marker and interferer shape.
    diameter : float
        Spot diameter (disc) or side (square), px.
    brightness : float
        Marker brightness ``d`` per fully covered pixel.
    residual : ndarray, shape (n, rows, cols), optional
        Static residual after compensation, ``kappa f + interferers``; see :meth:`static_residual`.
    noise_std : float
        Sensor noise per pixel per frame (>= 0).
    interferers : ndarray, shape (n, q, 2), optional
        Interferer positions (kept for plotting and capture tagging).
    decoys : ndarray, shape (n, T, 2), optional
        Paths of a moving imitating interferer (e.g. an emitter rotating like the marker about
        another centre), rendered into every frame with the marker's spot.
    decoy_brightness : float or ndarray, shape (n,)
        Decoy brightness per fully covered pixel (one value per trial allowed).
    exposure_steps : int
        1: the sensor samples the scene at the frame time (instant exposure). ``m > 1``: it integrates over the
        frame interval centred on the frame time, rendered as the mean of ``m`` sub-frame renders at
        ``tau_j = ((j + 1/2)/m - 1/2) dt``: the object moves by its velocity (central differences of the truth),
        the marker turns by ``omega tau_j`` about it, the decoy about its own centre (``decoy_phase``). The spot
        energy per frame is the same either way; only its spread changes. :meth:`frame` (recordings) is instant.
    decoy_phase : ndarray, shape (n,), optional
        Phase offset of each decoy from the marker (needed to smear a decoy).
    """

    MARGIN = 40  # px of zero padding around the image so that gates may leave it

    def __init__(
        self,
        truth: MarkerTruth,
        image_shape,
        spot: str,
        diameter: float,
        brightness: float,
        residual=None,
        noise_std: float = 0.0,
        interferers=None,
        decoys=None,
        decoy_brightness=0.0,
        exposure_steps: int = 1,
        decoy_phase=None,
    ):
        _check_spot(spot)
        if int(exposure_steps) < 1:
            raise ValueError(f"parameter 'exposure_steps' = {exposure_steps}; it must be >= 1")
        if noise_std < 0:
            raise ValueError(f"parameter 'noise_std' = {noise_std}; it must be >= 0")
        self.truth = truth
        self.n = truth.xr.shape[0]
        self.image_shape = tuple(image_shape)
        self.spot = spot
        self.diameter = float(diameter)
        self.brightness = float(brightness)
        self.noise_std = float(noise_std)
        self.interferers = np.zeros((self.n, 0, 2)) if interferers is None else np.asarray(interferers, float)
        self.decoys = None if decoys is None else np.asarray(decoys, dtype=float)
        self.decoy_brightness = np.broadcast_to(np.asarray(decoy_brightness, dtype=float), (self.n,))
        m = self.MARGIN
        rows, cols = self.image_shape
        self._padded = np.zeros((self.n, rows + 2 * m, cols + 2 * m), dtype=np.float32)
        if residual is not None:
            self._padded[:, m : m + rows, m : m + cols] = residual
        self._base = np.arange(self.n) * self._padded.shape[1] * self._padded.shape[2]
        self.exposure_steps = int(exposure_steps)
        if self.exposure_steps > 1:
            t = truth.t
            self._dt = float(t[1] - t[0]) if t.size > 1 else 1.0
            self._velocity = np.gradient(truth.center, self._dt, axis=1) if t.size > 1 else np.zeros_like(truth.center)
            if self.decoys is not None and decoy_phase is None:
                raise ValueError("an integrated exposure with a decoy needs 'decoy_phase'")
            self.decoy_phase = None if decoy_phase is None else np.asarray(decoy_phase, float).reshape(self.n)

    def _sub_positions(self, k: int) -> tuple[np.ndarray, np.ndarray | None]:
        """Marker (and decoy) positions at the ``m`` sub-frame times of frame ``k``, shape (m, n, 2) each."""
        tr, m = self.truth, self.exposure_steps
        tau = ((np.arange(m) + 0.5) / m - 0.5) * self._dt
        shift = tau[:, None, None] * self._velocity[None, :, k]  # object motion within the frame
        ang = tr.theta[None, :, k] + tr.omega[None, :, k] * tau[:, None]
        r = tr.r[None, :, k]
        centre = np.stack([tr.xr[:, k], tr.yr[:, k]], axis=-1)[None]
        marker = centre + shift + r[..., None] * np.stack([np.cos(ang), np.sin(ang)], axis=-1)
        if self.decoys is None:
            return marker, None
        a0 = tr.theta[:, k] + self.decoy_phase
        own = self.decoys[:, k] - r[0][:, None] * np.stack([np.cos(a0), np.sin(a0)], axis=-1)  # decoy's centre
        a = ang + self.decoy_phase[None]
        return marker, own[None] + shift + r[..., None] * np.stack([np.cos(a), np.sin(a)], axis=-1)

    @staticmethod
    def static_residual(
        rng: np.random.Generator,
        n: int,
        image_shape,
        *,
        kappa: float,
        background_std: float,
        corr_length: float,
        interferers,
        interferer_brightness,
        spot: str,
        diameter: float,
    ) -> np.ndarray:
        """``kappa * f + sum_q b_q spot(. - x_q)``: what compensation leaves of the static scene.

        Parameters
        ----------
        kappa : float
            Compensation residual factor in [0, 1] (0 = perfect estimate of the background).
        background_std : float
            Standard deviation of ``f`` before compensation.
        interferers : ndarray, shape (n, q, 2)
        interferer_brightness : float or ndarray, shape (n,) or (n, q)
            Residual brightness (after compensation) of each interferer, ``d / SIR``.

        Returns
        -------
        ndarray, shape (n, rows, cols), float32
        """
        if not 0 <= kappa <= 1:
            raise ValueError(f"parameter 'kappa' = {kappa}; it must be in [0, 1]")
        out = kappa * correlated_background(rng, n, image_shape, corr_length, background_std)
        q = np.asarray(interferers, dtype=float)
        b = np.asarray(interferer_brightness, dtype=float)
        b = np.broadcast_to(b[:, None] if b.ndim == 1 else b, q.shape[:2])
        add_spots(out, q, b, spot, diameter)
        return out

    def gate_crops(self, k: int, centres, size: int, rng: np.random.Generator | None):
        """Compensated signal ``u_d`` in square crops of side ``size`` around ``centres`` at frame ``k``.

        Parameters
        ----------
        k : int
            Frame index.
        centres : ndarray, shape (n, 2)
            Gate centres (px).
        size : int
            Crop side (px), e.g. :func:`tvtrack.measure.gate_crop_size`.
        rng : numpy.random.Generator or None
            Draws the sensor noise (None: noise-free).

        Returns
        -------
        crops : ndarray, shape (n, size, size), float32
        origin : ndarray of int, shape (n, 2)
            ``(x0, y0)`` of each crop's first pixel.
        inside : ndarray of bool, shape (n,)
            Whether the gate centre is inside the image.
        """
        c = np.asarray(centres, dtype=float)
        origin = np.floor(c - (size - 1) / 2.0).astype(np.int64)
        m = self.MARGIN
        rows, cols = self.image_shape
        inside = (c[:, 0] >= 0) & (c[:, 0] <= cols - 1) & (c[:, 1] >= 0) & (c[:, 1] <= rows - 1)
        ox = np.clip(origin[:, 0] + m, 0, cols + 2 * m - size)
        oy = np.clip(origin[:, 1] + m, 0, rows + 2 * m - size)
        origin = np.stack([ox - m, oy - m], axis=1)
        H, W = self._padded.shape[1:]
        ar = np.arange(size)
        flat = (self._base + oy * W + ox)[:, None, None] + (ar[:, None] * W + ar)[None]
        crops = self._padded.reshape(-1).take(flat)
        marker = np.stack(
            [
                self.truth.xr[:, k] + self.truth.r[:, k] * np.cos(self.truth.theta[:, k]),
                self.truth.yr[:, k] + self.truth.r[:, k] * np.sin(self.truth.theta[:, k]),
            ],
            axis=1,
        )
        if self.exposure_steps == 1:
            crops += self._spot(marker, size, origin, self.brightness)
            if self.decoys is not None:
                crops += self._spot(self.decoys[:, k], size, origin, self.decoy_brightness)
        else:
            sub_m, sub_d = self._sub_positions(k)
            for j in range(self.exposure_steps):
                crops += self._spot(sub_m[j], size, origin, self.brightness / self.exposure_steps)
                if sub_d is not None:
                    crops += self._spot(sub_d[j], size, origin, self.decoy_brightness / self.exposure_steps)
        if rng is not None and self.noise_std > 0:
            crops += self.noise_std * rng.standard_normal(crops.shape, dtype=np.float32)
        return crops, origin, inside

    def _spot(self, centers, size, origin, brightness) -> np.ndarray:
        if self.spot == "disc":
            flux = np.asarray(brightness, dtype=float) * disc_area(self.diameter)
            return disc_spot(centers, (size, size), self.diameter, flux, origin, dtype=np.float32)
        return render_spot("square", centers, (size, size), self.diameter, brightness, origin).astype(np.float32)

    def frame(self, trial: int, k: int, rng: np.random.Generator | None = None) -> np.ndarray:
        """Full compensated frame ``u_d`` of one trial at frame ``k``, shape (rows, cols), float32."""
        m = self.MARGIN
        rows, cols = self.image_shape
        img = self._padded[trial, m : m + rows, m : m + cols].copy()
        img += render_spot(
            self.spot, self.truth.marker[trial, k], self.image_shape, self.diameter, self.brightness
        ).astype(np.float32)
        if self.decoys is not None:
            img += render_spot(
                self.spot, self.decoys[trial, k], self.image_shape, self.diameter, self.decoy_brightness[trial]
            ).astype(np.float32)
        if rng is not None and self.noise_std > 0:
            img += self.noise_std * rng.standard_normal(img.shape, dtype=np.float32)
        return img


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
    at ``y_freq`` Hz and phase ``y_phase`` rad (``kind = "card"``).

    ``y_phase = None`` (the default) draws the sinusoid's phase per run, uniformly on ``[0, 2 pi)``: the paper
    gives none, and a fixed phase puts every run's start (about which the interferers are placed) at the same
    point of the path, so the object always crosses the interferers at the same speed (at ``y_phase = 0``: its
    full speed), a geometry one comparator can be more sensitive to than another (issue 40).

    ``x`` is an Ornstein-Uhlenbeck process (time constant ``x_tau`` s) passed through a first-order
    low-pass of time constant ``x_smooth`` s (so that the path has a finite velocity, as a real
    object's does) and scaled to the stationary standard deviation ``x_std`` px. Other kinds (the
    paper gives no amplitudes and no law for the interference runs): ``"sinusoids"``, ``x`` a
    sinusoid of amplitude ``sqrt 2 x_std`` (the same RMS) at ``0.7 y_freq`` Hz with a random phase;
    ``"random"``, ``y`` also such a smoothed OU process, of standard deviation ``y_amplitude / sqrt 2``
    (the sinusoid's RMS). Every kind first draws the card's ``x`` (common random numbers across kinds).

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
    # the y phase is drawn right after the card's x in every kind (common random numbers across kinds)
    psi = rng.uniform(0, 2 * np.pi, size=(n, 1)) if y_phase is None else np.full((n, 1), float(y_phase))
    ou_y = smoothed_ou(y_amplitude / np.sqrt(2)) if kind == "random" and y_amplitude > 0 else None
    if kind == "sinusoids":
        xr = np.sqrt(2) * x_std * np.sin(2 * np.pi * 0.7 * y_freq * t + rng.uniform(0, 2 * np.pi, size=(n, 1)))
    else:
        xr = ou_x
    yr = ou_y if ou_y is not None else y_amplitude * np.sin(2 * np.pi * y_freq * t + psi)
    return center[0] + xr, center[1] + yr


class CommonNormal:
    """Standard normal draws shared by blocks of trials (common random numbers).

    Wraps a generator; ``standard_normal(shape)`` with ``shape[0] = blocks * n_common`` draws
    ``n_common`` rows and repeats them, so trial ``j n_common + i`` gets the draws of trial ``i``.
    Used to run one set of trials at several SIR values (or markers) on the same noise.
    """

    def __init__(self, rng: np.random.Generator, n_common: int):
        if n_common < 1:
            raise ValueError(f"parameter 'n_common' = {n_common}; it must be >= 1")
        self.rng = rng
        self.n_common = int(n_common)

    def standard_normal(self, shape, dtype=np.float64):
        shape = tuple(np.atleast_1d(shape))
        if shape[0] % self.n_common:
            raise ValueError(f"leading size {shape[0]} is not a multiple of n_common = {self.n_common}")
        z = self.rng.standard_normal((self.n_common, *shape[1:]), dtype=dtype)
        return np.tile(z, (shape[0] // self.n_common,) + (1,) * (len(shape) - 1))


class BlockNormal:
    """Standard normal draws made block by block from several sources (one per seed), concatenated
    along the leading axis; each source is a generator or a :class:`CommonNormal`."""

    def __init__(self, sources, block: int):
        self.sources = list(sources)
        self.block = int(block)

    def standard_normal(self, shape, dtype=np.float64):
        shape = tuple(np.atleast_1d(shape))
        if shape[0] != self.block * len(self.sources):
            raise ValueError(f"leading size {shape[0]} is not {len(self.sources)} blocks of {self.block}")
        return np.concatenate([g.standard_normal((self.block, *shape[1:]), dtype=dtype) for g in self.sources])


def median_residual(
    rng: np.random.Generator,
    truth: MarkerTruth,
    n_frames: int,
    image_shape,
    spot: str,
    diameter: float,
    brightness: float,
    noise_std: float,
) -> np.ndarray:
    """What a temporal-median background estimate leaves of a static scene: ``-median_t(s_t + n_t)``.

    The compensation subtracts, from every frame, the per-pixel median of the first ``n_frames`` raw frames
    ``f + interferers + s_t + n_t`` (card 8.5: a median over >= 2 revolutions). Everything static -- background and
    stationary interferers -- cancels exactly, whatever its brightness; left is minus the median of the marker's
    sweep plus noise: a faint ring where the marker passes (a pixel it covers in a share ``p < 1/2`` of the frames
    reads ``-sigma Phi^-1(1 / (2 (1 - p)))`` for ``d >> sigma``), or the whole marker where it stood still for more
    than half of them. The median is computed exactly inside the box the marker visits (plus a spot); outside it,
    where only noise enters, it is drawn from the sample median's normal law, variance ``pi sigma^2 / (2 N)``.
    Instant exposure, and no decoy, in the median frames.

    Parameters
    ----------
    rng : numpy.random.Generator
    truth : MarkerTruth
        ``n`` trials; frames ``0 .. n_frames - 1`` enter the median.
    n_frames : int
        Frames in the median (``N``).
    image_shape : (int, int)
    spot, diameter, brightness, noise_std
        The marker spot and the sensor noise per pixel.

    Returns
    -------
    ndarray, shape (n, rows, cols), float32
    """
    N = int(min(max(n_frames, 1), truth.n_frames))
    n = truth.xr.shape[0]
    rows, cols = image_shape
    out = (-noise_std * np.sqrt(np.pi / (2 * N)) * rng.standard_normal((n, rows, cols))).astype(np.float32)
    m = truth.marker[:, :N]  # (n, N, 2)
    lo = np.floor(m.min(axis=1) - diameter / 2 - 2).astype(np.int64)
    size = int(np.max(np.ceil(m.max(axis=1) + diameter / 2 + 2).astype(np.int64) - lo)) + 1
    frames = render_spot(spot, np.swapaxes(m, 0, 1), (size, size), diameter, brightness, lo[None])  # (N, n, s, s)
    if noise_std > 0:
        frames = frames + noise_std * rng.standard_normal(frames.shape)
    box = -np.median(frames, axis=0)
    ar = np.arange(size)
    ys, xs = lo[:, 1, None] + ar, lo[:, 0, None] + ar
    ok = ((ys >= 0) & (ys < rows))[:, :, None] & ((xs >= 0) & (xs < cols))[:, None, :]
    trial = np.arange(n)[:, None, None]
    yi, xi = np.clip(ys, 0, rows - 1)[:, :, None], np.clip(xs, 0, cols - 1)[:, None, :]
    out[trial, yi, xi] = np.where(ok, box, out[trial, yi, xi])
    return out


def _tile(a, n: int):
    """Repeat the leading axis of ``a`` until it has ``n`` rows (``n`` a multiple of its length)."""
    a = np.asarray(a)
    return np.tile(a, (n // a.shape[0],) + (1,) * (a.ndim - 1))


def _generator_blocks(rng, n: int, n_common: int | None):
    """Split ``n`` trials into one consecutive block per generator (``rng`` one or a list), and check
    that ``n_common`` (trials sharing common random numbers; default: the whole block) divides a block.

    Returns ``(generators, trials per generator, n_common)``."""
    rngs = list(rng) if isinstance(rng, (list, tuple)) else [rng]
    n_block = n // len(rngs)
    n_common = n_block if n_common is None else int(n_common)
    if n % len(rngs) or n_common < 1 or n_block % n_common:
        raise ValueError(
            f"parameter 'n_common' = {n_common}; it must divide the trials per generator ({n} trials, "
            f"{len(rngs)} generators)"
        )
    return rngs, n_block, n_common


def build_scene(
    rng: np.random.Generator,
    truth: MarkerTruth,
    *,
    image_shape=(256, 256),
    spot: str = "disc",
    diameter: float = 8.0,
    brightness: float = 1.0,
    noise_std: float = 0.02,
    kappa: float = 0.1,
    background_std: float = 0.2,
    corr_length: float = 8.0,
    n_interferers: int = 0,
    sir=np.inf,
    interferer_radius: float = 12.0,
    interferer_center=None,
    radial_jitter: float = 0.0,
    interferer_diameter: float | None = None,
    decoys=None,
    decoy_brightness=0.0,
    n_common: int | None = None,
    blocks=None,
    exposure_steps: int = 1,
    decoy_phase=None,
    compensation: str = "kappa",
    median_frames: int = 0,
):
    """A compensated scene with ``n_interferers`` stationary interferers of post-compensation
    ``SIR = d / b_q`` (scalar or one value per trial; ``b_q`` per fully covered pixel, like ``d``), placed by
    :func:`place_interferers` around ``interferer_center`` (default: the object's initial centre), with the
    marker's spot or one of ``interferer_diameter``.

    ``n_common``: draw the background and the interferer positions for ``n_common`` trials and
    repeat them over the ``n / n_common`` blocks (common random numbers; default: all trials
    independent). ``rng`` may be a list of generators: each draws for its own consecutive block
    of ``n / len(rng)`` trials (several seeds in one batch). ``blocks``, one dict per generator,
    overrides ``kappa``, ``background_std``, ``corr_length`` or ``n_interferers`` block by block
    (several scene settings in one batch; a block with fewer interferers is padded with dark ones
    far outside the image).

    ``compensation``: ``"kappa"`` leaves ``kappa`` times the static scene (:meth:`RotatingMarkerScene.
    static_residual`); ``"median"`` subtracts the temporal median of the first ``median_frames`` frames
    (:func:`median_residual`: background and interferers cancel) in every block with ``kappa < 1`` (a block with
    ``kappa = 1`` stays uncompensated).

    Returns
    -------
    RotatingMarkerScene
    """
    n = truth.xr.shape[0]
    rngs, n_block, n_common = _generator_blocks(rng, n, n_common)
    blocks = [{}] * len(rngs) if blocks is None else list(blocks)
    if len(blocks) != len(rngs) or any(
        set(b) - {"kappa", "background_std", "corr_length", "n_interferers"} for b in blocks
    ):
        raise ValueError(
            "parameter 'blocks' needs one dict per generator with keys among kappa, background_std, "
            "corr_length, n_interferers"
        )
    if compensation not in COMPENSATIONS:
        raise ValueError(f"parameter 'compensation' = {compensation!r}; it must be one of {COMPENSATIONS}")
    q, residual, by_median = [], [], []
    for j, (g, b) in enumerate(zip(rngs, blocks)):
        first = j * n_block
        centre = truth.center[first : first + n_common, 0] if interferer_center is None else interferer_center
        q.append(
            _tile(
                place_interferers(
                    g, n_common, b.get("n_interferers", n_interferers), centre, interferer_radius, radial_jitter
                ),
                n_block,
            )
        )
        med = compensation == "median" and b.get("kappa", kappa) < 1
        by_median.append(np.full(n_block, med))
        if med:
            part = MarkerTruth(
                *(getattr(truth, f)[first : first + n_common] for f in ("xr", "yr", "r", "theta", "omega")), truth.t
            )
            res = median_residual(g, part, median_frames, image_shape, spot, diameter, brightness, noise_std)
        else:
            res = RotatingMarkerScene.static_residual(
                g,
                n_common,
                image_shape,
                kappa=b.get("kappa", kappa),
                background_std=b.get("background_std", background_std),
                corr_length=b.get("corr_length", corr_length),
                interferers=np.zeros((n_common, 0, 2)),
                interferer_brightness=np.zeros(n_common),
                spot=spot,
                diameter=diameter,
            )
        residual.append(_tile(res, n_block))
    n_q = max(x.shape[1] for x in q)
    q = np.concatenate([np.concatenate([x, np.full((x.shape[0], n_q - x.shape[1], 2), -1e4)], axis=1) for x in q])
    residual = np.concatenate(residual) if len(residual) > 1 else residual[0]
    sir = np.broadcast_to(np.asarray(sir, dtype=float), (n,))
    if np.any(sir <= 0):
        raise ValueError(f"parameter 'sir' has values <= 0 ({sir.min()}); it must be > 0")
    cancelled = np.concatenate(by_median)[:, None]  # a temporal median removes stationary interferers exactly
    add_spots(
        residual,
        q,
        np.where((q[..., 0] > -1e3) & ~cancelled, (brightness / sir)[:, None], 0.0),
        spot,
        diameter if interferer_diameter is None else interferer_diameter,
    )
    return RotatingMarkerScene(
        truth,
        image_shape,
        spot,
        diameter,
        brightness,
        residual,
        noise_std,
        q,
        decoys,
        decoy_brightness,
        exposure_steps,
        decoy_phase,
    )


@dataclass(frozen=True)
class Scenario:
    """One tracking experiment (defaults: the paper card's choices, sections 4.2-4.5 and 5).

    Units: px, s, Hz; brightness in units of the marker brightness ``d``.
    ``kappa`` = compensation residual (1 = none); ``noise_std`` and ``background_std`` are
    per pixel (the background before compensation). ``omega_mod``/``radius_mod`` are relative
    sinusoidal modulation depths of the rotation rate and radius (Fig. 2). ``y_phase`` is the phase of the
    object's y sinusoid (rad; None = uniformly random per run, :func:`object_motion`). ``decoy_offset`` > 0
    adds an imitating interferer rotating like the marker about a centre displaced by that many px,
    at the phase offset ``decoy_phase`` (rad; None = uniformly random per trial); its brightness at the tracker is
    ``decoy_gain d / SIR`` with the SIR passed to :func:`run_scenario`. The paper defines SIR with the brightness an
    interferer keeps *after* compensation; a decoy moves, so no background compensation removes it: ``decoy_gain = 1``
    (the default) puts the decoy at the brightness a stationary interferer keeps at that SIR (the paper's SIR read
    for the decoy), ``1 / kappa`` at the brightness a stationary interferer *emits* there (equal emitters).
    ``exposure`` ``"instant"`` or ``"integrated"`` over the frame (:attr:`exposure_steps` sub-frame renders);
    ``compensation`` ``"kappa"`` (``kappa`` times the static scene left) or ``"median"`` (a per-pixel temporal median
    of the first ``median_revolutions`` revolutions subtracted, :func:`median_residual`).
    """

    fps: float = 500.0
    duration_s: float = 10.0
    image_size: int = 256
    spot: str = "disc"
    diameter: float = 8.0
    brightness: float = 1.0
    noise_std: float = 0.02
    background_std: float = 0.2
    corr_length: float = 8.0
    kappa: float = 0.1
    rotating: bool = True
    radius: float = 12.0
    rotation_hz: float = 8.0
    omega_mod: float = 0.0
    omega_mod_hz: float = 0.5
    radius_mod: float = 0.0
    radius_mod_hz: float = 0.05
    motion: str = "card"
    x_std: float = 10.0
    x_tau: float = 1.0
    x_smooth: float = 0.05
    y_amplitude: float = 20.0
    y_freq: float = 0.5
    y_phase: float | None = None
    n_interferers: int = 0
    interferer_jitter: float = 0.0
    interferer_diameter: float | None = None
    interferer_radius_offset: float = 0.0
    interferer_centre: str = "object"
    decoy_offset: float = 0.0
    decoy_phase: float | None = None
    decoy_gain: float = 1.0
    gate_half: float = 12.0
    b_xy: float = 10.0
    b_r: float = 0.2
    b_omega: float = 6.0
    variant: str = "S"
    realise_phase_bandwidth: bool = False
    form: str = "quadrant"
    edge_norm: str = "slope"
    exposure: str = "instant"
    compensation: str = "kappa"
    median_revolutions: float = 2.0
    init_offset: tuple = (3.0, -3.0)
    init_radius_factor: float = 0.85
    init_phase: float = 0.2

    def __post_init__(self):
        if not 0 < self.rotation_hz < self.fps / 2:
            raise ValueError(
                f"parameter 'rotation_hz' = {self.rotation_hz}; it must be > 0 and below the frame-rate "
                f"Nyquist fps / 2 = {self.fps / 2:g} Hz (the gate samples the rotation once a frame)"
            )
        if self.motion not in MOTIONS:
            raise ValueError(f"parameter 'motion' = {self.motion!r}; it must be one of {MOTIONS}")
        if self.edge_norm not in ("slope", "slew"):
            raise ValueError(f"parameter 'edge_norm' = {self.edge_norm!r}; it must be 'slope' or 'slew'")
        if self.compensation not in COMPENSATIONS:
            raise ValueError(f"parameter 'compensation' = {self.compensation!r}; it must be one of {COMPENSATIONS}")
        if self.exposure not in EXPOSURES:
            raise ValueError(f"parameter 'exposure' = {self.exposure!r}; it must be one of {EXPOSURES}")

    @property
    def n_frames(self) -> int:
        return int(round(self.duration_s * self.fps))

    @property
    def omega0(self) -> float:
        return 2 * np.pi * self.rotation_hz

    @property
    def exposure_steps(self) -> int:
        """Sub-frame renders of an integrated exposure: the marker's largest arc per frame in half-pixel steps
        (``ceil(2 omega_max r_max / fps) + 1``); 1 for an instant exposure."""
        if self.exposure == "instant":
            return 1
        arc = self.omega0 * (1 + self.omega_mod) * self.radius * (1 + self.radius_mod) / self.fps
        return int(np.ceil(2 * arc)) + 1

    def slope(self) -> float:
        """Discriminator slope ``S`` per px: ``2 d D`` for the quadrant form; for the edge form
        the numerical slope of its static characteristic at zero error."""
        if self.form == "quadrant":
            return 2 * self.brightness * self.diameter
        if self.form == "centroid":
            return 1.0
        from .discriminators import static_characteristic

        if self.edge_norm == "slew":
            # matched slew: the normalised edge output saturates where the quadrant form's does
            off = np.linspace(0.0, self.gate_half, 49)
            quad = static_characteristic(self.spot_renderer(), off, form="quadrant", half=self.gate_half)
            edge = static_characteristic(
                self.spot_renderer(), off, form="edge", half=self.gate_half, a=self.diameter / 2
            )
            return float(np.max(edge) / (np.max(quad) / (2 * self.brightness * self.diameter)))
        f = static_characteristic(
            self.spot_renderer(), [-0.25, 0.25], form="edge", half=self.gate_half, a=self.diameter / 2
        )
        return float((f[1] - f[0]) / 0.5)

    def gains(self):
        """Loop gains: the stated bandwidths as designed loop by loop (:func:`loop_gains`), or with
        ``realise_phase_bandwidth`` the PLL retuned so that the coupled loop realises ``b_omega``."""
        if self.realise_phase_bandwidth and self.rotating:
            return gains_realising(self.b_xy, self.b_r, self.b_omega, rotation_hz=self.rotation_hz, r=self.radius)
        return loop_gains(self.b_xy, self.b_r, self.b_omega, rotation_hz=self.rotation_hz)

    def spot_renderer(self):
        """``render(centers, shape, origin)`` for this scenario's spot."""
        return lambda c, shape, origin: render_spot(self.spot, c, shape, self.diameter, self.brightness, origin)


def scenario_truth(rng: np.random.Generator, n: int, sc: Scenario) -> MarkerTruth:
    """Truth of a scenario: Fig. 1 motion, rotation with optional Fig. 2 modulation, random phase."""
    T, dt = sc.n_frames, 1.0 / sc.fps
    t = np.arange(T) * dt
    c = sc.image_size / 2
    xr, yr = object_motion(
        rng,
        n,
        T,
        dt,
        center=(c, c),
        x_std=sc.x_std,
        x_tau=sc.x_tau,
        x_smooth=sc.x_smooth,
        y_amplitude=sc.y_amplitude,
        y_freq=sc.y_freq,
        kind=sc.motion,
        y_phase=sc.y_phase,
    )
    if not sc.rotating:
        return marker_truth(xr, yr, np.zeros((n, T)), np.zeros((n, T)), np.zeros(n), dt)
    omega = sc.omega0 * (1 + sc.omega_mod * np.sin(2 * np.pi * sc.omega_mod_hz * t)) * np.ones((n, 1))
    r = sc.radius * (1 + sc.radius_mod * np.sin(2 * np.pi * sc.radius_mod_hz * t)) * np.ones((n, 1))
    return marker_truth(xr, yr, r, omega, rng.uniform(0, 2 * np.pi, n), dt)


PLACEMENTS = ("object", "image")
EXPOSURES = ("instant", "integrated")
COMPENSATIONS = ("kappa", "median")


def run_scenario(
    rng: np.random.Generator,
    n: int,
    sc: Scenario,
    sir=np.inf,
    *,
    tracker: str = "loops",
    ekf_meas_var: float = 0.05,
    noise: str = "projected",
    keep_full: bool = True,
    crop_callback=None,
    n_common: int | None = None,
    gains=None,
    blocks=None,
):
    """Simulate ``n`` trials of a scenario end to end (truth, scene, tracker, closed loop).

    The truth, the decoy, the scene and the sensor noise draw from four generators spawned from
    ``rng``, so two scenarios that differ only in what a draw does not depend on (SIR, rotating or
    static marker, gate, loop gains) see the same object motion, background, interferer
    placement and noise.

    Parameters
    ----------
    sir : float or ndarray, shape (n,)
        Post-compensation signal-to-interference ratio of the stationary interferers and of the
        decoy (brightness ``d / SIR`` each).
    tracker : {"loops", "ekf"}
        Fixed-bandwidth loops (variant ``sc.variant``) or the discrete EKF of eqs. (16)-(17).
    noise : {"projected", "pixel"}
        See :func:`tvtrack.papers.p003_rotating_marker_tracker.loops.run_closed_loop` (the edge form always uses pixel noise).
    n_common : int, optional
        Common random numbers: within a generator's block, trial ``j n_common + i`` repeats every
        draw of trial ``i`` (e.g. ``n_common`` trials at each of several SIR values).
    blocks : list of dict, optional
        Scene settings per generator block (see :func:`build_scene`).
    gains : LoopGains, optional
        Loop gains instead of ``sc.gains()``; fields may be arrays of shape (n,) (per-trial gains, e.g. several
        bandwidths run as one batch on common draws).

    ``rng`` may be a list of generators (e.g. one per seed): each draws for its own consecutive
    block of ``n / len(rng)`` trials, exactly as it would alone, so seeds can share one batch.

    Returns
    -------
    truth : MarkerTruth
    scene : RotatingMarkerScene
    history : tvtrack.papers.p003_rotating_marker_tracker.loops.TrackHistory
    """
    rngs, n_block, n_common = _generator_blocks(rng, n, n_common)
    if sc.interferer_centre not in PLACEMENTS:
        raise ValueError(f"parameter 'interferer_centre' = {sc.interferer_centre!r}; it must be one of {PLACEMENTS}")
    streams = [g.spawn(4) for g in rngs]  # truth, decoy, scene, noise
    bases = [scenario_truth(st[0], n_common, sc) for st in streams]
    truth = MarkerTruth(
        *(np.concatenate([_tile(getattr(b, f), n_block) for b in bases]) for f in ("xr", "yr", "r", "theta", "omega")),
        bases[0].t,
    )
    sir = np.broadcast_to(np.asarray(sir, dtype=float), (n,))
    decoys = None
    if sc.decoy_offset > 0:
        ang = np.concatenate([_tile(st[1].uniform(0, 2 * np.pi, n_common), n_block) for st in streams])[:, None]
        dphi = (
            np.concatenate([_tile(st[1].uniform(0, 2 * np.pi, n_common), n_block) for st in streams])[:, None]
            if sc.decoy_phase is None
            else np.full((n, 1), float(sc.decoy_phase))
        )
        decoys = np.stack(
            [
                truth.xr + sc.decoy_offset * np.cos(ang) + truth.r * np.cos(truth.theta + dphi),
                truth.yr + sc.decoy_offset * np.sin(ang) + truth.r * np.sin(truth.theta + dphi),
            ],
            axis=-1,
        )
    c = sc.image_size / 2
    scene = build_scene(
        [st[2] for st in streams],
        truth,
        image_shape=(sc.image_size, sc.image_size),
        spot=sc.spot,
        diameter=sc.diameter,
        brightness=sc.brightness,
        noise_std=sc.noise_std,
        kappa=sc.kappa,
        background_std=sc.background_std,
        corr_length=sc.corr_length,
        n_interferers=sc.n_interferers,
        sir=sir,
        interferer_radius=sc.radius + sc.interferer_radius_offset,
        interferer_center=None if sc.interferer_centre == "object" else np.array([c, c]),
        radial_jitter=sc.interferer_jitter,
        interferer_diameter=sc.interferer_diameter,
        decoys=decoys,
        decoy_brightness=sc.decoy_gain * sc.brightness / sir,
        n_common=n_common,
        blocks=blocks,
        exposure_steps=sc.exposure_steps,
        decoy_phase=None if decoys is None else dphi[:, 0],
        compensation=sc.compensation,
        median_frames=int(np.ceil(sc.median_revolutions * sc.fps / sc.rotation_hz)),
    )
    x0 = np.stack(
        [
            truth.xr[:, 0] + sc.init_offset[0],
            truth.yr[:, 0] + sc.init_offset[1],
            sc.init_radius_factor * truth.r[:, 0],
            truth.theta[:, 0] + sc.init_phase,
            np.full(n, sc.omega0 if sc.rotating else 0.0),
        ],
        axis=1,
    )
    slope = sc.slope()
    if tracker == "loops":
        trk = RotatingGateTracker(x0, sc.gains() if gains is None else gains, slope, sc.variant, sc.rotating)
    elif tracker == "ekf":
        q = ekf_noise_from_bandwidths(ekf_meas_var, 1.0 / sc.fps, sc.radius, sc.b_xy, sc.b_r, sc.b_omega)
        P0 = np.diag([9.0, 9.0, 4.0, 0.04, 1.0])
        trk = EKFTracker(x0, P0, q, ekf_meas_var, slope)
    else:
        raise ValueError(f"parameter 'tracker' = {tracker!r}; it must be 'loops' or 'ekf'")
    noise_rng = (
        streams[0][3] if n_common == n else BlockNormal([CommonNormal(st[3], n_common) for st in streams], n_block)
    )
    hist = run_closed_loop(
        scene,
        trk,
        noise_rng,
        gate_half=sc.gate_half,
        form=sc.form,
        edge_a=sc.diameter / 2,
        noise=noise if sc.form == "quadrant" else "pixel",
        keep_full=keep_full,
        crop_callback=crop_callback,
    )
    return truth, scene, hist


def state_errors(truth: MarkerTruth, history) -> np.ndarray:
    """Estimate minus truth of a closed-loop run, phase wrapped to ``(-pi, pi]``.

    Parameters
    ----------
    truth : MarkerTruth
        Per-trial truth, arrays of shape (n, T).
    history : tvtrack.papers.p003_rotating_marker_tracker.loops.TrackHistory
        Run with ``keep_full=True`` (``history.estimate`` of shape (n, T, 5)).

    Returns
    -------
    ndarray, shape (n, T, 5)
        Errors of ``x_r, y_r, r`` (px), ``theta`` (rad) and ``omega`` (rad/s).
    """
    tr = np.stack([truth.xr, truth.yr, truth.r, truth.theta, truth.omega], axis=-1)
    e = history.estimate - tr
    e[..., 3] = np.angle(np.exp(1j * e[..., 3]))
    return e


def interference_runs(rng: np.random.Generator, n: int, sc: Scenario, sir_values, blocks=None) -> dict:
    """Batched interference runs, ``n`` trials per SIR, keeping only what loss detection needs.

    The ``n`` trials are the same at every SIR (common random numbers: motion, background,
    interferer placement, decoy and noise), so loss curves against SIR are paired, and two
    scenarios run from the same ``rng`` state (e.g. rotating and static markers) share them too.

    Parameters
    ----------
    n : int
        Trials per SIR value.
    sc : Scenario
    sir_values : array_like, shape (m,)
        Post-compensation signal-to-interference ratios.

    Returns
    -------
    dict
        ``sir`` (m n,) per-trial SIR (trials of one SIR contiguous), ``miss`` (m n, T) px,
        ``inside`` (m n, T) bool, ``gate`` (m n, T, 2) px, ``interferers`` (m n, q, 2) px,
        ``trial`` (m n,) index of the common draws (0..n-1), ``dt`` frame interval (s),
        ``omega_hat`` (m n, T) the tracker's angular-velocity estimate (rad/s), ``omega_error``
        (m n, T) its relative error against the truth (NaN for a static marker). With a list
        of generators the blocks follow each other: ``block`` (k m n,) says which generator
        (``blocks``: scene settings per generator, see :func:`build_scene`).
    """
    rngs = list(rng) if isinstance(rng, (list, tuple)) else [rng]
    m = np.asarray(sir_values, float).size
    sir = np.tile(np.repeat(np.asarray(sir_values, float), n), len(rngs))
    truth, scene, h = run_scenario(rngs, sir.size, sc, sir, keep_full=False, n_common=n, blocks=blocks)
    with np.errstate(divide="ignore", invalid="ignore"):
        omega_error = np.where(truth.omega != 0, h.omega / truth.omega - 1, np.nan).astype(np.float32)
    return dict(
        sir=sir,
        miss=h.miss,
        inside=h.inside,
        gate=h.gate,
        interferers=scene.interferers,
        omega_hat=h.omega,
        omega_error=omega_error,
        trial=np.tile(np.arange(n), m * len(rngs)),
        block=np.repeat(np.arange(len(rngs)), m * n),
        dt=1.0 / sc.fps,
    )
