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
- An interval that straddles a bound means the Monte Carlo cannot decide: ``partly``; the rule says
  the verdict is not *settled* (:meth:`Rule.judge`), so the explorer can add replicates.
- Undecided is a verdict input: a NaN value, a NaN or degenerate interval of a random quantity, or an
  extrapolated estimate (``Estimate.extrapolated``) is ``undecided`` and never decides a claim.

Labels (:func:`label_parts`) are per part of a rule (each part of :class:`AllOf`; the whole rule
otherwise): ``unstable`` when independent replicates at the default disagree, ``depends`` when a
condition of the register changes the verdict (named in ``where``), ``unexplored`` when no regime,
operating point or model of the world was varied, else ``robust``; a claim's label is the weakest of
its parts' and its ``coverage`` text says what was tried. The explorer (:mod:`tvtrack.explore`) makes
these records; :class:`Robustness` is the older hand-built record, labelled by the same function.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

from .montecarlo import Estimate

__all__ = [
    "VERDICTS",
    "LABELS",
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
    "Condition",
    "Robustness",
    "rule_parts",
    "label_parts",
    "weakest_label",
]

#: The only verdicts a claim may carry.
VERDICTS = ("reproduced", "partly", "not reproduced", "undecided", "not checkable")
#: Robustness labels, weakest first.
LABELS = ("unstable", "depends", "unexplored", "robust")


def as_estimate(measured: Any) -> Estimate:
    """An :class:`Estimate` from an estimate, an estimate dict or a plain number (a number is
    exact: a deterministic computation, its interval the point itself)."""
    if isinstance(measured, Estimate):
        return measured
    if isinstance(measured, Mapping) and "value" in measured:
        fields = {
            k: measured[k]
            for k in ("value", "stderr", "ci_low", "ci_high", "n", "confidence", "method", "extrapolated")
            if k in measured
        }
        fields = {
            k: (float("nan") if v is None and k not in ("method", "extrapolated") else v) for k, v in fields.items()
        }
        fields["extrapolated"] = bool(fields.get("extrapolated") or False)
        return Estimate(**{"stderr": float("nan"), "n": 1, **fields})
    if isinstance(measured, (int, float)) or hasattr(measured, "__float__"):
        v = float(measured)
        return Estimate(v, 0.0, v, v, 1, 0.95, "exact")
    raise TypeError(f"cannot read a measured value from {type(measured).__name__}: {measured!r}")


def _is_exact(e: Estimate) -> bool:
    return e.method == "exact"


def calibrated(measured: Any) -> Estimate:
    """The estimate a rule decides on: an interval whose helper states a measured coverage short of its
    nominal level at this sample size (:func:`tvtrack.montecarlo.coverage_reached`) is widened to it
    (:func:`tvtrack.montecarlo.widen_to_nominal`; the method says so); others are returned as they are."""
    from .montecarlo import coverage_reached, stated_coverage, widen_to_nominal

    e = as_estimate(measured)
    s = stated_coverage(e)
    if math.isfinite(s) and not coverage_reached(e):
        return widen_to_nominal(e)
    return e


def is_undecided(measured: Any) -> bool:
    """True when an estimate cannot decide anything: NaN value, NaN interval or a degenerate interval
    (``ci_low == ci_high``) of a random quantity, a value extrapolated beyond the data, or an interval
    whose coverage at its sample size was never measured ("coverage unmeasured")."""
    from .montecarlo import stated_coverage

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


def _interval(e: Estimate) -> tuple[float, float]:
    """The estimate's interval (the point itself for an exact number)."""
    if _is_exact(e) and (math.isnan(e.ci_low) or math.isnan(e.ci_high)):
        return e.value, e.value
    return e.ci_low, e.ci_high


def _why_undecided(e: Estimate) -> str:
    if getattr(e, "extrapolated", False):
        return "extrapolated beyond the data"
    if math.isnan(e.value):
        return "not measured (NaN)"
    if "coverage unmeasured" in (e.method or ""):
        return "its interval's coverage at this sample size is unmeasured"
    return "its interval is undefined or degenerate"


def _g(x: float) -> str:
    return f"{x:.4g}"


def _show(e: Estimate, unit: str = "") -> str:
    a, b = _interval(e)
    u = f" {unit}" if unit else ""
    if math.isnan(a) or math.isnan(b) or a == b == e.value:
        return f"{_g(e.value)}{u}"
    widened = " (interval widened to its nominal coverage)" if "widened" in (e.method or "") else ""
    return f"{_g(e.value)} [{_g(a)}, {_g(b)}]{u}{widened}"


