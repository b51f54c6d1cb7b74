"""Probabilities from counts of events: exact intervals, the bound zero events certify, and words for them.

A rate decided from ``k`` events in ``n`` independent runs reads the counts directly (Clopper-Pearson,
or the one-sided zero-events bound), never a model's tail; a fitted rate the counts cannot resolve is
marked extrapolated and never decides. Re-exported by :mod:`tvtrack.montecarlo`.
"""

from __future__ import annotations

import functools
from dataclasses import replace

import numpy as np
import scipy  # scipy.stats is imported at its first use (scipy loads submodules lazily)

from .estimate import Estimate

__all__ = ["proportion_ci", "zero_events_bound", "rate_from_counts", "mark_extrapolated", "events_statement"]


def proportion_ci(successes: int, n: int, confidence: float = 0.95) -> Estimate:
    """A probability from ``successes`` out of ``n`` Bernoulli trials, with the exact
    Clopper-Pearson interval (scipy.stats.binomtest)."""
    if n <= 0:
        raise ValueError(f"proportion_ci needs n >= 1, got n={n}")
    k = int(successes)
    p = k / n
    low, high = _clopper_pearson(k, n, confidence)
    return Estimate(p, float(np.sqrt(p * (1 - p) / n)), low, high, n, confidence, "Clopper-Pearson")


@functools.lru_cache(maxsize=4096)
def _clopper_pearson(k: int, n: int, confidence: float) -> tuple[float, float]:
    """The exact interval's ends for ``k`` of ``n`` (scipy's root search, a few ms a call), kept for the next call
    with the same counts: an exploration asks the same few counts again in many of its runs."""
    ci = scipy.stats.binomtest(k, n).proportion_ci(confidence_level=confidence, method="exact")
    return float(ci.low), float(ci.high)


def zero_events_bound(n: int, confidence: float = 0.95) -> float:
    """The upper bound on a probability that zero events in ``n`` independent runs certify:
    ``1 - (1 - confidence)^(1/n)`` (one-sided Clopper-Pearson; about ``3/n`` at 95 %)."""
    if n <= 0:
        raise ValueError(f"zero_events_bound needs n >= 1, got n={n}")
    return float(1 - (1 - confidence) ** (1 / n))


def rate_from_counts(k: int, n: int, confidence: float = 0.95) -> Estimate:
    """A probability as the direct counts support it: ``k`` events in ``n`` independent runs.

    ``k > 0``: :func:`proportion_ci` (Clopper-Pearson). ``k = 0``: the interval ``[0, b]`` with ``b`` the
    bound zero events certify (:func:`zero_events_bound`, one-sided), so a rule can decide "the rate is
    below a target" from the counts alone and never from a model's tail. Both methods read as counts
    to :mod:`tvtrack.explore`, which pools replicates as summed counts.
    """
    if k > 0:
        return proportion_ci(k, n, confidence)
    b = zero_events_bound(n, confidence)
    return Estimate(
        0.0,
        float("nan"),
        0.0,
        b,
        n,
        confidence,
        f"count: 0 of {n} runs, rate < {b:.3g} (one-sided bound 1 - (1 - confidence)^(1/n))",
    )


def mark_extrapolated(fitted: Estimate, k: int, n: int, confidence: float = 0.95) -> Estimate:
    """A fitted probability (e.g. a logistic loss curve read at one SIR) marked ``extrapolated`` where
    the ``k`` of ``n`` direct counts behind it cannot resolve it: zero events, or a fitted value below
    the bound zero events would certify (``1 - 0.05^(1/n)``: the runs would most likely see nothing).
    An extrapolated estimate is shown but never decides (:func:`tvtrack.verdicts.is_undecided`); use
    :func:`rate_from_counts` to decide."""
    if k > 0 and fitted.value >= zero_events_bound(n, confidence):
        return fitted
    return replace(
        fitted,
        extrapolated=True,
        method=f"{fitted.method}; extrapolated: {events_statement(k, n, confidence)}".lstrip("; "),
    )


def events_statement(k: int, n: int, confidence: float = 0.95) -> str:
    """What ``k`` events in ``n`` runs say, in words: for ``k = 0`` the bound it certifies,
    otherwise the rate with its Clopper-Pearson interval."""
    if k == 0:
        return f"0 of {n} runs: rate < {zero_events_bound(n, confidence):.3g} ({confidence:.0%} one-sided)"
    e = proportion_ci(k, n, confidence)
    return f"{k} of {n} runs: rate {e.value:.3g} [{e.ci_low:.3g}, {e.ci_high:.3g}] ({confidence:.0%} Clopper-Pearson)"
