"""Discriminators of the generalised Stratonovich tracker (Yukhno 2025), with the corrections
to the printed equations derived here.

All discriminators here return ``+grad Pi`` (up to the positive factor ``d / N``): positive when
the true spot lies at larger ``x`` (``y``) than the gate centre, so loops use *positive* gains.
The printed eqs. (6), (20)-(23), (26) and the quadrant set (Q1)-(Q5) have the opposite sign
(the chain-rule minus of ``dh(z - lambda)/dlambda = -h'`` is dropped), (27)-(28) also have a
wrong relative sign, and (Q3) a misplaced bracket.

Edge form (eqs. (22), (23), corrected)::

    Delta_x = u_dx(x_m + a) - u_dx(x_m - a),   u_dx(x) = int u_d(x, y) h(y - y_m) dy      (21), (24)

Quadrant (integral) form, used in the paper's simulation::

    Delta_x = (u2 + u4) - (u1 + u3),   Delta_y = (u1 + u2) - (u3 + u4)

with ``u1`` = left-"upper" quadrant, where "upper" means ``y > y_m`` (defined by the inequality,
not by the screen display; ``y`` is the row coordinate here). Polar outputs (26)-(28),
corrected: ``e_r = Delta_x cos th + Delta_y sin th`` and ``e_th = -Delta_x sin th + Delta_y cos th``
(``dPi/dphi = r e_th``, ``dPi/domega = r t e_th``).

Coordinates follow :mod:`tvtrack.render`; crops carry leading batch axes ``(n, rows, cols)``.
"""

from __future__ import annotations

import numpy as np

from ... import jit
from ...render import pixel_fractions_box
from ._frame_kernels import quadrant_weights_f32


__all__ = [
    "interval_weights",
    "quadrant_weights",
    "quadrant_noise",
    "quadrant_discriminator",
    "centroid_discriminator",
    "edge_discriminator",
    "polar_errors",
    "static_characteristic",
    "quadrant_slope_fit",
    "two_emitter_discriminator",
    "two_emitter_slope",
    "FORMS",
]

FORMS = ("quadrant", "edge", "centroid")


def _edges(n: int, origin) -> np.ndarray:
    """Left edges ``origin + i - 1/2`` of ``n`` pixels, shape (..., n)."""
    return np.asarray(origin, dtype=float)[..., None] + np.arange(n) - 0.5


def _coverage(p, n: int, origin, edges=None) -> np.ndarray:
    """Length of each pixel ``[e, e + 1]`` lying below ``p``: ``clip(p - e, 0, 1)``, shape (..., n) (``edges``:
    :func:`_edges` of ``n, origin`` when already at hand)."""
    out = np.subtract(np.asarray(p, dtype=float)[..., None], _edges(n, origin) if edges is None else edges)
    np.maximum(out, 0.0, out=out)  # clip in place, without np.clip's per-call overhead (same numbers)
    return np.minimum(out, 1.0, out=out)


def interval_weights(lo, hi, n: int, origin) -> np.ndarray:
    """Overlap length (px) of ``[lo, hi]`` with each of ``n`` pixels starting at ``origin``
    (the pixel-fraction weights of :func:`tvtrack.render.pixel_fractions_box` times ``hi - lo``).

    Parameters
    ----------
    lo, hi : array_like, shape (...)
        Interval ends (px), ``hi >= lo``.
    origin : array_like of int, shape (...)
        Centre of the first pixel.

    Returns
    -------
    ndarray, shape (..., n)
    """
    return _coverage(hi, n, origin) - _coverage(lo, n, origin)


def _halves(center, half, n, origin):
    """Lower and upper half-gate weights, each (..., n)."""
    c = np.asarray(center, dtype=float)
    e = _edges(n, origin)
    mid = _coverage(c, n, origin, e)
    return mid - _coverage(c - half, n, origin, e), _coverage(c + half, n, origin, e) - mid


