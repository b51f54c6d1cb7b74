"""The paper's two EKFs for the dissector scan (Martyshevsky 1995, eqs. (6)-(9), (E1)-(E8)).

- variant 1 (:func:`variant1_filter`): state ``[X1, X2]``; the signal noise is modelled by the
  coloured process ``X2`` entering as ``sqrt(c_s S) X2`` (eqs. (6)-(8), (E1)-(E8), corrected (E5), (E6));
- variant 2 (:func:`variant2_filter`): scalar state; the noise intensity of eq. (2) evaluated at
  the estimate (eq. (9)).

The stationary-noise reference is variant 2 with ``P = 0`` on data with ``P = 0``. Both filters model one
sample as the pulse and the noise intensity at one instant (the sample's phase), with noise variance ``N / dt``.
"""

from __future__ import annotations

import numpy as np

from ...filters.ekf import ExtendedKalmanFilter
from .model import G22_MODES, SIGNAL_NOISE_SCALES, DissectorScan, GaussMarkovMessage, check_choice, check_real

__all__ = ["variant1_filter", "variant2_filter", "run_variant1", "run_variant2", "consistency", "g22_variance"]


def g22_variance(mode: str, beta: float, dt: float) -> float:
    """Process-noise variance of ``X2`` per step (eq. (E8) and its alternatives).

    Parameters
    ----------
    mode : str
        One of ``G22_MODES``: ``"paper"`` (eq. (E8) as printed), ``"euler"`` or the stationary sampled white noise.
    beta : float
        The velocity's bandwidth (1/T).
    dt : float
        The step (T).

    Returns
    -------
    float
        The variance added to ``X2`` per step (in ``X2``'s unit squared).
    """
    check_choice("g22", mode, G22_MODES)
    if mode == "paper":
        return 2.0 * beta * dt  # (E8) as printed: unit-variance X2
    if mode == "euler":
        return beta**2 * dt  # Euler of eq. (8): unit-intensity X2
    return (1.0 - (1.0 - beta * dt) ** 2) / dt  # stationary variance 1/dt: sampled white noise


def variant1_filter(
    scan: DissectorScan,
    message: GaussMarkovMessage,
    beta: float = 15.0,
    signal_noise_scale: str = "consistent",
    g22: str = "paper",
    start=0.0,
) -> ExtendedKalmanFilter:
    """Two-state EKF of variant 1 (eqs. (7), (8), (E1)-(E8), corrected (E5), (E6)).

    Parameters
    ----------
    beta : float   ``beta_0`` of the signal-noise process ``X2`` (units of ``1/T``)
    signal_noise_scale : {"consistent", "literal"}
        ``c_s`` in ``sqrt(c_s S) X2``: ``N0 P/(1-P)`` (consistent with eq. (2)) or ``A`` (eq. (6) as printed).
    g22 : {"paper", "euler", "matched"}
        ``G22``: ``2 beta dt`` (printed), ``beta^2 dt`` (Euler of (8)), or ``(1-(1-beta dt)^2)/dt``
        (discrete ``X2`` of stationary variance ``1/dt``).
    start : float or ndarray (n_trials,)
        The sweep's phase at switch-on (T), one per trial of the samples the filter runs on (the tracker knows its
        own sweep).
    """
    check_real("beta", beta, 0.0, 1.0 / scan.dt, low_open=True, high_open=True)
    check_choice("signal_noise_scale", signal_noise_scale, SIGNAL_NOISE_SCALES)
    a, dt = scan.amplitude, scan.dt
    c_s = scan.n0 * scan.signal_noise_ratio if signal_noise_scale == "consistent" else a
    f1, q1 = message.euler(dt)
    F = np.diag([f1, 1.0 - beta * dt])  # (E4)
    Q = np.diag([q1, g22_variance(g22, beta, dt)])  # (E8)
    sqrt_c = np.sqrt(c_s)

    def h(x, k):  # (E3)
        s = scan.shape(x[..., 0], k, start)
        return (a * s + sqrt_c * np.sqrt(s) * x[..., 1])[..., None]

    def jacobian(x, k):
        u = scan.offset(x[..., 0], k, start)
        s = np.exp(-0.5 * (u / scan.pulse_sigma) ** 2)
        root_s = np.sqrt(s)
        d1 = (
            a * s * u / scan.pulse_sigma**2 + sqrt_c * root_s * u / (2.0 * scan.pulse_sigma**2) * x[..., 1]
        )  # d sqrt(c S)/dx without 0/0
        return np.stack([d1, sqrt_c * root_s], axis=-1)[..., None, :]

    R = np.array([[scan.n0 / dt]])  # background only
    return ExtendedKalmanFilter(F, Q, h, jacobian, R)


