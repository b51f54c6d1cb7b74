"""Causal ``m``-step-ahead predictors of a measured coordinate sequence, for comparisons.

Every predictor takes measurements ``z`` of shape ``(..., T)`` (one scalar series per leading
index, e.g. ``(paths, trials, axes, T)``; time step = one frame) and returns ``forecast`` of the
same shape, where ``forecast[..., n]`` is the prediction of ``z[..., n + steps]`` made from
``z[..., :n+1]`` only (NaN while a method has too few samples). :func:`forecast_errors`
aligns forecasts with a reference.

Methods (Kokryatska & Hrynchyshyn 2005 name them as baselines, Sect. "results"):

- :func:`growing_memory_forecast`: the paper's filter (eqs. (2)-(6)), via
  :func:`tvtrack.filters.polynomial.growing_memory_filter`, with the frozen-gain floor;
- :func:`g1_floor_filter`: this project's *variant* floor (only ``g_1`` floored, ``g_2, g_3`` scaled
  by the same factor), which the core filter does not offer;
- :func:`sliding_regression_forecast`: least-squares polynomial of degree ``d`` on the last ``L``
  samples, extrapolated; ``L = d + 1`` is finite-difference (Newton) extrapolation;
- :func:`spline_forecast`: not-a-knot cubic spline (scipy) through the last ``L`` samples;
- :func:`fit_learned_predictor` / :func:`learned_forecast`: an MLP trained by back-propagation
  and an RBF network (Gaussian units at data points via Nystroem, ridge read-out; Orr 1996),
  scikit-learn, on ``L`` lagged increments;
- :func:`kalman_forecast` with :func:`constant_acceleration_model`: a constant-acceleration
  Kalman filter with white-jerk process noise, built on :mod:`tvtrack.filters.kalman`, and
  :func:`fit_constant_acceleration` choosing its noise levels by maximum likelihood;
- :func:`singer_model`: Singer's (1970) exponentially correlated acceleration, a Kalman filter
  whose acceleration forgets on a time constant ``tau`` (a principled floor: the memory is set
  by a model of the motion), with :func:`fit_singer` choosing ``tau``, the acceleration variance
  and the measurement variance by maximum likelihood.

Fitted methods are scored by cross-validation over paths (:func:`path_folds`; the learned networks through
``prediction_study.fit_learned_folds``; :func:`fit_constant_acceleration_folds`,
:func:`constant_acceleration_forecast`, :func:`fit_singer_folds`, :func:`singer_forecast`); :func:`hold_last` fills lost measurements.
:func:`batch_least_squares_states` is the direct eq. (4) the recursion must reproduce.
"""

from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view
from scipy.interpolate import CubicSpline

from ...filters.polynomial import (
    growing_memory_filter,
    growing_memory_gains,
    polynomial_observation_row,
    predict_ahead,
    taylor_transition,
)
from ._checks import check_steps, check_z

__all__ = [
    "forecast_errors",
    "growing_memory_forecast",
    "fading_memory_gains",
    "fading_memory_forecast",
    "g1_floor_gains",
    "g1_floor_filter",
    "g1_floor_forecast",
    "sliding_regression_forecast",
    "spline_forecast",
    "hold_last",
    "batch_least_squares_states",
]


def forecast_errors(forecast, reference, steps: int) -> np.ndarray:
    """Errors ``e[..., n] = forecast[..., n - steps] - reference[..., n]`` (NaN for ``n < steps``).

    Parameters
    ----------
    forecast : ndarray, shape (..., T)
        ``forecast[..., n]`` predicts frame ``n + steps``.
    reference : ndarray, broadcastable to (..., T)
        Measured or true coordinate per frame, px.
    """
    steps = check_steps(steps)
    f = np.asarray(forecast, dtype=float)
    r = np.broadcast_to(np.asarray(reference, dtype=float), f.shape)
    e = np.full(f.shape, np.nan)
    e[..., steps:] = f[..., :-steps] - r[..., steps:]
    return e


