"""Photon-counting CCD scene: ``Q`` point objects in linear motion seen through a Gaussian PSF.

Model (Savanevich 1999, eqs. (1)-(2), with eq. (2) normalised here so that it integrates to 1):
object ``j`` sits at ``(x_j(t), y_j(t)) = (x0_j + Vx_j t, y0_j + Vy_j t)``; each of its photons
lands at a point drawn from the circular normal ``N((x_j(t), y_j(t)), sigma^2 I)``; noise photons
land uniformly over the window. A pixel counts the photons that land inside it, so the expected
count of pixel ``(row k, col i)`` in frame ``l`` is ``m * sum_j F_xji F_yjk + b`` with the
pixel-integrated fractions ``F`` of :func:`tvtrack.render.pixel_fractions_gaussian`.

Units and conventions: lengths are in *pixels* (pixel centres at integers, ``x`` = column,
``y`` = row, window origin at pixel ``(0, 0)``), times in frames (``t_l = l``, ``l = 0..T-1``).
A motion state is ``theta = (x0, y0, Vx, Vy)``: position at ``t = 0`` (px) and velocity (px/frame).
Arrays carry trials on the leading axis: ``theta`` is ``(n_trials, Q, 4)``, counts are
``(n_trials, T, rows, cols)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator

import numpy as np

from tvtrack.render import gaussian_spot

from ._photon_kernel import add_photons

__all__ = [
    "SceneGeometry",
    "scene_geometry",
    "draw_truth",
    "designate",
    "frame_times",
    "pixel_probabilities",
    "simulate_counts",
    "scene_batches",
    "SceneBatch",
    "mixture_weights",
    "noise_per_pixel",
]


@dataclass(frozen=True)
class SceneGeometry:
    """A fixed window and a reference truth shared by all trials of one configuration.

    Attributes
    ----------
    theta : ndarray, shape (Q, 4)
        Reference motion states ``(x0, y0, Vx, Vy)`` in px and px/frame; trials add a random
        sub-pixel phase (see :func:`draw_truth`).
    shape : (int, int)
        Window ``(rows, cols)``; it holds every trajectory plus ``margin`` on each side, for
        any phase in ``[0, 1)`` px.
    sigma_px : float
        PSF standard deviation in px.
    """

    theta: np.ndarray
    shape: tuple[int, int]
    sigma_px: float

    @property
    def n_pixels(self) -> int:
        return int(self.shape[0] * self.shape[1])


def frame_times(n_frames: int) -> np.ndarray:
    """Frame times ``t_l = l`` (frames), shape (T,)."""
    if n_frames < 1:
        raise ValueError(f"n_frames = {n_frames} must be >= 1")
    return np.arange(n_frames, dtype=float)


def scene_geometry(
    n_objects: int,
    n_frames: int,
    separation_sigma: float,
    pixel_over_sigma: float,
    velocity_sigma=(0.2, 0.1),
    margin_sigma: float = 6.0,
) -> SceneGeometry:
    """Reference truth and window for ``Q`` objects on parallel tracks separated along ``y``.

    Parameters
    ----------
    n_objects : int
        ``Q`` >= 1; object ``j`` starts ``j * separation`` below object 0 (along +y).
    n_frames : int
        ``T`` >= 1.
    separation_sigma : float
        Separation ``d / sigma`` between neighbouring objects (>= 0).
    pixel_over_sigma : float
        Pixel size ``Delta / sigma`` (> 0); the PSF is ``sigma_px = 1 / pixel_over_sigma`` px.
    velocity_sigma : (float, float)
        Common velocity ``(Vx, Vy)`` in sigma per frame.
    margin_sigma : float
        Empty border around all trajectories, in sigma (>= 0).
    """
    if n_objects < 1:
        raise ValueError(f"n_objects = {n_objects} must be >= 1")
    if separation_sigma < 0:
        raise ValueError(f"separation_sigma = {separation_sigma} must be >= 0")
    if pixel_over_sigma <= 0:
        raise ValueError(f"pixel_over_sigma = {pixel_over_sigma} must be > 0")
    if margin_sigma < 0:
        raise ValueError(f"margin_sigma = {margin_sigma} must be >= 0")
    times = frame_times(n_frames)
    s = 1.0 / pixel_over_sigma
    v = np.asarray(velocity_sigma, dtype=float) * s
    start = np.zeros((n_objects, 2))
    start[:, 1] = np.arange(n_objects) * separation_sigma * s
    ends = start[None] + times[:, None, None] * v  # (T, Q, 2)
    lo = ends.min(axis=(0, 1))
    hi = ends.max(axis=(0, 1))
    pad = margin_sigma * s
    start = start - lo + pad - 0.5  # window edge at -0.5 px
    span = hi - lo + 2 * pad + 1.0  # +1 px for the phase
    cols, rows = (int(np.ceil(w)) for w in span)
    theta = np.concatenate([start, np.broadcast_to(v, (n_objects, 2))], axis=1)
    return SceneGeometry(theta=theta, shape=(rows, cols), sigma_px=s)


def draw_truth(rng: np.random.Generator, n_trials: int, geometry: SceneGeometry) -> np.ndarray:
    """Per-trial truth: the reference states shifted by one uniform sub-pixel phase per trial.

    Returns
    -------
    ndarray, shape (n_trials, Q, 4)
    """
    if n_trials < 1:
        raise ValueError(f"n_trials = {n_trials} must be >= 1")
    theta = np.repeat(geometry.theta[None], n_trials, axis=0)
    theta[..., :2] += rng.uniform(0.0, 1.0, size=(n_trials, 1, 2))
    return theta


def designate(rng: np.random.Generator, truth, position_sd_px: float, velocity_sd_px: float = 0.0) -> np.ndarray:
    """Target designation: the truth plus independent Gaussian errors per coordinate.

    Parameters
    ----------
    truth : ndarray, shape (n_trials, Q, 4)
    position_sd_px, velocity_sd_px : float
        Error standard deviations in px and px/frame (>= 0).
    """
    if position_sd_px < 0:
        raise ValueError(f"position_sd_px = {position_sd_px} must be >= 0")
    if velocity_sd_px < 0:
        raise ValueError(f"velocity_sd_px = {velocity_sd_px} must be >= 0")
    truth = np.asarray(truth, dtype=float)
    sd = np.array([position_sd_px, position_sd_px, velocity_sd_px, velocity_sd_px])
    return truth + rng.normal(size=truth.shape) * sd


def mixture_weights(photons: float, noise_per_pixel: float, n_pixels: int, n_objects: int):
    """Relative weights of eq. (2), normalised here: ``p_j = m / (Q m + b M)``,
    ``p_o = b M / (Q m + b M)``.

    Returns
    -------
    p : ndarray, shape (Q,)
    p_noise : float
    """
    if photons < 0 or noise_per_pixel < 0 or photons * n_objects + noise_per_pixel <= 0:
        raise ValueError(f"photons = {photons} and noise_per_pixel = {noise_per_pixel} must be >= 0, not both zero")
    total = n_objects * photons + noise_per_pixel * n_pixels
    return np.full(n_objects, photons / total), noise_per_pixel * n_pixels / total


def noise_per_pixel(noise_density: float, sigma_px: float) -> float:
    """Mean noise photons per pixel per frame: the density (photons per sigma^2 per frame) times the pixel's area
    in sigma^2, ``(Delta / sigma)^2 = 1 / sigma_px^2``.

    Parameters
    ----------
    noise_density : float
        Uniform noise photons per sigma^2 per frame (>= 0; the paper gives none; this project's default is
        rho_o = 0.01).
    sigma_px : float
        PSF standard deviation in px (> 0), i.e. ``sigma / Delta``.
    """
    if noise_density < 0 or not sigma_px > 0:
        raise ValueError(f"noise_density = {noise_density} must be >= 0 and sigma_px = {sigma_px} > 0")
    return float(noise_density) / float(sigma_px) ** 2


def _positions(theta, times) -> np.ndarray:
    """Object positions ``(..., T, Q, 2)`` from states ``(..., Q, 4)`` and times (T,)."""
    theta = np.asarray(theta, dtype=float)
    t = np.asarray(times, dtype=float)[:, None, None]
    return theta[..., None, :, :2] + t * theta[..., None, :, 2:]


def pixel_probabilities(theta, times, shape, sigma_px) -> np.ndarray:
    """Probability that a photon of object ``j`` lands in each pixel of each frame (U1).

    Returns
    -------
    ndarray, shape (..., Q, T, rows, cols)
        ``F_xji F_yjk``; summed over the pixels it gives the object's in-window PSF mass.
    """
    pos = np.moveaxis(_positions(theta, times), -2, -3)  # (..., Q, T, 2)
    return gaussian_spot(pos, shape, sigma_px)


def simulate_counts(
    rng: np.random.Generator,
    theta,
    times,
    shape,
    sigma_px: float,
    photons: float,
    noise_per_pixel: float,
    photon_model: str = "fixed",
) -> np.ndarray:
    """Photon counts of every pixel of every frame.

    Parameters
    ----------
    theta : ndarray, shape (n_trials, Q, 4)
        True states (px, px/frame).
    times : ndarray, shape (T,)
    shape : (int, int)
        Window (rows, cols).
    sigma_px : float
        PSF standard deviation (px, > 0).
    photons : float
        ``m_k``: target photons per object per frame (>= 0; an integer for ``"fixed"``).
    noise_per_pixel : float
        Mean noise photons per pixel per frame (>= 0); uniform noise photons are a Poisson count
        of ``noise_per_pixel * M`` per frame spread uniformly, i.e. independent Poisson per pixel.
    photon_model : {"fixed", "poisson"}
        ``"fixed"``: each object emits exactly ``photons`` photons per frame, each histogrammed
        at its Gaussian landing point (photons outside the window are lost);
        ``"poisson"``: the count per object is Poisson(``photons``).

    Returns
    -------
    ndarray of int32, shape (n_trials, T, rows, cols)
    """
    if sigma_px <= 0:
        raise ValueError(f"sigma_px = {sigma_px} must be > 0")
    if photons < 0:
        raise ValueError(f"photons = {photons} must be >= 0")
    if noise_per_pixel < 0:
        raise ValueError(f"noise_per_pixel = {noise_per_pixel} must be >= 0")
    if photon_model not in ("fixed", "poisson"):
        raise ValueError(f"photon_model = {photon_model!r} must be 'fixed' or 'poisson'")
    if photon_model == "fixed" and photons != int(photons):
        raise ValueError(f"photons = {photons} must be an integer for photon_model 'fixed'")
    theta = np.asarray(theta, dtype=float)
    n_trials, n_obj = theta.shape[:2]
    rows, cols = shape
    n_frames = len(times)
    counts = rng.poisson(noise_per_pixel, size=(n_trials, n_frames, rows, cols)).astype(np.int32)
    if photons == 0:
        return counts
    pos = _positions(theta, times)  # (N, T, Q, 2)
    if photon_model == "fixed":
        k, m = None, int(photons)
    else:
        k = rng.poisson(photons, size=(n_trials, n_frames, n_obj))
        m = int(k.max()) if k.size else 0
    # each photon at pos + sigma z, counted in the nearest pixel (the first k of the m drawn per object and frame)
    add_photons(counts, pos, rng.normal(size=(n_trials, n_frames, n_obj, m, 2)), sigma_px, k)
    return counts


@dataclass(frozen=True)
class SceneBatch:
    """One batch of trials: truth (n, Q, 4), designation (n, Q, 4), counts (n, T, rows, cols)."""

    truth: np.ndarray
    designation: np.ndarray
    counts: np.ndarray


def scene_batches(
    rng: np.random.Generator,
    geometry: SceneGeometry,
    n_trials: int,
    n_frames: int,
    photons: float,
    noise_per_pixel: float,
    designation_sd_px: float,
    designation_velocity_sd_px: float = 0.0,
    photon_model: str = "fixed",
    batch_size: int = 256,
) -> Iterator[SceneBatch]:
    """Generate ``n_trials`` trials in batches of at most ``batch_size`` (bounded memory).

    All draws come from ``rng`` in batch order, so the same seed gives the same trials.
    """
    if batch_size < 1:
        raise ValueError(f"batch_size = {batch_size} must be >= 1")
    times = frame_times(n_frames)
    done = 0
    while done < n_trials:
        n = min(batch_size, n_trials - done)
        truth = draw_truth(rng, n, geometry)
        desig = designate(rng, truth, designation_sd_px, designation_velocity_sd_px)
        counts = simulate_counts(
            rng, truth, times, geometry.shape, geometry.sigma_px, photons, noise_per_pixel, photon_model
        )
        yield SceneBatch(truth, desig, counts)
        done += n
