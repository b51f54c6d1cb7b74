"""The camera of study 004 (Kokryatska and Hrynchyshyn 2005): how the laser spot is imaged (:class:`SpotCamera`) and
measured frame by frame in a gate that follows it (:func:`track_spot`). Re-exported by :mod:`.beam_wander`, whose
paths it images.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import ndtr

from ...measure import centroid
from ...render import gate_origin, sensor_readout
from .spot_centre import windowed_centroid

__all__ = ["SpotCamera", "GateTrack", "track_spot"]


@dataclass(frozen=True)
class SpotCamera:
    """How the laser spot is imaged (this project's defaults; the paper states none).

    Attributes
    ----------
    spot_sigma_px : float
        Gaussian standard deviation, px (default 4 = 1/e^2 radius 8 px).
    peak_dn : float
        Peak pixel value of the spot at intensity factor 1, DN (default 200).
    background_dn : float
        Background level, DN (default 10).
    read_noise_dn : float
        Gaussian read noise RMS, DN (default 2).
    gain_e_per_dn : float
        Electrons per DN (default 1; Poisson noise on signal + background).
    bit_depth : int
        Quantisation and saturation (default 8).
    gate_size_px : int
        Side of the square measurement gate, px, odd (default 31, about +-4 sigma).
    threshold_sigma : float
        Centroid threshold in robust border RMS above the border median (default 3).
    centroid_mode : {"windowed", "gate"}
        ``"windowed"`` (default): :func:`tvtrack.papers.p004_laser_spot_prediction.spot_centre.windowed_centroid`, a soft
        window of ``centroid_window_px`` re-centred on the estimate (no pull toward the gate
        centre); ``"gate"``: the thresholded centroid over the whole gate
        (:func:`tvtrack.measure.centroid`), whose noise pixels pull the centre toward the previous
        measurement at high read noise (kept to show that bias).
    centroid_window_px : float or None
        Side of the windowed centroid's window, px; ``None`` (default) = 2/3 of the gate (21 px in
        the 31 px gate: about +-2.6 spot sigma, and the gate's remaining +-5 px leave room for the
        one-frame motion).
    """

    spot_sigma_px: float = 4.0
    peak_dn: float = 200.0
    background_dn: float = 10.0
    read_noise_dn: float = 2.0
    gain_e_per_dn: float = 1.0
    bit_depth: int = 8
    gate_size_px: int = 31
    threshold_sigma: float = 3.0
    centroid_mode: str = "windowed"
    centroid_window_px: float | None = None

    def __post_init__(self):
        checks = [
            ("centroid_mode", self.centroid_mode, self.centroid_mode in ("windowed", "gate"), "'windowed' or 'gate'"),
            (
                "centroid_window_px",
                self.centroid_window_px,
                self.centroid_window_px is None or 0 < self.centroid_window_px <= self.gate_size_px,
                f"None or in (0, gate_size_px = {self.gate_size_px}]",
            ),
            ("spot_sigma_px", self.spot_sigma_px, 0 < self.spot_sigma_px <= 32, "in (0, 32]"),
            ("peak_dn", self.peak_dn, self.peak_dn > 0, "> 0"),
            ("background_dn", self.background_dn, self.background_dn >= 0, ">= 0"),
            ("read_noise_dn", self.read_noise_dn, self.read_noise_dn >= 0, ">= 0"),
            ("gain_e_per_dn", self.gain_e_per_dn, self.gain_e_per_dn > 0, "> 0"),
            ("bit_depth", self.bit_depth, 1 <= self.bit_depth <= 16, "in [1, 16]"),
            (
                "gate_size_px",
                self.gate_size_px,
                self.gate_size_px >= 5 and self.gate_size_px % 2 == 1,
                "an odd integer >= 5",
            ),
            ("threshold_sigma", self.threshold_sigma, self.threshold_sigma >= 0, ">= 0"),
        ]
        for name, value, ok, allowed in checks:
            if not ok:
                raise ValueError(f"parameter {name!r} = {value!r}; it must be {allowed}")

    @property
    def window_px(self) -> float:
        """Side of the windowed centroid's window, px."""
        return 2.0 * self.gate_size_px / 3.0 if self.centroid_window_px is None else float(self.centroid_window_px)

    @property
    def flux_e(self) -> float:
        """Total spot signal at intensity 1, electrons (``2 pi sigma^2 peak gain``)."""
        return 2 * np.pi * self.spot_sigma_px**2 * self.peak_dn * self.gain_e_per_dn


