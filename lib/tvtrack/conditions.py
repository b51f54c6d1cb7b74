"""The explorer's conditions: projected to each claim's entries, sized like the default, searched for the smallest
flipping subset (:mod:`tvtrack.explore`).

- **Projection**: a condition's run for claim ``c`` sees only the changes of the entries ``c`` declares
  (``DEPENDS``): the claims a configuration touches are grouped by their projected configuration
  (:func:`tvtrack.register.project`) and one run is made per distinct projected configuration, asking only its
  group's claims. No claim is measured in a world its ``DEPENDS`` does not declare, and a condition's record for a
  claim is described by its projected changes. A claim is asked at most once per projected configuration and seed:
  a projection it already has (a subset of one joint equal to another's, to a one-at-a-time condition or to an
  earlier round's) is not run again, and a condition's further replicates start at the seed after the last it has.
  A projection that another claim shares may still be run again for that claim alone (its claims differ).
- **Sizing** (:func:`size_conditions`): a condition whose part is undecided, or decided on fewer replicates than
  the default needed to decide (:func:`tvtrack.explore.replicates_needed`), gets replicates on the default's replicate seeds (common random numbers: the
  condition's replicate ``i`` runs on the default's seed ``i``), asking only the claims concerned, until each of its
  parts is decisive on at least that many replicates, or is projected to need more than the cap, or reaches
  the cap. Its replicates pool as the default's do.
- **Sizing budget**: a condition whose part leans towards a flip (decisive the other way, or undecided with its
  point estimate on the other side of the rule) is always sized; one that leans towards agreement is sized while
  the exploration's stated budget of claim runs lasts (one claim measured at one replicate of a condition) (the one-at-a-time conditions first, then the joint
  design in its order, then the pinned ones); one left smaller than the default needed stays ``undecided``, its
  record marking it ``left by the sizing budget`` with the replicates that would decide it. A sub-combination
  (searched for a flip only) that leans towards agreement is never sized: it flips nothing at its size.
- **Subsets** (:func:`search_subsets`): a joint flip that no single entry (or smaller subset) explains has its
  pairs measured alone (sized like any condition) in rounds of :data:`SUBSET_ROUND`, those whose entries lean
  towards the flip alone first, until a pair flips it or every pair was tried; then its triples likewise (up to
  the exploration's stated ``max_subset``: 2 stops at pairs, and the flips they leave read ``unattributed``). The
  flip is named by the first subset found: a smallest one (no single entry, and for a triple no pair, flips it),
  not necessarily the only one.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

from .labels import part_judgements
from .pooling import pool
from .register import project
from .estimate import Estimate
from .verdicts import ByReading, Rule, is_decisive
from .measured import calibrated

__all__ = [
    "Run",
    "SizingBudget",
    "projected_runs",
    "condition_verdicts",
    "leans_flip",
    "point",
    "size_conditions",
    "unexplained_flips",
    "subset_configs",
    "lean_of_singles",
    "search_subsets",
    "SUBSET_ROUND",
]


@dataclass
class Run:
    """One measurement: a configuration, a seed and what it measured. A condition's run also carries the claims
    it counts for (``scope``) and its further replicates on the default's seeds (``sized``)."""

    config: dict
    seed: int
    stage: str  # "replicate", "single", "joint", "pinned", "combination" or "condition sizing"
    outputs: dict = field(default_factory=dict)
    claims: frozenset | None = None  # the claims this run is asked for (None: all), for a measure taking ``claims``
    scope: frozenset | None = None  # the claims this condition counts for (None: all): its projection's group
    sized: list = field(default_factory=list)  # the condition's further replicates (Run, stage "condition sizing")
    screened: frozenset = frozenset()  # claims whose value here is a screen's (smaller) measurement, no replicate
    left: dict = field(default_factory=dict)  # claim -> replicates it needed, where the sizing budget left it smaller
    off_point: str = ""  # why the exploration reports it outside the paper's stated operating point ("": it is not)

    def changed(self, default: Mapping[str, Any]) -> dict:
        """The entries whose value differs from ``default``."""
        return {k: v for k, v in self.config.items() if default.get(k) != v}

    def counts_for(self, cid: str) -> bool:
        """Whether this run says something about claim ``cid`` (in its scope and measured)."""
        return (self.scope is None or cid in self.scope) and cid in self.outputs

    def replicates(self, cid: str) -> list:
        """Claim ``cid`` over the condition's full-size replicates: this run's (unless screened), then each further
        one that asked for it."""
        if not self.counts_for(cid):
            return []
        more = [r.outputs[cid] for r in self.sized if cid in r.outputs and (r.claims is None or cid in r.claims)]
        return more if cid in self.screened else [self.outputs[cid], *more]

    def pooled(self, cid: str) -> Any:
        """Claim ``cid`` pooled over the condition's replicates (as the default's replicates pool); a claim with
        only a screened value has that value."""
        reps = self.replicates(cid)
        return pool(reps) if reps else self.outputs.get(cid) if self.counts_for(cid) else None

    def n_runs(self, cid: str) -> int:
        """The condition's full-size replicates behind claim ``cid`` (0 for a screened value alone)."""
        return len(self.replicates(cid))


