"""Compiled (numba) loops of paper 000's two EKF variants: the straight-line steps of :mod:`.cost`
(:func:`.cost.variant1_step`, :func:`.cost.variant2_step`) written once more as scalar loops over trials and
samples, the same operations in the same order. :func:`.cost.run_steps_variant1` / ``_variant2`` call them when
:func:`tvtrack.jit.enabled`, their NumPy twins (the vectorised steps) otherwise; the tests compare the two.
"""

from __future__ import annotations

import math

import numpy as np

from ...jit import njit

__all__ = ["variant1_loop", "variant2_loop"]


@njit
def variant2_loop(y, x0, d0, tk, f1, f11, q1, c_exp, c_h, a, r0, r1, noise_iterations):  # pragma: no cover - compiled
    """Variant 2 over ``y`` (n, K); ``tk`` (n, K) each trial's timing table ``tau_k - tau_c``. Returns (est, var)."""
    n, big_k = y.shape
    est = np.empty((n, big_k))
    var = np.empty((n, big_k))
    for i in range(n):
        x = x0[i]
        d = d0
        est[i, 0] = x
        var[i, 0] = d
        for k in range(1, big_k):
            xp = f1 * x
            p = f11 * d + q1
            u = tk[i, k] - xp
            s = math.exp(c_exp * (u * u))
            h = a * s
            dh = c_h * (s * u)
            ph = p * dh
            dh_ph = dh * ph
            nu = y[i, k] - h
            r = r0 + r1 * s
            v = dh_ph + r
            x = xp + (ph / v) * nu
            d = p * r / v
            for _ in range(noise_iterations):
                u1 = tk[i, k] - x
                r = r0 + r1 * math.exp(c_exp * (u1 * u1))
                v = dh_ph + r
                x = xp + (ph / v) * nu
                d = p * r / v
            est[i, k] = x
            var[i, k] = d
    return est, var


@njit
def variant1_loop(y, x0, d0, tk, f1, f2, f11, f12, f22, q1, q2, c_exp, c_h1, c_h2, a, sqrt_c, r):  # pragma: no cover
    """Variant 1 over ``y`` (n, K); ``x0`` (n, 2); ``d0`` (d11, d22); ``tk`` (n, K) each trial's timing table.
    Returns (estimate of X1, D11), each (n, K)."""
    n, big_k = y.shape
    est = np.empty((n, big_k))
    var = np.empty((n, big_k))
    for i in range(n):
        x1 = x0[i, 0]
        x2 = x0[i, 1]
        d11 = d0[0]
        d12 = 0.0
        d22 = d0[1]
        est[i, 0] = x1
        var[i, 0] = d11
        for k in range(1, big_k):
            xp1 = f1 * x1
            xp2 = f2 * x2
            p11 = f11 * d11 + q1
            p12 = f12 * d12
            p22 = f22 * d22 + q2
            u = tk[i, k] - xp1
            s = math.exp(c_exp * (u * u))
            root = sqrt_c * math.sqrt(s)
            h = a * s + root * xp2
            h1 = c_h1 * (s * u) + c_h2 * (root * u) * xp2
            h2 = root
            b1 = p11 * h1 + p12 * h2
            b2 = p12 * h1 + p22 * h2
            v = h1 * b1 + h2 * b2 + r
            k1 = b1 / v
            k2 = b2 / v
            nu = y[i, k] - h
            x1 = xp1 + k1 * nu
            x2 = xp2 + k2 * nu
            d11 = p11 - k1 * b1
            d12 = p12 - k1 * b2
            d22 = p22 - k2 * b2
            est[i, k] = x1
            var[i, k] = d11
    return est, var
