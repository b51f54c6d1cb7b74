"""Energy centre of a spot in a gate, without the pull toward the gate centre.

A thresholded centroid over a fixed gate weights every noise pixel that passes the threshold;
those pixels lie uniformly over the gate, so they pull the centre toward the *gate's* middle
(``x_c = (M x_spot + N x_gate) / (M + N)`` with ``M`` the spot's and ``N`` the noise's
weight). When the gate follows the previous measurement, the measured centre becomes a lagged
low-pass of the truth and its error is neither white nor unbiased at high read noise.

:func:`windowed_centroid` removes that pull: the sums run over a window of side ``window_px``
centred on the current estimate itself, with fractional weights for the pixels the window cuts
(a "soft" window whose middle is exactly the estimate), iterated from the gate centre. The noise
then pulls toward the estimate, and the fixed point of ``x = (M x_spot + N x) / (M + N)`` is
``x_spot`` (the window also cuts the spot's wings symmetrically about it). Background and
threshold come from the gate's border as in :func:`tvtrack.measure.centroid`.

Coordinates follow :mod:`tvtrack.render`: pixel centres at integers, ``x`` = column, ``y`` = row.
"""

from __future__ import annotations

import numpy as np

from ...measure import Centroid, border_statistics
from ...render import pixel_fractions_gaussian

__all__ = ["soft_window", "windowed_centroid", "centroid_mask", "gaussian_fit_centre"]


def soft_window(centre, half: float, n: int) -> np.ndarray:
    """Per-pixel overlap of ``[centre - half, centre + half]`` with pixels ``0..n-1`` (pixel ``i``
    spans ``[i - 1/2, i + 1/2]``), in [0, 1].

    Parameters
    ----------
    centre : ndarray, shape (...)
        Window middle, px (gate coordinates).
    half : float
        Half-width, px.

    Returns
    -------
    ndarray, shape (..., n)
    """
    c = np.asarray(centre, dtype=float)[..., None]
    i = np.arange(n, dtype=float)
    return np.clip(np.minimum(i + 0.5, c + half) - np.maximum(i - 0.5, c - half), 0.0, 1.0)


def _soft_windows(centre, half: float, edges: tuple) -> np.ndarray:
    """:func:`soft_window` by the same operations on the same numbers (so the same bits), with fewer temporaries:
    ``edges`` = ``(i + 0.5, i - 0.5)`` of the pixels ``i``, and the clip to [0, 1] as a maximum then a minimum in
    place (the overlap is never -0.0, the one value where the two could differ)."""
    c = centre[..., None]
    out = np.minimum(edges[0], c + half)
    out -= np.maximum(edges[1], c - half)
    np.maximum(out, 0.0, out=out)
    return np.minimum(out, 1.0, out=out)


def windowed_centroid(
    images, origin=(0, 0), *, window_px: float, threshold_sigma: float = 3.0, n_iter: int = 4, start=None
) -> Centroid:
    """Thresholded energy centre in a soft window re-centred on the estimate (see the module text).

    Parameters
    ----------
    images : ndarray, shape (..., rows, cols)
        Gate images, DN.
    origin : array_like, shape (2,) or (..., 2)
        ``(x0, y0)`` of each gate's first pixel (full-frame coordinates are returned).
    window_px : float
        Side of the centroid window, px (at most the gate side).
    threshold_sigma : float
        Keep pixels more than this many robust border RMS above the border median.
    n_iter : int
        Re-centring steps after the first (gate-centred) one; each shrinks the pull toward the
        previous estimate by ``N / (M + N)``.
    start : array_like, shape (2,) or (..., 2), optional
        Full-frame ``(x, y)`` of the first window's middle (default: the gate centre), e.g. the predicted
        centre when the "gate" is a whole frame.

    Returns
    -------
    Centroid
        ``valid`` is False where no pixel passed the threshold in the final window.
    """
    a = np.asarray(images, dtype=float)
    rows, cols = a.shape[-2:]
    if not (0 < window_px <= min(rows, cols)):
        raise ValueError(f"parameter 'window_px' = {window_px!r}; it must be in (0, gate side = {min(rows, cols)}]")
    if not (isinstance(n_iter, (int, np.integer)) and n_iter >= 0):
        raise ValueError(f"parameter 'n_iter' = {n_iter!r}; it must be an integer >= 0")
    level, rms = border_statistics(a)
    w = a - level[..., None, None]
    w = np.where(w > (threshold_sigma * rms)[..., None, None], w, 0.0)
    batch = a.shape[:-2]
    c = np.empty((2,) + batch)  # (cx, cy): one soft window of both axes per step where the gate is square
    cx, cy = c[0, ...], c[1, ...]  # views (0-d for one image)
    cx[...], cy[...] = (cols - 1) / 2.0, (rows - 1) / 2.0
    if start is not None:
        st = np.asarray(start, dtype=float) - np.asarray(origin, dtype=float)
        cx[...], cy[...] = np.broadcast_to(st[..., 0], batch), np.broadcast_to(st[..., 1], batch)
    half = window_px / 2.0
    xs, ys = np.arange(cols, dtype=float), np.arange(rows, dtype=float)
    ex, ey = (xs + 0.5, xs - 0.5), (ys + 0.5, ys - 0.5)
    for _ in range(n_iter + 1):
        if rows == cols:
            wx, wy = _soft_windows(c, half, ex)
        else:
            wx, wy = _soft_windows(cx, half, ex), _soft_windows(cy, half, ey)
        col_sum = (wy[..., None, :] @ w)[..., 0, :]  # window-weighted column profile (matmul: BLAS, not einsum)
        row_sum = (w @ wx[..., :, None])[..., 0]
        mass = np.einsum("...c,...c->...", col_sum, wx)
        valid = mass > 0
        x_new = np.einsum("...c,c->...", col_sum * wx, xs)
        y_new = np.einsum("...r,r->...", row_sum * wy, ys)
        if valid.all():  # the usual case: np.where's numbers without its temporaries
            np.divide(x_new, mass, out=cx)
            np.divide(y_new, mass, out=cy)
        else:
            safe = np.where(valid, mass, 1.0)
            cx[...], cy[...] = np.where(valid, x_new / safe, cx), np.where(valid, y_new / safe, cy)
    o = np.asarray(origin, dtype=float)
    xy = np.stack([cx + o[..., 0], cy + o[..., 1]], axis=-1)
    return Centroid(xy=np.where(valid[..., None], xy, np.nan), mass=mass, valid=valid)


