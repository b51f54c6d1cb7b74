"""Reading a measured value for a rule: a number, an estimate or its dict as an :class:`~tvtrack.montecarlo.Estimate`,
widened to its nominal coverage where its helper falls short (:func:`calibrated`), whether it can decide anything
(:func:`is_undecided`), and the runs projected to move a band edge out of its interval (:func:`runs_to_decide`).
:mod:`tvtrack.verdicts` decides with them and re-exports the public ones."""

from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

from .estimate import Estimate

__all__ = [
    "as_estimate",
    "calibrated",
    "is_undecided",
    "runs_to_decide",
    "with_lost_runs",
    "lost_runs",
    "interval_of",
    "why_undecided",
    "short_number",
    "show_estimate",
    "decide_note",
    "ends_to_decide",
    "record_end",
    "is_envelope",
    "why_no_runs",
    "fold_about",
]


def with_lost_runs(value: Any, in_lock: Any, lost: int, runs: int) -> dict:
    """A measured value over runs some of which lost lock or diverged: ``{"value": over every run, "in lock": over
    the runs in lock, "lost": runs that lost lock, "runs": every run}``. A rule judges ``value`` (:func:`as_estimate`
    reads it); the label records the share lost and the verdict on ``in lock`` beside it
    (:func:`tvtrack.labels.label_parts`); replicates pool ``value`` and ``in lock`` as estimates, ``lost`` and
    ``runs`` as counts (:func:`tvtrack.pooling.pool`).

    Parameters
    ----------
    value, in_lock : Estimate, its dict or a number
        The quantity over every run, and over the runs that kept lock (same unit).
    lost, runs : int
        Runs that lost lock or diverged, and all runs (``0 <= lost <= runs``, ``runs >= 1``).
    """
    lost, runs = int(lost), int(runs)
    if runs < 1 or not 0 <= lost <= runs:
        raise ValueError(f"with_lost_runs: lost {lost} of runs {runs}: need 0 <= lost <= runs and runs >= 1")
    return {"value": value, "in lock": in_lock, "lost": lost, "runs": runs}


def lost_runs(measured: Any) -> dict | None:
    """The ``{"in lock", "lost", "runs"}`` of a measured value built by :func:`with_lost_runs`, else None."""
    if isinstance(measured, Mapping) and {"value", "in lock", "lost", "runs"} <= set(measured):
        return {k: measured[k] for k in ("in lock", "lost", "runs")}
    return None


#: The words :func:`tvtrack.results.to_jsonable` writes beside a null for an infinite end, and what they read back as.
_OPEN_ENDS = {"+inf": math.inf, "-inf": -math.inf}


def record_end(d: Mapping, key: str) -> Any:
    """An interval end (``key``: ``"ci_low"``, ``"ci_high"``) of an estimate as a record holds it: the infinity
    its ``infinite`` marker names where JSON wrote null (:func:`tvtrack.results.to_jsonable`), else what is there."""
    return _OPEN_ENDS.get((d.get("infinite") or {}).get(key), d.get(key))


def as_estimate(measured: Any) -> Estimate:
    """An :class:`Estimate` from an estimate, an estimate dict or a plain number (a number is
    exact: a deterministic computation, its interval the point itself)."""
    if isinstance(measured, Estimate):
        return measured
    if lost_runs(measured) is not None:  # a value over runs some of which lost lock: the rule judges every run
        return as_estimate(measured["value"])
    if isinstance(measured, Mapping) and "value" in measured:
        fields = {
            k: measured[k]
            for k in ("value", "stderr", "ci_low", "ci_high", "n", "confidence", "method", "extrapolated")
            + ("sampling_low", "sampling_high")
            if k in measured
        }
        fields = {
            k: (float("nan") if v is None and k not in ("method", "extrapolated") else v) for k, v in fields.items()
        }
        for k, sign in (measured.get("infinite") or {}).items():  # an open end JSON wrote as null
            if k in fields and sign in _OPEN_ENDS:  # another word is no marker: the null stays NaN
                fields[k] = _OPEN_ENDS[sign]
        fields["extrapolated"] = bool(fields.get("extrapolated") or False)
        if measured.get("signed") is not None:  # a fold distance keeps the signed ratio it was folded from
            fields["signed"] = as_estimate(measured["signed"])
            fields["fold_reference"] = float(measured["fold_reference"])
        return Estimate(**{"stderr": float("nan"), "n": 1, **fields})
    if isinstance(measured, (int, float)) or hasattr(measured, "__float__"):
        v = float(measured)
        return Estimate(v, 0.0, v, v, 1, 0.95, "exact")
    raise TypeError(f"cannot read a measured value from {type(measured).__name__}: {measured!r}")


