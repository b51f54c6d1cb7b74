"""The generated prose of paper 000's notebook: one claim's details, the conclusions, the conditions a figure shows
(the findings table at the top is the core's :func:`tvtrack.results.claims_table`).

Every number and every interpretive word comes from the claims' rules and the exploration's records.
"""

from __future__ import annotations

from collections import Counter

from ...verdicts import ByReading
from ...measured import as_estimate
from ...run_words import lock_sentence, lost_basis, lost_lead
from ...wording import at_profile, claim_fields, main_part, shown_label

__all__ = [
    "claim_details",
    "conclusions",
    "reproduced_where",
    "condition_rows",
    "drawn_conditions",
    "conditions_above",
    "pull_in_words",
    "beside",
]


def claim_details(results, ex, claim_id: str) -> str:
    """The claim's rule, its verdict and label per part, the coverage and where a condition changes a part."""
    c = next(c for c in results.claims if c.id == claim_id)
    rec = c.robustness
    lines = [
        f"**{c.id}** ({c.statement}) **Rule:** {c.acceptance}.",
        "",
        f"**Verdict: {c.verdict}; label: {rec['coverage']}.**",
        "",
        "| part | verdict | label | replicates |",
        "|---|---|---|---|",
    ]
    for name, p in at_profile([c], "paper")[0]["robustness"]["parts"].items():  # the labels as the reader sees them
        lines.append(f"| {name} | {p['verdict']} | {p['label']} | {', '.join(p['replicate_verdicts'])} |")
    if rec["where"]:
        lines += ["", "Where a verdict differs: " + "; ".join(rec["where"]) + "."]
    return "\n".join(lines)


def conclusions(claims, ex) -> str:
    """The closing section: the verdicts and labels counted, each claim in one line, and what the register tried."""
    checkable = [c for c in claims if c.verdict != "not checkable"]
    verdicts = Counter(c.verdict for c in checkable)
    labels = Counter(shown_label(c) for c in checkable if c.robustness)
    adversarial = [e.name for e in ex.register if e.origin == "adversarial"]
    lines = [
        f"Of {len(checkable)} checkable claims: "
        + ", ".join(f"{n} {v}" for v, n in verdicts.most_common())
        + "; labels "
        + ", ".join(f"{n} {lab}" for lab, n in labels.most_common())
        + ".",
        f"The exploration ran {ex.settings['replicates']} independent replicates, {_configurations(ex)} over "
        f"{len(ex.register)} register entries"
        + (f" (added while trying to flip a label: {', '.join(adversarial)})." if adversarial else "."),
        "",
    ]
    open_ = [c for c in checkable if c.verdict != "reproduced" or shown_label(c) != "robust"]
    if open_:
        lines.append("Where a claim is not reproduced, or its verdict moves with the register (every named flip):")
    for c in sorted(open_, key=lambda c: int(c.id.split("-")[1])):
        shown = [w + _lost_flip(c, w) for w in ((c.robustness or {}).get("where") or [])]
        where = f": {'; '.join(shown)}" if shown else ""
        lines.append(f"- **{c.id}** {c.verdict}, {shown_label(c)}{where}.{_lost_default(c)}")
    return "\n".join(lines)


def _configurations(ex) -> str:
    """``"35 one-at-a-time configurations and 32 joint configurations (measured in 227 runs: ...)"``: configurations
    counted as configurations (a one-at-a-time one is one run; a joint sample of the register is measured once per
    group of claims that read its changes, so its runs are counted apart)."""
    default = ex.register.default()
    singles = {tuple(sorted(map(str, r.changed(default).items()))) for r in ex.runs if r.stage == "single"}
    joint = int(ex.settings.get("joint_configurations") or 0)
    runs = sum(r.stage == "joint" for r in ex.runs)
    said = f"{len(singles)} one-at-a-time configurations and {joint} joint configuration{'s' * (joint != 1)}"
    return said + (
        f" (measured in {runs} runs: each joint configuration once per group of claims that read what it changes)"
        if runs
        else ""
    )


def _lost_flip(claim, where: str) -> str:
    """Where only runs that lost lock carry the flip a line of ``where`` names (the record's ``lost_runs`` on that
    flip, as the findings table's sentence says it): how many of how many runs, and the verdict over the runs in
    lock; ``""`` for a flip the runs in lock carry too, or a line that names no flip."""
    parts = {n: p for n, p in ((claim.robustness or {}).get("parts") or {}).items() if isinstance(p, dict)}
    own = [p for n, p in parts.items() if where.startswith(f"({n}) ")]  # a line of a claim of several parts
    flips = [f for p in own or parts.values() for f in p.get("flips") or ()]
    named = [f for f in flips if f"{f.get('verdict')} when {f.get('text')}" in where]
    lost = (max(named, key=lambda f: len(f["text"])).get("lost_runs") or {}) if named else {}
    if not lost.get("carried"):
        return ""
    lead = lost_lead(lost, "the {k} of {n} runs that lost lock there")
    carry = "carries" if lost["lost"] == 1 else "carry"
    return (
        f", but {lead[:1].lower()}{lead[1:]} {carry} that flip: over {lost_basis(lost)}runs in lock alone the claim "
        f"is {lost['in_lock_verdict']}"
    )


