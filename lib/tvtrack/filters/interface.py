"""The one filter interface of the library (the filterpy / Stone Soup lesson): a ``predict`` / ``update`` pair
and a batched ``run`` over a sequence with any leading trial axes.

A filter that implements :class:`SequentialFilter` writes only its two steps; :meth:`SequentialFilter.run` is the
one loop over time: ``(x0, P0)`` is the prior for time 0, the first step is an update with ``zs[..., 0, :]``,
then predict / update alternate; a measurement row holding a NaN is absent (the filter coasts: the prior is
kept). The core's :class:`~tvtrack.filters.kalman.KalmanFilter`,
:class:`~tvtrack.filters.ekf.ExtendedKalmanFilter` and :class:`~tvtrack.filters.alphabeta.GainScheduleFilter`
implement it.

Shapes: state ``x`` (..., n), covariance ``P`` (..., n, n), measurement ``z`` (..., m); ``k`` is the time index
(0-based) of the step, for filters whose model changes with time.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np

__all__ = ["FilterOutput", "SequentialFilter"]


@dataclass(frozen=True)
class FilterOutput:
    """Filter history; time is the axis after the batch axes.

    Attributes
    ----------
    x_prior, x : ndarray, shape (..., T, n)   predicted and updated states
    P_prior, P : ndarray, shape (..., T, n, n)
    innovation : ndarray, shape (..., T, m)   NaN where the measurement was absent
    S : ndarray, shape (..., T, m, m)          innovation covariance
    nis : ndarray, shape (..., T)             normalised innovation squared (NaN where absent)
    """

    x_prior: np.ndarray
    P_prior: np.ndarray
    x: np.ndarray
    P: np.ndarray
    innovation: np.ndarray
    S: np.ndarray
    nis: np.ndarray


class SequentialFilter(ABC):
    """A recursive filter: :meth:`predict` and :meth:`update`, and the batched :meth:`run` built on them."""

    @abstractmethod
    def predict(self, x: np.ndarray, P: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Time update from step ``k - 1`` to step ``k``: returns the prior ``x`` (..., n) and ``P`` (..., n, n)."""

    @abstractmethod
    def update(
        self, x: np.ndarray, P: np.ndarray, z: np.ndarray, k: int, mask: np.ndarray | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Measurement update at step ``k`` with ``z`` (..., m), finite where ``mask`` (...) is True (all if None;
        elsewhere the prior is kept). Returns ``x``, ``P``, the innovation (..., m) and its covariance ``S``
        (..., m, m)."""

    def run(self, zs, x0, P0) -> FilterOutput:
        """Filter measurements ``zs`` (..., T, m) from the prior ``(x0, P0)`` of time 0 (broadcast to the batch
        axes ``zs.shape[:-2]``); NaN rows are absent (the filter coasts). Returns the whole history."""
        zs = np.asarray(zs, dtype=float)
        if zs.ndim < 2:
            raise ValueError(f"parameter 'zs' has shape {zs.shape}; it must be (..., T, m)")
        T, m, batch = zs.shape[-2], zs.shape[-1], zs.shape[:-2]
        P = np.asarray(P0, dtype=float)
        n = P.shape[-1]
        x = np.broadcast_to(np.asarray(x0, dtype=float), batch + (n,)).copy()
        P = np.broadcast_to(P, batch + (n, n)).copy()
        shapes = {"x_prior": (n,), "P_prior": (n, n), "x": (n,), "P": (n, n), "innovation": (m,), "S": (m, m)}
        out = {key: np.empty((T,) + batch + s) for key, s in shapes.items()}  # time-major while filling
        zs_t = np.moveaxis(zs, -2, 0)
        for k in range(T):
            if k > 0:
                x, P = self.predict(x, P, k)
            out["x_prior"][k], out["P_prior"][k] = x, P
            z = zs_t[k]
            present = np.all(np.isfinite(z), axis=-1)
            if present.all():  # nothing to mask (the fast path)
                x, P, nu, S = self.update(x, P, z, k)
            else:
                x, P, nu, S = self.update(x, P, np.where(present[..., None], z, 0.0), k, present)
                nu = np.where(present[..., None], nu, np.nan)
            out["innovation"][k], out["S"][k], out["x"][k], out["P"][k] = nu, S, x, P
        hist = {key: np.moveaxis(v, 0, len(batch)) for key, v in out.items()}
        nu = hist["innovation"]
        if m == 1:  # scalar measurement: nu^2 / S, no solve
            nis = nu[..., 0] ** 2 / hist["S"][..., 0, 0]
        else:
            nis = np.einsum("...i,...i->...", nu, np.linalg.solve(hist["S"], nu[..., None])[..., 0])
        return FilterOutput(**hist, nis=nis)