def variant2_filter(
    scan: DissectorScan,
    message: GaussMarkovMessage,
    assumed_contrast: float | None = None,
    noise_iterations: int = 0,
    start=0.0,
) -> ExtendedKalmanFilter:
    """Scalar EKF of variant 2: noise intensity of eq. (2) at the estimate (eq. (9)).

    Parameters
    ----------
    assumed_contrast : float, optional
        Contrast the filter assumes (default: the scan's); ``0`` gives the stationary-noise filter
        (used as the mismatched baseline on non-stationary data).
    noise_iterations : int
        0: intensity at the predicted estimate; 1: re-evaluated once at the updated estimate.
    start : float or ndarray (n_trials,)
        The sweep's phase at switch-on (T), as for :func:`variant1_filter`.
    """
    p = scan.contrast if assumed_contrast is None else assumed_contrast
    check_real("assumed_contrast", p, 0.0, 1.0, high_open=True)
    a, dt = scan.amplitude, scan.dt
    f1, q1 = message.euler(dt)
    start = np.asarray(start, dtype=float)

    def h(x, k):
        return a * scan.shape(x, k, start[..., None])

    def jacobian(x, k):
        return a * scan.shape_derivative(x, k, start[..., None])[..., None]

    def noise_cov(x, k):  # (eq. 9)
        return scan.sample_variance(x, k, p, start[..., None])[..., None]

    return ExtendedKalmanFilter(np.array([[f1]]), np.array([[q1]]), h, jacobian, noise_cov, noise_iterations)


def run_variant1(filt: ExtendedKalmanFilter, y, d0=(0.2, 1.0), init=None):
    """Run variant 1 on samples ``y`` (n_trials, K); ``init`` (n_trials, 2) are initial estimates
    (default: the process means, zero). Returns (estimate of X1 (n_trials, K), its variance D11 (n_trials, K))."""
    x0 = np.zeros(2) if init is None else init
    out = filt.run(y[..., None], x0, np.diag(d0))
    return out.x[..., 0], out.P[..., 0, 0]


def run_variant2(filt: ExtendedKalmanFilter, y, d0: float = 0.2, init=None):
    """Run variant 2 (or the stationary filter) on ``y`` (n_trials, K); ``init`` (n_trials,) initial
    estimates. Returns (estimate (n_trials, K), its variance (n_trials, K))."""
    x0 = np.zeros(1) if init is None else np.asarray(init)[..., None]
    out = filt.run(y[..., None], x0, np.array([[d0]]))
    return out.x[..., 0], out.P[..., 0, 0]


def consistency(filt: ExtendedKalmanFilter, y, x, d0, window: slice, init=None):
    """Per-run time-averaged NEES and NIS of variant 1 or 2 (the state size of ``filt`` says which) over
    ``window`` of the samples.

    Parameters
    ----------
    filt : ExtendedKalmanFilter
        From :func:`variant1_filter` (2 states) or :func:`variant2_filter` (1 state).
    y, x : ndarray, shape (n_trials, K)
        Samples and the true X1 they were drawn with.
    d0 : float or (float, float)
        Initial variance(s), as for :func:`run_variant2` / :func:`run_variant1`.
    window : slice or bool ndarray, shape (K,)
        Samples averaged (the steady state).
    init : ndarray, optional
        Initial estimates, as for the ``run_variant*`` functions.

    Returns
    -------
    nees, nis : ndarray, shape (n_trials,)
        Mean over the window of (x - X1_hat)^2 / D11 and of nu^2 / S (both 1 in expectation for a
        consistent filter; NEES here is the coordinate's, not the full state's).
    """
    n_states = filt.F.shape[0]
    P0 = np.diag(np.broadcast_to(np.asarray(d0, dtype=float), (n_states,)))
    x0 = np.zeros(n_states) if init is None else np.asarray(init).reshape(len(y), n_states)
    out = filt.run(y[..., None], x0, P0)
    nees = (x - out.x[..., 0]) ** 2 / out.P[..., 0, 0]
    return nees[:, window].mean(axis=1), out.nis[:, window].mean(axis=1)
