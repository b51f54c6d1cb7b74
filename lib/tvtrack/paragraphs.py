"""Paragraphs in plain words from claim records (``results.json``): one for a set of runs (the first screen of the
report, the README and the site) and one per paper (what it claims, what holds, what does not and why, then its
limitations).

Everything here reads the JSON dicts a run writes and the sentences of :mod:`tvtrack.wording`, so every place
says the same thing in the same words. Import :func:`results_summary` through :mod:`tvtrack.results`.
"""

from __future__ import annotations

import re
from collections import Counter
from typing import Mapping

from .wording import (
    PROVISIONAL,
    SIDE_ORDER,
    claim_fields,
    register_phrases,
    at_profile,
    claim_flips,
    claim_verdict_at,
    differs_whatever_is_open,
    moves_verdict,
    shown_label,
    side_words,
)
from .flip_words import flip_kinds, turns_on_sentence, why_not_clause
from .run_words import not_checkable_reason, thin_share

__all__ = ["results_summary", "turns_on", "paper_paragraph", "limitations", "label_words", "label_verdict"]


def _plural(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"


def _n(k: int, one: str, many: str) -> str:
    return f"{k} {one if k == 1 else many}"


def _join(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def _paper_of(claim_id: str) -> str:
    """The notebook number of a claim id (``"C000-6"`` -> ``"000"``), ``""`` for another form."""
    m = re.match(r"C(\d+)-", str(claim_id))
    return m.group(1) if m else ""


def turns_on(claims: list[Mapping]) -> dict[str, tuple[int, list[tuple[str, str, int]]]]:
    """``{side: (claims, [(entry title, paper, claims), ...] most often first)}``: how many claims a reading of the
    paper's text, an unreported setting of its experiment, a world beyond it (or several changes together) flips,
    and the register entries (each of one paper's register, named with the paper's number) that flip the most of
    them, every entry tied with the first kept. A claim counts once per side; every named flip that changes the
    whole claim's verdict counts (:func:`tvtrack.wording.moves_verdict`: one that moves only a part is counted by
    :func:`part_only`; a joint configuration is named only where no subset of it flips alone, so it is the smallest
    found)."""
    count: dict[str, int] = Counter()
    titles: dict[str, Counter] = {s: Counter() for s in SIDE_ORDER}
    for c in claims:
        c = claim_fields(c)
        if c.get("verdict") == "not checkable":
            continue
        known = register_phrases(c.get("robustness") or {})
        paper = _paper_of(c.get("id", ""))
        seen_sides, seen_titles = set(), set()
        for f in _whole_flips(c):
            side = f["side"] if f["side"] in SIDE_ORDER else "world"
            seen_sides.add(side)
            for k in f.get("changed") or {}:
                title = known.get(str(k), (str(k).replace("_", " "), "", {}))[0]
                if (side, title) not in seen_titles:
                    seen_titles.add((side, title))
                    titles[side][(title, paper)] += 1
        for s in seen_sides:
            count[s] += 1
    out = {}
    for s in SIDE_ORDER:
        if count[s]:
            ranked = titles[s].most_common()
            top = [(t, p, n) for (t, p), n in ranked if n == ranked[0][1]] if ranked else []
            out[s] = (count[s], top[:3] if len(top) > 1 else [(t, p, n) for (t, p), n in ranked[:2]])
    return out


def turns_by_paper(claims: list[Mapping]) -> dict[str, Counter]:
    """``{side: Counter(paper: claims)}``: how many claims of each paper a change of each side flips (as
    :func:`turns_on` counts them), so that the kind that dominates one paper is not hidden by the totals."""
    out: dict[str, Counter] = {s: Counter() for s in SIDE_ORDER}
    for c in claims:
        c = claim_fields(c)
        if c.get("verdict") == "not checkable":
            continue
        for side in {f["side"] if f["side"] in SIDE_ORDER else "world" for f in _whole_flips(c)}:
            out[side][_paper_of(c.get("id", ""))] += 1
    return out


def _whole_changes(claim: Mapping) -> list[dict]:
    """The changes of the claim's sized conditions whose whole verdict is decided (reproduced, partly, not
    reproduced) and not the claim's, whatever its parts undecided at the default turn out to be
    (:func:`tvtrack.wording.differs_whatever_is_open`)."""
    rows = (claim.get("robustness") or {}).get("conditions") or ()
    decided = ("reproduced", "partly", "not reproduced")
    return [
        dict(c.get("changed") or {})
        for c in rows
        if "undersized" not in c
        and not c.get("off_operating_point")  # counted beside the label: it explains no change of the verdict
        and c.get("verdict") in decided
        and differs_whatever_is_open(claim, c)
    ]


def _whole_flips(claim: Mapping) -> list[dict]:
    """The claim's named flips that change its whole verdict (not only one part's): alone
    (:func:`tvtrack.wording.moves_verdict`), or together with other named flips of the same side, where a condition
    made of their changes alone changes it (each part's flip named by its own entry, the joint configuration not
    named; flips of several sides that change it only together are counted under none)."""
    claim = claim_fields(claim)
    flips = claim_flips(claim)
    out = [f for f in flips if moves_verdict(claim, f)]
    for ch in _whole_changes(claim):
        inside = [f for f in flips if f["changed"].items() <= ch.items()]
        one_side = len({f["side"] if f["side"] in SIDE_ORDER else "world" for f in inside}) == 1
        if one_side and {k for f in inside for k in f["changed"]} == set(ch):
            out += [f for f in inside if f not in out]
    return out


def part_only(claims: list[Mapping]) -> int:
    """How many checkable claims have named flips, none of which changes the whole claim's verdict alone or with
    others (:func:`_whole_flips`), and no sized condition that changes it (each flip moves only a part, the
    claim's verdict staying as it is under every change explored)."""
    return len(_part_only_ids(claims))


def _part_only_ids(claims: list[Mapping]) -> list[str]:
    out = []
    for c in claims:
        c = claim_fields(c)
        if c.get("verdict") != "not checkable" and claim_flips(c) and not _whole_flips(c) and not _whole_changes(c):
            out.append(str(c.get("id", "")))
    return out


def _ids(ids: list[str]) -> str:
    """`` (C000-8)``: a few claim ids in brackets, for a count a reader wants to look up (none beyond three)."""
    ids = [i for i in ids if i]
    return f" ({_join(ids)})" if 0 < len(ids) <= 3 else ""


#: Each side as the first screen's count of what the verdicts turn on says it: a side holds combinations too.
_TURN_WORDS = {
    "reading": "a reading of the paper's text (alone or with other readings)",
    "setting": "a setting of the paper's own experiment that the paper never printed (alone or with readings or "
    "other settings)",
    "world": "a world beyond the paper (alone or with other worlds)",
    "unattributed": "a combination that no smaller subset explains (a reading or setting with a world, or more "
    "changes than the search tried; no smaller set of them was found to flip it)",
}


def _turns_sentence(claims: list[Mapping]) -> str:
    words = {**side_words(), **_TURN_WORDS}
    per_paper = turns_by_paper(claims)
    bits = []
    for side, (n, top) in turns_on(claims).items():
        best = [(t, p, k) for t, p, k in top if k == top[0][2]] if top else []
        named = [f"“{t}” ({_plural(k, 'claim')}{f' of {p}' if p else ''})" for t, p, k in best]
        often = f", most often {_join(named)}" if best and best[0][2] > 1 else ""
        papers = sorted(per_paper[side].items())
        split = (
            f" ({_join([f'{k} of {p}' for p, k in papers])})" if len(papers) > 1 and all(p for p, _ in papers) else ""
        )
        bits.append(f"{words[side]} flips {_plural(n, 'claim')}{split}{often}")
    only = _part_only_ids(claims)
    if only:
        stays = all(_stays(c) for c in claims if str(claim_fields(c).get("id", "")) in only)
        its = "its" if len(only) == 1 else "their"
        why = f"{'it is' if len(only) == 1 else 'they are'} undecided, or undecided there"
        bits.append(
            f"{_n(len(only), 'claim', 'claims')}{_ids(only)} {'moves' if len(only) == 1 else 'move'} only in a part "
            "under every change explored "
            + (
                f"(the whole verdict stays{' as it is' if len(only) == 1 else ''})"
                if stays
                else f"({its} whole verdict is not shown to move: {why})"
            )
        )
    return f"What the verdicts turn on: {'; '.join(bits)}." if bits else ""


def _stays(claim: Mapping) -> bool:
    """Whether a claim's whole verdict is decided and reads the same under every one of its named flips (a claim
    undecided at the default, or under a flip, may still move as its open parts turn out)."""
    claim = claim_fields(claim)
    here = claim.get("verdict")
    return here != "undecided" and all(claim_verdict_at(claim, f["changed"]) == here for f in claim_flips(claim))


def depends_only_with_a_world(claims: list[Mapping]) -> int:
    """How many claims labelled ``depends`` rest only on combinations that mix a reading or a setting with a world
    beyond the paper, none of whose changes flips the claim alone (no reading or setting flips them alone)."""
    return len(_only_with_a_world_ids(claims))


def _only_with_a_world_ids(claims: list[Mapping]) -> list[str]:
    out = []
    for c in claims:
        c = claim_fields(c)
        if shown_label(c) != "depends" or c.get("verdict") == "not checkable":
            continue
        flips, record = claim_flips(c), c.get("robustness") or {}
        if flips and all("world" in flip_kinds(f, record) for f in flips):  # a combination too large to search
            out.append(str(c.get("id", "")))  # need not hold a world: its entries say
    return out


def depends_also_on_a_world(claims: list[Mapping]) -> int:
    """How many claims labelled ``depends`` a world beyond the paper also flips alone (a named world flip that
    changes the whole claim's verdict): the label names the reading or setting, and this counts what it hides."""
    return len(_also_world_ids(claims))


def _also_world_ids(claims: list[Mapping]) -> list[str]:
    out = []
    for c in claims:
        c = claim_fields(c)
        if shown_label(c) == "depends" and c.get("verdict") != "not checkable":
            out += [str(c.get("id", ""))] if any(f["side"] == "world" for f in _whole_flips(c)) else []
    return out


#: How the claims that survive every reading are split by verdict (the first screen's count says which hold).
_SURVIVING = (
    ("reproduced", "holds", "hold"),
    ("partly", "holds in part", "hold in part"),
    ("not reproduced", "does not hold", "do not hold"),
    ("undecided", "is undecided", "are undecided"),
)


_ALL = {key: many for key, _, many in _SURVIVING}


def _surviving_split(claims: list[Mapping]) -> str:
    """``"of them 4 hold, 2 do not hold and 1 is undecided"`` (``"it holds"`` for one): the verdicts of the claims
    labelled robust or limited (those that survive every reading of the paper), so that a reader does not take
    surviving for holding."""
    v = Counter(str(c.get("verdict")) for c in claims if shown_label(c) in _PARTIAL_SCOPE)
    if sum(v.values()) == 1:
        return "it " + next(one for key, one, _ in _SURVIVING if v[key])
    if len(+v) == 1:  # one verdict for all of them
        return {"not reproduced": "none of them holds"}.get(next(iter(v)), "all " + _ALL.get(next(iter(v)), ""))
    return ("of them " + _join([_n(v[key], one, many) for key, one, many in _SURVIVING if v[key]])) if v else ""


_PARTIAL_SCOPE = ("robust", "limited")  # labels that say the verdict holds: of an undecided one, its decided parts


def label_verdict(claim: Mapping) -> str:
    """The verdict a claim's label is scoped by (:func:`label_words`): ``undecided`` where the claim or any of its
    parts is undecided (its label then speaks for its decided parts only), else the claim's verdict."""
    claim = claim_fields(claim)  # a Claim object or its record
    parts = (claim.get("robustness") or {}).get("parts") or {}
    parts = parts.values() if isinstance(parts, Mapping) else parts
    open_ = any(isinstance(p, Mapping) and p.get("verdict") == "undecided" for p in parts)
    return "undecided" if open_ else str(claim.get("verdict"))


def label_words(verdict: str, label: str) -> str:
    """A claim's label as its line shows it: ``"robust in its decided parts only"`` for an undecided verdict
    labelled robust or limited (the label speaks for the parts the default decides; a change may still move the
    undecided one), else the label as it is."""
    return f"{label} in its decided parts only" if verdict == "undecided" and label in _PARTIAL_SCOPE else label


def _sure_sentence(
    labels: Counter,
    checkable: int,
    with_world: int | list = 0,
    also_world: int = 0,
    partial: list = (),
    thin: list = (),
    split: str = "",
    both: list = (),
) -> str:
    """How sure the checkable verdicts are, by label; the counts add up to ``checkable`` (a verdict that decides no
    part, or has no record, carries no label and is counted so); ``with_world`` of the ``depends`` ones turn only
    on a reading or setting together with a world (:func:`depends_only_with_a_world`), and a world alone also
    changes ``also_world`` of them (:func:`depends_also_on_a_world`); ``partial`` names the undecided claims among
    those that survive (a claim that holds in part with a part undecided as ``(id, "open")``), labelled by their
    decided parts only (:func:`label_words`), and ``thin`` the robust ones
    most of whose explored configurations stayed undecided (:func:`tvtrack.run_words.thin_share`); ``split`` says
    the surviving verdicts by verdict (:func:`_surviving_split`) and ``both`` names the ``with_world`` claims that a
    world alone also flips (counted in both groups, and said so)."""
    sure = labels["robust"] + labels["limited"]
    ids = [i if isinstance(i, str) else i[0] for i in partial]  # (id, "open"): it holds in part, a part undecided
    how = "undecided" if all(isinstance(i, str) for i in partial) else "with a part undecided"
    part = f"; {len(partial)} of them{_ids(ids)} {how}, labelled by " if partial else ""
    part += f"{'its' if len(partial) == 1 else 'their'} decided parts only" if partial else ""
    part += f"; for {len(thin)}{_ids(list(thin))} most explored configurations stayed undecided" if thin else ""
    notes = [f"for {also_world} of them worlds beyond the paper (one or several), with no reading or setting changed, "
             "also flip the verdict"]  # fmt: skip
    notes = notes if also_world else []
    named = _ids(with_world) if isinstance(with_world, list) else ""
    with_world = len(with_world) if isinstance(with_world, list) else with_world
    among = f" ({_join(list(both))} {'is' if len(both) == 1 else 'are'} also among the {also_world})" if both else ""
    notes += (
        [f"{with_world}{'' if notes else ' of them'}{named} only together with a world beyond it{among}"]
        if with_world
        else []
    )
    return (
        _counts_sentence(labels, checkable)
        + _survive_sentence(sure, labels, split, part)
        + _world_sentence(labels["depends"], notes)
    )


def _counts_sentence(labels: Counter, checkable: int) -> str:
    """The checkable verdicts by how sure they are, in one sentence whose counts add up to ``checkable``."""
    sure, unexplored, bare = labels["robust"] + labels["limited"], labels["unexplored"], labels["—"]
    small = labels[PROVISIONAL]
    return (
        f"Of the {checkable} checkable verdicts, {_n(sure, 'survives', 'survive')} every reading of the paper, "
        f"{_n(labels['depends'], 'turns', 'turn')} on a reading of an ambiguous passage or a setting the paper "
        "never printed, "
        + (
            f"{_n(unexplored, 'has', 'have')} nothing explored to show how far "
            f"{'it extends' if unexplored == 1 else 'they extend'} (unexplored), "
            if unexplored
            else ""
        )
        + (
            f"{_n(bare, 'has', 'have')} no label (no part of {'it' if bare == 1 else 'them'} decided, or no record "
            "of what was explored), "
            if bare
            else ""
        )
        + (
            f"{_n(small, 'comes', 'come')} from a design too small to label (provisional: never called robust), "
            if small
            else ""
        )
        + f"and {_n(labels['unstable'], 'differs', 'differ')} between independent replicates."
    )


def _survive_sentence(sure: int, labels: Counter, split: str, part: str) -> str:
    """What the verdicts that survive every reading say, and how they are labelled (``""`` for none)."""
    if not sure:
        return ""
    split = split.removeprefix("of them ")
    who = "The one that survives every reading" if sure == 1 else f"The {sure} that survive every reading"
    return (
        f" {who}: {f'{split}; ' if split else ''}{labels['robust']} robust, {labels['limited']} limited (holding "
        f"only within the paper's world){part}."
    )


def _world_sentence(depends: int, notes: list[str]) -> str:
    """Which of the verdicts that turn on a reading or setting a world also flips (``""`` for none)."""
    if not notes:
        return ""
    return f" Of the {depends} that turn on a reading or setting, {', and '.join(notes)}."


def results_summary(claims: list[Mapping], profile: str = "paper") -> str:
    """A short paragraph: what holds, what does not, what the runs could not decide, how sure the verdicts are,
    and what they turn on by kind (readings of the paper's text, unreported settings of its experiment, worlds
    beyond it, each with the register title that flips the most claims); runs of another ``profile`` than
    ``"paper"`` are said not to be the paper-scale numbers, and none of their verdicts is called robust."""
    if not claims:
        return "No claim has been checked yet."
    claims = at_profile(claims, profile)
    v = Counter(str(c.get("verdict")) for c in claims)
    labels = Counter(shown_label(c) for c in claims if c.get("verdict") != "not checkable")
    checkable = len(claims) - v["not checkable"]
    text = [
        f"Of {_plural(len(claims), 'claim')} checked, {_n(v['reproduced'], 'holds', 'hold')}, "
        f"{_n(v['partly'], 'holds', 'hold')} in part and {_n(v['not reproduced'], 'does', 'do')} not; the runs could "
        f"not decide {v['undecided']}, and {_n(v['not checkable'], 'gives', 'give')} nothing to measure."
    ]
    if profile != "paper":  # a smoke-size run: every label provisional (at the paper profile, counted beside them)
        text.append(
            f"{_n(labels[PROVISIONAL], 'of the checkable verdicts comes', 'of the checkable verdicts come')} from a "
            f"design too small to label{' (a smoke-size run)' if profile != 'paper' else ''}: none of them is called "
            "robust."
        )
    else:
        scoped = [c for c in claims if label_words(label_verdict(c), shown_label(c)) != shown_label(c)]
        partial = [c["id"] if c.get("verdict") == "undecided" else (c["id"], "open") for c in scoped]
        with_world, also_world = _only_with_a_world_ids(claims), _also_world_ids(claims)
        thin = [c["id"] for c in claims if shown_label(c) == "robust" and _thin(c)]
        both = [i for i in with_world if i in also_world]
        split = _surviving_split([c for c in claims if c.get("verdict") != "not checkable"])
        text.append(_sure_sentence(labels, checkable, with_world, len(also_world), partial, thin, split, both))
    if profile != "paper":
        text.append(f"These are {profile}-profile runs, not the paper-scale numbers.")
    turns = _turns_sentence(claims)  # a paragraph of its own: the counts first, what they turn on after
    return " ".join(text) + (f"\n\n{turns}" if turns else "")


# --- one paragraph per paper -------------------------------------------------------------------------------------


def _statement(c: Mapping) -> str:
    return " ".join(str(c.get("statement") or "").split()).rstrip(".")


def limitations(data: Mapping, profile: str = "paper") -> list[str]:
    """What a reader should know before trusting a paper's verdicts, one sentence each, from its records: the
    limitations the notebook wrote down (``results.json`` ``limitations``), the simulated worlds calibrated to
    the paper's own operating point, the claims that are not checkable and why, those never tried beyond the
    paper's world, the undecided ones, runs that lost lock, and a smoke-size profile."""
    claims = at_profile(list(data.get("claims") or []), profile)
    out = [" ".join(str(t).split()).rstrip(".") + "." for t in data.get("limitations") or [] if str(t).strip()]
    register = list(data.get("register") or []) + [
        e for c in claims for e in ((c.get("robustness") or {}).get("register") or [])
    ]
    calibrated = sorted(
        {
            str(e.get("title") or e.get("name"))
            for e in register
            if isinstance(e, Mapping)
            and "calibrat" in (str(e.get("why")) + " ".join(map(str, (e.get("phrases") or {}).values())))
        }
    )
    if calibrated:
        out.append(
            f"The simulated world is calibrated to the paper's own operating point ({_join(calibrated)}): agreement "
            "at that point is partly by construction."
        )
    for c in claims:
        if c.get("verdict") == "not checkable":
            out.append(f"{c['id']} is not checkable: {not_checkable_reason(c)}.")
    labels = Counter(shown_label(c) for c in claims if c.get("verdict") != "not checkable")
    unexplored = [  # an undecided claim's limitation is the runs that would decide it (below)
        c["id"]
        for c in claims
        if c.get("verdict") not in ("not checkable", "undecided") and shown_label(c) == "unexplored"
    ]
    if unexplored:
        one = len(unexplored) == 1
        out.append(
            f"Nothing explored shows how far {_join(unexplored)} {'extends' if one else 'extend'}: no world beyond "
            f"the paper was varied for {'it' if one else 'them'}, or too little of what was explored was decided (the claim's "
            "sentence says which)."
        )
    undecided = [c["id"] for c in claims if c.get("verdict") == "undecided"]
    if undecided:
        out.append(f"More runs than these would be needed to decide {_join(undecided)}.")
    lost = [c["id"] for c in claims if _lost(c)]
    if lost:
        basis = _counted_over([s.get("lost_share") for c in claims for s in _spots(c) if s.get("decided_by_lost_runs")])
        out.append(
            f"Runs that lost lock carry the verdict of {_join(lost)}: over the runs in lock alone it differs{basis}."
        )
    carried = [c["id"] for c in claims if _carried_flips(c)]
    if carried:
        basis = _counted_over([f["lost_runs"] for c in claims for f in _carried_flips(c)])
        out.append(
            f"Runs that lost lock carry flips of {_join(carried)}: over the runs in lock alone those changes do not "
            f"flip the verdict{basis}."
        )
    shares = {c["id"]: _lost_share(c) for c in claims if c["id"] not in lost}
    shares = {k: v for k, v in shares.items() if v > 0}
    if shares:
        out.append(
            f"Some runs lost lock in {_join(sorted(shares))} (at most {max(shares.values()) * 100:.2g} % of them)."
        )
    if profile != "paper":
        out.append(f"These are {profile}-size runs: no verdict is labelled, and none is called robust.")
    elif labels[PROVISIONAL]:
        out.append(
            f"{_n(labels[PROVISIONAL], 'claim comes', 'claims come')} from a design too small to label: none is "
            "called robust."
        )
    return out


def _spots(c: Mapping) -> list[Mapping]:
    """Where a claim's record may count runs that lost lock: the claim, its record, each of its parts."""
    record = c.get("robustness") or {}
    return [c, record, *[p for p in (record.get("parts") or {}).values() if isinstance(p, Mapping)]]


def _lost(c: Mapping) -> bool:
    return any(s.get("decided_by_lost_runs") for s in _spots(c))


def _lost_share(c: Mapping) -> float:
    """The largest share of runs that lost lock the record gives (``lost_share``), 0 where it gives none."""
    shares = [s.get("lost_share") for s in _spots(c)]
    values = [
        float(v["value"] if isinstance(v, Mapping) else v) for v in shares if isinstance(v, (int, float, Mapping))
    ]
    return max(values, default=0.0)


def _carried_flips(c: Mapping) -> list[Mapping]:
    """The named flips of the claim that the runs that lost lock under them carry (their record's ``lost_runs``,
    :func:`tvtrack.lost_labels.mark_lost_runs`); empty where none is."""
    parts = ((c.get("robustness") or {}).get("parts") or {}).values()
    flips = [f for p in parts if isinstance(p, Mapping) for f in p.get("flips") or ()]
    return [f for f in flips if (f.get("lost_runs") or {}).get("carried")]


def _counted_over(counts: list) -> str:
    """`` (counted over one replicate's draws)`` where every count of lost runs behind a limitation says it is of
    the same stated number of replicates (the claims' verdicts pool more); empty otherwise."""
    reps = {c.get("replicates") if isinstance(c, Mapping) else None for c in counts}
    if len(reps) != 1 or None in reps:
        return ""
    (n,) = reps
    what = "one replicate's" if n == 1 else f"{n} replicates'"
    return f" (counted over {what} draws)"


def paper_paragraph(data: Mapping, profile: str = "paper") -> tuple[str, list[str]]:
    """One paper in plain words: ``(paragraph, limitations)``. The paragraph says how many claims the paper makes
    and how many can be checked, which hold (and how many of those robustly), which hold in part, what would change
    each of those (:func:`tvtrack.flip_words.turns_on_sentence`), which do not and why (the paper's words, then the notebook's reason or the value against the paper's), and which the runs
    could not decide; the limitations are :func:`limitations`."""
    claims = at_profile(list(data.get("claims") or []), profile)
    if not claims:
        return "No claim of this paper has been checked yet.", limitations(data, profile)
    by = {v: [c for c in claims if c.get("verdict") == v] for v in ("reproduced", "partly", "not reproduced")}
    checkable = [c for c in claims if c.get("verdict") != "not checkable"]
    text = [f"The paper makes {_plural(len(claims), 'claim')} checked here; {len(checkable)} can be measured."]
    if by["reproduced"]:
        robust = [c for c in by["reproduced"] if shown_label(c) == "robust"]
        thin = [c["id"] for c in robust if _thin(c)]
        thin_words = f" (most explored configurations stayed undecided for {_join(thin)})" if thin else ""
        ids = _join([c["id"] for c in by["reproduced"]])
        text.append(
            f"{_n(len(by['reproduced']), 'claim holds', 'claims hold')} ({ids})"
            + (f", {len(robust)} of them flipped by no reading or world explored{thin_words}." if robust else ".")
        )
    if by["partly"]:
        text.append(
            f"{_n(len(by['partly']), 'claim holds', 'claims hold')} in part ({_join([c['id'] for c in by['partly']])})."
        )
    text += [s for s in map(turns_on_sentence, by["reproduced"] + by["partly"]) if s]
    for c in by["not reproduced"]:
        text.append(f"It does not hold that {_lower(_statement(c))} ({c['id']}): {why_not_clause(c)}.")
    undecided = [c["id"] for c in claims if c.get("verdict") == "undecided"]
    if undecided:
        text.append(f"The runs could not decide {_join(undecided)}.")
    return " ".join(text), limitations(data, profile)


def _thin(c: Mapping) -> bool:
    """Whether a claim's robust label rests on a part most of whose explored configurations stayed undecided."""
    return thin_share((c.get("robustness") or {}).get("parts") or {}) is not None


def _lower(text: str) -> str:
    """A statement continued inside a sentence: its first letter lowered unless it starts an acronym or a name."""
    return text[:1].lower() + text[1:] if text[:2].istitle() and not text[:2].isupper() else text
