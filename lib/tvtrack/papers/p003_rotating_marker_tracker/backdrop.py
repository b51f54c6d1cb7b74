"""The static part of notebook 003's compensated image: the marker
and interferer spots, the correlated background, stationary interferers on a circle about the object (its start, or
its centre at each interferer's own frame of the run), and what a temporal-median compensation, the marker masked
out, leaves (beyond the paper).

Coordinates follow :mod:`tvtrack.render`: pixel centres at integers, ``x`` = column, ``y`` = row.
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy import ndimage

from ...render import box_spot, disc_area, disc_spot
from .motion import MarkerTruth

__all__ = [
    "check_spot",
    "SPOTS",
    "LAYOUTS",
    "render_spot",
    "correlated_background",
    "place_interferers",
    "add_spots",
    "median_residual",
]


SPOTS = ("disc", "square")


def check_spot(spot: str) -> None:
    """Refuse a spot shape not in :data:`SPOTS` (``ValueError`` naming the parameter and the shapes allowed)."""
    if spot not in SPOTS:
        raise ValueError(f"parameter 'spot' = {spot!r}; it must be one of {SPOTS}")


def render_spot(spot: str, centers, shape, diameter, brightness=1.0, origin=(0, 0)) -> np.ndarray:
    """A marker or interferer spot: ``"disc"`` (diameter ``D``) or ``"square"`` (side ``D``),
    ``brightness`` per fully covered pixel; shape ``(..., rows, cols)``."""
    check_spot(spot)
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


LAYOUTS = ("even", "independent")  # interferers on the circle: equally spaced, or each at its own random angle


def place_interferers(
    rng: np.random.Generator,
    n: int,
    count: int,
    center,
    radius: float,
    radial_jitter: float = 0.0,
    layout: str = "even",
) -> np.ndarray:
    """Stationary interferers on a circle (the area swept by the marker).

    One interferer sits at a uniformly random angle; with ``layout="even"`` several are equally spaced with a
    common random angular offset (a pattern symmetric about ``center``), with ``"independent"`` each at its own
    uniformly random angle. ``radial_jitter`` > 0 draws each radius uniformly in ``[radius - jitter, radius + jitter]``.
    ``center`` (px) is one point, one per trial (shape (n, 2)), or one per trial and interferer (shape
    (n, count, 2): each interferer on its own circle, e.g. about the object's centre at its own frame of the run).

    Returns
    -------
    ndarray, shape (n, count, 2)
        Positions ``(x, y)`` in px.
    """
    if count < 0:
        raise ValueError(f"parameter 'count' = {count}; it must be >= 0")
    if layout not in LAYOUTS:
        raise ValueError(f"parameter 'layout' = {layout!r}; it must be one of {LAYOUTS}")
    if count == 0:  # no interferer, no draw: a scene without interferers is the same whatever their layout
        return np.zeros((n, 0, 2))
    if layout == "independent":
        ang = rng.uniform(0, 2 * np.pi, size=(n, count))
    else:
        ang = rng.uniform(0, 2 * np.pi, size=(n, 1)) + 2 * np.pi * np.arange(count) / max(count, 1)
    rad = radius + rng.uniform(-radial_jitter, radial_jitter, size=(n, count))
    c = np.asarray(center, dtype=float)
    c = np.broadcast_to(c if c.ndim == 3 else np.broadcast_to(c, (n, 2))[:, None, :], (n, count, 2))
    return np.stack([c[..., 0] + rad * np.cos(ang), c[..., 1] + rad * np.sin(ang)], axis=-1)


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
    """What a temporal-median background estimate leaves of a static scene, the marker masked out.

    The compensation subtracts, from every frame, the per-pixel median of the first ``n_frames`` raw frames
    ``f + interferers + s_t + n_t`` (this project's choice: a median over >= 2 revolutions), each pixel's median taken
    over the frames in which the object's own marker spot does not cover it: eq. (19) subtracts ``f``, "the scene
    without the object" (eq. (10)), so neither marker (rotating, or still at the object's centre) enters the
    estimate. The background cancels exactly, whatever its brightness; left is minus the median of the noise over the
    frames the marker left free. (Without the mask the median would erase the whole marker where it stood still for
    more than half of the frames -- a non-rotating marker on a hovering object -- and leave a faint ring where it
    swept.) The interferers are added afterwards at their post-compensation brightness ``d / SIR`` (the paper's SIR,
    l. 198; :func:`.imaging.build_scene`). The median is computed exactly inside the box the marker visits (plus a
    spot); outside it, where only noise enters, it is drawn from the sample median's normal law, variance
    ``pi sigma^2 / (2 N)``, as are the pixels the marker covers in every frame (their ``f`` is estimated from no
    frame; taken as well as elsewhere). Instant exposure, and no decoy, in the median frames.

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
    covered = render_spot(spot, np.swapaxes(m, 0, 1), (size, size), diameter, brightness, lo[None]) > 0
    noise = noise_std * rng.standard_normal(covered.shape) if noise_std > 0 else np.zeros(covered.shape)
    free = ~covered.all(axis=0)  # pixels some frame shows without the marker
    with warnings.catch_warnings():  # an all-masked pixel's median is NaN; it keeps the normal-law draw below
        warnings.simplefilter("ignore", RuntimeWarning)
        box = -np.nanmedian(np.where(covered, np.nan, noise), axis=0)
    ar = np.arange(size)
    ys, xs = lo[:, 1, None] + ar, lo[:, 0, None] + ar
    ok = ((ys >= 0) & (ys < rows))[:, :, None] & ((xs >= 0) & (xs < cols))[:, None, :] & free
    trial = np.arange(n)[:, None, None]
    yi, xi = np.clip(ys, 0, rows - 1)[:, :, None], np.clip(xs, 0, cols - 1)[:, None, :]
    out[trial, yi, xi] = np.where(ok, box, out[trial, yi, xi])
    return out
