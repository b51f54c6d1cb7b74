"""Sentences about a claim's runs (:func:`tvtrack.wording.claim_summary`): how many independent replicates would
decide an undecided claim, where runs that lost lock carry its verdict or a flip, said over the replicates
whose draws they were counted on, how many explored configurations agree, flip or stay undecided, and why a
claim cannot be checked."""

from __future__ import annotations

import math
import re
from typing import Mapping

__all__ = [
    "slowest_part",
    "runs_sentence",
    "lock_sentence",
    "lost_lead",
    "lost_basis",
    "thin_share",
    "part_name",
    "plain_text",
    "not_checkable_reason",
    "share_counts",
    "explored_rows",
]


def slowest_part(parts: Mapping, main: Mapping) -> tuple[str | None, Mapping]:
    """The undecided part that needs the most runs (one no practical number of runs decides first), with its
    name where it is not ``main`` (the part whose value the sentence shows): the claim is decided only when every
    part is."""
    opened = [(n, p) for n, p in parts.items() if isinstance(p, Mapping) and p.get("runs_to_decide")]
    if not opened:
        return None, main
    name, part = max(opened, key=lambda np: np[1]["runs_to_decide"].get("replicates") or math.inf)
    return (None if part is main else name), part


def runs_sentence(part: Mapping, name: str | None = None) -> str:
    """How many replicates would decide the claim, said of part ``name`` where that is not the part shown."""
    r = part.get("runs_to_decide") or {}
    if not r:
        return ""
    it = f"its part {part_name(name)}" if name else "it"
    if r.get("replicates"):
        cap = re.search(r"beyond the cap of (\d+)", str(r.get("text") or ""))
        beyond = f", more than the {cap.group(1)} this run allows" if cap else ""
        return f"About {r['replicates']} independent replicates are projected to decide {it}{beyond}."
    return f"No practical number of runs is projected to decide {it}."


def lock_sentence(claim: Mapping, part: Mapping) -> str:
    """Runs that lost lock, where the record says they carry the verdict: how many, and the verdict without them
    (never "decide", which an undecided claim's sentence uses for the runs that would decide it)."""
    record = claim.get("robustness") or {}
    lost = next((s.get("decided_by_lost_runs") for s in (part, record, claim) if "decided_by_lost_runs" in s), None)
    if not lost:
        return ""
    in_lock = next((s.get("in_lock_verdict") for s in (part, record, claim) if s.get("in_lock_verdict")), None)
    share = next((s.get("lost_share") for s in (part, record, claim) if isinstance(s.get("lost_share"), Mapping)), {})
    if {"lost", "runs"} <= set(share):
        lead = f"{lost_lead(share, '{k} of {n} runs')} lost lock and {'carries' if share['lost'] == 1 else 'carry'}"
        lead += " this verdict"  # the default's: the sentence comes before any flip
    else:
        lead = "Runs that lost lock carry this verdict"
    return lead + (f": over {lost_basis(share)}runs in lock alone it is {in_lock}." if in_lock else ".")


def lost_lead(lost: Mapping, counts: str) -> str:
    """``counts`` (a template of ``{k}`` lost of ``{n}`` runs), said as a count over the draws of ``replicates``
    replicates where the record says so (the pooled verdict then rests on more)."""
    k, n, reps = lost["lost"], lost["runs"], lost.get("replicates")
    if not reps:
        return counts.format(k=k, n=n)[:1].upper() + counts.format(k=k, n=n)[1:]
    where = "one replicate" if reps == 1 else f"{reps} replicates"
    text = counts.replace(" of {n} runs", " of its {n} runs" if reps == 1 else " of their {n} runs")
    return f"In {where}, " + text.format(k=k, n=n)


def lost_basis(lost: Mapping) -> str:
    """Whose runs in lock: that replicate's where the count is over a stated number of replicates, else "the"."""
    reps = lost.get("replicates")
    return "the " if not reps else "that replicate's " if reps == 1 else "those replicates' "


def thin_share(parts: Mapping) -> tuple[str, Mapping] | None:
    """The robust part whose explored configurations mostly stayed undecided (more undecided than agreeing; the
    fewest agreeing first), with its name: its label rests on few decided configurations, so its share is said
    with it. ``None`` where every robust part's agreeing configurations outnumber its undecided ones."""
    thin = [
        (n, p)
        for n, p in parts.items()
        if isinstance(p, Mapping)
        and p.get("label") == "robust"
        and int((p.get("share") or {}).get("undecided") or 0) > int((p.get("share") or {}).get("agree") or 0)
    ]
    return min(thin, key=lambda np: int(np[1]["share"]["agree"])) if thin else None


_CODE = re.compile(r"\([^()]*\b[a-z]\w*\.[a-z_]\w*\b[^()]*\)|\([^()]*\w\(\)[^()]*\)")


def plain_text(text: str) -> str:
    """Text without the parentheses that name code (``(..., calibration.calibrate_bandwidth)``)."""
    return " ".join(_CODE.sub("", text).split()).replace(" :", ":").replace(" ,", ",")


