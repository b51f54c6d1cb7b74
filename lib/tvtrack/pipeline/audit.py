"""An independent check of the robustness labels in finished runs, from their ``results.json`` alone.

The label machinery (:mod:`tvtrack.labels`, :mod:`tvtrack.attribution`) writes, per claim, every condition it
measured with its runs and verdicts, and per part the share, the named flips and the label. This module re-reads
those records against the rules ``docs/verdicts.md`` states, without the code that wrote them, so that a label
that says more than its own record shows is found in the records a reader sees:

* **sized**: a condition with a decisive part verdict ran at least the replicates the default needed to decide
  (``design["replicates_needed"]``); so did every named flip;
* **declared**: every condition changes only entries of the claim's register (the entries its measurement
  declares it reads);
* **share**: the part's agree / flip / undecided equal the counts over its distinct one-at-a-time and joint
  configurations, and add up to all of them; the pinned configurations (known flips outside the design) are
  counted beside it as their verdicts give;
* **sides**: a flip's side is the side of its entries (a reading, an unreported setting, a world; ``unattributed``
  when readings or settings mix with worlds), never ``world`` when it changes a reading or a setting, and
  ``unattributed`` when it changes more than one entry beyond the largest subset the search tries
  (``design["max_subset"]``: a flip of one entry more is its own smallest, every smaller subset tried);
* **smallest**: every strict subset of a named flip's changes that the search tries (2 up to
  ``design["max_subset"]`` entries) was measured, and so was each single entry where the one-at-a-time stage ran;
  no sized configuration that changes a strict subset of a named flip's changes flips the part too; every sized
  configuration that flips the part contains a named flip (a configuration of one run flips
  only where it also differs from the default's run on the same random numbers);
* **label**: ``robust`` and ``unexplored`` parts have no flip, a ``limited`` part only flips on the world side,
  a ``depends`` part has a flip by a reading, a setting or an unattributed mix; a ``robust`` part with random draws
  was decided in as many of its explored configurations as a share needs (32, or all of a smaller design).

``tvtrack report`` prints the count of problems, and REPRODUCTION.md lists each one.
"""

from __future__ import annotations

import itertools
from typing import Any, Mapping, Sequence

from ..register import leaves_operating_point, side_of

__all__ = ["audit_claim", "audit_runs", "audit_markdown"]

_DECISIVE = ("reproduced", "not reproduced", "partly")
#: Explored configurations a share needs (docs/verdicts.md; a record's ``design["min_share_design"]`` where it
#: sets another): a robust part must be decided in this many.
_SHARE_DESIGN = 32


def _items(changed: Mapping[str, Any]) -> set:
    return {(k, repr(v)) for k, v in changed.items()}


def _distinct(conditions: Sequence[Mapping], kinds: tuple[str, ...] = ("single", "joint")) -> list[Mapping]:
    """The configurations of ``kinds`` (default one at a time and joint, as the share counts them), each once."""
    out, seen = [], set()
    for c in conditions:
        key = frozenset(_items(c["changed"]))
        if c.get("kind") in kinds and c["changed"] and key not in seen:
            seen.add(key)
            out.append(c)
    return out


def _pinned_problems(
    where: str, share: Mapping, pinned: Sequence[Mapping], name: str, default: str, key: str = "pinned"
) -> list[str]:
    """The pinned configurations (known flips, outside the design) must be counted beside the share
    (``share["pinned"]``) as their verdicts give, so that a flip they name is never shown beside a share without it;
    so must the subset search's combinations (``key="combinations"``)."""
    if not pinned and key not in share:
        return []
    verdicts = [c["parts"][name] for c in pinned]
    agree = sum(v == default for v in verdicts)
    flip = sum(v in _DECISIVE and v != default for v in verdicts)
    counted = {"agree": agree, "flip": flip, "undecided": len(verdicts) - agree - flip}
    shown = {k: int((share.get(key) or {}).get(k) or 0) for k in counted}
    if counted == shown:
        return []
    return [f"{where}: the {key} beside the share read {shown}, their verdicts give {counted}"]


def _off_point_problems(where: str, part: Mapping, off_rows: Sequence[Mapping], name: str, default: str) -> list[str]:
    """The configurations outside the paper's stated operating point (the register's ``off_operating_point``, or an
    ``operating_point_lost`` reason the exploration gave) must be counted beside the label (``part["off_operating_point"]``) as their verdicts give, never among its flips."""
    kinds = ("single", "joint", "pinned", "combination")
    verdicts = [c["parts"][name] for c in _distinct(off_rows, kinds)]
    agree = sum(v == default for v in verdicts)
    flip = sum(v in _DECISIVE and v != default for v in verdicts)
    counted = {"agree": agree, "flip": flip, "undecided": len(verdicts) - agree - flip} if verdicts else {}
    beside = part.get("off_operating_point") or {}
    shown = {k: int(beside[k]) for k in ("agree", "flip", "undecided") if k in beside}
    out = (
        []
        if counted == shown
        else [f"{where}: outside the operating point the record counts {shown}, its rows give {counted}"]
    )
    outside = [_items(c["changed"]) for c in off_rows]
    for f in part.get("flips") or ():
        if _items(f["changed"]) in outside:
            out.append(
                f"{where}: the flip at {f['text']} leaves the paper's operating point and is counted in the label"
            )
    return out


