"""The Kalman-filter baselines of paper 004 (Kokryatska and Hrynchyshyn 2005 name "Kalman filters, 1-2 px" among
their comparisons): a constant-acceleration filter with white jerk and a Singer-model filter (exponentially
correlated acceleration), their parameters fitted by maximum likelihood on the training paths of each fold, and the
generic Kalman forecast the optimal (true-model) predictor also uses. Re-exported by :mod:`.predictors`."""

from __future__ import annotations

import numpy as np
from scipy.linalg import expm

from ...filters.kalman import kf_predict, kf_update
from ...filters.polynomial import taylor_transition
from ._checks import check_steps, check_z

__all__ = [
    "constant_acceleration_model",
    "kalman_forecast",
    "fit_constant_acceleration",
    "fit_constant_acceleration_folds",
    "constant_acceleration_forecast",
    "singer_model",
    "fit_singer",
    "fit_singer_folds",
    "singer_forecast",
]


# -- Kalman filters -------------------------------------------------------------------------------
#: Prior of the Kalman predictors (state (x, x', x'') per frame, zero mean): diffuse.
_KALMAN_P0 = np.diag([1e4, 1e2, 1e1])


def constant_acceleration_model(jerk_psd, meas_var):
    """Constant-acceleration model per frame (state ``(x, x', x'')``, px, px/frame, px/frame^2).

    Process noise from white jerk of spectral density ``q`` (px^2/frame^5):
    ``Q = q [[1/20, 1/8, 1/6], [1/8, 1/3, 1/2], [1/6, 1/2, 1]]`` (Bar-Shalom et al. 2001, 6.2.3).

    Parameters
    ----------
    jerk_psd : float or ndarray, shape (...)
    meas_var : float or ndarray, shape (...)
        Measurement noise variance, px^2.

    Returns
    -------
    F (3, 3), Q (..., 3, 3), H (1, 3), R (..., 1, 1)
    """
    q = np.asarray(jerk_psd, dtype=float)
    r = np.asarray(meas_var, dtype=float)
    if np.any(q < 0) or np.any(r <= 0):
        raise ValueError(f"jerk_psd must be >= 0 and meas_var > 0; got {q!r}, {r!r}")
    base = np.array([[1 / 20, 1 / 8, 1 / 6], [1 / 8, 1 / 3, 1 / 2], [1 / 6, 1 / 2, 1.0]])
    return taylor_transition(2), q[..., None, None] * base, np.array([[1.0, 0.0, 0.0]]), r[..., None, None]


def kalman_forecast(z, F, Q, H, R, x0, P0, steps: int = 1, burn_in: int = 0):
    """Kalman filter over scalar series and its ``steps``-ahead forecast of ``H x``.

    The covariance does not depend on the data, so it is carried with only the batch axes of
    ``Q, R, P0`` (not one per series), which keeps long runs cheap.

    Parameters
    ----------
    z : ndarray, shape (..., T)
        Measurements (all finite), px.
    F : ndarray, shape (n, n) or (..., n, n); Q : (..., n, n); H : (1, n); R : (..., 1, 1)
        Batch axes of ``F, Q, R, P0`` broadcast against each other and against ``z.shape[:-1]``.
    x0 : ndarray, shape (..., n)
        Prior mean for frame 0; P0 : (..., n, n) its covariance.
    burn_in : int
        Frames whose innovations are left out of the log-likelihood (diffuse start).

    Returns
    -------
    forecast : ndarray, shape (..., T)
    loglik : ndarray, shape (...)
        Gaussian log-likelihood of the innovations after ``burn_in``, summed over time.
    """
    forecast, norm_sq, log_s, count = _kalman_pass(z, F, Q, H, R, x0, P0, steps, burn_in)
    loglik = -0.5 * (norm_sq + log_s + count * np.log(2 * np.pi))
    return forecast, np.broadcast_to(loglik, forecast.shape[:-1])


