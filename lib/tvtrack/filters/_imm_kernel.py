"""Compiled per-trial twin of :func:`tvtrack.filters.imm.imm_run` for a scalar position measurement.

:func:`imm_run` is batched NumPy: each frame is ~60 operations on stacks of 3 x 3 matrices, so a grid of IMM
settings on a few hundred series costs seconds (notebook 001 tunes its IMM comparator over 30 settings for every
training world of its register). This kernel runs the same cycle (Bar-Shalom, Li & Kirubarajan 2001, §11.6.6:
mixing, mode-matched prediction, Joseph-form update with ``H = (1, 0, ..., 0)``, log-domain mode probabilities,
combination; the three ways to coast of :func:`imm_run`) one trial at a time as scalar code compiled by numba
(``@njit``, no ``fastmath``), and returns only the combined posterior state. It is a second implementation of the
same equations, tested equal to :func:`imm_run` to rounding (``tests/papers/test_001_kalman_imm.py``): its sums
are taken in another order than NumPy's matrix products, so the numbers agree to ~1e-12 relative, not bit for bit.
Without numba (or with ``TVTRACK_NO_JIT=1``) :func:`imm_states` runs :func:`imm_run` itself.
"""

from __future__ import annotations

import math

import numpy as np

from .. import jit
from .imm import imm_inputs, imm_run

__all__ = ["COASTS", "imm_states", "kernel_python"]

#: coast option -> integer code passed to the kernel
COASTS = {"mix": 0, "frozen": 1, "mode": 2}

_compiled = {}


@jit.njit
def _mix(mu, M, coast, present, xs, Ps, cbar, xm, Pm, Mt, w):
    """Step 1 of :func:`imm_run` for one trial: ``mu`` (r,) (the most probable mode's alone when coasting with
    ``coast == 2``), ``cbar`` (r,), the mixed states ``xm`` (r, n) and covariances ``Pm`` (r, n, n); ``Mt``
    (r, r) and ``w`` (r,) are work space."""
    r, n = xs.shape
    for i in range(r):
        for j in range(r):
            Mt[i, j] = M[i, j] if (coast == 0 or present) else (1.0 if i == j else 0.0)
    if coast == 2 and not present:
        top = 0
        for j in range(1, r):
            if mu[j] > mu[top]:
                top = j
        for j in range(r):
            mu[j] = 1.0 if j == top else 0.0
    for j in range(r):
        s = 0.0
        for i in range(r):
            s += mu[i] * Mt[i, j]
        cbar[j] = s
    for j in range(r):
        for i in range(r):
            w[i] = mu[i] * Mt[i, j] / cbar[j] if cbar[j] > 0 else (1.0 if i == j else 0.0)
        for a in range(n):
            s = 0.0
            for i in range(r):
                s += w[i] * xs[i, a]
            xm[j, a] = s
        for a in range(n):
            for c in range(n):
                s = 0.0
                for i in range(r):
                    s += w[i] * (Ps[i, a, c] + (xs[i, a] - xm[j, a]) * (xs[i, c] - xm[j, c]))
                Pm[j, a, c] = s


@jit.njit
def _predict(Fs, Qs, xm, Pm, xs, Ps, tmp):
    """Step 2 for one trial: ``xs = F xm``, ``Ps = sym(F Pm F^T + Q)`` per mode (``Pm`` overwritten; ``tmp``
    (n, n) work space)."""
    r, n = xs.shape
    for j in range(r):
        for a in range(n):
            s = 0.0
            for c in range(n):
                s += Fs[j, a, c] * xm[j, c]
            xs[j, a] = s
        for a in range(n):
            for c in range(n):
                s = 0.0
                for d in range(n):
                    s += Fs[j, a, d] * Pm[j, d, c]
                tmp[a, c] = s
        for a in range(n):
            for c in range(n):
                s = 0.0
                for d in range(n):
                    s += tmp[a, d] * Fs[j, c, d]
                Pm[j, a, c] = s + Qs[j, a, c]
        for a in range(n):
            for c in range(n):
                Ps[j, a, c] = 0.5 * (Pm[j, a, c] + Pm[j, c, a])


