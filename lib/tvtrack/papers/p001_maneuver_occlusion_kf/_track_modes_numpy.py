"""The NumPy engine of :func:`~.track_modes.run_track_modes` (``engine="numpy"``, the fallback without numba): the
mode logic of Fisenko et al. (2008) (eq. 1, eq. 14, E1, with the mode steps and covariance recursion set out
here) batched over trials, one Python loop over the frames of in-place operations on contiguous ``(B,)`` arrays
(:class:`_FrameLoop`). The compiled per-trial kernels of :mod:`._track_modes_kernel` are a second implementation of
the same steps, tested equal to this one (``tests/papers/test_001_track_modes_jit.py``). The covariance correction
is the core's Joseph update (:func:`tvtrack.filters.kalman.joseph_covariance`); the state update stays inline, a
fixed-gain table of eq. 1 with its modes, not a Kalman filter's predict/update."""

from __future__ import annotations

import numpy as np

from ...filters.alphabeta import observation_row
from ...filters.kalman import joseph_covariance
from ...filters.polynomial import polynomial_observation_row, taylor_transition
from ._track_modes_kernel import COAST, TRACK2

__all__ = ["run_numpy"]


def _quadratic_fit(z_window, sigma_eps):
    """LS quadratic through ``window`` samples ending now: state at the newest sample and the
    noise covariance ``sigma^2 (H^T H)^-1``. ``z_window`` (m, w)."""
    w = z_window.shape[-1]
    H = polynomial_observation_row(2, np.arange(w - 1, -1, -1))  # lags back from the newest sample
    pinv = np.linalg.pinv(H)  # (3, w)
    return z_window @ pinv.T, sigma_eps**2 * pinv @ pinv.T


def run_numpy(z, visible, cfg, prep, sigma_eps: float, covariance: bool, batch) -> tuple:
    """:func:`~.track_modes.run_track_modes` with the NumPy frame loop.

    Parameters
    ----------
    z : ndarray, shape (B, T)                 measurements, elements (``B`` the flattened batch ``batch``)
    visible : ndarray of bool, shape (T,) or broadcastable to (..., T)   visibility
    cfg : TrackModeConfig; prep : _Prepared   the configuration and the constants derived from it
    sigma_eps : float                         measurement noise RMS, elements
    covariance : bool                         propagate the noise-driven covariance
    batch : tuple of int                      the batch axes of the outputs

    Returns
    -------
    tuple  the trial-major outputs ``(x, var, gate_var, mode, statistic, threshold, detection_frame, gains)`` that
    ``track_modes._output`` makes a :class:`~.track_modes.TrackModeOutput` of (this module imports nothing of
    :mod:`.track_modes`, which imports it)
    """
    B, T = z.shape
    # time-major, flat batch: every per-frame operation works in place on contiguous (B,) arrays,
    # and every output is written frame by frame into its (T, [3,] B) buffer (no gathers afterwards)
    zt = np.ascontiguousarray(np.moveaxis(z, -1, 0))  # (T, B)
    if visible.ndim == 1:  # one visibility for every trial: (T, 1) broadcasts
        vis = np.ascontiguousarray(np.broadcast_to(visible, (T,))[:, None])
    else:
        vis = np.ascontiguousarray(np.moveaxis(np.broadcast_to(visible, batch + (T,)).reshape(B, T), -1, 0))
    loop = _FrameLoop(zt, vis, cfg, prep, sigma_eps, covariance)
    for t in range(T):
        loop.frame(t)
    return loop.output(batch)


