"""Compiled E-step of the unified location EM (numba), the twin of :func:`em.expectation_step`.

The EM of the study runs tens of thousands of E-steps on small windows (4 x 4 to 9 x 9 pixels, a few
non-zero pixels per frame), where NumPy's per-call overhead, not arithmetic, sets the cost. This kernel
walks the non-zero pixels once per step and evaluates the pixel fractions (U3), local means (U6) and, when
sigma is estimated, ``E[z^2 | pixel]`` directly at each entry's pixel, accumulating the sums of eq. (10)
per trial and object. It is the same arithmetic as the NumPy path (up to the last bits of ``erfc`` against
``scipy.special.ndtr`` and the order of summation); ``tests/papers/test_002_kernels.py`` pins the two
together.
"""

from __future__ import annotations

import math

import numpy as np

from tvtrack.jit import njit

_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)
_INV_SQRT_2 = 1.0 / math.sqrt(2.0)
_TINY = 1e-300


@njit
def _axis_table(mu, s, n_cells, second, f_out, m_out, z_out):  # pragma: no cover - compiled
    """Fractions (U3), local means (U6) and E[z^2 | pixel] of N(mu, s^2) over the pixels 0..n_cells-1 of one
    axis, from the n_cells + 1 edges (each edge's tail mass and density evaluated once)."""
    g_prev = 0.0
    p_prev = 0.0
    a = 0.0
    for k in range(n_cells + 1):
        z = min(max(((k - 0.5) - mu) / s, -37.0), 37.0)
        g = 0.5 * math.erfc(abs(z) * _INV_SQRT_2)  # tail mass beyond the edge: no cancellation
        ph = math.exp(-0.5 * z * z) * _INV_SQRT_2PI
        if k > 0:
            b, ga, gb, pa, pb = z, g_prev, g, p_prev, ph
            if b <= 0.0:
                f = gb - ga
            elif a >= 0.0:
                f = ga - gb
            else:
                f = 1.0 - ga - gb
            centre = k - 1.0
            ok = f > _TINY
            mean = mu + s * ((pa - pb) / f) if ok else centre
            mean = min(max(mean, centre - 0.5), centre + 0.5)
            f_out[k - 1] = f
            m_out[k - 1] = mean
            if second:
                if ok:
                    ez2 = s * s * (1.0 + (a * pa - b * pb) / f) + 2.0 * mu * (mean - mu) + mu * mu
                else:
                    ez2 = centre * centre + 1.0 / 12.0
                z_out[k - 1] = max(ez2, mean * mean)
        a, g_prev, p_prev = z, g, ph


@njit
def _e_step_entries(
    loc, frame, row, col, count, theta, p, p_noise, sigma, times, rows, cols, second
):  # pragma: no cover
    n_act, q_n = theta.shape[0], theta.shape[1]
    n_t = times.shape[0]
    k_n = 9 if second else 7
    fx = np.empty((n_act, n_t, q_n, cols))
    mx = np.empty((n_act, n_t, q_n, cols))
    sx = np.empty((n_act, n_t, q_n, cols))
    fy = np.empty((n_act, n_t, q_n, rows))
    my = np.empty((n_act, n_t, q_n, rows))
    sy = np.empty((n_act, n_t, q_n, rows))
    for r in range(n_act):
        for f in range(n_t):
            t = times[f]
            for q in range(q_n):
                s = sigma[r, q]
                _axis_table(theta[r, q, 0] + theta[r, q, 2] * t, s, cols, second, fx[r, f, q], mx[r, f, q], sx[r, f, q])
                _axis_table(theta[r, q, 1] + theta[r, q, 3] * t, s, rows, second, fy[r, f, q], my[r, f, q], sy[r, f, q])
    sums = np.zeros((n_act, q_n, k_n))
    loglik = np.zeros(n_act)
    pv = np.empty(q_n)
    area = rows * cols
    for e in range(loc.shape[0]):
        r = loc[e]
        fr = frame[e]
        t = times[fr]
        c_x = col[e]
        c_y = row[e]
        total = 0.0
        for q in range(q_n):
            pv[q] = p[r, q] * (fx[r, fr, q, c_x] * fy[r, fr, q, c_y])
            total += pv[q]
        v = max(p_noise[r] / area + total, _TINY)
        c = count[e]
        loglik[r] += c * math.log(v)
        cv = c / v
        for q in range(q_n):
            w = pv[q] * cv
            wt = w * t
            ex = mx[r, fr, q, c_x]
            ey = my[r, fr, q, c_y]
            out = sums[r, q]
            out[0] += w
            out[1] += wt
            out[2] += wt * t
            out[3] += w * ex
            out[4] += wt * ex
            out[5] += w * ey
            out[6] += wt * ey
            if second:
                out[7] += w * sx[r, fr, q, c_x]
                out[8] += w * sy[r, fr, q, c_y]
    return sums, loglik


