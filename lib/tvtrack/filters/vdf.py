"""Variable-dimension (VD) filter of Bar-Shalom & Birmiwal (1982), batched over trials.

The textbook analogue of Fisenko et al.'s 2nd -> 3rd order switch (Bar-Shalom, Li & Kirubarajan
2001, §11.5): a constant-velocity Kalman filter in the state ``(x, v, a)`` with ``a = 0`` and no
acceleration variance; a fading-memory sum of normalised innovations squared

    rho_t = lam rho_{t-1} + nu_t^2 / S_t,      lam = 1 - 1/window

detects a manoeuvre when it exceeds a threshold. The manoeuvre is then taken to have started
``window`` frames back, at ``t0 = t - window``: the state is re-initialised there from the CV
posterior at ``t0 - 1`` and the measurement at ``t0``,

    a = 2 (z_t0 - (x + v)),   x = z_t0,   v = v_{t0-1} + a      (unit frame time)

with the covariance of those linear combinations of the CV errors and the measurement noise,
and the constant-acceleration filter is re-run over ``t0+1 .. t``. The history keeps the online
estimates (what the filter reported at each frame). Choices of this implementation: no return to
CV (the scenario's acceleration persists; the paper's scheme does not return to 2nd order
either); ``rho`` is frozen while the measurement is missing and the detector re-arms after
``window + 2`` consecutive measurements.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .imm import cv_ca_models
from .kalman import joseph_covariance

__all__ = ["VDOutput", "vd_filter_run", "vd_restart_covariance"]


@dataclass(frozen=True)
class VDOutput:
    """History; time after the batch axes.

    Attributes
    ----------
    x : ndarray, shape (..., T, 3)          online posterior (prior where the measurement is missing)
    x_prior : ndarray, shape (..., T, 3)    prediction before each frame's measurement
    var_prior : ndarray, shape (..., T)     its position variance ``P^-_00``, elements²
    rho : ndarray, shape (..., T)           detector statistic (NaN while in CA mode)
    ca : ndarray of bool, shape (..., T)    CA mode after the frame
    detection_frame : ndarray of int, shape (...)   -1 if none
    """

    x: np.ndarray
    x_prior: np.ndarray
    var_prior: np.ndarray
    rho: np.ndarray
    ca: np.ndarray
    detection_frame: np.ndarray


def vd_restart_covariance(P_xv: np.ndarray, sigma_eps: float) -> np.ndarray:
    """Covariance of the re-initialised ``(x, v, a)`` from the CV posterior covariance at ``t0 - 1``.

    The errors are linear in ``(e_x, e_v)`` at ``t0 - 1`` and the measurement error ``e_z`` at ``t0``:
    ``e_x' = e_z``, ``e_a' = 2 (e_z - e_x - e_v)``, ``e_v' = e_v + e_a'``.

    Parameters
    ----------
    P_xv : ndarray, shape (..., 2, 2)
        Posterior covariance of ``(x, v)`` at ``t0 - 1``, elements², elements²/frame, elements²/frame².
    sigma_eps : float
        Measurement noise RMS, elements.

    Returns
    -------
    ndarray, shape (..., 3, 3)
    """
    M = np.array([[0.0, 0.0, 1.0], [-2.0, -1.0, 2.0], [-2.0, -2.0, 2.0]])  # rows x, v, a; columns e_x, e_v, e_z
    Sigma = np.zeros(P_xv.shape[:-2] + (3, 3))
    Sigma[..., :2, :2] = P_xv
    Sigma[..., 2, 2] = sigma_eps**2
    return M @ Sigma @ M.T


def _predict_update(x, P, z, seen, Q, F, sigma2):
    """One Kalman cycle on (B, 3) states with per-trial ``Q`` (B, 3, 3); returns the prior too."""
    x = x @ F.T
    P = F @ P @ F.T + Q
    xp, var_p = x, P[:, 0, 0]
    S = var_p + sigma2
    nu = np.where(seen, z - x[:, 0], 0.0)
    K = P[:, :, 0] / S[:, None] * seen[:, None]
    x = x + K * nu[:, None]
    P = joseph_covariance(P, K[:, :, None], np.array([[1.0, 0.0, 0.0]]), sigma2)
    return x, P, xp, var_p, nu, S


def vd_filter_run(
    z, visible, q_cv: float, q_ca, sigma_eps: float, window: int, threshold: float, x0=None, P0=None
) -> VDOutput:
    """Run the VD filter on independent channels.

    Parameters
    ----------
    z : array_like, shape (..., T)
        Measured coordinate, elements (ignored where not visible).
    visible : array_like of bool, shape (T,) or (..., T)
    q_cv : float
        Process noise of the CV model (:func:`tvtrack.filters.imm.cv_ca_models`), elements²/frame⁴.
    q_ca : float or array_like broadcasting to the batch shape ``z.shape[:-1]``
        Process noise of the CA model, elements²/frame⁴; one per series runs a grid of settings in one call
        (each series' numbers those of its own call, tested bit for bit).
    sigma_eps : float
        Measurement noise RMS, elements.
    window : int
        Detector memory ``1 / (1 - lam)`` and the back-in-time restart depth, frames (>= 2).
    threshold : float
        Detection threshold on ``rho`` (np.inf: CV only).
    x0, P0 : array_like, shapes (3,) and (3, 3), optional
        Prior before frame 0; default ``0`` and ``diag(1e6, 1e4, 0)`` (diffuse position and velocity).

    Returns
    -------
    VDOutput
    """
    z = np.asarray(z, dtype=float)
    if not sigma_eps > 0:
        raise ValueError(f"parameter 'sigma_eps' = {sigma_eps!r}; it must be > 0")
    if not (isinstance(window, (int, np.integer)) and window >= 2):
        raise ValueError(f"parameter 'window' = {window!r}; it must be an integer >= 2")
    if not threshold > 0:
        raise ValueError(f"parameter 'threshold' = {threshold!r}; it must be > 0")
    batch, T = z.shape[:-1], z.shape[-1]
    B = int(np.prod(batch, dtype=np.int64))
    zt = np.moveaxis(z.reshape(B, T), -1, 0)
    vis = np.moveaxis(np.broadcast_to(np.asarray(visible, dtype=bool), z.shape).reshape(B, T), -1, 0)
    q_b = np.broadcast_to(np.asarray(q_ca, dtype=float), batch).reshape(B)
    Fs, Qs = cv_ca_models(q_cv, float(q_b.min()) if B else 0.0)
    Q1 = q_b[:, None, None] * cv_ca_models(q_cv, 1.0)[1][1]  # q_ca (0.5, 1, 1)(0.5, 1, 1)^T per series
    F = Fs[1]  # CA transition; CV trials keep a = 0 and no a-variance
    sigma2 = sigma_eps**2
    lam = 1.0 - 1.0 / window
    x = np.broadcast_to(np.zeros(3) if x0 is None else np.asarray(x0, float), (B, 3)).copy()
    P = np.broadcast_to(np.diag([1e6, 1e4, 0.0]) if P0 is None else np.asarray(P0, float), (B, 3, 3)).copy()
    x[:, 2] = 0.0
    P[:, 2, :] = P[:, :, 2] = 0.0
    depth = window + 2  # ring of posteriors back to t0 - 1
    ring_x, ring_P = np.empty((depth, B, 3)), np.empty((depth, B, 3, 3))
    ca = np.zeros(B, dtype=bool)
    rho = np.zeros(B)
    run = np.zeros(B, dtype=np.int64)  # consecutive measurements up to now
    detected = np.full(B, -1, dtype=np.int64)
    out_x, out_xp = np.empty((T, B, 3)), np.empty((T, B, 3))
    out_vp, out_rho, out_ca = np.empty((T, B)), np.full((T, B), np.nan), np.empty((T, B), dtype=bool)
    for t in range(T):
        seen = vis[t]
        Q = np.where(ca[:, None, None], Q1, Qs[0])
        x, P, out_xp[t], out_vp[t], nu, S = _predict_update(x, P, zt[t], seen, Q, F, sigma2)
        run = np.where(seen, run + 1, 0)
        rho = np.where(seen & ~ca, lam * rho + nu**2 / S, rho)
        out_rho[t] = np.where(ca, np.nan, rho)
        alarm = ~ca & (run >= depth) & (rho > threshold)
        if alarm.any():
            idx = np.flatnonzero(alarm)
            t0 = t - window
            prev = (t0 - 1) % depth
            xb, Pb = ring_x[prev, idx], ring_P[prev, idx]
            a = 2.0 * (zt[t0, idx] - xb[:, 0] - xb[:, 1])
            xr = np.stack([zt[t0, idx], xb[:, 1] + a, a], axis=-1)
            Pr = vd_restart_covariance(Pb[:, :2, :2], sigma_eps)
            for s in range(t0 + 1, t + 1):  # re-run the CA filter over the window
                xr, Pr = _predict_update(xr, Pr, zt[s, idx], np.ones(idx.size, bool), Q1[idx], F, sigma2)[:2]
            x[idx], P[idx] = xr, Pr
            ca[idx] = True
            detected[idx] = t
        ring_x[t % depth], ring_P[t % depth] = x, P
        out_x[t], out_ca[t] = x, ca

    def back(a, extra=()):
        return np.moveaxis(a, 0, 1).reshape(batch + (T,) + extra)

    return VDOutput(
        back(out_x, (3,)), back(out_xp, (3,)), back(out_vp), back(out_rho), back(out_ca), detected.reshape(batch)
    )
