"""Interacting multiple model (IMM) estimator batched over trials, built on
:mod:`tvtrack.filters.kalman` (Joseph-form updates).

Standard IMM cycle (Bar-Shalom, Li & Kirubarajan 2001, §11.6.6), the same order as
``filterpy.kalman.IMMEstimator`` (``predict`` then ``update`` each frame):

1. mixing: ``cbar_j = sum_i mu_i M_ij``, ``omega_ij = mu_i M_ij / cbar_j``,
   ``x0_j = sum_i omega_ij x_i``, ``P0_j = sum_i omega_ij (P_i + (x_i - x0_j)(x_i - x0_j)^T)``;
2. mode-matched prediction ``x_j, P_j <- F_j x0_j, F_j P0_j F_j^T + Q_j``;
3. mode-matched update and likelihood ``L_j = N(nu_j; 0, S_j)``;
4. ``mu_j = cbar_j L_j / sum``; combined ``x = sum mu_j x_j``, ``P = sum mu_j (P_j + dx dx^T)``.

A missing measurement (NaN) skips steps 3-4's update: ``mu = cbar`` and the priors are kept
(``coast="mix"``, the textbook cycle), or, with ``coast="frozen"``, skips the mixing too while
the measurement is missing: each mode predicts on its own and ``mu`` stays as it was, so the
constant-acceleration estimate is not pulled toward the constant-velocity mode's zero during an
occlusion; with ``coast="mode"`` the most probable mode at the last measurement takes all the
probability while the measurement is missing (no mixing), so the combined prediction is that
mode's own (e.g. CA-conditioned coasting after a manoeuvre). ``loglik`` is the log of the predictive density of each present measurement,
``log sum_j cbar_j L_j``, summed over frames (for tuning by maximum likelihood).
All models share one state space (e.g. ``(x, v, a)`` with the constant-velocity model zeroing
``a``), see :func:`cv_ca_models`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .kalman import kf_predict, kf_update
from .polynomial import taylor_transition

__all__ = ["IMMOutput", "imm_run", "cv_ca_models"]


def cv_ca_models(q_cv: float, q_ca: float):
    """Constant-velocity and constant-acceleration models in the state ``(x, v, a)``, unit step.

    CV: ``F`` of order 1 padded with ``a <- 0``; discrete white-acceleration noise
    ``q_cv (dt^4/4, dt^3/2; dt^3/2, dt^2)``. CA: ``F`` of order 2 with discrete white-jerk
    noise ``q_ca (dt^4/4, dt^3/2, dt^2/2; ...; dt^2/2, dt, 1)`` (Bar-Shalom et al. §6.3).

    Parameters
    ----------
    q_cv : float
        Variance of the per-frame acceleration noise of CV, elements^2/frame^4 (>= 0).
    q_ca : float
        Variance of the per-frame acceleration increment of CA, elements^2/frame^4 (>= 0).

    Returns
    -------
    Fs : ndarray, shape (2, 3, 3)
    Qs : ndarray, shape (2, 3, 3)
    """
    if not (q_cv >= 0 and q_ca >= 0):
        raise ValueError(f"process noises q_cv = {q_cv!r}, q_ca = {q_ca!r}; both must be >= 0")
    F_cv = np.zeros((3, 3))
    F_cv[:2, :2] = taylor_transition(1)
    g_cv = np.array([0.5, 1.0, 0.0])
    g_ca = np.array([0.5, 1.0, 1.0])
    Fs = np.stack([F_cv, taylor_transition(2)])
    Qs = np.stack([q_cv * np.outer(g_cv, g_cv), q_ca * np.outer(g_ca, g_ca)])
    return Fs, Qs


@dataclass(frozen=True)
class IMMOutput:
    """History; time after the batch axes.

    Attributes
    ----------
    x : ndarray, shape (..., T, n)       combined posterior (prior where the measurement is missing)
    P : ndarray, shape (..., T, n, n)
    mu : ndarray, shape (..., T, r)      mode probabilities
    x_prior : ndarray, shape (..., T, n) combined prior before each frame's measurement
    P_prior : ndarray, shape (..., T, n, n)
    loglik : ndarray, shape (...)        log predictive likelihood of the present measurements
    """

    x: np.ndarray
    P: np.ndarray
    mu: np.ndarray
    x_prior: np.ndarray
    P_prior: np.ndarray
    loglik: np.ndarray


def _combine(xs, Ps, w):
    """``sum_j w_j x_j`` and ``sum_j w_j (P_j + d d^T)``; xs (..., r, n), w (..., r)."""
    x = np.einsum("...j,...ji->...i", w, xs)
    d = xs - x[..., None, :]
    P = np.einsum("...j,...jab->...ab", w, Ps + d[..., :, None] * d[..., None, :])
    return x, 0.5 * (P + np.swapaxes(P, -1, -2))


#: the tolerance of ``np.isclose(s, 1.0)`` (``atol + rtol * 1.0``), written out: ``np.isclose`` costs ~10 us a call
#: and the checks run on every call of the compiled twin
_ONE_TOL = 1e-8 + 1e-5 * 1.0


def _check_broadcast(name: str, a: np.ndarray, shape: tuple) -> None:
    """Raise a ValueError naming parameter ``name`` unless ``a`` broadcasts to ``shape``."""
    if a.ndim <= len(shape) and a.shape == shape[len(shape) - a.ndim :]:
        return  # the usual case, without NumPy's broadcasting machinery
    try:
        ok = np.broadcast_shapes(a.shape, shape) == shape
    except ValueError:
        ok = False
    if not ok:
        raise ValueError(f"parameter '{name}' has shape {a.shape}; it must broadcast to {shape}")


def imm_inputs(batch: tuple, Fs, Qs, transition, x0, P0, mu0, coast: str):
    """The parameters of :func:`imm_run` as checked float arrays: the one check of :func:`imm_run` and of its
    compiled twin :func:`tvtrack.filters._imm_kernel.imm_states`.

    Parameters
    ----------
    batch : tuple of int
        Batch shape of the measurements (``zs.shape[:-2]`` in :func:`imm_run`).
    Fs, Qs, transition, x0, P0, mu0, coast
        As for :func:`imm_run`.

    Returns
    -------
    Fs : ndarray, shape (r, n, n)
    Qs, M, x0, P0 : ndarray
        Of shapes (..., r, n, n), (..., r, r), (..., n) and (..., n, n) broadcasting to the batch axes (not broadcast).
    mu0 : ndarray, shape (r,)

    Raises
    ------
    ValueError
        A shape that does not fit, ``transition`` not row-stochastic, ``mu0`` not probabilities summing to 1, or an
        unknown ``coast``.
    """
    Fs, Qs = np.asarray(Fs, float), np.asarray(Qs, float)
    M = np.asarray(transition, dtype=float)
    if Fs.ndim != 3 or Fs.shape[0] < 1 or Fs.shape[1] != Fs.shape[2]:
        raise ValueError(f"parameter 'Fs' has shape {Fs.shape}; it must be (r, n, n) with r >= 1")
    r, n = Fs.shape[:2]
    if Qs.shape[-3:] != Fs.shape or M.shape[-2:] != (r, r):
        raise ValueError(f"inconsistent IMM shapes: Fs {Fs.shape}, Qs {Qs.shape}, transition {M.shape}")
    # not np.any(M < 0) and np.allclose(row sums, 1.0), cheaper (a NaN fails either way)
    if M.size and not (M.min() >= 0 and all(abs(s - 1.0) <= _ONE_TOL for s in M.sum(axis=-1).ravel().tolist())):
        raise ValueError("parameter 'transition' must be a row-stochastic matrix")
    if coast not in ("mix", "frozen", "mode"):
        raise ValueError(f"parameter 'coast' = {coast!r}; it must be 'mix', 'frozen' or 'mode'")
    mu0 = np.asarray(mu0, dtype=float)
    if mu0.shape != (r,) or not (mu0.min() >= 0 and abs(mu0.sum() - 1.0) <= _ONE_TOL):
        raise ValueError(f"parameter 'mu0' = {mu0}; it must be {r} probabilities summing to 1")
    x0, P0 = np.asarray(x0, float), np.asarray(P0, float)
    for name, a, core in (("Qs", Qs, Fs.shape), ("transition", M, (r, r)), ("x0", x0, (n,)), ("P0", P0, (n, n))):
        _check_broadcast(name, a, batch + core)
    return Fs, Qs, M, x0, P0, mu0


def imm_run(zs, Fs, Qs, H, R, transition, x0, P0, mu0, coast: str = "mix") -> IMMOutput:
    """Run the IMM over measurements ``zs``.

    Parameters
    ----------
    zs : array_like, shape (..., T, m)
        Measurements; a row with a NaN is missing.
    Fs : array_like, shape (r, n, n)
        Mode transition matrices.
    Qs : array_like, shape (r, n, n) or (..., r, n, n)
        Process noise covariances; leading axes broadcast against the batch axes of ``zs`` (several
        tunings in one run: each batch element's numbers are those of its own run, tested bit for bit).
    H : array_like, shape (m, n)
    R : array_like, shape (m, m)
    transition : array_like, shape (r, r) or (..., r, r)
        Markov mode transition matrix, ``transition[i, j] = P(mode j next | mode i now)``; rows sum to 1;
        leading axes broadcast against the batch axes of ``zs``, as for ``Qs``.
    x0 : array_like, shape (n,) or (..., n)
        Initial estimate (the same for every mode), treated as the posterior before frame 0.
    P0 : array_like, shape (n, n) or (..., n, n)
    mu0 : array_like, shape (r,)
        Initial mode probabilities.
    coast : {"mix", "frozen", "mode"}
        While a measurement is missing: the textbook cycle ("mix"), no mixing and frozen mode
        probabilities ("frozen"), or no mixing and the most probable mode only ("mode").

    Returns
    -------
    IMMOutput
    """
    zs = np.asarray(zs, dtype=float)
    batch, T = zs.shape[:-2], zs.shape[-2]
    Fs, Qs, M, x0, P0, mu0 = imm_inputs(batch, Fs, Qs, transition, x0, P0, mu0, coast)
    r, n = Fs.shape[:2]
    xs = np.broadcast_to(x0, batch + (n,))[..., None, :].repeat(r, axis=-2)
    Ps = np.broadcast_to(P0, batch + (n, n))[..., None, :, :].repeat(r, axis=-3)
    mu = np.broadcast_to(mu0, batch + (r,)).copy()
    out = {k: [] for k in ("x", "P", "mu", "x_prior", "P_prior")}
    loglik_total = np.zeros(batch)
    eye = np.eye(r)
    for t in range(T):
        z = zs[..., t, :]
        present = np.all(np.isfinite(z), axis=-1)
        # 1. mixing (none while coasting with frozen mode probabilities)
        Mt = M if coast == "mix" else np.where(present[..., None, None], M, eye)
        if coast == "mode":
            top_mode = eye[np.argmax(mu, axis=-1)]
            mu = np.where(present[..., None], mu, top_mode)
        cbar = np.einsum("...i,...ij->...j", mu, Mt)  # (..., r)
        live = cbar > 0  # a mode with no probability keeps its own state
        omega = np.where(live[..., None, :], mu[..., :, None] * Mt / np.where(live, cbar, 1.0)[..., None, :], eye)
        x_mix = np.einsum("...ij,...ia->...ja", omega, xs)
        d = xs[..., :, None, :] - x_mix[..., None, :, :]  # (..., i, j, n)
        P_mix = np.einsum("...ij,...ijab->...jab", omega, Ps[..., :, None, :, :] + d[..., :, None] * d[..., None, :])
        # 2. mode-matched prediction
        xs, Ps = kf_predict(x_mix, P_mix, Fs, Qs)
        xp, Pp = _combine(xs, Ps, cbar)
        out["x_prior"].append(xp)
        out["P_prior"].append(Pp)
        # 3. mode-matched update with likelihoods
        zz = np.where(present[..., None], z, 0.0)[..., None, :]
        xs_u, Ps_u, nu, S = kf_update(xs, Ps, zz, H, R, present[..., None])
        m = nu.shape[-1]
        maha = np.einsum("...i,...i->...", nu, np.linalg.solve(S, nu[..., None])[..., 0])
        loglik = -0.5 * (maha + np.linalg.slogdet(S)[1] + m * np.log(2 * np.pi))
        # 4. mode probabilities (log domain, normalised) and combination
        logw = np.log(np.maximum(cbar, 1e-300)) + loglik
        top = logw.max(axis=-1, keepdims=True)
        w = np.exp(logw - top)
        loglik_total += np.where(present, top[..., 0] + np.log(w.sum(axis=-1)), 0.0)
        mu = np.where(present[..., None], w / w.sum(axis=-1, keepdims=True), cbar)
        xs, Ps = xs_u, Ps_u
        x, P = _combine(xs, Ps, mu)
        out["x"].append(x)
        out["P"].append(P)
        out["mu"].append(mu)
    axis = len(batch)
    return IMMOutput(**{k: np.stack(v, axis=axis) for k, v in out.items()}, loglik=loglik_total)
