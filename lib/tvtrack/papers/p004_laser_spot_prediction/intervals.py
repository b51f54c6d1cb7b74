"""The intervals of paper 004's study: one value per simulated path, each path one trial (the paths are the
independent units; the frames of one path are not)."""

from __future__ import annotations

import numpy as np

from ...estimate import Estimate
from ...montecarlo import mean_ci, ratio_ci, rms_ci

__all__ = ["root_mean_ci", "ratio_of_means_ci", "mean_ci_t"]


def root_mean_ci(mean_squares) -> Estimate:
    """RMS of per-path mean squares ``m`` (px^2), px: :func:`tvtrack.montecarlo.rms_ci` with each path one
    trial (the square root of the bootstrap-t interval of the mean square; its measured coverage in
    ``method``)."""
    return rms_ci(np.sqrt(np.asarray(mean_squares, dtype=float))[:, None])


def ratio_of_means_ci(numerator, denominator) -> Estimate:
    """Paired ratio of per-path means (the same paths under two methods):
    :func:`tvtrack.montecarlo.ratio_ci` (expanded percentile bootstrap over paths; coverage in ``method``)."""
    return ratio_ci(numerator, denominator, paired=True)


def mean_ci_t(samples) -> Estimate:
    """Mean of one value per path: :func:`tvtrack.montecarlo.mean_ci`, bootstrap-t (coverage in ``method``)."""
    return mean_ci(samples, method="bootstrap-t")
