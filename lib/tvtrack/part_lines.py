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

from .flip_words import flip_with_kind, mixed_kinds
from .run_words import explored_rows, lost_basis, part_name, parts_by_name, plain_text, share_counts
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
    ("partly", "holds in part for"),
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
    return parts_by_name(claim_fields(claim).get("robustness") or {})


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
        which = "its only flip" if len(flips) == 1 else f"one of its {len(flips)} flips"
        reps = lost.get("replicates")
        over = f" of {reps} replicate{'s' * (reps != 1)}" if reps else ""
        bits.append(
            f"{which}, under {plain_text(str(f.get('text') or ''))}, rests on the {lost['lost']} of the "
            f"{lost['runs']} runs{over} that lost lock there: over {lost_basis(lost)}runs in lock alone it is "
            f"{lost.get('in_lock_verdict')}"
        )
    return "; ".join(bits)


def _off_flips(part: Mapping) -> list[Mapping]:
    """The part's flips outside the paper's operating point (counted beside its label, never in it)."""
    return [f for f in (part.get("off_operating_point") or {}).get("flips") or [] if isinstance(f, Mapping)]


def _off_words(flips: list[Mapping]) -> str:
    """``"not reproduced when a camera at 5 frames/s (why)"``: flips outside the operating point, joined."""
    return "; ".join(
        f"{f.get('verdict')} when {plain_text(str(f.get('text') or ''))}"
        + (f" ({plain_text(str(f['why']))})" if f.get("why") else "")
        for f in flips
    )


def _unnamed(share: Mapping) -> int:
    """The share's count of flips, for a part that names none (a flip the attribution did not keep, or an older
    record's: one without ``flip`` counts its decided configurations that disagree as ``decided - agree``)."""
    if "flip" not in share and share.get("decided") is not None:
        return max(int(share["decided"]) - int(share.get("agree") or 0), 0)
    return int(share.get("flip") or 0)


def unflipped_words(claim: Any) -> str:
    """A claim none of whose parts has a named flip, and how many of those explored for each part stayed undecided
    (``"no explored configuration flips it (40 of the 43 explored for it stayed undecided)"``): not flipped is not
    shown to hold where most stayed undecided. A flip outside the paper's operating point (counted beside the label)
    or one the share counts without a name is said; a claim with no decided part, or none explored, has nothing
    explored that could flip it."""
    parts = _parts(claim)
    decided = {n: p for n, p in parts.items() if p.get("verdict") in ("reproduced", "not reproduced", "partly")}
    if not decided:
        verdicts = {p.get("verdict") for p in parts.values()}
        if verdicts == {"not checkable"}:
            return "nothing to flip: not checkable at the default"
        if verdicts == {"undecided"}:
            return "nothing to flip: undecided at the default"
        return "nothing to flip: no part decided at the default" if parts else "no configuration was explored for it"
    if not any((p.get("share") or {}).get("design") for p in decided.values()):
        return "no configuration was explored for it"
    said, off_any, unnamed_any = [], False, False
    for n, p in parts.items():
        share, name = p.get("share") or {}, "" if len(parts) == 1 else f"{part_name(n)}: "
        if share.get("design"):
            bit = f"{int(share.get('undecided') or 0)} of the {share['design']} explored for it stayed undecided"
            if _unnamed(share) and not p.get("flips"):
                k = _unnamed(share)
                bit += f", {k} flip{'s' * (k != 1)} but {'is' if k == 1 else 'are'} not named in the record"
                unnamed_any = True
            if _off_flips(p):
                bit += f", while outside the paper's operating point, counted beside the label, it reads {_off_words(_off_flips(p))}"
                off_any = True
            said.append(name + bit)
        elif p.get("verdict") == "undecided":
            said.append(f"{name}undecided at the default, so nothing to flip")
        elif n in decided:
            said.append(f"{name}no configuration explored for it")
    lead = "no explored configuration flips it"
    lead = "no configuration at the paper's operating point flips it" if off_any else lead
    lead = "no named configuration flips it" if unnamed_any else lead
    return lead + (f" ({'; '.join(said)})" if said else "")


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