def centroid_mask(images, origin, xy, *, window_px: float, threshold_sigma: float = 3.0) -> np.ndarray:
    """Pixels that weigh in :func:`windowed_centroid`'s final step: above the threshold and inside
    the window centred on the measured centre ``xy`` (for display).

    Parameters
    ----------
    images : ndarray, shape (..., rows, cols)
    origin : array_like, shape (..., 2)
    xy : ndarray, shape (..., 2)
        Measured centres, full-frame px (NaN: empty mask).

    Returns
    -------
    ndarray of bool, shape (..., rows, cols)
    """
    a = np.asarray(images, dtype=float)
    rows, cols = a.shape[-2:]
    level, rms = border_statistics(a)
    above = a - level[..., None, None] > (threshold_sigma * rms)[..., None, None]
    c = np.asarray(xy, dtype=float) - np.asarray(origin, dtype=float)
    wx = soft_window(np.nan_to_num(c[..., 0], nan=-1e9), window_px / 2.0, cols) > 0
    wy = soft_window(np.nan_to_num(c[..., 1], nan=-1e9), window_px / 2.0, rows) > 0
    return above & wy[..., :, None] & wx[..., None, :]


def _fraction_slope(centre, sigma: float, n: int) -> np.ndarray:
    """d/dc of :func:`tvtrack.render.pixel_fractions_gaussian` (pixel centres 0..n-1), shape (..., n)."""
    c = np.asarray(centre, dtype=float)[..., None]
    i = np.arange(n, dtype=float)
    a, b = (i - 0.5 - c) / sigma, (i + 0.5 - c) / sigma
    return (np.exp(-0.5 * a * a) - np.exp(-0.5 * b * b)) / (np.sqrt(2 * np.pi) * sigma)


def gaussian_fit_centre(
    images, origin, start_xy, *, sigma_px: float, read_noise: float, gain: float = 1.0, n_iter: int = 10
) -> np.ndarray:
    """Spot centre by fitting a pixel-integrated Gaussian of known width, Poisson plus read noise.

    Model ``lambda_ij = b + F f_x(j) f_y(i)`` (``f`` the pixel fractions of
    :func:`tvtrack.render.pixel_fractions_gaussian`), parameters ``(x, y, F, b)``, fitted by
    iteratively reweighted least squares with weights ``1 / (lambda / gain + read_noise^2)`` (DN^2):
    Gauss-Newton on the Gaussian approximation of the Poisson + read-noise likelihood, the usual
    MLE for spot location (its variance approaches the Cramer-Rao bound).

    Parameters
    ----------
    images : ndarray, shape (..., rows, cols)
        Gate images, DN.
    origin : array_like, shape (..., 2)
        First pixel ``(x0, y0)`` of each gate.
    start_xy : ndarray, shape (..., 2)
        Starting centre, full-frame px (e.g. the windowed centroid).
    sigma_px : float
        Spot standard deviation, px (known).
    read_noise : float
        Read noise RMS, DN.

    Returns
    -------
    ndarray, shape (..., 2)
        Fitted centres, full-frame px.
    """
    a = np.asarray(images, dtype=float)
    rows, cols = a.shape[-2:]
    o = np.asarray(origin, dtype=float)
    x = np.asarray(start_xy, dtype=float)[..., 0] - o[..., 0]
    y = np.asarray(start_xy, dtype=float)[..., 1] - o[..., 1]
    b = border_statistics(a)[0]
    F = np.maximum((a - b[..., None, None]).sum(axis=(-2, -1)), 1.0)
    for _ in range(n_iter):
        fx, fy = pixel_fractions_gaussian(x, sigma_px, cols), pixel_fractions_gaussian(y, sigma_px, rows)
        dx, dy = _fraction_slope(x, sigma_px, cols), _fraction_slope(y, sigma_px, rows)
        shape = fy[..., :, None] * fx[..., None, :]
        lam = b[..., None, None] + F[..., None, None] * shape
        w = 1.0 / (np.maximum(lam, 1e-6) / gain + read_noise**2)
        J = np.stack(
            [
                F[..., None, None] * fy[..., :, None] * dx[..., None, :],
                F[..., None, None] * dy[..., :, None] * fx[..., None, :],
                shape,
                np.ones_like(shape),
            ],
            axis=-1,
        ).reshape(a.shape[:-2] + (rows * cols, 4))
        r = (a - lam).reshape(a.shape[:-2] + (rows * cols,))
        wf = w.reshape(r.shape)
        JtW = np.swapaxes(J, -1, -2) * wf[..., None, :]
        step = np.linalg.solve(JtW @ J + 1e-9 * np.eye(4), (JtW @ r[..., None]))[..., 0]
        x = np.clip(x + step[..., 0], 0.0, cols - 1.0)
        y = np.clip(y + step[..., 1], 0.0, rows - 1.0)
        F = np.maximum(F + step[..., 2], 1.0)
        b = b + step[..., 3]
    return np.stack([x + o[..., 0], y + o[..., 1]], axis=-1)
