"""Posterior Cramer-Rao bound (Tichavsky, Muravchik & Nehorai 1998) for linear-Gaussian dynamics
with a nonlinear measurement whose noise variance may depend on the state.

For ``x(k+1) = F x(k) + w(k)``, ``w ~ N(0, Q)``, and measurements ``z(k) ~ N(mu(x, k), R(x, k))``,
the Bayesian information matrix obeys

    J(k+1) = (Q + F J(k)^-1 F^T)^-1 + E[ J_z(x(k+1), k+1) ]                       (TMN eq. 21)

and ``E[(x_hat - x)(x_hat - x)^T] >= J(k)^-1`` for every estimator. For a scalar Gaussian
measurement the Fisher information is ``mu'^2 / R + R'^2 / (2 R^2)``; the second term is what a
state-dependent (signal-dependent) variance carries. In the linear case (``mu = H x``, constant
``R``) the recursion is the Kalman information filter and ``J(k)^-1`` equals the Kalman covariance.
"""

from __future__ import annotations

import numpy as np

__all__ = ["expected_over_gaussian", "pcrlb_recursion"]


def expected_over_gaussian(func, mean, var, order: int = 41):
    """``E[func(x)]`` for ``x ~ N(mean, var)`` by Gauss-Hermite quadrature.

    Parameters
    ----------
    func : callable mapping an array of abscissae (order, ...) to values of the same shape
    mean, var : array_like, shape (...)  (e.g. one entry per time step)
    order : int   number of nodes

    Returns
    -------
    ndarray, shape (...)
    """
    if order < 1:
        raise ValueError(f"parameter 'order' = {order}; it must be >= 1")
    nodes, weights = np.polynomial.hermite_e.hermegauss(order)  # weight exp(-x^2/2)
    weights = weights / weights.sum()
    mean = np.asarray(mean, dtype=float)
    std = np.sqrt(np.asarray(var, dtype=float))
    shape = (order,) + (1,) * np.broadcast(mean, std).ndim
    x = mean + std * nodes.reshape(shape)
    return np.tensordot(weights, func(x), axes=(0, 0))


def pcrlb_recursion(F, Q, J0, measurement_info):
    """The PCRLB information recursion.

    Parameters
    ----------
    F : ndarray, shape (n, n)         transition per step
    Q : ndarray, shape (n, n)         process-noise covariance per step (positive definite)
    J0 : ndarray, shape (n, n)        prior information at time 0 (inverse prior covariance)
    measurement_info : ndarray, shape (T, n, n)
        Expected measurement information ``E[J_z(x(k), k)]`` at each time ``k = 0..T-1``
        (zero where there is no measurement).

    Returns
    -------
    bound : ndarray, shape (T, n, n)
        ``J(k)^-1``, the lower bound on the mean-square error matrix at time ``k``.
    """
    F = np.atleast_2d(np.asarray(F, dtype=float))
    Q = np.atleast_2d(np.asarray(Q, dtype=float))
    Jz = np.asarray(measurement_info, dtype=float)
    n = F.shape[0]
    if Q.shape != (n, n) or np.shape(J0) != (n, n) or Jz.ndim != 3 or Jz.shape[1:] != (n, n):
        raise ValueError(
            f"inconsistent shapes F{F.shape} Q{Q.shape} J0{np.shape(J0)} "
            f"measurement_info{Jz.shape}; expected (n,n), (n,n), (n,n), (T,n,n)"
        )
    if np.any(np.linalg.eigvalsh(Q) <= 0):
        raise ValueError("parameter 'Q' must be positive definite")
    bound = np.empty_like(Jz)
    J = np.asarray(J0, dtype=float) + Jz[0]
    bound[0] = np.linalg.inv(J)
    for k in range(1, Jz.shape[0]):
        prior_cov = F @ bound[k - 1] @ F.T + Q
        J = np.linalg.inv(prior_cov) + Jz[k]
        bound[k] = np.linalg.inv(J)
        bound[k] = 0.5 * (bound[k] + bound[k].T)
    return bound
