"""Robustness labels of a claim: how its verdict holds over the replicates and the register.

:func:`label_parts` gives each part of a claim's rule (each part of an :class:`~tvtrack.verdicts.AllOf`;
the whole rule otherwise) a label that noise cannot make (docs/verdicts.md):

- ``unstable``: independent replicates at the default disagree **decisively** (one reproduced, another
  not reproduced); a replicate too small to decide (``undecided``) never makes a part unstable;
- ``depends``: a configuration that changes **readings of the paper's text** (kinds reading, statistic,
  comparator) or **unreported settings of its own experiment** (kind unreported setting), or a combination that no
  searched subset isolates (``unattributed``: those mixed with worlds, or more entries than the search reaches),
  reaches a decisive verdict other than the default's decisive verdict: the claim depends on what the paper left
  open;
- ``limited``: the verdict holds under every explored reading and setting, and only isolated **worlds beyond the
  paper** (regime, model, operating point, scale) flip it: the claim does not extend there;
- ``unexplored``: no entry of the world was varied, the design is too small to estimate a share
  (``provisional``; e.g. the smoke profile), or fewer explored configurations decided the part than a share
  needs (:data:`MIN_SHARE_DESIGN`, or every combination where there are fewer; the others undecided: nothing
  showed that it holds there);
- ``robust``: none of the above, over a design large enough for a share, and as many of its configurations decided.

A condition flips a part only when its verdict, pooled over at least the replicates the default needed to decide,
is decisive and differs from the default's pooled decisive verdict: an interval that straddles (``undecided``), or
a condition smaller than that, is never a flip. A part whose default verdict is undecided has nothing to flip (label
``-``) and carries the runs projected to decide it.

Each part also carries the **share** (agree, flip and undecided over every explored configuration), the
**flips** named by the smallest subset that flips alone, each with its side, and a **sensitivity** ranking of the
entries from the one-at-a-time design (:mod:`tvtrack.attribution`); a value over runs some of which lost lock
(:func:`tvtrack.measured.with_lost_runs`) adds the share lost and the verdict on the runs in lock.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

from .attribution import (
    MAX_SUBSET,
    SENSITIVITY_METHOD,
    attribute,
    beside_operating_point,
    paired_rows,
    phrase,
    sensitivity,
    share,
)
from .lost_labels import lost_fields
from .reach import reached, world_reached
from .run_words import part_name
from .register import WORLD_KINDS, leaves_operating_point
from .verdicts import (
    LABELS,
    NOT_MEASURED,
    AllOf,
    ByReading,
    InBand,
    Judgement,
    NotCheckable,
    Rule,
    as_estimate,
    is_decisive,
)

__all__ = [
    "MIN_SHARE_DESIGN",
    "NO_PART_LABEL",
    "rule_parts",
    "part_pairs",
    "part_judgements",
    "weakest_label",
    "label_parts",
    "share",
    "attribute",
    "sensitivity",
    "Condition",
    "Robustness",
]

#: Distinct explored configurations a claim needs for its share to be estimated to about +-14 points (95 %);
#: fewer (and not every combination of its entries) makes the label provisional: never ``robust``. A part is
#: ``robust`` only where as many of them decided it (fewer decided: ``unexplored``).
MIN_SHARE_DESIGN = 32

#: Beyond this multiple of the runs, a projection says only that no practical run decides the part.
PRACTICAL_FACTOR = 1000.0

NO_PART_LABEL = "-"
"""The label of a part with nothing to flip: a :class:`NotCheckable` part, or a part whose default is undecided."""


def rule_parts(rule: Rule) -> dict[str, Rule]:
    """The parts a label is given for: each part of an :class:`AllOf`, else the whole rule as ``"claim"``; a
    :class:`ByReading` rule has its default reading's parts (every reading names the same parts)."""
    if isinstance(rule, ByReading):
        return rule_parts(rule.default)
    if isinstance(rule, AllOf):
        return dict(rule.parts)
    return {"claim": rule}