def hold_last(z) -> np.ndarray:
    """Replace lost measurements (NaN) by the last valid one along time, as a tracker that keeps
    its gate would; leading NaN take the first valid value (all-NaN series stay NaN).

    Parameters
    ----------
    z : ndarray, shape (..., T)
        Measured coordinate per frame, px; NaN = lost.

    Returns
    -------
    ndarray, shape (..., T)
    """
    z = np.asarray(z, dtype=float)
    ok = np.isfinite(z)
    idx = np.where(ok, np.arange(z.shape[-1]), 0)
    np.maximum.accumulate(idx, axis=-1, out=idx)
    first = np.argmax(ok, axis=-1)[..., None]
    idx = np.where(np.cumsum(ok, axis=-1) == 0, first, idx)
    return np.take_along_axis(z, idx, axis=-1)


def batch_least_squares_states(z, order: int = 2) -> np.ndarray:
    """Eq. (4) solved directly at every sample: the least-squares Taylor state at ``n`` from all
    samples ``0..n`` (``numpy.linalg.lstsq``, rows ``h_j`` for lags ``j = n..0``). O(T^2); the
    reference the recursion (5)-(6) must reproduce.

    Parameters
    ----------
    z : ndarray, shape (T,)
        One series; NaN marks a lost sample, left out of the fit (the others keep their true times).

    Returns
    -------
    ndarray, shape (T, order+1)
        NaN until ``order + 1`` samples are present (fewer samples than unknowns).
    """
    z = np.asarray(z, dtype=float)
    if z.ndim != 1 or np.any(np.isinf(z)):
        raise ValueError(f"parameter 'z' has shape {z.shape}; it must be one series (T,), NaN for lost samples")
    out = np.full(z.shape + (order + 1,), np.nan)
    present = np.isfinite(z)
    for n_ in range(order, z.size):
        keep = present[: n_ + 1]
        if keep.sum() < order + 1:
            continue
        lags = np.arange(n_, -1, -1.0)[keep]
        Hn = np.stack([(-lags) ** p / np.prod(np.arange(1, p + 1)) for p in range(order + 1)], axis=1)
        out[n_] = np.linalg.lstsq(Hn, z[: n_ + 1][keep], rcond=None)[0]
    return out


# -- the paper's filter and the floor variant ---------------------------------------------------
def growing_memory_forecast(z, steps: int = 1, order: int = 2, floor_memory: int | None = None) -> np.ndarray:
    """Growing-memory polynomial filter (eqs. (5)-(6)) and its ``steps``-ahead prediction.

    ``floor_memory`` = ``N_f``: gains frozen at ``g_{N_f}`` (``None`` = no floor).

    For complete series (no NaN) with a floor, the first ``N_f`` samples run through
    :func:`tvtrack.filters.polynomial.growing_memory_filter` and the fixed-gain remainder, a
    linear time-invariant system, through :func:`scipy.signal.lfilter` started from the filter's
    state (same result to rounding: ~1e-12 relative for N_f <= 30, ~1e-8 for N_f = 200). Even
    after the core filter's vectorised start-up this is ~12x faster than its loop over frames on
    the notebook's paper-profile calls (205 calls: 0.7 s against 8 s CPU).
    """
    steps = check_steps(steps)
    z = check_z(z)
    T = z.shape[-1]
    if floor_memory is None or floor_memory >= T or not np.all(np.isfinite(z)):
        return predict_ahead(growing_memory_filter(z, order, floor_memory), steps)
    head = growing_memory_filter(z[..., :floor_memory], order, floor_memory)
    out = np.empty(z.shape)
    out[..., :floor_memory] = predict_ahead(head, steps)
    out[..., floor_memory:] = _fixed_gain_forecast(
        z[..., floor_memory:], head[..., -1, :], order, growing_memory_gains(order, floor_memory)[-1], steps
    )
    return out


