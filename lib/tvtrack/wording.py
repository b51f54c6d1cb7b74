"""A claim record (``results.json``) in plain words: values with their units, a few sentences per claim, and the
glossary of the verdict and label words (the paragraphs per set of runs and per paper: :mod:`tvtrack.paragraphs`).

Everything here reads the JSON dicts a run writes (:mod:`tvtrack.results`), so the report, the site and the
notebooks say the same thing in the same words. Import it through :mod:`tvtrack.results`
(``claim_summary``, ``format_measured``, ``GLOSSARY``).

Conventions
-----------
- A number carries its rule's unit, or the quantity's name where the rule has no unit ("0.62 (MSE ratio
  network / filter)").
- A deterministic number (a zero-width interval) is shown without an interval.
- A vector of more than :data:`VECTOR_SHOWN` points is summarised by its ends and its trend.
- Register entries are named by their phrases (``register[].phrases``), never by their code names.
"""

from __future__ import annotations

import itertools
from typing import Any, Mapping

from .register import leaves_operating_point
from .numbers import finite, number, setting
from .run_words import lock_sentence, lost_basis, lost_lead, not_checkable_reason, part_name, plain_text
from .run_words import parts_by_name, runs_sentence, share_counts, slowest_part, thin_share
from .value_words import rule_in_force, value_clause

__all__ = [
    "VERDICT_WORDS",
    "LABEL_WORDS",
    "FLIP_WORDS",
    "FLIP_SHORT",
    "GLOSSARY",
    "PROVISIONAL",
    "SUMMARY_CHARS",
    "shown_label",
    "at_profile",
    "SIDE_ORDER",
    "side_words",
    "entry_side",
    "claim_flips",
    "named_flips",
    "claim_verdict_at",
    "moves_verdict",
    "differs_whatever_is_open",
    "summary_strength",
    "parts_tally",
    "main_part",
    "claim_summary",
    "claim_fields",
    "register_phrases",
]

#: What each verdict means, in the words a reader meets on the first screen.
VERDICT_WORDS = {
    "reproduced": "the whole 95 % interval lies where the paper's value (the rule's band) says",
    "partly": "the claim's parts disagree: some reproduced, some not",
    "not reproduced": "the whole 95 % interval lies outside the paper's band",
    "undecided": "the interval straddles an edge of the band: more runs may decide it (the runs quoted are "
    "projected from its width: at that size an estimate that holds clears the edge about half the time)",
    "not checkable": "the paper gives nothing this project can measure",
}
#: What each robustness label means (a label is about how sure the verdict is, not about the verdict).
LABEL_WORDS = {
    "robust": "no explored reading of the paper and no world beyond it changes the verdict (nor a decided part's)",
    "limited": "holds under every reading of the paper, but not in a named world beyond it",
    "depends": "another reading of an ambiguous passage of the paper, or a setting of its experiment that the paper "
    "never printed, changes the verdict, or a part's (alone, or only with a world beyond it)",
    "unstable": "independent replicates of the same run disagree decisively",
    "unexplored": "nothing explored shows how far it extends (no world varied, or too little of it decided)",
    "provisional": "too few configurations explored to label the verdict (a smoke-size run, or a claim explored "
    "over few entries): never robust",
    "—": "no label: the claim is not checkable, or no part of it is decided (nothing to flip)",
}
#: What counts as a flip (:mod:`tvtrack.labels`: a condition sized to the default's runs, decisive the other way).
FLIP_WORDS = (
    "a change (another reading, setting or world) flips a verdict only when, run at least as often as the default "
    "needed to decide, it decides the other way; an interval across a band edge, or fewer runs, leaves it undecided. "
    "The changes tried are each notebook's register: its list of what the paper left open (readings of its text, "
    "settings it never printed) or never tried (worlds beyond it), each entry with the value the default run uses"
)
FLIP_SHORT = "decisive the other way, from no fewer runs than the default needed"
""":data:`FLIP_WORDS` in one line (the site's glossary, with the whole as its tooltip)."""
GLOSSARY = {**VERDICT_WORDS, **LABEL_WORDS}
"""Every verdict and label word with its meaning (the site's tooltips, the report's glossary)."""
PROVISIONAL = "provisional"
"""The label shown for a record whose design is too small to label (``robustness.provisional``)."""
SUMMARY_CHARS = 250
""":func:`claim_summary` adds its optional sentences only while the whole stays within this many characters (two
lines of a page); the sentences it must say are never cut to fit."""
#: The sides a flip can be on, strongest first: a reading of the text, an unreported setting of the paper's own
#: experiment, a world beyond the paper, several changes that no single one explains.
SIDE_ORDER = ("reading", "setting", "world", "unattributed")
_SIDE_WORDS = {
    "reading": "a reading of the paper's text",
    "setting": "a setting of the paper's own experiment that the paper never printed",
    "world": "a world beyond the paper",
    "unattributed": "a combination of changes that no smaller set of them was found to flip",
}
_WORLD_KINDS = ("regime", "operating point", "model", "scale")


