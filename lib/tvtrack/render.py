"""Rendering scenes on a pixel grid, and the sensor read-out.

Pixel convention (used everywhere in tvtrack): pixel ``(row v, col u)`` has its centre at
``(x, y) = (u, v)`` and spans ``[u-1/2, u+1/2] x [v-1/2, v+1/2]``; ``x`` is the column and
``y`` the row coordinate, both in pixels. A window of ``shape = (rows, cols)`` whose first pixel
is ``origin = (x0, y0)`` covers pixels ``x0..x0+cols-1`` and ``y0..y0+rows-1``; a gate crop is
such a window, so rendering only the gate costs only the gate's pixels.

Spots are *pixel-integrated*: each pixel receives the integral of the profile over its area
(separable differences of the normal CDF for a Gaussian, of clipped ramps for a uniform box,
an edge ramp across the rim of a uniform disc), never a point sample, so centroids and Cramer-Rao bounds are those of a real sensor.
All functions broadcast over leading batch axes, e.g. ``(n_trials, n_frames)``.
"""

from __future__ import annotations

import numpy as np
from scipy.special import ndtr

__all__ = [
    "pixel_fractions_gaussian",
    "pixel_fractions_box",
    "gaussian_spot",
    "box_spot",
    "disc_spot",
    "disc_area",
    "gate_origin",
    "sensor_readout",
]