def _fixed_gain_forecast(z, x0, order: int, gain, steps: int) -> np.ndarray:
    """Forecasts of the fixed-gain filter ``X_t = A X_{t-1} + g z_t``, ``A = (I - g h_0) F``,
    from the state ``x0`` (..., n) before ``z[..., 0]``, as an IIR filter with initial conditions.

    As a state-space system in ``s_t = X_{t-1}``: ``s_{t+1} = A s_t + g z_t``,
    ``y_t = c A s_t + c g z_t`` with ``c`` the prediction row ``(steps^k / k!)``; its transfer
    function runs in ``lfilter``, and the initial conditions ``zi`` are chosen so that the
    zero-input response equals ``c A^(k+1) x0`` for the first ``n`` samples (then for all).
    """
    from scipy.signal import lfilter, ss2tf

    n = order + 1
    F = taylor_transition(order)
    A = (np.eye(n) - np.outer(gain, np.eye(n)[0])) @ F
    c = predict_ahead(np.eye(n), steps)  # (n,): row mapping a state to its forecast
    b, a = ss2tf(A, gain[:, None], (c @ A)[None, :], np.array([[c @ gain]]))
    b = b[0]
    # zero-input response of lfilter for unit initial conditions, first n samples: M (n, n)
    M = np.stack([lfilter(b, a, np.zeros(n), zi=np.eye(n)[i])[0] for i in range(n)], axis=1)
    O = np.stack([c @ np.linalg.matrix_power(A, k + 1) for k in range(n)])  # (n, n)
    zi = x0 @ np.linalg.solve(M, O).T
    return lfilter(b, a, z, axis=-1, zi=zi)[0]


def fading_memory_gains(theta: float) -> np.ndarray:
    """Steady-state gains of Morrison's 2nd-degree fading-memory polynomial filter, for the state
    ``(x, x', x'')`` per frame: ``(1 - theta^3, 1.5 (1 - theta)^2 (1 + theta), (1 - theta)^3)``
    (the g-h-k form ``g = 1 - theta^3``, ``h = 1.5 (1 - theta^2)(1 - theta)``, ``k = (1 - theta)^3 / 2``
    with ``x'' += 2k e``; Morrison 1969, Brookner 1998 Table 7.2-2). It is the least-squares
    quadratic fit with weights ``theta^j`` on the sample ``j`` frames back: a principled
    counterpart of the paper's frozen-gain floor.
    """
    if not (0 < theta < 1):
        raise ValueError(f"parameter 'theta' = {theta!r}; it must be in (0, 1)")
    return np.array([1 - theta**3, 1.5 * (1 - theta) ** 2 * (1 + theta), (1 - theta) ** 3])


def fading_switch(theta: float, n_max: int) -> int:
    """The samples the expanding (growing) memory runs before Morrison's fading memory takes over: the first ``N >= 3``
    whose growing-memory position gain ``g_{N,1}`` is at most the fading one, ``1 - theta^3`` (Morrison 1969; Brookner
    1998, section 7.4: the expanding-memory filter initialises the fading-memory one), at most ``n_max``."""
    g1 = growing_memory_gains(2, n_max)[2:, 0]
    below = np.nonzero(g1 <= fading_memory_gains(theta)[0])[0]
    return int(3 + below[0]) if below.size else int(n_max)


def fading_memory_forecast(z, theta: float, steps: int = 1) -> np.ndarray:
    """Morrison's fading-memory quadratic filter (:func:`fading_memory_gains`) and its
    ``steps``-ahead prediction. Started by the expanding memory (the growing-memory filter, from the exact quadratic
    through the first three samples, eq. (4)) until its gains fall to the fading ones (:func:`fading_switch`), then
    run with the fixed gains: a long memory is not started from three noisy samples, whose velocity and acceleration
    errors would take many times ``1 / (1 - theta)`` frames to fade.

    Parameters
    ----------
    z : ndarray, shape (..., T)
        Complete measurements, px.
    """
    steps = check_steps(steps)
    z = check_z(z)
    if not np.all(np.isfinite(z)) or z.shape[-1] < 4:
        raise ValueError("parameter 'z' must be complete (no NaN) with at least 4 samples")
    n = fading_switch(theta, z.shape[-1])
    head = growing_memory_filter(z[..., :n], 2, None)
    out = np.empty(z.shape)
    out[..., :n] = predict_ahead(head, steps)
    if n < z.shape[-1]:
        out[..., n:] = _fixed_gain_forecast(z[..., n:], head[..., -1, :], 2, fading_memory_gains(theta), steps)
    return out


