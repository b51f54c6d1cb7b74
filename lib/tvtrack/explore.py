"""The explorer: every claim measured over the register and over independent replicates.

A notebook gives a *measurement function* ``measure(config, seed) -> {claim id: measured}`` (one
full-size run of its study at a configuration of the register, every random draw from
``numpy.random.default_rng(seed)``), its :class:`~tvtrack.register.Register` and the claims' rules.
:func:`explore` runs

1. **independent replicates** at the default configuration: full-size runs with distinct seeds spawned
   from the run's seed (never slices of one run), at least three;
2. **one at a time**: every other defensible value of every register entry, at the first replicate's
   seed (common random numbers: a difference between configurations is not a difference of draws);
3. **joint samples**: a space-filling (Latin hypercube) sample of combinations of the entries, where
   interactions that single-axis sweeps miss show up, also at the first replicate's seed;
4. **adaptive replicates** (optional): while a claim's pooled verdict is not settled (its interval
   straddles a bound, or is undecided) more replicates run, up to ``max_replicates``; a clear claim
   stops at the minimum;
5. **condition sizing**: every condition gets replicates on the default's seeds until it decides on at least
   the default's replicates (:mod:`tvtrack.conditions`), and the subsets of every joint flip no single entry
   explains are measured alone (pairs, then triples), so a flip is named by the smallest subset that flips.

A condition's run for a claim sees only the entries the claim declares (its configuration projected on the
claim's ``DEPENDS``), and reads them through a guard that raises on any entry the claims asked for do not
declare (:func:`tvtrack.register.guard`).

The claim's measured value is the replicates pooled (equal weights; on the log scale for positive
quantities); its label comes from :func:`tvtrack.verdicts.label_parts`, part by part.

Work can be batched across configurations (``batched=True``: the measurement function takes lists of
configurations and seeds, so a register value can be one more axis of one vectorised computation) or
sent to an executor with ``submit`` (a :class:`concurrent.futures.Executor` or a
``dask.distributed.Client``, for explorations larger than one machine).
"""

from __future__ import annotations

import itertools
import math
import numbers
from dataclasses import dataclass
from typing import Any, Callable, Mapping, Sequence

import numpy as np
import scipy  # scipy.stats is imported at its first use (scipy loads submodules lazily)

from .declared import check_declared, takes_claims
from .estimate import Estimate
from .jobs import StageClock
from .conditions import SUBSET_ROUND, Run, SizingBudget, point, projected_runs, search_subsets, size_conditions
from .labels import label_parts, part_judgements, part_pairs
from .pooling import pool
from .attribution import MAX_SUBSET
from .register import Register
from .verdicts import Rule, is_decisive

__all__ = [
    "Run",
    "Exploration",
    "explore",
    "check_declared",
    "replicate_seeds",
    "joint_sample",
    "pool",
    "executor_for",
]


#: How the exploration stops adding runs (its record's ``design["stopping"]``).
STOPPING = (
    "replicates added one at a time while a part is undecided and the replicates projected to "
    "decide it fit under max_replicates; every condition (one at a time, joint, pinned, combination) gets "
    "replicates on the default's replicate seeds until each part the default decides is decisive on at least "
    "the replicates the default needed to decide it (the fewest first replicates whose pooled value decides "
    "every part as all of them do), is projected to need more than max_replicates, or reaches it; a condition "
    "smaller than that counts as undecided; a condition leaning towards agreement is sized within the stated "
    "sizing budget of claim runs (one at a time first, then joint, then pinned; a sub-combination leaning "
    "towards agreement not at all), one leaning towards a flip always"
)


def replicate_seeds(seed: int, n: int) -> list[int]:
    """``n`` independent seeds spawned from ``seed`` (:class:`numpy.random.SeedSequence`)."""
    return [int(s.generate_state(1, np.uint64)[0] % (2**63)) for s in np.random.SeedSequence(seed).spawn(n)]