def _pixel_edges(n: int, origin) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper pixel edges, shape (..., n), for windows starting at ``origin`` (...)."""
    centres = np.asarray(origin, dtype=float)[..., None] + np.arange(n)
    return centres - 0.5, centres + 0.5


def pixel_fractions_gaussian(center, sigma, n: int, origin=0) -> np.ndarray:
    """Fraction of a 1-D Gaussian's mass falling in each of ``n`` pixels.

    Parameters
    ----------
    center : array_like, shape (...)
        Profile centre in pixels.
    sigma : float or array_like broadcastable to ``center``
        Standard deviation in pixels (> 0).
    n : int
        Number of pixels.
    origin : int or array_like, shape (...)
        Coordinate of the first pixel's centre.

    Returns
    -------
    ndarray, shape (..., n)
        ``Phi((edge_hi - c)/sigma) - Phi((edge_lo - c)/sigma)``; sums to the in-window mass.
    """
    c = np.asarray(center, dtype=float)[..., None]
    s = np.asarray(sigma, dtype=float)[..., None]
    lo, hi = _pixel_edges(n, origin)
    return ndtr((hi - c) / s) - ndtr((lo - c) / s)


def pixel_fractions_box(center, half_width, n: int, origin=0) -> np.ndarray:
    """Fraction of a uniform 1-D box ``[c - a, c + a]`` falling in each of ``n`` pixels.

    Returns
    -------
    ndarray, shape (..., n)
        Overlap length of the box with each pixel divided by ``2a``.
    """
    c = np.asarray(center, dtype=float)[..., None]
    a = np.asarray(half_width, dtype=float)[..., None]
    lo, hi = _pixel_edges(n, origin)
    overlap = np.clip(np.minimum(hi, c + a) - np.maximum(lo, c - a), 0.0, None)
    return overlap / (2 * a)


def _separable(fx: np.ndarray, fy: np.ndarray, flux) -> np.ndarray:
    flux = np.asarray(flux, dtype=float)[..., None, None]
    return flux * fy[..., :, None] * fx[..., None, :]


def gaussian_spot(centers, shape, sigma, flux=1.0, origin=(0, 0)) -> np.ndarray:
    """Expected signal of a circular Gaussian spot integrated over square pixels.

    Parameters
    ----------
    centers : array_like, shape (..., 2)
        Spot centres ``(x, y)`` in pixels.
    shape : (int, int)
        Window size ``(rows, cols)``.
    sigma : float or array_like, shape (...)
        Gaussian standard deviation in pixels (for a 1/e^2 radius ``w``, ``sigma = w/2``).
    flux : float or array_like, shape (...)
        Total signal of the spot (photo-electrons or digital numbers), integrated over the plane.
        A peak *pixel* value ``A`` for a spot much wider than a pixel is ``flux = 2 pi sigma^2 A``.
    origin : array_like, shape (2,) or (..., 2)
        ``(x0, y0)``: coordinates of the window's first pixel centre (integers for gate crops).

    Returns
    -------
    ndarray, shape (..., rows, cols)
    """
    c = np.asarray(centers, dtype=float)
    o = np.asarray(origin, dtype=float)
    rows, cols = shape
    fx = pixel_fractions_gaussian(c[..., 0], sigma, cols, o[..., 0])
    fy = pixel_fractions_gaussian(c[..., 1], sigma, rows, o[..., 1])
    return _separable(fx, fy, flux)


def box_spot(centers, shape, half_size, flux=1.0, origin=(0, 0)) -> np.ndarray:
    """Expected signal of a uniform square (or rectangular) spot integrated over pixels.

    Parameters
    ----------
    centers : array_like, shape (..., 2)
        Spot centres ``(x, y)`` in pixels.
    shape : (int, int)
        Window size ``(rows, cols)``.
    half_size : float or array_like, shape (2,)
        Half side lengths ``(ax, ay)`` in pixels.
    flux : float or array_like, shape (...)
        Total signal of the spot.
    origin : array_like, shape (2,) or (..., 2)
        Coordinates of the window's first pixel centre.

    Returns
    -------
    ndarray, shape (..., rows, cols)
    """
    c = np.asarray(centers, dtype=float)
    o = np.asarray(origin, dtype=float)
    a = np.broadcast_to(np.asarray(half_size, dtype=float), (2,))
    rows, cols = shape
    fx = pixel_fractions_box(c[..., 0], a[0], cols, o[..., 0])
    fy = pixel_fractions_box(c[..., 1], a[1], rows, o[..., 1])
    return _separable(fx, fy, flux)


def disc_spot(centers, shape, diameter, flux=1.0, origin=(0, 0), dtype=np.float64) -> np.ndarray:
    """Expected signal of a uniform round spot (disc) integrated over square pixels.

    The covered fraction of a pixel whose centre lies at distance ``rho`` from the disc centre
    is approximated by ``clip(R + 1/2 - rho, 0, 1)``, ``R = diameter / 2`` (a unit-width ramp
    across the rim): exact for pixels wholly inside or outside, within a few percent of a pixel
    on the rim. The summed signal of a disc wholly inside the window equals ``flux`` within 5 %
    for ``diameter >= 4`` px and within 1 % for ``diameter >= 8`` px, at any sub-pixel position; a disc centred on a pixel centre, a pixel edge or a pixel
    corner has its centroid exactly at its centre (the coverage is symmetric).

    Parameters
    ----------
    centers : array_like, shape (..., 2)
        Disc centres ``(x, y)`` in pixels.
    shape : (int, int)
        Window size ``(rows, cols)``.
    diameter : float
        Disc diameter ``D`` in pixels (> 0).
    flux : float or array_like, shape (...)
        Total signal of the disc integrated over the plane; a fully covered pixel receives
        ``flux / (pi R^2)``.
    origin : array_like, shape (2,) or (..., 2)
        ``(x0, y0)``: coordinates of the window's first pixel centre.
    dtype : numpy float type
        Arithmetic and output precision (``np.float32`` halves the cost of large batches).

    Returns
    -------
    ndarray, shape (..., rows, cols)
    """
    if not diameter > 0:
        raise ValueError(f"parameter 'diameter' = {diameter}; it must be > 0")
    c = np.asarray(centers, dtype=float)
    o = np.asarray(origin, dtype=float)
    rows, cols = shape
    dx = (o[..., 0, None] + np.arange(cols) - c[..., 0, None]).astype(dtype)
    dy = (o[..., 1, None] + np.arange(rows) - c[..., 1, None]).astype(dtype)
    cover = np.square(dx)[..., None, :] + np.square(dy)[..., :, None]
    np.sqrt(cover, out=cover)
    np.subtract(dtype(diameter / 2 + 0.5), cover, out=cover)
    np.maximum(cover, 0.0, out=cover)  # clip in place, without np.clip's per-call overhead (same numbers)
    np.minimum(cover, 1.0, out=cover)
    cover *= (np.asarray(flux, dtype=float) / disc_area(diameter)).astype(dtype)[..., None, None]
    return cover


def disc_area(diameter) -> float:
    """Area ``pi D^2 / 4`` (px^2) of a disc of diameter ``D`` (px): the flux of a disc whose fully
    covered pixels read 1 (see :func:`disc_spot`)."""
    return np.pi * (diameter / 2) ** 2


def gate_origin(centers, size) -> np.ndarray:
    """Integer first-pixel coordinates of gates of ``size = (rows, cols)`` centred on ``centers``.

    Parameters
    ----------
    centers : array_like, shape (..., 2)
        Gate centres ``(x, y)`` in pixels.

    Returns
    -------
    ndarray of int64, shape (..., 2)
        ``(x0, y0)`` such that the gate covers ``x0..x0+cols-1``, ``y0..y0+rows-1`` and its
        middle is the pixel nearest the centre (for even sizes, the centre lies in the
        middle two pixels).
    """
    c = np.asarray(centers, dtype=float)
    rows, cols = size
    half = np.array([(cols - 1) / 2.0, (rows - 1) / 2.0])
    return np.floor(c - half + 0.5).astype(np.int64)


def sensor_readout(
    signal,
    rng: np.random.Generator,
    *,
    background: float = 0.0,
    photon_noise: bool = True,
    read_noise: float = 0.0,
    gain: float = 1.0,
    bit_depth: int | None = None,
) -> np.ndarray:
    """Turn expected signal into a sensor reading.

    Parameters
    ----------
    signal : ndarray
        Expected photo-electrons per pixel from the scene (any shape).
    rng : numpy.random.Generator
        The run's generator.
    background : float
        Expected background photo-electrons per pixel, added before noise.
    photon_noise : bool
        Draw Poisson photon counts (shot noise); otherwise use the expectation.
    read_noise : float
        Gaussian read noise, RMS in electrons (>= 0).
    gain : float
        Electrons per digital number (> 0).
    bit_depth : int, optional
        If given, round to integers and clip to ``[0, 2**bit_depth - 1]`` (saturation);
        otherwise return real values in digital numbers.

    Returns
    -------
    ndarray, same shape as ``signal``
        Digital numbers (float64; integer-valued when ``bit_depth`` is given).
    """
    if read_noise < 0:
        raise ValueError(f"read_noise = {read_noise} must be >= 0")
    if gain <= 0:
        raise ValueError(f"gain = {gain} must be > 0")
    electrons = np.asarray(signal, dtype=float) + background
    if photon_noise:
        electrons = rng.poisson(electrons).astype(float)
    out = electrons if isinstance(electrons, np.ndarray) else None  # a new array: the steps below work in place
    if read_noise > 0:
        electrons = np.add(electrons, rng.normal(0.0, read_noise, size=np.shape(electrons)), out=out)
    dn = np.divide(electrons, gain, out=out)
    if bit_depth is not None:
        dn = np.clip(np.rint(dn, out=out), 0, 2**bit_depth - 1, out=out)
    return dn
