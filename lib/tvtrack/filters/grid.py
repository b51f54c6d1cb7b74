"""Point-mass (grid) Bayesian filter for a scalar Gauss-Markov state, batched over trials.

The posterior density is held on a fixed uniform grid. Prediction convolves it with the Gaussian
transition ``x(k+1) | x(k) ~ N(f x(k), q)`` (a banded sparse matrix); the update multiplies by the
likelihood of the measurement (any model, given as a log-likelihood on the grid) and renormalises.
The posterior mean is the minimum-mean-square-error estimate up to the grid's resolution, so the
filter is a near-optimal reference for the EKFs.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from scipy import sparse, stats

__all__ = ["GridFilter", "GridOutput"]


@dataclass(frozen=True)
class GridOutput:
    """Posterior summaries; shapes (n_trials, T)."""

    mean: np.ndarray
    var: np.ndarray


@dataclass
class GridFilter:
    """Grid filter on ``[low, high]`` with ``n_points`` nodes.

    Parameters
    ----------
    low, high : float       grid limits (state units)
    n_points : int          number of nodes (>= 3)
    f, q : float            transition ``x(k+1) = f x(k) + w``, ``w ~ N(0, q)``, ``q > 0``
    log_likelihood : callable ``(z (n_trials,), k) -> (n_trials, n_points)``
        Log-likelihood of measurement ``z`` at time ``k`` at every grid node (additive constants
        do not matter); it receives the grid through :attr:`nodes`.
    band_sigmas : float     the transition kernel is cut at this many standard deviations
    """

    low: float
    high: float
    n_points: int
    f: float
    q: float
    log_likelihood: Callable
    band_sigmas: float = 6.0
    nodes: np.ndarray = field(init=False)
    _transition: sparse.csr_matrix = field(init=False, repr=False)

    def __post_init__(self):
        if not (np.isfinite(self.low) and np.isfinite(self.high) and self.high > self.low):
            raise ValueError(f"parameters 'low' = {self.low}, 'high' = {self.high}; need low < high, both finite")
        if int(self.n_points) != self.n_points or self.n_points < 3:
            raise ValueError(f"parameter 'n_points' = {self.n_points!r}; it must be an integer >= 3")
        if not (np.isfinite(self.q) and self.q > 0):
            raise ValueError(f"parameter 'q' = {self.q!r}; it must be > 0")
        self.nodes = np.linspace(self.low, self.high, int(self.n_points))
        dx = self.nodes[1] - self.nodes[0]
        half = int(np.ceil(self.band_sigmas * np.sqrt(self.q) / dx)) + 1
        # column j: density of x(k+1) on the grid given x(k) = node j (cell-integrated, renormalised)
        rows, cols, vals = [], [], []
        edges_half = 0.5 * dx
        sd = np.sqrt(self.q)
        for j, xj in enumerate(self.nodes):
            centre = self.f * xj
            i0 = max(int(np.floor((centre - self.low) / dx)) - half, 0)
            i1 = min(int(np.ceil((centre - self.low) / dx)) + half, self.nodes.size - 1)
            idx = np.arange(i0, i1 + 1)
            mass = stats.norm.cdf((self.nodes[idx] + edges_half - centre) / sd) - stats.norm.cdf(
                (self.nodes[idx] - edges_half - centre) / sd
            )
            if mass.sum() <= 0:
                continue
            rows.append(idx)
            cols.append(np.full(idx.size, j))
            vals.append(mass / mass.sum())
        self._transition = sparse.csr_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
            shape=(self.nodes.size, self.nodes.size),
        )

    def run(self, zs, prior_mean: float, prior_var: float) -> GridOutput:
        """Filter measurements ``zs`` (n_trials, T); a NaN column means no measurement at that step.

        The prior ``N(prior_mean, prior_var)`` is the density at time 0 (before ``zs[:, 0]``);
        prediction happens between consecutive steps.
        """
        zs = np.asarray(zs, dtype=float)
        if zs.ndim != 2:
            raise ValueError(f"parameter 'zs' has shape {zs.shape}; it must be (n_trials, T)")
        if not prior_var > 0:
            raise ValueError(f"parameter 'prior_var' = {prior_var!r}; it must be > 0")
        n_trials, T = zs.shape
        # grid-major layout (n_points, n_trials): the sparse product then needs no copy
        p = stats.norm.pdf(self.nodes, prior_mean, np.sqrt(prior_var))
        p = np.repeat((p / p.sum())[:, None], n_trials, axis=1)
        mean = np.empty((n_trials, T))
        var = np.empty((n_trials, T))
        tiny = np.finfo(float).tiny
        for k in range(T):
            if k > 0:
                p = self._transition @ p  # prediction
            z = zs[:, k]
            if np.all(np.isfinite(z)):
                logw = np.log(np.maximum(p, tiny)) + self.log_likelihood(z, k).T  # Bayes update
                logw -= logw.max(axis=0)
                p = np.exp(logw)
                p /= p.sum(axis=0)
            m = self.nodes @ p
            mean[:, k] = m
            var[:, k] = (self.nodes**2) @ p - m**2
        return GridOutput(mean, np.maximum(var, 0.0))