def joint_sample(register: Register, names: Sequence[str], n: int, seed: int) -> list[dict]:
    """``n`` configurations from a scrambled Latin hypercube over the entries ``names``.

    Each dimension is cut into as many equal strata as the entry has values at the paper's operating point: a
    value the register marks ``off_operating_point`` is tried one at a time only (its configurations are counted
    beside a label, never in it: a joint design spent there would leave the labels resting on fewer joints).
    Configurations equal to the default or differing from it in fewer than two entries (those are the one-at-a-time
    runs) are dropped, as are duplicates; so fewer than ``n`` may come back. A register so small that all its joint
    combinations (two or more entries off their defaults) number at most ``n`` gets every one of them.
    """
    values = {k: register[k].operating_values for k in names}
    names = [k for k in names if len(values[k]) > 1]
    if n <= 0 or len(names) < 2:
        return []
    default = register.default()
    full = (
        [
            {**default, **dict(zip(names, combo))}
            for combo in itertools.product(*(values[k] for k in names))
            if sum(v != default[k] for k, v in zip(names, combo)) >= 2
        ]
        if math.prod(len(values[k]) for k in names) <= 4 * n
        else None
    )
    if full is not None and len(full) <= n:  # a small register: every joint combination, not a sample
        return full
    u = scipy.stats.qmc.LatinHypercube(d=len(names), seed=np.random.default_rng(seed)).random(n)
    out, seen = [], set()
    for row in u:
        cfg = dict(default)
        for k, x in zip(names, row):
            vals = values[k]
            cfg[k] = vals[min(int(x * len(vals)), len(vals) - 1)]
        key = tuple(repr(cfg[k]) for k in names)
        if sum(cfg[k] != default[k] for k in names) >= 2 and key not in seen:
            seen.add(key)
            out.append(cfg)
    return out


# --------------------------------------------------------------------------- the exploration


@dataclass
class Exploration:
    """What :func:`explore` measured: every run, and per claim the pooled value and its labels."""

    register: Register
    rules: dict
    depends: dict
    runs: list
    settings: dict

    @property
    def default(self) -> dict:
        return self.register.default()

    def replicates(self) -> list[Run]:
        return [r for r in self.runs if r.stage == "replicate"]

    def measured(self, claim_id: str) -> Any:
        """The claim at the default, pooled over the independent replicates."""
        return pool([r.outputs.get(claim_id) for r in self.replicates()])

    def _relevant(self, claim_id: str, run: Run) -> bool:
        ch = run.changed(self.default)
        return bool(ch) and bool(set(ch) & set(self.depends[claim_id])) and run.counts_for(claim_id)

    def record(self, claim_id: str, rule: Rule | None = None) -> dict:
        """The claim's robustness record (:func:`tvtrack.verdicts.label_parts`) with its register entries."""
        rule = rule or self.rules[claim_id]
        entries = [self.register[k] for k in self.depends[claim_id]]
        reps = [{"seed": r.seed, "measured": r.outputs[claim_id]} for r in self.replicates() if claim_id in r.outputs]
        reads = set(self.depends[claim_id])  # a condition is described by the entries this claim reads
        conds = [
            {
                "changed": {k: v for k, v in r.changed(self.default).items() if k in reads},
                "config": {k: v for k, v in r.config.items() if k in reads},
                "kind": r.stage,
                "measured": r.pooled(claim_id),
                "runs": r.n_runs(claim_id),
                **({"left_by_budget": r.left[claim_id]} if claim_id in r.left else {}),
                **self._operating_point_lost(r),
            }
            for r in self.runs
            if r.stage != "replicate" and self._relevant(claim_id, r)
        ]
        needed = (self.settings.get("replicates_needed") or {}).get(claim_id)
        out = label_parts(rule, self.measured(claim_id), reps, conds, entries, design=self.settings, needed=needed)
        out["register"] = [e.to_dict() for e in entries]
        out["design"] = dict(self.settings)
        return out

    def _operating_point_lost(self, run: Run) -> dict:
        """``{"operating_point_lost": why}`` where the exploration's ``operating_point`` reported the condition (as the
        claims of its projection read it) outside the paper's stated operating point; else ``{}``."""
        return {"operating_point_lost": run.off_point} if run.off_point else {}

    def table(self, claim_id: str) -> str:
        """The claim over its replicates and conditions (each with its replicates and its changes in the register's
        words, joined as the named flips join them: :func:`tvtrack.attribution.phrase`) as a Markdown table (verdict
        per part)."""
        rec = self.record(claim_id)
        parts = list(rec["parts"])
        head = "| run | " + " | ".join(parts) + " |\n|" + " --- |" * (len(parts) + 1)
        rows = [
            f"| replicate {i} | " + " | ".join(r["parts"].get(p, "-") for p in parts) + " |"
            for i, r in enumerate(rec["replicates"], 1)
        ]
        rows += [
            f"| {c['kind']} ({_replicates(c.get('runs', 1))}): "
            + c["text"].replace("|", "/")
            + " | "
            + " | ".join(c["parts"].get(p, "-") for p in parts)
            + " |"
            for c in rec["conditions"]
        ]
        return "\n".join([head, *rows])

    def summary(self) -> str:
        """One Markdown line per claim: label and what it covers."""
        lines = []
        for cid in self.rules:
            rec = self.record(cid)
            lines.append(
                f"- **{cid}**: {rec['coverage']}" + (f"; differs: {'; '.join(rec['where'])}" if rec["where"] else "")
            )
        return "\n".join(lines)


