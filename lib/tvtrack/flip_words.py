"""How a named flip's kind is said: the first screen's bracket beside each claim that holds (what flips it, and
which other kinds also do), and a flip of several changes of different kinds with each change's own kind (a
reading and a setting together are never filed under the setting alone; a combination no smaller subset isolates
is "a combination", "with a world" only where one of its entries is a world); and, for each paper's paragraph, the
change under which a claim that fails would hold (:func:`why_not_clause`) and the one under which a claim that
holds would not (:func:`turns_on_sentence`), the flip its summary names."""

from __future__ import annotations

from typing import Mapping

from .run_words import explored_rows
from .value_words import rule_in_force, value_clause
from .wording import (
    claim_flips,
    claim_verdict_at,
    differs_whatever_is_open,
    kinds_of_changes,
    main_part,
    moves_verdict,
    named_flips,
    register_phrases,
    side_words,
    summary_strength,
)

__all__ = [
    "flip_kinds",
    "label_basis",
    "mixed_kinds",
    "flip_with_kind",
    "under_words",
    "why_not_clause",
    "turns_on_sentence",
]

_COUNT = {2: "two", 3: "three", 4: "four", 5: "five"}


def flip_kinds(flip: Mapping, record: Mapping) -> set[str]:
    """The kinds of the entries a flip changes (``reading``, ``setting``, ``world``; an entry the record's register
    does not know reads as a reading, as the core reads it)."""
    known = register_phrases(record)
    return {known.get(str(k), ("", "reading"))[1] for k in flip.get("changed") or {}}


_SIDE_SHORT = {
    "reading": ("a reading", "readings together"),
    "setting": ("an unprinted setting", "unprinted settings together"),
    "world": ("a world", "worlds together"),
}


def label_basis(claim: Mapping) -> str:
    """What flips a claim, in a few words for a list: the kind of the flip its sentence names
    (:func:`tvtrack.wording.summary_strength`), with how many changes it takes; "in a part only" where no flip the
    label rests on changes the whole claim's verdict; "a setting too", "a world too", "a combination too" where a
    setting, a world or a combination no smaller subset isolates also changes the claim's whole verdict
    (:func:`_also`), so the bracket names every kind the first screen's count files the claim under (``""`` for a
    claim no change flips). A combination is named with its entries' kinds (:func:`_combination`)."""
    flips = claim_flips(claim)
    if not flips:
        return ""
    first = min(flips, key=lambda f: summary_strength(claim, f))
    n, kinds, side = len(first.get("changed") or {}), flip_kinds(first, claim.get("robustness") or {}), first["side"]
    if side == "unattributed":
        text = _combination(n, kinds)
    else:
        one, many = _SIDE_SHORT.get(side, ("a world", "worlds together"))
        text = one if n <= 1 else f"{_COUNT.get(n, n)} {many}"
        if side == "setting" and n > 1:  # filed under the setting, as the first screen's count files it
            others = (
                "a reading"
                if n == 2 and kinds == {"setting", "reading"}
                else "one other change"
                if n == 2
                else f"{_COUNT.get(n - 1, n - 1)} other changes"
            )
            text = (
                f"{_COUNT.get(n, n)} unprinted settings together"
                if kinds == {"setting"}
                else f"an unprinted setting with {others}"
            )
    text += " (or fewer: a smaller part of them stays undecided)" if n > 1 and first.get("undecided_subsets") else ""
    text += "" if moves_verdict(claim, first) else ", in a part only"
    return text + "".join(_also(claim, flips, kind, side) for kind in ("setting", "world", "unattributed"))


def _combination(n: int, kinds: set[str]) -> str:
    """A flip no smaller subset isolates, as the first screen counts it (a combination), with its entries' kinds:
    "a combination with a world" only where one of them is a world."""
    if "world" in kinds:
        return "a combination with a world"
    among = ", an unprinted setting among them" if "setting" in kinds else ", all readings"
    return f"a combination of {_COUNT.get(n, n)} changes{among}"


