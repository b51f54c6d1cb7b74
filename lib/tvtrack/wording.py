"""A claim record (``results.json``) in plain words: values with their units, one sentence per claim, one
paragraph per set of runs, and the glossary of the verdict and label words.

Everything here reads the JSON dicts a run writes (:mod:`tvtrack.results`), so the report, the site and the
notebooks say the same thing in the same words. Import it through :mod:`tvtrack.results`
(``claim_summary``, ``format_measured``, ``results_summary``, ``GLOSSARY``).

Conventions
-----------
- A number carries its rule's unit, or the quantity's name where the rule has no unit ("0.62 (MSE ratio
  network / filter)").
- A deterministic number (a zero-width interval) is shown without an interval.
- A vector of more than :data:`VECTOR_SHOWN` points is summarised by its ends and its trend.
- Register entries are named by their phrases (``register[].phrases``), never by their code names.
"""

from __future__ import annotations

import math
import re
from collections import Counter
from typing import Any, Mapping

__all__ = [
    "VERDICT_WORDS",
    "LABEL_WORDS",
    "GLOSSARY",
    "PROVISIONAL",
    "SUMMARY_CHARS",
    "VECTOR_SHOWN",
    "number",
    "format_value",
    "format_measured",
    "unit_text",
    "band_text",
    "against",
    "shown_label",
    "claim_flips",
    "claim_summary",
    "results_summary",
]

#: What each verdict means, in the words a reader meets on the first screen.
VERDICT_WORDS = {
    "reproduced": "the whole 95 % interval lies where the paper's value (the rule's band) says",
    "partly": "the claim's parts disagree: some reproduced, some not",
    "not reproduced": "the whole 95 % interval lies outside the paper's band",
    "undecided": "the interval straddles an edge of the band: more runs would decide it",
    "not checkable": "the paper gives nothing this project can measure",
}
#: What each robustness label means (a label is about how sure the verdict is, not about the verdict).
LABEL_WORDS = {
    "robust": "no explored reading of the paper and no world beyond it changes the verdict",
    "limited": "holds under every reading of the paper, but not in a named world beyond it",
    "depends": "another reading of an ambiguous passage of the paper changes the verdict",
    "unstable": "independent replicates of the same run disagree decisively",
    "unexplored": "no world beyond the paper was varied: nothing to say how far it extends",
    "provisional": "too few configurations explored to label the verdict (a smoke-size run): never robust",
    "—": "no label: the claim is not checkable, or no part of it is decided (nothing to flip)",
}
GLOSSARY = {**VERDICT_WORDS, **LABEL_WORDS}
"""Every verdict and label word with its meaning (the site's tooltips, the report's glossary)."""
PROVISIONAL = "provisional"
"""The label shown for a record whose design is too small to label (``robustness.provisional``)."""
SUMMARY_CHARS = 250
"""At most this many characters in :func:`claim_summary` (two lines of a page)."""
VECTOR_SHOWN = 4
"""Vectors longer than this are summarised (ends and trend), never printed whole."""


# --- numbers ---------------------------------------------------------------------------------------------------


def number(x: Any, digits: int = 4) -> str:
    """A number in ``digits`` significant figures (``"351.6"``, ``"2.16e+05"``); text as it is."""
    if isinstance(x, bool) or x is None:
        return str(x)
    if isinstance(x, (int, float)) or hasattr(x, "__float__"):
        v = float(x)
        if not math.isfinite(v):
            return "∞" if v > 0 else ("-∞" if v < 0 else "NaN")
        return f"{v:.{digits}g}"
    return str(x)


def _finite(x: Any) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(float(x))


