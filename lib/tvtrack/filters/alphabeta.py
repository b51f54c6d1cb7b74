"""Fixed- and scheduled-gain alpha-beta (order 1) and alpha-beta-gamma (order 2) filters.

State per channel ``x = (x, v, a)`` (order 2) or ``(x, v)`` (order 1) in per-frame units
(elements, elements/frame, elements/frame^2). One frame of the filter (Fisenko et al. 2008,
eq. (1), with the innovation made the scalar ``Z_k - h F x_{k-1}``: as printed it subtracts the
vector ``F x_{k-1}`` from the scalar coordinate)::

    x_k = F x_{k-1} + K_k (Z_k - h F x_{k-1}),    F = taylor_transition(order),  h = (1, 0, ..)

The gain schedule is the growing-memory least-squares law (this project's reading: the paper describes
gains that decay with the frame number down to a lower bound but does not print them; from
:func:`tvtrack.filters.polynomial.growing_memory_gains`) with a *lower bound*:
``K_k = K(min(k, k_bound))``. ``K = 0`` is the paper's zero-gain prediction mode (E1).

With frozen gains ``K`` the estimation error ``e_k = x_k - x^true_k`` obeys
``e_k = A e_{k-1} + K eps_k`` with ``A = (I - K h) F`` (derived here), so its stationary covariance
solves the discrete Lyapunov equation ``P = A P A^T + sigma^2 K K^T`` and the lag-``m``
cross-covariance is ``E[e_{k+m} e_k^T] = A^m P``.

A growing-memory filter floored at ``N_f`` (gains frozen at ``K(N_f)``) is a fixed-gain
alpha-beta-gamma filter with ``alpha = g_1``, ``beta = g_2``, ``gamma = g_3 / 2`` (the g-h-k form
``x'' += 2 gamma e``), whose stationary error is :func:`steady_state_covariance`.

All filter functions broadcast over leading batch axes (trials, channels); time is the axis
just before the state axis.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import solve_discrete_lyapunov

from .interface import SequentialFilter
from .kalman import joseph_covariance
from .polynomial import growing_memory_gains, taylor_transition

__all__ = [
    "closed_form_gains",
    "gain_schedule",
    "observation_row",
    "closed_loop_matrix",
    "steady_state_covariance",
    "lagged_covariances",
    "error_covariance_sequence",
    "filter_step",
    "GainScheduleFilter",
    "scheduled_filter",
]

_ORDERS = (1, 2)


def _check_order(order) -> int:
    if order not in _ORDERS:
        raise ValueError(f"parameter 'order' = {order!r}; it must be 1 (alpha-beta) or 2 (alpha-beta-gamma)")
    return int(order)


def _order_of(K) -> int:
    K = np.asarray(K, dtype=float)
    if K.shape[-1] not in (2, 3):
        raise ValueError(f"gain vector has {K.shape[-1]} components; it must have 2 or 3")
    return K.shape[-1] - 1


def closed_form_gains(order: int, k) -> np.ndarray:
    """Growing-memory gains in closed form (derived here; they reproduce batch least squares), every ``k >= 1``.

    Order 1: ``(2(2k-1), 6) / (k(k+1))``; order 2:
    ``(3(3k^2-3k+2), 18(2k-1), 60) / (k(k+1)(k+2))``. For ``k <= order`` the least-squares fit
    is not yet determined, but these values make the recursion start from any initial state
    and reproduce the batch fit from ``k = order+1`` on.

    Parameters
    ----------
    k : int or array_like of int, shape (...)
        Number of measurements processed, including the current one (>= 1).

    Returns
    -------
    ndarray, shape (..., order+1)
    """
    _check_order(order)
    k = np.asarray(k, dtype=float)
    if np.any(k < 1):
        raise ValueError(f"parameter 'k' has values < 1 (min {k.min()}); it must be >= 1")
    if order == 1:
        d = k * (k + 1)
        return np.stack([2 * (2 * k - 1) / d, 6 / d], axis=-1)
    d = k * (k + 1) * (k + 2)
    return np.stack([3 * (3 * k**2 - 3 * k + 2) / d, 18 * (2 * k - 1) / d, 60 / d], axis=-1)


def gain_schedule(order: int, k_bound: int, n_max: int | None = None) -> np.ndarray:
    """Table of gains ``K(min(k, k_bound))`` for ``k = 1..n_max`` (row ``k-1``).

    Rows ``k >= order+1`` come from :func:`growing_memory_gains` (the least-squares law);
    the first ``order`` rows, where that law is undefined, from :func:`closed_form_gains`.

    Parameters
    ----------
    order : {1, 2}
    k_bound : int
        Frame number at which the gains stop decreasing (``k_b``; the paper's Fig. 4 parameter), >= 1.
    n_max : int, optional
        Table length; default ``k_bound`` (every later row equals the last).

    Returns
    -------
    ndarray, shape (n_max, order+1)
    """
    _check_order(order)
    if not (isinstance(k_bound, (int, np.integer)) and k_bound >= 1):
        raise ValueError(f"parameter 'k_bound' = {k_bound!r}; it must be an integer >= 1")
    n_max = int(k_bound if n_max is None else n_max)
    if n_max < 1:
        raise ValueError(f"parameter 'n_max' = {n_max}; it must be >= 1")
    m = max(min(k_bound, n_max), order + 1)
    table = growing_memory_gains(order, m)
    table[:order] = closed_form_gains(order, np.arange(1, order + 1))
    k = np.minimum(np.arange(1, n_max + 1), k_bound)
    return table[k - 1]


def observation_row(order: int) -> np.ndarray:
    """``h = (1, 0, ..)``, shape (order+1,)."""
    _check_order(order)
    h = np.zeros(order + 1)
    h[0] = 1.0
    return h


def closed_loop_matrix(K) -> np.ndarray:
    """``A = (I - K h) F`` for a frozen gain vector ``K`` of shape (order+1,) (derived here)."""
    K = np.asarray(K, dtype=float)
    order = _order_of(K)
    n = order + 1
    return (np.eye(n) - np.outer(K, observation_row(order))) @ taylor_transition(order)


def steady_state_covariance(K, sigma_eps: float = 1.0) -> np.ndarray:
    """Stationary filtered-error covariance of the frozen filter.

    Solves ``P = A P A^T + sigma_eps^2 K K^T`` (derived here) with
    :func:`scipy.linalg.solve_discrete_lyapunov`.

    Parameters
    ----------
    K : array_like, shape (order+1,)
        Frozen gains; the closed loop must be stable.
    sigma_eps : float
        Measurement noise RMS, elements (> 0).

    Returns
    -------
    ndarray, shape (order+1, order+1)
        Covariance of (x, v[, a]) errors in elements, elements/frame[, elements/frame^2].
    """
    if not sigma_eps > 0:
        raise ValueError(f"parameter 'sigma_eps' = {sigma_eps!r}; it must be > 0")
    K = np.asarray(K, dtype=float)
    A = closed_loop_matrix(K)
    rho = np.max(np.abs(np.linalg.eigvals(A)))
    if rho >= 1:
        raise ValueError(f"gains {K} give an unstable closed loop (spectral radius {rho:.4f} >= 1)")
    P = solve_discrete_lyapunov(A, sigma_eps**2 * np.outer(K, K))
    return 0.5 * (P + P.T)


def lagged_covariances(K, sigma_eps: float = 1.0, max_lag: int = 1) -> np.ndarray:
    """Stationary lagged error covariances ``C(m) = E[e_{k+m} e_k^T] = A^m P``, m = 0..max_lag.

    Returns
    -------
    ndarray, shape (max_lag+1, order+1, order+1)
    """
    if max_lag < 0:
        raise ValueError(f"parameter 'max_lag' = {max_lag}; it must be >= 0")
    P = steady_state_covariance(K, sigma_eps)
    A = closed_loop_matrix(K)
    out = np.empty((max_lag + 1,) + P.shape)
    out[0] = P
    for m in range(1, max_lag + 1):
        out[m] = A @ out[m - 1]
    return out


def error_covariance_sequence(gains, sigma_eps: float = 1.0, P0=None) -> np.ndarray:
    """Noise-driven error covariance of a filter with arbitrary gains (derived here).

    ``P_k = (I - K_k h) F P_{k-1} F^T (I - K_k h)^T + sigma_eps^2 K_k K_k^T``; a zero gain row
    is a coasting frame (``P_k = F P_{k-1} F^T``). Exact for any linear filter with no
    process noise; the dynamic (bias) error is separate.

    Parameters
    ----------
    gains : array_like, shape (..., T, order+1)
    sigma_eps : float
        Measurement noise RMS, elements.
    P0 : array_like, shape (..., order+1, order+1), optional
        Covariance before the first frame; default 0 (the initial state is a deterministic
        error, worked off by the growing-memory start).

    Returns
    -------
    ndarray, shape (..., T, order+1, order+1)
    """
    G = np.asarray(gains, dtype=float)
    order = _order_of(G)
    n = order + 1
    F = taylor_transition(order)
    h = observation_row(order)
    T = G.shape[-2]
    batch = G.shape[:-2]
    P = np.zeros(batch + (n, n)) if P0 is None else np.broadcast_to(np.asarray(P0, float), batch + (n, n)).copy()
    out = np.empty(batch + (T, n, n))
    for t in range(T):
        K = G[..., t, :]
        P = joseph_covariance(F @ P @ F.T, K[..., :, None], h[None, :], sigma_eps**2)
        out[..., t, :, :] = P
    return out


def filter_step(x, z, K, F):
    """One frame of eq. (1): predict with ``F``, correct with gains ``K``.

    Parameters
    ----------
    x : ndarray, shape (..., n)    previous estimate
    z : ndarray, shape (...)       measurement; NaN = missing (the filter coasts)
    K : ndarray, shape (..., n)    gains for this frame
    F : ndarray, shape (n, n)

    Returns
    -------
    x_new : ndarray, shape (..., n)
    innovation : ndarray, shape (...)   ``z - x_pred[0]``, NaN where missing
    """
    xp = x @ F.T  # (E1) prediction
    innovation = np.asarray(z, dtype=float) - xp[..., 0]  # (eq. 1) scalar innovation Z - h F x
    present = np.isfinite(innovation)
    x_new = xp + K * np.where(present, innovation, 0.0)[..., None]
    return x_new, innovation


def scheduled_filter(z, gains, x0=None) -> np.ndarray:
    """Run an alpha-beta(-gamma) filter with given gains along the time axis.

    Parameters
    ----------
    z : array_like, shape (..., T)
        Measurements in elements; NaN = missing (zero-gain prediction, (E1)).
    gains : array_like, shape (T, order+1) or (..., T, order+1)
        Gains per frame, e.g. ``gain_schedule(order, k_bound, T)``.
    x0 : array_like, shape (..., order+1), optional
        State before the first frame; default zeros.

    Returns
    -------
    ndarray, shape (..., T, order+1)
        Filtered states.
    """
    z = np.asarray(z, dtype=float)
    G = np.asarray(gains, dtype=float)
    order = _order_of(G)
    n = order + 1
    T = z.shape[-1]
    if G.shape[-2] != T:
        raise ValueError(f"gains cover {G.shape[-2]} frames but z has {T}")
    F = taylor_transition(order)
    batch = np.broadcast_shapes(z.shape[:-1], G.shape[:-2])
    x = np.zeros(batch + (n,)) if x0 is None else np.broadcast_to(np.asarray(x0, float), batch + (n,)).copy()
    out = np.empty(batch + (T, n))
    for t in range(T):
        x, _ = filter_step(x, z[..., t], G[..., t, :], F)
        out[..., t, :] = x
    return out


class GainScheduleFilter(SequentialFilter):
    """An alpha-beta(-gamma) filter with a gain per frame (eq. (1)) in the one filter interface
    (:class:`tvtrack.filters.interface.SequentialFilter`), carrying its noise-driven error covariance.

    The state is the polynomial (position, velocity, ...) of :func:`taylor_transition`; the measurement is the
    position (m = 1). :meth:`run` gives the states of :func:`scheduled_filter` and the covariances of
    :func:`error_covariance_sequence` when started from the prior of frame 0 (``x0 = F x_before``,
    ``P0 = F P_before F^T``).

    Parameters
    ----------
    gains : array_like, shape (T, order+1) or (..., T, order+1)
        Gains per frame (a zero row coasts), e.g. ``gain_schedule(order, k_bound, T)``.
    sigma_eps : float
        Measurement noise RMS (the covariance's unit squared).
    """

    def __init__(self, gains, sigma_eps: float = 1.0):
        self.gains = np.asarray(gains, dtype=float)
        self.order = _order_of(self.gains)
        self.F = taylor_transition(self.order)
        self.h = observation_row(self.order)
        self.sigma_eps = float(sigma_eps)

    def predict(self, x, P, k: int = 0):
        """``x <- F x``, ``P <- F P F^T`` (no process noise: the dynamic error is the bias of the schedule)."""
        return np.einsum("ij,...j->...i", self.F, x), self.F @ P @ self.F.T

    def update(self, x, P, z, k: int = 0, mask=None):
        """Correct with the gains of frame ``k``: ``x + K (z - x[0])``; ``P`` by the Joseph form with
        ``R = sigma_eps^2``. ``z`` (..., 1); returns ``x``, ``P``, the innovation (..., 1) and ``S`` (..., 1, 1)."""
        K = self.gains[..., k, :]
        nu = np.asarray(z, dtype=float) - x[..., :1]
        x_new = x + K * nu
        P_new = joseph_covariance(P, K[..., :, None], self.h[None, :], self.sigma_eps**2)
        S = (P[..., 0, 0] + self.sigma_eps**2)[..., None, None]
        if mask is not None:
            m = np.asarray(mask, dtype=bool)
            x_new = np.where(m[..., None], x_new, x)
            P_new = np.where(m[..., None, None], P_new, P)
        return x_new, P_new, nu, S