@dataclass(frozen=True)
class GateTrack:
    """Result of :func:`track_spot`.

    Attributes
    ----------
    xy : ndarray, shape (..., T, 2)
        Measured energy centres, px (NaN where nothing passed the threshold).
    origin : ndarray of int64, shape (..., T, 2)
        First pixel ``(x0, y0)`` of each frame's gate.
    gates : ndarray or None, shape (T, rows, cols)
        Gate images (DN) of the batch element ``keep``, if asked for.
    clipped : ndarray of bool or None, shape (..., T)
        Whether the gate held a pixel at the sensor's full scale (``2**bit_depth - 1``): saturation.
    """

    xy: np.ndarray
    origin: np.ndarray
    gates: np.ndarray | None
    clipped: np.ndarray | None = None


def _gate_signal(centres, origin, g: int, sigma: float, flux) -> np.ndarray:
    """``gaussian_spot(centres, (g, g), sigma, flux, origin=origin)`` for integer origins, with the same numbers:
    a pixel's upper edge is the next pixel's lower edge exactly (half-integers), so the normal CDF is taken once
    per edge (``g + 1``) instead of twice per pixel."""
    c = np.asarray(centres, dtype=float)
    edges = np.asarray(origin, dtype=float)[..., None] + np.arange(g + 1) - 0.5  # (..., 2, g + 1)
    cdf = ndtr((edges - c[..., None]) / sigma)
    f = cdf[..., 1:] - cdf[..., :-1]  # (..., 2, g): x then y fractions
    return np.asarray(flux, dtype=float)[..., None, None] * f[..., 1, :, None] * f[..., 0, None, :]


def track_spot(
    centres_px,
    intensity,
    rng: np.random.Generator,
    camera: SpotCamera = SpotCamera(),
    image_size_px: int = 128,
    keep: tuple | None = None,
) -> GateTrack:
    """Render each frame's gate crop and measure the spot's energy centre, frame by frame.

    The gate of frame ``n`` is centred on the centre measured in frame ``n-1`` (frame 0: on the
    true centre, i.e. after acquisition) and kept inside the sensor. Only the gate's pixels
    are rendered (pixel-integrated Gaussian), read out with Poisson + read noise, quantised to
    ``bit_depth``, and measured by ``camera.centroid_mode`` (border-median background,
    ``threshold_sigma`` robust RMS threshold; by default a window re-centred on the estimate).

    Parameters
    ----------
    centres_px : ndarray, shape (..., T, 2)
        True centres, px (any leading batch axes, e.g. (trials, paths)).
    intensity : ndarray, shape (..., T)
        Total-intensity factor per frame.
    rng : numpy.random.Generator
    camera : SpotCamera
    image_size_px : int
        Sensor side, px.
    keep : tuple of int, optional
        Index into the batch axes whose gate images to return.

    Returns
    -------
    GateTrack
    """
    c = np.asarray(centres_px, dtype=float)
    inten = np.broadcast_to(np.asarray(intensity, dtype=float), c.shape[:-1])
    g = camera.gate_size_px
    if g > image_size_px:
        raise ValueError(f"parameter 'gate_size_px' = {g}; it must be <= image_size_px = {image_size_px}")
    T = c.shape[-2]
    xy = np.full(c.shape, np.nan)
    origin = np.zeros(c.shape, dtype=np.int64)
    gates = None if keep is None else np.empty((T, g, g))
    clipped = np.zeros(c.shape[:-1], dtype=bool)
    full_scale = 2**camera.bit_depth - 1
    flux = camera.flux_e * inten  # each frame's factor as gaussian_spot computes it
    aim = c[..., 0, :]
    for t in range(T):
        o = np.minimum(np.maximum(gate_origin(aim, (g, g)), 0), image_size_px - g)  # np.clip's integers
        signal = _gate_signal(c[..., t, :], o, g, camera.spot_sigma_px, flux[..., t])
        img = sensor_readout(
            signal,
            rng,
            background=camera.background_dn * camera.gain_e_per_dn,
            photon_noise=True,
            read_noise=camera.read_noise_dn * camera.gain_e_per_dn,
            gain=camera.gain_e_per_dn,
            bit_depth=camera.bit_depth,
        )
        if camera.centroid_mode == "windowed":
            m = windowed_centroid(img, o, window_px=camera.window_px, threshold_sigma=camera.threshold_sigma)
        else:
            m = centroid(img, o, background="border", threshold_sigma=camera.threshold_sigma)
        xy[..., t, :] = m.xy
        origin[..., t, :] = o
        clipped[..., t] = img.max(axis=(-2, -1)) >= full_scale
        if keep is not None:
            gates[t] = img[keep]
        aim = np.where(m.valid[..., None], m.xy, aim)  # a lost frame keeps the old gate
    return GateTrack(xy, origin, gates, clipped)
