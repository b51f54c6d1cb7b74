"""A measured value against what the paper says, in words and units: one clause per rule (a band, an ordering,
a trend), the band said as what the paper's own words are read as, a share of runs in per cent
(:func:`value_clause`); and the rule in force for a measurement tagged with its reading (:func:`rule_in_force`).
The sentences around the clause are :mod:`tvtrack.wording`'s.
"""

from __future__ import annotations

import math
import re
from typing import Any, Mapping

from .numbers import net_trend, finite, format_measured, format_value, number, triple, vector_text, with_unit

__all__ = ["value_clause", "against_paper", "rule_in_force", "real_unit"]


def rule_in_force(rule: Mapping, measured: Any) -> tuple[Mapping, Any]:
    """The rule that judges a measurement: for a ``by_reading`` rule, the one in force for the reading the
    measurement is tagged with (nested ones followed down), else the rule itself.

    Parameters
    ----------
    rule : Mapping
        A rule as ``results.json`` stores it (``kind``, and for ``by_reading`` its ``rules`` and ``default``).
    measured : Any
        The claim's measured value (for ``by_reading``: ``{"reading": ..., "measured": ...}``).

    Returns
    -------
    tuple
        ``(rule in force, the measurement it judges)``.
    """
    if rule.get("kind") == "by_reading" and isinstance(measured, Mapping) and "reading" in measured:
        inner = (rule.get("rules") or {}).get(str(measured.get("reading"))) or rule.get("default") or {}
        return rule_in_force(inner, measured.get("measured"))
    return rule, measured


_LOWER_BETTER = ("variance", "error", "miss", "MSE", "RMS", "loss")
_PREPOSITIONS = ("with ", "at ", "against ", "in ", "for ", "from ", "without ", "over ")


def real_unit(rule: Mapping) -> str:
    """The rule's unit when it is one ("px", "× alpha", "variance ratio"); ``""`` for a dimensionless quantity
    (no unit, a parenthesised descriptor such as "(ratio)", or an ordering's "ratio of a to b")."""
    unit = str(rule.get("unit") or "").strip()
    return "" if not unit or unit.startswith("(") or unit.startswith("ratio of ") else unit


def _band_words(rule: Mapping, unit: str) -> str:
    """The rule's band in words: ``"[3, 6] px"``, ``"at most 2 px"``, ``"at least 20"``."""
    lo, hi = rule.get("low"), rule.get("high")
    if finite(lo) and finite(hi):
        return with_unit(f"[{number(lo)}, {number(hi)}]", unit)
    if finite(hi):
        return "at most " + with_unit(number(hi), unit)
    if finite(lo):
        return "at least " + with_unit(number(lo), unit)
    return ""


def _ratio_names(quantity: str) -> tuple[str, str, bool] | None:
    """``("two-stage", "ULA", lower is better)`` from a quantity such as "gain rho = two-stage / ULA variance at
    d = 1 sigma"; ``None`` when the quantity is not of that form."""
    m = re.search(r"(?:^|= )([\w'-]+(?: [\w'-]+)?) / ([\w'-]+) (\w+)", quantity)
    if not m:
        return None
    return m.group(1), m.group(2), any(w in m.group(3) for w in _LOWER_BETTER)


_SHARE_UNITS = ("of the runs", "of runs", "of the paths", "of the frames")


def _fraction_band(rule: Mapping) -> bool:
    """Whether the rule's band is of a dimensionless fraction: a finite end, and every finite end within [-1, 1]."""
    ends = [float(rule[k]) for k in ("low", "high") if finite(rule.get(k))]
    return bool(ends) and all(abs(e) <= 1 for e in ends)


def _percent(measured: Any, rule: Mapping, paper_value: str | None = None) -> tuple[Any, Mapping, str] | None:
    """A share of runs (unit "of the runs") as a percentage, and a dimensionless fraction where the paper gives
    its number in per cent (C000-2's "2 %"; of a paper value in pieces, the piece that is the band's own): the
    value, its interval and the band times 100."""
    unit = real_unit(rule)
    t = triple(measured)
    if t is None:
        return None
    if unit in _SHARE_UNITS:
        suffix = f"% {unit}"
    elif (
        not unit
        and _fraction_band(rule)
        and "%" in _own_piece(_paper_words(paper_value), rule.get("low"), rule.get("high"))
    ):
        suffix = "%"
    else:
        return None
    scaled = {"value": t[0] * 100, "ci_low": None if t[1] is None else t[1] * 100}
    scaled["ci_high"] = None if t[2] is None else t[2] * 100
    band = {k: (rule[k] * 100 if finite(rule.get(k)) else rule.get(k)) for k in ("low", "high")}
    return scaled, {**rule, **band}, suffix


