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
   stops at the minimum.

The claim's measured value is the replicates pooled (equal weights; on the log scale for positive
quantities); its label comes from :func:`tvtrack.verdicts.label_parts`, part by part.

Work can be batched across configurations (``batched=True``: the measurement function takes lists of
configurations and seeds, so a register value can be one more axis of one vectorised computation) or
sent to an executor with ``submit`` (a :class:`concurrent.futures.Executor` or a
``dask.distributed.Client``, for explorations larger than one machine).
"""

from __future__ import annotations

import inspect
import itertools
import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

import numpy as np
import scipy  # scipy.stats is imported at its first use (scipy loads submodules lazily)

from .montecarlo import Estimate
from .register import Register, UndeclaredEntry, guard
from .labels import label_parts, part_pairs
from .pooling import pool
from .verdicts import Rule, calibrated, is_decisive

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


@dataclass
class Run:
    """One measurement: a configuration, a seed and what it measured."""

    config: dict
    seed: int
    stage: str  # "replicate", "single", "joint" or "pinned" (a joint condition of Register.pinned)
    outputs: dict = field(default_factory=dict)
    claims: frozenset | None = None  # the claims this run measures (None: all), for a measure taking ``claims``

    def changed(self, default: Mapping[str, Any]) -> dict:
        """The entries whose value differs from ``default``."""
        return {k: v for k, v in self.config.items() if default.get(k) != v}


def replicate_seeds(seed: int, n: int) -> list[int]:
    """``n`` independent seeds spawned from ``seed`` (:class:`numpy.random.SeedSequence`)."""
    return [int(s.generate_state(1, np.uint64)[0] % (2**63)) for s in np.random.SeedSequence(seed).spawn(n)]


def joint_sample(register: Register, names: Sequence[str], n: int, seed: int) -> list[dict]:
    """``n`` configurations from a scrambled Latin hypercube over the entries ``names``.

    Each dimension is cut into as many equal strata as the entry has values. Configurations equal to
    the default or differing from it in fewer than two entries (those are the one-at-a-time runs) are
    dropped, as are duplicates; so fewer than ``n`` may come back. A register so small that all its joint
    combinations (two or more entries off their defaults) number at most ``n`` gets every one of them.
    """
    names = [k for k in names if len(register[k].values) > 1]
    if n <= 0 or len(names) < 2:
        return []
    default = register.default()
    full = (
        [
            {**default, **dict(zip(names, combo))}
            for combo in itertools.product(*(register[k].values for k in names))
            if sum(v != default[k] for k, v in zip(names, combo)) >= 2
        ]
        if math.prod(len(register[k].values) for k in names) <= 4 * n
        else None
    )
    if full is not None and len(full) <= n:  # a small register: every joint combination, not a sample
        return full
    u = scipy.stats.qmc.LatinHypercube(d=len(names), seed=np.random.default_rng(seed)).random(n)
    out, seen = [], set()
    for row in u:
        cfg = dict(default)
        for k, x in zip(names, row):
            vals = register[k].values
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
        return bool(ch) and bool(set(ch) & set(self.depends[claim_id])) and claim_id in run.outputs

    def record(self, claim_id: str, rule: Rule | None = None) -> dict:
        """The claim's robustness record (:func:`tvtrack.verdicts.label_parts`) with its register entries."""
        rule = rule or self.rules[claim_id]
        entries = [self.register[k] for k in self.depends[claim_id]]
        reps = [{"seed": r.seed, "measured": r.outputs[claim_id]} for r in self.replicates() if claim_id in r.outputs]
        reads = set(self.depends[claim_id])  # a joint sample is described by the entries this claim reads
        conds = [
            {
                "changed": {k: v for k, v in r.changed(self.default).items() if k in reads},
                "config": {k: v for k, v in r.config.items() if k in reads},
                "kind": r.stage,
                "measured": r.outputs[claim_id],
            }
            for r in self.runs
            if r.stage != "replicate" and self._relevant(claim_id, r)
        ]
        out = label_parts(rule, self.measured(claim_id), reps, conds, entries, design=self.settings)
        out["register"] = [e.to_dict() for e in entries]
        out["design"] = dict(self.settings)
        return out

    def table(self, claim_id: str) -> str:
        """The claim over its replicates and conditions as a Markdown table (verdict per part)."""
        rec = self.record(claim_id)
        parts = list(rec["parts"])
        head = "| run | " + " | ".join(parts) + " |\n|" + " --- |" * (len(parts) + 1)
        rows = [
            f"| replicate (seed {r['seed']}) | " + " | ".join(r["parts"].get(p, "-") for p in parts) + " |"
            for r in rec["replicates"]
        ]
        rows += [
            f"| {c['kind']}: "
            + (", ".join(f"{k} = {v}" for k, v in c["changed"].items())).replace("|", "/")
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


def takes_claims(fn: Callable) -> bool:
    """Whether a measurement function takes a ``claims`` keyword (it can skip the work of claims not asked)."""
    try:
        return "claims" in inspect.signature(fn).parameters
    except (TypeError, ValueError):
        return False


def check_declared(
    measure: Callable,
    register: Register,
    depends: Mapping[str, Sequence[str]],
    seed: int,
    claims: Sequence[str] | None = None,
    **measure_kwargs: Any,
) -> dict[str, str]:
    """Each claim measured alone at the default under :func:`tvtrack.register.guard`: the claims whose measurement
    uses a register entry their ``DEPENDS`` does not declare, each with the one-line message naming the entry.

    A measurement taking ``claims`` is asked for the one claim (``claims=frozenset({claim})``) and may read only
    that claim's entries; one that does not take ``claims`` measures every claim at once, so its guard allows the
    union of every claim's entries (it then catches only an entry that no claim declares).

    Parameters
    ----------
    measure : callable
        ``measure(config, seed, **measure_kwargs)`` (unbatched), as :func:`explore` takes it.
    register : Register
    depends : mapping claim id -> entry names
    seed : int
    claims : sequence of claim ids, optional
        The claims to check (default: every claim of ``depends``).
    **measure_kwargs
        Passed on to ``measure`` (e.g. a smaller size for a quick check).

    Returns
    -------
    dict claim id -> str
        Empty when every claim reads only what it declares.
    """
    default = register.default()
    asks = takes_claims(measure)
    everything = {k for names in depends.values() for k in names}
    out = {}
    for cid in claims if claims is not None else list(depends):
        allowed = set(depends[cid]) if asks else everything
        extra = {"claims": frozenset({cid})} if asks else {}
        try:
            measure(guard(default, allowed), seed, **measure_kwargs, **extra)
        except UndeclaredEntry as e:
            out[cid] = str(e)
    return out


def _execute(measure: Callable, jobs: list[Run], batched: bool, executor: Any) -> None:
    """Run ``jobs`` through ``measure``; a job's outputs are updated with what it measured (a confirmation at
    full size replaces the screened values of the claims it re-measures and keeps the others)."""
    if not jobs:
        return
    kw = takes_claims(measure)
    if batched:
        extra = {"claims": [j.claims for j in jobs]} if kw else {}
        outs = measure([j.config for j in jobs], [j.seed for j in jobs], **extra)
        if len(outs) != len(jobs):
            raise ValueError(f"a batched measurement returned {len(outs)} results for {len(jobs)} configurations")
        for j, o in zip(jobs, outs):
            j.outputs.update(o)
        return
    if executor is None:
        for j in jobs:
            j.outputs.update(measure(dict(j.config), j.seed, **({"claims": j.claims} if kw else {})))
        return
    futures = [executor.submit(measure, dict(j.config), j.seed, **({"claims": j.claims} if kw else {})) for j in jobs]
    try:
        for j, f in zip(jobs, futures):
            j.outputs.update(f.result())
    except BaseException:
        for f in futures:
            f.cancel()
        raise


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
    return {key: prule.judge(pm) for key, (prule, pm) in _part_measured(rules, outputs).items()}


def _point(pm: Any) -> Any:
    """A measured value's point estimate as an exact number (its interval dropped), element by element."""
    if isinstance(pm, (list, tuple)):
        return [_point(x) for x in pm]
    if isinstance(pm, Mapping) and "value" not in pm:
        return {k: _point(v) for k, v in pm.items()}
    try:
        return Estimate.exact(calibrated(pm).value)
    except (TypeError, ValueError):
        return pm


def _pooled(rules: Mapping[str, Rule], runs: list[Run]) -> dict:
    reps = [r for r in runs if r.stage == "replicate"]
    return _part_verdicts(rules, {cid: pool([r.outputs.get(cid) for r in reps]) for cid in rules})


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
        if cid in out or not changed & set(depends[cid]) or d is None or not is_decisive(d.verdict):
            continue
        v = prule.judge(pm).verdict
        if is_decisive(v) and v != d.verdict:
            out.add(cid)
        elif not is_decisive(v):
            try:
                if prule.judge(_point(pm)).verdict != d.verdict:
                    out.add(cid)
            except (TypeError, ValueError):
                out.add(cid)
    return frozenset(out)


def _touched(depends: Mapping[str, Sequence[str]], config: Mapping, default_cfg: Mapping) -> frozenset:
    """The claims that read an entry ``config`` changes (the only ones a condition can say anything about)."""
    changed = {k for k, v in config.items() if default_cfg.get(k) != v}
    return frozenset(cid for cid, names in depends.items() if changed & set(names))


def _flipping_unexplained(rules, depends, default_j, runs: list[Run], default_cfg) -> list[tuple[Run, set]]:
    """Joint or pinned runs that flip some part decisively where no smaller run explains it (a single entry or
    a sub-combination that flips the same part), each with the entries of the flipped claims it changed (only
    those with more than two: a pair is already the smallest combination)."""
    explainers = [r for r in runs if r.stage in ("single", "combination")]
    flips_of = {id(r): _flips(rules, default_j, r) for r in runs if r.stage != "replicate"}
    out = []
    for r in runs:
        if r.stage not in ("joint", "pinned"):
            continue
        ch = set(r.changed(default_cfg).items())
        todo = set()
        for key in flips_of[id(r)]:
            explained = any(key in flips_of[id(s)] and set(s.changed(default_cfg).items()) <= ch for s in explainers)
            if not explained:
                todo |= {k for k, _ in ch if k in depends[key[0]]}
        if len(todo) > 2:
            out.append((r, todo))
    return out


def _flips(rules, default_j, run: Run) -> set:
    return {
        key
        for key, j in _part_verdicts(rules, run.outputs).items()
        if key in default_j
        and is_decisive(j.verdict)
        and is_decisive(default_j[key].verdict)
        and j.verdict != default_j[key].verdict
    }


def _combination_runs(rules, depends, runs, default_cfg, seed0, cap, size) -> list[Run]:
    """Sub-combinations of ``size`` entries of every unexplained flipping joint run (not yet measured)."""
    default_j = _pooled(rules, runs)
    have = {tuple(sorted(r.changed(default_cfg).items(), key=repr)) for r in runs}
    out: list[Run] = []
    for r, names in _flipping_unexplained(rules, depends, default_j, runs, default_cfg):
        if size >= len(names):
            continue
        for combo in itertools.combinations(sorted(names), size):
            cfg = {**default_cfg, **{k: r.config[k] for k in combo}}
            key = tuple(sorted(((k, cfg[k]) for k in combo), key=repr))
            if key not in have and len(out) < cap:
                have.add(key)
                out.append(Run(cfg, seed0, "combination"))
    return out


def _n_joint_combinations(register: Register, names: Sequence[str]) -> int:
    """Configurations with at least two of ``names`` off their defaults."""
    sizes = [len(register[k].values) for k in names]
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
    combinations: int = 24,
) -> Exploration:
    """Measure every claim over the register and over independent replicates.

    Stages, in order: ``replicates`` independent full-size runs at the default; **sizing**: while a claim
    part's pooled verdict is undecided and the replicates projected to decide it (the rule's
    ``runs_factor``) fit under ``max_replicates``, one more replicate at a time (a part projected beyond the
    cap stops adding and its record says how many it needs); **one at a time** (every other value of every
    entry); **joint** (a Latin-hypercube design of ``joint`` configurations, measured with ``screen`` when
    given, and every configuration whose verdict is not decisively the default's re-measured at full size);
    **pinned** joint conditions; **combinations**: for each joint configuration that flips a part where no
    single entry does, its pairs of changed entries, then its triples where no pair flips (at most
    ``combinations`` runs), so a label names the smallest combination that flips. Every non-replicate stage
    runs on the first replicate's seed (common random numbers).

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
    combinations : int
        Cap on the sub-combination runs that name the smallest flipping combination.

    Returns
    -------
    Exploration
    """
    if replicates < 3:
        raise ValueError(f"explore: replicates must be at least 3 independent runs, got {replicates}")
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
    clock = _Clock(batched, executor)
    used = sorted({k for names in depends.values() for k in names}, key=register.names.index)
    runs = [Run(dict(default), s, "replicate") for s in seeds[:replicates]]
    clock.run(measure, runs, "replicates")
    n = _size(measure, rules, runs, seeds, cap, clock, default)

    def conditions(cfgs: Sequence[Mapping], stage: str) -> list[Run]:
        return [Run(dict(c), seeds[0], stage, claims=_touched(depends, c, default)) for c in cfgs]

    singles = conditions([{**default, k: v} for k in used for v in register[k].alternatives], "single")
    singles = singles if one_at_a_time else []
    joints = conditions(joint_sample(register, used, joint, seed + 1) if joint else [], "joint")
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
    n_combo = 0
    for size in (2, 3):
        combos = _combination_runs(rules, depends, runs, default, seeds[0], combinations - n_combo, size)
        for r in combos:
            r.claims = _touched(depends, r.config, default)
        clock.run(measure, combos, "combinations")
        runs += combos
        n_combo += len(combos)
    settings = {
        "replicates": n,
        "min_replicates": replicates,
        "max_replicates": cap,
        "stopping": "replicates added one at a time while a part is undecided and the replicates projected to "
        "decide it fit under max_replicates",
        "joint": joint,
        "joint_configurations": len(joints),
        "joint_exhaustive": bool(joints) and _n_joint_combinations(register, used) <= joint,
        "screened": screen is not None and bool(joints),
        "screened_singles": screen is not None and screen_singles and bool(singles),
        "confirmed_at_full_size": confirmed["runs"],
        "confirmed_claims": confirmed["claims"],
        "measures_claims_asked": takes_claims(measure),
        "combinations": n_combo,
        "one_at_a_time": one_at_a_time,
        "seed": seed,
        "timing": clock.table(),
    }
    return Exploration(register, rules, depends, runs, settings)