def _replicates(n: int) -> str:
    return f"{n} replicate" + ("" if n == 1 else "s")


def _part_measured(rules: Mapping[str, Rule], outputs: Mapping) -> dict:
    """``{(claim, part): (part rule in force, part measured)}`` of one run's outputs (:func:`labels.part_pairs`)."""
    return {
        (cid, part): pair
        for cid, rule in rules.items()
        if outputs.get(cid) is not None
        for part, pair in part_pairs(rule, outputs[cid]).items()
    }


def _part_verdicts(rules: Mapping[str, Rule], outputs: Mapping) -> dict:
    """``{(claim, part): Judgement}`` of one run's outputs (or of the pooled default)."""
    return {
        (cid, part): j
        for cid, rule in rules.items()
        if outputs.get(cid) is not None
        for part, j in part_judgements(rule, outputs[cid]).items()
    }


def _pooled(rules: Mapping[str, Rule], runs: list[Run]) -> dict:
    reps = [r for r in runs if r.stage == "replicate"]
    return _part_verdicts(rules, {cid: pool([r.outputs.get(cid) for r in reps]) for cid in rules})


def replicates_needed(rules: Mapping[str, Rule], runs: list[Run], default_j: Mapping) -> dict[str, int]:
    """Per claim, the replicates the default's sizing rule needed: the fewest ``k`` first replicates such that the
    pooled value of every prefix of ``k`` or more of them gives every part the default decides its final decisive
    verdict (a zero-loss part certified by 30 runs needs the replicates holding them; a clear part, one). A
    condition counts as flipping or agreeing only at this size or more.

    One replicate is enough only where each replicate alone decides as the default does, and the default's
    replicates agree within their own intervals (no pooled interval of the claim was widened by the agreement test,
    :func:`tvtrack.pooling.pool`): where only the first replicate's draw decides, or a rare event (a run that loses
    lock) moved one replicate beyond what the others' intervals allow, one run's interval says more than the
    default's replicates support. The minimum of three replicates at the default serves the check that independent
    replicates agree (``unstable``), not the decision, so it is not asked of every condition."""
    out = {}
    for cid, rule in rules.items():
        reps = [r.outputs[cid] for r in runs if r.stage == "replicate" and r.outputs.get(cid) is not None]
        decided = {p: j.verdict for (c, p), j in default_j.items() if c == cid and is_decisive(j.verdict)}

        def decides(m: Any, rule: Rule = rule, decided: dict = decided) -> bool:
            js = part_judgements(rule, m)
            return all(p in js and js[p].verdict == v for p, v in decided.items())

        one = all(decides(m) for m in reps) and not (decided and _widened(pool(reps)))
        prefixes = [decides(pool(reps[:j])) for j in range(1, len(reps))]
        out[cid] = next(
            (k for k in range(1 if one else 2, len(reps)) if all(prefixes[k - 1 :])),
            len(reps),
        )
    return out