def side_words() -> dict[str, str]:
    """Each side of a flip in plain words (the core's ``tvtrack.register.SIDE_PHRASES`` where it has them)."""
    from . import register

    return {**_SIDE_WORDS, **dict(getattr(register, "SIDE_PHRASES", {}) or {})}


def entry_side(entry: Mapping) -> str:
    """A register entry's side (its record's ``side``, else from its kind: a reading of the paper, an unreported
    setting of its experiment, or a world beyond it)."""
    side = entry.get("side")
    if side in SIDE_ORDER:
        return str(side)
    kind = entry.get("kind")
    if kind == "unreported setting":
        return "setting"
    return "world" if kind in _WORLD_KINDS else "reading"  # a record without kinds: readings, as it always read


def claim_fields(claim: Any) -> Mapping:
    """A claim as ``results.json`` stores it.

    Parameters
    ----------
    claim : Mapping or tvtrack.results.Claim
        A claim record as read from ``results.json``, or the object a notebook builds.

    Returns
    -------
    Mapping
        The dict as it is, or the claim's fields (``vars``) for an object.
    """
    return claim if isinstance(claim, Mapping) else vars(claim)


def at_profile(claims: list[Mapping], profile: str | None) -> list[Mapping]:
    """The claims as a reader of runs at ``profile`` sees them: at any profile but ``"paper"`` every record is
    marked provisional (a smoke-size design is too small to call anything robust, whatever its own flag says),
    and in a provisional record no part is shown as robust or unexplored either (its parts read
    :data:`PROVISIONAL`). Returns new dicts; the records themselves are not changed."""
    out = []
    for c in claims:
        c = dict(claim_fields(c))
        record = c.get("robustness")
        if record and (record.get("provisional") or (profile and profile != "paper")):
            parts = {
                n: (
                    {**p, "label": PROVISIONAL}
                    if isinstance(p, Mapping) and p.get("label") in ("robust", "unexplored")
                    else p
                )
                for n, p in (record.get("parts") or {}).items()
            }
            c["robustness"] = {**record, "provisional": True, **({"parts": parts} if record.get("parts") else {})}
        out.append(c)
    return out


def shown_label(claim: Mapping) -> str:
    """The label a reader sees: the record's; :data:`PROVISIONAL` in place of ``robust`` or ``unexplored`` when
    the design is too small to estimate a share (a smoke run is never shown as robust; a flip it found still
    shows as ``depends``, ``limited`` or ``unstable``); ``"—"`` without a record."""
    record = claim_fields(claim).get("robustness") or {}
    if not record:
        return "—"
    label = str(record.get("label", "—"))
    if label == "-":  # no part decided at the default: nothing to label (labels.NO_PART_LABEL)
        return "—"
    if record.get("provisional") and label in ("robust", "unexplored"):
        return PROVISIONAL
    return label


def register_phrases(record: Mapping) -> dict[str, tuple[str, str, dict]]:
    """The words a claim record's register gives each entry and each of its values.

    Parameters
    ----------
    record : Mapping
        A claim's robustness record (its ``register``: a list of entry dicts).

    Returns
    -------
    dict
        ``{entry name: (title, side, {str(value): phrase})}``, the side ``"reading"`` or ``"world"``
        (:func:`entry_side`).
    """
    out = {}
    for e in record.get("register") or []:
        if isinstance(e, Mapping) and "name" in e:
            out[str(e["name"])] = (str(e.get("title") or e["name"]), entry_side(e), dict(e.get("phrases") or {}))
    return out