def fold_about(ratio: Any, reference: float = 1.0) -> Estimate:
    """A positive ratio's fold distance from ``reference`` either way, ``k max(q / k, k / q)`` (``q`` itself for
    ``q >= k``, ``k^2 / q`` below it): a two-sided rule ("depends on", "about k") is one band on one number.

    The interval maps end by end; one that holds ``k`` starts at ``k`` (no measurable distance); a bound ``[0, b]``
    certifies a distance of at least ``fold(b)``; an infinite value (``q = 0``) reads its interval's near end. The
    standard error is the ratio's above ``k`` and ``k^2 / q^2`` times it below (the delta method). A ratio's
    resolution allowance does not map end by end through the fold: the result has no sampling interval.

    The ratio is first widened to its nominal coverage where its helper falls short (:func:`calibrated`). The result
    keeps that signed ratio (``signed``, ``fold_reference``): replicates pool the signed ratios and fold the pool
    (:func:`tvtrack.pooling.pool`). Folded first, a ratio of no change scattering either side of ``k`` would pool as
    a distance from it. A change to a fold distance belongs on its signed ratio, folded again: the pool reads only
    ``signed``.

    Parameters
    ----------
    ratio : Estimate, its dict or a number
        The signed ratio (positive), with its interval.
    reference : float
        The ratio of no change (``1`` for a dependence whose direction is not stated).
    """
    k = float(reference)
    if not (math.isfinite(k) and k > 0):
        raise ValueError(f"fold_about: parameter 'reference' = {reference!r}: a positive ratio of no change")
    e = calibrated(ratio)  # widened where its helper falls short, before the fold (after it, an end could cross k)
    q, a, b = e.value, e.ci_low, e.ci_high

    def fold(r: float) -> float:
        return r if r >= k else (k * k / r if r > 0 else math.inf)

    method = (
        f"{e.method}; fold distance from {k:g} either way, max(q, {k * k:g}/q), of the signed ratio "
        f"q = {q:.4g} [{a:.4g}, {b:.4g}]"
    )
    nan = math.nan
    if math.isnan(q) or math.isnan(a) or math.isnan(b):
        return Estimate(nan, nan, nan, nan, e.n, e.confidence, method, e.extrapolated, signed=e, fold_reference=k)
    low, high = sorted((fold(a), fold(b)))
    value = fold(q)
    stderr = e.stderr if q >= k else (e.stderr * (k / q) ** 2 if q > 0 else nan)
    return Estimate(
        value if math.isfinite(value) else low,
        stderr,
        k if a < k < b else low,
        high,
        e.n,
        e.confidence,
        method,
        e.extrapolated,
        signed=e,
        fold_reference=k,
    )


def _is_exact(e: Estimate) -> bool:
    return e.method == "exact"


def calibrated(measured: Any, difference: bool = False) -> Estimate:
    """The estimate a rule decides on: an interval whose helper states a measured coverage short of its
    nominal level at this sample size (:func:`tvtrack.montecarlo.coverage_reached`) is widened to it
    (:func:`tvtrack.montecarlo.widen_to_nominal`, on the linear scale for a ``difference``; the method says so);
    others are returned as they are."""
    from .coverage import coverage_reached, stated_coverage, widen_to_nominal

    e = as_estimate(measured)
    s = stated_coverage(e)
    if math.isfinite(s) and not coverage_reached(e):
        return widen_to_nominal(e, difference=difference)
    return e


def is_undecided(measured: Any) -> bool:
    """True when an estimate cannot decide anything: NaN value, NaN interval or a degenerate interval
    (``ci_low == ci_high``) of a random quantity, a value extrapolated beyond the data, or an interval
    whose coverage at its sample size was never measured ("coverage unmeasured")."""
    from .coverage import stated_coverage

    e = as_estimate(measured)
    if getattr(e, "extrapolated", False) or math.isnan(e.value):
        return True
    if not _is_exact(e) and math.isnan(stated_coverage(e)):
        return True
    if _is_exact(e):
        return False
    a, b = e.ci_low, e.ci_high
    if math.isnan(a) or math.isnan(b):
        return True
    return a == b


