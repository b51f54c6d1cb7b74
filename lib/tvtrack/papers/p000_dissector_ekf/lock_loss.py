"""Lock loss told apart from accuracy in paper 000's steady-state claims.

A dissector tracker that loses lock (its estimate leaves the image and the micro-raster reads background) errs by a
large fraction of the raster in that run, 25 or more times the mean square of a run in lock. Where a few per cent of
the runs do so, the ensemble mean square over all runs (the paper's sigma_x^2, what the claims' rules read) is
carried by them: C000-6's "exceeds 20 times" under its pinned joint condition (a filter ignoring the signal noise,
the background current held fixed) and C000-7's and C000-9's flips at
sigma_1 = 0.2 T come from 2-6 % of the runs. A run whose sweep switches on just past its pulse (the truth left of
the centre) can lose lock too, about one run in 100-300 at psi_A = 20, which reaches C000-2's RMS error and the
paired ratios of C000-3 and C000-5. So lock loss is its own quantity here: the share of runs that lost
lock (exact Clopper-Pearson interval), and each claim is scored again over the runs in lock, beside the mean over
all runs, with the verdict each gives. Both are read on every replicate the claim pools (:func:`lock_draws`): a
single replicate's count hides the runs that the others lost (at psi_A = 20 one run in 100-300 loses lock, so a
replicate of 600 runs may hold none or several).

**Which decides.** The mean over all runs: the paper's variances are ensemble means of the filter's error and a
run that lost lock is part of the ensemble. The note of each claim says whether its verdict, and each condition
that flips it, stays the same over the runs in lock, so a flip that only the lost runs make is said as such.

**Lost lock.** A run's steady mean square above ``lock_factor^2`` times the median run's at the same operating
point and filter (:func:`lost`); a paired ratio drops a run lost by either filter. The median, not the mean, is the
reference: the mean is what the lost runs inflate.

While :func:`in_lock` is active, :mod:`.study`'s paired ratios, C000-2's RMS errors, C000-6's bound ratio and
C000-9's statistics read the runs in lock only (:func:`keep`, :func:`keep_pair`) and count the runs dropped; outside
it they are untouched (the same arrays, bit for bit).
"""

from __future__ import annotations

import numbers
from contextlib import contextmanager

import numpy as np

from ...counts import proportion_ci
from ...explore import replicate_seeds
from ...labels import part_judgements
from ...pooling import pool

__all__ = [
    "lost",
    "keep",
    "keep_pair",
    "in_lock",
    "measure_in_lock",
    "flip_changes",
    "lock_draws",
    "lock_report",
    "LOCK_CLAIMS",
]

#: The claims whose ensemble means lock loss can carry (steady-state variances and their ratios).
LOCK_CLAIMS = ("C000-2", "C000-3", "C000-5", "C000-6", "C000-7", "C000-9")

_ACTIVE: dict | None = None  # {"factor": float, "counts": [(lost, runs), ...]} while in_lock() is active


def lost(steady, factor: float) -> np.ndarray:
    """Runs that lost lock: steady mean square above ``factor**2`` x the median run's (bool, one per run).

    Parameters
    ----------
    steady : array_like, shape (n,)
        Each run's steady-state mean squared error, T^2.
    factor : float
        The RMS factor (the study's ``lock_factor``, 5).
    """
    a = np.asarray(steady, float)
    return a > factor**2 * np.median(a)


def keep(a):
    """``a`` without the runs that lost lock while :func:`in_lock` is active (their count recorded), else ``a``."""
    if _ACTIVE is None:
        return a
    out = lost(a, _ACTIVE["factor"])
    _ACTIVE["counts"].append((int(out.sum()), int(out.size)))
    return a[~out]


def keep_pair(a, b):
    """Paired runs ``a``, ``b`` without those lost by either filter while :func:`in_lock` is active, else as given."""
    if _ACTIVE is None:
        return a, b
    out = lost(a, _ACTIVE["factor"]) | lost(b, _ACTIVE["factor"])
    _ACTIVE["counts"].append((int(out.sum()), int(out.size)))
    return a[~out], b[~out]