def part_name(name: object) -> str:
    """A rule part's name as a sentence says it: ``no_loss`` -> ``no loss`` (a name written for the code); a
    name with symbols (``psi_A=5, P=0.5``, a subscripted ``x_r``) as it is."""
    text = str(name)
    return text.replace("_", " ") if re.fullmatch(r"[a-z]{2,}(?:_[a-z]{2,})+", text) else text  # psi_A=5, x_r stay


def not_checkable_reason(claim: Mapping) -> str:
    """Why a claim cannot be checked, in one sentence: the first clause of the rule's reason or of the note,
    whichever says more."""
    firsts = []
    for text in (claim.get("rule") or {}).get("reason"), claim.get("note"):
        text = plain_text(str(text or "").strip())
        first = re.split(r"(?<=;)\s+|(?<=\.)\s+(?=[A-Z])", text)[0].rstrip(".;") if text else ""
        firsts.append(first)
    reason = max(firsts, key=len) or "nothing measurable"
    return reason[:1].lower() + reason[1:] if reason[1:2].islower() else reason  # after a colon: "In this" -> "in this"


def explored_rows(robustness: Mapping) -> list[Mapping]:
    """The distinct configurations a claim's design explored at the paper's operating point, as its record's
    condition rows: one at a time and the joint samples, each configuration once (the set the label's coverage
    counts; not the pinned known flips nor the combinations searched to name a flip, nor a configuration outside
    the operating point, which is counted beside the label)."""
    out, seen = [], set()
    for r in (robustness or {}).get("conditions") or ():
        key = tuple(sorted((str(k), repr(v)) for k, v in (r.get("changed") or {}).items()))
        explored = r.get("kind", "single") in ("single", "joint") and not r.get("off_operating_point")
        if explored and key and key not in seen:
            seen.add(key)
            out.append(r)
    return out


def share_counts(share: Mapping) -> str:
    """``"41 agree, 3 flip and 6 stay undecided of 50 explored configurations"``: the share over every explored
    configuration, never of the decided ones only (an older record without ``flip``: agree of decided, as it
    counted, said as such; one without ``decided`` either: agree of its design); empty without a share."""
    if not share or share.get("design", share.get("decided")) in (None, 0):
        return ""
    if "flip" not in share:
        if share.get("decided") is None:
            return f"{share.get('agree')} of {share['design']} explored configurations agree"
        return (
            f"{share.get('agree')} of the {share['decided']} decided configurations agree (this older record does "
            "not count the undecided ones)"
        )
    agree, flip, undecided = int(share["agree"]), int(share["flip"]), int(share.get("undecided", 0))
    design = int(share.get("design", agree + flip + undecided))
    left = int(share.get("left_by_budget") or 0)
    lean = "leans towards agreement but was" if left == 1 else "lean towards agreement but were"
    why = f" ({left} of them {lean} given fewer runs than the default: a cap limits the runs"
    why += " spent confirming agreement)"
    return (
        f"{agree} agree{'s' * (agree == 1)}, {flip} flip{'s' * (flip == 1)} and {undecided} "
        f"stay{'s' * (undecided == 1)} undecided{why if left else ''} of {design} explored "
        f"configuration{'s' * (design != 1)}{_pinned_counts(share.get('pinned'))}"
        f"{_beside(share.get('combinations'), 'combination{s} of entries searched inside flipping joint ones')}"
        f"{_off_point_counts(share.get('off_operating_point'))}"
    )


def _off_point_counts(off: Mapping | None) -> str:
    """``"; of 4 configurations outside the paper's operating point (counted beside the label, not in it), 2 flip,
    2 agree and 0 stay undecided"``; empty without such configurations."""
    return _beside(off, "configuration{s} outside the paper's operating point (counted beside the label, not in it)")


def _pinned_counts(pinned: Mapping | None) -> str:
    """``"; of 2 pinned configurations measured beside them (joint configurations every run measures), 1 flips,
    1 agrees and 0 stay undecided"``; empty without pinned configurations."""
    return _beside(pinned, "pinned configuration{s} measured beside them (joint configurations every run measures)")


def _beside(counts: Mapping | None, what: str) -> str:
    """``"; of N <what>, F flip(s), A agree(s) and U stay(s) undecided"`` (``{s}`` in ``what`` agrees with N)."""
    if not counts:
        return ""
    agree, flip, undecided = (int(counts.get(k) or 0) for k in ("agree", "flip", "undecided"))
    n = agree + flip + undecided
    return (
        f"; of {n} {what.format(s='s' * (n != 1))}, {flip} flip{'s' * (flip == 1)}, {agree} agree{'s' * (agree == 1)} "
        f"and {undecided} stay{'s' * (undecided == 1)} undecided"
    )


def parts_by_name(record: Mapping) -> dict[str, Mapping]:
    """A claim record's ``robustness`` parts by name (``{}`` where it has none); an older record's list of parts, each
    with its ``name``, read as the same mapping."""
    parts = (record or {}).get("parts") or {}
    if isinstance(parts, list):
        parts = {p.get("name", str(i)): p for i, p in enumerate(parts) if isinstance(p, Mapping)}
    return {str(n): p for n, p in parts.items() if isinstance(p, Mapping)}
