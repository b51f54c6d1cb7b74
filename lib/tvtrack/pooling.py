"""Pooling a claim's measured values over independent replicates (equal weights; counts as counts; certified
bounds to their envelope; positive quantities on the log scale; replicates that disagree beyond their own intervals
by Student's t over their values; a fold distance by its signed ratio, folded after), for :mod:`tvtrack.explore`."""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any, Mapping, Sequence

import numpy as np
import scipy  # scipy.stats is imported at its first use (scipy loads submodules lazily)

from .estimate import Estimate
from .measured import lost_runs
from .measured import calibrated, fold_about

__all__ = ["pool"]


def _z(conf: float) -> float:
    return float(scipy.stats.norm.ppf(0.5 + conf / 2))


def _is_count(e: Estimate) -> bool:
    return e.method == "Clopper-Pearson" or e.method.startswith("count")


def _pool_counts(es: list[Estimate]) -> Estimate:
    """Shares from direct counts pool as counts: ``sum k`` of ``sum n``, with the Clopper-Pearson interval (zero or
    all events: the one-sided bound they certify), never by averaging intervals (which under-covers for zero events)."""
    from .counts import proportion_ci, zero_events_bound

    n = int(sum(e.n for e in es))
    k = int(sum(round(e.value * e.n) for e in es))
    conf = es[0].confidence
    if 0 < k < n:
        return proportion_ci(k, n, conf)
    b = zero_events_bound(n, conf)
    lo, hi = (0.0, b) if k == 0 else (1.0 - b, 1.0)
    return Estimate(k / n, math.nan, lo, hi, n, conf, f"count over {len(es)} replicates: {k} of {n}, one-sided bound")


def _is_bound(e: Estimate) -> bool:
    """A one-sided interval: ``[a, inf)``, or ``[0, b]`` of a non-negative quantity that its method certifies as a
    bound (a count's, or e.g. no run of a threshold ratio's denominator broke on the grid). An interval merely
    clipped at zero (a bootstrap's lower end below zero) is no bound: it pools as an interval."""
    certified = _is_count(e) or "bound" in e.method
    return (e.ci_low == 0.0 < e.ci_high and e.value >= 0.0 and certified) or e.ci_high == math.inf


def _pool_estimates(es: list[Estimate]) -> Estimate:
    k = len(es)
    conf = es[0].confidence
    z = _z(conf)
    n = int(sum(e.n for e in es))
    extrap = any(e.extrapolated for e in es)
    if all(_is_count(e) for e in es) and not extrap:
        return _pool_counts(es)
    vals = np.array([e.value for e in es], float)
    if all(e.method == "exact" for e in es):
        if np.all(vals == vals[0]):
            return es[0]
        t = scipy.stats.t.ppf(0.5 + conf / 2, k - 1)
        m, s = vals.mean(), vals.std(ddof=1) / math.sqrt(k)
        return Estimate(
            float(m),
            float(s),
            float(m - t * s),
            float(m + t * s),
            k,
            conf,
            f"t interval over {k} independent replicates",
            extrap,
        )
    lo = np.array([e.ci_low for e in es], float)
    hi = np.array([e.ci_high for e in es], float)
    if any(_is_bound(e) for e in es) and not (np.isnan(lo).any() or np.isnan(hi).any() or np.isnan(vals).any()):
        # a certified one-sided bound has no standard error to combine: the envelope of the replicates'
        # intervals covers the truth at least as often as any one of them does (conservative, never negative)
        a, b = float(lo.min()), float(hi.max())
        return Estimate(
            float(np.clip(np.median(vals), a, b)),
            float((b - a) / (2 * z)),
            a,
            b,
            n,
            conf,
            f"envelope of {k} independent replicates' intervals (some are certified bounds)",
            extrap,
        )
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)) and np.all(np.isfinite(vals))):
        defined = vals[~np.isnan(vals)]  # no replicate with a value (every run lost lock): no value either
        return Estimate(
            float(defined.mean()) if defined.size else math.nan,
            math.nan,
            math.nan,
            math.nan,
            n,
            conf,
            f"pooled over {k} replicates: some intervals undefined",
            extrap,
        )
    if any(e.has_allowance for e in es):
        return _pool_with_allowance(es, vals, lo, hi, n, extrap)
    if np.all(lo > 0) and np.all(vals > 0):  # positive quantities on the log scale
        m, a, b, se, how = _combine(np.log(vals), np.log(lo), np.log(hi), conf, ", log scale")
        a, b = max(math.exp(a), float(lo.min())), min(math.exp(b), float(hi.max()))  # within the hull, as below
        return Estimate(float(math.exp(m)), float(math.exp(m) * se), a, b, n, conf, how, extrap)
    m, a, b, se, how = _combine(vals, lo, hi, conf, "")
    # never beyond every replicate's interval (a share difference's pooled interval stays within [-1, 1]): the truth
    # lies outside the hull only when it lies outside every replicate's interval
    a, b = max(a, float(lo.min())), min(b, float(hi.max()))
    return Estimate(float(m), float(se), a, b, n, conf, how, extrap)


