"""Rule pins from the papers: what each claim's rule must decide on values either side of the paper's statement.

Each paper's ``tests/papers/test_NNN_rule_pins.py`` holds a table ``PINS = {claim id: {part pattern: row}}``: the
paper's sentence (short), the direction or band it states, and synthetic measured values, one set the paper's
statement calls reproduced and one it calls not reproduced, written from the paper's own text and figures, not
from ``claims.py``. :func:`check` feeds every part of every rule its row's values as narrow
:class:`tvtrack.montecarlo.Estimate` s and asserts the verdict; a band row also probes just inside and just outside
each end it states, so a moved end fails too. A claim id or part with no row, or a row that matches no part, fails:
a new claim or part cannot land unpinned.

Part keys: an :class:`~tvtrack.verdicts.AllOf`'s part names joined by ``" / "``; a
:class:`~tvtrack.verdicts.ByReading` adds ``"<entry>=<value>"`` per reading and ``"<entry>=*default*"`` for the
rule of every other value, before its parts. A single rule's key is ``""``. Table keys are ``fnmatch`` patterns
(``"P=*"``); each part must match exactly one.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from fnmatch import fnmatchcase
from typing import Any

from tvtrack.montecarlo import Estimate
from tvtrack.verdicts import AllOf, ByReading, Rule

YES, NO = "reproduced", "not reproduced"
#: Relative width of the edge probes: a band end moved by more than this fails a probe.
EDGE = 1e-3


def est(v: float, h: float | None = None) -> Estimate:
    """A measured value with a narrow 95 % interval of half-width ``h`` (default 1e-6 of the value, at least
    1e-12)."""
    h = max(1e-6 * abs(v), 1e-12) if h is None else h
    return Estimate(float(v), h / 1.96, float(v) - h, float(v) + h, 10**6, 0.95, "t")


@dataclass(frozen=True)
class Band:
    """The paper states the quantity lies in ``[low, high]`` (``None``: open on that side).

    ``inside``: values the paper calls reproduced; ``outside``: values it calls not reproduced (for a two-sided band
    one beyond each end)."""

    sentence: str
    states: str
    low: float | None
    high: float | None
    inside: tuple[float, ...]
    outside: tuple[float, ...]
    unit: str | None = None
    says: tuple[str, ...] = ()

    def probes(self) -> list[tuple[Any, str]]:
        out = [(est(v), YES) for v in self.inside] + [(est(v), NO) for v in self.outside]
        lo, hi = self.low, self.high
        scale = max(abs(x) for x in (lo, hi) if x is not None) or 1.0
        if lo is not None and hi is not None:
            scale = max(hi - lo, 1e-300)
        d = EDGE * scale
        for end, sign in ((lo, -1.0), (hi, 1.0)):
            if end is not None:
                out += [(est(end - sign * d, d / 10), YES), (est(end + sign * d, d / 10), NO)]
        return out


@dataclass(frozen=True)
class Order:
    """The paper states an ordering; the rule decides on a ratio (reference 1) or a difference (reference 0).

    ``yes``: the ratio / difference on the paper's side; ``no``: on the other side."""

    sentence: str
    states: str
    yes: tuple[float, ...]
    no: tuple[float, ...]
    unit: str | None = None
    says: tuple[str, ...] = ()

    def probes(self) -> list[tuple[Any, str]]:
        return [(est(v), YES) for v in self.yes] + [(est(v), NO) for v in self.no]


@dataclass(frozen=True)
class Trend:
    """The paper states a trend along a grid: ``yes`` curves follow it, ``no`` curves go against it (or are
    measurably not monotone)."""

    sentence: str
    states: str
    yes: tuple[tuple[float, ...], ...]
    no: tuple[tuple[float, ...], ...]
    unit: str | None = None
    says: tuple[str, ...] = ()

    def probes(self) -> list[tuple[Any, str]]:
        curve = lambda c: [est(v) for v in c]  # noqa: E731
        return [(curve(c), YES) for c in self.yes] + [(curve(c), NO) for c in self.no]