def _holds_paper_number(said: str, low: Any, high: Any) -> bool:
    """Whether a number of the paper's words is the band's own: inside a two-sided band, on a one-sided band's
    edge, as written or (a per cent) as a share; True where the band has no finite end to compare."""
    lo, hi = (float(x) if finite(x) else None for x in (low, high))
    if lo is None and hi is None:
        return True
    nums = [float(x) for x in re.findall(r"(?<![\d.])-?\d+(?:\.\d+)?", said)]
    for x in [*nums, *(n / 100 for n in nums if "%" in said)]:
        if lo is not None and hi is not None and lo - 1e-12 <= x <= hi + 1e-12:
            return True
        if any(e is not None and math.isclose(x, e, rel_tol=1e-9, abs_tol=1e-12) for e in (lo, hi)):
            return True
    return False


def _paper_words(paper_value: str | None) -> str:
    """The paper's value as said: one line, without a closing remark in parentheses ("(one run)") or its quotes."""
    said = re.sub(r"\s*\([^()=]*\)\s*$", "", " ".join(str(paper_value or "").split())).strip()  # "(one run)"
    if len(said) > 1 and said[0] == said[-1] and said[0] in "'\"":  # the paper's words in their own quotes
        said = said[1:-1].strip()
    return said


def _own_piece(said: str, low: Any, high: Any) -> str:
    """Of a paper value in pieces (``"1 element; 10 elements/frame"``, one per part), the one piece whose number
    the band holds; else the whole value."""
    pieces = [p.strip() for p in said.split(";") if p.strip()]
    own = [p for p in pieces if re.search(r"\d", p) and _holds_paper_number(p, low, high)]
    return own[0] if len(pieces) > 1 and len(own) == 1 else said


def _names_another_quantity(said: str, quantity: str | None) -> bool:
    """Whether the paper's words state a bound on a symbol the rule's quantity never names (``"rho <= 0.5"``
    beside a false-alarm rate): its number is then not the band's, whatever their values."""
    m = re.match(r"\s*([^\W\d][\w^*]*)\s*(?:<=|>=|<|>|=|~|≤|≥)", said)  # "rho <= 0.5", "ρ ≤ 0.5"
    if not m or quantity is None:
        return False
    return re.search(rf"(?<![\w]){re.escape(m.group(1))}(?![\w])", quantity) is None


def against_paper(
    band: str, paper_value: str | None, low: Any = None, high: Any = None, quantity: str | None = None
) -> str:
    """What the rule's band stands for: ``", against [5.25, 5.75] s (the paper: 5.5 s)"``, or, where the paper
    gives no number, ``', where the paper says "fairly quickly" (read here as at most 10 %)'``; ``", where the
    paper has <band>"`` when the paper's value is not known (a bare rule). With the band's ends ``low`` and
    ``high``, a paper value none of whose numbers the band holds (:func:`_holds_paper_number`: the value of
    another quantity, as a threshold beside a probability) is said as what the band is read from:
    ``', against at least 0.1 (set here to check the paper's "2")'``; so is a bound on a symbol the rule's
    ``quantity`` never names (:func:`_names_another_quantity`). Of a paper value in pieces (``"1 element;
    10 elements/frame"``, one per part) only the one piece whose number the band holds is said."""
    if not band:
        return ""
    said = _paper_words(paper_value)
    if not said:
        return f", where the paper has {band}"
    if said.lower() == "qualitative":
        return f", against {band}, set here (the paper gives no number)"
    if not re.search(r"\d", said):
        return f', where the paper says "{said}" (read here as {band})'
    said = _own_piece(said, low, high)
    if not _holds_paper_number(said, low, high) or _names_another_quantity(said, quantity):
        return f', against {band} (set here to check the paper\'s "{said}")'
    return f", against {band} (the paper: {said})"


