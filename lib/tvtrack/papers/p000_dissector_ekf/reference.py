"""Bayesian references for paper 000: a grid (point-mass) filter with the likelihood of one sample, the
Fisher information of a sample, the posterior Cramer-Rao bound, and one scan's Cramer-Rao bound.

All of them model a sample as the pulse and noise intensity at one instant (the sample's phase) with noise
variance ``N / dt``: exact for point samples; for integrate-and-dump samples they are the midpoint rule
(the pulse and intensity at the interval centre), whose error is second order in ``dt``.
"""

from __future__ import annotations

import numpy as np

from ...bounds.pcrlb import expected_over_gaussian, pcrlb_recursion
from ...filters.grid import GridFilter
from .model import DissectorScan, GaussMarkovMessage

__all__ = ["grid_filter", "fisher_information", "pcrlb_variance", "scan_crlb"]


def grid_filter(
    scan: DissectorScan, message: GaussMarkovMessage, half_width: float = 0.5, n_points: int = 401, start=0.0
) -> GridFilter:
    """Point-mass Bayesian filter of ``X1`` with the likelihood of one sample of eq. (5) (near-optimal reference).

    The likelihood includes the signal-dependent variance, ``log p(z | x) = -(z - A S)^2 / (2 R) - log(R) / 2``
    with ``R = N(t_k) / dt``; the transition is the message's exact discretisation. The filter is the exact
    posterior (up to the grid) for point samples; for integrate-and-dump samples its likelihood is the midpoint
    rule (the message held at the interval centre), so it is near-optimal, not exact.

    Parameters
    ----------
    half_width : float   the grid covers ``[-half_width, half_width]`` (units of ``T``)
    n_points : int       number of grid nodes
    start : float or ndarray (n_trials,)   the sweep's phase at switch-on of each run it filters (T)

    Returns
    -------
    GridFilter  whose ``run(y, 0.0, sigma_1**2)`` filters samples ``y`` (n_trials, K) from :func:`simulate`
    """
    f, q = message.exact(scan.dt)
    nodes = np.linspace(-half_width, half_width, n_points)

    phi = np.asarray(start, dtype=float)[..., None]  # (n_trials, 1) against the nodes

    def loglik(z, k):
        var = scan.sample_variance(nodes, k, None, phi)
        return -0.5 * (z[:, None] - scan.amplitude * scan.shape(nodes, k, phi)) ** 2 / var - 0.5 * np.log(var)

    return GridFilter(-half_width, half_width, n_points, f, q, loglik)


def fisher_information(scan: DissectorScan, x, k, start=0.0):
    """Fisher information about ``x`` in one sample ``Y(k)`` (eq. (5)), mean and variance both
    depending on ``x``:  ``J = (A S')^2 / R + R'^2 / (2 R^2)``, ``R = N(t_k)/dt``; the sweep at phase ``start``
    (T) at switch-on.

    Returns
    -------
    total, mean_part : ndarrays broadcast from ``x`` and ``k`` (units of ``1/T^2``)
    """
    ds = scan.shape_derivative(x, k, start)
    r = scan.sample_variance(x, k, None, start)
    dr = scan.n0 * scan.signal_noise_ratio * ds / scan.dt
    mean_part = (scan.amplitude * ds) ** 2 / r
    return mean_part + 0.5 * (dr / r) ** 2, mean_part


def pcrlb_variance(scan: DissectorScan, message: GaussMarkovMessage, n_steps: int, score_at: str = "sample", start=0.0):
    """Posterior Cramer-Rao bound on the mean-square error of ``X1`` at every step ``k = 0..n_steps``.

    The model of point samples (exact message discretisation, stationary prior ``N(0, sigma_1^2)``, samples
    of eq. (5) from ``k = 1``; for integrated samples the midpoint rule, the sample at its interval centre); the
    per-sample information :func:`fisher_information` (mean and signal-dependent variance) is averaged over the prior
    of ``X1`` by Gauss-Hermite quadrature.

    ``score_at``: ``"sample"`` bounds the error at the sample's own time (a point sample's instant, an integrated
    sample's interval centre); ``"interval_end"`` bounds it half a step later, at the end of an integrated sample's
    interval, where the filtering error (E9) is scored: the bound at the centre propagated by the message over
    ``dt / 2`` with no new datum, ``f^2 B + q`` (the exact PCRLB prediction step of linear dynamics), so that the
    bound refers to the same time as the errors it is compared with.

    ``start``: the sweep's phase at switch-on (T), a number or an array of phases; with an array the bound is the
    mean of each phase's bound (the bound on the ensemble's mean square error when each run's phase, known to its
    filter, is drawn from those phases: e.g. a midpoint rule over [0, T) for a uniform phase).

    Returns
    -------
    ndarray, shape (n_steps + 1,)   bound on ``E[(X1 - X1_hat)^2]`` (units of ``T^2``)
    """
    if score_at not in ("sample", "interval_end"):
        raise ValueError(f"parameter 'score_at' = {score_at!r}; it must be 'sample' or 'interval_end'")
    f, q = message.exact(scan.dt)
    kk = np.arange(n_steps + 1)
    bounds = []
    for phi in np.atleast_1d(np.asarray(start, dtype=float)):
        jz = expected_over_gaussian(
            lambda s, phi=phi: fisher_information(scan, s, kk, phi)[0],
            np.zeros(kk.size),
            np.full(kk.size, message.sigma**2),
        )
        jz[0] = 0.0  # no sample at k = 0
        bounds.append(pcrlb_recursion([[f]], [[q]], [[1.0 / message.sigma**2]], jz[:, None, None])[:, 0, 0])
    bound = np.mean(bounds, axis=0)
    if score_at == "sample":
        return bound
    fh, qh = message.exact(scan.dt / 2)
    return fh**2 * bound + qh


def scan_crlb(scan: DissectorScan, start=0.0) -> float:
    """Cramer-Rao bound of one scan's measurement of ``X1`` at ``x = 0`` (no dynamics, no prior).

    ``1 / sum_k J(0, k)`` over the ``round(1/dt)`` samples of the scan (units of ``T^2``), the sweep at phase
    ``start`` (T) at switch-on: the samples sit at the scan phases ``(k - 1/2) dt + start``, so the bound depends on
    ``start`` modulo ``dt`` (the scan truncates the pulse's tails). With an array of phases, the mean of each one's
    bound (e.g. a midpoint rule over the uniform law of the runs' phases).
    """
    kk = np.arange(1, int(round(1.0 / scan.dt)) + 1)
    bounds = [1.0 / fisher_information(scan, 0.0, kk, phi)[0].sum() for phi in np.atleast_1d(start)]
    return float(np.mean(bounds))