def _widened(m: Any) -> bool:
    """Whether a pooled value holds an interval the agreement test widened (:func:`tvtrack.pooling.pool`: replicates
    that disagree beyond their own intervals), at any depth (an ``AllOf``'s parts, a ``Monotone``'s points)."""
    if isinstance(m, Estimate) or (isinstance(m, Mapping) and "ci_low" in m and "method" in m):
        return "disagree beyond their own intervals" in str(m.method if isinstance(m, Estimate) else m["method"])
    if isinstance(m, Mapping):
        return any(_widened(v) for v in m.values())
    if isinstance(m, (list, tuple)):
        return any(_widened(v) for v in m)
    return False


def _sizing_target(rules: Mapping[str, Rule], runs: list[Run], n: int, cap: int) -> tuple[int, frozenset] | None:
    """The replicates projected to decide every undecided part that can be decided within ``cap``, and the claims
    with a part still undecided (None: no part projected to decide). Every undecided claim rides along in a sizing
    replicate, not only those projected to decide: a projection from a few replicates is noisy (002's C002-2 was
    projected at 18 runs from 4 and decided at 5), and a claim left out would stay pooled over fewer replicates."""
    targets, claims = [], set()
    for (cid, _part), j in _pooled(rules, runs).items():
        if j.verdict == "undecided":
            claims.add(cid)
            need = max(n + 1, math.ceil(n * j.runs_factor)) if math.isfinite(j.runs_factor) else cap + 1
            if need <= cap:
                targets.append(need)
    return (max(targets), frozenset(claims)) if targets else None


def _to_confirm(rules, depends, default_j: Mapping, run: Run, default_cfg: Mapping) -> frozenset:
    """The claims of a screened run to confirm at full size: those with a part its changes touch, whose default
    verdict is decisive (an undecided default has nothing to flip), screened decisively otherwise, or undecided
    with its point estimate on the other side of the rule (it sits near a band edge and may flip)."""
    changed = set(run.changed(default_cfg))
    out = set()
    for (cid, part), (prule, pm) in _part_measured(rules, run.outputs).items():
        d = default_j.get((cid, part))
        in_scope = run.scope is None or cid in run.scope
        if cid in out or not in_scope or not changed & set(depends[cid]) or d is None or not is_decisive(d.verdict):
            continue
        v = prule.judge(pm).verdict
        if is_decisive(v) and v != d.verdict:
            out.add(cid)
        elif not is_decisive(v):
            try:
                if prule.judge(point(pm)).verdict != d.verdict:
                    out.add(cid)
            except (TypeError, ValueError):
                out.add(cid)
    return frozenset(out)


def _n_joint_combinations(register: Register, names: Sequence[str]) -> int:
    """Configurations with at least two of ``names`` off their defaults, at values that keep the paper's operating
    point (those :func:`joint_sample` draws from)."""
    sizes = [len(register[k].operating_values) for k in names]
    return math.prod(sizes) - 1 - sum(m - 1 for m in sizes)