def interval_of(e: Estimate) -> tuple[float, float]:
    """The interval a rule judges.

    Parameters
    ----------
    e : Estimate
        A measured value (in its own unit).

    Returns
    -------
    tuple of float
        ``(low, high)`` in the estimate's unit: its interval, or the point itself for an exact number whose
        interval is NaN.
    """
    if _is_exact(e) and (math.isnan(e.ci_low) or math.isnan(e.ci_high)):
        return e.value, e.value
    return e.ci_low, e.ci_high


def why_undecided(e: Estimate) -> str:
    """Why an undecided estimate (:func:`is_undecided`) cannot decide a rule, in words for a verdict's reason.

    Parameters
    ----------
    e : Estimate
        An estimate :func:`is_undecided` holds undecided.

    Returns
    -------
    str
        One clause: extrapolated, not measured, coverage unmeasured, or an undefined or degenerate interval.
    """
    if getattr(e, "extrapolated", False):
        return "extrapolated beyond the data"
    if math.isnan(e.value):
        return "not measured (NaN)"
    if "coverage unmeasured" in (e.method or ""):
        return "its interval's coverage at this sample size is unmeasured"
    return "its interval is undefined or degenerate"


def short_number(x: float) -> str:
    """A number as a verdict's words show it: four significant digits (``format(x, ".4g")``), unit-free."""
    return f"{x:.4g}"


def show_estimate(e: Estimate, unit: str = "") -> str:
    """An estimate in a verdict's words: ``"value [low, high] unit"``, or the bare value for an exact number.

    Parameters
    ----------
    e : Estimate
        The measured value.
    unit : str
        Its unit, appended after the numbers (none when empty).

    Returns
    -------
    str
        The value and its interval (:func:`interval_of`) with :func:`short_number`, and a note when the interval
        was widened to its nominal coverage, or to the spread of replicates that disagree.
    """
    a, b = interval_of(e)
    u = f" {unit}" if unit else ""
    if math.isnan(a) or math.isnan(b) or a == b == e.value:
        return f"{short_number(e.value)}{u}"
    m = e.method or ""
    how = [w for w, tag in ((WIDE_NOMINAL, "; widened x"), (WIDE_SPREAD, "widened to Student's t")) if tag in m]
    widened = f" (interval widened {' and '.join(how)})" if how else ""
    return f"{short_number(e.value)} [{short_number(a)}, {short_number(b)}]{u}{widened}"


#: :func:`show_estimate`'s note for an interval :func:`tvtrack.coverage.widen_to_nominal` widened.
WIDE_NOMINAL = "to its nominal coverage"
#: Its note for a pool of replicates that disagree beyond their own intervals (:mod:`tvtrack.pooling`).
WIDE_SPREAD = "to the replicates' spread, since they disagree"


def _zero_count(e: Estimate) -> bool:
    """A rate from direct counts with zero (or all) events: its interval is the one-sided bound they certify."""
    m = e.method or ""
    counted = "Clopper" in m or m.startswith("count")
    return counted and e.n > 0 and ((e.value == 0.0 and e.ci_low == 0.0) or (e.value == 1.0 and e.ci_high == 1.0))