def _expected_side(changed: Mapping[str, Any], kinds: Mapping[str, str]) -> str:
    sides = {side_of(kinds.get(k, "reading")) for k in changed}
    if sides == {"world"}:
        return "world"
    if "world" in sides:
        return "unattributed"
    return "setting" if "setting" in sides else "reading"


def _untried(flip: Mapping, rb: Mapping, max_subset: int) -> list[str]:
    """The strict subsets of a named flip's changes that its record should hold and does not: every one of 2 up
    to ``max_subset`` entries (the subset search tries them before it names a larger flip), and each single entry
    where the one-at-a-time stage ran (``design["one_at_a_time"]``)."""
    items = sorted(_items(flip["changed"]))
    have = {frozenset(_items(c["changed"])) for c in rb.get("conditions") or ()}
    first = 1 if (rb.get("design") or {}).get("one_at_a_time") else 2
    sizes = range(first, min(len(items) - 1, max_subset) + 1)
    missing = [sub for n in sizes for sub in itertools.combinations(items, n) if frozenset(sub) not in have]
    return [", ".join(f"{k} = {v}" for k, v in sub) for sub in missing]


def _reachable(rb: Mapping, off: Mapping[str, Sequence]) -> int:
    """The configurations of the claim's register entries other than the default that keep the paper's operating
    point (each entry's values less its marked ones), less those the exploration reports it could not keep there."""
    n = 1
    for e in rb.get("register") or ():
        n *= len([v for v in e.get("values") or [e.get("default")] if v not in (e.get("off_operating_point") or [])])
    lost = _distinct(
        [
            c
            for c in rb.get("conditions") or ()
            if c.get("operating_point_lost") and not leaves_operating_point(c["changed"], off)
        ]
    )
    return n - 1 - len(lost)


def _robust_problems(where: str, part: Mapping, rb: Mapping, off: Mapping[str, Sequence]) -> list[str]:
    """A ``robust`` part must rest on a share whose design, and whose decided configurations, each number at least
    what a share needs: 32 (a record's ``design["min_share_design"]`` where it states another), or every reachable
    configuration where there are fewer, with or without random draws; a configuration that left the part's value
    as the default's (``share["unchanged"]``, :mod:`tvtrack.reach`) never reached it and is not counted."""
    if part.get("label") != "robust":
        return []
    share = part.get("share")
    if not share:
        return [f"{where}: labelled robust without a share of explored configurations"]
    same, design = int(share.get("unchanged") or 0), int(share.get("design") or 0)
    decided = int(share.get("agree") or 0) + int(share.get("flip") or 0) - same
    reachable = _reachable(rb, off)
    need = min(int((rb.get("design") or {}).get("min_share_design", _SHARE_DESIGN)), reachable)
    out = [f"{where}: labelled robust over {design} explored configurations (a share needs {need})"] * (design < need)
    need = min(need, max(reachable - same, 1))  # of the configurations that can reach the part
    if decided < need:
        out.append(
            f"{where}: labelled robust, but only {decided} of its {design} explored configurations decided it "
            f"(a share needs {need})"
        )
    return out