def g1_floor_gains(order: int, n_frames: int, g1_min: float) -> np.ndarray:
    """Gain table of the *variant* floor: where ``g_{N,1} < g1_min``, ``g_N`` is scaled by
    ``g1_min / g_{N,1}`` (all components by the same factor), so ``g_1`` never drops below
    ``g1_min`` while ``g_2, g_3`` keep decaying (as ``~ g1_min / N`` and ``g1_min / N^2``).

    Returns
    -------
    ndarray, shape (n_frames, order+1)
        Row ``N-1`` is the gain for the ``N``-th sample; NaN for ``N <= order``.
    """
    if not (0 < g1_min <= 1):
        raise ValueError(f"parameter 'g1_min' = {g1_min!r}; it must be in (0, 1]")
    g = growing_memory_gains(order, n_frames)
    scale = np.where(g[:, 0] < g1_min, g1_min / g[:, 0], 1.0)
    return g * scale[:, None]


def g1_floor_filter(z, g1_min: float, order: int = 2) -> np.ndarray:
    """Polynomial filter with the variant floor of :func:`g1_floor_gains`.

    Starts like the core filter (exact polynomial through the first ``order+1`` samples,
    eq. (4)), then ``X <- F X; X <- X + g_N (z - x)`` (eqs. (5)-(6)).

    Parameters
    ----------
    z : ndarray, shape (..., T)
        Measurements, px; all finite (this variant does not coast over gaps).

    Returns
    -------
    ndarray, shape (..., T, order+1)
        States; NaN for the first ``order`` samples.
    """
    z = check_z(z)
    if not np.all(np.isfinite(z)):
        raise ValueError("parameter 'z' holds NaN; g1_floor_filter needs complete sequences")
    n = order + 1
    T = z.shape[-1]
    if T < n:
        raise ValueError(f"parameter 'z' has {T} samples; it needs >= order+1 = {n}")
    gains = g1_floor_gains(order, T, g1_min)
    F = taylor_transition(order)
    H = polynomial_observation_row(order, np.arange(n - 1, -1, -1.0))  # lags n-1..0 back from t = n-1
    states = np.full(z.shape + (n,), np.nan)
    x = np.linalg.solve(H, z[..., :n][..., None])[..., 0]  # (eq. 4) on the first n samples
    states[..., n - 1, :] = x
    for t in range(n, T):
        x = x @ F.T  # (eq. 5)
        x = x + gains[t] * (z[..., t] - x[..., 0])[..., None]  # (eq. 6), gain for N = t+1
        states[..., t, :] = x
    return states


def g1_floor_forecast(z, floor_memory: int, steps: int = 1, order: int = 2) -> np.ndarray:
    """``steps``-ahead forecast of the *variant* floor (:func:`g1_floor_filter`) at the floor memory ``N_f``:
    ``g_1`` never drops below ``g_{N_f,1}`` of the growing memory, ``g_2, g_3`` scaled by the same factor.

    Parameters
    ----------
    z : ndarray, shape (..., T)
        Complete measured series, px.

    Returns
    -------
    ndarray, shape like ``z``, px (NaN for the first ``order`` samples).
    """
    g1_min = float(growing_memory_gains(order, int(floor_memory))[-1, 0])
    return predict_ahead(g1_floor_filter(z, g1_min, order), check_steps(steps))