@contextmanager
def in_lock(factor: float):
    """Score over the runs in lock; yields the list of (lost, runs) counts, one per array read."""
    global _ACTIVE
    prev, _ACTIVE = _ACTIVE, {"factor": float(factor), "counts": []}
    try:
        yield _ACTIVE["counts"]
    finally:
        _ACTIVE = prev


def _seeds(seeds) -> list[int]:
    """One seed or a sequence of seeds as a non-empty list."""
    out = [int(seeds)] if isinstance(seeds, numbers.Integral) else [int(x) for x in seeds]
    if not out:
        raise ValueError("lock loss: no replicate seed to measure on")
    return out


def _most_lost(counts: list[list[tuple[int, int]]]) -> tuple[int, int]:
    """``(lost, runs)`` at the operating point where most runs lost lock, each point's counts summed over the
    replicates (``counts``: per replicate, one (lost, runs) per array read, in the same order)."""
    if not any(counts):
        return 0, 1
    if len({len(c) for c in counts}) == 1:  # the same arrays read in every replicate: sum them point by point
        points = [(sum(c[i][0] for c in counts), sum(c[i][1] for c in counts)) for i in range(len(counts[0]))]
    else:  # not expected (one configuration reads the same arrays on every seed): each replicate's worst point
        worst = [max(c, key=lambda x: (x[0] / x[1], x[1])) for c in counts if c]
        points = [(sum(k for k, _ in worst), sum(n for _, n in worst))]
    return max(points, key=lambda c: (c[0] / c[1], c[1]))


def measure_in_lock(measure, config: dict, seeds, sizes, claim: str) -> dict:
    """One claim measured over all runs and over the runs in lock, on the same draws: every replicate seed given,
    each measurement pooled over them as the claim's replicates are (:func:`tvtrack.pooling.pool`) (``measure``:
    the study's :func:`.study.measure`, passed in so that this module imports no study).

    Parameters
    ----------
    seeds : int or sequence of int
        The replicates' seeds (one seed: that replicate alone).

    Returns
    -------
    dict
        ``"all"`` and ``"in lock"``: the claim's measured value (as :func:`.study.measure` gives it) over all runs and
        over the runs in lock, pooled over the replicates; ``"lost"``: the share of runs that lost lock at the
        operating point where most did, its counts summed over the replicates (Clopper-Pearson), with
        ``"lost_runs"`` and ``"runs"``, the counts behind it, and ``"replicates"``, how many replicates they cover.
    """
    asked, every, kept, counts = frozenset({claim}), [], [], []
    for seed in _seeds(seeds):
        every.append(measure(config, seed, sizes, asked)[claim])
        with in_lock(sizes.lock_factor) as c:
            kept.append(measure(config, seed, sizes, asked)[claim])
        counts.append(c)
    k, n = _most_lost(counts)
    return {
        "all": pool(every),
        "in lock": pool(kept),
        "lost": proportion_ci(k, n),
        "lost_runs": k,
        "runs": n,
        "replicates": len(every),
    }


def _flips(record: dict) -> list[tuple[dict, int]]:
    """``(changes, replicates)`` of each configuration that flips a claim (every part's flips, each once)."""
    out: list[tuple[dict, int]] = []
    for part in (record.get("parts") or {}).values():
        for f in part.get("flips") or []:
            changed = dict(f.get("changed") or {})
            if changed and changed not in [c for c, _ in out]:
                out.append((changed, max(1, int(f.get("runs") or 1))))
    return out


def flip_changes(record: dict, limit: int = 4) -> list[dict]:
    """The changes of the configurations that flip a claim (its record's flips over every part, singles and the
    smallest combinations first, each once), at most ``limit``."""
    return [c for c, _ in _flips(record)[:limit]]