def _also(claim: Mapping, flips: list, kind: str, shown: str) -> str:
    """ "; a setting too" ("; a world too") where a flip of that kind other than the one named changes the whole
    verdict: one change alone, else "; settings with other changes too" ("; worlds together too"); where none of
    that kind changes it but one turns a part so that the decided claim reads undecided there, "; a world leaves it
    undecided" (more runs there would tell whether it flips); where one of that kind flips a part only, "; a world,
    in a part only" (the label counts a part's flip; the first screen's count of what flips verdicts does not)."""
    if shown == kind:
        return ""
    moving = [f for f in flips if f.get("side") == kind and moves_verdict(claim, f)]
    if kind == "unattributed":
        return "; a combination too" if moving else ""
    if not moving:
        opened = claim.get("verdict") != "undecided" and any(  # a part's flip that leaves the whole claim open
            f.get("side") == kind and claim_verdict_at(claim, f.get("changed") or {}) == "undecided" for f in flips
        )
        if opened:
            return f"; a {kind} leaves it undecided"
        return f"; a {kind}, in a part only" if any(f.get("side") == kind for f in flips) else ""
    if any(len(f.get("changed") or {}) <= 1 for f in moving):
        return f"; a {kind} too"
    return "; worlds together too" if kind == "world" else "; a setting with other changes too"


def mixed_kinds(flip: Mapping, record: Mapping) -> str:
    """A flip of several changes of different kinds, each change with its own kind (``"pixels 5 sigma wide (a
    setting the paper never printed) and distances of 3 and 1 pixels (a reading of the paper's text)"``); ``""``
    for one change, changes of one kind, or an entry the record's register does not know."""
    changed = flip.get("changed") or {}
    known = register_phrases(record)
    if len(changed) < 2 or len({known.get(str(k), ("", "reading"))[1] for k in changed}) < 2:
        return ""
    return kinds_of_changes(changed, record)


def under_words(flip: Mapping, record: Mapping) -> str:
    """What a named flip changes, introduced by its kind: one kind for one change, the count and the kind for several
    of one kind ("two worlds beyond the paper together: ..."), each change's own kind for a mix (a reading and a
    setting together are not filed under the setting)."""
    n = len(flip.get("changed") or {})
    mixed = mixed_kinds(flip, record)
    if mixed:
        return f"{_COUNT.get(n, n)} changes together: {mixed}"
    if n > 1 and flip.get("side") == "reading":
        return f"{_COUNT.get(n, n)} other readings of the paper's text together: {flip['text']}"
    if n > 1 and flip.get("side") == "world":
        return f"{_COUNT.get(n, n)} worlds beyond the paper together: {flip['text']}"
    if n > 1 and flip.get("side") == "setting":
        return f"{_COUNT.get(n, n)} settings the paper never printed, together: {flip['text']}"
    return f"{side_words().get(flip['side'], 'another change')}: {flip['text']}"


def flip_with_kind(flip: Mapping, record: Mapping) -> str:
    """A named flip and its kind in plain words, as a record's list of flips shows it: the change, then its kind
    in brackets; a mix of kinds names each change's own kind, so a reading and a setting together are not filed
    under the setting alone.

    Parameters
    ----------
    flip : Mapping
        A named flip (``text``, ``side``, ``changed``), as :func:`tvtrack.wording.claim_flips` lists them.
    record : Mapping
        The claim's robustness record (its ``register`` gives each entry's phrase and kind).
    """
    sides = side_words()
    mixed = mixed_kinds(flip, record)
    if mixed or flip.get("side") == "unattributed":
        return f"{mixed or flip['text']}, together{alone_words(flip)}"
    return f"{flip['text']} ({sides.get(flip['side'], sides['world'])})"


def alone_words(flip: Mapping) -> str:
    """How far a flip no smaller subset isolates is shown not to flip the claim in part: ``" (none of them flips the
    claim alone)"`` where every smaller subset measured was decided, else how many stayed undecided (one of them
    could still flip it alone); ``""`` for a flip that is not of that kind."""
    if flip.get("side") != "unattributed":
        return ""
    k = len(flip.get("undecided_subsets") or ())
    if not k:
        return " (none of them flips the claim alone)"
    sets = "one smaller set of them stays" if k == 1 else f"{_COUNT.get(k, k)} smaller sets of them stay"
    return f" (none of them is shown to flip the claim alone: {sets} undecided)"