def part_pairs(rule: Rule, measured: Any) -> dict[str, tuple[Rule, Any]]:
    """``{part: (the part's rule in force, the part's measured value)}`` of one measurement: a
    :class:`ByReading` measurement is split by the rule of the reading it was made under."""
    if isinstance(rule, ByReading):
        if not (isinstance(measured, Mapping) and "reading" in measured and "measured" in measured):
            return {}
        return part_pairs(rule.for_value(measured["reading"]), measured["measured"])
    if isinstance(rule, AllOf):
        if not isinstance(measured, Mapping):
            return {}
        return {n: (r, measured[n]) for n, r in rule.parts.items() if n in measured and measured[n] is not None}
    return {} if measured is None else {"claim": (rule, measured)}


def _fold(js: Sequence[Judgement]) -> Judgement:
    """Parts that must all hold, as one: not reproduced when one is, reproduced when all are, else undecided."""
    if any(j.verdict == "not reproduced" for j in js):
        return next(j for j in js if j.verdict == "not reproduced")
    if all(j.verdict == "reproduced" for j in js):
        return js[0]
    open_ = [j for j in js if j.verdict != "reproduced"]
    return Judgement("undecided", "; ".join(j.why for j in open_), False, max(j.runs_factor for j in open_))


def part_judgements(rule: Rule, measured: Any) -> dict[str, Judgement]:
    """``{part: Judgement}`` of one measurement over the parts a label is given for (:func:`rule_parts`).

    A :class:`ByReading` measurement is judged by its reading's own rule; where that rule has parts the default's
    rule lacks (a reading that says "at every P > 0.5"), those parts must hold too: each labelled part's verdict
    under the reading is the reading's part and its extra parts held together (not reproduced when one of them
    is), so a reading's failing extra part flips the claim."""
    js = {n: r.judge(m) for n, (r, m) in part_pairs(rule, measured).items()}
    names = rule_parts(rule)
    extra = [j for n, j in js.items() if n not in names]
    if not extra:
        return js
    out = {}
    for n in names:
        if n in js or len(names) == 1:
            out[n] = _fold([js[n], *extra] if n in js else extra)
    return out


def weakest_label(labels: Sequence[str]) -> str:
    """The weakest of ``labels`` in the order of :data:`tvtrack.verdicts.LABELS`."""
    return min(labels, key=LABELS.index) if labels else "unexplored"


def _scalar(m: Any) -> float:
    """One number for a part's measured value: an estimate's value, a curve's end-to-end change."""
    if m is None:
        return math.nan
    if isinstance(m, Mapping) and set(m) == {"reading", "measured"}:  # a part's ByReading tag: its value
        return _scalar(m["measured"])
    if isinstance(m, (list, tuple)):
        if len(m) < 2:
            return math.nan
        return _scalar(m[-1]) - _scalar(m[0])
    try:
        return float(as_estimate(m).value)
    except (TypeError, ValueError):
        return math.nan


def _runs_text(j: Judgement, n_reps: int, n_runs: int, cap: int | None) -> dict:
    f = j.runs_factor
    if math.isfinite(f) and f > PRACTICAL_FACTOR:
        return {
            "replicates": None,
            "now": n_reps,
            "factor": f,
            "text": f"undecided at {n_reps} replicates: the estimate sits so close to the band edge that only over "
            f"{PRACTICAL_FACTOR:g} times the runs are projected to decide it",
        }
    if not math.isfinite(f):
        return {
            "replicates": None,
            "now": n_reps,
            "factor": None,
            "text": f"undecided at {n_reps} replicates; no number of runs is projected to decide it",
        }
    reps = max(n_reps + 1, math.ceil(n_reps * f))
    runs = math.ceil(n_runs * f) if n_runs > n_reps else None
    what = f"about {reps} independent replicates" + (f" ({runs} runs)" if runs else "")
    beyond = f", beyond the cap of {cap}" if cap is not None and reps > cap else ""
    return {
        "replicates": reps,
        "now": n_reps,
        "factor": f,
        "runs": runs,
        "text": f"undecided at {n_reps} replicates: {what} are projected to decide it{beyond}",
    }


def _replicate_text(rv: Sequence[str]) -> str:
    counts = ", ".join(f"{v} in {rv.count(v)}" for v in dict.fromkeys(rv))
    return f"independent replicates disagree: {counts} of {len(rv)}"


