"""The steps of the unified location EM (:mod:`.em`): the sparse photon counts it reads, its E-step and M-step.

The counts of ``N`` trials of ``T`` frames enter as their non-zero pixels (:class:`PixelEntries`, sorted by trial);
:class:`ActiveEntries` holds those of the trials still iterating. The E-step (:func:`expectation_step`, eq. (10) with the
posterior shares ``lambda_jikl`` and the local means (U6)) tabulates the 1-D pixel fractions and local means once
per (trial, frame, object) from the pixel edges and sums over the non-zero pixels only, compiled
(:mod:`._kernels`) or in NumPy (:func:`expectation_step_numpy`, its reference). The M-step (:func:`maximisation_step`, eq. (11)) is
the weighted least-squares line per object and axis, with an optional Gaussian prior (MAP-EM), and
:func:`sigma_update` the PSF width update (an extension the paper calls feasible, derived here).

Units: pixels (centres at integers, window origin at pixel (0, 0); ``x`` = column, ``y`` = row) and frames.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import ndtr

from tvtrack import jit

from . import _kernels

__all__ = [
    "PixelEntries",
    "pixel_entries",
    "per_frame_entries",
    "check_entries",
    "ActiveEntries",
    "axis_tables",
    "expectation_step",
    "expectation_step_numpy",
    "maximisation_step",
    "sigma_update",
]

_SQRT_2PI = np.sqrt(2.0 * np.pi)
_TINY = 1e-300


@dataclass(frozen=True)
class PixelEntries:
    """The non-zero pixels of a count tensor, sorted by trial.

    Attributes
    ----------
    trial, frame : ndarray of int64, shape (nnz,)
    row, col : ndarray of float, shape (nnz,)
        Pixel-centre coordinates ``y`` and ``x`` (px).
    count : ndarray of float, shape (nnz,)
    n_trials, n_frames : int
    shape : (int, int)
        Window (rows, cols); ``M = rows * cols``.
    """

    trial: np.ndarray
    frame: np.ndarray
    row: np.ndarray
    col: np.ndarray
    count: np.ndarray
    n_trials: int
    n_frames: int
    shape: tuple[int, int]

    @property
    def n_pixels(self) -> int:
        return int(self.shape[0] * self.shape[1])

    def photons_per_trial(self) -> np.ndarray:
        """Total count of each trial, shape (n_trials,)."""
        return np.bincount(self.trial, weights=self.count, minlength=self.n_trials)


def pixel_entries(counts) -> PixelEntries:
    """Sparse form of a count tensor ``(n_trials, T, rows, cols)`` (non-negative integers)."""
    counts = np.asarray(counts)
    if counts.ndim != 4:
        raise ValueError(f"counts has shape {counts.shape}; it must be (n_trials, T, rows, cols)")
    if counts.size and counts.min() < 0:
        raise ValueError(f"counts has a negative value {counts.min()}; counts must be >= 0")
    n, t, r, c = np.nonzero(counts)
    return PixelEntries(
        trial=n,
        frame=t,
        row=r.astype(float),
        col=c.astype(float),
        count=counts[n, t, r, c].astype(float),
        n_trials=counts.shape[0],
        n_frames=counts.shape[1],
        shape=counts.shape[2:],
    )


def per_frame_entries(entries: PixelEntries) -> PixelEntries:
    """Treat every (trial, frame) as its own one-frame trial ``trial * T + frame`` (for marks)."""
    return PixelEntries(
        trial=entries.trial * entries.n_frames + entries.frame,
        frame=np.zeros_like(entries.frame),
        row=entries.row,
        col=entries.col,
        count=entries.count,
        n_trials=entries.n_trials * entries.n_frames,
        n_frames=1,
        shape=entries.shape,
    )


def check_entries(entries: PixelEntries) -> None:
    """Raise ``ValueError`` unless ``entries`` is a table the E-steps can read: the five arrays one-dimensional of one
    length, ``trial`` and ``frame`` integers, ``trial`` sorted and in ``[0, n_trials)``, ``frame`` in
    ``[0, n_frames)``, ``row`` and ``col`` whole pixel indices inside ``shape``, ``count`` finite and >= 0.

    :func:`pixel_entries` always builds such a table; a hand-built one that is not would make the compiled steps read
    and write past their tables (they index them unchecked). One vectorised pass over the entries: checked once per
    EM call (:func:`.em.unified_location_em`), not per step.
    """
    names = ("trial", "frame", "row", "col", "count")
    arrays = {name: np.asarray(getattr(entries, name)) for name in names}
    shapes = [a.shape for a in arrays.values()]
    if arrays["trial"].ndim != 1 or len(set(shapes)) != 1:
        raise ValueError(f"parameter 'entries' has {', '.join(names)} of shapes {shapes}; they must be (nnz,) each")
    shape = tuple(entries.shape)
    if len(shape) != 2:
        raise ValueError(f"parameter 'entries' has shape {entries.shape}; it must be the window (rows, cols)")
    for name in ("trial", "frame"):
        if arrays[name].dtype.kind not in "iu":
            raise ValueError(f"parameter 'entries' has {name} of dtype {arrays[name].dtype}; it must hold integers")
    limits = {"trial": entries.n_trials, "frame": entries.n_frames, "row": shape[0], "col": shape[1]}
    for name, limit in limits.items():
        a = arrays[name]
        if a.size and not (a.min() >= 0 and a.max() < limit):  # NaN fails both comparisons
            raise ValueError(f"parameter 'entries' has {name} from {a.min()} to {a.max()}; it must lie in [0, {limit})")
    for name in ("row", "col"):
        if np.any(arrays[name] != np.floor(arrays[name])):
            raise ValueError(f"parameter 'entries' has a {name} that is not a whole number; pixel centres are integers")
    if np.any(np.diff(arrays["trial"]) < 0):
        raise ValueError("parameter 'entries' is not sorted by trial; it must be (as pixel_entries builds it)")
    count = arrays["count"]
    if count.size and not (np.isfinite(count).all() and count.min() >= 0):
        raise ValueError(f"parameter 'entries' has a count {count.min()}; counts must be finite and >= 0")


class ActiveEntries:
    """Entries of the trials still iterating, with their segment starts for reduceat."""

    def __init__(self, entries: PixelEntries, trials: np.ndarray):
        keep = np.isin(entries.trial, trials)
        self.trials = trials
        g = entries.trial[keep]
        self.loc = np.searchsorted(trials, g)
        self.starts = np.searchsorted(self.loc, np.arange(trials.size))
        self.frame = entries.frame[keep]
        self.row = entries.row[keep]
        self.col = entries.col[keep]
        self.count = entries.count[keep]
        self.n_frames = entries.n_frames
        self.shape = tuple(entries.shape)
        self._index = {}
        self.kernel_arrays = None  # the entries typed for the compiled E-step, made at its first use

    def index(self, q: int, n_cells: int, rows: bool = False) -> np.ndarray:
        """Flat index (nnz, Q) into a per-(trial, frame, object, pixel) table of one axis."""
        key = (q, n_cells, rows)
        if key not in self._index:
            cell = (self.row if rows else self.col).astype(np.int64)
            base = (self.loc * self.n_frames + self.frame) * q
            self._index[key] = (base[:, None] + np.arange(q)) * n_cells + cell[:, None]
        return self._index[key]


def axis_tables(mu, s, n_cells: int, second: bool):
    """1-D pixel fractions (U3), local means (U6) and ``E[z^2 | pixel]`` for every pixel of one
    axis, evaluated once per (trial, frame, object) from the ``n_cells + 1`` pixel edges.

    Parameters
    ----------
    mu : ndarray, shape (n, T, Q)
        Object coordinate in each frame (px).
    s : ndarray, shape (n, 1, Q)
        PSF standard deviation (px).

    Returns
    -------
    F, mean[, ez2] : ndarray, shape (n, T, Q, n_cells)
    """
    edges = np.arange(n_cells + 1) - 0.5
    # standardised edges, clipped where the Gaussian tail is below double precision
    # (exp(-37^2/2) ~ 1e-298 is still a normal number: no slow denormal arithmetic)
    z = np.clip((edges - mu[..., None]) / s[..., None], -37.0, 37.0)
    G = ndtr(-np.abs(z))  # tail mass beyond each edge: no cancellation
    phi = np.exp(-0.5 * z * z) / _SQRT_2PI
    a, b = z[..., :-1], z[..., 1:]
    Ga, Gb = G[..., :-1], G[..., 1:]
    F = np.where(b <= 0, Gb - Ga, np.where(a >= 0, Ga - Gb, 1.0 - Ga - Gb))  # (U3)
    ok = F > _TINY
    Fs = np.where(ok, F, 1.0)
    m = mu[..., None]
    sd = s[..., None]
    centre = edges[:-1] + 0.5
    dphi = (phi[..., :-1] - phi[..., 1:]) / Fs
    mean = np.clip(np.where(ok, m + sd * dphi, centre), centre - 0.5, centre + 0.5)  # (U6)
    if not second:
        return F, mean, None
    za, zb = a * phi[..., :-1], b * phi[..., 1:]
    var_mu = sd * sd * (1.0 + (za - zb) / Fs)  # E[(z - mu)^2 | pixel]
    ez2 = np.where(ok, var_mu + 2 * m * (mean - m) + m * m, centre * centre + 1.0 / 12.0)
    return F, np.asarray(mean), np.maximum(ez2, mean * mean)


def expectation_step(work: ActiveEntries, theta, p, p_noise, sigma, times, shape, second: bool, live=None):
    """E-step sums per active trial and object.

    Returns
    -------
    sums : (n_act, Q, 7 or 9) = A, B, C, Dx, Dtx, Dy, Dty [, Sxx, Syy]  (eq. (10))
    loglik : (n_act,)  sum n ln v at ``theta``

    ``live`` ((n_act,) bool, optional): the trials still iterating; the compiled step leaves the others' rows zero.
    ``theta`` (n_act, Q, 4), ``p`` and ``sigma`` (n_act, Q), ``p_noise`` (n_act,), ``times`` (T,) and ``shape`` (the
    window of the entries) are checked against ``work`` (``ValueError``): the compiled step indexes them unchecked.
    """
    _check_step_inputs(work, theta, p, p_noise, sigma, times, shape, live)
    if jit.enabled():
        return _kernels.e_step(work, theta, p, p_noise, sigma, times, shape, second, live)
    return expectation_step_numpy(work, theta, p, p_noise, sigma, times, shape, second)


def _check_step_inputs(work: ActiveEntries, theta, p, p_noise, sigma, times, shape, live) -> None:
    """Raise ``ValueError`` unless the arguments of :func:`expectation_step` fit the working set ``work``."""
    n = work.trials.size
    q = np.shape(theta)[1] if np.ndim(theta) == 3 else "Q"
    wanted = {"theta": (n, q, 4), "p": (n, q), "p_noise": (n,), "sigma": (n, q), "times": (work.n_frames,)}
    given = {"theta": theta, "p": p, "p_noise": p_noise, "sigma": sigma, "times": times}
    if live is not None:
        wanted["live"], given["live"] = (n,), live
    for name, value in given.items():
        if np.shape(value) != wanted[name]:
            raise ValueError(
                f"parameter '{name}' has shape {np.shape(value)}; it must be {wanted[name]} to match 'work'"
            )
    if tuple(shape) != work.shape:
        raise ValueError(f"parameter 'shape' is {tuple(shape)}; it must be the entries' window {work.shape}")


def expectation_step_numpy(work: ActiveEntries, theta, p, p_noise, sigma, times, shape, second: bool, live=None):
    """:func:`expectation_step` in NumPy (the reference of the compiled kernel; used when ``TVTRACK_NO_JIT=1`` or without
    numba); it computes every row, ``live`` or not."""
    rows, cols = shape
    t = times[None, :, None]
    s = sigma[:, None, :]
    Fx, mx, sx = axis_tables(theta[:, None, :, 0] + theta[:, None, :, 2] * t, s, cols, second)
    Fy, my, sy = axis_tables(theta[:, None, :, 1] + theta[:, None, :, 3] * t, s, rows, second)
    ix, iy = work.index(theta.shape[1], cols), work.index(theta.shape[1], rows, rows=True)
    fx, fy = Fx.ravel()[ix], Fy.ravel()[iy]  # (nnz, Q)
    pv = p[work.loc] * (fx * fy)  # p_j F_jikl
    v = np.maximum(p_noise[work.loc] / (rows * cols) + pv.sum(axis=1), _TINY)  # (U1)
    w = pv * (work.count / v)[:, None]  # n_ikl lambda_jikl
    te = times[work.frame][:, None]
    wt = w * te
    ex, ey = mx.ravel()[ix], my.ravel()[iy]
    cols_ = [w, wt, wt * te, w * ex, wt * ex, w * ey, wt * ey]
    if second:
        cols_ += [w * sx.ravel()[ix], w * sy.ravel()[iy]]
    sums = np.add.reduceat(np.stack(cols_, axis=-1), work.starts, axis=0)
    loglik = np.add.reduceat(work.count * np.log(v), work.starts)
    return sums, loglik


def maximisation_step(sums, theta, static: bool, prior=None):
    """Closed-form M-step (11) per object and axis; returns new theta and a degenerate flag.

    ``prior = (mean (N, Q, 4), a (N, Q), c (N, Q))`` adds a Gaussian prior (MAP-EM): ``a`` and ``c``
    are sigma^2 times the prior precisions of the initial position and of the velocity, which
    enter the normal equations of (10) as ``(A + a) x0 + B V = D_x + a x0_prior`` and
    ``B x0 + (C + c) V = D_tx + c V_prior``."""
    A, B, C, Dx, Dtx, Dy, Dty = (sums[..., k] for k in range(7))
    new = np.empty_like(theta)
    if prior is not None and not static:
        mean, a, c = prior
        A, C = A + a, C + c
        Dx, Dy = Dx + a * mean[..., 0], Dy + a * mean[..., 1]
        Dtx, Dty = Dtx + c * mean[..., 2], Dty + c * mean[..., 3]
    if static:
        bad = A <= 1e-12
        As = np.where(bad, 1.0, A)
        new[..., 0] = Dx / As
        new[..., 1] = Dy / As
        new[..., 2:] = 0.0
    else:
        det = A * C - B * B
        bad = (A <= 1e-12) | (det <= 1e-9 * np.maximum(A * C, 1e-300))
        ds = np.where(bad, 1.0, det)
        new[..., 0] = (C * Dx - B * Dtx) / ds  # (11) x0
        new[..., 1] = (C * Dy - B * Dty) / ds  # (11) y0
        new[..., 2] = (A * Dtx - B * Dx) / ds  # (11) Vx with the new x0
        new[..., 3] = (A * Dty - B * Dy) / ds
    bad = bad | ~np.isfinite(new).all(axis=-1)
    new = np.where(bad[..., None], theta, new)
    return new, bad.any(axis=-1)


def sigma_update(sums, theta_new, sigma, bad):
    """The spot widths' update: sigma_j^2 = sum_pixels w E[(z - mu_new)^2 | pixel] over both axes / (2 A).

    Parameters
    ----------
    sums : numpy.ndarray
        E-step sums (n_act, Q, 9) with the second moments (:func:`expectation_step` with ``second=True``).
    theta_new : numpy.ndarray
        The M-step's new ``(x0, y0, Vx, Vy)`` (n_act, Q, 4), pixels and pixels per frame time.
    sigma : numpy.ndarray
        The current widths (n_act, Q), pixels.
    bad : numpy.ndarray
        Trials whose M-step was degenerate (n_act,): their widths are kept.

    Returns
    -------
    numpy.ndarray
        The new widths (n_act, Q), pixels; the current one wherever the update is not a positive finite number.
    """
    A, B, C, Dx, Dtx, Dy, Dty, Sxx, Syy = (sums[..., k] for k in range(9))
    x0, y0, vx, vy = (theta_new[..., k] for k in range(4))
    qx = Sxx - 2 * x0 * Dx - 2 * vx * Dtx + x0 * x0 * A + 2 * x0 * vx * B + vx * vx * C
    qy = Syy - 2 * y0 * Dy - 2 * vy * Dty + y0 * y0 * A + 2 * y0 * vy * B + vy * vy * C
    s2 = (qx + qy) / (2 * np.maximum(A, 1e-300))
    ok = ~bad[:, None] & (s2 > 0) & np.isfinite(s2)
    return np.where(ok, np.sqrt(np.where(ok, s2, 1.0)), sigma)