def why_not_clause(c: Mapping) -> str:
    """Why a claim does not hold: the value against what the paper says (in words where it reverses the paper's
    direction) and, where one is named, the change under which it would: the flip the claim's summary names
    (:func:`tvtrack.wording.named_flips`), with the whole claim's verdict there and whether only runs that lost lock
    make it."""
    rule, measured = rule_in_force(dict(c.get("rule") or {}), c.get("measured"))
    name = main_part(c)
    if rule.get("kind") == "all_of" and isinstance(measured, Mapping):
        rule, measured = (rule.get("parts") or {}).get(name) or {}, measured.get(name)
    text = value_clause(rule, measured, c.get("paper_value"))
    flips = [f for f in named_flips(c) if f.get("verdict") == "reproduced"]
    if flips:
        f = flips[0]
        whole = claim_verdict_at(c, f.get("changed") or {}) or f["verdict"]  # the claim's, not only its part's
        how = {"reproduced": "it holds", "partly": "it holds in part"}.get(whole, f"it reads {whole}")
        text += f"; {how} under {under_words(f, c.get('robustness') or {})}{_lost_clause(f)}"
    return text


def _lost_clause(flip: Mapping) -> str:
    """``", but in one replicate only through the 5 of its 600 runs that lost lock there"`` where only runs that
    lost lock carry a flip (a count over a stated number of replicates' draws says so: the claim pools more)."""
    lost = flip.get("lost_runs") or {}
    if not lost.get("carried"):
        return ""
    reps = lost.get("replicates")
    where = "" if not reps else "in one replicate " if reps == 1 else f"in {reps} replicates "
    of = "of" if not reps else "of its" if reps == 1 else "of their"
    return f", but {where}only through the {lost['lost']} {of} {lost['runs']} runs that lost lock there"


_DECIDED = ("reproduced", "partly", "not reproduced")


def turns_on_sentence(c: Mapping) -> str:
    """What would change a claim that holds (or holds in part), in one sentence: of the flips under which the whole
    claim's verdict is decided and differs from its own, the strongest (:func:`tvtrack.wording.summary_strength`: the
    flip the claim's summary names wherever that one changes the whole verdict), with that verdict, whether only runs that lost lock carry it, how many other smallest changes
    (named flips) change the whole verdict too, and in how many of the design's explored configurations it changes, or
    is left undecided but cannot come out as at the default (:func:`whole_flips`); ``""`` where no explored change does (a flip of a part only is not counted)."""

    def whole(f: Mapping) -> str | None:
        return claim_verdict_at(c, f.get("changed") or {}) or f.get("verdict")

    turning = [f for f in claim_flips(c) if whole(f) in _DECIDED and whole(f) != c.get("verdict")]
    if not turning:
        return ""
    texts = {f["text"] for f in turning}
    f = min(turning, key=lambda g: summary_strength(c, g))  # the summary's own flip wherever that one turns it
    how = {"reproduced": "holds", "partly": "holds only in part", "not reproduced": "does not hold"}[whole(f)]
    more = len(texts) - 1
    others = (
        f"{more} other smallest change{'s' if more > 1 else ''} flip{'s' if more == 1 else ''} it too; " if more else ""
    )
    flipped, explored, open_ = whole_flips(c)
    more = f", and in {open_} more it is undecided but cannot come out as at the default" if open_ else ""
    counted = f" ({others}its verdict changes in {flipped} of {explored} explored configurations{more})"
    counted = counted if explored else ""
    return f"{c['id']} {how} under {under_words(f, c.get('robustness') or {})}{_lost_clause(f)}{counted}."


def whole_flips(c: Mapping) -> tuple[int, int, int]:
    """``(changed, explored, open)``: of the distinct configurations the claim's design explored at the paper's
    operating point (:func:`tvtrack.run_words.explored_rows`: the set its label's coverage counts), how many decide the
    whole claim's verdict otherwise than the default does, how many there are, and how many more leave it undecided
    though it cannot come out as at the default whatever its undecided parts turn out
    (:func:`tvtrack.wording.differs_whatever_is_open`); at a size the default's sizing asks for (an undersized
    configuration changes nothing)."""
    rows = [r for r in explored_rows(c.get("robustness") or {}) if "undersized" not in r]
    default = ((c.get("robustness") or {}).get("parts") or {}).keys()

    def known(r: Mapping) -> bool:  # the row's parts and the default's: the open ones can be tried
        return isinstance(r.get("parts"), Mapping) and bool(default) and set(r["parts"]) == set(default)

    decided = [r for r in rows if r.get("verdict") in _DECIDED and c.get("verdict") in _DECIDED]
    changed = sum(r["verdict"] != c.get("verdict") for r in decided)
    open_ = sum(r not in decided and known(r) and differs_whatever_is_open(c, r) for r in rows)
    return changed, len(explored_rows(c.get("robustness") or {})), open_