def _n_combinations(names: Sequence[str], entries: Mapping[str, Any]) -> int:
    """Configurations of ``names`` other than the default, at values that keep the paper's operating point."""
    return math.prod(len(entries[k].operating_values) for k in names if k in entries) - 1


def label_parts(
    rule: Rule,
    measured: Any,
    replicates: Sequence[Mapping],
    conditions: Sequence[Mapping],
    entries: Sequence[Any] = (),
    deterministic: bool = False,
    design: Mapping | None = None,
    needed: int | None = None,
) -> dict:
    """Part-level robustness labels of one claim (see the module).

    Parameters
    ----------
    rule : Rule
        The claim's rule; labels are given per :func:`rule_parts`.
    measured : Any
        The claim at the default, pooled over the replicates: decides the default's verdict.
    replicates : sequence of {"seed", "measured"}
        Independent full-size runs at the default.
    conditions : sequence of {"changed": {entry: value}, "kind", "measured", "config" (optional), "runs" (optional)}
        The claim under other configurations: ``single`` (one entry), ``joint`` (the Latin-hypercube design),
        ``pinned`` (known flips measured every run) and ``combination`` (subsets of a flipping joint
        configuration, run to name the smallest that flips), each pooled over its ``runs`` replicates on the
        default's replicate seeds (common random numbers). A condition with fewer ``runs`` than ``needed``
        counts as ``undecided`` (it can neither flip nor agree); one without ``runs`` (a hand-built record) counts
        as sized like the default. A condition at a register value marked ``off_operating_point``, or with an
        ``operating_point_lost`` reason (the exploration's ``operating_point``), is counted beside the label.
    entries : sequence of :class:`tvtrack.register.Entry`
        The register entries the claim depends on.
    deterministic : bool
        No random draw is involved (replicates cannot differ).
    design : mapping, optional
        The explorer's settings (``max_replicates`` is the sizing cap; ``max_subset`` the largest subset searched,
        default :data:`tvtrack.attribution.MAX_SUBSET`; ``min_share_design`` overrides :data:`MIN_SHARE_DESIGN`).
    needed : int, optional
        The replicates the default needed to decide (:func:`tvtrack.explore.replicates_needed`): the size below
        which a condition counts as undecided; default all of ``replicates``.

    Returns
    -------
    dict
        ``label`` (weakest part), ``provisional``, ``where`` (plain lines), ``coverage``, ``parts`` {name:
        {verdict, label, where, replicate_verdicts, n_conditions, share, flips, sensitivity, sensitivity_method,
        runs_to_decide, and for a value with runs that lost lock lost_share, in_lock_verdict,
        decided_by_lost_runs}}, ``replicates`` and ``conditions`` with their part verdicts.
    """
    design = dict(design or {})
    parts = rule_parts(rule)
    by_name = {e.name: e for e in entries}
    default_cfg = {e.name: e.default for e in entries}
    rep_rows = [_row(rule, parts, r["measured"], {"seed": int(r["seed"])}) for r in replicates]
    size = needed if needed is not None else len(rep_rows)
    cond_rows = _condition_rows(rule, parts, conditions, by_name, default_cfg, max(size, 1))
    kept = [c for c in cond_rows if not c.get("off_operating_point")]  # the others are counted beside the label
    world_varied = any(by_name[k].kind in WORLD_KINDS for c in kept for k in c["changed"] if k in by_name)
    explored = _distinct([c for c in kept if c["kind"] in ("single", "joint")])
    # the configurations the paper's operating point admits: its values' combinations, less those the exploration
    # could not keep there (only those made of such values: one at a marked value was never among them)
    lost = _distinct(
        [
            c
            for c in cond_rows
            if c["kind"] in ("single", "joint")
            and c.get("operating_point_lost")
            and not leaves_operating_point(c["changed"], {k: e.off_operating_point for k, e in by_name.items()})
        ]
    )
    reachable = _n_combinations(list(by_name), by_name) - len(lost)
    need = min(int(design.get("min_share_design", MIN_SHARE_DESIGN)), reachable)
    provisional = not deterministic and len(explored) < max(need, 1)
    context = {
        "rep_rows": rep_rows,
        "cond_rows": cond_rows,
        "explored": explored,
        "by_name": by_name,
        "default_cfg": default_cfg,
        "open_world": world_varied and not provisional,
        "worlds": {k for k, e in by_name.items() if e.kind in WORLD_KINDS},
        "n_reps": len(rep_rows),
        "pooled_n": _runs_behind(measured),
        "max_replicates": design.get("max_replicates"),
        "max_subset": int(design.get("max_subset", MAX_SUBSET)),
        "unranked": _rule_selectors(rule),
        "need_decided": max(need, 1),  # no random draw spares a design its configurations
        "reachable": reachable,
    }
    part_out, where = {}, []
    pairs = part_pairs(rule, measured)
    for name, prule in parts.items():
        part_out[name] = _label_part(name, prule, pairs.get(name), context)
        prefix = "" if len(parts) == 1 else f"({part_name(name)}) "
        where += [prefix + w for w in part_out[name]["where"]]
    labels = [p["label"] for p in part_out.values() if p["label"] != NO_PART_LABEL]
    label = weakest_label(labels) if labels else NO_PART_LABEL  # no decided part: nothing to label
    for r in (*rep_rows, *cond_rows):
        r.pop("part_measured", None)
    return {
        "label": label,
        "provisional": provisional,
        "where": where,
        "coverage": _coverage(label, part_out, cond_rows, rep_rows, entries, deterministic, len(explored), provisional),
        "parts": part_out,
        "replicates": rep_rows,
        "conditions": cond_rows,
        "deterministic": deterministic,
    }


