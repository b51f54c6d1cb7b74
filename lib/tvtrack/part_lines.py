"""A claim's parts in plain words, from its robustness record (``results.json``'s ``robustness``, or
:meth:`tvtrack.explore.Exploration.record`): which parts hold, what a held claim's reader must also know, and one
line per part with its share over every explored configuration, its named flips and the entries that move its
value most.

Every notebook's exploration section shows :func:`exploration_lines`; the report's first screen says which parts
of a claim that holds in part hold (:func:`parts_held`) and carries a held claim's caveat (:func:`hold_note`). The
core only: no paper package is imported here.
"""

from __future__ import annotations

from typing import Any, Mapping

from .run_words import lost_basis, part_name, plain_text, share_counts
from .wording import PROVISIONAL, at_profile, claim_fields, claim_flips, side_words

__all__ = [
    "parts_held",
    "hold_note",
    "unflipped_words",
    "coverage_words",
    "part_line",
    "record_lines",
    "exploration_lines",
]

_PART_VERBS = (
    ("reproduced", "holds for"),
    ("not reproduced", "fails for"),
    ("undecided", "undecided for"),
    ("not checkable", "not checkable for"),
)
SENSITIVE = 0.1
"""The least share of the value's variation an entry must carry to be named among those that move it most."""
SENSITIVE_SHOWN = 3
"""At most this many entries are named as moving a part's value most (the rest are in the record)."""


