"""Acceptance rules as code.

A rule renders its own acceptance text and decides the verdict from measured estimates with
their intervals, so the text and the decision cannot disagree. Notebooks never type a verdict:
they pass a rule and the measured value to :meth:`tvtrack.results.Results.claim`.

Conventions (docs/verdicts.md):

- Where the paper gives a value, the rule is two-sided (:class:`InBand`, :class:`WithinFactor`).
  A measured value wholly beyond the paper's band is ``not reproduced`` even on the side the paper
  would call *better* (the claim's number is not what the run shows); the decision says so.
- A claim true by construction of the model is :class:`NotCheckable`, with the reason.
- A difference claimed without uncertainty is no evidence: orderings are decided by the interval
  of a paired difference or ratio (:class:`Ordering`), trends by the intervals along the curve
  (:class:`Monotone`).
- **Decided by the data, not the run size.** An interval that straddles a band edge (or contains an
  ordering's reference, or a trend that nothing along the grid resolves) is ``undecided``, never
  ``partly``: the judgement carries ``runs_factor``, the multiple of the current runs projected to
  decide it (:func:`runs_to_decide`), so the explorer can size the run. ``partly`` is only an
  :class:`AllOf` whose decided parts disagree.
- Undecided is also a verdict input: a NaN value, a NaN or degenerate interval of a random quantity, or
  an extrapolated estimate (``Estimate.extrapolated``) is ``undecided`` and never decides a claim.

Labels (:mod:`tvtrack.labels`) say how the verdict holds over the register and the replicates.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

from .estimate import Estimate
from .run_words import part_name
from .measured import (  # re-exported: tvtrack.verdicts.as_estimate, calibrated, is_undecided, runs_to_decide
    decide_note,
    ends_to_decide,
    why_no_runs,
    short_number,
    interval_of,
    show_estimate,
    why_undecided,
    as_estimate,
    calibrated,
    is_undecided,
    runs_to_decide,
)

__all__ = [
    "VERDICTS",
    "LABELS",
    "NOT_MEASURED",
    "as_estimate",
    "calibrated",
    "is_undecided",
    "Judgement",
    "Rule",
    "InBand",
    "WithinFactor",
    "Ordering",
    "Monotone",
    "AllOf",
    "NotCheckable",
    "ByReading",
    "for_config",
    "synthetic",
    "DECISIVE",
    "is_decisive",
    "runs_to_decide",
]

#: The only verdicts a claim may carry.
VERDICTS = ("reproduced", "partly", "not reproduced", "undecided", "not checkable")
#: Verdicts that decide a part: a condition can flip a part only from one of these to the other.
DECISIVE = ("reproduced", "not reproduced")
#: Robustness labels, weakest first (docs/verdicts.md defines each in a sentence).
LABELS = ("unstable", "depends", "limited", "unexplored", "robust")


def is_decisive(verdict: str) -> bool:
    """True for ``reproduced`` and ``not reproduced`` (and a claim's ``partly``: its decided parts disagree)."""
    return verdict in DECISIVE or verdict == "partly"


@dataclass(frozen=True)
class Judgement:
    """A rule's decision: the verdict, one sentence why, whether more data could change it
    (``settled`` is False for ``undecided``) and, for an interval that straddles a band edge,
    ``runs_factor``: the multiple of the runs behind the estimate projected to decide it
    (:func:`runs_to_decide`; ``inf`` where no number of runs is projected to, e.g. a value on the edge or
    an undefined interval; ``1.0`` for a decided verdict)."""

    verdict: str
    why: str
    settled: bool = True
    runs_factor: float = 1.0


#: A part whose value the measurement left out (``None``): undecided, and no number of runs decides it.
NOT_MEASURED = Judgement("undecided", "not measured", False, math.inf)


class Rule(ABC):
    """An acceptance rule: renders its text and decides a verdict from a measured value."""

    kind = "rule"

    @abstractmethod
    def text(self) -> str:
        """The acceptance criterion in words, with its numbers."""

    def decide(self, measured: Any) -> str:
        """One of :data:`VERDICTS`."""
        return self.judge(measured).verdict

    def explain(self, measured: Any) -> tuple[str, str]:
        """``(verdict, one sentence saying why, with the numbers)``."""
        j = self.judge(measured)
        return j.verdict, j.why

    @abstractmethod
    def judge(self, measured: Any) -> Judgement:
        """The :class:`Judgement` of ``measured``."""

    def params(self) -> dict:
        return {}

    def to_dict(self) -> dict:
        return {"kind": self.kind, "text": self.text(), **self.params()}


@dataclass(frozen=True)
class InBand(Rule):
    """The quantity lies in ``[low, high]`` (either end may be open).

    ``reproduced`` when the whole interval lies inside, ``not reproduced`` when it lies wholly
    outside, ``undecided`` when it straddles an end (with the runs projected to decide it). With
    ``better`` set, an interval wholly beyond the band on that side is still ``not reproduced``, and the
    decision says it is better than the paper's number.

    Parameters
    ----------
    quantity : str
        What is measured, in words.
    low, high : float or None
        The band's ends.
    unit : str
    better : {"lower", "higher", None}
        Which side the paper would call better, for a two-sided band.
    """

    quantity: str
    low: float | None = None
    high: float | None = None
    unit: str = ""
    better: str | None = None
    kind = "in_band"

    def __post_init__(self):
        if self.low is None and self.high is None:
            raise ValueError("InBand needs low, high or both")
        if self.low is not None and self.high is not None and self.low > self.high:
            raise ValueError(f"InBand: low {self.low} > high {self.high}")
        if self.better not in (None, "lower", "higher"):
            raise ValueError(f"InBand: better {self.better!r} must be 'lower', 'higher' or None")

    def _band(self) -> str:
        u = f" {self.unit}" if self.unit else ""
        if self.low is None:
            return f"at most {short_number(self.high)}{u}"
        if self.high is None:
            return f"at least {short_number(self.low)}{u}"
        return f"in [{short_number(self.low)}, {short_number(self.high)}]{u}"

    def text(self) -> str:
        t = (
            f"{self.quantity} {self._band()}: reproduced if the whole 95 % interval lies inside, not reproduced "
            f"if it lies wholly outside, undecided if it straddles a bound"
        )
        if self.better is not None:
            t += (
                f" (wholly {'below' if self.better == 'lower' else 'above'} the band is better than the paper's "
                f"number, and still not the paper's number)"
            )
        return t

    def params(self) -> dict:
        return {"quantity": self.quantity, "low": self.low, "high": self.high, "unit": self.unit, "better": self.better}

    def judge(self, measured):
        e = calibrated(measured)
        m = show_estimate(e, self.unit)
        if is_undecided(e):
            return Judgement("undecided", f"{self.quantity} = {m}: {why_undecided(e)}, so it cannot decide", False)
        a, b = interval_of(e)
        lo = -math.inf if self.low is None else self.low
        hi = math.inf if self.high is None else self.high
        if lo <= a and b <= hi:
            return Judgement("reproduced", f"{self.quantity} = {m} lies {self._band()}")
        below, above = b < lo, a > hi
        if below or above:
            side = "below" if below else "above"
            better = (below and self.better == "lower") or (above and self.better == "higher")
            return Judgement(
                "not reproduced",
                f"{self.quantity} = {m} lies wholly {side} the band ({self._band()})"
                + (": better than the paper's number, but not the paper's number" if better else ""),
            )
        f = runs_to_decide(e, (self.low, self.high))
        why = why_no_runs(e, (self.low, self.high))
        return Judgement(
            "undecided",
            f"{self.quantity} = {m} straddles a bound of the band ({self._band()}): {decide_note(f, why)}",
            False,
            f,
        )


@dataclass(frozen=True)
class WithinFactor(InBand):
    """The quantity is within a factor of the paper's value: the band ``[v / f, v f]``."""

    quantity: str = ""
    paper_value: float = 1.0
    factor: float = 2.0
    kind = "within_factor"

    def __init__(self, quantity: str, paper_value: float, factor: float, unit: str = "", better: str | None = None):
        if not (paper_value > 0 and factor >= 1):
            raise ValueError(f"WithinFactor needs paper_value > 0 and factor >= 1, got {paper_value}, {factor}")
        object.__setattr__(self, "paper_value", float(paper_value))
        object.__setattr__(self, "factor", float(factor))
        InBand.__init__(self, quantity, paper_value / factor, paper_value * factor, unit, better)

    def _band(self) -> str:
        u = f" {self.unit}" if self.unit else ""
        return (
            f"within a factor {short_number(self.factor)} of the paper's {short_number(self.paper_value)}{u} "
            f"([{short_number(self.low)}, {short_number(self.high)}])"
        )

    def params(self) -> dict:
        return {**super().params(), "paper_value": self.paper_value, "factor": self.factor}


@dataclass(frozen=True)
class Ordering(Rule):
    """``a`` is greater (or smaller) than ``b``, decided by the interval of their paired
    difference ``a - b`` (reference 0) or ratio ``a / b`` (reference 1).

    ``reproduced`` when the interval lies wholly on the claimed side, ``not reproduced`` when it
    lies wholly on the other, ``undecided`` when it contains the reference (no measurable difference at
    this size; ``runs_factor`` projects the runs that would resolve the measured one).
    """

    a: str
    b: str
    relation: str = ">"
    measure: str = "difference"
    paired: bool = True
    unit: str = ""
    kind = "ordering"

    def __post_init__(self):
        if self.relation not in (">", "<"):
            raise ValueError(f"Ordering: relation {self.relation!r} must be '>' or '<'")
        if self.measure not in ("difference", "ratio"):
            raise ValueError(f"Ordering: measure {self.measure!r} must be 'difference' or 'ratio'")

    @property
    def reference(self) -> float:
        return 0.0 if self.measure == "difference" else 1.0

    def _what(self) -> str:
        return f"{self.a} - {self.b}" if self.measure == "difference" else f"{self.a} / {self.b}"

    def text(self) -> str:
        side = "above" if self.relation == ">" else "below"
        how = "paired" if self.paired else "unpaired (independent samples)"
        return (
            f"{self.a} {self.relation} {self.b}, judged on the {how} {self.measure} {self._what()}: reproduced "
            f"if its 95 % interval lies wholly {side} {short_number(self.reference)}, not reproduced if wholly on the "
            f"other side, undecided if it contains {short_number(self.reference)}"
        )

    @property
    def quantity(self) -> str:
        """The quantity decided on, in words."""
        if self.measure == "ratio":
            return f"ratio of {self.a} to {self.b}"
        return f"difference {self.a} minus {self.b}" + (f" ({self.unit})" if self.unit else "")

    def params(self) -> dict:
        return {
            "a": self.a,
            "b": self.b,
            "relation": self.relation,
            "measure": self.measure,
            "paired": self.paired,
            "quantity": self.quantity,
            "unit": self.unit if self.measure == "difference" else f"ratio of {self.a} to {self.b}",
        }

    def judge(self, measured):
        e = calibrated(measured)
        m = f"{self._what()} = {show_estimate(e)}"
        if is_undecided(e):
            return Judgement("undecided", f"{m}: {why_undecided(e)}, so it cannot decide", False)
        lo, hi = interval_of(e)
        r = self.reference
        claimed_side = lo > r if self.relation == ">" else hi < r
        other_side = hi < r if self.relation == ">" else lo > r
        if claimed_side:
            return Judgement("reproduced", f"{m}: {self.a} {self.relation} {self.b}")
        if other_side:
            return Judgement("not reproduced", f"{m}: the opposite ordering holds")
        f = runs_to_decide(e, (r,))
        note = decide_note(f, why_no_runs(e, (r,)))
        return Judgement("undecided", f"{m} contains {short_number(r)}: no measurable difference yet; {note}", False, f)


@dataclass(frozen=True)
class Monotone(Rule):
    """The quantity increases (or decreases) along a grid, judged on the intervals.

    Steps between neighbours support the trend when their intervals are separated in its direction
    by more than ``tolerance`` and contradict it when separated the other way by more than it.
    ``reproduced``: first and last points separated in the claimed direction and no step contradicts;
    ``not reproduced``: the ends separated the other way, or some step measurably against the trend
    (the curve is decisively not monotone); ``undecided``: nothing resolves the trend either way (no
    measurable trend is not evidence against it), with the runs projected to separate the ends.

    Parameters
    ----------
    quantity, over : str
        What is measured and along what, in words.
    direction : {"increasing", "decreasing"}
    unit : str
    tolerance : float
        Separations of at most this size (in ``unit``) count as flat: for deterministic curves, where
        a rounding-level wiggle is not a trend (state why in the claim's note).
    """

    quantity: str
    over: str
    direction: str = "increasing"
    unit: str = ""
    tolerance: float = 0.0
    kind = "monotone"

    def __post_init__(self):
        if self.direction not in ("increasing", "decreasing"):
            raise ValueError(f"Monotone: direction {self.direction!r} must be 'increasing' or 'decreasing'")
        if not self.tolerance >= 0:
            raise ValueError(f"Monotone: tolerance {self.tolerance!r} must be >= 0")

    def text(self) -> str:
        tol = (
            f" by more than {short_number(self.tolerance)}{' ' + self.unit if self.unit else ''}"
            if self.tolerance
            else ""
        )
        return (
            f"{self.quantity} is {self.direction} in {self.over}: reproduced if the first and last 95 % intervals "
            f"are separated{tol} in that direction and no neighbouring pair is separated the other way; not "
            f"reproduced if the ends, or any neighbouring pair, are separated against the trend; undecided if "
            f"nothing along the grid resolves the trend"
        )

    def params(self) -> dict:
        return {
            "quantity": self.quantity,
            "over": self.over,
            "direction": self.direction,
            "unit": self.unit,
            "tolerance": self.tolerance,
        }

    def _sep(self, e0: Estimate, e1: Estimate) -> int:
        """+1 when ``e1`` is measurably beyond ``e0`` in the claimed direction, -1 the other way, 0 else."""
        a0, b0 = interval_of(e0)
        a1, b1 = interval_of(e1)
        up = a1 - b0 > self.tolerance
        down = a0 - b1 > self.tolerance
        s = 1 if up else (-1 if down else 0)
        return s if self.direction == "increasing" else -s

    def _ends_factor(self, e0: Estimate, e1: Estimate) -> float:
        """Runs projected to separate the end intervals (:func:`tvtrack.measured.ends_to_decide`)."""
        return ends_to_decide(e0, e1, self.tolerance)[0]

    def judge(self, measured: Sequence):
        es = [calibrated(m) for m in measured]
        if len(es) < 2:
            raise ValueError("Monotone needs at least two points")
        bad = [i for i, e in enumerate(es) if is_undecided(e)]
        if bad and (0 in bad or len(es) - 1 in bad or len(es) - len(bad) < 2):
            return Judgement(
                "undecided",
                f"{self.quantity}: points {bad} along {self.over} are undecided (NaN, "
                f"degenerate or extrapolated), so the trend cannot be decided",
                False,
                math.inf,
            )
        keep = [e for i, e in enumerate(es) if i not in bad]
        steps = [self._sep(x, y) for x, y in zip(keep[:-1], keep[1:])]
        ends = self._sep(keep[0], keep[-1])
        up, down = steps.count(1), steps.count(-1)
        u = f" {self.unit}" if self.unit else ""
        m = (
            f"{self.quantity}: {show_estimate(keep[0])}{u} at the first point, {show_estimate(keep[-1])}{u} at the last; "
            f"{up} of {len(steps)} steps measurably {self.direction}, {down} the other way"
            + (f" ({len(bad)} undecided points left out)" if bad else "")
        )
        if ends == -1:
            return Judgement("not reproduced", m + " (the ends go against the trend)")
        if down:
            return Judgement("not reproduced", m + " (measurably not monotone)")
        if ends == 1:
            return Judgement("reproduced", m)
        f, why = ends_to_decide(keep[0], keep[-1], self.tolerance)
        return Judgement("undecided", m + f" (no measurable trend yet; {decide_note(f, why)})", False, f)


@dataclass(frozen=True)
class AllOf(Rule):
    """Every part of a composite claim, each by its own rule: ``reproduced`` when all parts are,
    ``not reproduced`` when all decided parts are not, ``partly`` only when decided parts disagree,
    ``undecided`` when the decided parts agree but some part is undecided (it could still go either
    way) -- a part too small to decide never makes a claim ``partly``. A checkable part measured as ``None``
    (left out by the measurement) is undecided (:data:`NOT_MEASURED`); a :class:`NotCheckable` part needs no
    value."""

    parts: Mapping[str, Rule] = field(default_factory=dict)
    kind = "all_of"

    def __post_init__(self):
        if not self.parts:
            raise ValueError("AllOf needs at least one part")

    def text(self) -> str:
        return "all of: " + "; ".join(f"({part_name(name)}) {rule.text()}" for name, rule in self.parts.items())

    def params(self) -> dict:
        return {"parts": {name: rule.to_dict() for name, rule in self.parts.items()}}

    def judge(self, measured: Mapping):
        missing = [name for name in self.parts if name not in measured]
        if missing:
            raise ValueError(f"AllOf: measured lacks the parts {missing}")
        decided = {
            name: NOT_MEASURED
            if measured[name] is None and not isinstance(rule, NotCheckable)
            else rule.judge(measured[name])
            for name, rule in self.parts.items()
        }
        checked = {n: j for n, j in decided.items() if j.verdict != "not checkable"}
        why = "; ".join(f"({part_name(name)}) {j.verdict}: {j.why}" for name, j in decided.items())
        if not checked:
            return Judgement("not checkable", why)
        firm = {j.verdict for j in checked.values() if j.verdict != "undecided"}
        open_ = [j for j in checked.values() if j.verdict == "undecided"]
        if "partly" in firm or len(firm) > 1:
            return Judgement("partly", why, not open_)
        if open_:
            return Judgement("undecided", why, False, max(j.runs_factor for j in open_))
        return Judgement(firm.pop(), why)


@dataclass(frozen=True)
class NotCheckable(Rule):
    """A claim this project cannot check (true by construction of the model, or needing data the
    paper does not give): the reason is the text."""

    reason: str
    kind = "not_checkable"

    def text(self) -> str:
        return f"not checkable: {self.reason}"

    def params(self) -> dict:
        return {"reason": self.reason}

    def judge(self, measured):
        return Judgement("not checkable", self.reason)


@dataclass(frozen=True)
class ByReading(Rule):
    """A claim whose criterion changes with a reading of the paper: the rule in force is the one of the
    reading the measurement was made under, so no reading is judged by another reading's rule.

    The measurement function returns ``{"reading": value, "measured": ...}`` (:meth:`tag`), naming the value of
    ``entry`` it measured under; a value without a rule of its own is judged by ``default``.

    Parameters
    ----------
    entry : str
        The register entry whose value selects the rule.
    rules : mapping value -> Rule
    default : Rule
        The rule of every other value (the default reading's).
    """

    entry: str
    rules: Mapping[Any, Rule] = field(default_factory=dict)
    default: Rule | None = None
    kind = "by_reading"

    def __post_init__(self):
        if self.default is None:
            raise ValueError("ByReading needs the default reading's rule")

    def for_value(self, value: Any) -> Rule:
        """The rule in force under ``entry = value``."""
        return self.rules.get(value, self.default)

    def for_config(self, config: Mapping[str, Any]) -> Rule:
        return self.for_value(config.get(self.entry))

    @staticmethod
    def tag(value: Any, measured: Any) -> dict:
        """What a measurement function returns under ``entry = value``."""
        return {"reading": value, "measured": measured}

    def text(self) -> str:
        other = "; ".join(f"under {self.entry} = {v}: {r.text()}" for v, r in self.rules.items() if r != self.default)
        return f"{self.default.text()}" + (f" ({other})" if other else "")

    def params(self) -> dict:
        return {
            "entry": self.entry,
            "default": self.default.to_dict(),
            "rules": {str(v): r.to_dict() for v, r in self.rules.items()},
        }

    def judge(self, measured):
        if not (isinstance(measured, Mapping) and "reading" in measured and "measured" in measured):
            raise ValueError(f"ByReading({self.entry!r}) needs ByReading.tag(value, measured), got {measured!r}")
        return self.for_value(measured["reading"]).judge(measured["measured"])


def for_config(rule: Rule, config: Mapping[str, Any]) -> Rule:
    """The rule in force at a configuration of the register (a :class:`ByReading` picks its reading's rule;
    every other rule is the same everywhere)."""
    return rule.for_config(config) if isinstance(rule, ByReading) else rule


def synthetic(rule: Rule, verdict: str) -> Any:
    """A measured value that ``rule`` judges ``verdict`` (``"reproduced"`` or ``"not reproduced"``), or None
    where no value can reach it: the check that every reading can decide both ways (a rule that can never
    reproduce, or never fail, decides nothing).

    Parameters
    ----------
    rule : Rule
        :class:`InBand` (and :class:`WithinFactor`), :class:`Ordering`, :class:`Monotone`, :class:`AllOf`
        (every part the same way); a :class:`ByReading` is checked per reading with :func:`for_config`.
    """
    tight = lambda v: Estimate(v, 0.0, v - 1e-9 * max(1.0, abs(v)), v + 1e-9 * max(1.0, abs(v)), 10**6, 0.95, "t")
    yes = verdict == "reproduced"
    if isinstance(rule, NotCheckable):
        return None
    if isinstance(rule, AllOf):
        parts = {n: synthetic(r, verdict) for n, r in rule.parts.items()}
        if any(v is None for n, v in parts.items() if not isinstance(rule.parts[n], NotCheckable)):
            return None
        return parts
    if isinstance(rule, Ordering):
        r = rule.reference
        step = 0.5 * (r if rule.measure == "ratio" else 1.0)
        return tight(r + step if (rule.relation == ">") == yes else r - step)
    if isinstance(rule, Monotone):
        up = (rule.direction == "increasing") == yes
        span = 10.0 * (rule.tolerance + 1.0)
        return [tight(0.0), tight(span if up else -span)]
    if isinstance(rule, InBand):
        lo, hi = rule.low, rule.high
        if yes:
            if lo is not None and hi is not None:
                return tight((lo + hi) / 2)
            return tight(lo + abs(lo) + 1.0 if hi is None else hi - abs(hi) - 1.0)
        if hi is not None:
            return tight(hi + abs(hi) + 1.0)
        return tight(lo - abs(lo) - 1.0)
    return None
