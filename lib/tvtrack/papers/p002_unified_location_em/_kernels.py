"""Compiled E-step of the unified location EM (numba), the twin of :func:`em.expectation_step`.

The EM of the study runs tens of thousands of E-steps on small windows (4 x 4 to 9 x 9 pixels, a few
non-zero pixels per frame), where NumPy's per-call overhead, not arithmetic, sets the cost. This kernel
walks the non-zero pixels once per step and evaluates the pixel fractions (U3), local means (U6) and, when
sigma is estimated, ``E[z^2 | pixel]`` directly at each entry's pixel, accumulating the sums of eq. (10)
per trial and object. It is the same arithmetic as the NumPy path (up to the last bits of ``erfc`` against
``scipy.special.ndtr`` and the order of summation); ``tests/papers/test_002_kernels.py`` pins the two
together. Each (trial, frame) tabulates only the pixel range its photons fall in (a pixel's values depend on its
two edges only, so they are the full table's), and the trials that stopped are skipped.

:func:`em_trials` runs the whole EM (plain or SQUAREM, either stopping rule, no prior, fixed weights and widths)
one trial at a time with these steps: the vectorised loop's arithmetic element by element, so its estimates,
step counts and flags bit for bit (``tests/papers/test_002_em_trials.py``), without NumPy's per-pass cost, which
dominated the long tails (coarse pixels, the 5000-step cap).
"""

from __future__ import annotations

import math

import numpy as np

from tvtrack.jit import njit

_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)
_INV_SQRT_2 = 1.0 / math.sqrt(2.0)
_TINY = 1e-300
#: Successive steps whose Aitken gap must be below ``tol_loglik`` before a trial stops (:data:`.em_loop.CALM`).
CALM = 2


@njit
def _axis_table(mu, s, lo, hi, second, f_out, m_out, z_out):  # pragma: no cover - compiled
    """Fractions (U3), local means (U6) and E[z^2 | pixel] of N(mu, s^2) over the pixels lo..hi of one axis, from
    their hi - lo + 2 edges (each edge's tail mass and density evaluated once); the other pixels are not written.
    A pixel's values depend only on its two edges, so they do not depend on the range it is evaluated in."""
    g_prev = 0.0
    p_prev = 0.0
    a = 0.0
    for k in range(lo, hi + 2):
        z = min(max(((k - 0.5) - mu) / s, -37.0), 37.0)
        g = 0.5 * math.erfc(abs(z) * _INV_SQRT_2)  # tail mass beyond the edge: no cancellation
        ph = math.exp(-0.5 * z * z) * _INV_SQRT_2PI
        if k > lo:
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
def _cell_ranges(loc, frame, row, col, n_act, n_t):  # pragma: no cover - compiled
    """The lowest and highest column and row holding an entry, per (trial, frame), shape (4, n_act, n_t) in the order
    (column low, column high, row low, row high); high = -1 where the frame holds no entry."""
    out = np.empty((4, n_act, n_t), dtype=np.int64)
    out[0] = np.iinfo(np.int64).max
    out[1] = -1
    out[2] = np.iinfo(np.int64).max
    out[3] = -1
    for e in range(loc.shape[0]):
        r, f, c, w = loc[e], frame[e], col[e], row[e]
        out[0, r, f] = min(out[0, r, f], c)
        out[1, r, f] = max(out[1, r, f], c)
        out[2, r, f] = min(out[2, r, f], w)
        out[3, r, f] = max(out[3, r, f], w)
    return out


@njit
def _e_step_entries(
    loc, frame, row, col, count, span, live, theta, p, p_noise, sigma, times, rows, cols, second
):  # pragma: no cover
    n_act, q_n = theta.shape[0], theta.shape[1]
    n_t = times.shape[0]
    k_n = 9 if second else 7
    fx = np.empty((n_act, n_t, q_n, cols))
    mx = np.empty((n_act, n_t, q_n, cols))
    sx = np.empty((n_act, n_t, q_n, cols if second else 1))
    fy = np.empty((n_act, n_t, q_n, rows))
    my = np.empty((n_act, n_t, q_n, rows))
    sy = np.empty((n_act, n_t, q_n, rows if second else 1))
    for r in range(n_act):
        if not live[r]:
            continue
        for f in range(n_t):
            if span[1, r, f] < 0:  # no photon in this frame: no pixel of it is read
                continue
            t = times[f]
            for q in range(q_n):
                s = sigma[r, q]
                mu_x = theta[r, q, 0] + theta[r, q, 2] * t
                mu_y = theta[r, q, 1] + theta[r, q, 3] * t
                _axis_table(mu_x, s, span[0, r, f], span[1, r, f], second, fx[r, f, q], mx[r, f, q], sx[r, f, q])
                _axis_table(mu_y, s, span[2, r, f], span[3, r, f], second, fy[r, f, q], my[r, f, q], sy[r, f, q])
    sums = np.zeros((n_act, q_n, k_n))
    loglik = np.zeros(n_act)
    pv = np.empty(q_n)
    area = rows * cols
    for e in range(loc.shape[0]):
        r = loc[e]
        if not live[r]:
            continue
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


