"""Compiled per-trial kernels of the mode logic (:func:`track_modes.run_track_modes`, ``engine="jit"``).

The batched NumPy loop (:mod:`._track_modes_numpy`) spends its time in NumPy's per-call overhead (about 25
in-place operations on ``(B,)`` arrays per frame). These kernels run the same logic one trial at a time over the
frames, as scalar code compiled by numba (no ``fastmath``), the trials spread over the process's threads
(``prange``; the trials share nothing, so the numbers do not depend on the thread count, tested). One thread is
bound by memory bandwidth: each trial-frame writes 43 bytes of outputs, 54 MB for the 001 benchmark's 2000 x 625
(about 9.5 ms on one core of the 2-core machine, 4 ms on two). The thread count is numba's
(``NUMBA_NUM_THREADS``); ``tvtrack reproduce`` and the sweep runner give each notebook kernel ``cores // jobs``.
They are a second implementation of the same equations (Fisenko et al. 2008, eq. 1, eq. 14, E1, with the mode
steps and covariance recursion set out here), tested equal to the NumPy path
(``tests/papers/test_001_track_modes_jit.py``; every test of ``tests/papers/test_001_track_modes.py`` runs with both
engines):

- :func:`kernel_python`: everything, with the noise-driven covariance (gates, variances, restart C's Kalman
  gains); writes the gains per frame;
- :func:`kernel_fast_python`: ``covariance=False`` (restarts A and B), the same steps minus the covariance;
  writes each frame's gain-table row (int16), which :attr:`~.track_modes.TrackModeOutput.gains` expands on access.

The kernels write the Joseph step inline (:func:`_correct_covariance`): numba compiles scalar code per trial and
cannot call the core's batched :func:`tvtrack.filters.kalman.joseph_covariance`, which the NumPy path uses.

Both loop over trials and frames calling the steps of a frame (:func:`_count`, :func:`_predict_covariance`,
:func:`_kalman_gains`, :func:`_correct_covariance`, :func:`_predict_state`, :func:`_correct_state`,
:func:`_detect`, :func:`_restart_state`, :func:`_restart_covariance`), which numba inlines (:func:`_step`).

Numba is optional: without it (or with ``TVTRACK_NO_JIT=1``, or ``engine="numpy"``) ``run_track_modes`` uses the
NumPy path. Each kernel is compiled on its first use in a process (about 2 s for the fast one, 5-6 s for the
general one on the shared 2-core machine), or loaded from :func:`tvtrack.jit.cache_folder` when
``TVTRACK_JIT_CACHE`` is set (the pipeline's runs and the test session set it); :func:`compile_seconds` reports
the first call's time.

The only global (cross-trial) quantity of the NumPy path is ``had_gap``: it turns true at the first frame
where some trial is hidden (``gap_start``), and from then on the per-trial ``since_visible`` counter gates
the detector. The kernel receives ``gap_start`` and reproduces that counter per trial.
"""

from __future__ import annotations

import time

import numpy as np

from tvtrack import jit

__all__ = ["RESTART_CODES", "available", "compile_seconds", "get_kernel", "kernel_fast_python", "kernel_python"]
__all__ += ["use_jit_default", "COAST", "TRACK2", "TRACK3", "record_compile"]

#: Mode codes the kernels write (``in3 + TRACK2`` while seen), :attr:`.track_modes.TrackModeOutput.mode`.
COAST, TRACK2, TRACK3 = 0, 2, 3
#: Restart option -> integer code passed to the kernel.
RESTART_CODES = {"A": 0, "B": 1, "C": 2}

_compiled = {}
_compile_s = {}


def _step(fn):
    """A step of the kernels, written by numba into the kernel that calls it (:func:`tvtrack.jit.njit` with
    ``inline``): the compiled kernel is the code of the statements in place (same numbers, same speed; as calls of
    their own the steps were 1.4-3x slower). Called from Python (the uncompiled kernels) a step runs compiled."""
    return jit.njit(fn, error_model="python", inline=True)


@_step
def _count(seen, t, gap_start, k, row, cap, since):
    """One trial's counters after frame ``t``.

    Parameters
    ----------
    seen : bool        the object is visible at frame ``t``
    t, gap_start : int frame, and the first frame where some trial is hidden (``T`` if none)
    k : int            measurements since the (re)start
    row : int          gain-table row in force (-1 before the first measurement)
    cap : int          the row of the gain bound of the law in force (the row stops there)
    since : int        visible frames since the last loss, counted from ``gap_start`` on (the NumPy path's
                       ``since_visible``, which starts at ``gap_start`` from the count ``k``)

    Returns
    -------
    k, row, since : int
    """
    if t == gap_start:
        since = k
    if seen:
        k += 1
        row = min(row + 1, cap)
    if t >= gap_start:
        since = since + 1 if seen else 0
    return k, row, since


