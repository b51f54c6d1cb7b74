"""Compiled gate crops of notebook 003 (numba): the twin of the NumPy path of
:meth:`.imaging.RotatingMarkerScene.gate_crops` that copies each gate's window of the static image and adds the
spots' pre-rendered boxes where they meet it.

Per frame the NumPy path costs about 0.3 ms of fixed per-call overhead (a window view, fancy-indexed copies and
in-place adds, a partial-overlap pass), the interference measurement's largest cost (2,500 frames of three scene
groups). The compiled loops do the same float32 arithmetic element by element: each window pixel copied, then each
box pixel that falls inside its crop added once, layer after layer in the order NumPy adds them (the marker, then a
lit decoy; an integrated exposure's sub-steps in order). A copy and one float32 addition per pixel and layer do not
depend on the order in which the pixels are visited, so the crops are the same bits
(``tests/papers/test_003_crop_kernel.py`` compares the two).
"""

from __future__ import annotations

import numpy as np

from tvtrack.jit import njit

__all__ = ["gather_windows", "add_box_layers"]


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
