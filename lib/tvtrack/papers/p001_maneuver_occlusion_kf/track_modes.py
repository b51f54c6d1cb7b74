"""Per-channel track mode logic of Fisenko et al. (2008), batched over trials and channels.

Modes (names given here to the scheme of the paper's Fig. 1): ``TRACK2`` (alpha-beta, narrow band), ``TRACK3``
(alpha-beta-gamma entered on a manoeuvre detection with raised gains decaying to a lower bound) and ``COAST``
(object lost: zero gains, pure prediction (E1)). Every frame::

    visible, TRACK2: k += 1; x = F x + K2(min(k, kb2)) (Z - h F x)   (eq. 1), push v into the
                     detector window; if armed and |S| > c: switch to TRACK3 (restart A, B or C)
    visible, TRACK3: k += 1; x = F x + K3(min(k, kb3)) (Z - h F x)
    lost:            x = F x                                           (E1), k unchanged

The state is always ``(x, v, a)``; in TRACK2 the acceleration stays 0 (its gain is 0), so
``F`` of order 2 acts as the order-1 ``F``. Alongside the estimate the noise-driven error
covariance (the recursion derived here) is propagated per trial, giving the predicted gate at
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

#: Mode codes in :attr:`TrackModeOutput.mode` (defined with the kernels that write them).
COAST, TRACK2, TRACK3 = _kernel.COAST, _kernel.TRACK2, _kernel.TRACK3


@dataclass(frozen=True)
class TrackModeConfig:
    """Open choices of the mode logic (defaults = this project's choices).

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
        makes the filter linear, for this project's Fig. 4 computations.
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


@dataclass(frozen=True, eq=False)
class _Prepared:
    """The constants of a run, derived from its :class:`TrackModeConfig` (both engines).

    Attributes
    ----------
    n, arm_k, rearm : int            detector half-window, arming count and re-arming wait, frames
    thr : ndarray, shape (K,)        threshold ``c(alpha)``, elements/frame
    thr_by_k, thr3_by_k : ndarray, shape (T + max(restart_k, n) + 1,)
                                     TRACK2 and TRACK3 thresholds indexed directly by the count ``k``
    forced, detect3, by_frame : bool forced switch, tests in TRACK3, threshold read by frame
    table : ndarray, shape (2 kmax, 3)   gain rows: ``[0, kmax)`` TRACK2 (kappa3 = 0), ``[kmax, 2 kmax)`` TRACK3;
                                     row = in3 kmax + min(k, bound) - 1
    kmax : int                       rows per law, ``max(k_bound2, k_bound3)``
    bound3_row : int; kappa1_bound3 : float   the 3rd-order bound's row and its ``kappa1`` (restart C)
    """

    n: int
    arm_k: int
    rearm: int
    thr: np.ndarray
    thr_by_k: np.ndarray
    thr3_by_k: np.ndarray
    forced: bool
    detect3: bool
    by_frame: bool
    table: np.ndarray
    kmax: int
    bound3_row: int
    kappa1_bound3: float


def _resolve_engine(engine: str, sigma_eps: float, cfg: TrackModeConfig, covariance: bool) -> str:
    """Check the arguments of :func:`run_track_modes` that the config does not; the engine to run ("jit" or
    "numpy")."""
    if not 0 < sigma_eps < np.inf:
        raise ValueError(f"parameter 'sigma_eps' = {sigma_eps!r}; it must be finite and > 0")
    if engine not in ("auto", "jit", "numpy"):
        raise ValueError(f"parameter 'engine' = {engine!r}; it must be 'auto', 'jit' or 'numpy'")
    if engine == "auto":
        engine = "jit" if _kernel.use_jit_default() else "numpy"
    elif engine == "jit" and not _kernel.available():
        raise ImportError("engine='jit' needs numba, which is not importable; use engine='numpy' or 'auto'")
    if cfg.restart == "C" and not covariance:
        raise ValueError("parameter 'covariance' = False; restart 'C' needs the covariance (covariance=True)")
    return engine


def _prepare(cfg: TrackModeConfig, T: int) -> _Prepared:
    """The run's constants (:class:`_Prepared`) for ``T`` frames: detector settings, the gain table of the two
    laws (:func:`~tvtrack.filters.alphabeta.gain_schedule`) and the thresholds by count."""
    n = cfg.window
    thr = np.atleast_1d(np.asarray(cfg.threshold, dtype=float))
    thr3 = thr if cfg.threshold_track3 is None else np.atleast_1d(np.asarray(cfg.threshold_track3, dtype=float))
    kmax = max(cfg.k_bound2, cfg.k_bound3)
    table = np.zeros((2 * kmax, 3))
    table[:kmax, :2] = gain_schedule(1, cfg.k_bound2, kmax)
    table[kmax:] = gain_schedule(2, cfg.k_bound3, kmax)
    bound3_row = kmax + cfg.k_bound3 - 1
    # thresholds indexed directly by the count k (entry k-1 of the array, its last entry beyond it)
    counts = np.maximum(np.arange(T + max(cfg.restart_k, n) + 1), 1) - 1
    return _Prepared(
        n=n,
        arm_k=cfg.k_bound2 + 2 * n if cfg.arm_k is None else cfg.arm_k,
        rearm=2 * n if cfg.rearm_after_gap is None else cfg.rearm_after_gap,
        thr=thr,
        thr_by_k=thr[np.minimum(counts, thr.size - 1)],
        thr3_by_k=thr3[np.minimum(counts, thr3.size - 1)],
        forced=cfg.force_switch_k is not None,
        detect3=bool(cfg.detect_in_track3),
        by_frame=cfg.threshold_index == "frame",
        table=table,
        kmax=kmax,
        bound3_row=bound3_row,
        kappa1_bound3=table[bound3_row, 0],
    )


def _output(batch, T, x, var, gate_var, mode, statistic, threshold, detection_frame, **gains) -> TrackModeOutput:
    """:class:`TrackModeOutput` from trial-major views ``(B, T[, 3])`` (``var``, ``gate_var`` None without the
    covariance: NaN, as read-only broadcasts); ``gains`` as in :class:`TrackModeOutput`, already shaped."""

    def back(a, extra=()):
        """(B, T[, 3]) -> (..., T[, 3])"""
        return a.reshape(batch + (T,) + extra)

    if var is not None:
        var, gate_var = back(var, (3,)), back(gate_var)
    else:  # NaN, without allocating (read-only views)
        var = np.broadcast_to(np.nan, batch + (T, 3))
        gate_var = np.broadcast_to(np.nan, batch + (T,))
    return TrackModeOutput(
        x=back(x, (3,)),
        var=var,
        gate_var=gate_var,
        mode=back(mode),
        statistic=back(statistic),
        threshold=back(threshold),
        detection_frame=detection_frame.reshape(batch),
        **gains,
    )


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
        "numpy": the batched NumPy loop over frames (:mod:`._track_modes_numpy`); "jit": the numba-compiled per-trial
        kernel (:mod:`._track_modes_kernel`, the same logic, tested equal); "auto": the kernel when numba is
        importable and the environment variable ``TVTRACK_NO_JIT`` is unset or ``0``, else NumPy.

    Returns
    -------
    TrackModeOutput
    """
    z = np.asarray(z, dtype=float)
    T = z.shape[-1]
    batch = z.shape[:-1]
    engine = _resolve_engine(engine, sigma_eps, config, covariance)
    prep = _prepare(config, T)
    B = int(np.prod(batch, dtype=np.int64))
    visible = np.asarray(visible, dtype=bool)
    if engine == "jit":
        vis_bt = (
            np.broadcast_to(visible, (T,)).reshape(1, T)
            if visible.ndim == 1
            else np.broadcast_to(visible, z.shape).reshape(B, T)
        )
        return _run_jit(z.reshape(B, T), vis_bt, config, prep, sigma_eps, covariance, batch)
    from ._track_modes_numpy import run_numpy

    *views, gains = run_numpy(z.reshape(B, T), visible, config, prep, sigma_eps, covariance, batch)
    return _output(batch, T, *views, gains_array=gains)


def _restart_b_fits(n: int, sigma_eps: float):
    """Restart B's least-squares fits for every window length ``w <= n`` (``w < n`` only before frame ``n``).

    Returns
    -------
    pinv_w : ndarray, shape (n + 1, 3, n)   entry ``w``: the pseudo-inverse for the last ``w`` samples (zero-padded)
    Pb_w : ndarray, shape (n + 1, 3, 3)     entry ``w``: its noise covariance ``sigma² pinv pinv^T``, elements²
    """
    pinv_w, Pb_w = np.zeros((n + 1, 3, n)), np.zeros((n + 1, 3, 3))
    for w in range(1, n + 1):
        H = polynomial_observation_row(2, np.arange(w - 1, -1, -1))
        pinv = np.linalg.pinv(H)
        pinv_w[w, :, :w], Pb_w[w] = pinv, sigma_eps**2 * pinv @ pinv.T
    return pinv_w, Pb_w


def _run_jit(zt, vis, cfg: TrackModeConfig, prep: _Prepared, sigma_eps: float, covariance: bool, batch):
    """``run_track_modes`` with the compiled per-trial kernel: :func:`._track_modes_kernel.kernel_python` with the
    covariance, :func:`._track_modes_kernel.kernel_fast_python` without. ``zt`` (B, T) and ``vis`` (1 or B, T)
    trial-major; the other arguments as prepared there."""
    B, T = zt.shape
    z = np.ascontiguousarray(zt, dtype=float)
    if not z.flags.writeable:  # one compiled signature: writeable C arrays
        z = z.copy()
    vis = np.array(vis, dtype=bool, order="C")
    not_all = np.flatnonzero(~vis.all(axis=0))
    gap_start = int(not_all[0]) if not_all.size else T
    n, kmax = prep.n, prep.kmax
    pinv_w, Pb_w = _restart_b_fits(n, sigma_eps) if cfg.restart == "B" else (np.zeros((1, 3, 1)), np.zeros((1, 3, 3)))
    # every element is written by the kernel (NaN where not tested, zero gains while lost)
    out_x, out_mode = np.empty((B, T, 3)), np.empty((B, T), dtype=np.int8)
    out_S, out_c = np.empty((B, T)), np.empty((B, T))
    det = np.empty(B, dtype=np.int64)
    thr_args = (n, int(prep.arm_k), int(prep.rearm), prep.thr, prep.thr_by_k, prep.thr3_by_k, prep.by_frame)
    forced_args = (prep.forced, -1 if cfg.force_switch_k is None else int(cfg.force_switch_k))
    restart_args = (prep.detect3, _kernel.RESTART_CODES[cfg.restart], int(cfg.restart_k))
    table, kb2, kb3 = prep.table, cfg.k_bound2, cfg.k_bound3
    out_var = out_gate = None
    t0 = time.perf_counter()
    if covariance:
        out_K, out_var, out_gate = np.empty((B, T, 3)), np.empty((B, T, 3)), np.empty((B, T))
        F = np.ascontiguousarray(taylor_transition(2), dtype=float)
        h = np.ascontiguousarray(observation_row(2), dtype=float)
        _kernel.get_kernel(True)(
            z, vis, gap_start, table, kmax, kb2, kb3, float(prep.kappa1_bound3), F, h, *thr_args, *forced_args,
            *restart_args, float(cfg.restart_accel_var), pinv_w, Pb_w, float(sigma_eps**2), True,
            out_x, out_var, out_gate, out_K, out_mode, out_S, out_c, det,
        )  # fmt: skip
        gain_kw = {"gains_array": out_K.reshape(batch + (T, 3))}
    else:
        out_row = np.empty((B, T), dtype=np.int16 if table.shape[0] < 2**15 else np.int32)
        _kernel.get_kernel(False)(
            z, vis, gap_start, table, kmax, kb2, kb3, *thr_args, *forced_args, *restart_args,
            pinv_w, out_x, out_row, out_mode, out_S, out_c, det,
        )  # fmt: skip
        gain_kw = {"gain_rows": out_row.reshape(batch + (T,)), "gain_table": table}
    _kernel.record_compile(covariance, t0)
    return _output(batch, T, out_x, out_var, out_gate, out_mode, out_S, out_c, det, **gain_kw)


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