class _FrameLoop:
    """The NumPy engine of :func:`~.track_modes.run_track_modes`: the state of ``B`` trials advanced frame by frame, in place on
    contiguous ``(B,)`` arrays, every output written into its time-major ``(T, [3,] B)`` buffer.

    The per-trial counters start as scalars shared by all trials (lockstep) and become arrays at the first frame
    where trials differ (partial visibility, a detection).

    Parameters
    ----------
    zt : ndarray, shape (T, B)             measurements, elements
    vis : ndarray of bool, shape (T, 1) or (T, B)   visibility
    cfg : TrackModeConfig; prep : _Prepared
    sigma_eps : float                      measurement noise RMS, elements
    covariance : bool                      propagate the noise-driven covariance
    """

    def __init__(self, zt, vis, cfg, prep, sigma_eps: float, covariance: bool):
        T, B = zt.shape
        self.zt, self.vis, self.cfg, self.p = zt, vis, cfg, prep
        self.sigma_eps, self.covariance = sigma_eps, covariance
        self.hidden = ~vis
        self.all_seen, self.none_seen = vis.all(axis=1), ~vis.any(axis=1)
        self.cols = [np.ascontiguousarray(prep.table[:, i]) for i in range(3)]
        self.F, self.h = taylor_transition(2), observation_row(2)
        self.x0, self.x1, self.x2 = np.zeros(B), np.zeros(B), np.zeros(B)
        self.innov, self.tmp = np.empty(B), np.empty(B)
        self.P = np.zeros((B, 3, 3))
        self.k = np.int64(0)  # measurements since the (re)start
        self.row = np.int64(-1)  # gain-table row = in3 kmax + min(k, bound) - 1
        self.cap = np.int64(cfg.k_bound2 - 1)
        self.in3 = np.int64(0)  # 0 = TRACK2, 1 = TRACK3
        self.any3 = False  # some trial is in TRACK3
        self.kalman = np.zeros(B, dtype=bool)  # restart C: Kalman gains until kappa1 reaches the bound
        self.had_gap = False
        self.since_visible = np.int64(0)
        self.detected_at = np.full(B, -1, dtype=np.int64)
        self.detector_on = not prep.forced
        self.sum_old = self.sum_new = None  # running window sums of output velocities
        self.out_x = np.empty((T, 3, B))
        self.out_var = np.full((T, 3, B), np.nan) if covariance else None
        self.out_gate = np.full((T, B), np.nan) if covariance else None
        self.out_K = np.zeros((T, 3, B))  # gains used (0 while lost)
        self.out_mode = np.zeros((T, B), dtype=np.int8)  # COAST unless written
        self.out_S = np.full((T, B), np.nan)  # NaN unless tested
        self.out_c = np.full((T, B), np.nan)

    def frame(self, t: int) -> None:
        """Advance every trial over frame ``t`` and write its outputs."""
        seen = self.vis[t]
        self.count(t, seen)
        K0, K1, K2 = self.cols[0].take(self.row), self.cols[1].take(self.row), self.cols[2].take(self.row)
        if self.covariance:
            K0, K1, K2 = self.propagate_covariance(t, seen, K0, K1, K2)
        if self.all_seen[t]:
            self.out_K[t, 0], self.out_K[t, 1], self.out_K[t, 2] = K0, K1, K2
        elif not self.none_seen[t]:
            for i, Ki in enumerate((K0, K1, K2)):
                np.multiply(Ki, seen, out=self.out_K[t, i])
        self.filter(t, K0, K1, K2)
        alarm = self.detect(t, seen)
        if alarm is not None and alarm.any():
            self.switch(t, alarm)
        self.write(t, seen)

    def count(self, t: int, seen) -> None:
        """The counters after frame ``t``: measurements ``k``, gain row, visible frames since the last loss."""
        if self.all_seen[t]:
            self.k += 1
            if isinstance(self.row, np.ndarray):
                self.row += 1
                np.minimum(self.row, self.cap, out=self.row)
            else:
                self.row = np.minimum(self.row + 1, self.cap)
            if self.had_gap:
                self.since_visible += 1
        elif self.none_seen[t]:
            self.since_visible = self.since_visible * 0
            self.had_gap = True
        else:
            if not self.had_gap:
                self.since_visible = self.k + 0
            self.had_gap = True
            self.k = self.k + seen
            self.row = np.minimum(self.row + seen, self.cap)
            self.since_visible = np.where(seen, self.since_visible + 1, 0)

    def propagate_covariance(self, t: int, seen, K0, K1, K2):
        """Noise-driven covariance (derived here; no process noise): predict, write the gate
        ``[F P F^T]_00 + sigma²``, correct with the gains in force; restart C's Kalman gains replace the table's
        ``K0, K1, K2`` (each (B,) or a scalar) until ``kappa1`` reaches the 3rd-order bound. Returns the gains in
        force."""
        F, h, s2 = self.F, self.h, self.sigma_eps**2
        Pp = F @ self.P @ F.T
        self.out_gate[t] = Pp[:, 0, 0] + s2
        if self.kalman.any():
            Kk = Pp[:, :, 0] / (Pp[:, 0, 0] + s2)[:, None]
            reached = self.kalman & seen & (Kk[:, 0] <= self.p.kappa1_bound3)
            self.kalman = self.kalman & ~reached
            K0, K1, K2 = (np.where(self.kalman, Kk[:, i], Ki) for i, Ki in enumerate((K0, K1, K2)))
        Kc = np.stack(np.broadcast_arrays(K0, K1, K2), axis=-1) * seen[:, None]
        self.P = joseph_covariance(Pp, Kc[:, :, None], h[None, :], s2)
        return K0, K1, K2

    def filter(self, t: int, K0, K1, K2) -> None:
        """(eq. 1) predict and correct with the gains ``K0, K1, K2``; (E1) zero gains while lost (a = 0 in every
        TRACK2 trial); writes the velocity."""
        x0, x1, x2, tmp, innov = self.x0, self.x1, self.x2, self.tmp, self.innov
        x0 += x1
        if self.any3:
            np.multiply(x2, 0.5, out=tmp)
            x0 += tmp
            x1 += x2
        if not self.none_seen[t]:
            np.subtract(self.zt[t], x0, out=innov)
            if not self.all_seen[t]:
                np.copyto(innov, 0.0, where=self.hidden[t])
            np.multiply(K0, innov, out=tmp)
            x0 += tmp
            np.multiply(K1, innov, out=tmp)
            x1 += tmp
            if self.any3:
                np.multiply(K2, innov, out=tmp)
                x2 += tmp
        self.out_x[t, 1] = x1

    def detect(self, t: int, seen):
        """The detector (eq. 14) on the last 2n output velocities, sums kept running; writes the statistic and
        threshold where tested. Returns the alarms ((B,) bool, or a scalar) or None (not tested)."""
        p, n = self.p, self.p.n
        if p.forced:
            return seen & (self.in3 == 0) & (self.k == self.cfg.force_switch_k)
        if not (self.detector_on and t >= 2 * n - 1):
            return None
        out_x, tmp = self.out_x, self.tmp
        if self.sum_old is None:
            self.sum_old = out_x[t - 2 * n + 1 : t - n + 1, 1].sum(axis=0)
            self.sum_new = out_x[t - n + 1 : t + 1, 1].sum(axis=0)
        else:
            mid = out_x[t - n, 1]
            np.subtract(mid, out_x[t - 2 * n, 1], out=tmp)
            self.sum_old += tmp
            np.subtract(self.x1, mid, out=tmp)
            self.sum_new += tmp
        testing = self.k >= p.arm_k
        testing = testing & (self.in3 == 0) if not p.detect3 else testing
        if not self.all_seen[t]:
            testing &= seen
        if self.had_gap:
            testing &= self.since_visible >= p.rearm
        if not testing.any():
            return None
        S = self.sum_old - self.sum_new
        c = p.thr[min(t, p.thr.size - 1)] if p.by_frame else p.thr_by_k.take(self.k)
        if p.detect3 and self.any3:
            c = np.where(self.in3 == 1, p.thr3_by_k.take(self.k), c)
        np.copyto(self.out_S[t], S, where=testing)
        np.copyto(self.out_c[t], c, where=testing)
        return testing & (np.abs(S) > c)

    def switch(self, t: int, alarm) -> None:
        """Switch the alarmed trials to TRACK3 with raised gains (the paper's Fig. 1 text), restart A, B or C
        (:class:`TrackModeConfig`; the restart rule is this project's choice)."""
        cfg, p = self.cfg, self.p
        self.detected_at = np.where(alarm & (self.detected_at < 0), t, self.detected_at)
        x1_before = self.x1
        if cfg.restart == "C":
            self.x2 = np.where(alarm, 0.0, self.x2)
            prior = self.P * np.outer([1, 1, 0], [1, 1, 0])
            prior[:, 2, 2] = cfg.restart_accel_var
            self.P = np.where(alarm[:, None, None], prior, self.P)
            self.kalman = self.kalman | alarm
            self.k = np.where(alarm, 0, self.k)  # measurements since the restart
            self.row = np.where(alarm, p.bound3_row, self.row)
        elif cfg.restart == "A":
            self.x2 = np.where(alarm, 0.0, self.x2)
            if self.covariance:
                self.P = np.where(alarm[:, None, None], self.P * np.outer([1, 1, 0], [1, 1, 0]), self.P)
            self.k = np.where(alarm, cfg.restart_k, self.k)
            self.row = np.where(alarm, p.kmax + min(cfg.restart_k, cfg.k_bound3) - 1, self.row)
        else:
            self.restart_b(t, alarm)
        if self.sum_new is not None:
            self.sum_new = self.sum_new + (self.x1 - x1_before)  # the window holds the restarted velocity (B1)
        self.in3 = np.where(alarm, 1, self.in3)
        self.any3 = True
        self.cap = np.where(alarm, p.kmax + cfg.k_bound3 - 1, self.cap)
        if not p.detect3 and self.in3.all():
            self.detector_on = False
        self.out_x[t, 1] = self.x1  # a restart may have changed the velocity

    def restart_b(self, t: int, alarm) -> None:
        """Restart B: the alarmed trials take the least-squares quadratic through the last ``window``
        measurements (:func:`_quadratic_fit`) and continue the 3rd-order law at ``k = window``."""
        zw = self.zt[max(t - self.p.n + 1, 0) : t + 1].T
        xb, Pb = _quadratic_fit(zw, self.sigma_eps)
        self.x0, self.x1, self.x2 = (np.where(alarm, xb[:, i], v) for i, v in enumerate((self.x0, self.x1, self.x2)))
        if self.covariance:
            self.P = np.where(alarm[:, None, None], Pb, self.P)
        self.k = np.where(alarm, zw.shape[-1], self.k)
        self.row = np.where(alarm, self.p.kmax + min(zw.shape[-1], self.cfg.k_bound3) - 1, self.row)

    def write(self, t: int, seen) -> None:
        """Frame ``t``'s position, acceleration, variances and mode into the outputs."""
        self.out_x[t, 0], self.out_x[t, 2] = self.x0, self.x2
        if self.covariance:
            self.out_var[t] = np.diagonal(self.P, axis1=-2, axis2=-1).T
        if self.all_seen[t]:
            self.out_mode[t] = self.in3 + TRACK2
        elif not self.none_seen[t]:
            self.out_mode[t] = np.where(seen, self.in3 + TRACK2, COAST)

    def output(self, batch) -> tuple:
        """The outputs, as views of the time-major buffers, trial-major (:func:`run_numpy`)."""

        def trial_major(a):
            """(T, [3,] B) -> (B, T[, 3]), a view"""
            return None if a is None else np.moveaxis(a, -1, 0)

        x, var, gate_var, mode, S, c, K = (
            trial_major(a)
            for a in (self.out_x, self.out_var, self.out_gate, self.out_mode, self.out_S, self.out_c, self.out_K)
        )
        T = x.shape[1]
        return x, var, gate_var, mode, S, c, self.detected_at, K.reshape(batch + (T, 3))