def lock_draws(record: dict, limit: int = 4) -> tuple[list, list[int]]:
    """The draws a claim's lock report reads, from its robustness record (:meth:`tvtrack.explore.Exploration.record`):
    ``(conditions, seeds)``, the arguments of :func:`lock_report` of those names.

    ``seeds``: every replicate the claim pools at the default (its record's ``replicates``); ``conditions``: each
    configuration that flips it (:func:`flip_changes`, at most ``limit``) as ``(changes, seeds)``, the seeds of that
    condition's own replicates (a condition's replicate ``i`` runs on the default's seed ``i``, :mod:`tvtrack.conditions`,
    and may go past the claim's own replicates up to the exploration's ``max_replicates``)."""
    seeds = [int(r["seed"]) for r in record.get("replicates") or []]
    design = record.get("design") or {}
    spawned = seeds
    if design.get("seed") is not None and design.get("max_replicates"):
        spawned = replicate_seeds(int(design["seed"]), int(design["max_replicates"]))
        if spawned[: len(seeds)] != seeds:  # not the exploration's seeds: read the record's alone
            spawned = seeds
    conditions = [(c, spawned[: max(1, min(runs, len(spawned)))]) for c, runs in _flips(record)[:limit]]
    return conditions, seeds


def _lost_text(m: dict) -> str:
    e = m["lost"]
    return f"{m['lost_runs']} of {m['runs']} runs lost lock ({e.value:.3f} [{e.ci_low:.3f}, {e.ci_high:.3f}])"


def _replicates(n: int, whose: str) -> str:
    """``n`` replicates in words: "its one replicate", "their 4 replicates"."""
    return f"{whose} one replicate" if n == 1 else f"{whose} {n} replicates"


def _part_verdicts(rule, measured) -> dict:
    """``{part: verdict}`` of one measurement (a flip is per part: the whole claim's verdict may move by another)."""
    return {name: j.verdict for name, j in part_judgements(rule, measured).items()}


def _how(v0: str, v: str, k: str) -> str:
    """What the runs that lost lock do to a flipping condition's verdict on the report's draws: ``v0`` the
    default's (over all runs), ``v`` and ``k`` the condition's over all runs and over the runs in lock (the whole
    claim's: a part's flip is marked on its part, :func:`tvtrack.lost_labels.mark_lost_runs`)."""
    if v == "undecided":  # no verdict over all runs: no flip on these draws, for the lost runs to carry or to hide
        if k == v:
            return "over the runs in lock it reads undecided too: on these draws the claim as a whole shows no flip"
        return (
            f"over the runs in lock it reads {k}: over all runs these draws leave the claim as a whole undecided, so "
            "they show no flip of it for the runs that lost lock to carry"
        )
    if v == v0:  # these draws show no flip of the whole claim over all runs
        if k == v:
            return (
                f"over the runs in lock it reads {k} too: the claim as a whole reads as at the default on these draws"
            )
        return (
            f"over the runs in lock it reads {k}: over all runs the claim as a whole reads as at the default on these "
            "draws, so the runs that lost lock carry no flip of it"
        )
    if k == v:
        return f"over the runs in lock it still reads {k}: the flip is not made by the runs that lost lock"
    if k == "undecided":
        return "over the runs in lock it reads undecided: without the runs that lost lock these draws do not decide it"
    return f"over the runs in lock it reads {k}: the flip is carried by the runs that lost lock"


def _part_flips(p0: dict, every: dict, kept: dict) -> str:
    """The parts whose flip on the report's draws the runs that lost lock carry: a part decided at the default that
    reads another decided verdict over all runs and a third over the runs in lock; "" for a claim of one part or
    where none is."""
    if len(every) < 2:
        return ""
    bits = [
        f"part {name} reads {v} over all runs and {kept.get(name)} over the runs in lock"
        for name, v in every.items()
        if "undecided" not in (v, p0.get(name)) and v != p0.get(name) and kept.get(name) != v
    ]
    if not bits:
        return ""
    which = "that flip is" if len(bits) == 1 else "those flips are"
    return f"; of its parts, {'; '.join(bits)}: {which} carried by the runs that lost lock"