def _band_clause(rule: Mapping, measured: Any, paper_value: str | None = None) -> str:
    """``"<quantity> is 0.74 [0.60, 0.91] variance ratio, where the paper has [3, 6] variance ratio"``, and in
    words when the value reverses the direction the paper's band gives (a ratio below 1 where it has one above).
    A share of runs is given in per cent; with ``paper_value`` the band is said as what the paper's words are read
    as (:func:`against_paper`)."""
    shown, shown_rule, unit = _percent(measured, rule, paper_value) or (measured, rule, real_unit(rule))
    quantity = str(rule.get("quantity") or "the measured value")
    text = f"{quantity} is {format_value(shown, unit)}"
    text += against_paper(_band_words(shown_rule, unit), paper_value, rule.get("low"), rule.get("high"), quantity)
    t, lo, hi = triple(measured) or (None, None, None), rule.get("low"), rule.get("high")
    ratio = "ratio" in str(rule.get("unit") or "") or " / " in quantity
    if ratio and t[1] is not None and t[2] is not None:
        above = finite(lo) and lo > 1 and t[2] < 1  # a band wholly on one side of 1, the interval on the other
        below = finite(hi) and hi < 1 and t[1] > 1
        names = _ratio_names(quantity)
        if (above or below) and names:
            a, b, lower_better = names
            first_wins = above == lower_better
            winner, loser = (a, b) if first_wins else (b, a)
            text += f": the {winner} beats the {loser}, the reverse of the paper's direction"
        elif above or below:
            text += f": the ratio {'falls below' if above else 'rises above'} one, the reverse of the paper's direction"
    return text


def _ordering_clause(rule: Mapping, measured: Any) -> str:
    """``"<a> is 0.46 [0.45, 0.47] times <b>: smaller, where the paper has it larger"``."""
    a, b = str(rule.get("a") or "the first"), str(rule.get("b") or "the second")
    b = f"that {b}" if b.startswith(_PREPOSITIONS) else b
    claimed = "larger" if rule.get("relation", ">") == ">" else "smaller"
    other = "smaller" if claimed == "larger" else "larger"
    t = triple(measured)
    if rule.get("measure") == "ratio":
        text, ref = f"{a} is {format_value(measured, 'times')} {b}", 1.0
    else:
        text, ref = f"{a} minus {b} is {format_value(measured, real_unit(rule))}", 0.0
    if t is None or t[1] is None or t[2] is None:
        return text
    if t[1] > ref or t[2] < ref:
        found = "larger" if t[1] > ref else "smaller"
        return text + (
            f": {found}, as the paper says" if found == claimed else f": {other}, where the paper has it {claimed}"
        )
    return text + f": neither clearly larger nor smaller, where the paper has it {claimed}"


def _trend_clause(rule: Mapping, measured: Any) -> str:
    """``"<quantity> falls from 322 ms to 4.1 ms over 9 points, where the paper has it decreasing in <over>"``."""
    quantity = str(rule.get("quantity") or "the measured value")
    unit = real_unit(rule)
    shown = (
        vector_text(list(measured), unit, always=True)
        if isinstance(measured, (list, tuple))
        else format_value(measured, unit)
    )
    direction = rule.get("direction", "monotone")
    text = f"{quantity} {shown}, where the paper has it {direction} in {rule.get('over', 'its grid')}"
    ends = [triple(measured[0]), triple(measured[-1])] if isinstance(measured, (list, tuple)) and measured else []
    net = net_trend(*ends) if ends else ""  # the ends' intervals separate: a measured net trend
    reverse = {"decreasing": "rises", "increasing": "falls"}.get(str(direction))
    return text + (": the reverse of the paper's direction" if net and net == reverse else "")


def value_clause(rule: Mapping | None, measured: Any, paper_value: str | None = None) -> str:
    """What was measured against what the paper says, in words and units, for one rule (or one part's rule);
    ``paper_value``: the paper's own words or number for the claim (the band is then said as its reading)."""
    rule, measured = rule_in_force(dict(rule or {}), measured)
    kind = rule.get("kind")
    if kind == "ordering":
        return _ordering_clause(rule, measured)
    if kind == "monotone":
        return _trend_clause(rule, measured)
    if kind in ("in_band", "within_factor") and triple(measured) is not None:
        return _band_clause(rule, measured, paper_value)
    return f"{rule.get('quantity') or 'the measured value'} is {format_measured(measured, rule)}"