@_step
def _congruence(X, M, work, out):
    """``out = X M X^T`` for 3 x 3 arrays (``work``: ``X M``), summed in index order (the covariance recursions
    derived here)."""
    for i in range(3):
        for j in range(3):
            s = 0.0
            for m in range(3):
                s += X[i, m] * M[m, j]
            work[i, j] = s
    for i in range(3):
        for j in range(3):
            s = 0.0
            for m in range(3):
                s += work[i, m] * X[j, m]
            out[i, j] = s


@_step
def _predict_covariance(F, P, A, Pp):
    """Noise-driven covariance prediction ``Pp = F P F^T`` (derived here; no process noise).

    Parameters
    ----------
    F : ndarray, shape (3, 3)   transition (frame units)
    P : ndarray, shape (3, 3)   error covariance after the last frame, elements² (per frame powers)
    A : ndarray, shape (3, 3)   work space (``F P``)
    Pp : ndarray, shape (3, 3)  output: the predicted covariance
    """
    _congruence(F, P, A, Pp)


@_step
def _kalman_gains(Pp, S_inn, seen, kalman, kappa1_bound3, K0, K1, K2):
    """Restart C's gains: while ``kalman``, the Kalman gains ``K = Pp h^T / S_inn`` of the propagated covariance
    replace the table's ``K0, K1, K2``, until ``kappa1`` falls to the 3rd-order bound's on a visible frame (then
    the table's gains for good).

    Parameters
    ----------
    Pp : ndarray, shape (3, 3)   predicted covariance (:func:`_predict_covariance`)
    S_inn : float                predicted innovation variance ``Pp[0, 0] + sigma²``, elements²
    seen, kalman : bool          visible at this frame; restart C's Kalman gains in force
    kappa1_bound3 : float        ``kappa1`` at the 3rd-order bound
    K0, K1, K2 : float           the table's gains for this frame

    Returns
    -------
    kalman : bool
    K0, K1, K2 : float           the gains in force
    """
    if kalman:
        k0 = Pp[0, 0] / S_inn
        if seen and k0 <= kappa1_bound3:
            kalman = False
        else:
            K0 = k0
            K1 = Pp[1, 0] / S_inn
            K2 = Pp[2, 0] / S_inn
    return kalman, K0, K1, K2


@_step
def _gains_used(seen, K0, K1, K2):
    """The gains applied at a frame: ``K0, K1, K2`` when ``seen``, zero while lost (E1)."""
    c0 = K0 if seen else 0.0
    c1 = K1 if seen else 0.0
    c2 = K2 if seen else 0.0
    return c0, c1, c2


@_step
def _correct_covariance(h, Pp, sigma2, c0, c1, c2, A, IKh, P):
    """Covariance after the correction with the gains used ``c`` (exact for any gains; derived here):
    ``P = (I - c h) Pp (I - c h)^T + sigma² c c^T``, symmetrised.

    Parameters
    ----------
    h : ndarray, shape (3,)      observation row
    Pp : ndarray, shape (3, 3)   predicted covariance
    sigma2 : float               measurement noise variance, elements²
    c0, c1, c2 : float           the gains used (:func:`_gains_used`, zero while lost)
    A, IKh : ndarray, shape (3, 3)  work space
    P : ndarray, shape (3, 3)    output
    """
    for i in range(3):
        ci = c0 if i == 0 else (c1 if i == 1 else c2)
        for j in range(3):
            IKh[i, j] = (1.0 if i == j else 0.0) - ci * h[j]
    _congruence(IKh, Pp, A, P)
    for i in range(3):
        ci = c0 if i == 0 else (c1 if i == 1 else c2)
        for j in range(3):
            cj = c0 if j == 0 else (c1 if j == 1 else c2)
            P[i, j] = P[i, j] + sigma2 * ci * cj
    for i in range(3):
        for j in range(i + 1, 3):
            s = 0.5 * (P[i, j] + P[j, i])
            P[i, j] = s
            P[j, i] = s


