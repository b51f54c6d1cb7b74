"""A linear Kalman filter batched over leading axes (trials, channels).

Shapes: state ``x`` (..., n), covariance ``P`` (..., n, n), measurement ``z`` (..., m);
model matrices ``F`` (n, n), ``H`` (m, n), ``Q`` (n, n), ``R`` (m, m), or with leading batch
axes that broadcast. Covariance updates use the Joseph form and are symmetrised, so ``P``
stays symmetric positive definite for any gain.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .interface import FilterOutput, SequentialFilter

__all__ = ["joseph_covariance", "kf_predict", "kf_update", "KalmanFilter", "KalmanOutput"]


def _sym(P: np.ndarray) -> np.ndarray:
    return 0.5 * (P + np.swapaxes(P, -1, -2))


def joseph_covariance(P, K, H, R):
    """The Joseph-form covariance update, for any gain: the one used by every filter in the library.

    ``P+ = (I - K H) P (I - K H)^T + K R K^T``, symmetrised. Valid for a suboptimal gain (bounded,
    floored or fixed gains of the alpha-beta and growing-memory filters), not only the Kalman gain.
    ``I - K H`` is formed first, so a huge prior (a diffuse start, 1e12) loses no digits: the expanded
    form ``P - K b^T - b K^T + S K K^T`` cancels to zero there (``tests/test_filters_core.py``).

    Parameters
    ----------
    P : ndarray, shape (..., n, n)      prior covariance
    K : ndarray, shape (..., n, m)      gain (any)
    H : ndarray, shape (m, n) or (..., m, n)
    R : float or ndarray, shape (m, m) or (..., m, m)   measurement-noise covariance

    Returns
    -------
    ndarray, shape (..., n, n)
    """
    P = np.asarray(P, dtype=float)
    K = np.asarray(K, dtype=float)
    H = np.asarray(H, dtype=float)
    R = np.asarray(R, dtype=float)
    KRK = K @ (R if R.ndim >= 2 else R[..., None, None]) @ np.swapaxes(K, -1, -2)
    IKH = np.eye(P.shape[-1]) - K @ H
    return _sym(IKH @ P @ np.swapaxes(IKH, -1, -2) + KRK)


def kf_predict(x, P, F, Q):
    """Time update: ``x <- F x``, ``P <- F P F^T + Q``.

    Returns
    -------
    x, P : ndarray, shapes (..., n) and (..., n, n)
    """
    F = np.asarray(F, dtype=float)
    x = np.einsum("...ij,...j->...i", F, x)
    P = _sym(F @ P @ np.swapaxes(F, -1, -2) + Q)
    return x, P


def kf_update(x, P, z, H, R, mask=None):
    """Measurement update in Joseph form.

    Parameters
    ----------
    x : ndarray, shape (..., n)
    P : ndarray, shape (..., n, n)
    z : ndarray, shape (..., m)
    H : ndarray, shape (m, n) or (..., m, n)
    R : ndarray, shape (m, m) or (..., m, m)
    mask : ndarray of bool, shape (...), optional
        Where False, the measurement is absent and the prior is kept.

    Returns
    -------
    x, P : updated state and covariance
    innovation : ndarray, shape (..., m)  (``z - H x`` before the update)
    S : ndarray, shape (..., m, m)        innovation covariance ``H P H^T + R``
    """
    H = np.asarray(H, dtype=float)
    Ht = np.swapaxes(H, -1, -2)
    innovation = np.asarray(z, dtype=float) - np.einsum("...ij,...j->...i", H, x)
    S = _sym(H @ P @ Ht + R)
    K = np.swapaxes(np.linalg.solve(S, H @ np.swapaxes(P, -1, -2)), -1, -2)  # P H^T S^-1
    x_new = x + np.einsum("...ij,...j->...i", K, innovation)
    P_new = joseph_covariance(P, K, H, R)
    if mask is not None:
        m = np.asarray(mask, dtype=bool)
        x_new = np.where(m[..., None], x_new, x)
        P_new = np.where(m[..., None, None], P_new, np.broadcast_to(P, P_new.shape))
    return x_new, P_new, innovation, S


#: The history a filter's ``run`` returns (:class:`tvtrack.filters.interface.FilterOutput`).
KalmanOutput = FilterOutput


@dataclass
class KalmanFilter(SequentialFilter):
    """Time-invariant linear Kalman filter, run over a whole batch of sequences at once.

    Parameters
    ----------
    F : ndarray, shape (n, n)   state transition per step
    H : ndarray, shape (m, n)   observation matrix
    Q : ndarray, shape (n, n)   process noise covariance per step
    R : ndarray, shape (m, m)   measurement noise covariance
    """

    F: np.ndarray
    H: np.ndarray
    Q: np.ndarray
    R: np.ndarray

    def __post_init__(self):
        self.F, self.H, self.Q, self.R = (np.asarray(a, dtype=float) for a in (self.F, self.H, self.Q, self.R))
        n, m = self.F.shape[-1], self.H.shape[-2]
        if (
            self.F.shape[-2:] != (n, n)
            or self.H.shape[-1] != n
            or self.Q.shape[-2:] != (n, n)
            or self.R.shape[-2:] != (m, m)
        ):
            raise ValueError(f"inconsistent shapes F{self.F.shape} H{self.H.shape} Q{self.Q.shape} R{self.R.shape}")

    def predict(self, x, P, k: int = 0):
        """``x <- F x``, ``P <- F P F^T + Q`` (:func:`kf_predict`); ``k`` is unused (a time-invariant model)."""
        return kf_predict(x, P, self.F, self.Q)

    def update(self, x, P, z, k: int = 0, mask=None):
        """The Joseph-form update (:func:`kf_update`); ``k`` is unused."""
        return kf_update(x, P, z, self.H, self.R, mask)