@dataclass(frozen=True)
class Unchecked:
    """The claim (part) cannot be checked by a run: true by construction, or no data; the rule must say
    ``not checkable`` whatever it is given."""

    sentence: str
    why: str

    def probes(self) -> list[tuple[Any, str]]:
        return [(est(1.0), "not checkable"), (est(-1.0), "not checkable"), ([est(0.0), est(1.0)], "not checkable")]


def parts(rule: Rule, prefix: str = "") -> dict[str, Rule]:
    """``{part key: leaf rule}`` of ``rule`` (module docstring)."""
    join = lambda k: f"{prefix} / {k}" if prefix else k  # noqa: E731
    if isinstance(rule, ByReading):
        out: dict[str, Rule] = {}
        for value, r in rule.rules.items():
            out |= parts(r, join(f"{rule.entry}={value}"))
        return out | parts(rule.default, join(f"{rule.entry}=*default*"))
    if isinstance(rule, AllOf):
        out = {}
        for name, r in rule.parts.items():
            out |= parts(r, join(name))
        return out
    return {prefix: rule}


def _words(leaf: Rule) -> list[str]:
    """What a leaf rule says it measures: its quantity (an ordering's two sides, a trend's axis too; a claim that
    cannot be checked, its reason)."""
    names = {
        "not_checkable": ("reason",),
        "in_band": ("quantity",),
        "within_factor": ("quantity",),
        "ordering": ("a", "b"),
        "monotone": ("quantity", "over"),
    }
    return [getattr(leaf, n) for n in names.get(leaf.kind, ())]


def wording(leaf: Rule, row) -> list[str]:
    """What is wrong with how ``leaf`` names its quantity: each name a phrase (not empty, not a relation sign, no
    "None" formatted into it), the unit a string, the row's unit where the row states one, and in its text the
    conditions the row's ``says`` names (the paper's SIR, interferer count, gate sizes)."""
    phrase = lambda w: isinstance(w, str) and len(w) > 2 and "None" not in w  # noqa: E731
    out = [f"names {w!r} where a phrase belongs" for w in _words(leaf) if not phrase(w)]
    unit = getattr(leaf, "unit", "")
    if not isinstance(unit, str):
        out.append(f"unit {unit!r} is not a string")
    if getattr(row, "unit", None) is not None and unit != row.unit:
        out.append(f"unit {unit!r}, the paper's quantity is in {row.unit!r}")
    text = leaf.text()
    out += [f"does not say {w!r} (the paper's condition)" for w in getattr(row, "says", ()) if w not in text]
    return out


def problems(package: str, pins: dict) -> list[str]:
    """Every disagreement between ``package``'s rules and its pin table, as one line each (empty: all pinned and
    all decided as the paper says).

    The rules are built afresh by the package's ``claims.claim_rules()`` (at its default sizes), so that a mutation
    tool that changes the function sees its change; ``tests/test_rule_pins.py`` checks that the package's ``RULES``
    is that table."""
    paper = importlib.import_module(f"tvtrack.papers.{package}")
    rules = importlib.import_module(f"tvtrack.papers.{package}.claims").claim_rules()
    out = [f"{cid}: no row in the pin table" for cid in paper.CLAIMS if cid not in pins]
    out += [f"{cid}: a pin row but no claim" for cid in pins if cid not in paper.CLAIMS]
    for cid, rows in pins.items():
        if cid not in paper.CLAIMS:
            continue
        if cid not in rules:
            out.append(f"{cid}: no rule")
            continue
        used = set()
        for key, leaf in parts(rules[cid]).items():
            hit = [pat for pat in rows if fnmatchcase(key, pat)]
            if len(hit) != 1:
                out.append(f"{cid} part {key!r}: {'no row' if not hit else f'several rows {hit}'}")
                continue
            used.add(hit[0])
            out += [f"{cid} part {key!r}: {w}" for w in wording(leaf, rows[hit[0]])]
            for measured, want in rows[hit[0]].probes():
                got = leaf.decide(measured)
                if got != want:
                    shown = [m.value for m in measured] if isinstance(measured, list) else measured.value
                    out.append(f"{cid} part {key!r}: {shown} -> {got}, the paper says {want}")
        out += [f"{cid} row {pat!r}: matches no part" for pat in rows if pat not in used]
    return out