def _condition_rows(rule, parts: Mapping[str, Rule], conditions, by_name: Mapping, default_cfg: dict, n: int) -> list:
    """One row per condition: its changes in words, its full configuration, its runs and its verdicts
    (:func:`_row`); a condition with fewer runs than the ``n`` replicates the default needed reads ``undecided`` per part,
    its own verdicts kept as ``undersized``."""
    rows, off = [], {k: e.off_operating_point for k, e in by_name.items()}
    for c in conditions:
        extra = {
            "changed": dict(c["changed"]),
            "kind": c.get("kind", "single"),
            "text": phrase(c["changed"], by_name),
            "config": {**default_cfg, **dict(c.get("config", c["changed"]))},
        }
        if c.get("runs") is not None:
            extra["runs"] = int(c["runs"])
        if c.get("left_by_budget") is not None:  # leaning towards agreement, left smaller by the sizing budget
            extra["left_by_budget"] = int(c["left_by_budget"])
        if c.get("operating_point_lost"):  # the exploration says why no register value alone does
            extra["operating_point_lost"] = str(c["operating_point_lost"])
        if leaves_operating_point(c["changed"], off) or c.get("operating_point_lost"):
            extra["off_operating_point"] = True
        row = _row(rule, parts, c["measured"], extra)
        if row.get("runs", n) < n:
            row["undersized"] = dict(row["parts"])
            row["parts"] = {p: "undecided" for p in row["parts"]}
        rows.append(row)
    return rows