def _kalman_pass(z, F, Q, H, R, x0, P0, steps: int, burn_in: int):
    """The loop of :func:`kalman_forecast`: forecasts and, over frames ``>= burn_in``, the sums of
    normalised squared innovations ``nu^2 / S`` and of ``log S``, and their count."""
    steps = check_steps(steps)
    z = check_z(z)
    if not np.all(np.isfinite(z)):
        raise ValueError("parameter 'z' holds NaN; kalman_forecast needs complete sequences")
    T = z.shape[-1]
    F = np.asarray(F, dtype=float)
    H = np.asarray(H, dtype=float)
    forecast_row = (H @ np.linalg.matrix_power(F, steps))[..., 0, :]  # (..., n): state -> forecast of H x
    Q = np.asarray(Q, dtype=float)
    R = np.asarray(R, dtype=float)
    x0 = np.asarray(x0, dtype=float)
    P0 = np.asarray(P0, dtype=float)
    n = F.shape[-1]
    cov_batch = np.broadcast_shapes(F.shape[:-2], P0.shape[:-2], Q.shape[:-2], R.shape[:-2])
    P = np.broadcast_to(P0, cov_batch + (n, n)).copy()
    x = np.broadcast_to(x0, np.broadcast_shapes(z.shape[:-1], x0.shape[:-1], cov_batch) + (n,)).copy()
    forecast = []
    norm_sq, log_s = 0.0, 0.0
    # the core's steps (kf_predict / kf_update), not SequentialFilter.run: that carries P per series and keeps the
    # whole history, where this loop carries P per noise setting only and keeps just the forecast and likelihood
    for t in range(T):
        if t > 0:
            x, P = kf_predict(x, P, F, Q)
        x, P, nu, S = kf_update(x, P, z[..., t, None], H, R)
        if t >= burn_in:
            norm_sq = norm_sq + nu[..., 0] ** 2 / S[..., 0, 0]
            log_s = log_s + np.log(S[..., 0, 0])
        forecast.append(np.einsum("...j,...j->...", forecast_row, x))
    return np.stack(forecast, axis=-1), norm_sq, log_s, max(T - burn_in, 0)


def fit_constant_acceleration(z, jerk_grid, meas_var_grid, burn_in: int = 10):
    """Maximum-likelihood white-jerk density and measurement variance on a grid.

    Parameters
    ----------
    z : ndarray, shape (..., T)
        Training series.
    jerk_grid, meas_var_grid : array_like, shapes (A,), (B,)

    Returns
    -------
    (jerk_psd, meas_var) : floats at the grid maximum of the summed log-likelihood
    loglik : ndarray, shape (A, B)
    """
    z = check_z(z).reshape(-1, np.shape(z)[-1])
    q = np.asarray(jerk_grid, dtype=float)[:, None, None]
    r = np.asarray(meas_var_grid, dtype=float)[None, :, None]
    F, Q, H, R = constant_acceleration_model(q, r)  # Q (A,1,1,3,3), R (A,B,1,1,1)
    _, ll = kalman_forecast(z, F, Q, H, R, np.zeros(3), _KALMAN_P0, burn_in=burn_in)
    ll = ll.sum(axis=-1)
    a, b = np.unravel_index(np.argmax(ll), ll.shape)
    return (float(q[a, 0, 0]), float(r[0, b, 0])), ll


def fit_constant_acceleration_folds(z, folds, jerk_grid, meas_var_grid) -> list[tuple[float, float]]:
    """:func:`fit_constant_acceleration` on the training paths of each fold.

    Parameters
    ----------
    z : ndarray, shape (paths, ..., T)
        Training series (one trial), px.

    Returns
    -------
    list of (jerk_psd, meas_var), one per fold
    """
    return [fit_constant_acceleration(z[train], jerk_grid, meas_var_grid)[0] for train, _ in folds]


def _fold_forecasts(z, models, folds, steps: int) -> np.ndarray:
    """Kalman forecasts of each fold's test paths with that fold's ``(F, Q, H, R, P0)``;
    ``z`` (trials, paths, ..., T) px, the result shaped like ``z`` (NaN where not forecast)."""
    z = check_z(z)
    out = np.full(z.shape, np.nan)
    for (F, Q, H, R, P0), (_, test) in zip(models, folds):
        out[:, test] = kalman_forecast(z[:, test], F, Q, H, R, np.zeros(3), P0, steps)[0]
    return out


def constant_acceleration_forecast(z, fits, folds, steps: int = 1) -> np.ndarray:
    """Constant-acceleration Kalman forecasts of the test paths of each fold, with that fold's
    noise levels from :func:`fit_constant_acceleration_folds` (prior as in the fit).

    Parameters
    ----------
    z : ndarray, shape (trials, paths, ..., T)
        Complete measured series, px.

    Returns
    -------
    ndarray, shape like ``z``
    """
    return _fold_forecasts(z, [(*constant_acceleration_model(q, r), _KALMAN_P0) for q, r in fits], folds, steps)