def quadrant_weights(origin, center, half, shape, dtype=np.float64):
    """Weights of the quadrant discriminator as two matrices.

    Returns
    -------
    wy : ndarray, shape (n, 2, rows)
        Rows: ``[lower + upper, upper - lower]`` half-gate row weights.
    wx : ndarray, shape (n, cols, 2)
        Columns: ``[left + right, right - left]`` half-gate column weights.
        ``wy @ u @ wx = [[energy, Delta_x], [Delta_y, cross]]``.
    """
    o = np.asarray(origin)
    c = np.asarray(center, dtype=float)
    rows, cols = shape
    square = rows == cols and np.ndim(half) == 0 and o.shape == c.shape
    if square and jit.enabled() and dtype == np.float32 and c.ndim == 2 and o.dtype.kind == "i":
        # the frame loop's case, compiled (._frame_kernels): the same bits
        return quadrant_weights_f32(o.astype(np.int64), np.ascontiguousarray(c), float(half), rows)
    if square:
        # both axes and the centre and both gate edges in one pass (the frame loop's case): the same numbers
        p = np.empty(c.shape + (3,))
        p[..., 0], p[..., 1], p[..., 2] = c, c - half, c + half
        cov = _coverage(p, rows, o[..., None])  # (..., 2 axes, 3 points, rows)
        mid = cov[..., 0, :]
        lo, hi = mid - cov[..., 1, :], cov[..., 2, :] - mid
        xl, yl, xr, yu = lo[..., 0, :], lo[..., 1, :], hi[..., 0, :], hi[..., 1, :]
    else:
        xl, xr = _halves(c[..., 0], half, cols, o[..., 0])
        yl, yu = _halves(c[..., 1], half, rows, o[..., 1])
    wy = np.empty(yl.shape[:-1] + (2, rows), dtype)  # sums and differences in float64, one rounding to dtype
    np.add(yl, yu, out=wy[..., 0, :])
    np.subtract(yu, yl, out=wy[..., 1, :])
    wx = np.empty(xl.shape[:-1] + (cols, 2), dtype)
    np.add(xl, xr, out=wx[..., 0])
    np.subtract(xr, xl, out=wx[..., 1])
    return wy, wx


def quadrant_noise(wy, wx, sigma: float, rng: np.random.Generator) -> np.ndarray:
    """Draw the white-noise part of ``(Delta_x, Delta_y)`` directly (exact in distribution).

    The quadrant discriminator is linear in the pixels, so white Gaussian pixel noise of standard
    deviation ``sigma`` enters it as a zero-mean Gaussian pair with covariance
    ``sigma^2 [[|a|^2 |b|^2, (a.c)(b.e)], [., |c|^2 |e|^2]]`` (``a, c``: row weights full/diff,
    ``b, e``: column weights diff/full). Costs two draws per gate instead of one per pixel.

    Returns
    -------
    ndarray, shape (n, 2)
    """
    a, c = wy[:, 0], wy[:, 1]
    e, b = wx[..., 0], wx[..., 1]
    vxx = np.einsum("ny,ny->n", a, a) * np.einsum("nx,nx->n", b, b)
    vyy = np.einsum("ny,ny->n", c, c) * np.einsum("nx,nx->n", e, e)
    vxy = np.einsum("ny,ny->n", a, c) * np.einsum("nx,nx->n", b, e)
    l11 = np.sqrt(vxx)
    l21 = vxy / np.where(l11 > 0, l11, 1.0)
    l22 = np.sqrt(np.maximum(vyy - l21**2, 0.0))
    z = rng.standard_normal((wy.shape[0], 2))
    return sigma * np.stack([l11 * z[:, 0], l21 * z[:, 0] + l22 * z[:, 1]], axis=1)