def _label_part(name: str, prule: Rule, pair: tuple | None, ctx: Mapping) -> dict:
    """One part's record: its pooled verdict (``pair``: (rule, measured) at the default, None when the part was
    not measured), label, where-lines, replicate verdicts, share, flips, sensitivity and runs to decide;
    ``ctx`` holds the claim's rows and design (:func:`label_parts`)."""
    j = pair[0].judge(pair[1]) if pair else NOT_MEASURED
    rv = [r["parts"][name] for r in ctx["rep_rows"] if name in r["parts"]]
    # a configuration that leaves the paper's stated operating point is counted beside the label, never in it
    every = [{**c, "verdict": c["parts"][name]} for c in ctx["cond_rows"] if name in c["parts"]]
    rows = [c for c in every if not c.get("off_operating_point")]
    flips = attribute(j.verdict, rows, ctx["by_name"], rv[0] if rv else None, ctx["max_subset"])
    ex_rows = [{**c, "verdict": c["parts"][name]} for c in ctx["explored"] if name in c["parts"]]  # at the point
    unranked = ctx["unranked"] | _rule_selectors(prule)  # their values measure other quantities: not one scale
    reps = [_scalar(r["part_measured"].get(name)) for r in ctx["rep_rows"] if name in r["parts"]]
    singles = [c for c in ex_rows if c["kind"] == "single" and not set(c["changed"]) & unranked]
    sens_rows = paired_rows(singles, [_scalar(c["part_measured"].get(name)) for c in singles], reps)
    if pair:
        sens_rows.append({"config": ctx["default_cfg"], "value": _scalar(pair[1])})
    pwhere: list[str] = []
    runs = None
    if isinstance(prule, NotCheckable):
        label = NO_PART_LABEL
    elif len({v for v in rv if v in ("reproduced", "not reproduced")}) > 1:
        label = "unstable"
        pwhere.append(_replicate_text(rv))
    elif not is_decisive(j.verdict):
        label = NO_PART_LABEL
        runs = _runs_text(j, ctx["n_reps"], ctx["pooled_n"], ctx["max_replicates"])
        pwhere.append(runs["text"])
    else:  # a world must have reached the part itself, not only another part of the claim (:mod:`tvtrack.reach`)
        label = _decided_label(flips, ctx["open_world"] and world_reached(rows, name, ctx["rep_rows"], ctx["worlds"]))
    pinned = _distinct([r for r in rows if r["kind"] == "pinned"])
    combos = _distinct([r for r in rows if r["kind"] == "combination"])
    part_share = _share(ex_rows, j.verdict, pinned, combos) if label != NO_PART_LABEL else None
    if part_share is not None:  # agreeing configurations that left the part's value as the default's, bit for bit
        live = reached(ex_rows, name, ctx["rep_rows"])
        part_share["unchanged"] = sum(1 for c in ex_rows if c["verdict"] == j.verdict) - sum(
            1 for c in live if c["verdict"] == j.verdict
        )
    ps, same = part_share or {}, int((part_share or {}).get("unchanged") or 0)  # same: never reached the part
    decided = int(ps.get("agree") or 0) + int(ps.get("flip") or 0) - same  # as many as a share, of those reachable
    if label == "robust" and decided < (need := min(ctx["need_decided"], max(ctx["reachable"] - same, 1))):
        label, ps["decided_needed"] = "unexplored", need  # fewer than a share needs: most of the design is open
    pwhere += [f"{f['verdict']} when {f['text']}{_open_subsets(f)}" for f in flips]
    off = beside_operating_point(every, j.verdict) if is_decisive(j.verdict) else None
    if off and part_share:  # counted beside the share, as the pinned ones are
        part_share["off_operating_point"] = {k: off[k] for k in ("agree", "flip", "undecided")}
    pwhere += [
        f"{f['verdict']} when {f['text']} (outside the paper's operating point{': ' + f['why'] if f.get('why') else ''})"
        for f in (off or {}).get("flips", ())
    ]
    return {
        "verdict": j.verdict,
        "label": label,
        "where": pwhere,
        "replicate_verdicts": rv,
        "n_conditions": len(rows),
        "share": part_share,
        "flips": flips,
        "sensitivity": []
        if isinstance(prule, NotCheckable)
        else sensitivity(  # no verdict to move: no ranking
            sens_rows,
            [k for k in ctx["by_name"] if k not in unranked],
            ctx["by_name"],
            ctx["default_cfg"],
            floor=_moving_floor(prule, pair[1] if pair else None),
        ),
        "sensitivity_method": SENSITIVITY_METHOD,
        "runs_to_decide": runs,
        **({"off_operating_point": off} if off else {}),
        **(lost_fields(pair[0], pair[1], j.verdict) if pair else {}),
    }


def _moving_floor(rule: Rule, measured: Any) -> float:
    """The least change of a part's value that the ranking counts as a move: a hundredth of the default's distance
    to its band's nearest edge (a band rule; 0 for others), so that round-off far inside a band ranks nothing."""
    value = _scalar(measured)
    edges = [e for e in (getattr(rule, "low", None), getattr(rule, "high", None)) if e is not None]
    if not isinstance(rule, InBand) or not edges or not math.isfinite(value):
        return 0.0
    return 0.01 * min(abs(value - float(e)) for e in edges)