def describe(changed: Mapping, record: Mapping) -> str:
    """A configuration's changes in plain words (the register's phrases; ``"<title> = <value>"`` without one)."""
    known = register_phrases(record)
    bits = []
    for k, v in changed.items():
        title, _, phrases = known.get(str(k), (str(k).replace("_", " "), "reading", {}))
        bits.append(phrases.get(str(v)) or f"{title} = {number(v) if finite(v) else v}")
    return " and ".join(bits) or "the default reading"  # one configuration: its changes hold together


def _side(changed: Mapping, record: Mapping) -> str:
    """``"reading"`` when every changed entry is a reading of the paper, ``"setting"`` when every one is a reading
    or an unreported setting (one at least), else ``"world"`` (as the core's flips)."""
    known = register_phrases(record)
    sides = {known.get(str(k), ("", "reading"))[1] for k in changed}
    if sides <= {"reading"}:
        return "reading"
    return "setting" if sides <= {"reading", "setting"} else "world"


def _legacy_flips(claim: Mapping, record: Mapping, names: list[str], part: str | None) -> list[dict]:
    """The conditions whose decisive verdict differs from the claim's (a record without ``parts[].flips``)."""
    flips = []
    for c in record.get("conditions") or []:
        changed = c.get("changed") or c.get("choices") or {}
        v = (c.get("parts") or {}).get(part) if part else c.get("verdict")
        if v in ("reproduced", "not reproduced") and v != claim.get("verdict") and changed:
            kind = "single" if len(changed) == 1 else c.get("kind", "joint")
            flips.append({"changed": changed, "kind": kind, "verdict": v, "side": _side(changed, record), "part": part})
    return flips


_KIND_ORDER = {"single": 0, "combination": 1, "pinned": 2, "joint": 3}
_SIDE_RANK = {"reading": 0, "setting": 1, "unattributed": 2, "world": 3}  # what a label rests on, strongest first


def flip_strength(flip: Mapping) -> tuple:
    """Sort key of a flip, strongest first: its side as the label reads it (a reading before a world), then the
    fewest entries changed (a joint configuration that is its own smallest flipping subset counts its entries,
    like a combination found inside one), then how it was found (a single entry, a searched combination, a pinned
    or a joint configuration)."""
    return (
        _SIDE_RANK.get(flip.get("side", "reading"), 4),
        len(flip.get("changed") or {}),
        _KIND_ORDER.get(flip.get("kind"), 4),
    )


def moves_verdict(claim: Mapping, flip: Mapping) -> bool:
    """Whether a flip changes the whole claim's verdict (not only one part's): true for a claim of one part or no
    condition at the flip's changes to tell; else :func:`differs_whatever_is_open` (an undecided claim that reads
    ``partly`` under the flip may read ``partly`` at the default too)."""
    claim = claim_fields(claim)
    parts = ((claim.get("robustness") or {}).get("parts") or {}), ((claim.get("rule") or {}).get("parts") or {})
    if max(map(len, parts)) <= 1:
        return True
    row = _condition_at(claim, flip.get("changed") or {})
    return row is None or differs_whatever_is_open(claim, row)


def differs_whatever_is_open(claim: Mapping, row: Mapping) -> bool:
    """Whether the whole claim's verdict under a condition (``row``, a record's ``conditions`` item) differs from
    the default's for every outcome of the parts undecided on either side: a part undecided on both sides is
    taken to come out the same way on both, one undecided on one side only either way. Two decided verdicts
    compare as they are; a row without its parts' verdicts compares its whole verdict (undecided on both sides is
    not shown to move: the claim's sentence says it "stays undecided")."""
    here, there = claim_fields(claim).get("verdict"), row.get("verdict")
    if "undecided" not in (here, there):
        return there != here
    default = {n: p.get("verdict") for n, p in ((claim.get("robustness") or {}).get("parts") or {}).items()}
    at = row.get("parts")
    if not isinstance(at, Mapping) or not default or set(at) != set(default):
        return there != here  # undecided on both sides: not shown to move, as the claim's sentence says
    names = [n for n in default if "not checkable" not in (default[n], at[n])]
    open_ = [n for n in names if "undecided" in (default[n], at[n])]
    for outcome in itertools.product(("reproduced", "not reproduced"), repeat=len(open_)):
        pick = dict(zip(open_, outcome))
        a = {default[n] if default[n] != "undecided" else pick[n] for n in names}
        b = {at[n] if at[n] != "undecided" else pick[n] for n in names}
        if (a if len(a) == 1 else {"partly"}) == (b if len(b) == 1 else {"partly"}):
            return False
    return True


