"""Acceptance rules as code, and the robustness record of a claim.

A rule renders its own acceptance text and decides the verdict from measured estimates with
their intervals, so the text and the decision cannot disagree. Notebooks never type a verdict:
they pass a rule and the measured value to :meth:`tvtrack.results.Results.claim`.

Conventions (README, "Writing a notebook"):

- Where the paper gives a value, the rule is two-sided (:class:`InBand`, :class:`WithinFactor`).
  A measured value wholly beyond the paper's band on the side the paper would call *better* is
  ``partly`` (the claim's number is not what the run shows), with that said in the decision.
- A claim true by construction of the model is :class:`NotCheckable`, with the reason.
- A difference claimed without uncertainty is no evidence: orderings are decided by the interval
  of a paired difference or ratio (:class:`Ordering`), trends by the intervals along the curve
  (:class:`Monotone`).
- An interval that straddles a bound means the Monte Carlo cannot decide: ``partly``.

The robustness record (:class:`Robustness`) lists what the paper left unstated
(:class:`Choice`), the claim measured under each defensible reading (:class:`Condition`) and under
independent seeds; :func:`robustness_label` derives ``robust``, ``depends`` or ``unstable``.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

from .montecarlo import Estimate

__all__ = ["VERDICTS", "LABELS", "as_estimate", "Rule", "InBand", "WithinFactor", "Ordering", "Monotone",
           "AllOf", "NotCheckable", "Choice", "Condition", "Robustness", "robustness_label"]

#: The only verdicts a claim may carry.
VERDICTS = ("reproduced", "partly", "not reproduced", "not checkable")
#: Robustness labels.
LABELS = ("robust", "depends", "unstable")


def as_estimate(measured: Any) -> Estimate:
    """An :class:`Estimate` from an estimate, an estimate dict or a plain number (a number is
    exact: a deterministic computation, its interval the point itself)."""
    if isinstance(measured, Estimate):
        return measured
    if isinstance(measured, Mapping) and "value" in measured:
        fields = {k: measured[k] for k in ("value", "stderr", "ci_low", "ci_high", "n", "confidence", "method")
                  if k in measured}
        fields = {k: (float("nan") if v is None and k != "method" else v) for k, v in fields.items()}
        return Estimate(**{"stderr": float("nan"), "n": 1, **fields})
    if isinstance(measured, (int, float)) or hasattr(measured, "__float__"):
        v = float(measured)
        return Estimate(v, 0.0, v, v, 1, 0.95, "exact")
    raise TypeError(f"cannot read a measured value from {type(measured).__name__}: {measured!r}")


def _interval(e: Estimate) -> tuple[float, float]:
    """The estimate's interval; the point where the interval is undefined."""
    a, b = e.ci_low, e.ci_high
    if not (math.isfinite(a) and math.isfinite(b)):
        return e.value, e.value
    return a, b


def _g(x: float) -> str:
    return f"{x:.4g}"


def _show(e: Estimate, unit: str = "") -> str:
    a, b = _interval(e)
    u = f" {unit}" if unit else ""
    if a == b == e.value:
        return f"{_g(e.value)}{u}"
    return f"{_g(e.value)} [{_g(a)}, {_g(b)}]{u}"


class Rule(ABC):
    """An acceptance rule: renders its text and decides a verdict from a measured value."""

    kind = "rule"

    @abstractmethod
    def text(self) -> str:
        """The acceptance criterion in words, with its numbers."""

    def decide(self, measured: Any) -> str:
        """One of :data:`VERDICTS`."""
        return self.explain(measured)[0]

    @abstractmethod
    def explain(self, measured: Any) -> tuple[str, str]:
        """``(verdict, one sentence saying why, with the numbers)``."""

    def params(self) -> dict:
        return {}

    def to_dict(self) -> dict:
        return {"kind": self.kind, "text": self.text(), **self.params()}