@_step
def _predict_state(x0, x1, x2):
    """(eq. 1) prediction ``x <- F x`` of the state (position, elements; velocity, elements/frame; acceleration,
    elements/frame²), ``F`` the order-2 Taylor transition; returns the predicted ``x0, x1, x2``."""
    x0 += x1
    x0 += 0.5 * x2
    x1 += x2
    return x0, x1, x2


@_step
def _correct_state(x0, x1, x2, z, K0, K1, K2):
    """(eq. 1) correction of the predicted state with the measurement ``z`` (elements) and the gains ``K0, K1, K2``;
    returns the corrected ``x0, x1, x2``."""
    innov = z - x0
    x0 += K0 * innov
    x1 += K1 * innov
    x2 += K2 * innov
    return x0, x1, x2


@_step
def _window_sums(out_x, b, t, n, x1, sum_old, sum_new):
    """(eq. 14) the detector's window sums at frame ``t >= 2n - 1``: output velocities (elements/frame) summed over
    the older half-window ``[t - 2n + 1, t - n]`` and the newer ``[t - n + 1, t]``, from scratch at the first frame,
    kept running after it.

    Parameters
    ----------
    out_x : ndarray, shape (B, T, 3)   states written so far (velocities of frames ``<= t``)
    b, t, n : int                      trial, frame, half-window
    x1 : float                         velocity at frame ``t``
    sum_old, sum_new : float           the sums at frame ``t - 1``

    Returns
    -------
    sum_old, sum_new : float
    """
    if t == 2 * n - 1:
        sum_old = 0.0
        for u in range(t - 2 * n + 1, t - n + 1):
            sum_old += out_x[b, u, 1]
        sum_new = 0.0
        for u in range(t - n + 1, t + 1):
            sum_new += out_x[b, u, 1]
    else:
        mid = out_x[b, t - n, 1]
        sum_old += mid - out_x[b, t - 2 * n, 1]
        sum_new += x1 - mid
    return sum_old, sum_new


@_step
def _armed(seen, t, k, in3, since, gap_start, arm_k, rearm, detect3):
    """Whether the detector tests at frame ``t``: visible, ``k >= arm_k``, in TRACK2 unless ``detect3``, and from
    ``gap_start`` on ``rearm`` visible frames after the last loss."""
    return seen and k >= arm_k and (detect3 or in3 == 0) and (t < gap_start or since >= rearm)


@_step
def _threshold(t, k, in3, thr, thr_by_k, thr3_by_k, by_frame, detect3):
    """The threshold ``c`` (elements/frame) in force at frame ``t``: by frame or by the count ``k``, the TRACK3
    array's in TRACK3 with ``detect3``."""
    c = thr[min(t, thr.shape[0] - 1)] if by_frame else thr_by_k[k]
    if detect3 and in3 == 1:
        c = thr3_by_k[k]
    return c


@_step
def _detect(
    out_x, b, t, x1, seen, k, in3, since, sum_old, sum_new, gap_start, n, arm_k, rearm, thr, thr_by_k, thr3_by_k,
    by_frame, forced, force_k, detect3,
):  # fmt: skip
    """The detector at frame ``t`` (eq. 14): ``|S| > c`` with ``S = sum_old - sum_new`` of the last 2n output
    velocities (:func:`_window_sums`), or the forced switch at the TRACK2 count ``force_k``.

    Arguments as in :func:`kernel_python` and :func:`_count`; ``x1`` the velocity at frame ``t``, ``sum_old,
    sum_new`` the window sums at frame ``t - 1``.

    Returns
    -------
    alarm : bool
    S, c : float          statistic and threshold, elements/frame (NaN when not tested)
    sum_old, sum_new : float
    """
    alarm = False
    S = np.nan
    c = np.nan
    if forced:
        alarm = seen and in3 == 0 and k == force_k
    elif t >= 2 * n - 1:
        sum_old, sum_new = _window_sums(out_x, b, t, n, x1, sum_old, sum_new)
        if _armed(seen, t, k, in3, since, gap_start, arm_k, rearm, detect3):
            S = sum_old - sum_new
            c = _threshold(t, k, in3, thr, thr_by_k, thr3_by_k, by_frame, detect3)
            alarm = abs(S) > c
    return alarm, S, c, sum_old, sum_new