def flip_leaves_operating_point(claim: Mapping, flip: Mapping) -> bool:
    """Whether a flip changes an entry to a value the register marks as leaving the operating point the paper
    states (``off_operating_point`` in the record's register)."""
    register = (claim_fields(claim).get("robustness") or {}).get("register") or []
    off = {e.get("name"): e.get("off_operating_point") or [] for e in register if isinstance(e, Mapping)}
    return leaves_operating_point(flip.get("changed") or {}, off)


def summary_strength(claim: Mapping, flip: Mapping) -> tuple:
    """Sort key of the flip a claim's sentence names, strongest first: a reading or an unreported setting before a
    mix no subset isolates, before a world (so the named flip is one the label rests on); then one that changes
    the whole claim's verdict before one that moves only a part; then one that keeps the paper's stated operating
    point before one that leaves it (:func:`flip_leaves_operating_point`); then :func:`flip_strength`."""
    group = {"reading": 0, "setting": 0, "unattributed": 1, "world": 2}.get(flip.get("side", "reading"), 3)
    return (group, not moves_verdict(claim, flip), flip_leaves_operating_point(claim, flip), *flip_strength(flip))


def named_flips(claim: Mapping) -> list[dict]:
    """The flips a claim's sentences name, strongest first (:func:`summary_strength`): its main part's
    (:func:`main_part`), or every part's where another part has a stronger one (the one the label rests on). The
    first is the flip the summary, the table and the paper's paragraph all name."""
    flips, every = claim_flips(claim, main_part(claim)), claim_flips(claim)

    def strength(f: Mapping) -> tuple:
        return summary_strength(claim, f)

    if not flips or (every and min(map(strength, every)) < min(map(strength, flips))):
        flips = every  # a stronger flip of another part is the one the label rests on
    return sorted(flips, key=strength)


def claim_flips(claim: Mapping, part: str | None = None) -> list[dict]:
    """The configurations that flip the claim (or one part): ``[{text, side, kind, verdict, part, changed}]`` (and
    ``lost_runs`` where the paper counted the runs that lost lock under it),
    by side as the label reads them (readings of the paper, then unreported settings, then combinations of mixed
    sides that no subset isolates, all of which make ``depends``, then worlds beyond it), within a side single entries before the smallest combinations, each text said
    once: the first is the flip that the claim's label rests on.

    Reads ``parts[].flips`` (the explorer's attribution); for a record without it, the conditions whose decisive
    verdict differs from the claim's."""
    claim = claim_fields(claim)
    record = claim.get("robustness") or {}
    parts = parts_by_name(record)
    names = [part] if part else list(parts)
    flips = [{**f, "part": n} for n in names for f in ((parts.get(n) or {}).get("flips") or [])]
    if not flips and not any("flips" in (parts.get(n) or {}) for n in names):
        flips = _legacy_flips(claim, record, names, part)
    out, seen = [], set()
    for f in sorted(flips, key=flip_strength):
        text = str(f.get("text") or describe(f.get("changed") or {}, record))
        if text in seen:  # the same flip through another part: what its copy carries is kept
            kept = next(o for o in out if o["text"] == text)
            kept.update({k: f[k] for k in ("lost_runs", "undecided_subsets") if f.get(k) and not kept.get(k)})
        else:
            seen.add(text)
            out.append(
                {
                    "text": text,
                    "side": f.get("side", "reading"),
                    "kind": f.get("kind"),
                    "verdict": f.get("verdict"),
                    "part": f.get("part"),
                    "changed": dict(f.get("changed") or {}),
                    **({"lost_runs": f["lost_runs"]} if f.get("lost_runs") else {}),
                    **({"undecided_subsets": list(f["undecided_subsets"])} if f.get("undecided_subsets") else {}),
                }
            )
    return out


_LABEL_ORDER = ("unstable", "depends", "limited", "unexplored", "robust")