def _key(config: Mapping) -> tuple:
    return tuple(sorted((k, repr(v)) for k, v in config.items()))


def projected_runs(
    cfgs: Sequence[Mapping],
    stage: str,
    depends: Mapping[str, Sequence[str]],
    default: Mapping,
    seed: int,
    have: dict,
    only: Sequence[frozenset | None] | None = None,
) -> list[Run]:
    """One run per distinct projected configuration of ``cfgs`` (see the module), each asking its group's claims.

    Parameters
    ----------
    have : dict projected-configuration key -> set of claims
        The conditions already measured for each claim; a claim is not measured again at a projected configuration
        it already has. Updated in place.
    only : sequence of frozenset or None, optional
        Per configuration, the claims it is run for (None: every claim it touches).
    """
    out: dict[tuple, Run] = {}
    for i, cfg in enumerate(cfgs):
        changed = {k for k, v in cfg.items() if default.get(k) != v}
        for cid, names in depends.items():
            if not changed & set(names) or (only is not None and only[i] is not None and cid not in only[i]):
                continue
            proj = project(cfg, names, default)
            key = _key(proj)
            if cid in have.setdefault(key, set()):
                continue
            have[key].add(cid)
            r = out.setdefault(key, Run(proj, seed, stage, claims=frozenset(), scope=frozenset()))
            r.scope = r.claims = r.scope | {cid}
    return list(out.values())


def condition_verdicts(rules: Mapping[str, Rule], run: Run, n_default: Mapping[str, int]) -> dict:
    """``{(claim, part): verdict}`` of a condition pooled over its replicates; ``undecided`` where it has fewer
    replicates than the default needed (``n_default``: a condition smaller than that neither flips nor agrees)."""
    out = {}
    for cid, rule in rules.items():
        if not run.counts_for(cid):
            continue
        k = run.n_runs(cid)
        for part, j in part_judgements(rule, run.pooled(cid)).items():
            out[(cid, part)] = j.verdict if k >= n_default.get(cid, 0) else "undecided"
    return out


def _target(rule: Rule, run: Run, cid: str, default_j: Mapping, nd: int, cap: int) -> int:
    """The replicates claim ``cid`` of a condition should reach next: the default's ``nd`` while it has fewer, one
    more while a part the default decides is undecided and projected to decide within ``cap``, else what it has."""
    k = run.n_runs(cid)
    judged = {p: j for p, j in part_judgements(rule, run.pooled(cid)).items() if (cid, p) in default_j}
    relevant = [j for p, j in judged.items() if is_decisive(default_j[(cid, p)].verdict)]
    if not relevant or k >= cap:
        return k
    if k < nd:
        return min(nd, cap)
    for j in relevant:
        if (
            not is_decisive(j.verdict)
            and math.isfinite(j.runs_factor)
            and max(k + 1, math.ceil(k * j.runs_factor)) <= cap
        ):
            return k + 1
    return k