def _draws(cond, seeds: list[int]) -> tuple[dict, list[int]]:
    """A condition as ``(changes, seeds)``: a dict of changes runs on the default's ``seeds``."""
    return (dict(cond[0]), _seeds(cond[1])) if isinstance(cond, tuple) else (dict(cond), seeds)


def lock_report(measure, rule, default: dict, conditions: list, seeds, sizes, claim: str, phrase) -> dict:
    """The claim at the default and under each condition that flips it: the share of runs that lost lock and the
    verdict over all runs and over the runs in lock, on the same draws: every replicate given, the counts summed and
    each measurement pooled as the claim's replicates are (:func:`measure_in_lock`).

    Parameters
    ----------
    measure : callable
        The study's :func:`.study.measure`.
    rule : Rule
        The claim's rule.
    default : dict
        The register's default configuration.
    conditions : list
        The configurations that flip the claim (the exploration's flips), each a dict of changes from the default
        (measured on ``seeds``) or ``(changes, seeds)`` with the seeds of its own replicates (:func:`lock_draws`).
    seeds : int or sequence of int
        The seeds of every replicate the claim pools at the default (:func:`lock_draws`).
    phrase : callable
        ``phrase(changed) -> str``, the changes in plain words (:meth:`tvtrack.register.Register.describe`).

    Returns
    -------
    dict
        ``"note"``: one paragraph for the claim's record; ``"metric"``: per configuration (``"default"`` or its
        phrase) the lost share, the counts, the replicates and both verdicts; ``"rows"``: the same per configuration
        as ``Results.claim(lost_runs=...)`` reads them, with each part's verdicts and the replicates the counts
        cover (:func:`tvtrack.lost_labels.mark_lost_runs`).
    """
    base, rows = _seeds(seeds), []
    for changed, at in [({}, _seeds(seeds))] + [_draws(c, base) for c in conditions]:
        m = measure_in_lock(measure, {**default, **changed}, at, sizes, claim)
        rows.append((changed, m, rule.decide(m["all"]), rule.decide(m["in lock"])))
    _, m0, v0, k0 = rows[0]
    same = "the same" if k0 == v0 else k0
    reps = _replicates(m0["replicates"], "the default's")
    bits = [
        f"Lock loss, its own quantity: over {reps} (every one the claim "
        f"pools) {_lost_text(m0)} at the operating point where most did; pooled as the claim is, they read {v0} over "
        f"all runs and {same} over the runs in lock."
    ]
    p0 = _part_verdicts(rule, m0["all"])
    for changed, m, v, k in rows[1:]:
        over = _replicates(m["replicates"], "its")
        parts = _part_flips(p0, _part_verdicts(rule, m["all"]), _part_verdicts(rule, m["in lock"]))
        bits.append(f"Where it reads {v} ({phrase(changed)}), over {over} {_lost_text(m)}; {_how(v0, v, k)}{parts}.")
    bits.append(
        "The mean over all runs decides the verdict (the paper's variances are ensemble means, and a run that lost "
        "lock is part of the ensemble)."
    )
    metric = {
        (phrase(c) if c else "default"): {
            "lost_share": m["lost"],
            "lost_runs": m["lost_runs"],
            "runs": m["runs"],
            "replicates": m["replicates"],
            "verdict_all_runs": v,
            "verdict_in_lock": k,
        }
        for c, m, v, k in rows
    }
    marks = [
        {"changed": c, "lost": m["lost_runs"], "runs": m["runs"], "verdict": v, "in_lock_verdict": k}
        | {"replicates": m["replicates"]}
        | {"parts": _part_verdicts(rule, m["all"]), "in_lock_parts": _part_verdicts(rule, m["in lock"])}
        for c, m, v, k in rows
    ]
    return {"note": " ".join(bits), "metric": metric, "rows": marks}
