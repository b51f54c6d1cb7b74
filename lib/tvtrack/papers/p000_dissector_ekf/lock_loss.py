"""Lock loss told apart from accuracy in paper 000's steady-state claims.

A dissector tracker that loses lock (its estimate leaves the image and the micro-raster reads background) errs by a
large fraction of the raster in that run, 25 or more times the mean square of a run in lock. Where a few per cent of
the runs do so, the ensemble mean square over all runs (the paper's sigma_x^2, what the claims' rules read) is
carried by them: C000-6's "exceeds 20 times" under its joint reading and C000-7's and C000-9's flips at
sigma_1 = 0.2 T come from 2-6 % of the runs. A run whose sweep switches on just past its pulse (the truth left of
the centre) can lose lock too, about one run in 100-300 at psi_A = 20, which reaches C000-2's RMS error and the
paired ratios of C000-3 and C000-5. So lock loss is its own quantity here: the share of runs that lost
lock (exact Clopper-Pearson interval), and each claim is scored again over the runs in lock, beside the mean over
all runs, with the verdict each gives.

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

from contextlib import contextmanager

import numpy as np

from ...counts import proportion_ci
from ...labels import part_judgements

__all__ = ["lost", "keep", "keep_pair", "in_lock", "measure_in_lock", "flip_changes", "lock_report", "LOCK_CLAIMS"]

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


def measure_in_lock(measure, config: dict, seed: int, sizes, claim: str) -> dict:
    """One claim measured over all runs and over the runs in lock, on the same draws (``measure``: the study's
    :func:`.study.measure`, passed in so that this module imports no study).

    Returns
    -------
    dict
        ``"all"`` and ``"in lock"``: the claim's measured value (as :func:`.study.measure` gives it) over all runs and
        over the runs in lock; ``"lost"``: the share of runs that lost lock at the operating point where most did
        (Clopper-Pearson), with ``"lost_runs"`` and ``"runs"``, the counts behind it.
    """
    asked = frozenset({claim})
    every = measure(config, seed, sizes, asked)[claim]
    with in_lock(sizes.lock_factor) as counts:
        kept = measure(config, seed, sizes, asked)[claim]
    k, n = max(counts, key=lambda c: (c[0] / c[1], c[1])) if counts else (0, 1)
    return {"all": every, "in lock": kept, "lost": proportion_ci(k, n), "lost_runs": k, "runs": n}


def flip_changes(record: dict, limit: int = 4) -> list[dict]:
    """The changes of the configurations that flip a claim (its record's flips over every part, singles and the
    smallest combinations first, each once), at most ``limit``."""
    out = []
    for part in (record.get("parts") or {}).values():
        for f in part.get("flips") or []:
            changed = dict(f.get("changed") or {})
            if changed and changed not in out:
                out.append(changed)
    return out[:limit]


def _lost_text(m: dict) -> str:
    e = m["lost"]
    return f"{m['lost_runs']} of {m['runs']} runs lost lock ({e.value:.3f} [{e.ci_low:.3f}, {e.ci_high:.3f}])"


def _part_verdicts(rule, measured) -> dict:
    """``{part: verdict}`` of one measurement (a flip is per part: the whole claim's verdict may move by another)."""
    return {name: j.verdict for name, j in part_judgements(rule, measured).items()}


def lock_report(measure, rule, default: dict, conditions: list, seed: int, sizes, claim: str, phrase) -> dict:
    """The claim at the default and under each condition that flips it: the share of runs that lost lock and the
    verdict over all runs and over the runs in lock (same draws: the first replicate's seed).

    Parameters
    ----------
    measure : callable
        The study's :func:`.study.measure`.
    rule : Rule
        The claim's rule.
    default : dict
        The register's default configuration.
    conditions : list of dict
        The changes from the default of the configurations that flip the claim (the exploration's flips).
    phrase : callable
        ``phrase(changed) -> str``, the changes in plain words (:meth:`tvtrack.register.Register.describe`).

    Returns
    -------
    dict
        ``"note"``: one paragraph for the claim's record; ``"metric"``: per configuration (``"default"`` or its
        phrase) the lost share, the counts and both verdicts; ``"rows"``: the same per configuration as
        ``Results.claim(lost_runs=...)`` reads them, with each part's verdicts (:func:`tvtrack.labels.mark_lost_runs`).
    """
    rows = []
    for changed in [{}] + [dict(c) for c in conditions]:
        m = measure_in_lock(measure, {**default, **changed}, seed, sizes, claim)
        rows.append((changed, m, rule.decide(m["all"]), rule.decide(m["in lock"])))
    _, m0, v0, k0 = rows[0]
    same = "the same" if k0 == v0 else k0
    bits = [
        f"Lock loss, its own quantity: in the default's first replicate {_lost_text(m0)} at the operating point "
        f"where most did; that replicate alone reads {v0} over all its runs and {same} over its runs in lock (the "
        "claim's verdict pools every replicate)."
    ]
    for changed, m, v, k in rows[1:]:
        if v == v0 and k != v:  # these draws show no flip over all runs: the lost runs hide it, carry none
            how = (
                f"over the runs in lock it reads {k}: over all runs these draws read as at the default, so the runs "
                "that lost lock carry no flip"
            )
        elif k == v:
            how = f"over the runs in lock it still reads {k}: the flip is not made by the runs that lost lock"
        else:
            how = f"over the runs in lock it reads {k}: the flip is carried by the runs that lost lock"
        bits.append(f"Where it reads {v} ({phrase(changed)}), {_lost_text(m)}; {how}.")
    bits.append(
        "The mean over all runs decides the verdict (the paper's variances are ensemble means, and a run that lost "
        "lock is part of the ensemble)."
    )
    metric = {
        (phrase(c) if c else "default"): {
            "lost_share": m["lost"],
            "lost_runs": m["lost_runs"],
            "runs": m["runs"],
            "verdict_all_runs": v,
            "verdict_in_lock": k,
        }
        for c, m, v, k in rows
    }
    marks = [
        {"changed": c, "lost": m["lost_runs"], "runs": m["runs"], "verdict": v, "in_lock_verdict": k, "replicates": 1}
        | {"parts": _part_verdicts(rule, m["all"]), "in_lock_parts": _part_verdicts(rule, m["in lock"])}
        for c, m, v, k in rows
    ]
    return {"note": " ".join(bits), "metric": metric, "rows": marks}