@dataclass(frozen=True)
class InBand(Rule):
    """The quantity lies in ``[low, high]`` (either end may be open).

    ``reproduced`` when the whole interval lies inside, ``not reproduced`` when it lies wholly
    outside, ``partly`` when it straddles an end. With ``better`` set, an interval wholly beyond
    the band on that side is ``partly`` (better than the paper's number, not the paper's number).

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
            return f"at most {_g(self.high)}{u}"
        if self.high is None:
            return f"at least {_g(self.low)}{u}"
        return f"in [{_g(self.low)}, {_g(self.high)}]{u}"

    def text(self) -> str:
        t = (f"{self.quantity} {self._band()}: reproduced if the whole 95 % interval lies inside, not reproduced "
             f"if it lies wholly outside, partly if it straddles a bound")
        if self.better is not None:
            t += f"; wholly {'below' if self.better == 'lower' else 'above'} the band (better than the paper) is partly"
        return t

    def params(self) -> dict:
        return {"quantity": self.quantity, "low": self.low, "high": self.high, "unit": self.unit,
                "better": self.better}

    def explain(self, measured):
        e = as_estimate(measured)
        a, b = _interval(e)
        lo = -math.inf if self.low is None else self.low
        hi = math.inf if self.high is None else self.high
        m = _show(e, self.unit)
        if not (math.isfinite(a) and math.isfinite(b)) and not (math.isinf(a) or math.isinf(b)):
            return "not reproduced", f"{self.quantity} could not be measured ({m})"
        if lo <= a and b <= hi:
            return "reproduced", f"{self.quantity} = {m} lies {self._band()}"
        below, above = b < lo, a > hi
        if below or above:
            side = "below" if below else "above"
            if (below and self.better == "lower") or (above and self.better == "higher"):
                return "partly", f"{self.quantity} = {m} lies wholly {side} the band ({self._band()}): better than the paper's number"
            return "not reproduced", f"{self.quantity} = {m} lies wholly {side} the band ({self._band()})"
        return "partly", f"{self.quantity} = {m} straddles a bound of the band ({self._band()}): undecided at this sample size"


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
        return (f"within a factor {_g(self.factor)} of the paper's {_g(self.paper_value)}{u} "
                f"([{_g(self.low)}, {_g(self.high)}])")

    def params(self) -> dict:
        return {**super().params(), "paper_value": self.paper_value, "factor": self.factor}


@dataclass(frozen=True)
class Ordering(Rule):
    """``a`` is greater (or smaller) than ``b``, decided by the interval of their paired
    difference ``a - b`` (reference 0) or ratio ``a / b`` (reference 1).

    ``reproduced`` when the interval lies wholly on the claimed side, ``not reproduced`` when it
    lies wholly on the other, ``partly`` when it contains the reference (no measurable difference).
    """

    a: str
    b: str
    relation: str = ">"
    measure: str = "difference"
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
        return (f"{self.a} {self.relation} {self.b}, judged on the paired {self.measure} {self._what()}: reproduced "
                f"if its 95 % interval lies wholly {side} {_g(self.reference)}, not reproduced if wholly on the "
                f"other side, partly if it contains {_g(self.reference)}")

    def params(self) -> dict:
        return {"a": self.a, "b": self.b, "relation": self.relation, "measure": self.measure}

    def explain(self, measured):
        e = as_estimate(measured)
        lo, hi = _interval(e)
        r = self.reference
        m = f"{self._what()} = {_show(e)}"
        claimed_side = lo > r if self.relation == ">" else hi < r
        other_side = hi < r if self.relation == ">" else lo > r
        if claimed_side:
            return "reproduced", f"{m}: {self.a} {self.relation} {self.b}"
        if other_side:
            return "not reproduced", f"{m}: the opposite ordering holds"
        return "partly", f"{m} contains {_g(r)}: no measurable difference at this sample size"


@dataclass(frozen=True)
class Monotone(Rule):
    """The quantity increases (or decreases) along a grid, judged on the intervals.

    Steps between neighbours support the trend when their intervals are separated in its
    direction and contradict it when separated the other way. ``reproduced``: first and last
    points separated in the claimed direction and no step contradicts; ``not reproduced``: first
    and last separated the other way, or no step and no end-to-end change is measurable; else
    ``partly``.
    """

    quantity: str
    over: str
    direction: str = "increasing"
    kind = "monotone"

    def __post_init__(self):
        if self.direction not in ("increasing", "decreasing"):
            raise ValueError(f"Monotone: direction {self.direction!r} must be 'increasing' or 'decreasing'")

    def text(self) -> str:
        return (f"{self.quantity} is {self.direction} in {self.over}: reproduced if the first and last 95 % intervals "
                f"are separated in that direction and no neighbouring pair is separated the other way; not "
                f"reproduced if the ends are separated the other way or nothing along the grid is measurably "
                f"{self.direction}; partly otherwise")

    def params(self) -> dict:
        return {"quantity": self.quantity, "over": self.over, "direction": self.direction}

    def _sep(self, e0: Estimate, e1: Estimate) -> int:
        """+1 when ``e1`` is measurably beyond ``e0`` in the claimed direction, -1 the other way, 0 else."""
        a0, b0 = _interval(e0)
        a1, b1 = _interval(e1)
        up = a1 > b0
        down = b1 < a0
        s = 1 if up else (-1 if down else 0)
        return s if self.direction == "increasing" else -s

    def explain(self, measured: Sequence):
        es = [as_estimate(m) for m in measured]
        if len(es) < 2:
            raise ValueError("Monotone needs at least two points")
        steps = [self._sep(x, y) for x, y in zip(es[:-1], es[1:])]
        ends = self._sep(es[0], es[-1])
        up, down = steps.count(1), steps.count(-1)
        m = (f"{self.quantity}: {_show(es[0])} at the first point, {_show(es[-1])} at the last; "
             f"{up} of {len(steps)} steps measurably {self.direction}, {down} the other way")
        if ends == -1:
            return "not reproduced", m
        if ends == 1 and down == 0:
            return "reproduced", m
        if ends == 0 and up == 0:
            return "not reproduced", m + " (no measurable trend)"
        return "partly", m


@dataclass(frozen=True)
class AllOf(Rule):
    """Every part of a composite claim, each by its own rule: ``reproduced`` when all parts are,
    ``not reproduced`` when none is reproduced or partly, else ``partly``."""

    parts: Mapping[str, Rule] = field(default_factory=dict)
    kind = "all_of"

    def __post_init__(self):
        if not self.parts:
            raise ValueError("AllOf needs at least one part")

    def text(self) -> str:
        return "all of: " + "; ".join(f"({name}) {rule.text()}" for name, rule in self.parts.items())

    def params(self) -> dict:
        return {"parts": {name: rule.to_dict() for name, rule in self.parts.items()}}

    def explain(self, measured: Mapping):
        missing = [name for name in self.parts if name not in measured]
        if missing:
            raise ValueError(f"AllOf: measured lacks the parts {missing}")
        decided = {name: rule.explain(measured[name]) for name, rule in self.parts.items()}
        verdicts = [v for v, _ in decided.values() if v != "not checkable"]
        why = "; ".join(f"({name}) {v}: {w}" for name, (v, w) in decided.items())
        if not verdicts:
            return "not checkable", why
        if all(v == "reproduced" for v in verdicts):
            return "reproduced", why
        if all(v == "not reproduced" for v in verdicts):
            return "not reproduced", why
        return "partly", why


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

    def explain(self, measured):
        return "not checkable", self.reason


# --------------------------------------------------------------------------- robustness

@dataclass(frozen=True)
class Choice:
    """Something the paper left unstated that a claim depends on.

    Attributes
    ----------
    name : str
        Short name, used in conditions (``"epoch"``).
    default : Any
        The value the notebook's headline uses.
    values : sequence
        Every defensible value (the default among them).
    why : str
        Why these values are defensible (a reading of a sentence, a convention, a regime).
    """

    name: str
    default: Any
    values: Sequence[Any]
    why: str

    def __post_init__(self):
        if self.default not in list(self.values):
            raise ValueError(f"choice {self.name!r}: default {self.default!r} is not among {list(self.values)}")


@dataclass(frozen=True)
class Condition:
    """The claim measured under one reading: ``choices`` maps choice names to values."""

    choices: Mapping[str, Any]
    measured: Any


@dataclass
class Robustness:
    """How a claim's verdict moves with what the paper left unstated and with the seed.

    Parameters
    ----------
    choices : list of Choice
        The unstated choices the claim depends on (empty only with a ``note`` saying why none matters).
    conditions : list of Condition
        The claim measured under readings other than the default (one-at-a-time or a grid).
    seeds : mapping seed -> measured
        The claim at the default reading under at least three independent seeds.
    note : str
        Anything the record alone does not say; required when ``choices`` is empty or when
        ``deterministic``.
    deterministic : bool
        The measurement involves no random draw (the seed cannot matter; ``note`` says why).
    """

    choices: list = field(default_factory=list)
    conditions: list = field(default_factory=list)
    seeds: Mapping[int, Any] = field(default_factory=dict)
    note: str = ""
    deterministic: bool = False

    def validate(self) -> None:
        if not self.choices and not self.note:
            raise ValueError("a robustness record without unstated choices needs a note saying why none matters")
        if self.deterministic and not self.note:
            raise ValueError("a deterministic robustness record needs a note saying why the seed cannot matter")
        if not self.deterministic and len(self.seeds) < 3:
            raise ValueError(f"a robustness record needs the claim under at least 3 seeds, got {len(self.seeds)}")
        names = {c.name for c in self.choices}
        for cond in self.conditions:
            unknown = set(cond.choices) - names
            if unknown:
                raise ValueError(f"condition {dict(cond.choices)} names unknown choices {sorted(unknown)}")
            for k, v in cond.choices.items():
                allowed = list(next(c for c in self.choices if c.name == k).values)
                if v not in allowed:
                    raise ValueError(f"condition {dict(cond.choices)}: {k} = {v!r} is not among {allowed}")

    def record(self, rule: Rule, default_verdict: str) -> dict:
        """The JSON record: choices, conditions and seeds each with its verdict by ``rule``,
        the label and where the verdict differs from ``default_verdict``."""
        self.validate()
        conditions = [{"choices": dict(c.choices), "measured": c.measured, "verdict": rule.decide(c.measured)}
                      for c in self.conditions]
        seeds = [{"seed": int(s), "measured": m, "verdict": rule.decide(m)} for s, m in self.seeds.items()]
        label, where = robustness_label(default_verdict, conditions, seeds)
        return {
            "label": label,
            "where": where,
            "choices": [{"name": c.name, "default": c.default, "values": list(c.values), "why": c.why}
                        for c in self.choices],
            "conditions": conditions,
            "seeds": seeds,
            "deterministic": self.deterministic,
            "note": self.note,
        }


def _describe(choices: Mapping[str, Any]) -> str:
    return ", ".join(f"{k} = {v}" for k, v in choices.items()) or "the default reading"


def robustness_label(default_verdict: str, conditions: Sequence[Mapping], seeds: Sequence[Mapping]) -> tuple[str, list]:
    """``(label, where)`` from the verdicts of the conditions and the seeds.

    ``unstable`` when the seeds at the default reading disagree; else ``depends`` when any
    condition's verdict differs from the default verdict; else ``robust``. ``where`` says, for
    each differing verdict, the conditions (or seeds) that give it.
    """
    seed_verdicts = {s["verdict"] for s in seeds}
    if len(seed_verdicts) > 1:
        by = {}
        for s in seeds:
            by.setdefault(s["verdict"], []).append(str(s["seed"]))
        return "unstable", [f"{v} with seed {', '.join(ss)}" for v, ss in by.items()]
    by_verdict: dict[str, list[str]] = {}
    for c in conditions:
        if c["verdict"] != default_verdict:
            by_verdict.setdefault(c["verdict"], []).append(_describe(c["choices"]))
    if by_verdict:
        return "depends", [f"{v} when {'; '.join(cs)}" for v, cs in by_verdict.items()]
    return "robust", []