def _part_problems(cid: str, name: str, part: Mapping, rb: Mapping, needed: int, kinds: Mapping) -> list[str]:
    """The problems of one part's share, flips and label (see the module)."""
    max_subset = int((rb.get("design") or {}).get("max_subset", 3))
    where = cid if len(rb["parts"]) == 1 else f"{cid} ({name})"
    default, out = part["verdict"], []
    if default not in _DECISIVE:  # nothing to flip: no share, no flips, no label to check
        return out
    off = {e["name"]: e.get("off_operating_point") or [] for e in rb.get("register") or () if "name" in e}
    every = [c for c in rb["conditions"] if name in c.get("parts", {})]
    # outside it (a marked register value, or a configuration the exploration said it could not keep there): beside
    rows = [c for c in every if not (leaves_operating_point(c["changed"], off) or c.get("operating_point_lost"))]
    out += _off_point_problems(where, part, [c for c in every if c not in rows], name, default)
    share = part.get("share")
    if share:
        verdicts = [c["parts"][name] for c in _distinct(rows)]
        agree = sum(v == default for v in verdicts)
        flip = sum(v in _DECISIVE and v != default for v in verdicts)
        counted = (agree, flip, len(verdicts) - agree - flip, len(verdicts))
        shown = (share["agree"], share["flip"], share["undecided"], share["design"])
        if counted != shown:
            out.append(
                f"{where}: the share reads {shown[:3]} of {shown[3]}, its configurations give {counted[:3]} of {counted[3]}"
            )
        out += _pinned_problems(where, share, _distinct(rows, ("pinned",)), name, default)
        out += _pinned_problems(where, share, _distinct(rows, ("combination",)), name, default, "combinations")
    first = (part.get("replicate_verdicts") or [None])[0]  # the default's run on the conditions' random numbers
    crn = first if first in _DECISIVE else default
    flipping = [
        c
        for c in rows
        if c["parts"][name] in _DECISIVE
        and c["parts"][name] != default
        and c.get("runs", needed) >= needed
        and (c.get("runs", 1) > 1 or c["parts"][name] != crn)  # one run must differ from its own default run too
    ]
    flips = part.get("flips") or []
    for f in flips:
        changes = ", ".join(f"{k} = {v}" for k, v in f["changed"].items())
        if f.get("runs", needed) < needed:
            out.append(f"{where}: the flip at {changes} ran {f['runs']} replicates, the default needed {needed}")
        side = _expected_side(f["changed"], kinds)
        if len(f["changed"]) > max_subset + 1 and f["side"] != "unattributed":
            out.append(
                f"{where}: the flip at {changes} changes {len(f['changed'])} entries, more than one beyond the "
                f"{max_subset} the subset search tried, and is filed as {f['side']}"
            )
        if f["side"] != side and not (f["side"] == "unattributed" and f.get("note")):
            out.append(f"{where}: the flip at {changes} is filed as {f['side']}, its entries make it {side}")
        out += [f"{where}: the flip at {changes} is named with {u} never measured" for u in _untried(f, rb, max_subset)]
        smaller = [c for c in flipping if _items(c["changed"]) < _items(f["changed"])]
        if smaller:
            out.append(f"{where}: the flip at {changes} is not the smallest: {smaller[0]['text']} flips it too")
    for c in flipping:
        if not any(_items(f["changed"]) <= _items(c["changed"]) for f in flips):
            out.append(f"{where}: {c['text']} flips the part and no named flip explains it")
    sides = {f["side"] for f in flips}
    label = part.get("label")
    if label in ("robust", "unexplored") and flips:
        out.append(f"{where}: labelled {label} with {len(flips)} flip(s)")
    out += _robust_problems(where, part, rb, off)
    if label == "limited" and (not flips or sides != {"world"}):
        out.append(f"{where}: labelled limited, but its flips are on the sides {sorted(sides) or 'none'}")
    if label == "depends" and not sides & {"reading", "setting", "unattributed"}:
        out.append(f"{where}: labelled depends without a flip by a reading, a setting or an unattributed mix")
    return out


def audit_claim(claim: Mapping) -> list[str]:
    """The problems of one claim's robustness record (see the module); an empty list when it has none.

    Parameters
    ----------
    claim : mapping
        One entry of ``results.json``'s ``claims``.
    """
    rb = claim.get("robustness")
    if not rb or not rb.get("parts"):
        return []
    cid = claim["id"]
    design = rb.get("design") or {}
    needed = (design.get("replicates_needed") or {}).get(cid)
    needed = int(needed) if needed is not None else len(rb.get("replicates") or ())
    kinds = {e["name"]: e.get("kind", "reading") for e in rb.get("register") or ()}
    out = []
    for c in rb.get("conditions") or ():
        unknown = sorted(set(c["changed"]) - set(kinds))
        if unknown:
            out.append(f"{cid}: a {c.get('kind', 'single')} condition changes {unknown}, not in the claim's register")
        decisive = [p for p, v in c.get("parts", {}).items() if v in _DECISIVE]
        if decisive and c.get("runs", needed) < needed:
            out.append(f"{cid}: {c['text']} counts at {c['runs']} replicates, the default needed {needed}")
    for name, part in rb["parts"].items():
        out += _part_problems(cid, name, part, rb, needed, kinds)
    return out


def audit_runs(runs: Mapping[str, tuple[dict | None, dict | None]]) -> dict[str, list[str]]:
    """Every finished notebook's problems: ``{notebook: [problem, ...]}`` over the (run record, results) pairs of
    :func:`tvtrack.pipeline.report.collect_runs`; a notebook without results is left out."""
    return {nb: [p for c in data.get("claims", ()) for p in audit_claim(c)] for nb, (_, data) in runs.items() if data}


def audit_markdown(problems: Mapping[str, Sequence[str]]) -> list[str]:
    """The audit as a section of REPRODUCTION.md: the count, then each problem by notebook."""
    total = sum(len(v) for v in problems.values())
    head = [
        "## The labels checked against their own records",
        "",
        "Each claim's record was re-read without the code that wrote it: conditions sized as the default needed, "
        "entries the claim declares, shares that count every configuration, flips on the side of their entries "
        "and named by the smallest configuration that flips, labels that follow from the flips.",
        "",
    ]
    if not problems:
        return head + ["No finished run to check.", ""]
    if not total:
        return head + [f"No problem in {len(problems)} notebook(s).", ""]
    lines = head + [f"{total} problem(s):", ""]
    for nb, items in problems.items():
        lines += [f"- `{nb}`: {p}" for p in items]
    return lines + [""]