@jit.njit
def _update(z, R, cbar, mu, xs, Ps, K, tmp, logw):
    """Steps 3-4 for one trial with a measurement ``z`` of the position: Joseph-form update of each mode
    (``H = e1``), its log-likelihood and the mode probabilities ``mu``; ``K`` (n,), ``tmp`` (n, n) and ``logw``
    (r,) are work space."""
    r, n = xs.shape
    for j in range(r):
        S = Ps[j, 0, 0] + R
        nu = z - xs[j, 0]
        for a in range(n):
            K[a] = Ps[j, a, 0] / S
        for a in range(n):
            xs[j, a] += K[a] * nu
        # (I - K H) P (I - K H)^T + K R K^T, H = e1: row a of (I - K H) P is P[a] - K[a] P[0]
        for a in range(n):
            for c in range(n):
                tmp[a, c] = Ps[j, a, c] - K[a] * Ps[j, 0, c]
        for a in range(n):
            for c in range(a, n):
                Ps[j, a, c] = 0.5 * (
                    (tmp[a, c] - tmp[a, 0] * K[c] + K[a] * R * K[c]) + (tmp[c, a] - tmp[c, 0] * K[a] + K[c] * R * K[a])
                )
                Ps[j, c, a] = Ps[j, a, c]
        logw[j] = np.log(max(cbar[j], 1e-300)) + -0.5 * (nu * nu / S + np.log(S) + np.log(2 * np.pi))
    top = -np.inf
    for j in range(r):
        top = max(top, logw[j])
    tot = 0.0
    for j in range(r):
        logw[j] = np.exp(logw[j] - top)
        tot += logw[j]
    for j in range(r):
        mu[j] = logw[j] / tot


def kernel_python(zs, Fs, Qs, R, M, x0, P0, mu0, coast, out):
    """Combined posterior states ``out`` (B, T, n) of the IMM on scalar position measurements ``zs`` (B, T) (NaN:
    missing); ``Fs, Qs`` (r, n, n), ``R`` the measurement variance, ``M`` (r, r), ``x0`` (n,), ``P0`` (n, n),
    ``mu0`` (r,), ``coast`` a code of :data:`COASTS`. The statements follow :func:`imm_run` step by step
    (:func:`_mix`, :func:`_predict`, :func:`_update`)."""
    B, T = zs.shape
    r, n = Fs.shape[0], Fs.shape[1]
    for b in range(B):
        xs, Ps = np.empty((r, n)), np.empty((r, n, n))
        xm, Pm = np.empty((r, n)), np.empty((r, n, n))
        for j in range(r):  # element by element: no shape check, whose error message numba would compile
            for a in range(n):
                xs[j, a] = x0[a]
                for c in range(n):
                    Ps[j, a, c] = P0[a, c]
        mu, cbar = mu0.copy(), np.empty(r)
        Mt, w, K, tmp = np.empty((r, r)), np.empty(r), np.empty(n), np.empty((n, n))
        for t in range(T):
            z = zs[b, t]
            present = np.isfinite(z)
            _mix(mu, M, coast, present, xs, Ps, cbar, xm, Pm, Mt, w)
            _predict(Fs, Qs, xm, Pm, xs, Ps, tmp)
            if present:
                _update(z, R, cbar, mu, xs, Ps, K, tmp, w)
            else:
                for j in range(r):
                    mu[j] = cbar[j]
            for a in range(n):
                s = 0.0
                for j in range(r):
                    s += mu[j] * xs[j, a]
                out[b, t, a] = s


def _kernel():
    """:func:`kernel_python` compiled (with its steps) on its first call in this process."""
    if "imm" not in _compiled:
        _compiled["imm"] = jit.njit(kernel_python)
    return _compiled["imm"]


