"""Loss-of-lock studies of the rotating-marker tracker: loss curves over seeds, fitted against SIR.

A *study* runs one :class:`~tvtrack.papers.p003_rotating_marker_tracker.scene.Scenario` at every SIR of a grid for
``n`` trials per seed and seed (common random numbers across the SIR grid, and across scenarios
run with the same ``stream`` and seeds: the same object motion, background, interferer placement
and noise), detects the first loss of each run and fits P(loss within the run) against log SIR
(:func:`tvtrack.papers.p003_rotating_marker_tracker.lock.fit_loss_curve`), pooled over seeds and per seed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .lock import (LossCriterion, LossFit, classify_losses, fit_loss_curve, first_loss, omega_alarm,
                           ratio_of_fits, tag_capture)
from ...montecarlo import Estimate
from .scene import Scenario, interference_runs

__all__ = ["LossStudy", "study_rng", "bootstrap_index", "loss_study", "plot_loss_fit", "threshold_ratio", "seed_ratios"]


@dataclass
class LossStudy:
    """A loss study's outcome.

    Attributes
    ----------
    fit : LossFit, pooled over seeds
    seeds : dict seed -> LossFit
    captures : (m,) int, losses tagged as capture by a stationary interferer, per SIR
    loss_frame, sir, cluster : (N,) per run (cluster = seed position * n + trial)
    by_criterion : dict name -> LossFit, the pooled fit under other loss criteria (same runs)
    mechanism : (N,) int8, how each run lost lock (index into ``tvtrack.papers.p003_rotating_marker_tracker.lock.MECHANISMS``, -1 none)
    alarm_frame : (N,) int, first alarm of the truth-free omega lock detector (-1 none; -1 everywhere
        for a static marker, which has no rotation to watch)
    """

    fit: LossFit
    seeds: dict
    captures: np.ndarray
    loss_frame: np.ndarray
    sir: np.ndarray
    cluster: np.ndarray
    by_criterion: dict
    mechanism: np.ndarray
    alarm_frame: np.ndarray

    def within(self, n_frames: int, dt: float, boot_index: np.ndarray) -> LossFit:
        """The pooled fit of P(loss within the first ``n_frames`` frames) (losses later are censored)."""
        fl = np.where(self.loss_frame < n_frames, self.loss_frame, -1)
        return fit_loss_curve(fl, self.sir, self.cluster, self.fit.sir, dt=dt, n_frames=n_frames, rng=None,
                              boot_index=boot_index)


def study_rng(stream: int, seed: int) -> np.random.Generator:
    """The generator of one seed of one family of studies: studies that share ``stream`` share draws."""
    return np.random.default_rng([int(stream), int(seed)])


def bootstrap_index(rng: np.random.Generator, n_clusters: int, n_boot: int) -> np.ndarray:
    """Cluster resamples, shape (n_boot, n_clusters), shared by studies on the same clusters (paired)."""
    return rng.integers(0, n_clusters, size=(n_boot, n_clusters))


def loss_study(sc: Scenario, sir_values, *, n: int, seeds, stream: int, criterion: LossCriterion,
               capture_radius: float, boot_index: np.ndarray, seed_boot: int = 100,
               other_criteria: dict | None = None, max_batch: int = 256, omega_tol: float = 0.2) -> LossStudy:
    """Run ``sc`` at every SIR for ``n`` trials per seed and fit the loss curve.

    Parameters
    ----------
    sc : Scenario
    sir_values : array_like, shape (m,), increasing
    n : int
        Trials per seed (the same trials at every SIR).
    seeds : sequence of int
        At least one; the pooled fit concatenates them.
    stream : int
        Family of the draws (:func:`study_rng`): equal streams give common random numbers.
    criterion : LossCriterion
    capture_radius : float
        Distance (px) from an interferer within which a lost gate counts as captured.
    boot_index : ndarray of int, shape (B, n * len(seeds))
        Cluster resamples for the pooled fit (:func:`bootstrap_index`); reuse it across studies
        on the same clusters for paired comparisons.
    seed_boot : int
        Bootstrap resamples of each per-seed fit: the first ``seed_boot`` rows of ``boot_index``
        reduced modulo ``n`` (uniform resamples of that seed's trials, paired across studies too).
    other_criteria : dict name -> LossCriterion, optional
        Further loss criteria applied to the same runs (pooled fits only).
    max_batch : int
        Seeds are batched together in one closed-loop run while the batch holds at most this
        many runs (each seed's draws are the same batched or alone; memory ~0.45 MB per run).
    omega_tol : float
        Relative angular-velocity error that counts as a lost rotation, both in the loss
        classification and in the omega lock detector (over the criterion's window).

    Returns
    -------
    LossStudy
    """
    sirs = np.asarray(sir_values, float)
    if np.any(np.diff(sirs) <= 0):
        raise ValueError("parameter 'sir_values' must be strictly increasing")
    other_criteria = other_criteria or {}
    loss, sir, cluster, capt, mech, alarm = [], [], [], [], [], []
    other = {name: [] for name in other_criteria}
    per_seed = {}
    seeds = [int(x) for x in seeds]
    per_batch = max(1, max_batch // (n * sirs.size))
    for first in range(0, len(seeds), per_batch):
        group = seeds[first:first + per_batch]
        runs = interference_runs([study_rng(stream, x) for x in group], n, sc, sirs)
        fl_all = first_loss(runs["miss"], criterion, runs["inside"])
        capt_all = tag_capture(runs["gate"], runs["interferers"], fl_all, criterion.window, capture_radius,
                               criterion.fraction)
        other_all = {name: first_loss(runs["miss"], crit, runs["inside"]) for name, crit in other_criteria.items()}
        mech_all = classify_losses(fl_all, runs["gate"], runs["interferers"], runs["miss"], runs["omega_error"],
                                   criterion.window, capture_radius, criterion.fraction, omega_tol)
        alarm_all = (omega_alarm(runs["omega_hat"], sc.omega0, criterion.window, omega_tol) if sc.rotating
                     else np.full(fl_all.shape, -1))
        for b, x in enumerate(group):
            sel = runs["block"] == b
            j = first + b
            fl = fl_all[sel]
            per_seed[x] = fit_loss_curve(fl, runs["sir"][sel], runs["trial"][sel], sirs, dt=runs["dt"],
                                         n_frames=sc.n_frames, rng=None, boot_index=boot_index[:seed_boot] % n)
            loss.append(fl)
            capt.append(capt_all[sel])
            mech.append(mech_all[sel])
            alarm.append(alarm_all[sel])
            sir.append(runs["sir"][sel])
            cluster.append(j * n + runs["trial"][sel])
            for name in other_criteria:
                other[name].append(other_all[name][sel])
        del runs
    loss, sir, cluster, capt, mech, alarm = (np.concatenate(v) for v in (loss, sir, cluster, capt, mech, alarm))
    pooled = fit_loss_curve(loss, sir, cluster, sirs, dt=1.0 / sc.fps, n_frames=sc.n_frames, rng=None,
                            boot_index=boot_index)
    captures = np.array([capt[sir == s].sum() for s in sirs])
    by_criterion = {name: fit_loss_curve(np.concatenate(v), sir, cluster, sirs, dt=1.0 / sc.fps, n_frames=sc.n_frames,
                                         rng=None, boot_index=boot_index) for name, v in other.items()}
    return LossStudy(pooled, per_seed, captures, loss, sir, cluster, by_criterion, mech, alarm)


def plot_loss_fit(ax, fit: LossFit, label: str, **line_kw):
    """Observed loss share per SIR with 95 % Clopper-Pearson bars and the fitted logistic curve
    with its 95 % bootstrap band, on a log SIR axis. Returns the fitted line."""
    from ...montecarlo import proportion_ci

    grid = np.exp(np.linspace(np.log(fit.sir.min()), np.log(fit.sir.max()), 120))
    ok = np.isfinite(fit.boot_50)
    if ok.any():
        z = fit.boot_beta[ok, None] * (np.log(fit.boot_50[ok, None]) - np.log(grid))
        band = np.quantile(1 / (1 + np.exp(-z)), [0.025, 0.975], axis=0)
    line, = ax.plot(grid, [fit.p_at(s) for s in grid], label=label, **line_kw)
    if ok.any():
        ax.fill_between(grid, band[0], band[1], color=line.get_color(), alpha=0.12, lw=0)
    ci = [proportion_ci(int(k), int(n)) for k, n in zip(fit.k, fit.n)]
    p = fit.k / fit.n
    ax.errorbar(fit.sir, p, yerr=[p - [c.ci_low for c in ci], [c.ci_high for c in ci] - p], fmt="o", ms=3,
                color=line.get_color(), lw=0.8, capsize=0)
    ax.set_xscale("log")
    from matplotlib.ticker import FormatStrFormatter, LogLocator
    ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 1.5, 2.0, 3.0, 5.0, 7.0)))
    ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
    ax.xaxis.set_minor_formatter(FormatStrFormatter(""))
    return line


def threshold_ratio(a: LossFit, b: LossFit) -> Estimate:
    """``SIR_5%(a) / SIR_5%(b)`` with the percentile interval of the replicate ratios (paired when
    both fits used the same cluster resamples, independent otherwise). Where ``a`` saw no loss at
    all, its threshold lies below its grid and the ratio gets the interval ``[0, bound]``."""
    n = min(a.sir_05.n, b.sir_05.n)
    if a.k.sum() == 0 and b.k.sum() > 0:     # no loss against a: its threshold lies below its grid
        return Estimate(float("nan"), float("nan"), 0.0, a.sir_05.ci_high / b.sir_05.ci_low, n, 0.95,
                        "no loss in the numerator's runs: bound from its grid's smallest SIR")
    return ratio_of_fits(a.boot_05, b.boot_05, a.sir_05.value / b.sir_05.value, n)


def seed_ratios(a: LossStudy, b: LossStudy) -> dict:
    """:func:`threshold_ratio` per seed (the seeds both studies ran)."""
    return {s: threshold_ratio(a.seeds[s], b.seeds[s]) for s in a.seeds if s in b.seeds}
