"""The classical tracker the paper's introduction criticises: a per-scan centroid discriminator followed by a
fixed-gain smoother (a study beyond the paper)."""

from __future__ import annotations

import numpy as np

from .model import DissectorScan

__all__ = ["scan_centroids", "fixed_gain_track", "tune_fixed_gain"]


def scan_centroids(scan: DissectorScan, y, start=None):
    """Classical time-of-arrival discriminator: the centroid of each scan's samples (a study beyond the paper).

    ``z_j = sum_k u_k Y_k / sum_k Y_k`` over the ``round(1/dt)`` samples of scan ``j`` (``u_k = tau_k - tau_c``,
    the pulse offset the sample sees for ``x = 0``), divided by the discriminator slope at ``x = 0``,
    ``sum u^2 S / (sigma_t^2 sum S)`` (the scan truncates the pulse's tails, which pulls the raw centroid
    toward the centre: slope 0.71 for the paper's pulse). It uses no model of the noise.

    Parameters
    ----------
    y : ndarray, shape (n_trials, n_steps + 1)   samples from :func:`simulate` (column 0 NaN)
    start : None or ndarray (n_trials,)
        Each run's sweep phase at switch-on (T; None: 0). A block of ``round(1/dt)`` consecutive samples sees every
        phase of the sweep once, wherever it starts, so it holds the pulse once; ``u_k`` is each sample's own phase.

    Returns
    -------
    ndarray, shape (n_trials, n_scans)   one measurement per block of a scan's length, referred to the block's end
    """
    per_scan = int(round(1.0 / scan.dt))
    n_scans = (y.shape[1] - 1) // per_scan
    k = np.arange(1, 1 + n_scans * per_scan)
    phi = np.zeros((y.shape[0], 1)) if start is None else np.asarray(start, dtype=float)[:, None]
    u = scan.offset(0.0, k, phi).reshape(y.shape[0], n_scans, per_scan)
    blocks = y[:, 1 : 1 + n_scans * per_scan].reshape(y.shape[0], n_scans, per_scan)
    s0 = scan.shape(0.0, k[:per_scan], phi)
    slope = np.sum(u[:, 0] ** 2 * s0, axis=1) / (scan.pulse_sigma**2 * np.sum(s0, axis=1))
    return (blocks * u).sum(axis=2) / blocks.sum(axis=2) / slope[:, None]


def fixed_gain_track(z, transition: float, gain: float):
    """Fixed-gain (alpha) smoother of scan measurements: ``x_j = f x_{j-1} + g (z_j - f x_{j-1})``, ``x_0 = 0``.

    Parameters
    ----------
    z : ndarray, shape (n_trials, n_scans)   measurements
    transition : float                        ``f`` per scan (``exp(-alpha_0 T)``)
    gain : float                              ``g`` in (0, 1]

    Returns
    -------
    ndarray, shape (n_trials, n_scans)   estimates at the scan ends
    """
    if not 0 < gain <= 1:
        raise ValueError(f"parameter 'gain' = {gain!r}; it must be in (0, 1]")
    out = np.empty_like(z)
    x = np.zeros(z.shape[0])
    for j in range(z.shape[1]):
        x = transition * x + gain * (z[:, j] - transition * x)
        out[:, j] = x
    return out


def tune_fixed_gain(z, truth, transition: float, gains, mask):
    """The gain of :func:`fixed_gain_track` with the least mean squared error over the scans in ``mask``,
    on training runs (``z``, ``truth`` at the scan ends, shape (n_trials, n_scans)); the least-squares
    tuning the EKF gets for free from its model."""
    errors = [np.nanmean((fixed_gain_track(z, transition, g) - truth)[:, mask] ** 2) for g in gains]
    return float(np.asarray(gains)[int(np.nanargmin(errors))])