#: Correlation time (frames) up to which Singer's closed-form Q is used (Van Loan above).
_SINGER_CLOSED_FORM_MAX_TAU = 10.0


def _singer_q_closed_form(a):
    """Singer (1970) eq. (11): Q per frame for unit white-acceleration-noise density, ``a = 1/tau``
    (shape (...)); accurate for ``a`` >~ 0.05."""
    e1, e2 = np.exp(-a), np.exp(-2 * a)
    q11 = (1 - e2 + 2 * a + 2 * a**3 / 3 - 2 * a**2 - 4 * a * e1) / (2 * a**5)
    q12 = (e2 + 1 - 2 * e1 + 2 * a * e1 - 2 * a + a**2) / (2 * a**4)
    q13 = (1 - e2 - 2 * a * e1) / (2 * a**3)
    q22 = (4 * e1 - 3 - e2 + 2 * a) / (2 * a**3)
    q23 = (e2 + 1 - 2 * e1) / (2 * a**2)
    q33 = (1 - e2) / (2 * a)
    return np.stack([np.stack([q11, q12, q13], -1), np.stack([q12, q22, q23], -1), np.stack([q13, q23, q33], -1)], -2)


def _singer_q_van_loan(tau):
    """Q per frame for unit noise density by Van Loan (1978): ``expm([[-A, G G^T], [0, A^T]])`` holds
    ``F^-1 Q`` and ``F^T``; accurate for ``tau`` >~ 0.3 frames (shape (...))."""
    M = np.zeros(np.shape(tau) + (6, 6))
    M[..., 0, 1] = M[..., 1, 2] = -1.0  # -A
    M[..., 2, 2] = 1.0 / tau
    M[..., 2, 5] = 1.0  # G G^T
    M[..., 4, 3] = M[..., 5, 4] = 1.0  # A^T
    M[..., 5, 5] = -1.0 / tau
    E = expm(M)
    return np.swapaxes(E[..., 3:, 3:], -1, -2) @ E[..., :3, 3:]


def singer_model(tau_frames, accel_var, meas_var):
    """Singer's exponentially correlated acceleration model per frame (Singer 1970, IEEE Trans.
    AES-6, eqs. (5)-(11)); state ``(x, x', x'')`` in px, px/frame, px/frame^2.

    The acceleration is a first-order Gauss-Markov process, ``da/dt = -a / tau + w``, with
    stationary variance ``accel_var`` (white ``w`` of density ``2 accel_var / tau``). Over one frame,
    with ``alpha = 1 / tau``,
    ``F = [[1, 1, (alpha - 1 + e^{-alpha}) / alpha^2], [0, 1, (1 - e^{-alpha}) / alpha], [0, 0, e^{-alpha}]]``,
    and ``Q`` is the exact discretisation: Singer's closed-form entries for ``tau <= 10`` frames,
    Van Loan's matrix exponential above (the closed form cancels catastrophically for long ``tau``,
    the matrix exponential overflows for short ``tau``; both agree to ~1e-9 at 10 frames). As ``tau -> inf`` with ``2 accel_var / tau = q`` fixed the model becomes the
    white-jerk constant-acceleration model (:func:`constant_acceleration_model` with density ``q``);
    as ``tau -> 0`` the acceleration is white and the model tends to constant velocity.

    Parameters
    ----------
    tau_frames : float or ndarray, shape (...)
        Acceleration correlation time, frames (> 0).
    accel_var : float or ndarray, shape (...)
        Stationary acceleration variance, (px/frame^2)^2 (>= 0).
    meas_var : float or ndarray, shape (...)
        Measurement noise variance, px^2 (> 0).

    Returns
    -------
    F (..., 3, 3), Q (..., 3, 3), H (1, 3), R (..., 1, 1)
        Batch axes are those of ``tau_frames`` (F) and of ``tau_frames, accel_var`` broadcast (Q).
    """
    tau = np.asarray(tau_frames, dtype=float)
    s2 = np.asarray(accel_var, dtype=float)
    r = np.asarray(meas_var, dtype=float)
    if np.any(tau <= 0) or np.any(s2 < 0) or np.any(r <= 0):
        raise ValueError(f"tau_frames must be > 0, accel_var >= 0 and meas_var > 0; got {tau!r}, {s2!r}, {r!r}")
    a = 1.0 / tau
    e1 = np.exp(-a)
    F = np.zeros(tau.shape + (3, 3))
    F[..., 0, 0] = F[..., 1, 1] = F[..., 0, 1] = 1.0
    F[..., 0, 2] = np.where(
        a < 1e-3, 0.5 - a / 6 + a**2 / 24, (a - 1 + e1) / np.maximum(a, 1e-3) ** 2
    )  # series: no cancellation
    F[..., 1, 2] = -np.expm1(-a) / a
    F[..., 2, 2] = e1
    short = tau <= _SINGER_CLOSED_FORM_MAX_TAU
    Q_unit = np.empty(tau.shape + (3, 3))
    Q_unit[short] = _singer_q_closed_form(a[short])
    Q_unit[~short] = _singer_q_van_loan(tau[~short])
    Q = (2 * s2 * a)[..., None, None] * Q_unit
    return F, 0.5 * (Q + np.swapaxes(Q, -1, -2)), np.array([[1.0, 0.0, 0.0]]), r[..., None, None]