def _open_words(flip: Mapping) -> str:
    """``"; the smallest found: ... stays undecided"`` for a flip whose smaller subsets stayed undecided (it is the
    smallest subset found to flip the part, not shown to be the smallest that does); else empty."""
    open_ = [plain_text(str(t)) for t in flip.get("undecided_subsets") or ()]
    return (
        f"; the smallest found: {'; '.join(open_)} {'stays' if len(open_) == 1 else 'stay'} undecided" if open_ else ""
    )


def _flip_words(part: Mapping, share: Mapping, counted: bool, record: Mapping | None = None) -> str:
    """``"; flipped by: ..."``: a part's named flips with their kinds, then those outside the paper's operating
    point (counted beside the label); where it names none, what its counts say (never "no explored configuration
    flips it" beside a count of flips, or of flips outside the operating point)."""
    sides = side_words()
    flips = [f for f in part.get("flips") or [] if isinstance(f, Mapping)]
    off = _off_flips(part)
    text = ""
    if flips:
        text += "; flipped by: " + "; ".join(
            f"{f.get('verdict')} when {plain_text(flip_with_kind(f, record))}{_open_words(f)}"
            if record is not None and (mixed_kinds(f, record) or f.get("side") == "unattributed")
            else f"{f.get('verdict')} when {plain_text(str(f.get('text') or ''))} "
            f"({sides.get(f.get('side'), f.get('side'))}{_open_words(f)})"
            for f in flips
        )
    elif counted and _unnamed(share):
        k = _unnamed(share)
        text += f"; {'its flip is' if k == 1 else f'its {k} flips are'} not named in the record"
    elif counted:
        text += (
            "; no configuration at the paper's operating point flips it"
            if off
            else "; no explored configuration flips it"
        )
    if off:
        text += f"; outside the paper's operating point (counted beside the label) flipped by: {_off_words(off)}"
    return text


def part_line(head: str, part: Mapping, explored: int = 0, record: Mapping | None = None) -> str:
    """One part as a Markdown bullet: its verdict and label; how many of every explored configuration agree, flip
    and stay undecided (with the share agreeing, 95 %), and how many of the claim's ``explored`` configurations do
    not measure the part (a reading there leaves it out); every flip in plain words with its kind; the runs
    projected to decide an undecided part; the entries that move its value most (their share of its variation)."""
    text = f"- **{head}**: {part.get('verdict')}, {_label_words(part)}"
    share = part.get("share") or {}
    counts, _, beside = share_counts(share).partition("; ")  # the share, then what is counted beside it
    if counts:
        text += f"; {counts}"
        left = explored - int(share.get("design") or 0)
        verb = "does" if left == 1 else "do"
        text += f" ({left} of {explored} explored configurations {verb} not measure this part)" if left > 0 else ""
        if share.get("ci_low") is not None and share.get("ci_high") is not None:
            text += f" (share agreeing {share['ci_low']:.2f}-{share['ci_high']:.2f}, 95 %)"
        text += f"; {beside}" if beside else ""
    text += _flip_words(part, share, bool(counts), record)  # with the record, a mix names each change's kind
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
    cover = coverage_words(shown, verdict)
    word = str(shown.get("label") or "")
    if shown.get("provisional") and word in ("robust", "unexplored"):  # the record's label word is not shown
        cover = PROVISIONAL + (cover[len(word) :] if cover.startswith(word) else f": {cover}")
    lines = [f"- **{cid}**: {cover}"]
    designs = (int((p.get("share") or {}).get("design") or 0) for p in parts.values())
    explored = len(explored_rows(shown)) or max(designs, default=0)  # a record without its rows: the widest share
    for name, part in parts.items():
        head = cid if len(parts) == 1 else f"{cid} ({part_name(name)})"
        lines.append("  " + part_line(head, part, explored, shown))
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