def _triple(value: Any) -> tuple[float, float | None, float | None] | None:
    """``(value, low, high)`` of an Estimate (or its dict) or a number (missing or infinite ends are ``None``)."""
    if hasattr(value, "to_dict") and not isinstance(value, Mapping):
        value = value.to_dict()
    if isinstance(value, Mapping) and "value" in value:
        v = value.get("value")
        if not _finite(v):
            return None
        lo, hi = value.get("ci_low"), value.get("ci_high")
        return float(v), (float(lo) if _finite(lo) else None), (float(hi) if _finite(hi) else None)
    if _finite(value):
        return float(value), float(value), float(value)
    return None


def _with_unit(text: str, unit: str) -> str:
    if not unit:
        return text
    if unit.startswith("("):
        return f"{text} {unit}"
    if unit.startswith("ratio"):
        return f"{text} ({unit})"
    return f"{text} {unit}" if unit not in ("%",) else f"{text} %"


def format_value(value: Any, unit: str = "") -> str:
    """One estimate or number with its unit: ``"351.6 [350, 353.1] x alpha"``.

    A zero-width interval (a deterministic number) shows no interval; the interval's ends get as many figures
    as they need to differ from the value (up to 6); a one-sided interval reads ``"(at most b)"``."""
    t = _triple(value)
    if t is None:
        if isinstance(value, Mapping) and "value" in value:
            return "no value"
        return _with_unit(number(value), unit) if value is not None else "no value"
    v, lo, hi = t
    if lo is None and hi is None:
        return _with_unit(number(v), unit)
    if lo is not None and hi is not None:
        if hi - lo <= 1e-12 * max(1.0, abs(v)):
            return _with_unit(number(v), unit)
        for digits in (4, 5, 6):
            shown = [number(x, digits) for x in (lo, v, hi)]
            if len(set(shown)) == 3 or (lo == v and shown[0] != shown[2]) or (hi == v and shown[0] != shown[2]):
                break
        else:
            return _with_unit(number(v), unit)
        return _with_unit(f"{shown[1]} [{shown[0]}, {shown[2]}]", unit)
    bound = f"at least {number(lo)}" if lo is not None else f"at most {number(hi)}"
    return _with_unit(f"{number(v)} ({bound})", unit)


def _vector(values: list, unit: str) -> str:
    """A long vector by its ends and its trend: ``"falls from 2.163e+05 to 0.178 over 9 points"``."""
    points = [_triple(v) for v in values]
    centres = [p[0] for p in points if p is not None]
    if len(values) <= VECTOR_SHOWN or len(centres) < 2:
        return ", ".join(format_value(v) for v in values) + (f" {unit}" if unit and values else "")
    steps = [b - a for a, b in zip(centres, centres[1:])]
    if all(s < 0 for s in steps):
        trend = "falls"
    elif all(s > 0 for s in steps):
        trend = "rises"
    elif all(abs(s) <= 1e-12 * max(1.0, abs(c)) for s, c in zip(steps, centres)):
        trend = "stays"
    else:
        trend = f"ranges {number(min(centres))} to {number(max(centres))}, going"
    return f"{trend} from {format_value(values[0], unit)} to {format_value(values[-1], unit)} over {len(values)} points"


def unit_text(rule: Mapping | None) -> str:
    """The unit a rule's quantity is measured in, else the quantity's own name in parentheses, else ``""``."""
    rule = rule or {}
    unit = str(rule.get("unit") or "").strip()
    if unit:
        return unit
    quantity = str(rule.get("quantity") or rule.get("measure") or "").strip()
    return f"({quantity})" if quantity else ""


def format_measured(value: Any, rule: Mapping | None = None) -> str:
    """Short text for a claim's ``measured`` field: each number with its unit (from ``rule``; an ``all_of``
    rule gives each part its own), deterministic numbers without an interval, long vectors summarised.

    ``"a: 2 px; b: 0.5 (ratio of MSEs)"`` for parts; ``"falls from 322 to 4.14 px over 15 points"`` for a
    long vector."""
    rule = rule or {}
    if hasattr(value, "to_dict") and not isinstance(value, Mapping):  # an Estimate
        value = value.to_dict()
    if isinstance(value, Mapping) and "value" in value and "ci_low" in value:
        return format_value(value, unit_text(rule))
    if isinstance(value, Mapping):
        parts = rule.get("parts") or {}
        return "; ".join(f"{k}: {format_measured(v, parts.get(k, {}))}" for k, v in value.items())
    if isinstance(value, (list, tuple)):
        return _vector(list(value), unit_text(rule))
    return format_value(value, unit_text(rule))