def fit_singer(z, tau_grid, ratio_grid, burn_in: int = 10):
    """Maximum-likelihood Singer parameters: ``tau`` and the ratio ``accel_var / meas_var`` on a
    grid, the common scale (``meas_var``) in closed form.

    Scaling ``Q``, ``R`` and the prior covariance by ``c`` leaves the Kalman gains and the
    innovations unchanged and scales every innovation variance ``S`` by ``c``, so with the model
    run at ``meas_var = 1`` the likelihood is maximised by ``c = mean(nu^2 / S)`` (the
    concentrated likelihood; Harvey 1989, Sect. 3.4). All series share the parameters.

    Parameters
    ----------
    z : ndarray, shape (..., T)
        Training series, px.
    tau_grid, ratio_grid : array_like, shapes (A,), (B,)
        Acceleration correlation times, frames; ratios ``accel_var / meas_var``, frame^-4.
    burn_in : int
        Innovations of the first frames left out of the likelihood (diffuse start).

    Returns
    -------
    (tau, accel_var, meas_var) : floats, at the grid maximum (frames, (px/frame^2)^2, px^2)
    loglik : ndarray, shape (A, B)
        Concentrated log-likelihood, summed over the series.
    """
    z = check_z(z).reshape(-1, np.shape(z)[-1])
    tau = np.asarray(tau_grid, dtype=float)[:, None, None]
    ratio = np.asarray(ratio_grid, dtype=float)[None, :, None]
    F, Q, H, R = singer_model(tau, ratio, 1.0)  # F (A,1,1,3,3), Q (A,B,1,3,3)
    _, norm_sq, log_s, count = _kalman_pass(z, F, Q, H, R, np.zeros(3), _KALMAN_P0, 1, burn_in)
    n = count * z.shape[0]
    scale = norm_sq.sum(axis=-1) / n  # (A, B): ML measurement variance
    log_s = np.broadcast_to(log_s, norm_sq.shape).sum(axis=-1)  # S is shared by the series: one value per cell
    ll = -0.5 * (n * (1 + np.log(2 * np.pi * scale)) + log_s)
    a, b = np.unravel_index(np.argmax(ll), ll.shape)
    c = float(scale[a, b])
    return (float(tau[a, 0, 0]), float(ratio[0, b, 0]) * c, c), ll


def fit_singer_folds(z, folds, tau_grid, ratio_grid) -> list[tuple[float, float, float]]:
    """:func:`fit_singer` on the training paths of each fold (``z`` as for
    :func:`fit_constant_acceleration_folds`); one ``(tau_frames, accel_var, meas_var)`` per fold."""
    return [fit_singer(z[train], tau_grid, ratio_grid)[0] for train, _ in folds]


def singer_forecast(z, fits, folds, steps: int = 1) -> np.ndarray:
    """Singer-model Kalman forecasts of the test paths of each fold, with that fold's parameters
    from :func:`fit_singer_folds` (prior as in the fit: ``meas_var`` times the unit-scale prior);
    ``z`` as for :func:`constant_acceleration_forecast`, the result shaped like it."""
    return _fold_forecasts(z, [(*singer_model(tau, s2, r), r * _KALMAN_P0) for tau, s2, r in fits], folds, steps)
