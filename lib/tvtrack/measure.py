"""Measuring inside gates (strobes): crops and energy centres.

Coordinates follow :mod:`tvtrack.render`: pixel centres at integers, ``x`` = column, ``y`` = row.
Everything is batched over leading axes, e.g. ``(n_trials, n_frames, rows, cols)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["gate_crop_size", "crop", "border_statistics", "Centroid", "centroid"]


def gate_crop_size(gate_half: float) -> int:
    """Side (px) of the square crop that holds a gate ``[c - A, c + A]`` at any sub-pixel
    position: ``ceil(2 A) + 2``."""
    return int(np.ceil(2 * gate_half)) + 2


def crop(images, origin, size) -> np.ndarray:
    """Cut gates of ``size = (rows, cols)`` out of full frames.

    Parameters
    ----------
    images : ndarray, shape (..., H, W)
    origin : array_like of int, shape (..., 2)
        ``(x0, y0)`` of each gate's first pixel (see :func:`tvtrack.render.gate_origin`).
        A gate that would leave the frame is shifted back inside it, so a crop always has
        the full size; shift the reported origin the same way with :func:`numpy.clip`.

    Returns
    -------
    ndarray, shape (..., rows, cols)
    """
    images = np.asarray(images)
    rows, cols = size
    H, W = images.shape[-2:]
    if rows > H or cols > W:
        raise ValueError(f"gate size {size} exceeds the frame {(H, W)}")
    o = np.asarray(origin, dtype=np.int64)
    x0 = np.clip(o[..., 0], 0, W - cols)
    y0 = np.clip(o[..., 1], 0, H - rows)
    batch = images.shape[:-2]
    x0 = np.broadcast_to(x0, batch)
    y0 = np.broadcast_to(y0, batch)
    yy = y0[..., None, None] + np.arange(rows)[:, None]
    xx = x0[..., None, None] + np.arange(cols)[None, :]
    idx = np.indices(batch, sparse=True)
    return images[tuple(i[..., None, None] for i in idx) + (yy, xx)]


def border_statistics(images) -> tuple[np.ndarray, np.ndarray]:
    """Median and robust RMS (1.4826 x median absolute deviation) of each image's border pixels.

    Returns
    -------
    median, rms : ndarray, shape (...)
    """
    a = np.asarray(images, dtype=float)
    border = np.concatenate([a[..., 0, :], a[..., -1, :], a[..., 1:-1, 0], a[..., 1:-1, -1]], axis=-1)
    med = _median_last(border)
    rms = 1.4826 * _median_last(np.abs(border - med[..., None]))
    return med, rms


def _median_last(x: np.ndarray) -> np.ndarray:
    """``np.median(x, axis=-1)`` with the same numbers (the middle order statistic, or the mean ``(a + b) / 2`` of
    the middle two, as NumPy computes it), without its per-call overhead: a tracking loop takes two medians per
    frame. Rows holding NaN, and empty rows, go to ``np.median`` itself."""
    n = x.shape[-1]
    if n == 0 or np.isnan(x).any():
        return np.median(x, axis=-1)
    h = n // 2
    s = np.sort(x, axis=-1)  # the order statistics np.median's partition finds (a sort is faster on a gate's border)
    return s[..., h] if n % 2 else (s[..., h - 1] + s[..., h]) / 2


@dataclass(frozen=True)
class Centroid:
    """Energy centres of a batch of images.

    Attributes
    ----------
    xy : ndarray, shape (..., 2)
        Intensity-weighted centre ``(x, y)`` in pixels (full-frame coordinates when an origin
        was given); NaN where ``valid`` is False.
    mass : ndarray, shape (...)
        Sum of the weights (background-subtracted, thresholded intensity).
    valid : ndarray of bool, shape (...)
        False where no pixel survived the threshold (nothing to measure).
    """

    xy: np.ndarray
    mass: np.ndarray
    valid: np.ndarray


def centroid(
    images, origin=(0, 0), *, background="border", threshold_sigma: float | None = None, threshold: float | None = None
) -> Centroid:
    """Energy centre (intensity-weighted centroid) of each image or gate crop.

    Parameters
    ----------
    images : ndarray, shape (..., rows, cols)
    origin : array_like, shape (2,) or (..., 2)
        ``(x0, y0)`` of the first pixel, to return full-frame coordinates.
    background : "border", float, array_like (...) or None
        Subtracted before weighting: ``"border"`` = median of each image's border pixels,
        a number or per-image array = that level, ``None`` = nothing subtracted.
    threshold_sigma : float, optional
        Keep only pixels more than this many robust border RMS above the background.
    threshold : float, optional
        Keep only pixels whose background-subtracted value exceeds this (digital numbers).
        Pixels not kept, and negative residuals, get zero weight.

    Returns
    -------
    Centroid
    """
    a = np.asarray(images, dtype=float)
    rows, cols = a.shape[-2:]
    if isinstance(background, str):
        if background != "border":
            raise ValueError(f"background = {background!r}; use 'border', a number or None")
        level, rms = border_statistics(a)
    else:
        level = (
            np.zeros(a.shape[:-2])
            if background is None
            else np.broadcast_to(np.asarray(background, dtype=float), a.shape[:-2])
        )
        rms = border_statistics(a)[1] if threshold_sigma is not None else None
    w = a - np.asarray(level)[..., None, None]
    cut = np.zeros(a.shape[:-2])
    if threshold_sigma is not None:
        cut = np.maximum(cut, threshold_sigma * rms)
    if threshold is not None:
        cut = np.maximum(cut, threshold)
    w = np.where(w > cut[..., None, None], w, 0.0)
    mass = w.sum(axis=(-2, -1))
    valid = mass > 0
    safe = np.where(valid, mass, 1.0)
    o = np.asarray(origin, dtype=float)
    x = (w.sum(axis=-2) @ np.arange(cols, dtype=float)) / safe + o[..., 0]
    y = (w.sum(axis=-1) @ np.arange(rows, dtype=float)) / safe + o[..., 1]
    xy = np.stack([x, y], axis=-1)
    xy = np.where(valid[..., None], xy, np.nan)
    return Centroid(xy=xy, mass=mass, valid=valid)