def e_step(work, theta, p, p_noise, sigma, times, shape, second: bool, live=None):
    """Compiled :func:`em.expectation_step` (same arguments, same returns: ``sums (n_act, Q, 7 or 9)``, ``loglik``).

    Only the pixels of the range each (trial, frame) holds photons in are tabulated, and with ``live`` ((n_act,)
    bool) only the trials still iterating: the others' sums and log-likelihood are zero (nobody reads them)."""
    rows, cols = shape
    n_act = theta.shape[0]
    if work.kernel_arrays is None:  # the working set's entries, typed once per working set
        loc, frame, row, col = (
            np.ascontiguousarray(x, dtype=np.int64) for x in (work.loc, work.frame, work.row, work.col)
        )
        span = _cell_ranges(loc, frame, row, col, n_act, int(times.shape[0]))
        work.kernel_arrays = (loc, frame, row, col, np.ascontiguousarray(work.count, dtype=np.float64), span)
    live = np.ones(n_act, dtype=np.bool_) if live is None else np.ascontiguousarray(live, dtype=np.bool_)
    return _e_step_entries(
        *work.kernel_arrays,
        live,
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
def _m_step_row(sums, theta, static, new):  # pragma: no cover - compiled
    """The M-step (11) of one trial: ``new`` (Q, 4) from its E-step ``sums`` (Q, 7), ``theta`` (Q, 4) kept for an
    object whose fit is singular; returns whether one was."""
    any_bad = False
    for q in range(theta.shape[0]):
        A, B, C = sums[q, 0], sums[q, 1], sums[q, 2]
        Dx, Dtx, Dy, Dty = sums[q, 3], sums[q, 4], sums[q, 5], sums[q, 6]
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
            any_bad = True
            for k in range(4):
                new[q, k] = theta[q, k]
        else:
            new[q, 0], new[q, 1], new[q, 2], new[q, 3] = v0, v1, v2, v3
    return any_bad


@njit
def _m_step_entries(sums, theta, static):  # pragma: no cover - compiled
    new = np.empty_like(theta)
    any_bad = np.zeros(theta.shape[0], dtype=np.bool_)
    for r in range(theta.shape[0]):
        any_bad[r] = _m_step_row(sums[r], theta[r], static, new[r])
    return new, any_bad


def m_step(sums, theta, static: bool):
    """Compiled :func:`em_steps.maximisation_step` without a prior (same arguments, same returns: ``new theta (N, Q, 4)``,
    ``degenerate (N,)``), the same arithmetic element by element (bit for bit; tests/papers/test_002_kernels.py)."""
    return _m_step_entries(
        np.ascontiguousarray(sums, dtype=np.float64), np.ascontiguousarray(theta, dtype=np.float64), bool(static)
    )


# The whole EM of one trial at a time (:func:`em_trials`): the same steps as :func:`.em_loop.iterate` with the
# compiled E- and M-step, element by element the same arithmetic (the SQUAREM norms summed in NumPy's order,
# :func:`_sum_squares`), so the same estimates, bit for bit, without NumPy's per-call cost on every pass.


@njit
def _trial_e_step(
    e0, e1, frame, row, col, count, span, r, th, pw, p0, sg, times, shape, tables, sums, want_ll=True
):  # pragma: no cover
    """The E-step of trial ``r`` (its entries ``e0:e1``) at ``th`` (Q, 4): ``sums`` (Q, 7) filled as the rows of
    :func:`_e_step_entries`, the log-likelihood returned (0.0 without ``want_ll``: not evaluated)."""
    rows, cols = shape
    fx, mx, fy, my, scratch, pv = tables
    q_n = th.shape[0]
    for f in range(times.shape[0]):
        if span[1, r, f] < 0:
            continue
        t = times[f]
        for q in range(q_n):
            s = sg[q]
            _axis_table(th[q, 0] + th[q, 2] * t, s, span[0, r, f], span[1, r, f], False, fx[f, q], mx[f, q], scratch)
            _axis_table(th[q, 1] + th[q, 3] * t, s, span[2, r, f], span[3, r, f], False, fy[f, q], my[f, q], scratch)
    sums[:] = 0.0
    loglik = 0.0
    area = rows * cols
    for e in range(e0, e1):
        fr = frame[e]
        t = times[fr]
        c_x = col[e]
        c_y = row[e]
        total = 0.0
        for q in range(q_n):
            pv[q] = pw[q] * (fx[fr, q, c_x] * fy[fr, q, c_y])
            total += pv[q]
        v = max(p0 / area + total, _TINY)
        c = count[e]
        if want_ll:
            loglik += c * math.log(v)
        cv = c / v
        for q in range(q_n):
            w = pv[q] * cv
            wt = w * t
            ex = mx[fr, q, c_x]
            ey = my[fr, q, c_y]
            sums[q, 0] += w
            sums[q, 1] += wt
            sums[q, 2] += wt * t
            sums[q, 3] += w * ex
            sums[q, 4] += wt * ex
            sums[q, 5] += w * ey
            sums[q, 6] += wt * ey
    return loglik


@njit
def _sum_squares(x):  # pragma: no cover - compiled
    """``(x**2).sum()`` of a (Q, 4) array in NumPy's order (its pairwise sum: below 8 terms one after the other;
    from 8, eight running sums added in pairs, then the rest), so the same bits as the NumPy path's norms."""
    a = x.ravel()
    n = a.size
    if n < 8:
        res = 0.0
        for i in range(n):
            res += a[i] * a[i]
        return res
    r = np.empty(8)
    for j in range(8):
        r[j] = a[j] * a[j]
    i = 8
    while i < n - (n % 8):
        for j in range(8):
            r[j] += a[i + j] * a[i + j]
        i += 8
    res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]))
    while i < n:
        res += a[i] * a[i]
        i += 1
    return res


