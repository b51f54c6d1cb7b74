"""Loss-of-lock detection for gate trackers, with the criterion as a parameter.

The paper (Yukhno 2025) speaks only of "loss of tracking or switching to a stationary source";
the criteria here are this project's choice:

- ``"window"`` (default): loss at the first frame where more than ``fraction`` of the last
  ``window`` frames had a miss distance above ``threshold``. Robust to a gate captured by an
  interferer on the marker's circle, which the true marker crosses once per revolution.
- ``"consecutive"``: loss after ``window`` consecutive frames above ``threshold``.

A gate whose centre leaves the image is a loss at once. Which criteria a loss meets (capture by one
interferer, drift among several, a lost rotation) is :func:`loss_criteria`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["LossCriterion", "first_loss", "CRITERIA", "loss_criteria"]

KINDS = ("window", "consecutive")


@dataclass(frozen=True)
class LossCriterion:
    """A loss-of-lock rule.

    Attributes
    ----------
    threshold : float
        Miss distance (px) counted as "off the marker", e.g. the gate half-size 12 px.
    window : int
        Frames in the sliding window (or the run length for ``"consecutive"``), >= 1.
    fraction : float
        Share of the window above threshold that declares loss, in [0, 1).
    kind : {"window", "consecutive"}
    """

    threshold: float
    window: int
    fraction: float = 0.5
    kind: str = "window"

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"parameter 'kind' = {self.kind!r}; it must be one of {KINDS}")
        if not self.threshold > 0:
            raise ValueError(f"parameter 'threshold' = {self.threshold}; it must be > 0")
        if not (isinstance(self.window, (int, np.integer)) and self.window >= 1):
            raise ValueError(f"parameter 'window' = {self.window}; it must be an integer >= 1")
        if not 0 <= self.fraction < 1:
            raise ValueError(f"parameter 'fraction' = {self.fraction}; it must be in [0, 1)")


def first_loss(miss, criterion: LossCriterion, inside=None) -> np.ndarray:
    """Frame index of the first loss of lock per trial, ``-1`` where lock was kept.

    Parameters
    ----------
    miss : ndarray, shape (n, T)
        Marker miss distance per frame (px).
    criterion : LossCriterion
    inside : ndarray of bool, shape (n, T), optional
        Gate centre inside the image; a frame outside is a loss.

    Returns
    -------
    ndarray of int, shape (n,)
    """
    off = np.asarray(miss) > criterion.threshold
    n, T = off.shape
    w = criterion.window
    if criterion.kind == "window":
        csum = np.concatenate([np.zeros((n, 1), np.int64), np.cumsum(off, axis=1)], axis=1)
        count = csum[:, 1:] - csum[:, np.maximum(np.arange(T) + 1 - w, 0)]
        lost = count > criterion.fraction * w
    else:
        # run length of consecutive "off" frames ending at each frame
        last_on = np.maximum.accumulate(np.where(off, -1, np.arange(T)), axis=1)
        lost = off & ((np.arange(T) - last_on) >= w)
    if inside is not None:
        lost |= ~np.asarray(inside, bool)
    any_lost = lost.any(axis=1)
    return np.where(any_lost, lost.argmax(axis=1), -1)


CRITERIA = ("capture", "drift among several", "frequency")


def loss_criteria(
    loss_frame,
    gate,
    interferers,
    miss,
    omega_error,
    window: int,
    radius: float,
    fraction: float = 0.5,
    omega_tol: float = 0.2,
) -> np.ndarray:
    """Which loss criteria each loss meets, each judged on its own (no order between them).

    Over the ``window`` frames that end at the loss frame, a frame is *near* an interferer when the gate is within
    ``radius`` of it while more than ``radius`` from the marker (a gate following a rotating marker passes over
    interferers on the marker's circle without leaving it). Columns (:data:`CRITERIA`): *capture*, near one
    interferer for more than ``fraction`` of the window; *drift among several*, near at least two different
    interferers; *frequency*, ``|omega_error| > omega_tol`` for more than ``fraction`` of the window (never for a
    static marker, whose ``omega_error`` is NaN). A loss may meet several criteria or none (a *drift*).

    Returns
    -------
    ndarray of bool, shape (n, 3)
        All False for runs that kept lock.
    """
    loss = np.asarray(loss_frame)
    gate, q = np.asarray(gate), np.asarray(interferers)
    n = gate.shape[0]
    frames = np.clip(loss[:, None] - np.arange(window)[::-1], 0, None)  # (n, window)
    rows = np.arange(n)[:, None]
    out = np.zeros((n, 3), bool)
    with np.errstate(invalid="ignore"):
        out[:, 2] = (np.abs(np.asarray(omega_error)[rows, frames]) > omega_tol).mean(axis=1) > fraction
    if q.shape[1]:
        off_marker = np.asarray(miss)[rows, frames] > radius  # (n, window)
        near = (np.linalg.norm(gate[rows, frames][:, :, None, :] - q[:, None, :, :], axis=-1) < radius) & off_marker[
            :, :, None
        ]
        out[:, 0] = (near.mean(axis=1) > fraction).any(axis=1)
        out[:, 1] = near.any(axis=1).sum(axis=1) >= 2
    out[loss < 0] = False
    return out