def main_part(claim: Mapping) -> str | None:
    """The part a claim's sentence and its specification curve are about: for a claim that does not hold, its
    part that does not; for an undecided one, its undecided part; else its weakest-labelled part (a part with
    named flips before one without). ``None`` for a record without parts."""
    claim = claim_fields(claim)
    parts = {n: p for n, p in ((claim.get("robustness") or {}).get("parts") or {}).items() if isinstance(p, Mapping)}
    rule = rule_in_force(dict(claim.get("rule") or {}), claim.get("measured"))[0]
    if rule.get("kind") != "all_of":
        return next(iter(parts), None)
    rules = rule.get("parts") or {}
    names = [n for n in rules if (rules[n] or {}).get("kind") != "not_checkable"] or list(rules)
    want = {"not reproduced": "not reproduced", "partly": "not reproduced", "undecided": "undecided"}
    target = want.get(str(claim.get("verdict")), "reproduced")

    def key(n: str):
        p = parts.get(n, {})
        lab = p.get("label")
        return (p.get("verdict") != target, not p.get("flips"), _LABEL_ORDER.index(lab) if lab in _LABEL_ORDER else 9)

    return min(names, key=key) if names else None


# --- one sentence per claim ------------------------------------------------------------------------------------

_HEAD = {
    "reproduced": "Reproduced",
    "not reproduced": "Not reproduced",
    "partly": "Partly reproduced",
    "undecided": "Undecided",
}


def _cap(text: str) -> str:
    return text[:1].upper() + text[1:]


def _share_sentence(part: Mapping, name: str | None = None) -> str:
    """A part's share as a sentence, said of its part ``name`` where that is not the part the sentence shows."""
    text = share_counts(part.get("share") or {})
    return "" if not text else f"For its part {part_name(name)}, {text}." if name else f"{_cap(text)}."


def claim_verdict_at(claim: Mapping, changed: Mapping) -> str | None:
    """The whole claim's verdict under the condition that changes ``changed`` (None where no condition does)."""
    return None if (row := _condition_at(claim, changed)) is None else str(row["verdict"])


def _condition_at(claim: Mapping, changed: Mapping) -> Mapping | None:
    """The record's condition that changes ``changed`` and carries a verdict (None where none does)."""
    rows = (claim.get("robustness") or {}).get("conditions") or ()
    return next((c for c in rows if dict(c.get("changed") or {}) == dict(changed) and c.get("verdict")), None)


def parts_tally(verdicts: list) -> str:
    """A claim's checkable parts by verdict: ``"all 3 parts hold"``, ``"5 parts hold, 1 fails, 4 undecided"``."""
    n = len(verdicts)
    held = sum(v == "reproduced" for v in verdicts)
    if held == n:
        return f"all {n} parts hold"
    failed = sum(v == "not reproduced" for v in verdicts)
    open_ = n - held - failed
    bits = [f"{held} part{'s' * (held != 1)} hold{'s' * (held == 1)}" if held else "no part holds"]
    bits += [f"{failed} fail{'s' * (failed == 1)}"] if failed else []
    bits += [f"{open_} undecided"] if open_ else []
    return ", ".join(bits)


def _flip_to(flip: Mapping, claim: Mapping, n_parts: int) -> str:
    """Where a flip takes the claim: the part's verdict is the claim's only for a claim of one part; a claim of
    several says the whole claim's verdict there, and the part's where the two differ."""
    verdict = flip.get("verdict")
    if not verdict:
        return "the verdict changes"
    whole = claim_verdict_at(claim, flip.get("changed") or {}) if n_parts > 1 else None
    if whole is None or whole == verdict:
        return f"it is {verdict}"
    said = _HEAD.get(whole, whole).lower()
    if whole == claim.get("verdict"):  # the whole claim keeps its word; undecided, it may still not end the same
        late = (
            ", so it cannot come out as at the default" if whole == "undecided" and moves_verdict(claim, flip) else ""
        )
        return f"the claim stays {said}, but its part {part_name(flip.get('part'))} is {verdict}{late}"
    return f"the claim is {said} (its part {part_name(flip.get('part'))}: {verdict})"