@njit
def _nan_max(a, b):  # pragma: no cover - compiled
    """``numpy.maximum`` of two floats (NaN if either is)."""
    if a != a or b != b:
        return math.nan
    return a if a >= b else b


@njit
def _change(a, b, span):  # pragma: no cover - compiled
    """:meth:`.em_loop.EMModel.change` of one trial: the largest position change (px) or velocity change times
    ``span`` between ``a`` and ``b`` (Q, 4)."""
    dp = -math.inf
    dv = -math.inf
    for q in range(a.shape[0]):
        for k in range(4):
            d = abs(a[q, k] - b[q, k])
            if k < 2:
                dp = _nan_max(dp, d)
            else:
                dv = _nan_max(dv, d)
    return _nan_max(dp, span * dv)


@njit
def _copy_rows(dst, src):  # pragma: no cover - compiled
    """``dst[:] = src`` for two (Q, 4) arrays, element by element: the same bits, without the shape check whose
    error message numba would compile (seconds of string code at every first compile)."""
    for q in range(dst.shape[0]):
        for k in range(4):
            dst[q, k] = src[q, k]


@njit
def _squarem(ent, r, th, pw, p0, sg, times, shape, static, span_t, tables, sums, work, new):  # pragma: no cover
    """One SQUAREM cycle of trial ``r`` from ``th`` (:func:`.em_loop.squarem_update`): ``new`` (Q, 4) receives the
    update; returns ``(log-likelihood at th, singular, largest change)``."""
    t1, t2, tx, t3, d1, d2 = work[0], work[1], work[2], work[3], work[4], work[5]
    l0 = _trial_e_step(*ent, r, th, pw, p0, sg, times, shape, tables, sums)
    bad1 = _m_step_row(sums, th, static, t1)
    _trial_e_step(*ent, r, t1, pw, p0, sg, times, shape, tables, sums, False)  # its log-likelihood is not read
    bad2 = _m_step_row(sums, t1, static, t2)
    for q in range(th.shape[0]):
        for k in range(4):
            d1[q, k] = t1[q, k] - th[q, k]
            d2[q, k] = (t2[q, k] - t1[q, k]) - d1[q, k]
    nr = math.sqrt(_sum_squares(d1))
    nv = math.sqrt(_sum_squares(d2))
    alpha = -1.0
    if nv > 0:
        x = -nr / nv
        alpha = x if (x < -1.0 or x != x) else -1.0
    for q in range(th.shape[0]):
        for k in range(4):
            tx[q, k] = (th[q, k] - (2.0 * alpha) * d1[q, k]) + (alpha * alpha) * d2[q, k]
    lx = _trial_e_step(*ent, r, tx, pw, p0, sg, times, shape, tables, sums)
    bad3 = _m_step_row(sums, tx, static, t3)
    if lx >= l0 and math.isfinite(lx) and not bad3:
        _copy_rows(new, t3)
        return l0, bad1 or bad2, _change(t3, tx, span_t)
    _copy_rows(new, t2)
    return l0, bad1 or bad2, _change(t2, t1, span_t)


@njit
def _aitken(ll, prev_ll, prev_rise):  # pragma: no cover - compiled
    """:func:`.em_loop._aitken_gap` of one trial."""
    rise = ll - prev_ll
    if not (math.isfinite(prev_rise) and math.isfinite(rise)):
        return math.inf
    a = rise / prev_rise
    gap = rise * a / (1 - a) if (a >= 0 and a < 1) else math.inf
    return _nan_max(gap, 0.0)