def point(pm: Any) -> Any:
    """A measured value's point estimate as an exact number (its interval dropped), element by element."""
    if isinstance(pm, (list, tuple)):
        return [point(x) for x in pm]
    if isinstance(pm, Mapping) and "value" not in pm:
        return {k: point(v) for k, v in pm.items()}
    try:
        return Estimate.exact(calibrated(pm).value)
    except (TypeError, ValueError):
        return pm


def _at_point(rule: Rule, pm: Any) -> Any:
    """A claim's measured value with each part's value at its point (:func:`point`), a reading's tag kept as it is
    (a reading may be a number). Asked only of a value with parts, so a :class:`ByReading` value is tagged."""
    if isinstance(rule, ByReading):
        return {**pm, "measured": _at_point(rule.for_value(pm["reading"]), pm["measured"])}
    return point(pm)


def leans_flip(rule: Rule, run: Run, cid: str, default_j: Mapping) -> bool:
    """Whether a part of claim ``cid`` that the default decides leans towards a flip at ``run``'s present size: its
    pooled verdict is decisive the other way, or undecided with the point estimate on the other side of the rule (a
    value that cannot be judged as a point counts as leaning). A part is judged as a condition's verdict judges it
    (:func:`tvtrack.labels.part_judgements`): with the parts a reading's rule has beyond the default reading's, which
    must hold too, so a condition that flips a part through one of them leans towards that flip."""
    pm = run.pooled(cid)
    for part, j in part_judgements(rule, pm).items():
        d = default_j.get((cid, part))
        if d is None or not is_decisive(d.verdict):
            continue
        if is_decisive(j.verdict):
            if j.verdict != d.verdict:
                return True
            continue
        try:  # the same parts at their points (point keeps every part's place)
            if part_judgements(rule, _at_point(rule, pm))[part].verdict != d.verdict:
                return True
        except (TypeError, ValueError):
            return True
    return False


@dataclass
class SizingBudget:
    """The claim runs (a claim at one replicate of a condition) that conditions leaning towards agreement may take (``runs``; None: no limit), and what
    the sizing spent and left (see the module)."""

    runs: int | None = None
    used: int = 0
    left: int = 0  # (condition, claim) pairs left smaller than the default needed

    def grant(self, n: int) -> bool:
        """Take ``n`` runs from the budget if it holds them."""
        if self.runs is not None and self.used + n > self.runs:
            return False
        self.used += n
        return True


def size_conditions(
    measure: Callable,
    rules: Mapping[str, Rule],
    conds: Sequence[Run],
    default_j: Mapping,
    n_default: Mapping[str, int],
    seeds: Sequence[int],
    cap: int,
    run_stage: Callable,
    budget: SizingBudget | None = None,
) -> int:
    """Add replicates to ``conds`` (see the module) in rounds, each round's runs measured together through
    ``run_stage(measure, jobs, "condition sizing")``. A claim of a condition that leans towards agreement
    (:func:`leans_flip` false) takes its runs from ``budget`` (in the order of ``conds``); refused, it stays at its
    size, its ``left`` entry holding the replicates it needed. Returns the runs added."""
    budget = budget if budget is not None else SizingBudget()
    added = 0
    while True:
        jobs = []
        for r in conds:
            want = {}
            for cid in sorted(r.scope if r.scope is not None else rules):
                if cid not in rules or not r.counts_for(cid) or cid in r.left:
                    continue
                k = r.n_runs(cid)
                t = _target(rules[cid], r, cid, default_j, n_default.get(cid, 0), cap)
                if t <= k:
                    continue
                if leans_flip(rules[cid], r, cid, default_j) or budget.grant(t - k):
                    want[cid] = (k, t)
                else:
                    r.left[cid] = t
                    budget.left += 1
            for i in sorted({i for lo, hi in want.values() for i in range(lo, hi)}):
                asked = frozenset(c for c, (lo, hi) in want.items() if lo <= i < hi)
                job = Run(dict(r.config), seeds[i], "condition sizing", claims=asked, scope=asked)
                r.sized.append(job)
                jobs.append(job)
        if not jobs:
            return added
        run_stage(measure, jobs, "condition sizing")
        added += len(jobs)