def cpu_seconds() -> float:
    """CPU seconds of this process and of its live child processes (an executor's workers, which the process's
    own clock does not see). A child that ends between two readings takes its seconds with it: the stages
    read it around a pool that lives through the exploration."""
    import psutil

    total = time.process_time()
    for child in psutil.Process().children(recursive=True):
        try:
            t = child.cpu_times()
        except psutil.Error:  # ended meanwhile
            continue
        total += t.user + t.system
    return total


class _Clock:
    """Runs the stages' jobs and keeps where the exploration's time goes: per stage its configurations, wall
    seconds and CPU seconds (:func:`cpu_seconds`: this process and an executor's workers)."""

    def __init__(self, batched: bool, executor: Any):
        self.batched, self.executor = batched, executor
        self.rows: dict[str, list] = {}

    def run(self, fn: Callable, jobs: list[Run], stage: str) -> None:
        t0, c0 = time.perf_counter(), cpu_seconds()
        _execute(fn, jobs, self.batched, self.executor)
        row = self.rows.setdefault(stage, [0, 0.0, 0.0])
        row[0] += len(jobs)
        row[1] += time.perf_counter() - t0
        row[2] += max(0.0, cpu_seconds() - c0)

    def table(self) -> dict:
        return {
            k: {"configurations": n, "wall_s": round(w, 3), "cpu_s": round(c, 3)}
            for k, (n, w, c) in self.rows.items()
            if n
        }


def _size(measure, rules, runs: list[Run], seeds: list[int], cap: int, clock: _Clock, default: dict) -> int:
    """Sizing: one replicate at a time (as many at once as an executor has workers), re-judged after each, while
    a part is undecided and projected to decide under ``cap``; a measurement taking ``claims`` measures only the
    claims still undecided. Appends to ``runs``; returns the replicates run."""
    n = len(runs)
    while n < cap:
        sized = _sizing_target(rules, runs, n, cap)
        if sized is None:
            break
        target, undecided = sized
        step = max(1, min(target - n, int(getattr(clock.executor, "_max_workers", 1) or 1)))
        extra = [Run(dict(default), s, "replicate", claims=undecided) for s in seeds[n : n + step]]
        clock.run(measure, extra, "sizing")
        runs += extra
        n += step
    return n


def _measure_stage(measure, screen, jobs, name, rules, depends, runs, default, clock: _Clock) -> tuple[int, int]:
    """One stage of conditions: at full size, or screened with ``screen`` and the claims that may flip confirmed
    at full size (the others keep their screened values). Returns (runs confirmed, claims confirmed)."""
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
