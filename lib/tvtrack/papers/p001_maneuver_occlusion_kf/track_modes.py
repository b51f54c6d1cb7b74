"""Per-channel track mode logic of Fisenko et al. (2008), batched over trials and channels.

Modes (card §4.4): ``TRACK2`` (alpha-beta, narrow band), ``TRACK3`` (alpha-beta-gamma entered
on a manoeuvre detection with raised gains decaying to a lower bound) and ``COAST`` (object lost:
zero gains, pure prediction (E1)). Every frame::

    visible, TRACK2: k += 1; x = F x + K2(min(k, kb2)) (Z - h F x)   (eq. 1), push v into the
                     detector window; if armed and |S| > c: switch to TRACK3 (restart A, B or C)
    visible, TRACK3: k += 1; x = F x + K3(min(k, kb3)) (Z - h F x)
    lost:            x = F x                                           (E1), k unchanged

The state is always ``(x, v, a)``; in TRACK2 the acceleration stays 0 (its gain is 0), so
``F`` of order 2 acts as the order-1 ``F``. Alongside the estimate the noise-driven error
covariance (card §4.5 recursion) is propagated per trial, giving the predicted gate at
reappearance. Choices the paper leaves open are fields of :class:`TrackModeConfig`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ...filters.alphabeta import gain_schedule, observation_row
from ...filters.polynomial import polynomial_observation_row, taylor_transition
from . import _track_modes_kernel as _kernel

__all__ = ["COAST", "TRACK2", "TRACK3", "TrackModeConfig", "TrackModeOutput", "run_track_modes", "manoeuvre_truth"]

#: Mode codes in :attr:`TrackModeOutput.mode`.
COAST, TRACK2, TRACK3 = 0, 2, 3


@dataclass(frozen=True)
class TrackModeConfig:
    """Open choices of the mode logic (defaults = the card's suggestions, §5).

    Attributes
    ----------
    k_bound2, k_bound3 : int
        Gain lower bounds (frame number where the gains freeze) of the 2nd- and 3rd-order laws.
    window : int
        Detector half-window ``n``, frames.
    threshold : float or array_like, shape (K,)
        ``c(alpha)``; an array is indexed by the TRACK2 measurement count ``k`` (entry ``k-1``,
        the last entry for larger ``k``), for thresholds computed for the time-varying gains, or by the
        frame (``threshold_index="frame"``).
    threshold_index : {"count", "frame"}
        How an array ``threshold`` is read: by the TRACK2 count ``k`` (entry ``k-1``), or by the frame ``t``
        (entry ``t``), for thresholds that include a coast (``maneuver_detector.track2_thresholds``).
    arm_k : int or None
        The detector tests once ``k >= arm_k`` in TRACK2; default ``k_bound2 + 2 window``. At least
        ``2 window + 1``: the velocity after the first measurement (``3 Z_1``) carries no velocity information,
        so a window holding it alarms in every run.
    restart : {"A", "B", "C"}
        On detection: "A" keeps ``x, v``, sets ``a = 0`` and restarts the 3rd-order law at
        ``restart_k``; "B" fits a quadratic to the last ``window`` measurements by least
        squares and continues the law at ``k = window``; "C" (covariance-consistent) keeps
        ``x, v`` with their TRACK2 noise covariance, sets ``a = 0`` with variance
        ``restart_accel_var`` (a diffuse prior) and runs the Kalman gains of that covariance
        (no process noise, ``K = P^- h^T / (h P^- h^T + sigma^2)``) until ``kappa1`` falls to the
        3rd-order bound's, then the bound's gains. "C" needs the covariance.
    restart_k : int
        Restart index for option A (>= 1).
    restart_accel_var : float
        Prior variance of the acceleration at restart C, elements²/frame⁴.
    detect_in_track3 : bool
        Keep testing in TRACK3 (a new detection restarts the 3rd-order law again).
    threshold_track3 : float or array_like, shape (K3,), or None
        The threshold for tests in TRACK3, an array indexed by the TRACK3 count. Required with
        ``detect_in_track3`` when ``threshold`` is an array (a TRACK2 array does not apply to the
        3rd-order filter); with a scalar ``threshold`` and None, the scalar applies in TRACK3.
    rearm_after_gap : int or None
        After an occlusion the detector waits this many visible frames before testing again
        (the window must not span predicted velocities); default ``2 window``.
    force_switch_k : int or None
        Switch to TRACK3 at this TRACK2 count regardless of the detector (which is then off):
        makes the filter linear, for the Fig. 4 computations (card §4.5).
    """

    k_bound2: int = 50
    k_bound3: int = 100
    window: int = 25
    threshold: float | np.ndarray = np.inf
    threshold_index: str = "count"
    arm_k: int | None = None
    restart: str = "A"
    restart_k: int = 3
    restart_accel_var: float = 1e4
    detect_in_track3: bool = False
    threshold_track3: float | np.ndarray | None = None
    rearm_after_gap: int | None = None
    force_switch_k: int | None = None

    def __post_init__(self):
        for name in ("k_bound2", "k_bound3", "window", "restart_k"):
            v = getattr(self, name)
            if not (isinstance(v, (int, np.integer)) and v >= 1):
                raise ValueError(f"parameter '{name}' = {v!r}; it must be an integer >= 1")
        if self.k_bound3 < 3:
            raise ValueError(f"parameter 'k_bound3' = {self.k_bound3}; it must be >= 3")
        if self.restart not in ("A", "B", "C"):
            raise ValueError(f"parameter 'restart' = {self.restart!r}; it must be 'A', 'B' or 'C'")
        if not self.restart_accel_var > 0:
            raise ValueError(f"parameter 'restart_accel_var' = {self.restart_accel_var!r}; it must be > 0")
        if self.restart == "B" and self.window < 3:
            raise ValueError(f"parameter 'window' = {self.window}; restart 'B' needs >= 3")
        if self.threshold_index not in ("count", "frame"):
            raise ValueError(f"parameter 'threshold_index' = {self.threshold_index!r}; it must be 'count' or 'frame'")
        if self.arm_k is not None and self.arm_k < 2 * self.window + 1:
            raise ValueError(
                f"parameter 'arm_k' = {self.arm_k}; it must be >= 2 window + 1 = {2 * self.window + 1} "
                f"(a window holding the first measurement's velocity 3 Z_1 alarms in every run)"
            )
        th = np.atleast_1d(np.asarray(self.threshold, dtype=float))
        if th.ndim != 1 or np.any(~(th > 0)):
            raise ValueError("parameter 'threshold' must be a positive number or a 1-D array of them")
        if self.threshold_track3 is not None:
            th3 = np.atleast_1d(np.asarray(self.threshold_track3, dtype=float))
            if th3.ndim != 1 or np.any(~(th3 > 0)):
                raise ValueError("parameter 'threshold_track3' must be None, a positive number or a 1-D array of them")
        elif self.detect_in_track3 and th.size > 1:
            raise ValueError(
                "parameter 'threshold_track3' is required with detect_in_track3 and a threshold array "
                "(the TRACK2 array, indexed by the TRACK2 count, does not apply in TRACK3)"
            )
        for name in ("arm_k", "rearm_after_gap", "force_switch_k"):
            v = getattr(self, name)
            if v is not None and not (isinstance(v, (int, np.integer)) and v >= 0):
                raise ValueError(f"parameter '{name}' = {v!r}; it must be None or an integer >= 0")


@dataclass(frozen=True, eq=False)
class TrackModeOutput:
    """Per-frame history; time is the axis after the batch axes.

    Attributes
    ----------
    x : ndarray, shape (..., T, 3)        estimate after each frame (prediction while lost)
    var : ndarray, shape (..., T, 3)      noise-driven error variances of (x, v, a)
    gate_var : ndarray, shape (..., T)    predicted innovation variance ``[F P F^T]_00 + sigma^2``
                                          before each frame's measurement
    gains : ndarray, shape (..., T, 3)    gains used (0 while lost); a property, expanded on first access
                                          when the run stored the gain-table rows instead (compiled kernel
                                          without covariance)
    mode : ndarray of int8, shape (..., T)  COAST / TRACK2 / TRACK3
    statistic : ndarray, shape (..., T)   detector statistic S (NaN when not tested)
    threshold : ndarray, shape (..., T)   threshold in force (NaN when not tested)
    detection_frame : ndarray of int, shape (...)  first detection (-1 if none)
    """

    x: np.ndarray
    var: np.ndarray
    gate_var: np.ndarray
    mode: np.ndarray
    statistic: np.ndarray
    threshold: np.ndarray
    detection_frame: np.ndarray
    gains_array: np.ndarray | None = field(default=None, repr=False)
    gain_rows: np.ndarray | None = field(default=None, repr=False)  # (..., T) row of gain_table, -1 while lost
    gain_table: np.ndarray | None = field(default=None, repr=False)  # (R, 3)

    @cached_property
    def gains(self) -> np.ndarray:
        """Gains used per frame, shape (..., T, 3) (0 while lost)."""
        if self.gains_array is not None:
            return self.gains_array
        table = np.vstack([self.gain_table, np.zeros((1, 3))])  # row -1 -> zeros
        return table[self.gain_rows]


def _quadratic_fit(z_window, sigma_eps):
    """LS quadratic through ``window`` samples ending now: state at the newest sample and the
    noise covariance ``sigma^2 (H^T H)^-1``. ``z_window`` (m, w)."""
    w = z_window.shape[-1]
    H = polynomial_observation_row(2, np.arange(w - 1, -1, -1))  # lags back from the newest sample
    pinv = np.linalg.pinv(H)  # (3, w)
    return z_window @ pinv.T, sigma_eps**2 * pinv @ pinv.T


def run_track_modes(
    z, visible, config: TrackModeConfig, sigma_eps: float = 1.0, covariance: bool = True, engine: str = "auto"
) -> TrackModeOutput:
    """Run the mode logic on measurements of independent channels.

    Parameters
    ----------
    z : array_like, shape (..., T)
        Measured coordinate per frame, elements (values where ``visible`` is False are ignored).
    visible : array_like of bool, shape (T,) or (..., T)
        False while the object is lost (the measurer reports loss).
    config : TrackModeConfig
    sigma_eps : float
        Measurement noise RMS, elements, for the covariance (and restart B).
    covariance : bool
        Propagate the noise-driven covariance (``var``, ``gate_var``); when False those
        outputs are NaN and the run is faster. Restart "C" needs it.
    engine : {"auto", "jit", "numpy"}
        "numpy": the batched NumPy loop over frames; "jit": the numba-compiled per-trial kernel
        (:mod:`._track_modes_kernel`, the same logic, tested equal); "auto": the kernel when numba is
        importable and the environment variable ``TVTRACK_NO_JIT`` is unset or ``0``, else NumPy.

    Returns
    -------
    TrackModeOutput
    """
    z = np.asarray(z, dtype=float)
    T = z.shape[-1]
    batch = z.shape[:-1]
    if not sigma_eps > 0:
        raise ValueError(f"parameter 'sigma_eps' = {sigma_eps!r}; it must be > 0")
    if engine not in ("auto", "jit", "numpy"):
        raise ValueError(f"parameter 'engine' = {engine!r}; it must be 'auto', 'jit' or 'numpy'")
    if engine == "auto":
        engine = "jit" if _kernel.use_jit_default() else "numpy"
    elif engine == "jit" and not _kernel.available():
        raise ImportError("engine='jit' needs numba, which is not importable; use engine='numpy' or 'auto'")
    cfg = config
    if cfg.restart == "C" and not covariance:
        raise ValueError("parameter 'covariance' = False; restart 'C' needs the covariance (covariance=True)")
    n = cfg.window
    arm_k = cfg.k_bound2 + 2 * n if cfg.arm_k is None else cfg.arm_k
    rearm = 2 * n if cfg.rearm_after_gap is None else cfg.rearm_after_gap
    thr = np.atleast_1d(np.asarray(cfg.threshold, dtype=float))
    thr3 = thr if cfg.threshold_track3 is None else np.atleast_1d(np.asarray(cfg.threshold_track3, dtype=float))
    forced = cfg.force_switch_k is not None
    detect3 = bool(cfg.detect_in_track3)
    by_frame = cfg.threshold_index == "frame"

    # gain table: rows [0, kmax) = TRACK2 (kappa3 = 0), rows [kmax, 2 kmax) = TRACK3;
    # row = in3 * kmax + min(k, bound) - 1
    kmax = max(cfg.k_bound2, cfg.k_bound3)
    table = np.zeros((2 * kmax, 3))
    table[:kmax, :2] = gain_schedule(1, cfg.k_bound2, kmax)
    table[kmax:] = gain_schedule(2, cfg.k_bound3, kmax)
    cols = [np.ascontiguousarray(table[:, i]) for i in range(3)]
    bound3_row = kmax + cfg.k_bound3 - 1
    kappa1_bound3 = table[bound3_row, 0]
    F = taylor_transition(2)
    h = observation_row(2)
    # thresholds indexed directly by the count k (entry k-1 of the array, its last entry beyond it)
    counts = np.maximum(np.arange(T + max(cfg.restart_k, n) + 1), 1) - 1
    thr_by_k = thr[np.minimum(counts, thr.size - 1)]
    thr3_by_k = thr3[np.minimum(counts, thr3.size - 1)]

    B = int(np.prod(batch, dtype=np.int64))
    visible = np.asarray(visible, dtype=bool)
    if engine == "jit":
        vis_bt = (
            np.broadcast_to(visible, (T,)).reshape(1, T)
            if visible.ndim == 1
            else np.broadcast_to(visible, z.shape).reshape(B, T)
        )
        return _run_jit(
            z.reshape(B, T), vis_bt, table, thr, thr_by_k, thr3_by_k, cfg, arm_k, rearm, sigma_eps, covariance, batch
        )

    # time-major, flat batch: every per-frame operation works in place on contiguous (B,) arrays,
    # and every output is written frame by frame into its (T, [3,] B) buffer (no gathers afterwards)
    zt = np.ascontiguousarray(np.moveaxis(z.reshape(B, T), -1, 0))  # (T, B)
    if visible.ndim == 1:  # one visibility for every trial: (T, 1) broadcasts
        vis = np.ascontiguousarray(np.broadcast_to(visible, (T,))[:, None])
    else:
        vis = np.ascontiguousarray(np.moveaxis(np.broadcast_to(visible, z.shape).reshape(B, T), -1, 0))
    hidden = ~vis
    all_seen, none_seen = vis.all(axis=1), ~vis.any(axis=1)

    x0, x1, x2 = np.zeros(B), np.zeros(B), np.zeros(B)
    innov, tmp = np.empty(B), np.empty(B)
    P = np.zeros((B, 3, 3))
    # per-trial counters start as scalars shared by all trials (lockstep) and become arrays
    # at the first frame where trials differ (partial visibility, a detection)
    k = np.int64(0)  # measurements since the (re)start
    row = np.int64(-1)  # gain-table row = in3 kmax + min(k, bound) - 1
    cap = np.int64(cfg.k_bound2 - 1)
    in3 = np.int64(0)  # 0 = TRACK2, 1 = TRACK3
    any3 = False  # some trial is in TRACK3
    kalman = np.zeros(B, dtype=bool)  # restart C: Kalman gains until kappa1 reaches the bound
    had_gap = False
    since_visible = np.int64(0)
    detected_at = np.full(B, -1, dtype=np.int64)
    detector_on = not forced
    sum_old = sum_new = None  # running window sums of output velocities

    out_x = np.empty((T, 3, B))
    out_var = np.full((T, 3, B), np.nan) if covariance else None
    out_gate = np.full((T, B), np.nan) if covariance else None
    out_K = np.zeros((T, 3, B))  # gains used (0 while lost)
    out_mode = np.zeros((T, B), dtype=np.int8)  # COAST unless written
    out_S = np.full((T, B), np.nan)  # NaN unless tested
    out_c = np.full((T, B), np.nan)

    for t in range(T):
        seen = vis[t]
        if all_seen[t]:
            k += 1
            if isinstance(row, np.ndarray):
                row += 1
                np.minimum(row, cap, out=row)
            else:
                row = np.minimum(row + 1, cap)
            if had_gap:
                since_visible += 1
        elif none_seen[t]:
            since_visible = since_visible * 0
            had_gap = True
        else:
            if not had_gap:
                since_visible = k + 0
            had_gap = True
            k = k + seen
            row = np.minimum(row + seen, cap)
            since_visible = np.where(seen, since_visible + 1, 0)
        K0, K1, K2 = cols[0].take(row), cols[1].take(row), cols[2].take(row)
        if covariance:
            # noise-driven covariance: predict, then correct with the gains in force (card §4.5)
            Pp = F @ P @ F.T
            out_gate[t] = Pp[:, 0, 0] + sigma_eps**2
            if kalman.any():
                # restart C: Kalman gains of the propagated covariance, until kappa1 reaches the bound
                Kk = Pp[:, :, 0] / (Pp[:, 0, 0] + sigma_eps**2)[:, None]
                reached = kalman & seen & (Kk[:, 0] <= kappa1_bound3)
                kalman = kalman & ~reached
                K0, K1, K2 = (np.where(kalman, Kk[:, i], Ki) for i, Ki in enumerate((K0, K1, K2)))
            Kc = np.stack(np.broadcast_arrays(K0, K1, K2), axis=-1) * seen[:, None]
            IKh = np.eye(3) - Kc[:, :, None] * h
            P = IKh @ Pp @ np.swapaxes(IKh, -1, -2) + sigma_eps**2 * Kc[:, :, None] * Kc[:, None, :]
            P = 0.5 * (P + np.swapaxes(P, -1, -2))
        if all_seen[t]:
            out_K[t, 0], out_K[t, 1], out_K[t, 2] = K0, K1, K2
        elif not none_seen[t]:
            for i, Ki in enumerate((K0, K1, K2)):
                np.multiply(Ki, seen, out=out_K[t, i])
        # (eq. 1) predict and correct; (E1) zero gains while lost (a = 0 in every TRACK2 trial)
        x0 += x1
        if any3:
            np.multiply(x2, 0.5, out=tmp)
            x0 += tmp
            x1 += x2
        if not none_seen[t]:
            np.subtract(zt[t], x0, out=innov)
            if not all_seen[t]:
                np.copyto(innov, 0.0, where=hidden[t])
            np.multiply(K0, innov, out=tmp)
            x0 += tmp
            np.multiply(K1, innov, out=tmp)
            x1 += tmp
            if any3:
                np.multiply(K2, innov, out=tmp)
                x2 += tmp
        out_x[t, 1] = x1

        # detector (eq. 14) on the last 2n output velocities, sums kept running
        alarm = None
        if forced:
            alarm = seen & (in3 == 0) & (k == cfg.force_switch_k)
        elif detector_on and t >= 2 * n - 1:
            if sum_old is None:
                sum_old = out_x[t - 2 * n + 1 : t - n + 1, 1].sum(axis=0)
                sum_new = out_x[t - n + 1 : t + 1, 1].sum(axis=0)
            else:
                mid = out_x[t - n, 1]
                np.subtract(mid, out_x[t - 2 * n, 1], out=tmp)
                sum_old += tmp
                np.subtract(x1, mid, out=tmp)
                sum_new += tmp
            testing = k >= arm_k
            testing = testing & (in3 == 0) if not detect3 else testing
            if not all_seen[t]:
                testing &= seen
            if had_gap:
                testing &= since_visible >= rearm
            if testing.any():
                S = sum_old - sum_new
                c = thr[min(t, thr.size - 1)] if by_frame else thr_by_k.take(k)
                if detect3 and any3:
                    c = np.where(in3 == 1, thr3_by_k.take(k), c)
                np.copyto(out_S[t], S, where=testing)
                np.copyto(out_c[t], c, where=testing)
                alarm = testing & (np.abs(S) > c)
        # switch to TRACK3 with raised gains (card §4.4 step 4)
        if alarm is not None and alarm.any():
            detected_at = np.where(alarm & (detected_at < 0), t, detected_at)
            x1_before = x1
            if cfg.restart == "C":
                x2 = np.where(alarm, 0.0, x2)
                prior = P * np.outer([1, 1, 0], [1, 1, 0])
                prior[:, 2, 2] = cfg.restart_accel_var
                P = np.where(alarm[:, None, None], prior, P)
                kalman = kalman | alarm
                k = np.where(alarm, 0, k)  # measurements since the restart
                row = np.where(alarm, bound3_row, row)
            elif cfg.restart == "A":
                x2 = np.where(alarm, 0.0, x2)
                if covariance:
                    P = np.where(alarm[:, None, None], P * np.outer([1, 1, 0], [1, 1, 0]), P)
                k = np.where(alarm, cfg.restart_k, k)
                row = np.where(alarm, kmax + min(cfg.restart_k, cfg.k_bound3) - 1, row)
            else:
                zw = zt[max(t - n + 1, 0) : t + 1].T
                xb, Pb = _quadratic_fit(zw, sigma_eps)
                x0, x1, x2 = (np.where(alarm, xb[:, i], v) for i, v in enumerate((x0, x1, x2)))
                if covariance:
                    P = np.where(alarm[:, None, None], Pb, P)
                k = np.where(alarm, zw.shape[-1], k)
                row = np.where(alarm, kmax + min(zw.shape[-1], cfg.k_bound3) - 1, row)
            if sum_new is not None:
                sum_new = sum_new + (x1 - x1_before)  # the window holds the restarted velocity (B1)
            in3 = np.where(alarm, 1, in3)
            any3 = True
            cap = np.where(alarm, kmax + cfg.k_bound3 - 1, cap)
            if not detect3 and in3.all():
                detector_on = False
            out_x[t, 1] = x1  # a restart may have changed the velocity

        out_x[t, 0], out_x[t, 2] = x0, x2
        if covariance:
            out_var[t] = np.diagonal(P, axis1=-2, axis2=-1).T
        if all_seen[t]:
            out_mode[t] = in3 + TRACK2
        elif not none_seen[t]:
            out_mode[t] = np.where(seen, in3 + TRACK2, COAST)

    def back(a, extra=()):
        """(T, [3,] B) -> (..., T[, 3]), a view"""
        return np.moveaxis(a, -1, 0).reshape(batch + (T,) + extra)

    if covariance:
        out_var, out_gate = back(out_var, (3,)), back(out_gate)
    else:  # NaN, without allocating (read-only views)
        out_var = np.broadcast_to(np.nan, batch + (T, 3))
        out_gate = np.broadcast_to(np.nan, batch + (T,))
    return TrackModeOutput(
        x=back(out_x, (3,)),
        var=out_var,
        gate_var=out_gate,
        mode=back(out_mode),
        statistic=back(out_S),
        threshold=back(out_c),
        detection_frame=detected_at.reshape(batch),
        gains_array=back(out_K, (3,)),
    )


def _run_jit(zt, vis, table, thr, thr_by_k, thr3_by_k, cfg, arm_k, rearm, sigma_eps, covariance, batch):
    """``run_track_modes`` with the compiled per-trial kernel; arguments as prepared there, ``zt`` (B, T)
    and ``vis`` (1 or B, T) trial-major."""
    B, T = zt.shape
    z = np.ascontiguousarray(zt, dtype=float)
    if not z.flags.writeable:  # one compiled signature: writeable C arrays
        z = z.copy()
    vis = np.array(vis, dtype=bool, order="C")
    not_all = np.flatnonzero(~vis.all(axis=0))
    gap_start = int(not_all[0]) if not_all.size else T
    n = cfg.window
    kmax = max(cfg.k_bound2, cfg.k_bound3)
    if cfg.restart == "B":  # least-squares fits for every window length w <= n (w < n only before frame n)
        pinv_w, Pb_w = np.zeros((n + 1, 3, n)), np.zeros((n + 1, 3, 3))
        for w in range(1, n + 1):
            H = polynomial_observation_row(2, np.arange(w - 1, -1, -1))
            pinv = np.linalg.pinv(H)
            pinv_w[w, :, :w], Pb_w[w] = pinv, sigma_eps**2 * pinv @ pinv.T
    else:
        pinv_w, Pb_w = np.zeros((1, 3, 1)), np.zeros((1, 3, 3))
    # every element is written by the kernel (NaN where not tested, zero gains while lost)
    out_x, out_mode = np.empty((B, T, 3)), np.empty((B, T), dtype=np.int8)
    out_S, out_c = np.empty((B, T)), np.empty((B, T))
    det = np.empty(B, dtype=np.int64)
    thr_args = (n, int(arm_k), int(rearm), thr, thr_by_k, thr3_by_k, cfg.threshold_index == "frame")
    forced_args = (cfg.force_switch_k is not None, -1 if cfg.force_switch_k is None else int(cfg.force_switch_k))
    restart_args = (bool(cfg.detect_in_track3), _kernel.RESTART_CODES[cfg.restart], int(cfg.restart_k))
    t0 = time.perf_counter()
    if covariance:
        out_K, out_var, out_gate = np.empty((B, T, 3)), np.empty((B, T, 3)), np.empty((B, T))
        _kernel.get_kernel(True)(
            z,
            vis,
            gap_start,
            table,
            kmax,
            cfg.k_bound2,
            cfg.k_bound3,
            float(table[kmax + cfg.k_bound3 - 1, 0]),
            np.ascontiguousarray(taylor_transition(2), dtype=float),
            np.ascontiguousarray(observation_row(2), dtype=float),
            *thr_args,
            *forced_args,
            *restart_args,
            float(cfg.restart_accel_var),
            pinv_w,
            Pb_w,
            float(sigma_eps**2),
            True,
            out_x,
            out_var,
            out_gate,
            out_K,
            out_mode,
            out_S,
            out_c,
            det,
        )
        gain_kw = {"gains_array": out_K.reshape(batch + (T, 3))}
    else:
        out_row = np.empty((B, T), dtype=np.int16 if table.shape[0] < 2**15 else np.int32)
        _kernel.get_kernel(False)(
            z, vis, gap_start, table, kmax, cfg.k_bound2, cfg.k_bound3, *thr_args, *forced_args, *restart_args,
            pinv_w, out_x, out_row, out_mode, out_S, out_c, det,
        )  # fmt: skip
        gain_kw = {"gain_rows": out_row.reshape(batch + (T,)), "gain_table": table}
    _kernel._record_compile(covariance, t0)

    def back(a, extra=()):
        """(B, T[, 3]) -> (..., T[, 3])"""
        return a.reshape(batch + (T,) + extra)

    if covariance:
        out_var, out_gate = back(out_var, (3,)), back(out_gate)
    else:
        out_var = np.broadcast_to(np.nan, batch + (T, 3))
        out_gate = np.broadcast_to(np.nan, batch + (T,))
    return TrackModeOutput(
        x=back(out_x, (3,)),
        var=out_var,
        gate_var=out_gate,
        mode=back(out_mode),
        statistic=back(out_S),
        threshold=back(out_c),
        detection_frame=det.reshape(batch),
        **gain_kw,
    )


def manoeuvre_truth(v0: float, accel: float, onset_frame: int, n_frames: int) -> np.ndarray:
    """True ``(x, v, a)`` per frame: uniform motion from ``x = 0``, constant acceleration from the onset.

    Parameters
    ----------
    v0 : float
        Initial velocity, elements/frame.
    accel : float
        Acceleration from ``onset_frame`` on, elements/frame².
    onset_frame, n_frames : int

    Returns
    -------
    ndarray, shape (n_frames, 3)
        Position (elements), velocity (elements/frame), acceleration (elements/frame²).
    """
    if n_frames < 1:
        raise ValueError(f"parameter 'n_frames' = {n_frames}; it must be >= 1")
    f = np.arange(n_frames)
    d = np.clip(f - onset_frame, 0, None)
    a = np.where(f >= onset_frame, accel, 0.0)
    return np.stack([v0 * f + 0.5 * accel * d**2, v0 + accel * d, a], axis=-1)