@dataclass(frozen=True)
class Judgement:
    """A rule's decision: the verdict, one sentence why, and whether more data could change it
    (``settled`` is False for an interval that straddles a bound and for ``undecided``)."""

    verdict: str
    why: str
    settled: bool = True


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
        t = (
            f"{self.quantity} {self._band()}: reproduced if the whole 95 % interval lies inside, not reproduced "
            f"if it lies wholly outside, partly if it straddles a bound"
        )
        if self.better is not None:
            t += f"; wholly {'below' if self.better == 'lower' else 'above'} the band (better than the paper) is partly"
        return t

    def params(self) -> dict:
        return {"quantity": self.quantity, "low": self.low, "high": self.high, "unit": self.unit, "better": self.better}

    def judge(self, measured):
        e = calibrated(measured)
        m = _show(e, self.unit)
        if is_undecided(e):
            return Judgement("undecided", f"{self.quantity} = {m}: {_why_undecided(e)}, so it cannot decide", False)
        a, b = _interval(e)
        lo = -math.inf if self.low is None else self.low
        hi = math.inf if self.high is None else self.high
        if lo <= a and b <= hi:
            return Judgement("reproduced", f"{self.quantity} = {m} lies {self._band()}")
        below, above = b < lo, a > hi
        if below or above:
            side = "below" if below else "above"
            if (below and self.better == "lower") or (above and self.better == "higher"):
                return Judgement(
                    "partly",
                    f"{self.quantity} = {m} lies wholly {side} the band ({self._band()}): "
                    f"better than the paper's number",
                )
            return Judgement("not reproduced", f"{self.quantity} = {m} lies wholly {side} the band ({self._band()})")
        return Judgement(
            "partly",
            f"{self.quantity} = {m} straddles a bound of the band ({self._band()}): undecided at this sample size",
            False,
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
            f"within a factor {_g(self.factor)} of the paper's {_g(self.paper_value)}{u} "
            f"([{_g(self.low)}, {_g(self.high)}])"
        )

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
    paired: bool = True
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
            f"if its 95 % interval lies wholly {side} {_g(self.reference)}, not reproduced if wholly on the "
            f"other side, partly if it contains {_g(self.reference)}"
        )

    def params(self) -> dict:
        return {"a": self.a, "b": self.b, "relation": self.relation, "measure": self.measure, "paired": self.paired}

    def judge(self, measured):
        e = calibrated(measured)
        m = f"{self._what()} = {_show(e)}"
        if is_undecided(e):
            return Judgement("undecided", f"{m}: {_why_undecided(e)}, so it cannot decide", False)
        lo, hi = _interval(e)
        r = self.reference
        claimed_side = lo > r if self.relation == ">" else hi < r
        other_side = hi < r if self.relation == ">" else lo > r
        if claimed_side:
            return Judgement("reproduced", f"{m}: {self.a} {self.relation} {self.b}")
        if other_side:
            return Judgement("not reproduced", f"{m}: the opposite ordering holds")
        return Judgement("partly", f"{m} contains {_g(r)}: no measurable difference at this sample size", False)


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
        return (
            f"{self.quantity} is {self.direction} in {self.over}: reproduced if the first and last 95 % intervals "
            f"are separated in that direction and no neighbouring pair is separated the other way; not "
            f"reproduced if the ends are separated the other way or nothing along the grid is measurably "
            f"{self.direction}; partly otherwise"
        )

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
            )
        keep = [e for i, e in enumerate(es) if i not in bad]
        steps = [self._sep(x, y) for x, y in zip(keep[:-1], keep[1:])]
        ends = self._sep(keep[0], keep[-1])
        up, down = steps.count(1), steps.count(-1)
        m = (
            f"{self.quantity}: {_show(keep[0])} at the first point, {_show(keep[-1])} at the last; "
            f"{up} of {len(steps)} steps measurably {self.direction}, {down} the other way"
            + (f" ({len(bad)} undecided points left out)" if bad else "")
        )
        if ends == -1:
            return Judgement("not reproduced", m)
        if ends == 1 and down == 0:
            return Judgement("reproduced", m)
        if ends == 0 and up == 0:
            return Judgement("not reproduced", m + " (no measurable trend)", False)
        return Judgement("partly", m, ends != 0)


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

    def judge(self, measured: Mapping):
        missing = [name for name in self.parts if name not in measured]
        if missing:
            raise ValueError(f"AllOf: measured lacks the parts {missing}")
        decided = {name: rule.judge(measured[name]) for name, rule in self.parts.items()}
        verdicts = [j.verdict for j in decided.values() if j.verdict != "not checkable"]
        settled = all(j.settled for j in decided.values())
        why = "; ".join(f"({name}) {j.verdict}: {j.why}" for name, j in decided.items())
        if not verdicts:
            return Judgement("not checkable", why)
        firm = [v for v in verdicts if v != "undecided"]
        if len(firm) < len(verdicts):
            # an undecided part never decides: the claim is partly only if decided parts already disagree
            mixed = "partly" in firm or len(set(firm)) > 1
            return Judgement("partly" if mixed else "undecided", why, False)
        if all(v == "reproduced" for v in verdicts):
            return Judgement("reproduced", why, settled)
        if all(v == "not reproduced" for v in verdicts):
            return Judgement("not reproduced", why, settled)
        return Judgement("partly", why, settled)


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


