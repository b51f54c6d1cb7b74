"""Direct-count estimators of notebook 003's verdicts: loss shares, grid-censored thresholds and their ratios, the
adaptive grid extension, fold distances and C003-10's compensation ratio.

Every estimate reads direct counts, never a fitted tail: the probability of loss at a grid SIR is a count with its
Clopper-Pearson interval (zero events: the one-sided bound they certify); a threshold is the geometric mean of the
per-run breaking SIRs, with a Student-t interval widened by half the grid step (the ratio of two such thresholds, by
half of each run's step in each curve: each is read off the grid to within half of its step).
"""

from __future__ import annotations


import numpy as np

from ...estimate import Estimate
from ...montecarlo import mean_ci, ratio_ci
from ...counts import proportion_ci, zero_events_bound

__all__ = [
    "loss_share",
    "log_thresholds",
    "threshold",
    "threshold_bound",
    "threshold_ratio",
    "extend_grid",
    "LOCK_LIMIT",
    "grid_in_lock",
    "interval_estimate",
    "share_difference",
    "compensation_factor",
]


def interval_estimate(value, lo, hi, n, method, extrapolated=False, sampling=None) -> Estimate:
    """An estimate known by its value and 95 % interval only (no standard error).

    Parameters
    ----------
    value, lo, hi : float
        The value and its interval's ends (in the quantity's unit).
    n : int
        The runs behind it.
    method : str
        How the interval was obtained.
    extrapolated : bool
        Whether the value lies beyond the measured grid.
    sampling : (float, float), optional
        The interval of the sampling error alone, where ``[lo, hi]`` adds a resolution allowance to it (half a grid
        step for a threshold, up to a whole one for a ratio of two: :attr:`tvtrack.estimate.Estimate.sampling_low`).

    Returns
    -------
    Estimate
        At 95 % confidence, ``stderr`` NaN.
    """
    s_lo, s_hi = (float("nan"), float("nan")) if sampling is None else map(float, sampling)
    return Estimate(
        float(value), float("nan"), float(lo), float(hi), int(n), 0.95, method, bool(extrapolated), s_lo, s_hi
    )


def loss_share(events) -> Estimate:
    """Share of runs with the event (loss, capture), from the direct count.

    ``k`` of ``n`` with the exact Clopper-Pearson 95 % interval; zero events give ``[0, b]`` with ``b`` the
    one-sided bound they certify (:func:`tvtrack.montecarlo.zero_events_bound`), and ``n`` events ``[1 - b, 1]``.

    Parameters
    ----------
    events : array_like of bool, shape (n,)
    """
    e = np.asarray(events, bool).ravel()
    n, k = e.size, int(e.sum())
    if k == 0:
        return interval_estimate(0.0, 0.0, zero_events_bound(n), n, "count: zero events, one-sided 95 % bound")
    if k == n:
        return interval_estimate(1.0, 1 - zero_events_bound(n), 1.0, n, "count: all events, one-sided 95 % bound")
    return proportion_ci(k, n)


def log_thresholds(lost, sirs) -> tuple[np.ndarray, np.ndarray]:
    """Per-run log breaking SIR from the losses on a SIR grid (the same runs at every SIR).

    A run that lost lock at the grid SIRs below ``s_k`` and kept it from ``s_k`` on broke between ``s_{k-1}`` and
    ``s_k``; its log threshold is the midpoint ``(ln s_{k-1} + ln s_k) / 2``. A non-monotone run counts its losses:
    ``ln s_0 + sum_i lost_i (ln s_{i+1} - ln s_i)`` is the upper end, minus half the step below it.

    Parameters
    ----------
    lost : array_like of bool, shape (m, n)
        Loss of lock at each of ``m`` grid SIRs (increasing) for ``n`` runs.
    sirs : array_like, shape (m,)

    Returns
    -------
    tau : ndarray, shape (n,)
        Log thresholds.
    censored : ndarray of bool, shape (n,)
        Runs that broke outside the grid (lost at its top, or kept lock at its bottom).
    """
    tau, censored, _ = _readings(lost, sirs)
    return tau, censored