def explore(
    measure: Callable,
    register: Register,
    rules: Mapping[str, Rule],
    *,
    seed: int,
    replicates: int = 3,
    max_replicates: int | None = None,
    joint: int = 0,
    depends: Mapping[str, Sequence[str]] | None = None,
    batched: bool = False,
    executor: Any = None,
    one_at_a_time: bool = True,
    screen: Callable | None = None,
    screen_singles: bool = False,
    combinations: int | None = None,
    guard: bool = True,
    sizing_budget: int | None = None,
    max_subset: int = MAX_SUBSET,
    operating_point: Callable | None = None,
) -> Exploration:
    """Measure every claim over the register and over independent replicates.

    Stages, in order: ``replicates`` independent full-size runs at the default; **sizing**: while a claim
    part's pooled verdict is undecided and the replicates projected to decide it (the rule's
    ``runs_factor``) fit under ``max_replicates``, one more replicate at a time (a part projected beyond the
    cap stops adding and its record says how many it needs); **one at a time** (every other value of every
    entry); **joint** (a Latin-hypercube design of ``joint`` configurations, measured with ``screen`` when
    given, and every configuration whose verdict is not decisively the default's re-measured at full size);
    **pinned** joint conditions; **condition sizing**: every condition gets replicates on the default's seeds
    until it decides on at least the default's replicates (:func:`tvtrack.conditions.size_conditions`);
    **combinations**: for each joint configuration that flips a part where no single entry does, its pairs of
    changed entries in rounds (those whose entries lean towards the flip alone first) until one flips it or all
    were tried, then its triples likewise, each sized like any condition, so a label names a smallest
    combination that flips (:func:`tvtrack.conditions.search_subsets`). A condition's run for a claim sees only the changes of the entries the claim
    declares (:func:`tvtrack.conditions.projected_runs`), and its first replicate runs on the first replicate's
    seed (common random numbers).

    Parameters
    ----------
    measure : callable
        ``measure(config, seed) -> {claim id: measured}``: one full-size run at ``config`` (a dict with
        every register entry) drawing from ``numpy.random.default_rng(seed)``. With ``batched=True``:
        ``measure(configs, seeds) -> [dict, ...]``. A module-level function (picklable) for executors.
        A measurement with a ``claims`` keyword is asked only for the claims a run needs (a frozenset of
        claim ids, ``None`` for all; batched: one per configuration) and may skip the work of the others:
        a condition asks for the claims that read an entry it changes, a sizing replicate for the claims
        with a part still undecided, a confirmation for the claims that may flip (the others keep their
        screened values). It may return more claims than asked.
    register : Register
    rules : mapping claim id -> Rule
    seed : int
        The run's seed; replicate seeds are spawned from it.
    replicates : int
        Independent full-size runs at the default, at least 3.
    max_replicates : int, optional
        Sizing cap (default ``replicates``: no sizing).
    joint : int
        Latin-hypercube joint configurations of the register (0: none).
    depends : mapping claim id -> entry names, optional
        The entries each claim depends on (default: every entry). A condition counts for a claim only
        if it changes one of its entries.
    batched : bool
        ``measure`` (and ``screen``) take lists (configurations of a stage computed together).
    executor : object with ``submit``, optional
        ``concurrent.futures`` executor or ``dask.distributed.Client``.
    one_at_a_time : bool
        Run every other value of every entry at the default of the others.
    screen : callable, optional
        A cheaper measurement with ``measure``'s signature (e.g. fewer trials) for the joint design.
    screen_singles : bool
        Screen the one-at-a-time stage too (its configurations confirmed at full size likewise).
    combinations : int, optional
        Ignored: the subset search that names a smallest flipping combination tries pairs, then triples, until
        one flips or all were tried, with no run cap (kept so that older callers run).
    max_subset : int
        The largest subset of a joint flip's changed entries the search tries alone, 1 to
        :data:`tvtrack.attribution.MAX_SUBSET` (1: no search; 2: pairs only). A joint flip of more entries that no
        subset up to this size explains is ``unattributed``, its record saying so; the design records the size.
    sizing_budget : int, optional
        The claim runs (one claim at one replicate of a condition) that conditions leaning towards agreement may
        take (None or negative: no limit). A condition leaning
        towards a flip is always sized; one leaning towards agreement beyond the budget stays undecided, marked as
        left by the budget with the replicates that would decide it (:mod:`tvtrack.conditions`).
    operating_point : callable, optional
        ``operating_point(config) -> str or None``: why a configuration (as one claim reads it, every other entry
        at its default) cannot be kept at the operating point the paper states, where no register value says so
        alone (e.g. a joint world that no re-calibration brings back to the paper's error); None where it is kept.
        Such a condition is counted beside the claim's labels, as one at a register value marked
        ``off_operating_point`` is (:func:`tvtrack.verdicts.label_parts`), and explains no other flip in the subset
        search, nor has its own flips searched. Called in this process on each condition as it is made, before it is measured.
    guard : bool
        Hand every condition's run a guarded configuration (:func:`tvtrack.register.guard`): reading an entry that
        none of the claims it is asked for declares raises :class:`tvtrack.register.UndeclaredEntry`. A measurement
        without ``claims`` is asked for every claim, so its guard allows every entry some claim declares.

    Returns
    -------
    Exploration
    """
    if replicates < 3:
        raise ValueError(f"explore: replicates must be at least 3 independent runs, got {replicates}")
    if not _is_subset_size(max_subset):
        raise ValueError(f"explore: max_subset must be an integer in [1, {MAX_SUBSET}], got {max_subset!r}")
    cap = replicates if max_replicates is None else int(max_replicates)
    if cap < replicates:
        raise ValueError(f"explore: max_replicates {cap} < replicates {replicates}")
    rules = dict(rules)
    if not rules:
        raise ValueError("explore: no claims to measure")
    depends = {cid: list(depends.get(cid, register.names)) if depends else list(register.names) for cid in rules}
    for cid, names in depends.items():
        unknown = set(names) - set(register.names)
        if unknown:
            raise KeyError(f"explore: claim {cid} depends on unknown register entries {sorted(unknown)}")
    seeds = replicate_seeds(seed, cap)
    default = register.default()
    clock = StageClock(batched, executor, depends if guard else None)
    used = sorted({k for names in depends.values() for k in names}, key=register.names.index)
    runs = [Run(dict(default), s, "replicate") for s in seeds[:replicates]]
    clock.run(measure, runs, "replicates", guarded=False)
    n = _size(measure, rules, runs, seeds, cap, clock, default)
    default_j = _pooled(rules, runs)
    n_default = replicates_needed(rules, runs, default_j)
    have: dict = {}  # projected configuration -> the claims already measured there

    def conditions(cfgs: Sequence[Mapping], stage: str, only=None) -> list[Run]:
        return _mark_off_point(projected_runs(cfgs, stage, depends, default, seeds[0], have, only), operating_point)

    alternatives = [{**default, k: v} for k in used for v in register[k].alternatives]
    singles = conditions(alternatives, "single") if one_at_a_time else []
    joint_cfgs = joint_sample(register, used, joint, seed + 1) if joint else []
    joints = conditions(joint_cfgs, "joint")
    confirmed = {"runs": 0, "claims": 0}  # runs measured at full size after a screen (an unscreened joint: all)
    for name, jobs, screened in (("one at a time", singles, screen_singles), ("joint", joints, True)):
        stage_screen = screen if screened else None
        done = _measure_stage(measure, stage_screen, jobs, name, rules, depends, runs, default, clock)
        confirmed["runs"] += done[0] if stage_screen is not None or name == "joint" else 0
        confirmed["claims"] += done[1]
        runs += jobs
    pinned = conditions([{**default, **p} for p in register.pinned if set(p) & set(used)], "pinned")
    clock.run(measure, pinned, "pinned")
    runs += pinned
    sizing = (measure, rules)
    conds = [*singles, *joints, *pinned]
    budget = SizingBudget(None if sizing_budget is None or sizing_budget < 0 else int(sizing_budget))
    sized = size_conditions(*sizing, conds, default_j, n_default, seeds, cap, clock.run, budget)
    runs, combos, added = search_subsets(
        measure, rules, depends, default_j, n_default, default, seeds, cap, clock.run, conditions, runs, max_subset
    )
    sized += added
    settings = {
        "replicates": n,
        "min_replicates": replicates,
        "max_replicates": cap,
        "stopping": STOPPING,
        "joint": joint,
        "joint_configurations": len(joint_cfgs),
        "joint_exhaustive": bool(joints) and _n_joint_combinations(register, used) <= joint,
        "screened": screen is not None and bool(joints),
        "screened_singles": screen is not None and screen_singles and bool(singles),
        "confirmed_at_full_size": confirmed["runs"],
        "confirmed_claims": confirmed["claims"],
        "measures_claims_asked": takes_claims(measure),
        "combinations": len(combos),
        "max_subset": int(max_subset),
        "subset_round": SUBSET_ROUND,
        "condition_runs": sized,
        "sizing_budget": sizing_budget,
        "sizing_budget_used": budget.used,
        "left_by_budget": budget.left,
        "replicates_needed": n_default,
        "guarded": bool(guard),
        "one_at_a_time": one_at_a_time,
        "seed": seed,
        "timing": clock.table(),
    }
    return Exploration(register, rules, depends, runs, settings)


