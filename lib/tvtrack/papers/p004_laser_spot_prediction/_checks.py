"""Argument checks shared by the predictors of paper 004 (:mod:`.predictors`, :mod:`.kalman_baselines`)."""

from __future__ import annotations

import numpy as np

__all__ = ["check_steps", "check_z"]


def check_steps(steps) -> int:
    """The forecast horizon as an int (frames ahead); ``ValueError`` naming ``steps`` unless an integer >= 1."""
    if not (isinstance(steps, (int, np.integer)) and steps >= 1):
        raise ValueError(f"parameter 'steps' = {steps!r}; it must be an integer >= 1 (frames ahead)")
    return int(steps)


def check_z(z) -> np.ndarray:
    """Measurements as a float array, time on the last axis (px); ``ValueError`` naming ``z`` unless that axis has
    at least 2 frames."""
    z = np.asarray(z, dtype=float)
    if z.ndim < 1 or z.shape[-1] < 2:
        raise ValueError(f"parameter 'z' has shape {z.shape}; it needs a time axis (last) of length >= 2")
    return z