def _aside(unit: str) -> bool:
    """A unit said after the numbers in parentheses ("(ratio of MSEs)", "(quantity)") rather than after each."""
    return unit.startswith("ratio") or unit.startswith("(")


def band_text(rule: Mapping | None, with_unit: bool = True) -> str:
    """The rule's band in the quantity's unit (``"[0, 2] x alpha"``, ``"<= 2 x alpha"``, ``"5.5 s within a
    factor 1.2"``), or what an ordering or a trend asks (``"a >= b"``, ``"decreasing in P"``); ``""`` when the
    rule says nothing."""
    rule = rule or {}
    kind, unit = rule.get("kind"), (unit_text(rule) if with_unit else "")
    if kind == "within_factor" and _finite(rule.get("paper_value")):
        return f"{_with_unit(number(rule['paper_value']), unit)} within a factor {number(rule.get('factor'))}"
    lo, hi = rule.get("low"), rule.get("high")
    if _finite(lo) and _finite(hi):
        return _with_unit(f"[{number(lo)}, {number(hi)}]", unit)
    if _finite(hi):
        return "<= " + _with_unit(number(hi), unit)
    if _finite(lo):
        return ">= " + _with_unit(number(lo), unit)
    if kind == "ordering" and rule.get("relation"):
        return f"{rule.get('a', 'a')} {rule['relation']} {rule.get('b', 'b')}"
    if kind == "monotone":
        return f"{rule.get('direction', 'monotone')} in {rule.get('over', 'its grid')}"
    return ""


def against(measured: Any, rule: Mapping | None) -> str:
    """``"351.6 [350, 353.1] x alpha against <= 2 x alpha"``; a unit said in parentheses comes once, at the end."""
    rule = rule or {}
    unit = unit_text(rule)
    band = band_text(rule, with_unit=not _aside(unit))
    if _aside(unit) and band and _triple(measured) is not None:
        return f"{format_value(measured)} against {band} {unit if unit.startswith('(') else f'({unit})'}"
    text = format_measured(measured, rule)
    return f"{text} against {band}" if band and rule.get("kind") != "monotone" else text


# --- labels and flips --------------------------------------------------------------------------------------------


def _as_dict(claim: Any) -> Mapping:
    """A claim as ``results.json`` stores it: a dict as it is, a :class:`tvtrack.results.Claim` by its fields."""
    return claim if isinstance(claim, Mapping) else vars(claim)


def shown_label(claim: Mapping) -> str:
    """The label a reader sees: the record's; :data:`PROVISIONAL` in place of ``robust`` or ``unexplored`` when
    the design is too small to estimate a share (a smoke run is never shown as robust; a flip it found still
    shows as ``depends``, ``limited`` or ``unstable``); ``"—"`` without a record."""
    record = _as_dict(claim).get("robustness") or {}
    if not record:
        return "—"
    label = str(record.get("label", "—"))
    if label == "-":  # no part decided at the default: nothing to label (labels.NO_PART_LABEL)
        return "—"
    if record.get("provisional") and label in ("robust", "unexplored"):
        return PROVISIONAL
    return label


def _phrases(record: Mapping) -> dict[str, tuple[str, str, dict]]:
    """``{entry name: (title, side, {str(value): phrase})}`` from the record's register."""
    out = {}
    for e in record.get("register") or []:
        if isinstance(e, Mapping) and "name" in e:
            side = e.get("side") or ("world" if e.get("kind") in ("regime", "operating point", "model") else "reading")
            out[str(e["name"])] = (str(e.get("title") or e["name"]), side, dict(e.get("phrases") or {}))
    return out