def _flip_sentence(flip: Mapping, claim: Mapping | None = None, n_parts: int = 1) -> str:
    """The strongest named flip in plain words: what kind of change it is, where it takes the claim (and its part,
    for a claim of several parts), and the change itself (the register's phrases)."""
    side, text = flip.get("side", "reading"), plain_text(str(flip.get("text") or ""))
    to = _flip_to(flip, claim or {}, n_parts)
    lost = flip.get("lost_runs") or {}
    carried = (
        f" {lost_lead(lost, 'the {k} of {n} runs that lost lock there')} "
        f"{'carries' if lost['lost'] == 1 else 'carry'} that flip: over {lost_basis(lost)}runs in lock alone the "
        f"claim is {lost['in_lock_verdict']}, but the verdict counts every run, so the flip stands."
        if lost.get("carried")
        else ""
    )
    if side == "world":
        return f"It does not extend to {text}: there {to}.{carried}"
    changed = flip.get("changed") or {}
    if len(changed) > 1 and side != "reading":  # a mix: each change with its kind, so the reader sees which is which
        text = kinds_of_changes(changed, (claim or {}).get("robustness") or {}) or text
    return f"{_flip_lead(side, len(changed), not flip.get('undecided_subsets'))} {to}: {text}.{carried}"


_COUNT_WORDS = {2: "two", 3: "three", 4: "four", 5: "five"}
_KIND_TAGS = {
    "reading": "a reading of the paper's text",
    "setting": "a setting the paper never printed",
    "world": "a world beyond the paper",
}


def _common_sentence(flips: list, record: Mapping) -> str:
    """Where every named flip (two at least, one a combination) shares a change, that change and its kind: the
    common cause a list of combinations hides ("Every change that flips it includes lost frames skipped (a world
    beyond the paper)."); ``""`` otherwise."""
    if len(flips) < 2 or all(len(f.get("changed") or {}) < 2 for f in flips):
        return ""
    items = [{(k, repr(v)) for k, v in (f.get("changed") or {}).items()} for f in flips]
    common = set.intersection(*items)
    if not common:
        return ""
    first = flips[0].get("changed") or {}
    shared = {k: v for k, v in first.items() if (k, repr(v)) in common}
    text = kinds_of_changes(shared, record)
    return f"Every change that flips it includes {text}." if text else ""


def kinds_of_changes(changed: Mapping, record: Mapping) -> str:
    """The changes of a combination in plain words, each followed by its kind (``"fast wander (a setting the
    paper never printed) and lost frames skipped (a world beyond the paper)"``); ``""`` where the record's
    register does not know an entry."""
    known = register_phrases(record)
    bits = []
    for k, v in changed.items():
        if str(k) not in known:
            return ""
        title, side, phrases = known[str(k)]
        phrase = plain_text(str(phrases.get(str(v)) or setting(title, v)))
        bits.append(f"{phrase} ({_KIND_TAGS.get(side, _KIND_TAGS['reading'])})")
    return " and ".join(bits) if len(bits) < 3 else ", ".join(bits[:-1]) + " and " + bits[-1]


def _flip_lead(side: str, n: int, shown: bool = True) -> str:
    """How a flip that is not a world is introduced: its kind and, for a combination, how many changes it takes
    (a combination is a setting where one of its entries is; :func:`tvtrack.attribution.flip_side`)."""
    if n <= 1:
        return {
            "reading": "Under another reading of the paper's text",
            "setting": "Under another setting of the paper's own experiment, one the paper never printed,",
        }.get(side, "Under another change")
    w = _COUNT_WORDS.get(n, str(n))
    return {
        "reading": f"Under {w} other readings of the paper's text together",
        "setting": f"Under {w} changes together",
    }.get(side, f"Under {w} changes together (none of them {'flips' if shown else 'is shown to flip'} it alone)")


def _unexplored_sentence(claim: Mapping, parts: Mapping) -> str:
    """Why a claim is ``unexplored``: nothing was varied for it, none of its explored configurations was decided,
    fewer were decided than a share needs, or no world beyond the paper was among them (its part so labelled with
    the fewest decided configurations says which, named where several are)."""
    if shown_label(claim) != "unexplored" or claim.get("verdict") == "undecided":  # undecided: its runs come first
        return ""
    weak = [(n, p) for n, p in parts.items() if isinstance(p, Mapping) and p.get("label") == "unexplored"]
    name, part = min(weak, key=lambda w: int((w[1].get("share") or {}).get("decided") or 0), default=(None, {}))
    share = part.get("share") or {}
    design = int(share.get("design") or 0)
    if not design:
        return "Nothing was varied for it, so nothing shows how far it extends."
    if not share.get("agree"):
        which = "the one change" if design == 1 else f"each of the {design} changes"
        return f"Beyond the paper's default, {which} explored for it left it undecided, so nothing shows how far it extends."
    if share.get("decided_needed"):
        decided = int(share.get("agree") or 0) + int(share.get("flip") or 0)
        whose = f" (its part {part_name(name)})" if len(weak) > 1 else ""
        return (
            f"Beyond the paper's default, only {decided} of the {design} changes explored for it{whose} decided it and "
            f"{int(share.get('undecided') or 0)} left it undecided; {share['decided_needed']} decided ones are needed "
            "to say how far it extends, so nothing shows that yet."
        )
    return "No world beyond the paper was varied for it, so nothing shows how far it extends."