def _flips(rules, default_j, run: Run, n_default) -> set:
    return {
        key
        for key, v in condition_verdicts(rules, run, n_default).items()
        if key in default_j and is_decisive(v) and is_decisive(default_j[key].verdict) and v != default_j[key].verdict
    }


def _changed_items(run: Run, default: Mapping, cache: dict | None) -> frozenset:
    """``run``'s changed ``(entry, value)`` pairs (kept in ``cache``: a run's configuration never changes)."""
    if cache is None:
        return frozenset(run.changed(default).items())
    hit = cache.get(("changed", id(run)))
    if hit is None or hit[0] is not run:
        hit = cache[("changed", id(run))] = (run, frozenset(run.changed(default).items()))
    return hit[1]


def _flips_kept(rules, default_j, run: Run, n_default, cache: dict | None) -> set:
    """:func:`_flips` of ``run``, kept in ``cache`` while the run is as it was (its outputs, its further replicates
    and their outputs, its screened claims): a run's verdicts change only when one of those does."""
    if cache is None:
        return _flips(rules, default_j, run, n_default)
    state = (len(run.outputs), run.scope, run.screened, tuple((id(s), len(s.outputs)) for s in run.sized))
    hit = cache.get(("flips", id(run)))
    if hit is None or hit[0] is not run or hit[1] != state:
        hit = cache[("flips", id(run))] = (run, state, _flips(rules, default_j, run, n_default))
    return hit[2]


def unexplained_flips(rules, depends, default_j, runs: Sequence[Run], default: Mapping, n_default, cache=None) -> list:
    """Joint or pinned runs at the paper's operating point that flip some part decisively where no smaller run
    explains it (a single entry or a subset that flips the same part, at the operating point), each with the flipped
    claims and the entries of theirs it changed (only those with more than two: a pair is already the smallest
    combination). A run with ``off_point`` explains no flip and is not searched: its flips are counted beside the
    labels, where no flip is named by a subset (:func:`tvtrack.attribution.beside_operating_point`).

    ``cache`` (a dict kept by the caller across calls on the same growing ``runs``, optional) keeps each run's
    changed entries and its flips while the run is unchanged, so a search that asks again after each round
    recomputes only the runs that round measured or sized; the answer is the same with or without it."""
    conds = [r for r in runs if r.stage != "replicate"]  # a smaller flipping joint explains a larger one too
    flips_of = {id(r): _flips_kept(rules, default_j, r, n_default, cache) for r in conds}
    flipping: dict = {}  # (claim, part) -> the changed entries of every condition that flips it
    for r in conds:
        if r.off_point:  # a flip outside the paper's operating point is counted beside the label: it explains none
            continue
        for key in flips_of[id(r)]:
            flipping.setdefault(key, []).append(_changed_items(r, default, cache))
    out = []
    for r in runs:
        if r.stage not in ("joint", "pinned") or r.off_point:  # counted beside the labels: no flip there is named
            continue
        ch = _changed_items(r, default, cache)
        todo, claims = set(), set()
        for key in flips_of[id(r)]:
            if not any(s < ch for s in flipping.get(key, ())):
                todo |= {k for k, _ in ch if k in depends[key[0]]}
                claims.add(key[0])
        if len(todo) > 2:
            out.append((r, todo, frozenset(claims)))
    return out


