"""What a part's flips are, how many configurations agree, and which entries move it (:mod:`tvtrack.labels`).

- :func:`share`: agree, flip and undecided counted over **every** explored configuration, and the share that
  agrees of all of them (Clopper-Pearson), never a share of the decided ones only;
- :func:`attribute`: each flip named by the smallest set of entries that flips it alone, with its **side**
  (:data:`tvtrack.register.SIDES`): a reading of the paper's text, an unreported setting of its own experiment, a
  world beyond it, or ``unattributed`` (a flip mixing sides that no subset isolates, or one with more than one entry
  beyond the searched size, :data:`MAX_SUBSET` by default, of which no subset of up to that size flips);
- :func:`sensitivity`: the entries ranked by the spread of the part's value over their one-at-a-time values.
"""

from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

import numpy as np
import scipy  # scipy.stats is imported at its first use (scipy loads submodules lazily)

from .numbers import setting
from .register import side_of
from .verdicts import is_decisive

__all__ = [
    "MAX_SUBSET",
    "SENSITIVITY_METHOD",
    "share",
    "attribute",
    "sensitivity",
    "paired_rows",
    "beside_operating_point",
    "flip_side",
    "phrase",
]

#: The largest subset of a joint flip's changed entries the explorer tries alone by default (pairs, then
#: triples); ``explore(max_subset=...)`` states another, recorded in the design.
MAX_SUBSET = 3

SENSITIVITY_METHOD = (
    "one at a time: each entry's score is the variance of the part's value over the entry's one-at-a-time values "
    "(the default's value included), as a share of the sum over the entries; joint configurations are left out, "
    "so an entry that only co-occurs with the real cause scores nothing; an entry whose values choose another rule "
    "(a reading under which the claim measures another quantity) is not ranked, its values being on other scales; "
    "each configuration's value is compared with the default's over the same replicate seeds; an entry that moves "
    "the value by less than a hundredth of the default's distance to its band's nearest edge scores nothing; "
    "configurations outside the paper's stated operating point are left out"
)


def phrase(changed: Mapping[str, Any], entries: Mapping[str, Any]) -> str:
    """A configuration's changes in plain words (the entries' phrases)."""
    out = []
    for k, v in changed.items():
        e = entries.get(k)
        out.append(e.phrase(v) if e is not None else setting(k, v))
    return " and ".join(out) or "the default reading"  # one configuration: its changes hold together


def flip_side(changed: Mapping[str, Any], entries: Mapping[str, Any]) -> str:
    """The side of a flip that changes ``changed`` and that no subset of it isolates: ``"reading"`` when every
    entry is a reading of the paper, ``"setting"`` when every entry is a reading or an unreported setting and one a
    setting, ``"world"`` when every entry is a world, ``"unattributed"`` when readings or settings mix with worlds.
    An entry of no register is read as a reading (the label is then never stronger than ``depends``)."""
    sides = {entries[k].side if k in entries else side_of("reading") for k in changed}
    if sides == {"world"}:
        return "world"
    if "world" in sides:
        return "unattributed"
    return "setting" if "setting" in sides else "reading"


def share(verdicts: Sequence[str], default: str, confidence: float = 0.95) -> dict | None:
    """Agree, flip and undecided over every explored configuration, and the share that agrees of all of them.

    Parameters
    ----------
    verdicts : sequence of str
        One verdict per distinct explored configuration (``undecided`` for one too small to decide).
    default : str
        The default's pooled verdict (decisive; else there is no share).

    Returns
    -------
    dict or None
        ``agree``, ``flip``, ``undecided``, ``design`` (their sum), ``decided`` (agree + flip), ``value`` (agree /
        design) and its Clopper-Pearson interval ``ci_low``, ``ci_high`` over the design.
    """
    if not is_decisive(default):
        return None
    n = len(verdicts)
    agree = sum(v == default for v in verdicts)
    flip = sum(is_decisive(v) and v != default for v in verdicts)
    out = {"agree": agree, "flip": flip, "undecided": n - agree - flip, "design": n, "decided": agree + flip}
    if n == 0:
        return {**out, "value": math.nan, "ci_low": 0.0, "ci_high": 1.0}
    ci = scipy.stats.binomtest(agree, n).proportion_ci(confidence, method="exact")
    return {**out, "value": agree / n, "ci_low": float(ci.low), "ci_high": float(ci.high)}


def _subset(a: Mapping, b: Mapping) -> bool:
    return all(k in b and b[k] == v for k, v in a.items())