@njit
def _em_trials(ent, theta, pw, p0, sg, times, shape, options, state):  # pragma: no cover - compiled
    """:func:`.em_loop.iterate` one trial at a time (the trials are independent): ``state = (loglik, n_iter,
    converged, degenerate)`` and ``theta`` (N, Q, 4) updated in place, ``loglik`` the log-likelihood at the returned
    estimates (trials degenerate from the start keep theirs); ``options = (static, squarem, tol_px, tol_loglik
    (< 0: none), max_iter, span)``."""
    static, squarem, tol_px, tol_ll, max_iter, span_t = options
    loglik, n_iter, converged, degenerate = state
    starts = ent[0]
    q_n, n_t = theta.shape[1], times.shape[0]
    rows, cols = shape
    tables = (
        np.empty((n_t, q_n, cols)),
        np.empty((n_t, q_n, cols)),
        np.empty((n_t, q_n, rows)),
        np.empty((n_t, q_n, rows)),
        np.empty(1),
        np.empty(q_n),
    )
    sums = np.empty((q_n, 7))
    work = np.empty((6, q_n, 4))
    new = np.empty((q_n, 4))
    th = np.empty((q_n, 4))
    for r in range(theta.shape[0]):
        if degenerate[r]:
            continue
        trial = (starts[r], starts[r + 1]) + ent[1:]
        prev_ll, prev_rise, calm = -math.inf, math.nan, 0
        while True:
            _copy_rows(th, theta[r])
            if squarem:
                ll, bad, delta = _squarem(
                    trial, r, th, pw[r], p0[r], sg[r], times, shape, static, span_t, tables, sums, work, new
                )
                n_iter[r] += 3
            else:  # the step's log-likelihood is read only by the log-likelihood stop (the returned one is below)
                ll = _trial_e_step(*trial, r, th, pw[r], p0[r], sg[r], times, shape, tables, sums, tol_ll >= 0)
                bad = _m_step_row(sums, th, static, new)
                delta = _change(new, th, span_t)
                n_iter[r] += 1
            loglik[r] = ll
            if not bad:
                _copy_rows(theta[r], new)
            if tol_ll < 0:
                conv = delta < tol_px and not bad
            else:
                gap = _aitken(ll, prev_ll, prev_rise)
                prev_rise, prev_ll = ll - prev_ll, ll
                calm = calm + 1 if gap < tol_ll else 0
                conv = calm >= CALM and not bad
            converged[r] = conv
            degenerate[r] = bad
            if conv or bad or n_iter[r] >= max_iter:
                break
        # the log-likelihood at the returned estimates (what :func:`.em._final_loglik` evaluates, the same sums)
        loglik[r] = _trial_e_step(*trial, r, theta[r], pw[r], p0[r], sg[r], times, shape, tables, sums)


def em_trials(entries, times, static: bool, span: float, state, *, accelerate, tol_px, tol_loglik, max_iter) -> bool:
    """Run the EM of :func:`.em_loop.iterate` (no prior, fixed weights and widths, no history) compiled, one trial
    at a time, on ``state`` (an :class:`.em_loop.EMState`, updated in place), followed by :func:`.em._final_loglik`
    (``state.loglik`` the log-likelihood at the returned estimates of every trial not degenerate from the start):
    the same estimates, log-likelihoods, step counts and flags bit for bit. Returns False, doing nothing, where the
    entries are not sorted by trial."""
    trial = np.ascontiguousarray(entries.trial, dtype=np.int64)  # one compiled layout of _cell_ranges, as e_step's
    if trial.size and np.any(np.diff(trial) < 0):
        return False
    n, n_t = entries.n_trials, entries.n_frames
    frame, row, col = (np.ascontiguousarray(x, dtype=np.int64) for x in (entries.frame, entries.row, entries.col))
    ent = (
        np.searchsorted(trial, np.arange(n + 1)).astype(np.int64),
        frame,
        row,
        col,
        np.ascontiguousarray(entries.count, dtype=np.float64),
        _cell_ranges(trial, frame, row, col, n, n_t),
    )
    tol_ll = -1.0 if tol_loglik is None else float(tol_loglik)
    options = (bool(static), accelerate == "squarem", float(tol_px), tol_ll, int(max_iter), float(span))
    flags = (state.loglik, state.n_iter, state.converged, state.degenerate)
    shape = (int(entries.shape[0]), int(entries.shape[1]))
    _em_trials(
        ent,
        state.theta,
        state.pw,
        state.p0,
        state.sigma,
        np.ascontiguousarray(times, dtype=np.float64),
        shape,
        options,
        flags,
    )
    return True