def _pool_with_allowance(
    es: list[Estimate], vals: np.ndarray, lo: np.ndarray, hi: np.ndarray, n: int, extrap
) -> Estimate:
    """Replicates whose intervals add a resolution allowance to their sampling error (``Estimate.sampling_low`` and
    ``sampling_high``): their sampling intervals pooled as any interval is (:func:`_combine`, on the log scale for
    positive quantities), then the largest allowance of a replicate added back on each side. The allowance (a grid
    step, a frame) is the same in every replicate and no number of replicates shrinks it; pooled as sampling error
    it was divided by the square root of the replicates (003's thresholds: 0.82-0.86 coverage at 3-5 replicates
    whose runs scatter less than a grid step). The pooled estimate keeps its sampling interval."""
    conf = es[0].confidence
    slo = np.array([e.sampling_low if e.has_allowance else e.ci_low for e in es], float)
    shi = np.array([e.sampling_high if e.has_allowance else e.ci_high for e in es], float)
    log = bool(np.all(lo > 0) and np.all(vals > 0))
    f, g = (np.log, np.exp) if log else (np.asarray, float)
    m, a, b, se, how = _combine(f(vals), f(slo), f(shi), conf, ", log scale" if log else "")
    below, above = float(np.max(f(slo) - f(lo))), float(np.max(f(hi) - f(shi)))
    low, high = max(float(g(a - below)), float(lo.min())), min(float(g(b + above)), float(hi.max()))
    value = float(g(m))
    return Estimate(
        value,
        float(value * se if log else se),
        low,
        high,
        n,
        conf,
        how + "; the replicates' resolution allowance added back",
        extrap,
        min(max(float(g(a)), low), value),
        max(min(float(g(b)), high), value),
    )


#: The agreement test's level: replicates whose values scatter more than their own intervals allow at this level
#: are pooled by the t interval over their values (see :func:`_combine`).
AGREEMENT_LEVEL = 0.05


def _combine(vals: np.ndarray, lo: np.ndarray, hi: np.ndarray, conf: float, scale: str) -> tuple:
    """``(value, low, high, stderr, method)`` of equal-weight replicates on one scale.

    The standard errors read from the replicates' intervals combine into the pooled one. The replicates must also
    agree with each other: Cochran's Q of their values about the pooled one, each weighed by its own standard
    error, against chi-square with ``k - 1`` degrees of freedom. Where they disagree at :data:`AGREEMENT_LEVEL` (a
    rare event, such as a run that loses lock, moved one replicate's value far beyond what the others' intervals,
    which never saw one, allow), the interval is widened to Student's t over the replicates' values, which needs no
    replicate's interval to be right."""
    k, z = len(vals), _z(conf)
    se_i = (hi - lo) / (2 * z)
    m = float(vals.mean())
    se = math.sqrt(float(np.sum(se_i**2))) / k
    with np.errstate(divide="ignore", invalid="ignore"):
        q = float(np.sum(np.where(vals == m, 0.0, ((vals - m) / se_i) ** 2)))
    p = float(scipy.stats.chi2.sf(q, k - 1)) if math.isfinite(q) else 0.0
    if p >= AGREEMENT_LEVEL:
        return m, m - z * se, m + z * se, se, f"pooled over {k} independent replicates (equal weights{scale})"
    spread = float(vals.std(ddof=1)) / math.sqrt(k)
    half = max(z * se, float(scipy.stats.t.ppf(0.5 + conf / 2, k - 1)) * spread)
    return (
        m,
        m - half,
        m + half,
        max(se, spread),
        (
            f"pooled over {k} independent replicates that disagree beyond their own intervals (agreement test "
            f"p = {p:.2g}): widened to Student's t over their values{scale}"
        ),
    )


