"""Compiled steps of notebook 003's frame loop (numba), each the twin of a NumPy path that the tests compare with it
(``tests/papers/test_003_frame_kernels.py``): the same operations on each element, so the same bits.

- :func:`gather_windows` and :func:`add_box_layers`, for :meth:`.imaging.RotatingMarkerScene.gate_crops`: each gate's
  window of the static image copied, then each pre-rendered spot box pixel that falls inside its crop added once,
  layer after layer in the order NumPy adds them (the marker, then a lit decoy; an integrated exposure's sub-steps in
  order). A copy and one float32 addition per pixel and layer do not depend on the order the pixels are visited in.
  The kernels do not check their indices: :func:`crop_request` checks a request for both paths, so a bad one is the
  same error both ways (never a read of memory the images do not own), and a crop smaller than a spot's box gets the
  box's overlap on either path.
- :func:`quadrant_weights_f32`, for :func:`.discriminators.quadrant_weights` in the frame loop's case (a square crop,
  one gate half-size, float32 weights): each pixel's covered lengths ``clip(p - e, 0, 1)`` in float64, their
  differences, sums and differences, one rounding to float32, as NumPy computes them elementwise.

Per frame the NumPy paths cost a fixed ~0.1 ms each in per-call overhead (window views, fancy-indexed copies and
in-place adds, a partial-overlap pass; nine small elementwise passes for the weights), the largest share of a
replicate's time after the float32 matrix products of the discriminator (which stay in NumPy: their sums are BLAS's).
"""

from __future__ import annotations

import numpy as np

from tvtrack.jit import njit

__all__ = ["crop_request", "gather_windows", "add_box_layers", "quadrant_weights_f32"]


def crop_request(padded_shape, every, centres, size, trials=None) -> tuple[np.ndarray, np.ndarray]:
    """The trials (indices; a boolean mask read as its true entries; None: ``every``) and centres (n, 2) of a crop
    request on padded images of shape ``padded_shape`` (trials, rows, cols), checked as NumPy's indexing and window
    views check them, so that :func:`gather_windows` and :func:`add_box_layers` (which do not check) meet the same
    errors as the NumPy path: an index out of range, a crop side outside ``[1, rows]``, centres that do not broadcast
    to one per trial."""
    n_all, side = padded_shape[0], min(padded_shape[1:])
    t = every if trials is None else np.asarray(trials)
    if trials is not None:
        t = np.flatnonzero(t) if t.dtype == bool else t
        if t.dtype.kind not in "iu" or (t.size and not -n_all <= t.min() <= t.max() < n_all):
            raise IndexError(f"parameter 'trials': integer indices in [-{n_all}, {n_all}) or a mask, got {trials!r}")
    if not 1 <= size <= side:
        raise ValueError(f"parameter 'size' = {size!r}: a crop side in [1, {side}] px (the padded image's)")
    c = np.asarray(centres, dtype=float)
    return t, (c if c.shape == (len(t), 2) else np.broadcast_to(c, (len(t), 2)))


@njit
def gather_windows(padded, trials, oy, ox, size):  # pragma: no cover - compiled
    """The windows ``padded[trials[i], oy[i]:oy[i] + size, ox[i]:ox[i] + size]``, shape (n, size, size), copied."""
    n = trials.size
    out = np.empty((n, size, size), np.float32)
    for i in range(n):
        a, y0, x0 = trials[i], oy[i], ox[i]
        for y in range(size):
            for x in range(size):
                out[i, y, x] = padded[a, y0 + y, x0 + x]
    return out


@njit
def add_box_layers(crops, box0, patch, origin, rows):  # pragma: no cover - compiled
    """Add the boxes ``patch`` (L, n, side, side) with first pixels ``box0`` (L, n, 2) (x, y) to the crops
    ``rows`` (n,) of ``crops`` (., size, size), whose first pixels are ``origin`` (n, 2), in place: each box pixel
    inside its crop once, layer after layer; pixels outside the crop are left out."""
    size, side = crops.shape[-1], patch.shape[-1]
    for layer in range(box0.shape[0]):
        for j in range(rows.size):
            r = rows[j]
            rx = box0[layer, j, 0] - origin[j, 0]
            ry = box0[layer, j, 1] - origin[j, 1]
            y_lo, y_hi = max(0, -ry), min(side, size - ry)
            x_lo, x_hi = max(0, -rx), min(side, size - rx)
            for yy in range(y_lo, y_hi):
                for xx in range(x_lo, x_hi):
                    crops[r, ry + yy, rx + xx] += patch[layer, j, yy, xx]


@njit
def _covered(p, e):  # pragma: no cover - compiled
    """``min(max(p - e, 0), 1)`` as NumPy's ``maximum`` and ``minimum`` give it (a NaN stays NaN)."""
    v = p - e
    if v < 0.0:
        v = 0.0
    if v > 1.0:
        v = 1.0
    return v


@njit
def quadrant_weights_f32(origin, center, half, size):  # pragma: no cover - compiled
    """:func:`.discriminators.quadrant_weights` of ``size`` x ``size`` crops with first pixels ``origin`` (n, 2) int,
    gate centres ``center`` (n, 2) px and half-size ``half`` px, as float32: ``wy`` (n, 2, size) and ``wx``
    (n, size, 2)."""
    n = center.shape[0]
    wy = np.empty((n, 2, size), np.float32)
    wx = np.empty((n, size, 2), np.float32)
    for i in range(n):
        for ax in range(2):
            c = center[i, ax]
            c_lo, c_hi, o = c - half, c + half, float(origin[i, ax])
            for j in range(size):
                e = (o + j) - 0.5  # the pixel's left edge
                mid = _covered(c, e)
                lower, upper = mid - _covered(c_lo, e), _covered(c_hi, e) - mid
                if ax == 0:
                    wx[i, j, 0], wx[i, j, 1] = np.float32(lower + upper), np.float32(upper - lower)
                else:
                    wy[i, 0, j], wy[i, 1, j] = np.float32(lower + upper), np.float32(upper - lower)
    return wy, wx