def runs_to_decide(e: Estimate, edges: Sequence[float]) -> float:
    """The multiple of the runs behind ``e`` projected to move every band edge in ``edges`` that its interval
    straddles out of the interval.

    An interval's half-width shrinks as ``1/sqrt(n)``: an edge at distance ``d`` from the point, with the
    half-width ``h`` on that side, leaves the interval at about ``(h / d)^2`` times the runs (a projection: the
    explorer re-judges after every added replicate), with ``d`` and ``h`` on the log scale for a pool made there
    (:func:`tvtrack.pooling.pool`: its interval shrinks about the log of its value); of an interval that holds a
    resolution allowance ``a`` on that side (``Estimate.sampling_low``/``sampling_high``) only the sampling part
    shrinks: ``((h - a) / (d - a))^2``, and an edge within the allowance is never left (``inf``). Zero events in ``n`` runs certify
    ``p <= 1 - alpha^(1/n)``: an upper edge ``L`` is certified at ``n = ln(alpha) / ln(1 - L)`` runs of zero
    events (29 for ``L = 0.1`` at 95 %), and all events likewise for a lower edge. Returns ``inf`` when the
    point sits on an edge, the interval is undefined or is an envelope of certified bounds (:func:`is_envelope`:
    more replicates only widen it), ``1.0`` when nothing is straddled.
    """
    a, b = interval_of(e)
    v = e.value
    inside = [c for c in edges if c is not None and math.isfinite(c) and a < c < b]
    if not inside:
        return 1.0
    if any(math.isnan(x) for x in (a, b, v)) or is_envelope(e):
        return math.inf
    if _zero_count(e):
        alpha = 1.0 - e.confidence
        need = []
        for c in inside:
            p = c if v == 0.0 else 1.0 - c  # the rate (or its complement) the bound must certify
            if not 0.0 < p < 1.0:
                return math.inf
            need.append(math.log(alpha) / math.log(1.0 - p))
        return max(need) / e.n
    sa, sb = _sampling_ends(e)
    if _on_log_scale(e):  # a pool on the log scale shrinks there (every edge inside is then positive)
        a, b, v, sa, sb = (math.log(x) for x in (a, b, v, sa, sb))
        inside = [math.log(c) for c in inside]
    factors = []
    for c in inside:
        d = abs(v - c)
        h = (b - v) if c > v else (v - a)
        if not math.isfinite(h):  # an unbounded side: no projection from its width
            return math.inf
        allowance = (b - sb) if c > v else (sa - a)  # a resolution allowance: no number of runs shrinks it
        if d <= allowance or d == 0.0:
            return math.inf
        factors.append(((h - allowance) / (d - allowance)) ** 2)
    return max(factors)


def is_envelope(e: Estimate) -> bool:
    """Whether ``e`` is the envelope of replicates' intervals that :func:`tvtrack.pooling.pool` makes where some are
    certified one-sided bounds: its ends are the widest replicate's, so adding replicates never narrows it."""
    return str(getattr(e, "method", "") or "").startswith("envelope of")


def why_no_runs(e: Estimate, edges: Sequence[float]) -> str:
    """Why :func:`runs_to_decide` projects no number of runs for ``e`` against the straddled ``edges``: the words
    :func:`decide_note` puts in brackets."""
    a, b = interval_of(e)
    if any(math.isnan(x) for x in (a, b, e.value)):
        return "the interval is undefined"
    if is_envelope(e):
        return "an envelope of the replicates' certified bounds, which more replicates do not narrow"
    if any(c is not None and c == e.value for c in edges):
        return "the point sits on the edge"
    if not (math.isfinite(a) and math.isfinite(b)):
        return "the interval is unbounded on a side it straddles an edge"
    if e.has_allowance:
        return "the edge lies within the resolution of the grid it is read on, which more runs do not shrink"
    return ""


def ends_to_decide(e0: Estimate, e1: Estimate, tolerance: float = 0.0) -> tuple[float, str]:
    """Runs projected to separate a trend's end intervals by more than ``tolerance``, at least 1.

    On the two facing sides (the first end's side towards the last and the last's towards the first) each end's
    sampling part, from its value to its sampling interval's end (``Estimate.sampling_low`` / ``sampling_high``;
    the interval's end where there is no allowance), shrinks as ``1/sqrt(n)`` and its resolution allowance beyond
    it stays (as in :func:`runs_to_decide`), on the log scale for a pool made there (:func:`tvtrack.pooling.pool`:
    its interval and its allowance are multiplicative). The projection is the multiple ``f`` at which the facing
    ends are ``tolerance`` apart; on the linear scale ``f = (s / (|v1 - v0| - tolerance - a))^2`` with ``s`` the
    sum of the facing sampling parts and ``a`` of the facing allowances. Where no number of runs would separate
    them, why: an end is an envelope of certified bounds (:func:`is_envelope`), the ends are not apart beyond
    ``tolerance``, or beyond their allowances, or an end is unbounded."""
    if is_envelope(e0) or is_envelope(e1):
        return (
            math.inf,
            "an end is an envelope of the replicates' certified bounds, which more replicates do not narrow",
        )
    up = e1.value >= e0.value
    facing = ((e0, "high"), (e1, "low")) if up else ((e0, "low"), (e1, "high"))
    if not all(math.isfinite(x) for e, side in facing for x in _side(e, side)):
        return math.inf, "an end's interval is unbounded"

    def gap(t: float) -> float:
        """How far the facing ends lie apart beyond ``tolerance`` at ``1 / t^2`` times the runs."""
        (x0, x1) = (_end_at(e, side, t) for e, side in facing)
        return (x1 - x0 if up else x0 - x1) - tolerance

    if not gap(0.0) > 0:  # at any number of runs the facing ends are the values, moved by their allowances
        if abs(e1.value - e0.value) - tolerance > 0:
            return (
                math.inf,
                "the ends lie within the resolution of the grid they are read on, which more runs do not shrink",
            )
        return math.inf, "the ends' values are not apart by more than the flat tolerance"
    if gap(1.0) >= 0:
        return 1.0, ""
    return _solve_factor(gap), ""


