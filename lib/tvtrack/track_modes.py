"""Per-channel track mode logic of Fisenko et al. (2008), batched over trials and channels.

Modes (card §4.4): ``TRACK2`` (alpha-beta, narrow band), ``TRACK3`` (alpha-beta-gamma entered
on a manoeuvre detection with raised gains decaying to a lower bound) and ``COAST`` (object lost:
zero gains, pure prediction (E1)). Every frame::

    visible, TRACK2: k += 1; x = F x + K2(min(k, kb2)) (Z - h F x)   (eq. 1), push v into the
                     detector window; if armed and |S| > c: switch to TRACK3 (restart A or B)
    visible, TRACK3: k += 1; x = F x + K3(min(k, kb3)) (Z - h F x)
    lost:            x = F x                                           (E1), k unchanged

The state is always ``(x, v, a)``; in TRACK2 the acceleration stays 0 (its gain is 0), so
``F`` of order 2 acts as the order-1 ``F``. Alongside the estimate the noise-driven error
covariance (card §4.5 recursion) is propagated per trial, giving the predicted gate at
reappearance. Choices the paper leaves open are fields of :class:`TrackModeConfig`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .detect.maneuver import window_statistic
from .filters.alphabeta import filter_step, gain_schedule, observation_row
from .filters.polynomial import polynomial_observation_row, taylor_transition

__all__ = ["COAST", "TRACK2", "TRACK3", "TrackModeConfig", "TrackModeOutput", "run_track_modes"]

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
        the last entry for larger ``k``), for thresholds computed for the time-varying gains.
    arm_k : int or None
        The detector tests once ``k >= arm_k`` in TRACK2; default ``k_bound2 + 2 window``.
    restart : {"A", "B"}
        On detection: "A" keeps ``x, v``, sets ``a = 0`` and restarts the 3rd-order law at
        ``restart_k``; "B" fits a quadratic to the last ``window`` measurements by least
        squares and continues the law at ``k = window``.
    restart_k : int
        Restart index for option A (>= 1).
    detect_in_track3 : bool
        Keep testing in TRACK3 (a new detection restarts the 3rd-order law again).
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
    arm_k: int | None = None
    restart: str = "A"
    restart_k: int = 3
    detect_in_track3: bool = False
    rearm_after_gap: int | None = None
    force_switch_k: int | None = None

    def __post_init__(self):
        for name in ("k_bound2", "k_bound3", "window", "restart_k"):
            v = getattr(self, name)
            if not (isinstance(v, (int, np.integer)) and v >= 1):
                raise ValueError(f"parameter '{name}' = {v!r}; it must be an integer >= 1")
        if self.k_bound3 < 3:
            raise ValueError(f"parameter 'k_bound3' = {self.k_bound3}; it must be >= 3")
        if self.restart not in ("A", "B"):
            raise ValueError(f"parameter 'restart' = {self.restart!r}; it must be 'A' or 'B'")
        if self.restart == "B" and self.window < 3:
            raise ValueError(f"parameter 'window' = {self.window}; restart 'B' needs >= 3")
        th = np.atleast_1d(np.asarray(self.threshold, dtype=float))
        if th.ndim != 1 or np.any(~(th > 0)):
            raise ValueError("parameter 'threshold' must be a positive number or a 1-D array of them")
        for name in ("arm_k", "rearm_after_gap", "force_switch_k"):
            v = getattr(self, name)
            if v is not None and not (isinstance(v, (int, np.integer)) and v >= 0):
                raise ValueError(f"parameter '{name}' = {v!r}; it must be None or an integer >= 0")


@dataclass(frozen=True)
class TrackModeOutput:
    """Per-frame history; time is the axis after the batch axes.

    Attributes
    ----------
    x : ndarray, shape (..., T, 3)        estimate after each frame (prediction while lost)
    var : ndarray, shape (..., T, 3)      noise-driven error variances of (x, v, a)
    gate_var : ndarray, shape (..., T)    predicted innovation variance ``[F P F^T]_00 + sigma^2``
                                          before each frame's measurement
    gains : ndarray, shape (..., T, 3)    gains used (0 while lost)
    mode : ndarray of int8, shape (..., T)  COAST / TRACK2 / TRACK3
    statistic : ndarray, shape (..., T)   detector statistic S (NaN when not tested)
    threshold : ndarray, shape (..., T)   threshold in force (NaN when not tested)
    detection_frame : ndarray of int, shape (...)  first detection (-1 if none)
    """

    x: np.ndarray
    var: np.ndarray
    gate_var: np.ndarray
    gains: np.ndarray
    mode: np.ndarray
    statistic: np.ndarray
    threshold: np.ndarray
    detection_frame: np.ndarray


def _quadratic_fit(z_window, sigma_eps):
    """LS quadratic through ``window`` samples ending now: state at the newest sample and the
    noise covariance ``sigma^2 (H^T H)^-1``. ``z_window`` (m, w)."""
    w = z_window.shape[-1]
    H = polynomial_observation_row(2, np.arange(w - 1, -1, -1))   # lags back from the newest sample
    pinv = np.linalg.pinv(H)                                        # (3, w)
    return z_window @ pinv.T, sigma_eps**2 * pinv @ pinv.T


def run_track_modes(z, visible, config: TrackModeConfig, sigma_eps: float = 1.0) -> TrackModeOutput:
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

    Returns
    -------
    TrackModeOutput
    """
    z = np.asarray(z, dtype=float)
    T = z.shape[-1]
    batch = z.shape[:-1]
    vis = np.broadcast_to(np.asarray(visible, dtype=bool), z.shape)
    if not sigma_eps > 0:
        raise ValueError(f"parameter 'sigma_eps' = {sigma_eps!r}; it must be > 0")
    cfg = config
    n = cfg.window
    arm_k = cfg.k_bound2 + 2 * n if cfg.arm_k is None else cfg.arm_k
    rearm = 2 * n if cfg.rearm_after_gap is None else cfg.rearm_after_gap
    thr = np.atleast_1d(np.asarray(cfg.threshold, dtype=float))

    K2 = np.zeros((cfg.k_bound2, 3))
    K2[:, :2] = gain_schedule(1, cfg.k_bound2)
    K3 = gain_schedule(2, cfg.k_bound3)
    F = taylor_transition(2)
    h = observation_row(2)

    x = np.zeros(batch + (3,))
    P = np.zeros(batch + (3, 3))
    k = np.zeros(batch, dtype=np.int64)
    mode = np.full(batch, TRACK2, dtype=np.int8)
    since_visible = np.zeros(batch, dtype=np.int64)
    detected_at = np.full(batch, -1, dtype=np.int64)
    vhist = np.full(batch + (T,), np.nan)

    out_x = np.empty(batch + (T, 3))
    out_var = np.empty(batch + (T, 3))
    out_gate = np.empty(batch + (T,))
    out_K = np.empty(batch + (T, 3))
    out_mode = np.empty(batch + (T,), dtype=np.int8)
    out_S = np.full(batch + (T,), np.nan)
    out_c = np.full(batch + (T,), np.nan)

    for t in range(T):
        seen = vis[..., t]
        k = k + seen
        since_visible = np.where(seen, since_visible + 1, 0)
        track3 = mode == TRACK3
        K = np.where(track3[..., None], K3[np.clip(k, 1, cfg.k_bound3) - 1],
                     K2[np.clip(k, 1, cfg.k_bound2) - 1])
        K = np.where(seen[..., None], K, 0.0)
        # noise-driven covariance: predict, then correct with the gains in force (card §4.5)
        Pp = F @ P @ F.T
        out_gate[..., t] = Pp[..., 0, 0] + sigma_eps**2
        IKh = np.eye(3) - K[..., :, None] * h
        P = IKh @ Pp @ np.swapaxes(IKh, -1, -2) + sigma_eps**2 * K[..., :, None] * K[..., None, :]
        P = 0.5 * (P + np.swapaxes(P, -1, -2))
        x, _ = filter_step(x, np.where(seen, z[..., t], np.nan), K, F)  # (eq. 1) / (E1) when lost
        vhist[..., t] = x[..., 1]

        # detector (eq. 14) on the last 2n output velocities
        if t >= 2 * n - 1:
            S = window_statistic(vhist[..., t - 2 * n + 1:t + 1], n)[..., -1]
            c = thr[np.clip(k, 1, thr.size) - 1]
            testing = seen & (k >= arm_k) & (since_visible >= rearm) & (cfg.force_switch_k is None)
            testing &= (mode == TRACK2) | ((mode == TRACK3) & cfg.detect_in_track3)
            out_S[..., t] = np.where(testing, S, np.nan)
            out_c[..., t] = np.where(testing, c, np.nan)
            alarm = testing & (np.abs(S) > c)
        else:
            alarm = np.zeros(batch, dtype=bool)
        if cfg.force_switch_k is not None:
            alarm = seen & (mode == TRACK2) & (k == cfg.force_switch_k)
        detected_at = np.where(alarm & (detected_at < 0), t, detected_at)

        # switch to TRACK3 with raised gains (card §4.4 step 4)
        if np.any(alarm):
            if cfg.restart == "A":
                x = np.where(alarm[..., None], x * np.array([1.0, 1.0, 0.0]), x)
                P = np.where(alarm[..., None, None], P * np.outer([1, 1, 0], [1, 1, 0]), P)
                k = np.where(alarm, cfg.restart_k, k)
            else:
                zw = z[..., max(t - n + 1, 0):t + 1]
                xb, Pb = _quadratic_fit(zw, sigma_eps)
                x = np.where(alarm[..., None], xb, x)
                P = np.where(alarm[..., None, None], Pb, P)
                k = np.where(alarm, zw.shape[-1], k)
            mode = np.where(alarm, TRACK3, mode)

        out_x[..., t, :] = x
        out_var[..., t, :] = np.diagonal(P, axis1=-2, axis2=-1)
        out_K[..., t, :] = K
        out_mode[..., t] = np.where(seen, mode, COAST)
    return TrackModeOutput(out_x, out_var, out_gate, out_K, out_mode, out_S, out_c, detected_at)