def _and(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def _parts(claim: Mapping) -> dict[str, Mapping]:
    parts = (claim_fields(claim).get("robustness") or {}).get("parts") or {}
    return {str(n): p for n, p in parts.items() if isinstance(p, Mapping)}


def parts_held(claim: Any) -> str:
    """Which of a claim's parts hold and which do not, by verdict (``"holds for “finite” and “loss free”; fails for “not
    lower”"``, each part's name quoted), from its record; ``""`` for a claim of one part or without a record of its parts."""
    parts = _parts(claim)
    if len(parts) < 2:
        return ""
    bits = []
    for verdict, verb in _PART_VERBS:
        names = [f"“{part_name(n)}”" for n, p in parts.items() if p.get("verdict") == verdict]
        if names:
            bits.append(f"{verb} {_and(names)}")
    return "; ".join(bits)


def _lower_first(text: str) -> str:
    """A sentence made a clause: its first letter lower-cased unless it opens an acronym or a symbol (ULA, C001)."""
    return text[:1].lower() + text[1:] if text[:2].istitle() and text[:2].isalpha() else text


def hold_note(claim: Any) -> str:
    """What a reader of a claim that holds must know beside its label: its caveat (whole) and, where runs that lost
    lock carry a flip, which flip and what the runs in lock alone say; ``""`` where there is neither."""
    claim = claim_fields(claim)
    bits = []
    caveat = plain_text(str(claim.get("caveat") or "")).strip().rstrip(".")
    if caveat:
        bits.append(_lower_first(caveat))
    flips = claim_flips(claim)
    carried = [f for f in flips if (f.get("lost_runs") or {}).get("carried")]
    for f in carried:
        lost = f["lost_runs"]
        which = "its only flip" if len(flips) == 1 else "its flip"
        reps = lost.get("replicates")
        over = f" of {reps} replicate{'s' * (reps != 1)}" if reps else ""
        bits.append(
            f"{which}, under {plain_text(str(f.get('text') or ''))}, rests on the {lost['lost']} of the "
            f"{lost['runs']} runs{over} that lost lock there: over {lost_basis(lost)}runs in lock alone it is "
            f"{lost.get('in_lock_verdict')}"
        )
    return "; ".join(bits)


def unflipped_words(claim: Any) -> str:
    """A claim no explored configuration flips, and how many of those explored for each part stayed undecided
    (``"no explored configuration flips it (40 of the 43 explored for it stayed undecided)"``): not flipped is not
    shown to hold where most stayed undecided."""
    parts = _parts(claim)
    said = []
    for n, p in parts.items():
        share, name = p.get("share") or {}, "" if len(parts) == 1 else f"{part_name(n)}: "
        if share.get("design"):
            said.append(
                f"{name}{int(share.get('undecided') or 0)} of the {share['design']} explored for it stayed undecided"
            )
        elif p.get("verdict") == "undecided":
            said.append(f"{name}undecided at the default, so nothing to flip")
    if parts and all(
        p.get("verdict") == "undecided" and not (p.get("share") or {}).get("design") for p in parts.values()
    ):
        return "nothing to flip: undecided at the default"
    return "no explored configuration flips it" + (f" ({'; '.join(said)})" if said else "")


def coverage_words(record: Mapping, verdict: str | None = None) -> str:
    """A record's ``coverage`` line as a reader needs it: a claim that is not checkable (``verdict``, or every part
    of the record) carries no label because the default has no verdict to flip (conditions under other readings may
    still be measured), not because no part was decided."""
    text = str(record.get("coverage") or "")
    verdicts = {p.get("verdict") for p in (record.get("parts") or {}).values() if isinstance(p, Mapping)}
    if verdict == "not checkable" or verdicts == {"not checkable"}:
        for older in ("no part decided at the default: nothing to flip", "not checkable: nothing measured"):
            text = text.replace(f"no label ({older})", "no label (not checkable at the default: no verdict to flip)")
    return text


def _label_words(part: Mapping) -> str:
    label = str(part.get("label") or "-")
    if label not in ("-", "—"):
        return label
    if part.get("verdict") == "not checkable":
        return "no label (not checkable at the default: no verdict to flip)"
    return "no label (undecided at the default: nothing to flip)"


def part_line(head: str, part: Mapping) -> str:
    """One part as a Markdown bullet: its verdict and label; how many of every explored configuration agree, flip
    and stay undecided (with the share agreeing, 95 %); every flip in plain words with its kind; the runs
    projected to decide an undecided part; the entries that move its value most (their share of its variation)."""
    text = f"- **{head}**: {part.get('verdict')}, {_label_words(part)}"
    share = part.get("share") or {}
    counts, _, beside = share_counts(share).partition("; ")  # the share, then what is counted beside it
    if counts:
        text += f"; {counts}"
        if share.get("ci_low") is not None and share.get("ci_high") is not None:
            text += f" (share agreeing {share['ci_low']:.2f}-{share['ci_high']:.2f}, 95 %)"
        text += f"; {beside}" if beside else ""
    sides = side_words()
    flips = [f for f in part.get("flips") or [] if isinstance(f, Mapping)]
    if flips:
        text += "; flipped by: " + "; ".join(
            f"{f.get('verdict')} when {plain_text(str(f.get('text') or ''))} ({sides.get(f.get('side'), f.get('side'))})"
            for f in flips
        )
    elif counts:
        text += "; no explored configuration flips it"
    if (part.get("runs_to_decide") or {}).get("text"):
        text += f"; {part['runs_to_decide']['text']}"
    moves = [
        f"{d['title']} ({100 * float(d['score']):.0f} %)"
        for d in (part.get("sensitivity") or [])
        if isinstance(d, Mapping) and float(d.get("score") or 0) >= SENSITIVE
    ][:SENSITIVE_SHOWN]
    if moves:
        text += "; its value moves most with: " + "; ".join(moves)
    return text + "."


def record_lines(cid: str, record: Mapping, verdict: str | None = None) -> list[str]:
    """A claim's lines: what its label covers (:func:`coverage_words`), then one line per part (:func:`part_line`),
    the record as a reader sees it (a provisional design's parts read :data:`tvtrack.wording.PROVISIONAL`)."""
    shown = at_profile([{"robustness": dict(record)}], "paper")[0]["robustness"]
    parts = {str(n): p for n, p in (shown.get("parts") or {}).items() if isinstance(p, Mapping)}
    label = PROVISIONAL if shown.get("provisional") and shown.get("label") in ("robust", "unexplored") else None
    cover = coverage_words(shown, verdict)
    lines = [f"- **{cid}**: {label + ': ' if label else ''}{cover}"]
    for name, part in parts.items():
        lines.append("  " + part_line(cid if len(parts) == 1 else f"{cid} ({part_name(name)})", part))
    return lines


LEAD = (
    "Each claim part over every configuration explored for it (one at a time, joint samples, pinned conditions): its "
    "verdict and label, how many agree, flip and stay undecided, every flip by name with its kind, and the register "
    "entries that move its value most (their share of its variation over the one-at-a-time values)."
)
""":func:`exploration_lines`' first paragraph: what each line says."""


def exploration_lines(*explorations: Any, claim_ids: list[str] | None = None) -> str:
    """Every claim of ``explorations`` (``claim_ids``, default all of each one's) part by part, as Markdown after
    :data:`LEAD`: agree / flip / undecided over every explored configuration, the flips by name and the entries
    that move each part most."""
    lines = [LEAD, ""]
    for ex in explorations:
        ids = [c for c in ex.rules if claim_ids is None or c in claim_ids]
        lines += [line for cid in ids for line in record_lines(cid, ex.record(cid))]
    return "\n".join(lines)