def _solve_factor(gap) -> float:
    """The multiple ``f = 1 / t^2`` of the runs at which ``gap(t)``, positive at ``t = 0`` and negative at ``t = 1``
    and falling between, is 0; solved for ``log t``, so that a root far below 1 (ends apart by a rounding margin)
    keeps its relative precision."""
    from scipy.optimize import brentq  # here: scipy.optimize costs every process that reads a record a second

    low = -1.0
    while not gap(math.exp(low)) > 0:
        low *= 2.0
        if low < -700.0:  # the ends are apart by less than a rounding step beyond the tolerance
            return math.inf
    u = brentq(lambda u: gap(math.exp(u)), low, 0.0, xtol=1e-13, rtol=1e-13)
    return max(math.exp(-2.0 * u), 1.0)


def _sampling_ends(e: Estimate) -> tuple[float, float]:
    """``e``'s sampling interval, the part that more runs shrink: without a resolution allowance its interval."""
    return (e.sampling_low, e.sampling_high) if e.has_allowance else interval_of(e)


def _side(e: Estimate, side: str) -> tuple[float, float]:
    """``(sampling end, interval end)`` of ``e`` on ``side`` ("low" or "high")."""
    (sa, sb), (a, b) = _sampling_ends(e), interval_of(e)
    return (sa, a) if side == "low" else (sb, b)


def _on_log_scale(e: Estimate) -> bool:
    """Whether ``e`` is a pool made on the log scale (:func:`tvtrack.pooling.pool`), its interval positive (its
    sampling interval and value, within it, are then too), so that it shrinks about the log of its value."""
    return "log scale" in (e.method or "") and interval_of(e)[0] > 0.0  # a record's method may be null


def _end_at(e: Estimate, side: str, t: float) -> float:
    """Where ``e``'s interval ends on ``side`` ("low" or "high") once its sampling part is ``t`` times as wide
    (``t = 1/sqrt(f)`` at ``f`` times the runs), its resolution allowance kept: on the log scale for a log-scale
    pool (:func:`_on_log_scale`); a rate of zero (or all) events by the bound they certify, ``1 - alpha^(1/n)``
    at ``n`` runs, as :func:`runs_to_decide` projects it."""
    if _zero_count(e) and (side == "high") == (e.value == 0.0):
        bound = -math.expm1(t * t * math.log(1.0 - e.confidence) / e.n)  # 1 - alpha^(t^2 / n): the rate at n / t^2
        return bound if e.value == 0.0 else 1.0 - bound
    s, c = _side(e, side)
    if _on_log_scale(e):
        return e.value * (s / e.value) ** t * (c / s)
    return e.value + t * (s - e.value) + (c - s)


def decide_note(factor: float, why: str = "") -> str:
    """The words of a verdict that a straddled band edge leaves undecided.

    Parameters
    ----------
    factor : float
        The multiple of the runs projected to decide it (:func:`runs_to_decide`; ``inf`` when none would).
    why : str
        Why none would, where ``factor`` is not finite (:func:`why_no_runs`); said in brackets.

    Returns
    -------
    str
        ``"about F times the runs are projected to decide it"``, or that no number of runs is, and why.
    """
    if not math.isfinite(factor):
        return "no number of runs is projected to decide it" + (f" ({why})" if why else "")
    return f"about {factor:.2g} times the runs are projected to decide it"
