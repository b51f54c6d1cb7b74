"""Whether an explored configuration reached a claim's part at all.

A claim declares the register entries its measurement reads (``DEPENDS``), but a claim of several parts may read an
entry in one part only: 003's C003-9 measures the square discriminator's linearity from the spot geometry alone, so
the compensation model it declares for its other parts never touches that part's number. A configuration that
changes only such entries leaves the part's value as the default gives it on the same random numbers (every
condition runs on the default's replicate seeds), bit for bit. Such a configuration agrees, and is counted so in the
part's share, but it explores nothing of that part: it is no evidence that the part survives a world, and it does
not count among the decided configurations a ``robust`` label needs (:mod:`tvtrack.labels`).

Only values whose equality says the computation did not change count as unchanged: estimates of a continuous
quantity and exact numbers. A count (a share of runs that lost lock: zero events under two worlds) can coincide by
chance, so a condition with a count anywhere in the part's value is always taken to have reached it.
"""

from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

from .measured import as_estimate, lost_runs
from .pooling import pool

__all__ = ["reached", "unchanged", "world_reached"]


def _is_count_method(method: str) -> bool:
    return method == "Clopper-Pearson" or method.startswith("count")


def _numbers(m: Any) -> tuple | None:
    """Every number of a part's value (each estimate's value, interval and size, in order), or None where the value
    holds a count or a value with runs that lost lock (never taken as unchanged) or is not a value at all."""
    if m is None:
        return ()
    if isinstance(m, Mapping) and set(m) == {"reading", "measured"}:  # a ByReading tag: its reading and value
        inner = _numbers(m["measured"])
        return None if inner is None else (repr(m["reading"]), *inner)
    if lost_runs(m) is not None:
        return None
    if isinstance(m, (list, tuple)):
        out: list = []
        for x in m:
            got = _numbers(x)
            if got is None:
                return None
            out += got
        return tuple(out)
    if isinstance(m, Mapping) and "value" not in m:  # parts
        return _numbers([m[k] for k in sorted(m)])
    try:
        e = as_estimate(m)
    except (TypeError, ValueError):
        return None
    if _is_count_method(str(e.method)):
        return None
    return (float(e.value), float(e.ci_low), float(e.ci_high), int(e.n))


def _same(a: tuple, b: tuple) -> bool:
    def eq(x: Any, y: Any) -> bool:
        if isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y):
            return True
        return x == y

    return len(a) == len(b) and all(eq(x, y) for x, y in zip(a, b))


def unchanged(condition: Any, replicates: Sequence[Any], runs: int | None) -> bool:
    """Whether a condition's value of one part (pooled over its ``runs`` replicates, on the default's first
    ``runs`` replicate seeds) equals the default's value pooled over the same replicates, in every number.

    Parameters
    ----------
    condition : estimate, dict or list
        The part's value under the condition.
    replicates : sequence
        The part's value in each of the default's replicates, in seed order.
    runs : int or None
        The condition's replicates (None: a hand-built record, taken as sized like the default: all of them).

    Returns
    -------
    bool
        False where either value holds a count (it may coincide by chance), or the default's replicates are fewer
        than the condition's.
    """
    k = len(replicates) if runs is None else int(runs)
    if k < 1 or k > len(replicates) or any(r is None for r in replicates[:k]):
        return False
    mine, default = _numbers(condition), _numbers(pool(list(replicates[:k])))
    return mine is not None and default is not None and bool(mine) and _same(mine, default)


def reached(rows: Sequence[Mapping], name: str, replicates: Sequence[Mapping]) -> list:
    """The condition rows (each with ``part_measured`` and ``runs``, :mod:`tvtrack.labels`) whose value of the part
    ``name`` is not :func:`unchanged` from the default's replicate rows ``replicates`` on the same random numbers."""
    reps = [r["part_measured"].get(name) for r in replicates]
    return [c for c in rows if not unchanged(c["part_measured"].get(name), reps, c.get("runs"))]


def world_reached(rows: Sequence[Mapping], name: str, replicates: Sequence[Mapping], worlds: set) -> bool:
    """Whether some condition row changed a world entry (``worlds``: their names) and is seen to have moved the part
    ``name``: its value differs from that of the same configuration without its world entries (the default's
    replicates where it changes nothing else, else the row measured at the rest, on as many replicates), or either
    value holds a count (which cannot show it did not). A row whose rest was not measured on as many replicates
    shows nothing either way; each world value measured one at a time has the default as its rest."""
    reps = [r["part_measured"].get(name) for r in replicates]
    for r in rows:
        if not set(r["changed"]) & worlds:
            continue
        rest = {k: v for k, v in r["changed"].items() if k not in worlds}
        mine = r["part_measured"].get(name)
        if not rest:
            if not unchanged(mine, reps, r.get("runs")):
                return True
            continue
        key = sorted((k, repr(v)) for k, v in rest.items())
        base = [s for s in rows if sorted((k, repr(v)) for k, v in s["changed"].items()) == key]
        base = [s for s in base if s.get("runs") == r.get("runs")]
        if not base:
            continue
        a, b = _numbers(mine), _numbers(base[0]["part_measured"].get(name))
        if not a or b is None or not _same(a, b):  # no numbers of its own (a count, a lost run): cannot say
            return True
    return False