@_step
def _least_squares_fit(z, b, t, n, pinv_w):
    """Restart B's state: the least-squares quadratic through the last ``w = min(n, t + 1)`` measurements, at the
    newest one.

    Parameters
    ----------
    z : ndarray, shape (B, T)             measurements, elements
    b, t, n : int                         trial, frame, half-window
    pinv_w : ndarray, shape (n + 1, 3, n) pseudo-inverse for ``w`` samples (entry ``w``)

    Returns
    -------
    w : int
    x0, x1, x2 : float                    position, velocity, acceleration (elements, per frame, per frame²)
    """
    w = min(n, t + 1)
    x0 = 0.0
    x1 = 0.0
    x2 = 0.0
    for u in range(w):
        zu = z[b, t - w + 1 + u]
        x0 += pinv_w[w, 0, u] * zu
        x1 += pinv_w[w, 1, u] * zu
        x2 += pinv_w[w, 2, u] * zu
    return w, x0, x1, x2


@_step
def _restart_state(restart, z, b, t, n, kmax, kb3, restart_k, restart_row, cap3, pinv_w, x0, x1, x2):
    """The state and counters after a switch to TRACK3 (restart rules chosen here): restart A keeps ``x, v``, sets
    ``a = 0`` and continues the 3rd-order law at ``restart_k``; B fits a quadratic (:func:`_least_squares_fit`) and
    continues at ``w``; C keeps ``x, v``, sets ``a = 0`` and starts at the bound's row with ``k = 0``.

    Returns
    -------
    x0, x1, x2 : float
    k, row : int          the count and the gain-table row
    """
    if restart == 2:
        return x0, x1, 0.0, 0, cap3
    if restart == 0:
        return x0, x1, 0.0, restart_k, restart_row
    w, x0, x1, x2 = _least_squares_fit(z, b, t, n, pinv_w)
    return x0, x1, x2, w, kmax + min(w, kb3) - 1


@_step
def _switch(
    restart, z, b, t, n, kmax, kb3, restart_k, restart_row, cap3, pinv_w, x0, x1, x2, forced, sum_new, detected
):
    """The switch to TRACK3 at an alarm at frame ``t`` (the paper's Fig. 1 text), common to both kernels: the restarted
    state, count and gain row (:func:`_restart_state`); the detector's new-window sum takes the restart's velocity
    jump (elements/frame) unless the switch was forced; ``detected`` becomes ``t`` at the first alarm.

    Returns
    -------
    x0, x1, x2, k, row, sum_new, detected
    """
    if detected < 0:
        detected = t
    x1_before = x1
    x0, x1, x2, k, row = _restart_state(
        restart, z, b, t, n, kmax, kb3, restart_k, restart_row, cap3, pinv_w, x0, x1, x2
    )
    if not forced:
        sum_new += x1 - x1_before
    return x0, x1, x2, k, row, sum_new, detected


@_step
def _restart_covariance(restart, P, w, accel_var, Pb_w):
    """The covariance after a switch to TRACK3: restart A zeroes the acceleration's row and column, C also sets
    its variance to ``accel_var`` (elements²/frame⁴), B takes the fit's ``Pb_w[w]`` ((n + 1, 3, 3)); ``P`` (3, 3)
    in place."""
    if restart == 1:
        for i in range(3):
            for j in range(3):
                P[i, j] = Pb_w[w, i, j]
        return
    for i in range(3):
        P[i, 2] = 0.0
        P[2, i] = 0.0
    if restart == 2:
        P[2, 2] = accel_var


