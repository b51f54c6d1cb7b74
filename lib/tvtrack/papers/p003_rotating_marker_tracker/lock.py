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

from ...estimate import Estimate
from ...counts import proportion_ci

__all__ = [
    "LossCriterion",
    "first_loss",
    "tag_capture",
    "MECHANISMS",
    "CRITERIA",
    "loss_criteria",
    "classify_losses",
    "omega_alarm",
    "loss_threshold",
    "losses_by_sir",
    "loss_curve",
    "fit_logistic_loss",
    "fit_logistic_loss_batch",
    "sir_at_loss",
    "LossFit",
    "loss_rate",
    "fit_loss_curve",
    "ratio_of_fits",
]

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
    frames = np.clip(loss[:, None] - np.arange(window)[::-1], 0, None)  # (n, window)
    seg = gate[np.arange(n)[:, None], frames]  # (n, window, 2)
    near = np.linalg.norm(seg[:, :, None, :] - q[:, None, :, :], axis=-1) < radius
    return (loss >= 0) & (near.mean(axis=1) > fraction).any(axis=1)


MECHANISMS = ("capture", "drift among several", "frequency", "drift")


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


def classify_losses(
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
    """How each loss of lock happened, from the ``window`` frames that end at the loss frame.

    A frame counts as *near* an interferer when the gate is within ``radius`` of it while more
    than ``radius`` from the marker: a gate that follows a rotating marker passes over interferers
    on the marker's circle without leaving the marker, and that is not a loss mechanism.
    One label per loss, by precedence (index into :data:`MECHANISMS`; -1 = no loss); a loss can meet several
    criteria, so tables of mechanisms count :func:`loss_criteria` instead, which does not depend on an order:

    0. *capture*: near one interferer for more than ``fraction`` of the window;
    1. *drift among several*: near at least two different interferers during the window (it is
       passed from one to another, the five-interferer mode);
    2. *frequency*: the relative angular-velocity error exceeds ``omega_tol`` for more than
       ``fraction`` of the window (the phase loop lost the rotation; never for a static marker,
       whose ``omega_error`` is NaN);
    3. *drift*: none of these (the gate slid off with the rotation held and no interferer near).

    Parameters
    ----------
    loss_frame : ndarray of int, shape (n,)
        From :func:`first_loss`.
    gate : ndarray, shape (n, T, 2)
    interferers : ndarray, shape (n, q, 2)
    miss : ndarray, shape (n, T)
        Distance of the gate centre from the marker (px).
    omega_error : ndarray, shape (n, T)
        ``omega_hat / omega - 1``.
    window : int
    radius : float
        px.

    Returns
    -------
    ndarray of int8, shape (n,)
    """
    met = loss_criteria(loss_frame, gate, interferers, miss, omega_error, window, radius, fraction, omega_tol)
    out = np.full(met.shape[0], 3, np.int8)
    for j in (2, 1, 0):  # the documented precedence: capture first
        out[met[:, j]] = j
    out[np.asarray(loss_frame) < 0] = -1
    return out


def omega_alarm(omega_hat, omega_nominal: float, window: int, tol: float = 0.2) -> np.ndarray:
    """A lock detector that needs no truth: the first frame at which the moving mean over ``window``
    frames of ``|omega_hat / omega_nominal - 1|`` exceeds ``tol`` (-1 = never).

    Parameters
    ----------
    omega_hat : ndarray, shape (n, T)
        The tracker's angular-velocity estimate (rad/s).
    omega_nominal : float
        The marker's design rotation rate (rad/s), which the tracker knows.

    Returns
    -------
    ndarray of int, shape (n,)
    """
    dev = np.abs(np.asarray(omega_hat, float) / omega_nominal - 1.0)
    c = np.cumsum(np.pad(dev, ((0, 0), (1, 0))), axis=1)
    mean = (c[:, window:] - c[:, :-window]) / window  # frames window-1 .. T-1
    hit = mean > tol
    return np.where(hit.any(axis=1), hit.argmax(axis=1) + window - 1, -1)


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
        :func:`tvtrack.papers.p003_rotating_marker_tracker.scene.interference_runs`; equally many runs per SIR.
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
    return dict(
        p=[proportion_ci(int(c), n) for c in counts],
        losses=counts,
        n=n,
        threshold=loss_threshold(sir_values, counts),
        captures=np.array([capt[runs["sir"] == s].sum() for s in sir_values]),
    )


# --- loss of lock as a fitted curve of SIR ------------------------------------------------------


def fit_logistic_loss_batch(sir, k, n, max_slope: float = 200.0, iterations: int = 60) -> tuple[np.ndarray, np.ndarray]:
    """Maximum-likelihood fits of ``P(loss) = 1 / (1 + exp(-beta (log SIR_50 - log SIR)))``, many at once.

    Newton's method (iteratively reweighted least squares) on ``logit p = a + b (log SIR - mean)``
    for every row, steps limited to 5 logit units, ``beta = -b`` kept in ``[0.05, max_slope]`` (a
    grid that separates perfectly has no finite maximum; the slope then stops at ``max_slope``).

    Parameters
    ----------
    sir : ndarray, shape (m,)
        SIR grid (> 0).
    k, n : ndarray, shape (B, m) or (m,)
        Losses and runs at each SIR, one row per fit.

    Returns
    -------
    sir_50, beta : ndarray, shape (B,)
        SIR of 50 % loss and the slope in log SIR; NaN where every run lost or none did.
    """
    k = np.atleast_2d(np.asarray(k, float))
    n = np.atleast_2d(np.asarray(n, float))
    x = np.log(np.asarray(sir, float))
    xm = x.mean()
    xc = x - xm
    tot_k, tot_n = k.sum(1), n.sum(1)
    ok = (tot_k > 0) & (tot_k < tot_n)
    p0 = np.clip(tot_k / np.maximum(tot_n, 1), 0.02, 0.98)
    a = np.log(p0 / (1 - p0))
    b = np.full(k.shape[0], -5.0)
    for _ in range(iterations):
        eta = a[:, None] + b[:, None] * xc
        p = 0.5 * (1.0 + np.tanh(0.5 * eta))
        r = k - n * p
        w = n * p * (1 - p) + 1e-9
        ga, gb = r.sum(1), (r * xc).sum(1)
        haa, hab, hbb = w.sum(1), (w * xc).sum(1), (w * xc * xc).sum(1)
        det = haa * hbb - hab**2
        da = (hbb * ga - hab * gb) / det
        db = (haa * gb - hab * ga) / det
        scale = np.minimum(1.0, 5.0 / np.maximum(np.abs(da), np.abs(db)).clip(1e-12))
        a = a + scale * da
        b = np.clip(b + scale * db, -max_slope, -0.05)
    beta = -b
    s50 = np.exp(xm + a / beta)
    return np.where(ok, s50, np.nan), np.where(ok, beta, np.nan)


def fit_logistic_loss(sir, k, n, max_slope: float = 200.0) -> tuple[float, float]:
    """One fit of :func:`fit_logistic_loss_batch`: ``(sir_50, beta)``, ``(nan, nan)`` when every
    run lost or none did (no transition on the grid)."""
    s50, beta = fit_logistic_loss_batch(sir, k, n, max_slope)
    return float(s50[0]), float(beta[0])


def sir_at_loss(sir_50: float, beta: float, level: float = 0.05) -> float:
    """SIR at which the fitted curve gives ``P(loss) = level``: ``SIR_50 exp(-logit(level) / beta)``."""
    return float(sir_50 * np.exp(-np.log(level / (1 - level)) / beta))


@dataclass
class LossFit:
    """A loss curve fitted over seeds (see :func:`fit_loss_curve`).

    Attributes
    ----------
    sir : (m,) grid; k, n : (m,) losses and runs per SIR (pooled over seeds)
    sir_50, sir_05 : Estimate, SIR of 50 % and 5 % loss within the run length (cluster bootstrap)
    beta : float, fitted slope in log SIR
    boot_50, boot_05, boot_beta : (B,) bootstrap replicates (NaN where a resample had no transition)
    rate : list of m Estimate, losses per second of tracking before the loss (Poisson interval)
    duration_s : float, run length
    """

    sir: np.ndarray
    k: np.ndarray
    n: np.ndarray
    sir_50: Estimate
    sir_05: Estimate
    beta: float
    boot_50: np.ndarray
    boot_05: np.ndarray
    boot_beta: np.ndarray
    rate: list
    duration_s: float

    def p_at(self, s: float) -> float:
        """Fitted P(loss) at SIR ``s`` (0 or 1 where the grid had no transition)."""
        if not np.isfinite(self.sir_50.value):
            return 0.0 if self.k.sum() == 0 else 1.0
        return float(1.0 / (1.0 + np.exp(-self.beta * (np.log(self.sir_50.value) - np.log(s)))))

    def p_estimate(self, s: float) -> Estimate:
        """Fitted P(loss) at SIR ``s`` with its bootstrap interval."""
        ok = np.isfinite(self.boot_50)
        boot = 1.0 / (1.0 + np.exp(-self.boot_beta[ok] * (np.log(self.boot_50[ok]) - np.log(s))))
        if not np.isfinite(self.sir_50.value):
            return (
                Estimate(
                    self.p_at(s),
                    float("nan"),
                    0.0,
                    3.0 / float(self.n.sum()),
                    int(self.n.sum()),
                    0.95,
                    "no loss on the grid (rule of three over all runs)",
                )
                if self.k.sum() == 0
                else Estimate(1.0, float("nan"), 1.0, 1.0, int(self.n.sum()), 0.95, "every run lost")
            )
        return _boot_estimate(self.p_at(s), np.concatenate([boot, np.full((~ok).sum(), np.nan)]), self.sir_50.n)

    def summary(self) -> dict:
        """What results.json keeps per condition."""
        return dict(
            sir=self.sir,
            losses=self.k,
            runs=self.n,
            sir_50=self.sir_50,
            sir_05=self.sir_05,
            slope_log_sir=self.beta,
            loss_rate_per_s=dict(zip(map(lambda v: f"{v:g}", self.sir), self.rate)),
            duration_s=self.duration_s,
        )


def _boot_estimate(value: float, boot: np.ndarray, n: int, confidence: float = 0.95) -> Estimate:
    ok = boot[np.isfinite(boot)]
    a = (1 - confidence) / 2
    lo, hi = np.quantile(ok, [a, 1 - a]) if ok.size >= 0.9 * boot.size else (np.nan, np.nan)
    return Estimate(
        float(value),
        float(np.std(ok)) if ok.size else float("nan"),
        float(lo),
        float(hi),
        n,
        confidence,
        f"cluster bootstrap percentile ({boot.size} resamples of the trials)",
    )


def loss_rate(loss_frame, dt: float, n_frames: int, confidence: float = 0.95) -> Estimate:
    """Losses per second of locked tracking: ``k / sum(time to loss or end)``, exact Poisson interval."""
    from scipy.stats import chi2

    loss = np.asarray(loss_frame)
    k = int((loss >= 0).sum())
    exposure = float(np.where(loss >= 0, loss + 1, n_frames).sum() * dt)
    a = 1 - confidence
    lo = chi2.ppf(a / 2, 2 * k) / 2 / exposure if k > 0 else 0.0
    hi = chi2.ppf(1 - a / 2, 2 * k + 2) / 2 / exposure
    return Estimate(
        k / exposure, np.sqrt(k) / exposure, float(lo), float(hi), loss.size, confidence, "exact Poisson (chi-square)"
    )


def fit_loss_curve(
    loss_frame,
    sir,
    cluster,
    sir_values,
    *,
    dt: float,
    n_frames: int,
    rng: np.random.Generator,
    n_boot: int = 300,
    level: float = 0.05,
    boot_index=None,
) -> LossFit:
    """Fit P(loss within the run) against log SIR and bootstrap SIR_50 and the SIR at ``level``.

    Parameters
    ----------
    loss_frame : ndarray of int, shape (N,)
        First loss frame per run (-1: kept lock), :func:`first_loss`.
    sir : ndarray, shape (N,)
        Each run's SIR (values from ``sir_values``).
    cluster : ndarray of int, shape (N,)
        Runs that share their random draws (the same trial at every SIR, common random numbers)
        carry the same cluster id; the bootstrap resamples clusters, keeping the pairing.
    sir_values : ndarray, shape (m,)
    dt, n_frames : frame interval (s) and run length (frames), for the loss rate.
    rng : numpy.random.Generator
        Draws the bootstrap resamples (ignored when ``boot_index`` is given).
    boot_index : ndarray of int, shape (B, C), optional
        Resampled cluster positions (into the sorted unique cluster ids) to reuse, so that
        curves on the same clusters are bootstrapped jointly (paired ratios).

    Returns
    -------
    LossFit
    """
    sir_values = np.asarray(sir_values, float)
    lost = np.asarray(loss_frame) >= 0
    ids, cl = np.unique(np.asarray(cluster), return_inverse=True)
    col = (
        np.searchsorted(sir_values, np.asarray(sir, float))
        if np.all(np.diff(sir_values) > 0)
        else np.array([int(np.flatnonzero(sir_values == s)[0]) for s in sir])
    )
    C, m = ids.size, sir_values.size
    lost_cm = np.zeros((C, m))
    runs_cm = np.zeros((C, m))
    np.add.at(lost_cm, (cl, col), lost)
    np.add.at(runs_cm, (cl, col), 1)
    k, n = lost_cm.sum(0), runs_cm.sum(0)
    s50, beta = fit_logistic_loss(sir_values, k, n)
    s05 = sir_at_loss(s50, beta, level) if np.isfinite(s50) else float("nan")
    if boot_index is None:
        boot_index = rng.integers(0, C, size=(n_boot, C))
    W = np.stack([np.bincount(idx, minlength=C) for idx in boot_index]).astype(float)  # (B, C) resample weights
    b50, bbeta = fit_logistic_loss_batch(sir_values, W @ lost_cm, W @ runs_cm)
    b05 = b50 * np.exp(-np.log(level / (1 - level)) / bbeta)
    rate = [loss_rate(np.asarray(loss_frame)[col == j], dt, n_frames) for j in range(m)]
    if np.isfinite(s50):
        e50, e05 = _boot_estimate(s50, b50, C), _boot_estimate(s05, b05, C)
    elif k.sum() == 0:  # no loss anywhere: the thresholds lie below the grid
        e50 = e05 = Estimate(
            float("nan"),
            float("nan"),
            0.0,
            float(sir_values.min()),
            C,
            0.95,
            "no loss on the grid: below its smallest SIR",
        )
    else:  # every run lost: above the grid
        e50 = e05 = Estimate(
            float("inf"),
            float("nan"),
            float(sir_values.max()),
            float("inf"),
            C,
            0.95,
            "every run lost: above the largest SIR of the grid",
        )
    return LossFit(sir_values, k.astype(int), n.astype(int), e50, e05, beta, b50, b05, bbeta, rate, n_frames * dt)


def ratio_of_fits(a: np.ndarray, b: np.ndarray, value: float, n: int, confidence: float = 0.95) -> Estimate:
    """Ratio of two fitted thresholds from jointly (paired) or independently resampled bootstrap
    replicates ``a``, ``b`` (same length): percentile interval of ``a / b``."""
    r = np.asarray(a) / np.asarray(b)
    return _boot_estimate(value, r, n, confidence)