def _rule_selectors(rule: Rule) -> frozenset:
    """The entries whose values choose another rule (:class:`tvtrack.verdicts.ByReading` with a rule of its own
    for some value): under those values the claim measures another quantity, so the sensitivity does not rank
    them on the default's scale (their flips say what they do)."""
    if isinstance(rule, ByReading) and any(r != rule.default for r in rule.rules.values()):
        return frozenset({rule.entry})
    return frozenset()


def _share(
    rows: Sequence[Mapping], default: str, pinned: Sequence[Mapping] = (), combinations: Sequence[Mapping] = ()
) -> dict | None:
    """The part's share (:func:`tvtrack.attribution.share`) with ``left_by_budget``: the undecided configurations
    that lean towards agreement and were left smaller than the default needed by the exploration's sizing budget.

    The share is over the design (one at a time and joint). The register's pinned configurations, known flips
    measured every run, are chosen for flipping, so they stay out of it and are counted beside it (``pinned``:
    agree, flip and undecided), so that a flip they name is never shown beside a share without one; so are the
    combinations the subset search measured inside flipping joint configurations (``combinations``)."""
    out = share([c["verdict"] for c in rows], default)
    if out is not None:
        out["left_by_budget"] = sum(1 for c in rows if c["verdict"] == "undecided" and c.get("left_by_budget"))
        for key, rows_beside in (("pinned", pinned), ("combinations", combinations)):
            if rows_beside:
                beside = share([c["verdict"] for c in rows_beside], default)
                out[key] = {k: beside[k] for k in ("agree", "flip", "undecided")}
    return out


def _open_subsets(flip: Mapping) -> str:
    """`` (the smallest found: ... stays undecided)`` for a flip with undecided smaller subsets; else empty."""
    open_ = flip.get("undecided_subsets") or ()
    return (
        f" (the smallest found: {'; '.join(open_)} {'stays' if len(open_) == 1 else 'stay'} undecided)" if open_ else ""
    )


def _decided_label(flips: Sequence[Mapping], open_world: bool) -> str:
    """The label of a part decided at the default with replicates that agree: ``depends`` when a reading of the
    paper, an unreported setting of its experiment, or a flip no subset attributes flips it; ``limited`` when only
    isolated worlds beyond it do; else ``robust`` where the explored design was large enough and varied the world
    (``open_world``), ``unexplored`` where not."""
    if any(f["side"] in ("reading", "setting", "unattributed") for f in flips):
        return "depends"
    if flips:
        return "limited"
    return "robust" if open_world else "unexplored"


def _row(rule: Rule, parts: Mapping[str, Rule], measured: Any, extra: dict) -> dict:
    pairs = {n: pr for n, pr in part_pairs(rule, measured).items() if n in parts}
    return {
        **extra,
        "measured": measured,
        "verdict": rule.decide(measured),
        "parts": {n: j.verdict for n, j in part_judgements(rule, measured).items() if n in parts},
        "part_measured": {n: m for n, (_, m) in pairs.items()},
    }


def _distinct(rows: Sequence[dict]) -> list[dict]:
    out, seen = [], set()
    for r in rows:
        key = tuple(sorted((k, repr(v)) for k, v in r["changed"].items()))
        if r["changed"] and key not in seen:
            seen.add(key)
            out.append(r)
    return out


def _runs_behind(measured: Any) -> int:
    """The runs behind a pooled measured value (its ``n``; the largest over parts)."""
    if isinstance(measured, Mapping) and "value" not in measured:
        return max((_runs_behind(v) for v in measured.values()), default=0)
    if isinstance(measured, (list, tuple)):
        return max((_runs_behind(v) for v in measured), default=0)
    try:
        return int(as_estimate(measured).n)
    except (TypeError, ValueError):
        return 0