def kernel_python(
    z, vis, gap_start, table, kmax, kb2, kb3, kappa1_bound3, F, h, n, arm_k, rearm, thr, thr_by_k, thr3_by_k,
    by_frame, forced, force_k, detect3, restart, restart_k, accel_var, pinv_w, Pb_w, sigma2, covariance, out_x,
    out_var, out_gate, out_K, out_mode, out_S, out_c, det
):  # fmt: skip
    """Per-trial mode logic; writes the outputs in place. Each frame: the counters (:func:`_count`), the covariance
    (:func:`_predict_covariance`, :func:`_kalman_gains`, :func:`_correct_covariance`), the state (eq. 1:
    :func:`_predict_state`, :func:`_correct_state`), the detector (eq. 14: :func:`_detect`) and on an alarm the
    switch to TRACK3 (:func:`_restart_state`, :func:`_restart_covariance`).

    Parameters
    ----------
    z : ndarray, shape (B, T)                 measurements, elements
    vis : ndarray of bool, shape (Bv, T)      visibility, ``Bv`` = 1 (shared) or ``B``
    gap_start : int                           first frame where some trial is hidden (``T`` if none)
    table : ndarray, shape (2 kmax, 3)        gain rows: TRACK2 then TRACK3
    kmax : int                                rows per law in ``table`` (``max(kb2, kb3)``)
    kb2, kb3 : int                            gain bounds of the 2nd- and 3rd-order laws
    kappa1_bound3 : float                     ``kappa1`` at the 3rd-order bound (restart C)
    F : ndarray, shape (3, 3); h : ndarray, shape (3,)   transition and observation row
    n, arm_k, rearm : int                     detector half-window, arming count, re-arming wait
    thr : ndarray, shape (K,)                 threshold array (read by frame when ``by_frame``)
    thr_by_k, thr3_by_k : ndarray             thresholds indexed by the count ``k``
    by_frame, forced, detect3 : bool          options of :class:`~.track_modes.TrackModeConfig`
    force_k : int                             forced switch count (when ``forced``)
    restart : int                             :data:`RESTART_CODES`
    restart_k : int; accel_var : float        restart A index, restart C acceleration variance
    pinv_w : ndarray, shape (n + 1, 3, n)     restart B: least-squares pseudo-inverse for ``w`` samples
    Pb_w : ndarray, shape (n + 1, 3, 3)       restart B: its noise covariance
    sigma2 : float                            measurement noise variance
    covariance : bool                         propagate the covariance (``out_var``, ``out_gate``)
    out_x, out_var, out_K : ndarray, shape (B, T, 3); out_gate, out_S, out_c : ndarray, shape (B, T)
    out_mode : ndarray of int8, shape (B, T); det : ndarray of int64, shape (B,)
        Outputs, every element written (``out_var``, ``out_gate`` only with ``covariance``).
    """
    B, T = z.shape
    last_row = table.shape[0] - 1
    cap2 = kb2 - 1
    cap3 = kmax + kb3 - 1  # also the row of the 3rd-order bound (restart C)
    restart_row = kmax + min(restart_k, kb3) - 1
    v_stride = 0 if vis.shape[0] == 1 else 1
    for b in jit.prange(B):  # trials are independent: numba runs them on the process's threads
        vb = b * v_stride
        P = np.zeros((3, 3))  # each trial's own scratch (shared between threads they would race)
        Pp = np.zeros((3, 3))
        A = np.zeros((3, 3))
        IKh = np.zeros((3, 3))
        x0 = x1 = x2 = 0.0
        k, row, cap, in3, since, detected = 0, -1, cap2, 0, 0, -1
        kalman = False
        sum_old = sum_new = 0.0
        for t in range(T):
            seen = vis[vb, t]
            k, row, since = _count(seen, t, gap_start, k, row, cap, since)
            r = row if row >= 0 else last_row
            K0, K1, K2 = table[r, 0], table[r, 1], table[r, 2]
            if covariance:
                _predict_covariance(F, P, A, Pp)
                S_inn = Pp[0, 0] + sigma2
                out_gate[b, t] = S_inn
                kalman, K0, K1, K2 = _kalman_gains(Pp, S_inn, seen, kalman, kappa1_bound3, K0, K1, K2)
            c0, c1, c2 = _gains_used(seen, K0, K1, K2)
            if covariance:
                _correct_covariance(h, Pp, sigma2, c0, c1, c2, A, IKh, P)
            out_K[b, t, 0] = c0
            out_K[b, t, 1] = c1
            out_K[b, t, 2] = c2
            # (eq. 1) predict and correct; (E1) zero gains while lost
            x0, x1, x2 = _predict_state(x0, x1, x2)
            if seen:
                x0, x1, x2 = _correct_state(x0, x1, x2, z[b, t], K0, K1, K2)
            out_x[b, t, 1] = x1
            alarm, S, c, sum_old, sum_new = _detect(
                out_x, b, t, x1, seen, k, in3, since, sum_old, sum_new, gap_start, n, arm_k, rearm, thr, thr_by_k,
                thr3_by_k, by_frame, forced, force_k, detect3,
            )  # fmt: skip
            out_S[b, t] = S
            out_c[b, t] = c
            if alarm:  # switch to TRACK3 with raised gains (the paper's Fig. 1 text)
                x0, x1, x2, k, row, sum_new, detected = _switch(
                    restart, z, b, t, n, kmax, kb3, restart_k, restart_row, cap3, pinv_w, x0, x1, x2, forced,
                    sum_new, detected,
                )  # fmt: skip
                if restart == 2:
                    kalman = True
                if covariance:
                    _restart_covariance(restart, P, min(n, t + 1), accel_var, Pb_w)
                in3 = 1
                cap = cap3
                out_x[b, t, 1] = x1
            out_x[b, t, 0] = x0
            out_x[b, t, 2] = x2
            if covariance:
                out_var[b, t, 0] = P[0, 0]
                out_var[b, t, 1] = P[1, 1]
                out_var[b, t, 2] = P[2, 2]
            out_mode[b, t] = in3 + 2 if seen else 0
        det[b] = detected