def quadrant_discriminator(crops, origin, center, half):
    """Quadrant (integral) discriminator, corrected sign: ``(Delta_x, Delta_y, energy)``.

    Computed as two bilinear forms per crop (a batched matrix product), equal to
    ``(u2 + u4) - (u1 + u3)``, ``(u1 + u2) - (u3 + u4)`` and ``u1 + u2 + u3 + u4``.

    Parameters
    ----------
    crops : ndarray, shape (n, rows, cols)
    origin : array_like of int, shape (n, 2)
    center : array_like, shape (n, 2)
        Gate centre (px).
    half : float
        Gate half-size ``A`` (px).

    Returns
    -------
    dx, dy, energy : ndarray, shape (n,)
        In (signal units) x px^2. For a uniform spot of brightness ``d`` and diameter ``D``
        inside the gate, offset by ``delta``: ``Delta ~= 2 d D delta`` for ``|delta| < D/2``.
    """
    u = np.asarray(crops)
    wy, wx = quadrant_weights(origin, center, half, u.shape[-2:], u.dtype)
    m = wy @ (u @ wx)  # (n, 2, 2)
    return m[..., 0, 1], m[..., 1, 0], m[..., 0, 0]


def centroid_discriminator(crops, origin, center, half):
    """Centroid of the gate window minus the gate centre (px): the classical non-modulated tracker's discriminator.

    First moments of the crop over the gate window (pixel-fraction weights of the window edges, pixel centres at
    ``origin + i``) over its zeroth moment; for a spot wholly inside the gate and no background, its offset.

    Parameters
    ----------
    crops : ndarray, shape (n, rows, cols)
    origin : ndarray of int, shape (n, 2)
        Centre ``(x, y)`` of each crop's first pixel.
    center : ndarray, shape (n, 2)
        Gate centres (px).
    half : float
        Gate half-size (px).

    Returns
    -------
    dx, dy : ndarray, shape (n,)
        Slope 1 per px of spot offset.
    """
    crops = np.asarray(crops, dtype=float)
    o, c = np.asarray(origin), np.asarray(center, dtype=float)
    n, rows, cols = crops.shape
    wy, wx = quadrant_weights(o, c, half, (rows, cols))
    ry, cx = wy[:, 0, :], wx[:, :, 0]  # whole-window row and column weights
    xs = o[:, 0, None] + np.arange(cols) - c[:, 0, None]
    ys = o[:, 1, None] + np.arange(rows) - c[:, 1, None]
    colsum = np.einsum("nr,nrc->nc", ry, crops)
    rowsum = np.einsum("nrc,nc->nr", crops, cx)
    m0 = np.einsum("nc,nc->n", colsum, cx)
    m0 = np.where(np.abs(m0) > 1e-9, m0, np.inf)  # an empty window gives no correction
    return np.einsum("nc,nc->n", colsum, cx * xs) / m0, np.einsum("nr,nr->n", rowsum, ry * ys) / m0


def edge_discriminator(crops, origin, center, a: float):
    """Edge discriminator, corrected eqs. (22)-(24): ``u_dx(x_m + a) - u_dx(x_m - a)`` and the
    same in ``y``, with ``u_dx`` the column profile inside the selection window of side ``2a``
    (rows ``[y_m - a, y_m + a]``, fractional weights), linearly interpolated between pixel centres.

    Returns
    -------
    dx, dy : ndarray, shape (n,)
    """
    u = np.asarray(crops, dtype=float)
    o = np.asarray(origin)
    c = np.asarray(center, dtype=float)
    rows, cols = u.shape[-2:]
    hy = interval_weights(c[..., 1] - a, c[..., 1] + a, rows, o[..., 1])
    hx = interval_weights(c[..., 0] - a, c[..., 0] + a, cols, o[..., 0])
    u_dx = np.einsum("...y,...yx->...x", hy, u)  # (24)-type profile along x
    u_dy = np.einsum("...yx,...x->...y", u, hx)
    return (
        _interp(u_dx, o[..., 0], c[..., 0] + a) - _interp(u_dx, o[..., 0], c[..., 0] - a),
        _interp(u_dy, o[..., 1], c[..., 1] + a) - _interp(u_dy, o[..., 1], c[..., 1] - a),
    )