# --------------------------------------------------------------------------- labels


def rule_parts(rule: Rule) -> dict[str, Rule]:
    """The parts a label is given for: each part of an :class:`AllOf`, else the whole rule as ``"claim"``."""
    if isinstance(rule, AllOf):
        return dict(rule.parts)
    return {"claim": rule}


def _part_measured(rule: Rule, measured: Any) -> dict[str, Any]:
    if isinstance(rule, AllOf):
        return {name: measured[name] for name in rule.parts if isinstance(measured, Mapping) and name in measured}
    return {"claim": measured}


NO_PART_LABEL = "-"
"""The label of a :class:`NotCheckable` part inside an :class:`AllOf` (it takes no part in the claim's label)."""


def weakest_label(labels: Sequence[str]) -> str:
    """The weakest of ``labels`` in the order of :data:`LABELS`."""
    return min(labels, key=LABELS.index) if labels else "unexplored"


def _describe(changed: Mapping[str, Any]) -> str:
    return ", ".join(f"{k} = {v}" for k, v in changed.items()) or "the default reading"


def label_parts(
    rule: Rule,
    measured: Any,
    replicates: Sequence[Mapping],
    conditions: Sequence[Mapping],
    entries: Sequence[Any] = (),
    deterministic: bool = False,
) -> dict:
    """Part-level robustness labels of one claim.

    Parameters
    ----------
    rule : Rule
        The claim's rule; labels are given per :func:`rule_parts`.
    measured : Any
        The claim at the default (pooled over the replicates): decides the claim's verdict.
    replicates : sequence of {"seed", "measured"}
        Independent full-size runs at the default. Conditions are compared with the first replicate,
        which ran on the same random numbers (common random numbers).
    conditions : sequence of {"changed": {entry: value}, "kind": "single" | "joint", "measured"}
        The claim under other values of the register: one entry at a time, or joint samples.
    entries : sequence of :class:`tvtrack.register.Entry`
        The register entries the claim depends on.
    deterministic : bool
        No random draw is involved (replicates cannot differ).

    Returns
    -------
    dict
        ``label`` (weakest part), ``where`` (the parts and conditions where a verdict differs),
        ``coverage`` (what was tried), ``parts`` {name: {verdict, label, where, replicate_verdicts,
        n_conditions}}, ``replicates`` and ``conditions`` with their part verdicts.
    """
    from .register import WORLD_KINDS

    parts = rule_parts(rule)
    kinds = {e.name: e.kind for e in entries}
    rep_rows = [
        {
            "seed": int(r["seed"]),
            "measured": r["measured"],
            "verdict": rule.decide(r["measured"]),
            "parts": {n: p.decide(m) for n, (p, m) in _zip_parts(parts, rule, r["measured"]).items()},
        }
        for r in replicates
    ]
    cond_rows = [
        {
            "changed": dict(c["changed"]),
            "kind": c.get("kind", "single"),
            "measured": c["measured"],
            "verdict": rule.decide(c["measured"]),
            "parts": {n: p.decide(m) for n, (p, m) in _zip_parts(parts, rule, c["measured"]).items()},
        }
        for c in conditions
    ]
    world_varied = any(kinds.get(k) in WORLD_KINDS for c in cond_rows for k in c["changed"])
    part_out, where = {}, []
    for name, prule in parts.items():
        pm = _part_measured(rule, measured).get(name)
        verdict = prule.decide(pm) if pm is not None else "undecided"
        rv = [r["parts"][name] for r in rep_rows if name in r["parts"]]
        ref = rv[0] if rv else verdict  # conditions ran on the first replicate's random numbers
        flips: dict[str, list[str]] = {}
        undecided: list[str] = []
        for c in cond_rows:
            v = c["parts"].get(name)
            if v is None:
                continue
            if v == "undecided" and ref != "undecided":
                undecided.append(_describe(c["changed"]))
            elif v != ref:
                flips.setdefault(v, []).append(_describe(c["changed"]))
        pwhere = []
        if isinstance(prule, NotCheckable):
            label = NO_PART_LABEL  # an identity or a statement this project cannot check has nothing to flip
        elif len(set(rv)) > 1:
            label = "unstable"
            pwhere += [f"{v} in {rv.count(v)} of {len(rv)} independent replicates" for v in dict.fromkeys(rv)]
        elif flips:
            label = "depends"
        elif not world_varied:
            label = "unexplored"
        else:
            label = "robust"
        pwhere += [f"{v} when {'; '.join(cs)}" for v, cs in flips.items()]
        if undecided:
            pwhere.append(f"undecided when {'; '.join(undecided)}")
        prefix = "" if len(parts) == 1 else f"({name}) "
        where += [prefix + w for w in pwhere]
        part_out[name] = {
            "verdict": verdict,
            "label": label,
            "where": pwhere,
            "replicate_verdicts": rv,
            "n_conditions": sum(1 for c in cond_rows if name in c["parts"]),
        }
    label = weakest_label([p["label"] for p in part_out.values() if p["label"] != NO_PART_LABEL])
    return {
        "label": label,
        "where": where,
        "coverage": _coverage(label, part_out, cond_rows, rep_rows, entries, deterministic),
        "parts": part_out,
        "replicates": rep_rows,
        "conditions": cond_rows,
        "deterministic": deterministic,
    }