def _per_trial(a: np.ndarray, core: tuple, batch: tuple) -> np.ndarray:
    """``a`` (checked to broadcast to ``batch + core``) as the C-contiguous ``core`` array the kernel takes when its
    leading axes are all of length 1 (or absent), else broadcast to one per trial, shape ``(B,) + core``."""
    if a.shape == core:
        return np.ascontiguousarray(a)
    lead = a.shape[: max(a.ndim - len(core), 0)]
    if all(k == 1 for k in lead):
        return np.ascontiguousarray(np.broadcast_to(a.reshape(a.shape[len(lead) :]), core))
    return np.ascontiguousarray(np.broadcast_to(a, batch + core).reshape((math.prod(batch),) + core))


def imm_states(zs, Fs, Qs, R: float, transition, x0, P0, mu0, coast: str = "mix", engine: str = "auto") -> np.ndarray:
    """Combined posterior states (..., T, n) of :func:`imm_run` on scalar position measurements.

    Both engines check and broadcast the parameters as :func:`imm_run` does
    (:func:`tvtrack.filters.imm.imm_inputs`); parameters with batch axes (a grid of settings) run the kernel one
    trial at a time, the numbers of one call per setting.

    Parameters
    ----------
    zs : array_like, shape (..., T)
        Measured position (``H = (1, 0, ..., 0)``), elements; NaN where missing.
    Fs : array_like, shape (r, n, n)
    Qs : array_like, shape (r, n, n) or (..., r, n, n)
    R : float
        Measurement variance, elements².
    transition : array_like, shape (r, r) or (..., r, r)
    x0 : array_like, shape (n,) or (..., n)
    P0 : array_like, shape (n, n) or (..., n, n)
    mu0 : array_like, shape (r,)
    coast : {"mix", "frozen", "mode"}
    engine : {"auto", "jit", "numpy"}
        ``"numpy"``: :func:`imm_run`; ``"jit"``: the compiled kernel; ``"auto"``: the kernel when
        :func:`tvtrack.jit.enabled`.

    Returns
    -------
    ndarray, shape (..., T, n)

    Raises
    ------
    ValueError
        As :func:`imm_run`: shapes that do not fit, ``transition`` or ``mu0`` not probabilities, an unknown ``coast``;
        and ``R`` negative or not finite.
    """
    zs = np.asarray(zs, dtype=float)
    if not 0 <= float(R) < np.inf:  # a negative variance ran on both engines, to different meaningless numbers
        raise ValueError(f"parameter 'R' = {R!r}; a measurement variance must be finite and >= 0 (elements^2)")
    if engine == "auto":
        engine = "jit" if jit.enabled() else "numpy"
    if engine == "numpy":
        H, Rm = np.eye(1, np.shape(Fs)[-1]), np.array([[float(R)]])
        return imm_run(zs[..., None], Fs, Qs, H, Rm, transition, x0, P0, mu0, coast=coast).x
    batch, T = zs.shape[:-1], zs.shape[-1]
    Fs, Qs, M, x0, P0, mu0 = imm_inputs(batch, Fs, Qs, transition, x0, P0, mu0, coast)
    r, n = Fs.shape[:2]
    Qs, M, x0, P0 = (_per_trial(a, c, batch) for a, c in ((Qs, (r, n, n)), (M, (r, r)), (x0, (n,)), (P0, (n, n))))
    zs = np.ascontiguousarray(zs.reshape(-1, T))
    out = np.empty((zs.shape[0], T, n))
    Fs, mu0, R, code, kernel = np.ascontiguousarray(Fs), np.ascontiguousarray(mu0), float(R), COASTS[coast], _kernel()
    if Qs.ndim == 3 and M.ndim == 2 and x0.ndim == 1 and P0.ndim == 2:
        kernel(zs, Fs, Qs, R, M, x0, P0, mu0, code, out)
    else:  # a parameter per trial: the kernel one trial at a time (its trials are independent)
        for b in range(zs.shape[0]):
            Qb, Mb, xb, Pb = (a[b] if a.ndim > k else a for a, k in ((Qs, 3), (M, 2), (x0, 1), (P0, 2)))
            kernel(zs[b : b + 1], Fs, Qb, R, Mb, xb, Pb, mu0, code, out[b : b + 1])
    return out.reshape(batch + (T, n))