# -- window methods -------------------------------------------------------------------------------
def _windowed(z, window: int, shortest: int, weights) -> np.ndarray:
    """``weights(n) @`` the last ``n = min(window, t + 1)`` samples at every frame ``t >= shortest - 1`` (NaN
    before): a frame with fewer than ``window`` samples behind it uses all it has, so a window longer than the first
    scored frame is scored over the same frames as every other method. ``weights(n)``: (n,), oldest first."""
    out = np.full(z.shape, np.nan)
    out[..., window - 1 :] = sliding_window_view(z, window, axis=-1) @ weights(window)
    for n in range(shortest, window):
        out[..., n - 1] = z[..., :n] @ weights(n)
    return out


def sliding_regression_forecast(z, window: int, degree: int, steps: int = 1) -> np.ndarray:
    """Least-squares polynomial of ``degree`` on the last ``window`` samples, evaluated
    ``steps`` ahead. Linear in the data, so it is one fixed FIR filter applied to all windows;
    ``window = degree + 1`` is exact finite-difference (Newton) extrapolation. Before ``window`` samples the fit
    uses all there are (at least ``degree + 1``, :func:`_windowed`).
    """
    steps = check_steps(steps)
    z = check_z(z)
    if not (isinstance(degree, (int, np.integer)) and 0 <= degree <= 5):
        raise ValueError(f"parameter 'degree' = {degree!r}; it must be an integer in [0, 5]")
    if not (isinstance(window, (int, np.integer)) and degree + 1 <= window <= z.shape[-1]):
        raise ValueError(
            f"parameter 'window' = {window!r}; it must be an integer in [degree+1, T] = [{degree + 1}, {z.shape[-1]}]"
        )

    def weights(n):
        t = np.arange(n, dtype=float) - (n - 1)  # 0 = newest sample
        V = np.vander(t, degree + 1, increasing=True)
        return (np.vander(np.array([float(steps)]), degree + 1, increasing=True) @ np.linalg.pinv(V))[0]

    return _windowed(z, window, degree + 1, weights)


def spline_forecast(z, window: int, steps: int = 1) -> np.ndarray:
    """Not-a-knot cubic spline (``scipy.interpolate.CubicSpline``) through the last ``window``
    samples, extrapolated ``steps`` ahead (``window >= 4``).

    The spline is linear in its data, so its extrapolation is one FIR filter: the weights are
    the spline's extrapolations of the ``window`` unit vectors, applied to every window. Before ``window`` samples
    the spline runs through all there are (at least 4, :func:`_windowed`).
    """
    steps = check_steps(steps)
    z = check_z(z)
    if not (isinstance(window, (int, np.integer)) and 4 <= window <= z.shape[-1]):
        raise ValueError(f"parameter 'window' = {window!r}; it must be an integer in [4, {z.shape[-1]}]")

    def weights(n):  # the weight of each sample, oldest first
        return CubicSpline(np.arange(n, dtype=float), np.eye(n), axis=0, extrapolate=True)(n - 1.0 + steps)

    return _windowed(z, window, 4, weights)


def natural_spline_forecast(z, window: int, steps: int = 1) -> np.ndarray:
    """Natural cubic spline (zero second derivative at both ends) through the last ``window``
    samples, extrapolated ``steps`` ahead as a natural spline extends beyond its last knot: linearly,
    ``S(t_n) + steps * S'(t_n)`` (``window >= 4``; the classical spline of the numerical-methods texts,
    the minimiser of the integrated squared second derivative on the whole line).

    Like :func:`spline_forecast` it is one FIR filter applied to every window, over all the samples there are before
    ``window`` of them (at least 4).
    """
    steps = check_steps(steps)
    z = check_z(z)
    if not (isinstance(window, (int, np.integer)) and 4 <= window <= z.shape[-1]):
        raise ValueError(f"parameter 'window' = {window!r}; it must be an integer in [4, {z.shape[-1]}]")

    def weights(n):  # (n,), oldest first
        spl = CubicSpline(np.arange(n, dtype=float), np.eye(n), axis=0, bc_type="natural")
        return spl(n - 1.0) + steps * spl.derivative()(n - 1.0)

    return _windowed(z, window, 4, weights)


# the learned predictors (scikit-learn networks) and their cross-validation live in .learned