def _zip_parts(parts: Mapping[str, Rule], rule: Rule, measured: Any) -> dict:
    pm = _part_measured(rule, measured)
    return {n: (parts[n], pm[n]) for n in parts if n in pm and pm[n] is not None}


def _coverage(label, parts, conds, reps, entries, deterministic) -> str:
    single = [c for c in conds if c["kind"] == "single"]
    joint = [c for c in conds if c["kind"] == "joint"]
    pinned = [c for c in conds if c["kind"] == "pinned"]
    varied: dict[str, set] = {}
    for c in single:
        for k, v in c["changed"].items():
            varied.setdefault(k, set()).add(str(v))
    over = ", ".join(f"{k} ({len(v) + 1} values)" for k, v in varied.items()) or "no register entry"
    reps_text = "deterministic (no random draw)" if deterministic else f"{len(reps)} independent replicates"
    weak = [n for n, p in parts.items() if p["label"] == label]
    which = "" if len(parts) == 1 else f" (weakest part{'s' if len(weak) > 1 else ''}: {', '.join(weak)})"
    return (
        f"{label}{which} over {len(conds)} conditions: {len(single)} one at a time over {over}; "
        f"{len(joint)} joint samples{f' and {len(pinned)} pinned joint conditions' if pinned else ''}; x {reps_text}"
    )


# --------------------------------------------------------------------------- hand-built records


@dataclass(frozen=True)
class Condition:
    """The claim measured under one reading: ``choices`` maps entry names to values."""

    choices: Mapping[str, Any]
    measured: Any


@dataclass
class Robustness:
    """A hand-built robustness record (prefer :func:`tvtrack.explore.explore`).

    Parameters
    ----------
    choices : list of Entry
        The register entries the claim depends on (empty only with a ``note`` saying why none matters).
    conditions : list of Condition
        The claim measured under readings other than the default.
    seeds : mapping seed -> measured
        The claim at the default reading under at least three independent full-size runs.
    note : str
        Required when ``choices`` is empty or when ``deterministic``.
    deterministic : bool
        The measurement involves no random draw (``note`` says why).
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

    def record(self, rule: Rule, measured: Any) -> dict:
        """The JSON record: :func:`label_parts` over the conditions and seeds, with the entries."""
        self.validate()
        reps = [{"seed": s, "measured": m} for s, m in self.seeds.items()]
        conds = [
            {"changed": dict(c.choices), "kind": "single" if len(c.choices) == 1 else "joint", "measured": c.measured}
            for c in self.conditions
        ]
        out = label_parts(rule, measured, reps, conds, self.choices, self.deterministic)
        out.update({"register": [c.to_dict() for c in self.choices], "note": self.note, "built": "by hand"})
        return out