def describe(changed: Mapping, record: Mapping) -> str:
    """A configuration's changes in plain words (the register's phrases; ``"<title> = <value>"`` without one)."""
    known = _phrases(record)
    bits = []
    for k, v in changed.items():
        title, _, phrases = known.get(str(k), (str(k).replace("_", " "), "reading", {}))
        bits.append(phrases.get(str(v)) or f"{title} = {number(v) if _finite(v) else v}")
    return " and ".join(bits) or "the default reading"  # one configuration: its changes hold together


def _side(changed: Mapping, record: Mapping) -> str:
    """``"reading"`` when every changed entry is a reading of the paper, ``"setting"`` when every one is a reading
    or an unreported setting (one at least), else ``"world"`` (as the core's flips)."""
    known = _phrases(record)
    sides = {known.get(str(k), ("", "reading"))[1] for k in changed}
    if sides <= {"reading"}:
        return "reading"
    return "setting" if sides <= {"reading", "setting"} else "world"


def claim_flips(claim: Mapping, part: str | None = None) -> list[dict]:
    """The configurations that flip the claim (or one part): ``[{text, side, kind, verdict}]``, single entries
    first (readings of the paper, then worlds beyond it), then the smallest combinations, each text said once.

    Reads ``parts[].flips`` (the explorer's attribution); for a record without it, the conditions whose decisive
    verdict differs from the claim's."""
    claim = _as_dict(claim)
    record = claim.get("robustness") or {}
    parts = record.get("parts") or {}
    names = [part] if part else list(parts)
    flips = [f for n in names for f in ((parts.get(n) or {}).get("flips") or [])]
    if not flips and not any("flips" in (parts.get(n) or {}) for n in names):
        decisive = ("reproduced", "not reproduced")
        for c in record.get("conditions") or []:
            changed = c.get("changed") or c.get("choices") or {}
            verdicts = [(c.get("parts") or {}).get(part)] if part else [c.get("verdict")]
            v = verdicts[0]
            if v in decisive and v != claim.get("verdict") and changed:
                kind = "single" if len(changed) == 1 else c.get("kind", "joint")
                flips.append({"changed": changed, "kind": kind, "verdict": v, "side": _side(changed, record)})
    out, seen = [], set()
    order = {"single": 0, "combination": 1, "pinned": 2, "joint": 3}
    for f in sorted(
        flips,
        key=lambda f: (order.get(f.get("kind"), 4), f.get("side") != "reading", len(f.get("changed") or {})),
    ):
        text = str(f.get("text") or describe(f.get("changed") or {}, record))
        if text not in seen:
            seen.add(text)
            out.append(
                {"text": text, "side": f.get("side", "reading"), "kind": f.get("kind"), "verdict": f.get("verdict")}
            )
    return out


# --- one sentence per claim ------------------------------------------------------------------------------------


def _clip(text: str, n: int) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= n else text[: n - 1].rstrip(" ,;") + "…"


_LABEL_ORDER = ("unstable", "depends", "limited", "unexplored", "robust")


def _measured_bits(claim: Mapping, max_parts: int) -> str:
    rule, measured = claim.get("rule") or {}, claim.get("measured")
    if rule.get("kind") == "all_of" and isinstance(measured, Mapping):
        info = {n: p for n, p in ((claim.get("robustness") or {}).get("parts") or {}).items() if isinstance(p, Mapping)}

        def weight(n):  # the parts that do not hold first, then the weakest labels
            p = info.get(n, {})
            lab = p.get("label")
            return (p.get("verdict") == "reproduced", _LABEL_ORDER.index(lab) if lab in _LABEL_ORDER else 9)

        shown = sorted(measured, key=weight)[:max_parts]
        parts = rule.get("parts") or {}
        text = "; ".join(f"{n}: {against(measured[n], parts.get(n))}" for n in shown)
        more = len(measured) - len(shown)
        return text + (f"; {more} more part{'s' * (more > 1)}" if more else "")
    return against(measured, rule)


