"""Compiled histogram of the simulated photons (numba), the twin of the NumPy histogram of :func:`.model.simulate_counts`.

A scene's photons land at ``position + sigma * z`` (``z`` the standard normal draws, px); each is counted in the pixel
whose centre is nearest (``floor(x + 0.5)``), photons outside the window are lost. NumPy does it in a dozen passes
with temporaries over every photon (a third of the scene's cost at 240 trials of 50 frames); the kernel walks the
photons once with the same arithmetic per photon (a product and a sum, then ``floor``), so the same counts
(``tests/papers/test_002_kernels.py`` compares the two).
"""

from __future__ import annotations

import math

import numpy as np

from tvtrack import jit
from tvtrack.jit import njit

__all__ = ["add_photons", "add_photons_numpy"]


@njit
def _add_photons(counts, pos, z, sigma, k, limited):  # pragma: no cover - compiled
    n_trials, n_frames, rows, cols = counts.shape
    n_obj, m = z.shape[2], z.shape[3]
    for i in range(n_trials):
        for f in range(n_frames):
            for q in range(n_obj):
                x0, y0 = pos[i, f, q, 0], pos[i, f, q, 1]
                n_q = k[i, f, q] if limited else m
                for j in range(min(n_q, m)):
                    u = math.floor((x0 + sigma * z[i, f, q, j, 0]) + 0.5)  # column
                    v = math.floor((y0 + sigma * z[i, f, q, j, 1]) + 0.5)  # row
                    if u >= 0 and u < cols and v >= 0 and v < rows:
                        counts[i, f, int(v), int(u)] += 1


def add_photons_numpy(counts, pos, z, sigma_px: float, k=None) -> None:
    """:func:`add_photons` in NumPy (the reference; used without numba)."""
    n_trials, n_frames, rows, cols = counts.shape
    xy = pos[..., None, :] + sigma_px * z
    u = np.floor(xy[..., 0] + 0.5).astype(np.int64)  # column of each photon
    v = np.floor(xy[..., 1] + 0.5).astype(np.int64)  # row
    inside = (u >= 0) & (u < cols) & (v >= 0) & (v < rows)
    if k is not None:
        inside &= np.arange(z.shape[3]) < k[..., None]
    n_idx = np.arange(n_trials)[:, None, None, None]
    l_idx = np.arange(n_frames)[None, :, None, None]
    flat = ((n_idx * n_frames + l_idx) * rows + v) * cols + u
    counts += np.bincount(flat[inside], minlength=counts.size).reshape(counts.shape).astype(counts.dtype)


def _checked_inputs(counts, pos, z, k):
    """``pos``, ``z`` and ``k`` of :func:`add_photons` as float, float and integer arrays of the shapes the kernel
    indexes, ``pos`` and ``k`` broadcast to them."""
    if not isinstance(counts, np.ndarray) or counts.ndim != 4:
        raise ValueError(
            f"parameter 'counts' has shape {np.shape(counts)}; it must be an array (n_trials, T, rows, cols)"
        )
    pos, z = np.asarray(pos, dtype=float), np.asarray(z, dtype=float)
    n, t = counts.shape[:2]
    if z.ndim != 5 or z.shape[:2] != (n, t) or z.shape[4] != 2:
        raise ValueError(f"parameter 'z' has shape {z.shape}; it must be ({n}, {t}, Q, m, 2) for counts {counts.shape}")
    q = z.shape[2]
    pos = _broadcast(pos, (n, t, q, 2), "pos")
    if k is not None:
        k = np.asarray(k)
        if k.dtype.kind not in "iu":
            raise ValueError(f"parameter 'k' has dtype {k.dtype}; it must hold integers (photons per object and frame)")
        k = _broadcast(k, (n, t, q), "k")
    return pos, z, k


def _broadcast(a, shape, name):
    """``a`` broadcast to ``shape`` (a read-only view; ``a`` itself where it has that shape), or ``ValueError``
    naming the parameter ``name``."""
    if a.shape == shape:
        return a
    try:
        return np.broadcast_to(a, shape)
    except ValueError:
        raise ValueError(f"parameter '{name}' has shape {a.shape}; it must broadcast to {shape}") from None


def add_photons(counts, pos, z, sigma_px: float, k=None) -> None:
    """Count photons into ``counts`` (n_trials, T, rows, cols; integers, updated in place).

    Parameters
    ----------
    counts : ndarray of int32, shape (n_trials, T, rows, cols)
        The counts so far (the noise photons).
    pos : ndarray, shape (n_trials, T, Q, 2)
        Object positions ``(x, y)`` in each frame, px.
    z : ndarray, shape (n_trials, T, Q, m, 2)
        Standard normal draws of each photon's offset (in units of ``sigma_px``).
    sigma_px : float
        PSF standard deviation, px.
    k : ndarray of int, shape (n_trials, T, Q), optional
        Photons of each object in each frame (only the first ``k`` of the ``m`` drawn count); None: all ``m``.

    Raises
    ------
    ValueError
        ``counts`` not 4-D, ``z`` not (n_trials, T, Q, m, 2) for the trials and frames of ``counts``, ``pos`` or
        ``k`` not broadcastable to (n_trials, T, Q, 2) or (n_trials, T, Q) (they are broadcast, as NumPy does), or
        ``k`` not integers: the compiled histogram indexes them unchecked.
    """
    pos, z, k = _checked_inputs(counts, pos, z, k)
    if not jit.enabled() or counts.dtype != np.int32 or not counts.flags.c_contiguous:
        add_photons_numpy(counts, pos, z, sigma_px, k)
        return
    limited = k is not None
    kk = np.ascontiguousarray(k, dtype=np.int64) if limited else np.zeros((1, 1, 1), dtype=np.int64)
    _add_photons(counts, np.ascontiguousarray(pos), np.ascontiguousarray(z), float(sigma_px), kk, limited)