def attribute(
    default: str,
    rows: Sequence[Mapping],
    entries: Mapping[str, Any],
    same_seed: str | None = None,
    max_subset: int = MAX_SUBSET,
) -> list[dict]:
    """The configurations that flip a part, each named by the smallest set of entries found to flip it alone.

    A configuration flips the part when its verdict is decisive and differs from the default's pooled decisive
    verdict. A configuration of one run (a hand-built record, or an unsized one) must differ, where the default's
    run on the same random numbers (the first replicate) is decisive, from that run's verdict too.

    Parameters
    ----------
    default : str
        The default's pooled decisive verdict.
    rows : sequence of {"changed", "kind", "verdict", "runs" (optional)}
        The part under every explored condition (``kind``: single, joint, pinned or combination); ``verdict`` is
        ``undecided`` for a condition smaller than the default.
    entries : mapping name -> Entry
    same_seed : str, optional
        The verdict of the default's run on the conditions' first random numbers.
    max_subset : int, optional
        The largest subset the explorer searched (its design's ``max_subset``): a joint flip of ``max_subset + 1``
        entries that no searched subset explains is its own smallest flipping subset (every smaller one was tried);
        one of more entries is ``unattributed``.

    Returns
    -------
    list of dict
        ``{"changed", "side", "kind", "verdict", "text", "runs"}``: single entries first (readings, settings,
        worlds), then the smallest combinations that flip a joint configuration no single entry explains and the
        joint configurations no subset of which flips (each its own smallest subset), pairs before triples:
        ``side`` from their entries (mixed sides: ``unattributed``); after them ``unattributed`` with a ``note``,
        a joint configuration of more than ``max_subset + 1`` changed entries; last, every combination that flips the part alone and contains no flip named before it
        (one searched for another part, or inside a joint configuration a single entry explains).
    """
    if not is_decisive(default):
        return []
    crn = same_seed if same_seed is not None and is_decisive(same_seed) else default
    flipped = [
        r
        for r in rows
        if is_decisive(r["verdict"]) and r["verdict"] != default and (r.get("runs", 1) > 1 or r["verdict"] != crn)
    ]
    singles = [r for r in flipped if r["kind"] == "single"]
    combos = [r for r in flipped if r["kind"] == "combination"]
    joints = [r for r in flipped if r["kind"] in ("joint", "pinned")]
    out: list[dict] = []
    seen: set = set()
    order = {"reading": 0, "setting": 1, "unattributed": 2, "world": 3}

    def add(r: Mapping, kind: str, side: str, note: str = "") -> None:
        key = tuple(sorted((k, repr(v)) for k, v in r["changed"].items()))
        if key in seen:
            return
        seen.add(key)
        f = {"changed": dict(r["changed"]), "side": side, "kind": kind, "verdict": r["verdict"]}
        f.update({"text": phrase(r["changed"], entries), "runs": r.get("runs", 1)})
        if side == "unattributed" and not note:
            note = (
                "readings or unreported settings changed together with worlds; no subset of them was found to flip it"
            )
        out.append({**f, "note": note} if note else f)

    for r in sorted(singles, key=lambda r: order[flip_side(r["changed"], entries)]):
        add(r, "single", flip_side(r["changed"], entries))
    later: list[tuple] = []
    for j in joints:
        if any(_subset(s["changed"], j["changed"]) for s in singles):
            continue  # a single entry already explains it
        subs = [c for c in (*combos, *joints) if _subset(c["changed"], j["changed"]) and c["changed"] != j["changed"]]
        if subs:  # a smaller combination (or a smaller joint configuration) that flips alone names it
            smallest = min(len(c["changed"]) for c in subs)
            if any(len(c["changed"]) == smallest and c["kind"] != "combination" for c in subs):
                continue  # the smaller joint flip is named in its own right
            later += [(smallest, c, "combination", "") for c in subs if len(c["changed"]) == smallest]
        elif len(j["changed"]) > max_subset + 1:  # every smaller subset of one entry more was searched
            note = (
                f"{len(j['changed'])} entries changed together and no subset of up to {max_subset} of them, at the "
                "paper's operating point, was found to flip it: unattributed"
            )
            later.append((len(j["changed"]) + 100, j, "joint", note))  # after every named combination
        else:
            later.append((len(j["changed"]), j, "joint", ""))  # its own smallest subset: beside those of its size
    for _, r, kind, note in sorted(later, key=lambda t: (t[0], order[flip_side(t[1]["changed"], entries)])):
        add(r, kind, "unattributed" if note else flip_side(r["changed"], entries), note)
    # a combination searched for another part (or inside a joint a single explains) that flips this part alone
    for c in sorted(combos, key=lambda r: (len(r["changed"]), order[flip_side(r["changed"], entries)])):
        if not any(_subset(f["changed"], c["changed"]) for f in out):
            add(c, "combination", flip_side(c["changed"], entries))
    for f in out:  # named the smallest only as far as its smaller subsets were decided
        open_ = _undecided_subsets(f["changed"], rows, entries)
        if open_:
            f["undecided_subsets"] = open_
    return out