def claim_summary(claim: Mapping, chars: int = SUMMARY_CHARS) -> str:
    """The claim in a few complete sentences chosen from its record, never cut: the verdict with the measured
    value in words and units against what the paper says (and the direction in words where it reverses the
    paper's), the strongest named flip in plain words (a reading of the text, an unreported setting of the
    paper's experiment, or a world it does not extend to), whether runs that lost lock decide it, for an undecided
    claim the runs that would decide it, for a robust one resting on few decided configurations its share
    (:func:`tvtrack.run_words.thin_share`); then, while the whole stays within ``chars``, the share and how many
    other changes flip it. Everything else is in the record behind the click.

    Parameters
    ----------
    claim : dict or tvtrack.results.Claim
        A claim as ``results.json`` stores it (``id, verdict, measured, rule, robustness, ...``), or as
        :meth:`tvtrack.results.Results.claim` returns it.
    chars : int
        The length the optional sentences must keep the whole within (the required ones are never cut).

    Returns
    -------
    str
        E.g. ``"Not reproduced: ... is 351.6 [350, 353.1] x alpha, where the paper has [0, 2] x alpha. Under another
        reading of the paper's text (...) it is reproduced. 29 agree, 3 flip and 0 stay undecided of 32 ..."``
    """
    claim = claim_fields(claim)
    verdict = str(claim.get("verdict", ""))
    if verdict == "not checkable":
        return f"Not checkable: {not_checkable_reason(claim)}."
    rule, measured = rule_in_force(dict(claim.get("rule") or {}), claim.get("measured"))
    name = main_part(claim)
    parts = (claim.get("robustness") or {}).get("parts") or {}
    part = parts.get(name) if isinstance(parts.get(name), Mapping) else {}
    aside = []
    if rule.get("kind") == "all_of" and isinstance(measured, Mapping):
        checked = [n for n, r in (rule.get("parts") or {}).items() if (r or {}).get("kind") != "not_checkable"]
        if len(checked) > 1:
            aside.append(parts_tally([(parts.get(n) or {}).get("verdict") for n in checked]))
        rule, measured = (rule.get("parts") or {}).get(name) or {}, measured.get(name)
    if shown_label(claim) == PROVISIONAL:
        aside.append("too few configurations to label")
    head = _HEAD.get(verdict, _cap(verdict)) + (f" ({'; '.join(aside)})" if aside else "")
    flips = named_flips(claim)
    required = [f"{head}: {value_clause(rule, measured, claim.get('paper_value'))}."]
    required += [plain_text(str(claim["caveat"])).rstrip(".") + "."] if claim.get("caveat") else []
    required += [s for s in (lock_sentence(claim, part),) if s]  # the default's own lost runs, before any flip
    first = _flip_sentence(flips[0], claim, len(parts)) if flips else ""
    common = _common_sentence(claim_flips(claim), claim.get("robustness") or {})  # "it": the claim, every part's flips
    required += [s for s in (first, common, _unexplored_sentence(claim, parts)) if s]
    if verdict == "undecided":
        slow_name, slow = slowest_part(parts, part)
        required.append(runs_sentence(slow, slow_name))
    thin = thin_share(parts) if shown_label(claim) == "robust" else None  # a label resting on few: its share
    required += [_share_sentence(thin[1], thin[0] if thin[1] is not part else None)] if thin else []
    optional = [] if thin else [_share_sentence(part)]
    if len(flips) > 1:
        others = len(flips) - 1
        optional.append(f"{others} other change{'s' if others > 1 else ''} flip{'' if others > 1 else 's'} it too.")
    text = " ".join(s for s in required if s)
    for s in optional:
        if s and len(text) + 1 + len(s) <= chars:
            text += " " + s
    return text