#: Subsets of one unexplained flip measured per round of the search (:func:`search_subsets`).
SUBSET_ROUND = 4


def lean_of_singles(rules: Mapping[str, Rule], runs: Sequence[Run], default: Mapping, default_j: Mapping) -> dict:
    """``{(claim, entry, repr(value)): True}`` for each one-at-a-time condition that leans towards a flip of the
    claim (:func:`leans_flip`) at its final size: the order in which :func:`subset_configs` tries subsets."""
    out = {}
    for r in runs:
        ch = r.changed(default) if r.stage == "single" else {}
        if len(ch) != 1:
            continue
        ((k, v),) = ch.items()
        for cid in rules:
            if r.counts_for(cid) and leans_flip(rules[cid], r, cid, default_j):
                out[(cid, k, repr(v))] = True
    return out


def subset_configs(
    unexplained: Sequence[tuple],
    default: Mapping,
    size: int,
    tried: dict | None = None,
    lean: Mapping | None = None,
    per_flip: int | None = None,
) -> tuple[list[dict], list[frozenset]]:
    """The next subsets of ``size`` changed entries of each unexplained flip, as configurations, each with the
    claims it is run for (those the joint configuration flipped).

    Subsets are ordered by how many of their entries lean towards flipping one of those claims alone (``lean``,
    :func:`lean_of_singles`; most first), then by name; those in ``tried`` (``{id(joint run): set of subsets}``,
    updated) are skipped; at most ``per_flip`` per flip (None: all)."""
    tried = {} if tried is None else tried
    lean = lean or {}
    cfgs, only = [], []
    for r, names, claims in unexplained:
        if size >= len(names):
            continue
        done = tried.setdefault(id(r), set())
        combos = [c for c in itertools.combinations(sorted(names), size) if c not in done]
        combos.sort(key=lambda c: -sum(bool(lean.get((cid, k, repr(r.config[k])))) for k in c for cid in claims))
        for combo in combos[:per_flip]:
            done.add(combo)
            cfgs.append({**default, **{k: r.config[k] for k in combo}})
            only.append(claims)
    return cfgs, only


def search_subsets(
    measure, rules, depends, default_j, n_default, default, seeds, cap, run_stage, conditions, runs, max_subset=None
):
    """Name each unexplained joint flip by a smallest subset that flips it alone (see the module).

    Rounds: every still-unexplained flip has its next :data:`SUBSET_ROUND` untried pairs (most leaning first)
    measured together, then sized (:func:`size_conditions`, no budget for agreement); a flip that a sized pair
    flips is explained and leaves the search. A flip whose every pair was tried without one flipping goes on to
    triples likewise. ``conditions(cfgs, stage, only)`` makes the projected runs. Returns ``(runs, combinations,
    sizing runs added)``. ``max_subset`` (default :data:`tvtrack.attribution.MAX_SUBSET`) is the largest subset
    tried: 2 stops at pairs, 1 searches nothing."""
    from .attribution import MAX_SUBSET

    lean = lean_of_singles(rules, runs, default, default_j)
    tried: dict = {}
    kept: dict = {}  # each run's changed entries and flips while unchanged (:func:`unexplained_flips`)
    combos: list[Run] = []
    sized = 0
    for size in range(2, (MAX_SUBSET if max_subset is None else int(max_subset)) + 1):
        while True:
            pending = unexplained_flips(rules, depends, default_j, runs, default, n_default, kept)
            cfgs, only = subset_configs(pending, default, size, tried, lean, SUBSET_ROUND)
            if not cfgs:
                break
            found = conditions(cfgs, "combination", only)
            run_stage(measure, found, "combinations")
            sized += size_conditions(
                measure, rules, found, default_j, n_default, seeds, cap, run_stage, SizingBudget(0)
            )
            runs, combos = runs + found, combos + found
    return runs, combos, sized