def _share_text(claim: Mapping, with_ci: bool) -> str:
    parts = (claim.get("robustness") or {}).get("parts") or {}
    shares = [
        (n, p["share"]) for n, p in parts.items() if isinstance(p, Mapping) and (p.get("share") or {}).get("decided")
    ]
    if not shares:
        return ""
    name, s = min(shares, key=lambda ns: ns[1].get("value") if _finite(ns[1].get("value")) else 1.0)
    where = "" if len(parts) == 1 else f" ({name})"
    ci = f", 95 % CI {s['ci_low'] * 100:.0f}-{s['ci_high'] * 100:.0f} %" if with_ci and "ci_low" in s else ""
    return f"{s.get('agree')} of {s.get('decided', s.get('design'))} explored configurations agree{where}{ci}"


def _runs_text(claim: Mapping) -> str:
    parts = (claim.get("robustness") or {}).get("parts") or {}
    for p in parts.values():
        r = (p or {}).get("runs_to_decide") if isinstance(p, Mapping) else None
        if r and r.get("text"):  # "undecided at 3 replicates: about 7 ... would decide it" -> what decides it
            text = str(r["text"])
            return re.sub(r"^undecided at \d+ replicates?[:;] ", "", text)
    return ""


def _flip_text(flips: list[dict], n_each: int, chars: int) -> str:
    readings = [f["text"] for f in flips if f["side"] == "reading"]
    settings = [f["text"] for f in flips if f["side"] == "setting"]
    worlds = [f["text"] for f in flips if f["side"] not in ("reading", "setting")]
    bits = []
    for what, items in (
        ("flips when", readings),
        ("flips with a setting the paper did not report:", settings),
        ("does not extend to", worlds),
    ):
        if items:
            more = len(items) - n_each
            bits.append(
                f"{what} {'; '.join(_clip(t, chars) for t in items[:n_each])}"
                + (f" (+{more} more)" if more > 0 else "")
            )
    return "; ".join(bits)


def claim_summary(claim: Mapping, chars: int = SUMMARY_CHARS) -> str:
    """The claim in at most ``chars`` characters (two lines): the verdict with the measured value against the
    rule's band in the same unit; the share of the explored configurations that agree; the readings of the paper
    that flip it, then the worlds it does not extend to; for an undecided claim, how many runs would decide it.

    Parameters
    ----------
    claim : dict or tvtrack.results.Claim
        A claim as ``results.json`` stores it (``id, verdict, measured, rule, robustness, ...``), or as
        :meth:`tvtrack.results.Results.claim` returns it.
    chars : int
        The longest sentence returned.

    Returns
    -------
    str
        E.g. ``"Not reproduced: 351.6 [350, 353.1] x alpha against [0, 2] x alpha. 29 of 32 explored
        configurations agree. Flips when sigma read as the SD of the raw velocity increments."``
    """
    claim = _as_dict(claim)
    verdict = str(claim.get("verdict", ""))
    if verdict == "not checkable":
        note = claim.get("note") or (claim.get("rule") or {}).get("reason") or "nothing measurable"
        return _clip(f"Not checkable: {note}", chars)
    label = shown_label(claim)
    head = verdict[:1].upper() + verdict[1:]
    if label == PROVISIONAL:
        head += " (too few configurations to label)"
    flips = claim_flips(claim)
    # from the fullest sentence to the shortest, the first that fits
    for max_parts, with_ci, n_each, flip_chars in (
        (2, True, 2, 90),
        (2, False, 1, 80),
        (1, False, 1, 60),
        (1, False, 1, 40),
    ):
        bits = [f"{head}: {_measured_bits(claim, max_parts)}."]
        for extra in (_share_text(claim, with_ci), _flip_text(flips, n_each, flip_chars), _runs_text(claim)):
            if extra:
                bits.append(extra[:1].upper() + extra[1:] + ".")
        text = " ".join(bits)
        if len(text) <= chars:
            return text
    return _clip(text, chars)


