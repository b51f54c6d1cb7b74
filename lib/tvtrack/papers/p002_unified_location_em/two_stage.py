"""Two-stage ("trajectory") processing: per-frame marks, then least-squares straight lines.

This is the baseline of Savanevich (1999, Figs 3-6): primary processing forms a *mark* (position
estimate) for each object in each frame on its own; secondary processing fits the linear-motion
model (1) to the marks by ordinary least squares, i.e. eq. (11) with unit weights.

Marks (the two kinds of Fig. 3a):

* :func:`centre_of_region_marks` -- "by the centre of the region" (Fig. 3a, curve 1): the
  count-weighted centroid of the pixel centres inside a square gate around the designated
  position in that frame (the paper does not define the region; the gate is this project's choice).
* :func:`em_marks` -- the iterative mark formation of ref. [5] (Fig. 3a curve 2, Figs 4-6
  curve 1): the EM of :func:`tvtrack.papers.p002_unified_location_em.em.unified_location_em` applied to one
  frame with a static model, ``x = D_x / A``.

Start of the per-frame EM (``init``): the designation propagated to the frame, the previous
frame's marks, or (``"moments"``, designation-free) :func:`moment_starts`, a split of the frame's
brightest region along its principal axis.

Association rule (not stated in the paper; all variants are parameters):

* ``"designation"``: labels are carried by the initialisation -- mark ``j`` of frame ``l`` is
  object ``j``'s because it was started from object ``j``'s designated (or previous) position;
* ``"assignment"``: after forming the marks, reorder them in each frame by the minimum-cost
  assignment (summed squared distances, all ``Q!`` orders) to the designated positions
  propagated to that frame;
* ``"lines"`` (designation-free, gate-free, multi-frame, in the spirit of ref. [4]):
  :func:`associate_by_lines`, the per-frame orders that (locally) minimise the total residual of
  the straight-line fits.

Units: pixels and frames (see :mod:`tvtrack.papers.p002_unified_location_em.model`).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
from scipy.ndimage import uniform_filter

from tvtrack.measure import crop
from tvtrack.render import gate_origin
from .em_steps import per_frame_entries, pixel_entries
from .em import unified_location_em

__all__ = [
    "Marks",
    "LineFit",
    "propagate",
    "centre_of_region_marks",
    "em_marks",
    "associate",
    "fit_lines",
    "moment_starts",
    "associate_by_lines",
]


@dataclass
class Marks:
    """Per-frame position marks.

    Attributes
    ----------
    xy : ndarray, shape (N, T, Q, 2)
        Mark positions (px); where ``valid`` is False the value is the initialisation and must
        not be used.
    valid : ndarray of bool, shape (N, T, Q)
        A mark was formed (the gate or the frame held photons and the fit was not singular).
    n_iter : ndarray of int, shape (N, T)
        EM steps per frame (zeros for centroid marks).
    cap_hit : ndarray of bool, shape (N, T)
        The per-frame EM reached its iteration cap.
    """

    xy: np.ndarray
    valid: np.ndarray
    n_iter: np.ndarray
    cap_hit: np.ndarray


def propagate(theta, times) -> np.ndarray:
    """Positions ``(N, T, Q, 2)`` of linear-motion states ``(N, Q, 4)`` at ``times`` (T,)."""
    theta = np.asarray(theta, dtype=float)
    t = np.asarray(times, dtype=float)[None, :, None, None]
    return theta[:, None, :, :2] + t * theta[:, None, :, 2:]


def centre_of_region_marks(counts, predicted, half_gate_px: float) -> Marks:
    """Count-weighted centroid of the pixel centres in a square gate per object and frame.

    Parameters
    ----------
    counts : ndarray, shape (N, T, rows, cols)
    predicted : ndarray, shape (N, T, Q, 2)
        Gate centres (px), e.g. the designation propagated with :func:`propagate`.
    half_gate_px : float
        The gate holds the pixels whose centres lie within ``half_gate_px`` of the nearest
        pixel centre to the prediction (> 0); gates leaving the window are shifted inside.
    """
    counts = np.asarray(counts, dtype=float)
    predicted = np.asarray(predicted, dtype=float)
    if half_gate_px <= 0:
        raise ValueError(f"half_gate_px = {half_gate_px} must be > 0")
    if counts.ndim != 4 or predicted.shape[:2] != counts.shape[:2] or predicted.shape[-1] != 2:
        raise ValueError(
            f"counts {counts.shape} must be (N, T, rows, cols) and predicted {predicted.shape} (N, T, Q, 2)"
        )
    rows, cols = counts.shape[-2:]
    g = 2 * int(np.floor(half_gate_px)) + 1
    size = (min(g, rows), min(g, cols))
    origin = gate_origin(predicted, size)
    origin = np.stack([np.clip(origin[..., 0], 0, cols - size[1]), np.clip(origin[..., 1], 0, rows - size[0])], axis=-1)
    q = predicted.shape[2]
    gates = crop(np.repeat(counts[:, :, None], q, axis=2), origin, size)  # (N, T, Q, g, g)
    total = gates.sum(axis=(-1, -2))
    sx = (gates.sum(axis=-2) * np.arange(size[1])).sum(axis=-1)
    sy = (gates.sum(axis=-1) * np.arange(size[0])).sum(axis=-1)
    valid = total > 0
    ts = np.where(valid, total, 1.0)
    xy = np.where(valid[..., None], origin + np.stack([sx, sy], axis=-1) / ts[..., None], predicted)
    n, t = counts.shape[:2]
    return Marks(xy=xy, valid=valid, n_iter=np.zeros((n, t), dtype=np.int64), cap_hit=np.zeros((n, t), dtype=bool))


def associate(marks: Marks, predicted) -> Marks:
    """Reorder the marks of each frame by the minimum-cost assignment to ``predicted``
    (N, T, Q, 2): the order of all ``Q!`` that minimises the summed squared distance."""
    predicted = np.asarray(predicted, dtype=float)
    q = predicted.shape[2]
    if q > 7:
        raise ValueError(f"Q = {q}; the assignment enumerates Q! orders and allows Q <= 7")
    perms = np.array(list(itertools.permutations(range(q))))  # (P, Q)
    cost = ((marks.xy[:, :, perms] - predicted[:, :, None]) ** 2).sum(axis=(-1, -2))  # (N, T, P)
    best = perms[cost.argmin(axis=-1)]  # (N, T, Q)
    xy = np.take_along_axis(marks.xy, best[..., None], axis=2)
    valid = np.take_along_axis(marks.valid, best, axis=2)
    return Marks(xy=xy, valid=valid, n_iter=marks.n_iter, cap_hit=marks.cap_hit)


def em_marks(
    counts,
    designation,
    times,
    sigma_px,
    p,
    p_noise,
    *,
    init: str = "designation",
    association: str = "designation",
    tol_px: float = 1e-6,
    max_iter: int = 5000,
    accelerate: str | None = None,
    tol_loglik: float | None = None,
) -> Marks:
    """Marks from the iterative per-frame EM ("mark formation", ref. [5]).

    Parameters
    ----------
    counts : ndarray, shape (N, T, rows, cols)
    designation : ndarray, shape (N, Q, 4)
        Target designation (px, px/frame); it gives each frame's initial positions.
    times : ndarray, shape (T,)
    sigma_px, p, p_noise
        PSF width and mixture weights as in :func:`unified_location_em`.
    init : {"designation", "previous", "moments"}
        Start frame ``l`` from the designation propagated to ``t_l``, or (``"previous"``) from
        the previous frame's marks moved by the designated velocity (frame 0 from the
        designation; the frames run in sequence), or (``"moments"``) from :func:`moment_starts`
        (no designation).
    association : {"designation", "assignment", "lines"}
        See the module docstring; ``"lines"`` uses no designation.
    tol_px, max_iter, accelerate, tol_loglik
        Stopping rule and acceleration of the per-frame EM (``tol_loglik``: on each frame's own
        log-likelihood, see :func:`unified_location_em`).
    """
    counts = np.asarray(counts)
    designation = np.asarray(designation, dtype=float)
    times = np.asarray(times, dtype=float)
    if init not in ("designation", "previous", "moments"):
        raise ValueError(f"init = {init!r} must be 'designation', 'previous' or 'moments'")
    if association not in ("designation", "assignment", "lines"):
        raise ValueError(f"association = {association!r} must be 'designation', 'assignment' or 'lines'")
    predicted = propagate(designation, times)  # (N, T, Q, 2)
    mixture = (sigma_px, p, p_noise)
    em_kw = dict(tol_px=tol_px, max_iter=max_iter, accelerate=accelerate, tol_loglik=tol_loglik)
    if init == "previous":
        marks = _marks_in_sequence(counts, predicted[:, 0], designation[..., 2:], times, mixture, em_kw)
    else:
        q = designation.shape[1]
        starts = predicted if init == "designation" else moment_starts(counts, sigma_px, q)
        marks = _marks_at_once(counts, starts, mixture, em_kw)
    if association == "lines":
        return associate_by_lines(marks, times)
    return associate(marks, predicted) if association == "assignment" else marks


def _frame_state(xy) -> np.ndarray:
    """Static states ``(x, y, 0, 0)`` (..., Q, 4) of the positions ``xy`` (..., Q, 2), px."""
    th = np.zeros(xy.shape[:-1] + (4,))
    th[..., :2] = xy
    return th


def _frame_em(entries, xy, mixture, em_kw):
    """The static one-frame EM (``x = D_x / A``, eq. (11) with ``V = 0``) of every trial of ``entries`` started at
    ``xy`` (n, Q, 2) px; ``mixture = (sigma_px, p, p_noise)`` and ``em_kw`` (the stopping rule and acceleration)
    as in :func:`~.em.unified_location_em`. Returns its :class:`~.em.EMResult`."""
    return unified_location_em(entries, _frame_state(xy), *mixture, times=np.zeros(1), motion="static", **em_kw)


def _marks_at_once(counts, starts, mixture, em_kw) -> Marks:
    """The marks of every frame of every trial from one EM call over all ``N T`` frames as separate trials,
    started at ``starts`` (N, T, Q, 2) px (:func:`_frame_em` for the other arguments)."""
    n, t = counts.shape[:2]
    q = starts.shape[2]
    res = _frame_em(per_frame_entries(pixel_entries(counts)), starts.reshape(n * t, q, 2), mixture, em_kw)
    return Marks(
        xy=res.theta[..., :2].reshape(n, t, q, 2),
        valid=~res.degenerate.reshape(n, t)[..., None] & np.ones(q, dtype=bool),
        n_iter=res.n_iter.reshape(n, t),
        cap_hit=res.cap_hit.reshape(n, t),
    )


def _marks_in_sequence(counts, start, velocity, times, mixture, em_kw) -> Marks:
    """The marks frame after frame (``init = "previous"``): frame 0 started at ``start`` (N, Q, 2) px, each next
    frame at the previous frame's marks (where valid; else its own start) moved by ``velocity`` (N, Q, 2) px/frame
    over the frame interval of ``times`` (T,) (:func:`_frame_em` for the other arguments)."""
    n, t = counts.shape[:2]
    q = start.shape[1]
    xy = np.empty((n, t, q, 2))
    valid = np.empty((n, t, q), dtype=bool)
    n_iter = np.empty((n, t), dtype=np.int64)
    cap = np.empty((n, t), dtype=bool)
    for l in range(t):  # loop over frames only
        res = _frame_em(pixel_entries(counts[:, l : l + 1]), start, mixture, em_kw)
        xy[:, l] = res.theta[..., :2]
        valid[:, l] = ~res.degenerate[:, None]
        n_iter[:, l] = res.n_iter
        cap[:, l] = res.cap_hit
        if l + 1 < t:
            step = (times[l + 1] - times[l]) * velocity
            start = np.where(valid[:, l, :, None], xy[:, l], start) + step
    return Marks(xy=xy, valid=valid, n_iter=n_iter, cap_hit=cap)


def _gate_moments(counts, py, px, half: int):
    """Count-weighted centroid (N, T, 2) and second-moment matrix (N, T, 2, 2) of each frame inside
    the square gate of half-size ``half`` px around pixel ``(py, px)`` (N, T)."""
    rows, cols = counts.shape[-2:]
    yy = np.arange(rows, dtype=float)[:, None]  # pixel centres, px
    xx = np.arange(cols, dtype=float)[None, :]
    inside = (np.abs(yy - py[..., None, None]) <= half) & (np.abs(xx - px[..., None, None]) <= half)
    w = counts * inside
    tot = np.maximum(w.sum(axis=(-1, -2)), 1e-12)
    mx = (w * xx).sum(axis=(-1, -2)) / tot
    my = (w * yy).sum(axis=(-1, -2)) / tot
    dx, dy = xx - mx[..., None, None], yy - my[..., None, None]
    sxx, sxy, syy = ((w * a * b).sum(axis=(-1, -2)) / tot for a, b in ((dx, dx), (dx, dy), (dy, dy)))
    cov = np.stack([np.stack([sxx, sxy], -1), np.stack([sxy, syy], -1)], -2)
    return np.stack([mx, my], axis=-1), cov


def moment_starts(
    counts, sigma_px: float, q: int, half_gate_sigma: float = 3.0, peak_fraction: float = 0.5
) -> np.ndarray:
    """Designation-free starting positions of the per-frame EM, shape (N, T, Q, 2), px.

    In each frame the count image is box-filtered over a gate ``2 * ceil(half_gate_sigma * sigma)
    + 1`` px wide and its ``Q`` brightest regions are found greedily (each found region masks a
    square twice the gate's half-size around it). If every one of them holds at least
    ``peak_fraction`` of the brightest one's counts, the objects are resolved: the starts are the
    regions' centroids. Otherwise they overlap: inside the brightest region, the count-weighted
    centroid ``c`` and the principal axis ``u`` (largest eigenvalue ``lam``) of the second moments
    give ``Q`` starts on ``u`` through ``c``, equally spaced with the spread that explains the
    excess ``lam - sigma^2 - 1/12`` (PSF and pixel variance removed; at least ``(sigma / 2)^2`` so
    that the EM's symmetric start is broken).

    Parameters
    ----------
    counts : ndarray, shape (N, T, rows, cols)
    sigma_px : float
        PSF standard deviation, px.
    q : int
        Number of objects.
    half_gate_sigma : float
        Half-size of a region, in sigma.
    peak_fraction : float
        A region this bright relative to the brightest counts as a separate object.
    """
    counts = np.asarray(counts, dtype=float)
    n, t, rows, cols = counts.shape
    half = int(np.ceil(half_gate_sigma * sigma_px))
    smooth = uniform_filter(counts, size=(1, 1, 2 * half + 1, 2 * half + 1), mode="constant")
    yy, xx = np.arange(rows)[:, None], np.arange(cols)[None, :]
    peaks, heights = [], []
    for _ in range(q):
        k = smooth.reshape(n, t, -1).argmax(axis=-1)
        py, px = np.unravel_index(k, (rows, cols))
        peaks.append((py, px))
        heights.append(np.take_along_axis(smooth.reshape(n, t, -1), k[..., None], axis=-1)[..., 0])
        near = (np.abs(yy - py[..., None, None]) <= 2 * half) & (np.abs(xx - px[..., None, None]) <= 2 * half)
        smooth = np.where(near, -np.inf, smooth)
    resolved = np.all([h >= peak_fraction * heights[0] for h in heights], axis=0)  # (N, T)
    centres = np.stack([_gate_moments(counts, py, px, half)[0] for py, px in peaks], axis=2)  # (N, T, Q, 2)
    c, cov = _gate_moments(counts, *peaks[0], half)
    lam, vec = np.linalg.eigh(cov)
    u = vec[..., :, -1]  # (N, T, 2)
    excess = np.maximum(lam[..., -1] - sigma_px**2 - 1 / 12, (sigma_px / 2) ** 2)
    spacing = np.sqrt(12 * excess / (q * q - 1)) if q > 1 else np.zeros_like(excess)
    offsets = (np.arange(q) - (q - 1) / 2)[None, None, :, None]
    split = c[:, :, None, :] + offsets * spacing[..., None, None] * u[:, :, None, :]
    return np.where(resolved[..., None, None], centres, split)


def associate_by_lines(marks: Marks, times, max_rounds: int = 20) -> Marks:
    """Gate-free multi-frame association without a designation: per-frame orders of the marks
    that (locally) minimise the total squared residual of the ``Q`` straight-line fits.

    Start: in each frame, order the marks by their projection on the principal direction of all
    the trial's marks about their frame means (the direction that separates the objects). Then
    alternate a least-squares line fit (:func:`fit_lines`) and a per-frame minimum-cost
    re-assignment to the lines (:func:`associate`) until no order changes (coordinate descent
    on the total residual; each round cannot increase it).

    Parameters
    ----------
    marks : Marks
    times : ndarray, shape (T,)
    max_rounds : int
        Cap on the fit/re-assign rounds.
    """
    xy = marks.xy
    n, t, q, _ = xy.shape
    w = marks.valid[..., None].astype(float)
    frame_mean = (w * xy).sum(axis=2, keepdims=True) / np.maximum(w.sum(axis=2, keepdims=True), 1)
    c = (xy - frame_mean) * w
    cov = np.einsum("ntqi,ntqj->nij", c, c)
    u = np.linalg.eigh(cov)[1][..., -1]  # (N, 2)
    order = np.argsort(np.einsum("ntqi,ni->ntq", xy - frame_mean, u), axis=2)
    current = Marks(
        xy=np.take_along_axis(xy, order[..., None], axis=2),
        valid=np.take_along_axis(marks.valid, order, axis=2),
        n_iter=marks.n_iter,
        cap_hit=marks.cap_hit,
    )
    fallback = np.concatenate([current.xy.mean(axis=1), np.zeros((n, q, 2))], axis=-1)
    for _ in range(max_rounds):
        fit = fit_lines(current, times, fallback)
        new = associate(current, propagate(fit.theta, times))
        if np.array_equal(new.xy, current.xy):
            break
        current = new
    return current


@dataclass
class LineFit:
    """Least-squares straight lines through marks.

    Attributes
    ----------
    theta : ndarray, shape (N, Q, 4)
        ``(x0, y0, Vx, Vy)``; where ``valid`` is False, the designation is returned.
    valid : ndarray of bool, shape (N, Q)
        At least two frames with distinct times held valid marks.
    """

    theta: np.ndarray
    valid: np.ndarray


def fit_lines(marks: Marks, times, fallback, velocity=None) -> LineFit:
    """Ordinary least squares ``x_l = x0 + Vx t_l`` per object and axis over the valid marks
    (eq. (11) with unit weights: ``A' = sum 1``, ``B' = sum t``, ``C' = sum t^2``).

    Parameters
    ----------
    marks : Marks
    times : ndarray, shape (T,)
    fallback : ndarray, shape (N, Q, 4)
        Returned for objects with fewer than two usable marks (flagged invalid).
    velocity : ndarray, shape (N, Q, 2), optional
        A known velocity (px/frame): then only ``x0 = mean(x_l - V t_l)`` over the valid marks is
        fitted (one usable mark suffices), the two-stage counterpart of a ULA whose velocity is fixed.
    """
    t = np.asarray(times, dtype=float)[None, :, None]
    w = marks.valid.astype(float)  # (N, T, Q)
    if velocity is not None:
        v = np.asarray(velocity, dtype=float)
        A = w.sum(axis=1)
        ok = A > 0
        resid = marks.xy - t[..., None] * v[:, None]  # (N, T, Q, 2)
        x0 = (w[..., None] * resid).sum(axis=1) / np.where(ok, A, 1.0)[..., None]
        theta = np.where(ok[..., None], np.concatenate([x0, v], axis=-1), np.asarray(fallback, float))
        return LineFit(theta=theta, valid=ok)
    A = w.sum(axis=1)
    B = (w * t).sum(axis=1)
    C = (w * t * t).sum(axis=1)
    Dx = (w[..., None] * marks.xy).sum(axis=1)  # (N, Q, 2)
    Dt = (w[..., None] * t[..., None] * marks.xy).sum(axis=1)
    det = A * C - B * B
    ok = det > 1e-9 * np.maximum(A * C, 1e-300)
    ds = np.where(ok, det, 1.0)[..., None]
    x0 = (C[..., None] * Dx - B[..., None] * Dt) / ds
    v = (A[..., None] * Dt - B[..., None] * Dx) / ds
    theta = np.where(ok[..., None], np.concatenate([x0, v], axis=-1), np.asarray(fallback, float))
    return LineFit(theta=theta, valid=ok)
