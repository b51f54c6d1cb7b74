"""Values in words: a measured value (an estimate with its interval, a number, a vector along a grid) as a reader
meets it in the report, the site and the notebooks, with its rule's unit (:mod:`tvtrack.wording` builds the
sentences around it).

- A number carries its rule's unit, or the quantity's name where the rule has no unit ("0.62 (MSE ratio
  network / filter)").
- A deterministic number (a zero-width interval) is shown without an interval.
- A vector of more than :data:`VECTOR_SHOWN` points is summarised by its ends and its trend.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

__all__ = [
    "VECTOR_SHOWN",
    "number",
    "finite",
    "triple",
    "with_unit",
    "format_value",
    "vector_text",
    "format_measured",
    "unit_text",
    "value_range",
    "setting",
    "percent",
]

VECTOR_SHOWN = 4
"""Vectors longer than this are summarised (ends and trend), never printed whole."""


def number(x: Any, digits: int = 4) -> str:
    """A number in ``digits`` significant figures (``"351.6"``, ``"2.163e+06"``); below a million it
    is written out in full, as a reader writes it, every integer digit shown (``"28395"``, not ``"28390"``), beyond it with an exponent; text as it is."""
    if isinstance(x, bool) or x is None:
        return str(x)
    if isinstance(x, str):  # numpy's str_ too: it has a __float__
        return x
    if getattr(getattr(x, "dtype", None), "kind", "") == "b":  # numpy's bool_: a truth value, not 1 or 0
        return str(bool(x))
    if isinstance(x, (int, float)) or hasattr(x, "__float__"):
        v = float(x)
        if not math.isfinite(v):
            return "∞" if v > 0 else ("-∞" if v < 0 else "NaN")
        if 10**digits <= abs(v) < 1e6:  # more integer digits than figures: all of them, as a reader writes it
            return f"{v:.0f}"
        text = f"{v:.{digits}g}"
        return f"{float(text):.0f}" if "e+" in text and abs(float(text)) < 1e6 else text
    return str(x)


def percent(share: float) -> str:
    """A share (0..1) in whole per cent, as a reader writes it: ``"38%"``; a share that is neither 0 nor 1 never
    reads as either (``"<1%"``, ``">99%"``), so a rare event is not said to be absent."""
    text = f"{share:.0%}"
    if 0 < share and text == "0%":
        return "<1%"
    if share < 1 and text == "100%":
        return ">99%"
    return text


def value_range(low: Any, high: Any, spec: str = "g") -> str:
    """The range of a value over paths or trials, ``"0.03..0.05"`` in the format ``spec``; a single value where both
    ends print alike (``"0.032"``, never ``"0.032..0.032"``)."""
    a, b = format(low, spec), format(high, spec)
    return a if a == b else f"{a}..{b}"


def setting(name: Any, value: Any) -> str:
    """A register entry set to a value, as a reader meets it: ``"spectral index = 1.667"``, ``"restart_accel_var =
    1e+06"`` (a number in :func:`number`'s four figures, never ``1.6666666666666667`` or ``1000000.0``); text and
    truth values as they are."""
    return f"{name} = {number(value)}"


def finite(x: Any) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(float(x))


def triple(value: Any) -> tuple[float, float | None, float | None] | None:
    """``(value, low, high)`` of an Estimate (or its dict) or a number (missing or infinite ends are ``None``)."""
    if hasattr(value, "to_dict") and not isinstance(value, Mapping):
        value = value.to_dict()
    if isinstance(value, Mapping) and "value" in value:
        v = value.get("value")
        if not finite(v):
            return None
        lo, hi = value.get("ci_low"), value.get("ci_high")
        return float(v), (float(lo) if finite(lo) else None), (float(hi) if finite(hi) else None)
    if finite(value):
        return float(value), float(value), float(value)
    return None


def with_unit(text: str, unit: str) -> str:
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
    t = triple(value)
    if t is None:
        if isinstance(value, Mapping) and "value" in value:
            return "no value"
        return with_unit(number(value), unit) if value is not None else "no value"
    v, lo, hi = t
    if lo is None and hi is None:
        return with_unit(number(v), unit)
    if lo is not None and hi is not None:
        if hi - lo <= 1e-12 * max(1.0, abs(v)):
            return with_unit(number(v), unit)
        for digits in (4, 5, 6):
            shown = [number(x, digits) for x in (lo, v, hi)]
            if len(set(shown)) == 3 or (lo == v and shown[0] != shown[2]) or (hi == v and shown[0] != shown[2]):
                break
        else:
            return with_unit(number(v), unit)
        return with_unit(f"{shown[1]} [{shown[0]}, {shown[2]}]", unit)
    bound = f"at least {number(lo)}" if lo is not None else f"at most {number(hi)}"
    return with_unit(f"{number(v)} ({bound})", unit)


def vector_text(values: list, unit: str, always: bool = False) -> str:
    """A long vector (any of two points or more with ``always``) by its ends and its trend: ``"falls from
    2.163e+05 to 0.178 over 9 points"``."""
    points = [triple(v) for v in values]
    centres = [p[0] for p in points if p is not None]
    if (len(values) <= VECTOR_SHOWN and not always) or len(centres) < 2:
        return ", ".join(format_value(v) for v in values) + (f" {unit}" if unit and values else "")
    steps = [b - a for a, b in zip(centres, centres[1:])]
    if all(s < 0 for s in steps):
        trend = "falls"
    elif all(s > 0 for s in steps):
        trend = "rises"
    elif all(abs(s) <= 1e-12 * max(1.0, abs(c)) for s, c in zip(steps, centres)):
        trend = "stays"
    else:  # neither falls nor rises throughout: its measured net trend, then how far it strays between them
        up, down = _measured_steps([p for p in points if p is not None])
        rise = f"{up} of its {len(steps)} steps measurably rise{'s' if up == 1 else ''}" if up else None
        rise = rise or f"no single one of its {len(steps)} steps measurably rises"  # a net rise may still be measured
        moves = f"{rise} and {down or 'none'} fall{'s' if down == 1 or not down else ''}"
        net = net_trend(points[0], points[-1])
        against = {"falls": up, "rises": down}.get(net, 1)  # a net trend no measured step goes against is steady
        ends = (
            f"{net} from {format_value(values[0], unit)} to {format_value(values[-1], unit)} over {len(values)} points"
        )
        spread = f"between {number(min(centres))} and {with_unit(number(max(centres)), unit)}"
        return f"{ends}{', not steadily' if against else ''} ({moves}; {spread})"
    return f"{trend} from {format_value(values[0], unit)} to {format_value(values[-1], unit)} over {len(values)} points"


def net_trend(first: tuple | None, last: tuple | None) -> str:
    """``"falls"`` or ``"rises"`` where the last point's interval lies wholly below (above) the first's (a point
    without an interval is its own), else ``"goes"``."""
    if first is None or last is None:
        return "goes"
    (a, alo, ahi), (b, blo, bhi) = first, last
    alo, ahi = a if alo is None else alo, a if ahi is None else ahi
    blo, bhi = b if blo is None else blo, b if bhi is None else bhi
    return "falls" if bhi < alo else "rises" if blo > ahi else "goes"


def _measured_steps(points: list) -> tuple[int, int]:
    """Steps that measurably rise and fall: the next point's interval wholly above (below) this one's (a point
    without an interval is its own)."""
    up = down = 0
    for (a, alo, ahi), (b, blo, bhi) in zip(points, points[1:]):
        alo, ahi = a if alo is None else alo, a if ahi is None else ahi
        blo, bhi = b if blo is None else blo, b if bhi is None else bhi
        up += blo > ahi
        down += bhi < alo
    return up, down


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
        return vector_text(list(value), unit_text(rule))
    return format_value(value, unit_text(rule))


# --- labels and flips --------------------------------------------------------------------------------------------