def _undecided_subsets(changed: Mapping, rows: Sequence[Mapping], entries: Mapping[str, Any]) -> list[str]:
    """The strict subsets of a flip's changes measured and left ``undecided`` (smaller than the default needed: a
    sizing budget, or a searched combination leaning towards agreement, which is never sized), in words: while one
    is open, the flip is the smallest found, not the smallest shown."""
    out: list[str] = []
    for r in rows:
        ch = r["changed"]
        if ch and len(ch) < len(changed) and _subset(ch, changed) and r["verdict"] == "undecided":
            text = phrase(ch, entries)
            out += [] if text in out else [text]
    return out


def sensitivity(
    rows: Sequence[Mapping], names: Sequence[str], entries: Mapping[str, Any], default: Mapping, floor: float = 0.0
) -> list:
    """Entries ranked by how much their one-at-a-time values move a part's value (:data:`SENSITIVITY_METHOD`).

    Only rows at the default and rows that change one entry count: an entry's score is the variance of the
    part's value over its values (each value's rows averaged; the default's value included), as a share of the
    sum over the entries. Joint rows are left out, so an entry that co-occurs with the real cause in the joint
    design scores nothing it did not move alone. An entry none of whose values moves the value by more than
    ``floor`` from the default's scores nothing. Needs the default's row and some spread; else an empty list.

    Parameters
    ----------
    rows : sequence of {"config": full configuration, "value": float}
    names : entry names the claim reads
    default : the default configuration (an entry missing from a row's config is at its default)
    floor : the least change of the value that counts as a move (same unit as the value)
    """
    pts = [(r["config"], r["value"]) for r in rows if math.isfinite(r["value"])]

    def changes(c: Mapping) -> list:
        return [k for k in names if repr(c.get(k, default.get(k))) != repr(default.get(k))]

    base = [v for c, v in pts if not changes(c)]
    if not base:
        return []
    spread = {}
    for k in names:
        levels: dict[str, list] = {repr(default.get(k)): base}
        for c, v in pts:
            if changes(c) == [k]:
                levels.setdefault(repr(c.get(k)), []).append(v)
        means = [float(np.mean(v)) for v in levels.values()]
        moved = max(abs(m - means[0]) for m in means) > floor
        spread[k] = float(np.var(means)) if len(levels) > 1 and moved else 0.0
    total = sum(spread.values())
    if not total > 0:
        return []
    out = [
        {"entry": k, "title": (entries[k].title or k) if k in entries else k, "score": spread[k] / total} for k in names
    ]
    return sorted(out, key=lambda d: -d["score"])


def paired_rows(conditions: Sequence[Mapping], values: Sequence[float], replicates: Sequence[float]) -> list:
    """Sensitivity rows (``{"config", "value"}``) of one-at-a-time ``conditions`` whose ``values`` were pooled
    over their first ``runs`` replicate seeds, each compared with the default over the same seeds (common random
    numbers): a condition's value is moved by the default's mean over all its ``replicates`` minus its mean over
    those seeds, so the replicates' own scatter does not score as an entry's effect."""
    reps = [float(r) for r in replicates]
    out = []
    for c, v in zip(conditions, values):
        k = int(c.get("runs") or len(reps))
        same = reps[:k]
        shift = float(np.mean(reps) - np.mean(same)) if same and all(map(math.isfinite, reps)) else 0.0
        out.append({"config": c["config"], "value": float(v) + shift})
    return out


def beside_operating_point(rows: Sequence[Mapping], default: str) -> dict | None:
    """The configurations of one part that leave the paper's stated operating point (``off_operating_point``),
    counted beside its label: ``{"agree", "flip", "undecided", "flips": [{"changed", "verdict", "text"}]}`` (each
    configuration once; a flip whose configuration the exploration marked also says ``why``); None when there are
    none."""
    seen, out = set(), {"agree": 0, "flip": 0, "undecided": 0, "flips": []}
    for r in rows:
        key = frozenset((k, repr(v)) for k, v in r["changed"].items())
        if not r.get("off_operating_point") or key in seen:
            continue
        seen.add(key)
        v = r["verdict"]
        kind = "agree" if v == default else "flip" if v in ("reproduced", "not reproduced") else "undecided"
        out[kind] += 1
        if kind == "flip":
            why = {"why": r["operating_point_lost"]} if r.get("operating_point_lost") else {}
            out["flips"].append({"changed": dict(r["changed"]), "verdict": v, "text": r["text"], **why})
    out["flips"].sort(key=lambda f: len(f["changed"]))
    return out if seen else None