def _mark_off_point(runs: list[Run], operating_point: Callable | None) -> list[Run]:
    """Mark each run whose configuration (one claim group's projection) the exploration's ``operating_point`` reports
    outside the paper's stated operating point (``Run.off_point``: its reason). Such a run is measured and sized like
    any condition and counted beside the labels; it explains no other flip in the subset search and starts none
    (:func:`tvtrack.conditions.unexplained_flips`). A register value marked ``off_operating_point`` needs no mark
    here: every configuration that contains it leaves the operating point too, so it explains no flip at it."""
    for r in runs if operating_point is not None else ():
        r.off_point = str(operating_point(dict(r.config)) or "")
    return runs


def _is_subset_size(n: Any) -> bool:
    """Whether ``n`` is a subset size the search takes: an integer (never a bool, a float or a string, which would
    be coerced to another size than the one stated) in 1 to :data:`tvtrack.attribution.MAX_SUBSET`."""
    return isinstance(n, numbers.Integral) and not isinstance(n, bool) and 1 <= n <= MAX_SUBSET


def _size(measure, rules, runs: list[Run], seeds: list[int], cap: int, clock: StageClock, default: dict) -> int:
    """Sizing: one replicate at a time, re-judged after each, while a part is undecided and projected to decide
    under ``cap``; a measurement taking ``claims`` measures only the claims still undecided. Appends to ``runs``;
    returns the replicates run.

    An executor with several workers measures as many replicates at once (up to the projection), and they are
    then taken in order as the one-at-a-time sizing would take them: one after which the sizing would have
    stopped is dropped, and so is one measured for other claims than the sizing then asks (it is measured again
    with those). The replicates kept, and so every result, do not depend on the number of workers."""
    n = len(runs)
    width = max(1, int(getattr(clock.executor, "_max_workers", 1) or 1))
    while n < cap:
        sized = _sizing_target(rules, runs, n, cap)
        if sized is None:
            break
        target, undecided = sized
        step = max(1, min(target - n, width))
        extra = [Run(dict(default), s, "replicate", claims=undecided) for s in seeds[n : n + step]]
        clock.run(measure, extra, "sizing", guarded=False)
        for run in extra:  # the first is what the sizing asks now; each later one, what it asks after those kept
            again = _sizing_target(rules, runs, n, cap)
            if again is None or again[1] != run.claims:
                break
            runs.append(run)
            n += 1
    return n