def _readings(lost, sirs) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`log_thresholds` and each run's step: the width on the log scale of the grid step it is read in (its
    log threshold lies within half of it of the truth)."""
    L = np.asarray(lost, bool)
    ls = np.log(np.asarray(sirs, float))
    steps = np.diff(ls)
    k = L[:-1].sum(axis=0)  # grid steps climbed (index of the first kept SIR)
    upper = ls[0] + (L[:-1] * steps[:, None]).sum(axis=0)
    below = np.where(k > 0, steps[np.maximum(k - 1, 0)], steps[0])
    return upper - below / 2, L[-1] | ~L[0], below


def _half_step(sirs) -> float:
    """Half the widest step of an SIR grid on the log scale (natural log units): how far a threshold read off the
    grid can lie from its true place."""
    return float(np.max(np.diff(np.log(np.asarray(sirs, float)))) / 2)


def threshold(lost, sirs) -> Estimate:
    """Geometric-mean breaking SIR of the runs, from :func:`log_thresholds`.

    ``exp(mean tau)`` with the Student-t 95 % interval of the mean widened by half the largest grid step on each
    side (each run's threshold is known only to within its grid step); ``extrapolated`` when any run broke outside
    the grid (the mean would then rest on a guess).
    """
    tau, cens = log_thresholds(lost, sirs)
    h = _half_step(sirs)
    m = mean_ci(tau)
    return interval_estimate(
        np.exp(m.value),
        np.exp(m.ci_low - h),
        np.exp(m.ci_high + h),
        tau.size,
        "geometric mean of per-run breaking SIRs (grid-censored), t interval + half a grid step",
        extrapolated=bool(cens.any()),
        sampling=(np.exp(m.ci_low), np.exp(m.ci_high)),
    )


def threshold_bound(lost, sirs) -> Estimate:
    """The side of the paper's value a threshold certifies, from the same runs as :func:`threshold`.

    :func:`threshold` is ``extrapolated`` (undecided) as soon as one run broke outside the grid; but a run that kept
    lock at the grid's bottom broke below it, and one that lost lock at its top broke above it, so censoring on one
    side still bounds the geometric mean on the other: with runs censored below, ``[0, exp(upper t bound of the
    mean with those runs at the bottom + h)]``; censored above, ``[exp(lower t bound with those runs at the top - h),
    inf]`` (``h`` half the largest grid step, as in :func:`threshold`). Without censoring it equals
    :func:`threshold`; censored on both sides it stays ``extrapolated``. The value is :func:`threshold`'s.
    """
    L = np.asarray(lost, bool)
    ls = np.log(np.asarray(sirs, float))
    tau, _ = log_thresholds(L, sirs)
    point = threshold(L, sirs)
    low_c, high_c = ~L[0], L[-1]  # kept lock at the bottom (broke below) / lost at the top (broke above)
    if not (low_c.any() or high_c.any()):
        return point
    h = _half_step(sirs)
    lo = 0.0 if low_c.any() else float(np.exp(mean_ci(np.where(high_c, ls[-1], tau)).ci_low - h))
    hi = float("inf") if high_c.any() else float(np.exp(mean_ci(np.where(low_c, ls[0], tau)).ci_high + h))
    return interval_estimate(
        point.value,
        lo,
        hi,
        tau.size,
        f"bound certified by the censoring: {int(low_c.sum())} run(s) broke below the grid, "
        f"{int(high_c.sum())} above it; t bound + half a grid step",
        extrapolated=bool(low_c.any() and high_c.any()),
    )


def _paired_allowance(width_a, width_b) -> float:
    """How far the mean of paired log-threshold differences read off a grid can lie from the truth: the mean over
    the runs of half of each curve's step (``width_a``, ``width_b``: per run, 0 where a run is a bound)."""
    return float(np.mean(np.asarray(width_a, float) + np.asarray(width_b, float)) / 2)


def threshold_ratio(lost_a, lost_b, sirs) -> Estimate:
    """Ratio of the geometric-mean thresholds of two curves run on the same draws (paired per run).

    ``exp(mean(tau_a - tau_b))`` with the paired t interval widened on each side by the mean over the runs of half
    the step each curve's run is read in, summed over the two curves: each run is read off the grid to within half
    its step, and the two errors need not cancel (a run of ``a`` high in its step and one of ``b`` low in the same
    step differ by up to a whole step where their midpoints agree: with half the widest step, six paired runs
    breaking within one step covered the true ratio in 0.77 of experiments); a run placed at the grid's edge as a
    bound (below) reads no error on the side it bounds and adds nothing;
    ``extrapolated`` when a run of either curve broke outside the grid -- except where the censoring certifies a
    bound: when the runs of ``a`` broke outside the grid only below it and those of ``b`` only above it, each
    censored run's log threshold is at most (``a``) or at least (``b``) the grid's edge, so the ratio is bounded
    above: ``[0, exp(upper t bound of mean(ub_a - lb_b) + h)]`` (value: the bound's point), like the zero-events
    bound of a share; mirrored, when ``a`` broke outside only above the grid and ``b`` only below it, the ratio is
    bounded below: ``[exp(lower t bound of mean(lb_a - ub_b) - h), inf]`` (e.g. C003-12's imitator when a bright decoy
    breaks lock at every grid SIR).
    """
    La, Lb = np.asarray(lost_a, bool), np.asarray(lost_b, bool)
    ta, ca, wa = _readings(La, sirs)
    tb, cb, wb = _readings(Lb, sirs)
    steps = np.diff(np.log(np.asarray(sirs, float)))
    if (ca.any() or cb.any()) and not La[-1].any() and Lb[0].all():
        ub = np.where(~La[0], ta + steps[0] / 2, ta)  # a: kept lock at the bottom, threshold below it
        lb = np.where(Lb[-1], tb + steps[-1] / 2, tb)  # b: lost at the top, threshold above it
        h = _paired_allowance(np.where(~La[0], 0.0, wa), np.where(Lb[-1], 0.0, wb))  # edges bound: no error
        m = mean_ci(ub - lb)
        return interval_estimate(
            np.exp(m.value),
            0.0,
            np.exp(m.ci_high + h),
            ta.size,
            f"upper bound: {int((~La[0]).sum())} run(s) of the first curve kept lock at the grid's bottom, "
            f"{int(Lb[-1].sum())} of the second lost it at its top; paired t bound + the runs' grid steps",
        )
    if (ca.any() or cb.any()) and La[0].all() and not Lb[-1].any():  # the mirror case: a lower bound
        lb = np.where(La[-1], ta + steps[-1] / 2, ta)  # a: lost at the top, threshold above it
        ub = np.where(~Lb[0], tb + steps[0] / 2, tb)  # b: kept lock at the bottom, threshold below it
        h = _paired_allowance(np.where(La[-1], 0.0, wa), np.where(~Lb[0], 0.0, wb))
        m = mean_ci(lb - ub)
        return interval_estimate(
            np.exp(m.value),
            np.exp(m.ci_low - h),
            np.inf,
            ta.size,
            f"lower bound: {int(La[-1].sum())} run(s) of the first curve lost lock at the grid's top, "
            f"{int((~Lb[0]).sum())} of the second kept it at its bottom; paired t bound + the runs' grid steps",
        )
    h = _paired_allowance(wa, wb)
    m = mean_ci(ta - tb)
    return interval_estimate(
        np.exp(m.value),
        np.exp(m.ci_low - h),
        np.exp(m.ci_high + h),
        ta.size,
        "paired ratio of geometric-mean thresholds, t interval + the runs' grid steps",
        extrapolated=bool(ca.any() or cb.any()),
        sampling=(np.exp(m.ci_low), np.exp(m.ci_high)),
    )


def extend_grid(
    curves: dict, sirs, run, step: float = 1.5, max_points: int = 2, trigger=None
) -> tuple[np.ndarray, dict]:
    """Adaptive grid points for thresholds that would break outside the grid (C003-12 was undecided for them).

    While some run of some curve kept lock at the grid's bottom (or lost it at its top), the curves with such runs
    are run at one more SIR, the bottom over ``step`` (the top times ``step``), up to ``max_points`` on each side.
    A curve not run there is filled by monotonicity, exactly where it is known: every one of its runs lost lock at
    the old bottom, so it loses below it (kept lock at the old top, so it keeps it above). With the same draws at
    every SIR (common random numbers) the extended curves stay paired run by run. With ``trigger`` (keys), a side is
    extended only while one of those curves needs it (the others' censoring may certify a bound instead, see
    :func:`threshold_ratio`).

    Parameters
    ----------
    curves : dict of key -> ndarray of bool, shape (m, n)
        Loss indicators on ``sirs``.
    sirs : array_like, shape (m,)
    run : callable
        ``run(keys, sir) -> {key: ndarray of bool, shape (n,)}``: the named curves' runs at one more SIR.

    Returns
    -------
    sirs : ndarray, shape (m',)
    curves : dict of key -> ndarray of bool, shape (m', n)
    """
    s = list(np.asarray(sirs, float))
    out = {k: np.asarray(v, bool) for k, v in curves.items()}
    for side in ("low", "high"):
        for _ in range(max_points):
            edge = 0 if side == "low" else -1
            need = [k for k, v in out.items() if (~v[edge] if side == "low" else v[edge]).any()]
            if not need or (trigger is not None and not set(need) & set(trigger)):
                break
            sir = s[0] / step if side == "low" else s[-1] * step
            new = run(need, sir)
            for k, v in out.items():
                row = np.asarray(new[k], bool) if k in new else np.full(v.shape[1], side == "low")
                out[k] = np.vstack([row[None], v]) if side == "low" else np.vstack([v, row[None]])
            s = [sir] + s if side == "low" else s + [sir]
    return np.asarray(s), out


def share_difference(a, b) -> Estimate:
    """Paired difference of two loss shares on the same runs (Student t on per-run differences; all-equal runs:
    the zero-events bound). Both shares lie in [0, 1], so the difference and its interval lie in [-1, 1].

    Where every run has the same difference ``d0``, the runs that differ from it are zero events, so their share
    ``q`` is at most the zero-events bound ``b``. With no discordant run (``d0 = 0``) the two discordant shares sum
    to ``q``, so the difference lies in ``[-b, b]``; where every run differs by +1 (or -1) the shares of 0 and of
    -1 sum to ``q``, and the worst case puts all of it at -1: the difference is at least ``1 - 2b`` (the open end
    moves only; a single run included)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = a - b
    if np.all(d == d[0]):
        reach = zero_events_bound(d.size) * (1.0 + abs(d[0]))  # b with no discordant run, 2b where all are
        return interval_estimate(
            d[0],
            max(d[0] - reach, -1.0),
            min(d[0] + reach, 1.0),
            d.size,
            "every run the same difference: the zero-events bound on the others, one-sided 95 %",
        )
    m = mean_ci(d)
    return interval_estimate(
        m.value, max(m.ci_low, -1.0), min(m.ci_high, 1.0), d.size, "paired t on per-run differences"
    )


def compensation_factor(lost_unc, usirs, lost_comp, sirs, kappa: float) -> Estimate:
    """Compensated SIR_0 threshold (``kappa`` x its SIR threshold) over the uncompensated SIR_0 threshold: about
    ``kappa`` if compensation is worth its 1/kappa background reduction (C003-10), 0 if the raw background alone
    breaks lock.

    When any run without compensation lost lock at the grid's top SIR_0, its loss-free threshold lies above the grid:
    the ratio is then bounded above by the compensated threshold's upper bound over the grid's top (a direct-count bound,
    reported as ``[0, bound]``); a run that broke below the grid leaves the ratio undecided (extrapolated).
    """
    unc = np.asarray(lost_unc, bool)
    comp = threshold(lost_comp, sirs)
    if unc[-1].any():
        hi = kappa * comp.ci_high / float(usirs[-1])
        return interval_estimate(
            0.0,
            0.0,
            hi,
            unc.shape[1],
            f"{int(unc[-1].sum())} of {unc.shape[1]} uncompensated runs "
            f"lost even at SIR_0 {usirs[-1]:g}: bound from the grid's top",
            extrapolated=comp.extrapolated,
        )
    u = threshold(unc, usirs)
    return interval_estimate(
        kappa * comp.value / u.value,
        kappa * comp.ci_low / u.ci_high,
        kappa * comp.ci_high / u.ci_low,
        u.n,
        "ratio of thresholds, interval from their bounds",
        extrapolated=bool(u.extrapolated or comp.extrapolated),
    )


#: A grid point where more than this share of the runs lost lock is read as lost, not as a point of a trend (the
#: limit C003-1 asks of a tracker that follows its object).
LOCK_LIMIT = 0.1


def _not_read(n: int, why: str) -> Estimate:
    return Estimate(float("nan"), float("nan"), float("nan"), float("nan"), int(n), 0.95, why)


def grid_in_lock(lost, ripple, control, grid, pair, limit: float = LOCK_LIMIT) -> dict:
    """A trend along a loop-bandwidth grid read only where the tracker keeps lock, lost points reported as such.

    A tracker that lost lock has no ripple to speak of: its error is the distance to the object it left, and a
    rotation-locked share of that error says nothing about the loop's width. So each grid point is read on its
    runs that kept lock, a point where more than ``limit`` of the runs lost lock is left out of the trend, and every
    point's share of lost runs is reported (Clopper-Pearson).

    Parameters
    ----------
    lost : ndarray of bool, shape (G, n)
        Runs that lost lock at each grid point (the same draws at every point).
    ripple, control : ndarray, shape (G, n)
        The rotation-locked amplitude of the error and the amplitude locked to a control frequency, per run.
    grid : sequence of float
        The G loop bandwidths, Hz.
    pair : (float, float)
        Two grid bandwidths whose locked ripples are compared (the first over the second), Hz.
    limit : float

    Returns
    -------
    dict
        ``"trend"``: the paired ratio ripple / control at each point in lock, in grid order (two NaN points when
        fewer than two keep lock: the trend is then undecided); ``"lost"``: ``{"<b> Hz": share of runs that lost
        lock}``; ``"read"``: the bandwidths in the trend; ``"pair"``: ripple at ``pair[0]`` over ``pair[1]`` on the
        runs in lock at both (NaN where either point is lost).
    """
    lost = np.asarray(lost, bool)
    n = lost.shape[1]
    shares = {f"{b:g} Hz": loss_share(lost[i]) for i, b in enumerate(grid)}
    kept = [i for i in range(len(grid)) if lost[i].mean() <= limit]
    trend = [ratio_ci(ripple[i][~lost[i]], control[i][~lost[i]]) for i in kept]
    if len(trend) < 2:
        trend = [_not_read(n, "fewer than two grid points keep lock")] * 2
    i, j = (list(grid).index(b) for b in pair)
    both = ~lost[i] & ~lost[j]
    if i in kept and j in kept and both.sum() >= 2:
        ratio = ratio_ci(ripple[i][both], ripple[j][both])
    else:
        ratio = _not_read(n, "the tracker lost lock at one of the two bandwidths")
    return {"trend": trend, "lost": shares, "read": [float(grid[k]) for k in kept], "pair": ratio}