def kernel_fast_python(
    z, vis, gap_start, table, kmax, kb2, kb3, n, arm_k, rearm, thr, thr_by_k, thr3_by_k, by_frame, forced, force_k,
    detect3, restart, restart_k, pinv_w, out_x, out_row, out_mode, out_S, out_c, det
):  # fmt: skip
    """:func:`kernel_python` without the covariance (``covariance=False``, restarts A and B): the same
    steps minus the covariance recursion; the gains are written as the row of ``table`` in force (``out_row``
    (B, T) int16, -1 while lost), expanded on access (:attr:`~.track_modes.TrackModeOutput.gains`). Arguments as in
    :func:`kernel_python`."""
    B, T = z.shape
    cap2 = kb2 - 1
    cap3 = kmax + kb3 - 1
    restart_row = kmax + min(restart_k, kb3) - 1
    v_stride = 0 if vis.shape[0] == 1 else 1
    for b in jit.prange(B):  # trials are independent: numba runs them on the process's threads
        vb = b * v_stride
        x0 = x1 = x2 = 0.0
        k, row, cap, in3, since, detected = 0, -1, cap2, 0, 0, -1
        sum_old = sum_new = 0.0
        for t in range(T):
            seen = vis[vb, t]
            k, row, since = _count(seen, t, gap_start, k, row, cap, since)
            # (eq. 1) predict and correct; (E1) zero gains while lost
            x0, x1, x2 = _predict_state(x0, x1, x2)
            if seen:
                out_row[b, t] = row
                x0, x1, x2 = _correct_state(x0, x1, x2, z[b, t], table[row, 0], table[row, 1], table[row, 2])
            else:
                out_row[b, t] = -1
            out_x[b, t, 1] = x1
            alarm, S, c, sum_old, sum_new = _detect(
                out_x, b, t, x1, seen, k, in3, since, sum_old, sum_new, gap_start, n, arm_k, rearm, thr, thr_by_k,
                thr3_by_k, by_frame, forced, force_k, detect3,
            )  # fmt: skip
            out_S[b, t] = S
            out_c[b, t] = c
            if alarm:  # switch to TRACK3 with raised gains (the paper's Fig. 1 text)
                x0, x1, x2, k, row, sum_new, detected = _switch(
                    restart, z, b, t, n, kmax, kb3, restart_k, restart_row, cap3, pinv_w, x0, x1, x2, forced,
                    sum_new, detected,
                )  # fmt: skip
                in3 = 1
                cap = cap3
                out_x[b, t, 1] = x1
            out_x[b, t, 0] = x0
            out_x[b, t, 2] = x2
            out_mode[b, t] = in3 + 2 if seen else 0
        det[b] = detected


def available() -> bool:
    """True when numba can be imported (:func:`tvtrack.jit.available`)."""
    return jit.available()


def use_jit_default() -> bool:
    """The ``engine="auto"`` choice: the JIT when numba is importable and ``TVTRACK_NO_JIT`` is unset or 0
    (:func:`tvtrack.jit.switched_off`)."""
    return not jit.switched_off() and available()


def get_kernel(covariance: bool = True):
    """The compiled kernel: :func:`kernel_python` (``covariance``) or :func:`kernel_fast_python`, each
    compiled on its first call in this process."""
    name = "general" if covariance else "fast"
    if name not in _compiled:
        _compiled[name] = jit.njit(
            kernel_python if covariance else kernel_fast_python, parallel=True, error_model="python"
        )
    return _compiled[name]


def compile_seconds(covariance: bool = False) -> float | None:
    """Seconds the first (compiling) call of the kernel (see :func:`get_kernel`) took in this process;
    None before it."""
    return _compile_s.get("general" if covariance else "fast")


def record_compile(covariance: bool, t0: float) -> None:
    """Note the first (compiling) call's duration for :func:`compile_seconds`; later calls keep the first.

    Parameters
    ----------
    covariance : bool
        Whether the general (covariance-carrying) kernel was called, else the fast one.
    t0 : float
        ``time.perf_counter()`` at the call's start (s).
    """
    _compile_s.setdefault("general" if covariance else "fast", time.perf_counter() - t0)