def _lost_default(claim) -> str:
    """The runs that lost lock where they carry the claim's own verdict at the default (the sentence the findings
    table gives, :func:`tvtrack.run_words.lock_sentence`), after a space; ``""`` where they do not."""
    record = claim_fields(claim)
    part = ((record.get("robustness") or {}).get("parts") or {}).get(main_part(record)) or {}
    sentence = lock_sentence(record, part)
    return f" {sentence}" if sentence else ""


def reproduced_where(rule, named: dict) -> list:
    """The names whose measured value the rule judges ``reproduced``: ``named`` maps a name (a condition, or a part
    of an :class:`~tvtrack.verdicts.AllOf` rule when ``rule`` is one) to what the rule (or that part's rule) reads."""
    parts = getattr(rule, "parts", None)
    return [k for k, m in named.items() if (parts[k] if parts else rule).decide(m) == "reproduced"]


def condition_rows(ex, claim_id: str, plain: bool = False) -> list:
    """``(description, measured)`` of the claim pooled at the default, then under each condition of its exploration:
    each condition named by the register entries it changes and their values, as the register's table shows them
    (short, for a figure's axis), or in the register's plain words (``plain``, for prose)."""
    rows = [("default (pooled replicates)", ex.measured(claim_id))]
    for c in ex.record(claim_id)["conditions"]:
        name = (
            ex.register.describe(c["changed"]) if plain else ", ".join(_setting(k, v) for k, v in c["changed"].items())
        )
        rows.append((name, c["measured"]))
    return rows


#: A condition's kind (:class:`tvtrack.explore.Exploration`'s records) in a reader's words, one and several.
_KIND_WORDS = {
    "single": ("register entry changed alone", "register entries changed one at a time"),
    "pinned": ("pinned joint condition", "pinned joint conditions"),
    "joint": ("joint sample of the register", "joint samples of the register"),
    "combination": (
        "combination searched inside a flipping joint sample",
        "combinations searched inside flipping joint samples",
    ),
}


def _counted(counts: Counter) -> str:
    """``"23 register entries changed one at a time, 32 joint samples of the register"``: each kind's count."""
    return ", ".join(f"{n} {_KIND_WORDS.get(k, (k, k))[n != 1]}" for k, n in counts.items())


def drawn_conditions(ex, claim_id: str, rule) -> tuple[list, str]:
    """The rows a figure of one claim over its exploration draws, in the register's plain words: the default
    (pooled replicates), every entry changed alone, every pinned joint condition and every other condition whose
    verdict is decided and differs from the default's (each flip); and, for the caption, a sentence on what is left
    out (``""`` where nothing is): the conditions that agree with the default's verdict and those undecided, each
    counted by kind, with how many of the undecided the sizing budget left smaller than the default needed. A
    condition's verdict is the record's (:meth:`tvtrack.explore.Exploration.record`): one with fewer replicates than
    the default needed is undecided, whatever its own value reads."""
    rule = rule.default if isinstance(rule, ByReading) else rule
    verdict = rule.decide(_measured(ex.measured(claim_id)))
    rows = [("the default (replicates pooled)", ex.measured(claim_id))]
    agree, open_, short = Counter(), Counter(), Counter()
    for c in ex.record(claim_id)["conditions"]:
        v = "undecided" if c.get("undersized") else c.get("verdict")
        if c["kind"] in ("single", "pinned") or v not in (None, "undecided", verdict):
            rows.append((ex.register.describe(c["changed"]), c["measured"]))
        elif v == verdict:
            agree[c["kind"]] += 1
        else:
            open_[c["kind"]] += 1
            short[c["kind"]] += 1 if c.get("left_by_budget") else 0
    said = [f"{_counted(agree)} agreeing with the default's verdict"] if agree else []
    if open_:
        each = [
            f"{_counted(Counter({k: n}))}"
            + (f" ({short[k]} of them left smaller than the default needed by the sizing budget)" if short[k] else "")
            for k, n in open_.items()
        ]
        said.append(f"undecided (neither agreeing nor flipping): {', '.join(each)}")
    return rows, (f"Not drawn: {'; '.join(said)}." if said else "")