def _interp(profile, origin, x):
    """Linear interpolation of ``profile`` (..., n) sampled at ``origin + i`` at points ``x`` (...)."""
    n = profile.shape[-1]
    pos = np.clip(np.asarray(x, dtype=float) - origin, 0, n - 1)
    i0 = np.minimum(np.floor(pos).astype(int), n - 2)
    f = pos - i0
    if profile.ndim == 2 and i0.shape == profile.shape[:1]:  # one point per profile (the frame loop): a plain gather
        rows = np.arange(profile.shape[0])
        p0, p1 = profile[rows, i0], profile[rows, i0 + 1]
    else:
        p0 = np.take_along_axis(profile, i0[..., None], -1)[..., 0]
        p1 = np.take_along_axis(profile, i0[..., None] + 1, -1)[..., 0]
    return (1 - f) * p0 + f * p1


def polar_errors(dx, dy, theta):
    """Radial and tangential discriminator outputs (corrected (26)-(28) without the ``r``, ``r t``
    factors): ``e_r = dx cos th + dy sin th``, ``e_th = -dx sin th + dy cos th``."""
    c, s = np.cos(theta), np.sin(theta)
    return dx * c + dy * s, -dx * s + dy * c


def static_characteristic(
    render,
    offsets,
    *,
    form: str = "quadrant",
    half: float,
    a: float | None = None,
    axis: int = 0,
    extra=None,
    gate_center=(0.3, -0.2),
) -> np.ndarray:
    """Noise-free discriminator output against the spot's offset from the gate centre (S-curve).

    Parameters
    ----------
    render : callable
        ``render(centers (m, 2), shape (rows, cols), origin (m, 2)) -> (m, rows, cols)``: any spot
        shape (e.g. ``functools.partial(render_spot, "disc", diameter=8)`` adapted to this call).
    offsets : array_like, shape (m,)
        Offsets (px) of the spot from the gate centre along ``axis``.
    form : {"quadrant", "edge"}
    half : float
        Gate half-size ``A`` for the quadrant form (the crop covers the gate).
    a : float, optional
        Edge half-width for the edge form (the spot half-size).
    axis : {0, 1}
        0: offset in ``x`` and return ``Delta_x``; 1: ``y`` and ``Delta_y``.
    extra : ndarray, shape (rows, cols), optional
        Static addition to every crop (an interferer, background), same crop geometry.
    gate_center : (float, float)
        Gate centre (px); its sub-pixel position sets the pixel-grid asymmetry.

    Returns
    -------
    ndarray, shape (m,)
    """
    if form not in FORMS:
        raise ValueError(f"parameter 'form' = {form!r}; it must be one of {FORMS}")
    off = np.asarray(offsets, dtype=float)
    reach = max(half, (a or 0.0)) + np.abs(off).max() + 8
    size = int(2 * np.ceil(reach)) + 3
    centre = np.asarray(gate_center, dtype=float)
    origin = np.broadcast_to(np.floor(centre - (size - 1) / 2).astype(int), (off.size, 2))
    pos = np.tile(centre, (off.size, 1))
    pos[:, axis] += off
    crops = render(pos, (size, size), origin)
    if extra is not None:
        crops = crops + extra
    gate = np.tile(centre, (off.size, 1))
    if form == "quadrant":
        d = quadrant_discriminator(crops, origin, gate, half)[:2]
    elif form == "centroid":
        d = centroid_discriminator(crops, origin, gate, half)
    else:
        if a is None:
            raise ValueError("parameter 'a' is required for the edge form")
        d = edge_discriminator(crops, origin, gate, a)
    return d[axis]