def _measure_stage(measure, screen, jobs, name, rules, depends, runs, default, clock: StageClock) -> tuple[int, int]:
    """One stage of conditions: at full size, or screened with ``screen`` and the claims that may flip confirmed
    at full size (the others keep their screened values, marked ``screened``: a screened value is no replicate of
    the condition, and the condition's sizing measures it at full size where the default decides the claim).
    Returns (runs confirmed, claims confirmed)."""
    if screen is None or not jobs:
        clock.run(measure, jobs, name)
        return len(jobs), 0
    clock.run(screen, jobs, f"{name}, screened")
    default_j = _pooled(rules, runs)
    redo = []
    for r in jobs:
        r.claims = _to_confirm(rules, depends, default_j, r, default)
        if r.claims:
            redo.append(r)
    clock.run(measure, redo, f"{name}, confirmed at full size")
    everything = not takes_claims(measure)  # a confirmation then re-measures every claim at full size
    for r in jobs:  # the claims whose value is the screen's: they count only once sized at full size
        scope = r.scope if r.scope is not None else frozenset(rules)
        r.screened = frozenset() if r.claims and everything else scope - (r.claims or frozenset())
    return len(redo), sum(len(r.claims) for r in redo)


def executor_for(address: str | None, timeout_s: float = 10.0) -> Any:
    """An executor for :func:`explore`: ``None`` (in process) for an empty address, else a
    ``dask.distributed.Client`` connected to the scheduler at ``address`` (``host:port`` or
    ``tcp://host:port``) within ``timeout_s`` (:func:`tvtrack.executors.connect_dask`).

    Raises
    ------
    ValueError
        One line naming the address: it has no port, nothing listens there, or what listens does not
        answer as a Dask scheduler in time.
    """
    if not address:
        return None
    from .executors import connect_dask

    return connect_dask(address, timeout_s)