def e_step(work, theta, p, p_noise, sigma, times, shape, second: bool):
    """Compiled :func:`em.expectation_step` (same arguments, same returns: ``sums (n_act, Q, 7 or 9)``, ``loglik``)."""
    rows, cols = shape
    if work.kernel_arrays is None:  # the working set's entries, typed once per working set
        work.kernel_arrays = (
            np.ascontiguousarray(work.loc, dtype=np.int64),
            np.ascontiguousarray(work.frame, dtype=np.int64),
            np.ascontiguousarray(work.row, dtype=np.int64),
            np.ascontiguousarray(work.col, dtype=np.int64),
            np.ascontiguousarray(work.count, dtype=np.float64),
        )
    return _e_step_entries(
        *work.kernel_arrays,
        np.ascontiguousarray(theta, dtype=np.float64),
        np.ascontiguousarray(p, dtype=np.float64),
        np.ascontiguousarray(p_noise, dtype=np.float64),
        np.ascontiguousarray(sigma, dtype=np.float64),
        np.ascontiguousarray(times, dtype=np.float64),
        int(rows),
        int(cols),
        bool(second),
    )


@njit
def _m_step_entries(sums, theta, static):  # pragma: no cover - compiled
    n, q_n = theta.shape[0], theta.shape[1]
    new = np.empty_like(theta)
    any_bad = np.zeros(n, dtype=np.bool_)
    for r in range(n):
        for q in range(q_n):
            A, B, C = sums[r, q, 0], sums[r, q, 1], sums[r, q, 2]
            Dx, Dtx, Dy, Dty = sums[r, q, 3], sums[r, q, 4], sums[r, q, 5], sums[r, q, 6]
            if static:
                bad = A <= 1e-12
                As = 1.0 if bad else A
                v0, v1, v2, v3 = Dx / As, Dy / As, 0.0, 0.0
            else:
                det = A * C - B * B
                AC = A * C
                bad = (A <= 1e-12) or (det <= 1e-9 * (AC if AC >= 1e-300 else 1e-300))
                ds = 1.0 if bad else det
                v0 = (C * Dx - B * Dtx) / ds
                v1 = (C * Dy - B * Dty) / ds
                v2 = (A * Dtx - B * Dx) / ds
                v3 = (A * Dty - B * Dy) / ds
            if not (math.isfinite(v0) and math.isfinite(v1) and math.isfinite(v2) and math.isfinite(v3)):
                bad = True
            if bad:
                any_bad[r] = True
                for k in range(4):
                    new[r, q, k] = theta[r, q, k]
            else:
                new[r, q, 0], new[r, q, 1], new[r, q, 2], new[r, q, 3] = v0, v1, v2, v3
    return new, any_bad


def m_step(sums, theta, static: bool):
    """Compiled :func:`em_steps.maximisation_step` without a prior (same arguments, same returns: ``new theta (N, Q, 4)``,
    ``degenerate (N,)``), the same arithmetic element by element (bit for bit; tests/papers/test_002_kernels.py)."""
    return _m_step_entries(
        np.ascontiguousarray(sums, dtype=np.float64), np.ascontiguousarray(theta, dtype=np.float64), bool(static)
    )