def _coverage(label, parts, conds, reps, entries, deterministic, n_explored, provisional) -> str:
    """The record's coverage line: the label over the configurations at the paper's operating point, by stage, and
    how many were outside it (counted beside the label)."""
    off = [c for c in conds if c.get("off_operating_point")]
    conds = [c for c in conds if not c.get("off_operating_point")]
    single = [c for c in conds if c["kind"] == "single"]
    joint = [c for c in conds if c["kind"] == "joint"]
    pinned = [c for c in conds if c["kind"] == "pinned"]
    combos = [c for c in conds if c["kind"] == "combination"]
    reps_text = "deterministic (no random draw)" if deterministic else f"{len(reps)} independent replicates"
    weak = [n for n, p in parts.items() if p["label"] == label]
    which = "" if len(parts) == 1 or not weak else f" (weakest part{'s' if len(weak) > 1 else ''}: {', '.join(weak)})"
    extra = [f"{len(pinned)} pinned known flip{'s' * (len(pinned) != 1)}"] if pinned else []
    extra += [f"{len(combos)} sub-combinations of flipping joint configurations"] if combos else []
    extra += [f"{len(off)} outside the paper's operating point, counted beside the label"] if off else []
    small = f"; provisional: {n_explored} distinct configurations are too few for a share" if provisional else ""
    if label == NO_PART_LABEL:  # not checkable at the default: no verdict there for a condition to flip
        nothing = {p.get("verdict") for p in parts.values()} == {"not checkable"}
        why = "not checkable at the default: no verdict to flip" if nothing else ""
        label, which = f"no label ({why or 'no part decided at the default: nothing to flip'})", ""
    return (
        f"{label}{which} over {n_explored} distinct configurations ({len(single)} one at a time over "
        f"{len(entries)} register entries, {len(joint)} joint samples"
        + (", " + ", ".join(extra) if extra else "")
        + f"); x {reps_text}{small}"
    )


# --------------------------------------------------------------------------- hand-built records


@dataclass(frozen=True)
class Condition:
    """The claim measured under one reading: ``choices`` maps entry names to values."""

    choices: Mapping[str, Any]
    measured: Any


@dataclass
class Robustness:
    """A hand-built robustness record (prefer :func:`tvtrack.explore.explore`).

    Parameters
    ----------
    choices : list of Entry
        The register entries the claim depends on (empty only with a ``note`` saying why none matters).
    conditions : list of Condition
        The claim measured under readings other than the default.
    seeds : mapping seed -> measured
        The claim at the default reading under at least three independent full-size runs.
    note : str
        Required when ``choices`` is empty or when ``deterministic``.
    deterministic : bool
        The measurement involves no random draw (``note`` says why).
    """

    choices: list = field(default_factory=list)
    conditions: list = field(default_factory=list)
    seeds: Mapping[int, Any] = field(default_factory=dict)
    note: str = ""
    deterministic: bool = False

    def validate(self) -> None:
        if not self.choices and not self.note:
            raise ValueError("a robustness record without unstated choices needs a note saying why none matters")
        if self.deterministic and not self.note:
            raise ValueError("a deterministic robustness record needs a note saying why the seed cannot matter")
        if not self.deterministic and len(self.seeds) < 3:
            raise ValueError(f"a robustness record needs the claim under at least 3 seeds, got {len(self.seeds)}")
        names = {c.name for c in self.choices}
        for cond in self.conditions:
            unknown = set(cond.choices) - names
            if unknown:
                raise ValueError(f"condition {dict(cond.choices)} names unknown choices {sorted(unknown)}")
            for k, v in cond.choices.items():
                allowed = list(next(c for c in self.choices if c.name == k).values)
                if v not in allowed:
                    raise ValueError(f"condition {dict(cond.choices)}: {k} = {v!r} is not among {allowed}")

    def record(self, rule: Rule, measured: Any) -> dict:
        """The JSON record: :func:`label_parts` over the conditions and seeds, with the entries."""
        self.validate()
        reps = [{"seed": s, "measured": m} for s, m in self.seeds.items()]
        conds = [
            {"changed": dict(c.choices), "kind": "single" if len(c.choices) == 1 else "joint", "measured": c.measured}
            for c in self.conditions
        ]
        out = label_parts(rule, measured, reps, conds, self.choices, self.deterministic)
        out.update({"register": [c.to_dict() for c in self.choices], "note": self.note, "built": "by hand"})
        return out
