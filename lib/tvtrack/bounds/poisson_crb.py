"""Cramer-Rao bound for binned Poisson photon counts of ``Q`` objects in linear motion.

Model (this project's addition to paper 002, on the paper's imaging model): the count of pixel
``(row k, col i)`` in frame ``l`` is Poisson with mean

    Lambda_ikl = m sum_j F_xji(mu_xjl) F_yjk(mu_yjl) + b,   mu_xjl = x0_j + Vx_j t_l,

with the pixel-integrated Gaussian fractions ``F`` (unnumbered in the paper; (U3) in this project).
The Fisher information of the motion states ``theta = (x0_1, y0_1, Vx_1, Vy_1, ..., x0_Q, ..., Vy_Q)`` is

    I = sum_{l,i,k} grad Lambda_ikl grad Lambda_ikl^T / Lambda_ikl,

with ``dLambda/dx0_j = m F_yjk dF_xji/dmu`` (eq. (4), ``dF/dmu = N(alpha) - N(beta)``) and
``dLambda/dVx_j = t_l dLambda/dx0_j`` (eq. (6)). For a fixed number of photons per object the
data are a superposition of multinomials; its information equals this Poisson one for a single
object without noise and is close to it otherwise (the notebook says which it compares).

Units: pixels (x along columns, y along rows, centre of pixel i at i) and frames.
"""

from __future__ import annotations

import numpy as np

from ..render import pixel_fractions_gaussian

__all__ = ["fisher_linear_motion", "crb_linear_motion", "position_crb_sum"]

_SQRT_2PI = np.sqrt(2.0 * np.pi)


def _dfraction(center, sigma, n):
    """d/dmu of the pixel fractions: ``(phi(a) - phi(b)) / sigma``, shape (..., n)."""
    c = np.asarray(center, dtype=float)[..., None]
    lo = np.arange(n) - 0.5
    a = (lo - c) / sigma
    b = a + 1.0 / sigma
    return (np.exp(-0.5 * a * a) - np.exp(-0.5 * b * b)) / (_SQRT_2PI * sigma)


def fisher_linear_motion(
    theta, times, shape, sigma_px: float, photons: float, noise_per_pixel: float, chunk: int = 16
) -> np.ndarray:
    """Fisher information of the stacked motion states.

    Parameters
    ----------
    theta : ndarray, shape (..., Q, 4)
        True states (px, px/frame).
    times : ndarray, shape (T,)
    shape : (int, int)
        Window (rows, cols).
    sigma_px : float
        PSF standard deviation (px, > 0).
    photons : float
        Mean target photons per object per frame (> 0).
    noise_per_pixel : float
        Mean noise photons per pixel per frame (>= 0).
    chunk : int
        Configurations evaluated together (bounds memory: ``chunk * 4Q * T * rows * cols``).

    Returns
    -------
    ndarray, shape (..., 4Q, 4Q)
        Ordered ``(x0, y0, Vx, Vy)`` per object.
    """
    if sigma_px <= 0:
        raise ValueError(f"sigma_px = {sigma_px} must be > 0")
    if photons <= 0:
        raise ValueError(f"photons = {photons} must be > 0")
    if noise_per_pixel < 0:
        raise ValueError(f"noise_per_pixel = {noise_per_pixel} must be >= 0")
    theta = np.asarray(theta, dtype=float)
    batch = theta.shape[:-2]
    q = theta.shape[-2]
    flat = theta.reshape((-1, q, 4))
    t = np.asarray(times, dtype=float)
    rows, cols = shape
    out = np.empty((flat.shape[0], 4 * q, 4 * q))
    for s in range(0, flat.shape[0], chunk):
        th = flat[s : s + chunk]  # (c, Q, 4)
        mux = th[:, :, None, 0] + th[:, :, None, 2] * t  # (c, Q, T)
        muy = th[:, :, None, 1] + th[:, :, None, 3] * t
        fx = pixel_fractions_gaussian(mux, sigma_px, cols)  # (c, Q, T, C)
        fy = pixel_fractions_gaussian(muy, sigma_px, rows)  # (c, Q, T, R)
        dx = _dfraction(mux, sigma_px, cols)
        dy = _dfraction(muy, sigma_px, rows)
        lam = photons * np.einsum("cqtr,cqtk->ctrk", fy, fx) + noise_per_pixel
        if noise_per_pixel == 0:
            lam = np.maximum(lam, 1e-300)
        gx = photons * fy[..., :, None] * dx[..., None, :]  # dLambda/dx0 (4)
        gy = photons * dy[..., :, None] * fx[..., None, :]  # dLambda/dy0 (5)
        tt = t[None, None, :, None, None]
        g = np.stack([gx, gy, gx * tt, gy * tt], axis=2)  # (c, Q, 4, T, R, C) (6),(7)
        g = g.reshape(g.shape[0], 4 * q, *g.shape[3:]) / np.sqrt(lam)[:, None]
        out[s : s + chunk] = np.einsum("cptrk,cstrk->cps", g, g)
    return out.reshape(batch + (4 * q, 4 * q))


def crb_linear_motion(theta, times, shape, sigma_px: float, photons: float, noise_per_pixel: float) -> np.ndarray:
    """Inverse Fisher information (the CRB covariance), shape (..., 4Q, 4Q); singular
    information (e.g. coincident objects) gives ``inf`` on the diagonal, never NaN."""
    return crb_from_fisher(fisher_linear_motion(theta, times, shape, sigma_px, photons, noise_per_pixel))


def crb_from_fisher(fim) -> np.ndarray:
    """The CRB covariance from a Fisher information ``fim`` of shape (..., k, k) (:func:`crb_linear_motion`
    without recomputing the information): its inverse, ``inf`` on the diagonal where it is singular."""
    fim = np.asarray(fim, dtype=float)
    cond = np.linalg.cond(fim)
    ok = np.isfinite(cond) & (cond < 1e14)
    safe = np.where(ok[..., None, None], fim, np.eye(fim.shape[-1]))
    inv = np.linalg.inv(safe)
    return np.where(ok[..., None, None], inv, np.diag(np.full(fim.shape[-1], np.inf)))


def position_crb_sum(crb) -> np.ndarray:
    """Sum of the CRB variances of all ``x0_j`` and ``y0_j`` (the paper's "total variance of the
    coordinate estimates"), shape (...)."""
    d = np.diagonal(crb, axis1=-2, axis2=-1)
    q = d.shape[-1] // 4
    return d.reshape(d.shape[:-1] + (q, 4))[..., :2].sum(axis=(-1, -2))