def quadrant_slope_fit(render, diameter: float, half: float) -> dict:
    """Slope of the quadrant S-curve at zero error and its straight-line fit over ``+-D/2``.

    Parameters
    ----------
    render : callable
        Spot renderer as in :func:`static_characteristic`.
    diameter : float
        Spot diameter or side ``D`` (px).
    half : float
        Gate half-size ``A`` (px).

    Returns
    -------
    dict
        ``slope_at_zero``: least-squares slope over offsets ``+-D/8, +-D/4`` (output per px);
        ``fit_slope_halfD``: slope of the line fitted over 9 offsets in ``[-D/2, D/2]``;
        ``max_dev_from_line``: largest deviation from that line over the fitted line's value at
        ``D/2`` (0 for a perfectly linear S-curve). The prediction is ``2 d D`` (section 3).
    """
    D = diameter
    small = np.array([-1.0, -0.5, 0.5, 1.0]) * D / 4
    f = static_characteristic(render, small, form="quadrant", half=half)
    grid = np.linspace(-D / 2, D / 2, 9)
    g = static_characteristic(render, grid, form="quadrant", half=half)
    lin = np.polyfit(grid, g, 1)
    return dict(
        slope_at_zero=float(np.polyfit(small, f, 1)[0]),
        fit_slope_halfD=float(lin[0]),
        max_dev_from_line=float(np.max(np.abs(g - np.polyval(lin, grid))) / (lin[0] * D / 2)),
    )


def two_emitter_discriminator(
    line, origin, lam_hat, *, beta: float, a: float, c1, c2, form: str = "edge", half_gate: float | None = None
):
    """1-D two-emitter discriminator, corrected eq. (6) (emitter 1 at ``lambda - beta``).

    Edge form: ``c1 [u(l - b + a) - u(l - b - a)] + c2 [u(l + b + a) - u(l + b - a)]``
    (``u`` linearly interpolated). Integral form (the 1-D analogue of the quadrant form): each
    edge difference replaced by ``int_{p}^{p + A1} u - int_{p - A1}^{p} u`` around ``p = l -+ b``.

    Parameters
    ----------
    line : ndarray, shape (n, L)
        Observed line ``u(z)`` per trial.
    origin : int
        Coordinate of the first pixel centre.
    lam_hat : ndarray, shape (n,)
        Current estimate.
    c1, c2 : float or ndarray, shape (n,)
        Brightness laws at this time.
    half_gate : float, optional
        ``A1`` for the integral form.

    Returns
    -------
    ndarray, shape (n,)
    """
    u = np.asarray(line, dtype=float)
    lam = np.asarray(lam_hat, dtype=float)
    o = np.full(lam.shape, origin)
    if form == "edge":
        diff = lambda p: _interp(u, o, p + a) - _interp(u, o, p - a)
    elif form == "integral":
        if half_gate is None:
            raise ValueError("parameter 'half_gate' is required for the integral form")
        n = u.shape[-1]

        def diff(p):
            lo, hi = _halves(p, half_gate, n, o)
            return np.einsum("...z,...z->...", hi - lo, u)
    else:
        raise ValueError(f"parameter 'form' = {form!r}; it must be 'edge' or 'integral'")
    return c1 * diff(lam - beta) + c2 * diff(lam + beta)


def two_emitter_slope(
    *, beta: float, a: float, form: str = "edge", half_gate: float | None = None, n: int = 256, step: float = 0.5
) -> float:
    """Numerical slope (output per px of error) of the 1-D two-emitter discriminator at zero error.

    Emitter 1 alone (``c1 = 1``, ``c2 = 0``), a box of half-width ``a`` and unit brightness per
    fully covered pixel on a line of ``n`` pixels, estimate at the line's centre; central
    difference over ``step`` px. Used to normalise the discriminator into a pixel error.

    Parameters
    ----------
    beta, a : float
        Emitter half-spacing and half-width (px), as in :func:`two_emitter_discriminator`.
    form : {"edge", "integral"}
    half_gate : float, optional
        Gate half-width of the integral form (px).
    """
    c = n / 2
    vals = [
        two_emitter_discriminator(
            2 * a * pixel_fractions_box(np.array([lam - beta]), a, n),
            0,
            np.array([c]),
            beta=beta,
            a=a,
            c1=1.0,
            c2=0.0,
            form=form,
            half_gate=half_gate,
        )[0]
        for lam in (c - step / 2, c + step / 2)
    ]
    return (vals[1] - vals[0]) / step