def conditions_above(ex, claim_id: str, rule, line: str) -> str:
    """A Markdown list of the conditions under which ``rule`` reads the claim reproduced (in the register's plain
    words), led by how many of how many explored conditions (counted by kind) they are; ``line`` says what
    reproduced means (``"put the ratio's whole 95 % interval above the paper's 20"``)."""
    conditions = ex.record(claim_id)["conditions"]
    named = {ex.register.describe(c["changed"]): c["measured"] for c in conditions}
    over = reproduced_where(rule, named)
    counts = Counter(c["kind"] for c in conditions)
    head = f"Of the {len(conditions)} explored conditions ({_counted(counts)}), {len(over) or 'none'} {line}"
    return head + (":\n\n" + "\n".join(f"- {o}" for o in over) if over else ".")


def pull_in_words(offsets, acq: dict, pull: dict, by_T: float, limit: float = 0.1) -> str:
    """The pull-in range (:func:`.studies.pull_in_range`) on each side, said to the grid's resolution: the farthest
    offset tried from which the share of runs not in lock for good by ``by_T`` stays within ``limit`` (its whole
    95 % interval), with the share there and at the next offset tried beyond it; a side where even the nearest
    offset fails is said so (its edge lies short of that offset); then the shares at the nearest
    offset either side, which show how symmetric the range is."""
    offsets = [float(o) for o in offsets]

    def late(a: dict, o: float) -> str:
        return f"{100 * a['late'][offsets.index(o)].value:.1f} %"

    def side(a: dict, edge, sign: float) -> str:
        beyond = sorted((o for o in offsets if sign * o > sign * (edge or 0.0)), key=abs)
        if edge:
            nxt = f", {late(a, beyond[0])} at {beyond[0]:+g} T" if beyond else ""
            return f"to {edge:+g} T ({late(a, edge)} not in lock there{nxt})"
        if not beyond:
            return "no offset tried"
        return f"short of {beyond[0]:+g} T, the nearest offset tried ({late(a, beyond[0])} not in lock there)"

    grid = ", ".join(f"{o:+g}" if o else "0" for o in offsets)
    said = "; ".join(
        f"variant {v[1]}, negative side {side(acq[v], p['negative'], -1.0)}, positive side "
        f"{side(acq[v], p['positive'], 1.0)}"
        for v, p in pull.items()
    )
    near = [min((o for o in offsets if sign * o > 0), key=abs, default=None) for sign in (-1.0, 1.0)]
    either = (
        f" At the nearest offsets either side of the start, {near[0]:+g} T and {near[1]:+g} T, the runs not in lock "
        f"for good by {by_T:g} T are "
        + "; ".join(f"{late(a, near[0])} and {late(a, near[1])} (variant {v[1]})" for v, a in acq.items())
        + "."
        if None not in near
        else ""
    )
    return (
        f"Pull-in range on the offsets tried ({grid} T: each edge is known only to the grid's spacing), the farthest "
        f"offset from which at most {100 * limit:g} % of the runs, whole 95 % interval, are not in lock for good by "
        f"{by_T:g} T: {said}.{either}"
    )


def _setting(entry: str, value) -> str:
    return f"{entry} = {value:g}" if isinstance(value, float) else f"{entry} = {value}"


def _fmt(measured) -> str:
    e = as_estimate(measured[-1] if isinstance(measured, (list, tuple)) else measured)
    return f"{e.value:.3g} [{e.ci_low:.3g}, {e.ci_high:.3g}]"


def _measured(m):
    """A measurement without its reading's tag (:meth:`tvtrack.verdicts.ByReading.tag`)."""
    return m["measured"] if isinstance(m, dict) and set(m) == {"reading", "measured"} else m


def beside(ex, rules: dict, claim_ids, entry: str, value) -> str:
    """A Markdown table: each part of each claim at the default (pooled replicates) and with ``entry = value``
    (the one-at-a-time condition, first replicate's draws), values with 95 % intervals and each verdict (a list
    part, a trend, shows its last point); the two columns are headed by the register's plain words."""
    words = ex.register[entry]
    lines = [
        f"| claim, part | {words.phrase(words.default)} (default) | verdict | {words.phrase(value)} | verdict |",
        "|---|---|---|---|---|",
    ]
    for cid in claim_ids:
        other = next(
            (
                c["measured"]
                for c in ex.record(cid)["conditions"]
                if c["kind"] == "single" and c["changed"] == {entry: value}
            ),
            None,
        )
        if other is None:
            continue
        rule = rules[cid].default if isinstance(rules[cid], ByReading) else rules[cid]
        parts = getattr(rule, "parts", None) or {"claim": rule}
        here, other = (_measured(m) for m in (ex.measured(cid), other))
        for name, rule in parts.items():
            a, b = (here, other) if name == "claim" else (here[name], other[name])
            lines.append(f"| {cid}, {name} | {_fmt(a)} | {rule.decide(a)} | {_fmt(b)} | {rule.decide(b)} |")
    return "\n".join(lines)