# --- one paragraph per set of runs ---------------------------------------------------------------------------------


def _plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def results_summary(claims: list[Mapping], profile: str = "paper") -> str:
    """A short paragraph: what holds, what does not, what the runs could not decide, and on what the main
    verdicts turn (the register titles whose values flip the most claims); runs of another ``profile`` than
    ``"paper"`` are said not to be the paper-scale numbers."""
    if not claims:
        return "No claim has been checked yet."
    v = Counter(str(c.get("verdict")) for c in claims)
    labels = Counter(shown_label(c) for c in claims if c.get("verdict") != "not checkable")
    checkable = len(claims) - v["not checkable"]
    sure = labels["robust"] + labels["limited"]

    def n(k: int, one: str, many: str) -> str:
        return f"{k} {one if k == 1 else many}"

    text = [
        f"Of {_plural(len(claims), 'claim')} checked, {n(v['reproduced'], 'holds', 'hold')}, "
        f"{n(v['partly'], 'holds', 'hold')} in part and {n(v['not reproduced'], 'does', 'do')} not; the runs could "
        f"not decide {v['undecided']}, and {n(v['not checkable'], 'gives', 'give')} nothing to measure."
    ]
    if labels[PROVISIONAL]:
        text.append(
            f"{n(labels[PROVISIONAL], 'of the checkable verdicts comes', 'of the checkable verdicts come')} from a "
            "design too small to label (a smoke-size run): none of them is called robust."
        )
    else:
        text.append(
            f"Of the {checkable} checkable verdicts, {n(sure, 'survives', 'survive')} every reading of the paper "
            f"({labels['robust']} robust, {labels['limited']} only within the paper's world), "
            f"{n(labels['depends'], 'turns', 'turn')} on a reading of an ambiguous passage and "
            f"{n(labels['unstable'], 'differs', 'differ')} between independent replicates."
        )
    turns: Counter = Counter()
    for c in claims:
        record = c.get("robustness") or {}
        known = _phrases(record)
        seen = set()
        for f in record_flip_entries(c):
            title = known.get(f, (f.replace("_", " "), "", {}))[0]
            if title not in seen:
                seen.add(title)
                turns[title] += 1
    if turns:
        top = [f"{t} ({_plural(n, 'claim')})" for t, n in turns.most_common(3)]
        text.append(
            f"The verdicts turn most often on {', '.join(top[:-1]) + ' and ' if len(top) > 1 else ''}{top[-1]}."
        )
    if profile != "paper":
        text.append(f"These are {profile}-profile runs, not the paper-scale numbers.")
    return " ".join(text)


def record_flip_entries(claim: Mapping) -> list[str]:
    """The register entry names of the claim's smallest flipping configurations (singles and combinations)."""
    record = claim.get("robustness") or {}
    names: list[str] = []
    for p in (record.get("parts") or {}).values():
        for f in (p or {}).get("flips", []) if isinstance(p, Mapping) else []:
            if f.get("kind") in ("single", "combination"):
                names += [str(k) for k in (f.get("changed") or {}) if str(k) not in names]
    if not names and not any(isinstance(p, Mapping) and "flips" in p for p in (record.get("parts") or {}).values()):
        for c in record.get("conditions") or []:
            changed = c.get("changed") or c.get("choices") or {}
            if (
                len(changed) == 1
                and c.get("verdict") in ("reproduced", "not reproduced")
                and c.get("verdict") != claim.get("verdict")
            ):
                names += [str(k) for k in changed if str(k) not in names]
    return names