def _unmeasured_kept(es: list[Estimate], pooled: Estimate) -> Estimate:
    """``pooled``, its method saying "coverage unmeasured" where a replicate's does (an interval of fewer runs than
    its helper's coverage was measured at): a pool of such intervals has no measured coverage either, and stays
    undecided (:func:`tvtrack.measured.is_undecided`) as each of them is."""
    from .coverage import stated_coverage

    short = [e for e in es if math.isnan(stated_coverage(e))]
    if not short or math.isnan(stated_coverage(pooled)):
        return pooled
    n = min(e.n for e in short)
    return replace(pooled, method=f"{pooled.method}; coverage unmeasured (replicates of {n} runs)")


def _folded_after_pooling(es: list[Estimate]) -> Estimate | None:
    """Fold distances (:func:`tvtrack.measured.fold_about`) about one reference: their signed ratios pooled, the
    pool folded; None where no replicate is one (a pool of some with other estimates, or about different
    references, is refused). Folded first, replicates of a ratio of no change that scatter either side of the
    reference each read a distance from it, and their pool a dependence that is not there."""
    folded = [e.signed is not None for e in es]
    if not any(folded):
        return None
    ks = {e.fold_reference for e in es if e.signed is not None}
    if not all(folded) or len(ks) != 1:  # a fold's pool needs every replicate's signed ratio, about one reference
        raise ValueError(
            f"pool: fold distances pool only with fold distances about the same reference, got {len(es)} replicates "
            f"of which {sum(folded)} fold distances about {sorted(ks)}"
        )
    return fold_about(pool([e.signed for e in es]), ks.pop())


def _is_estimate_like(x: Any) -> bool:
    return isinstance(x, Estimate) or (isinstance(x, Mapping) and "value" in x and "ci_low" in x)


def _is_reading_tag(m: Any) -> bool:
    """Whether ``m`` is what :meth:`tvtrack.verdicts.ByReading.tag` returns: ``{"reading": value, "measured": ...}``."""
    return isinstance(m, Mapping) and set(m) == {"reading", "measured"}


def pool(measured: Sequence[Any]) -> Any:
    """Pool a claim's measured values from independent replicates.

    Estimates are averaged with equal weights and their standard errors (from the intervals) combined
    (on the log scale when every interval is positive); exact numbers that vary between replicates get
    a Student-t interval over the replicates; lists and dicts (``Monotone`` points, ``AllOf`` parts)
    are pooled element by element; a value with runs that lost lock (:func:`tvtrack.measured.with_lost_runs`) pools
    its two estimates and sums its counts; a :class:`tvtrack.verdicts.ByReading` tag keeps its reading (a number
    such as a contrast of 0 names a rule, it is not averaged) and pools what was measured. An undefined interval in any replicate makes the pooled interval
    undefined (the verdict is then ``undecided``).
    """
    ms = [m for m in measured if m is not None]
    if not ms:
        return None
    if len(ms) == 1:
        return ms[0]
    first = ms[0]
    if _is_estimate_like(first) or isinstance(first, (int, float, np.number)):
        es = [calibrated(m) for m in ms]  # each replicate's interval at its nominal coverage before pooling
        refolded = _folded_after_pooling(es)
        return refolded if refolded is not None else _unmeasured_kept(es, _pool_estimates(es))
    if lost_runs(first) is not None and all(lost_runs(m) is not None for m in ms):  # counts add up
        return {
            "value": pool([m["value"] for m in ms]),
            "in lock": pool([m["in lock"] for m in ms]),
            "lost": int(sum(m["lost"] for m in ms)),
            "runs": int(sum(m["runs"] for m in ms)),
        }
    if _is_reading_tag(first) and all(_is_reading_tag(m) for m in ms):  # the reading names a rule: not averaged
        return {"reading": first["reading"], "measured": pool([m["measured"] for m in ms])}  # the first's, as a text
    if isinstance(first, Mapping):
        keys = [k for k in first if all(isinstance(m, Mapping) and k in m for m in ms)]
        return {k: pool([m[k] for m in ms]) for k in keys}
    if isinstance(first, (list, tuple)) and all(isinstance(m, (list, tuple)) and len(m) == len(first) for m in ms):
        return [pool([m[i] for m in ms]) for i in range(len(first))]
    return first
