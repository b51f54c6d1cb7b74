"""Loss-of-lock detection for gate trackers, with the criterion as a parameter.

The paper (Yukhno 2025) speaks only of "loss of tracking or switching to a stationary source";
the criteria here follow the paper card (003, section 4.5):

- ``"window"`` (default): loss at the first frame where more than ``fraction`` of the last
  ``window`` frames had a miss distance above ``threshold``. Robust to a gate captured by an
  interferer on the marker's circle, which the true marker crosses once per revolution.
- ``"consecutive"``: loss after ``window`` consecutive frames above ``threshold``.

A gate whose centre leaves the image is a loss at once. A loss is tagged as a *capture* when,
over the window ending at the loss, the gate centre stayed within ``capture_radius`` of one
interferer for more than ``fraction`` of the frames.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..montecarlo import proportion_ci

__all__ = ["LossCriterion", "first_loss", "tag_capture", "loss_threshold", "losses_by_sir", "loss_curve"]

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


def tag_capture(gate, interferers, loss_frame, window: int, radius: float, fraction: float = 0.5) -> np.ndarray:
    """Whether each loss was a capture by a stationary interferer.

    Parameters
    ----------
    gate : ndarray, shape (n, T, 2)
        Gate centres (px).
    interferers : ndarray, shape (n, q, 2)
    loss_frame : ndarray of int, shape (n,)
        From :func:`first_loss` (-1 = no loss).
    window : int
        Frames before the loss that are examined.
    radius : float
        Capture radius (px), e.g. ``D / 2``.

    Returns
    -------
    ndarray of bool, shape (n,)
    """
    gate = np.asarray(gate)
    q = np.asarray(interferers)
    loss = np.asarray(loss_frame)
    n = gate.shape[0]
    if q.shape[1] == 0:
        return np.zeros(n, bool)
    frames = np.clip(loss[:, None] - np.arange(window)[::-1], 0, None)          # (n, window)
    seg = gate[np.arange(n)[:, None], frames]                                  # (n, window, 2)
    near = np.linalg.norm(seg[:, :, None, :] - q[:, None, :, :], axis=-1) < radius
    return (loss >= 0) & (near.mean(axis=1) > fraction).any(axis=1)


def loss_threshold(sir_values, losses) -> float:
    """Loss-free threshold on a grid: the smallest SIR such that it and every larger SIR of the
    grid had no loss; NaN if the largest SIR had losses.

    Parameters
    ----------
    sir_values : array_like, shape (m,)
        Grid of signal-to-interference ratios (any order).
    losses : array_like of int, shape (m,)
        Number of losses at each SIR.
    """
    s = np.asarray(sir_values, dtype=float)
    n = np.asarray(losses)
    order = np.argsort(s)[::-1]
    thr = float("nan")
    for i in order:
        if n[i] > 0:
            break
        thr = float(s[i])
    return thr


def losses_by_sir(loss_frame, sir, sir_values) -> np.ndarray:
    """Number of runs that lost lock at each SIR of a grid.

    Parameters
    ----------
    loss_frame : ndarray of int, shape (n,)
        First loss frame per run, -1 if none (:func:`first_loss`).
    sir : ndarray, shape (n,)
        Each run's SIR.
    sir_values : array_like, shape (m,)

    Returns
    -------
    ndarray of int, shape (m,)
    """
    lost = np.asarray(loss_frame) >= 0
    return np.array([lost[sir == s].sum() for s in sir_values])


def loss_curve(runs: dict, sir_values, criterion: LossCriterion, capture_radius: float) -> dict:
    """Loss-of-lock probability against SIR, with its threshold and the captures.

    Parameters
    ----------
    runs : dict
        ``sir`` (n,), ``miss`` (n, T) px, ``inside`` (n, T) bool, ``gate`` (n, T, 2) px and
        ``interferers`` (n, q, 2) px, e.g. from
        :func:`tvtrack.scenes.rotating_marker.interference_runs`; equally many runs per SIR.
    sir_values : ndarray, shape (m,)
        The SIR grid.
    criterion : LossCriterion
    capture_radius : float
        Distance (px) from an interferer within which a lost gate counts as captured.

    Returns
    -------
    dict
        ``p``: list of m :class:`tvtrack.montecarlo.Estimate` (Clopper-Pearson), ``losses`` (m,),
        ``n`` runs per SIR, ``threshold`` (:func:`loss_threshold`), ``captures`` (m,).
    """
    loss = first_loss(runs["miss"], criterion, runs["inside"])
    capt = tag_capture(runs["gate"], runs["interferers"], loss, criterion.window, capture_radius, criterion.fraction)
    counts = losses_by_sir(loss, runs["sir"], sir_values)
    n = int((runs["sir"] == sir_values[0]).sum())
    return dict(p=[proportion_ci(int(c), n) for c in counts], losses=counts, n=n,
                threshold=loss_threshold(sir_values, counts),
                captures=np.array([capt[runs["sir"] == s].sum() for s in sir_values]))
