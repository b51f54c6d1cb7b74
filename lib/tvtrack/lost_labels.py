"""The runs that lost lock, in a claim's labels: the share lost at the default and which flips those runs carry.

:func:`lost_fields` adds to a part's record, for a value over runs some of which lost lock
(:func:`tvtrack.measured.with_lost_runs`), the share lost and the verdict on the runs in lock;
:func:`mark_lost_runs` marks a claim's record with a paper's own count of those runs (:mod:`tvtrack.labels`).
"""

from __future__ import annotations

from typing import Any, Mapping, Sequence

from .measured import lost_runs
from .verdicts import Rule

__all__ = ["lost_fields", "mark_lost_runs"]


def lost_fields(prule: Rule, pm: Any, verdict: str) -> dict:
    """For a value with runs that lost lock (:func:`tvtrack.measured.with_lost_runs`): the share lost (exact
    Clopper-Pearson), the verdict on the runs in lock, and whether the two verdicts differ."""
    info = lost_runs(pm)
    if info is None:
        return {}
    from .counts import proportion_ci

    e = proportion_ci(info["lost"], info["runs"])
    in_lock = prule.judge(info["in lock"]).verdict
    return {
        "lost_share": {
            "lost": info["lost"],
            "runs": info["runs"],
            "value": e.value,
            "ci_low": e.ci_low,
            "ci_high": e.ci_high,
        },
        "in_lock_verdict": in_lock,
        "decided_by_lost_runs": in_lock != verdict,
    }


def _carried(row: Mapping, name: str, flip: Mapping, n_parts: int) -> bool:
    """Whether the runs that lost lock carry a flip of part ``name``: on the row's draws the part reads the flip's
    verdict over every run and another over the runs in lock. The part's own verdicts (``parts``,
    ``in_lock_parts``) where the row gives them; the whole claim's only for a claim of one part (another part's
    verdict may move the whole claim's)."""
    every, kept = (row.get("parts") or {}).get(name), (row.get("in_lock_parts") or {}).get(name)
    if every is None or kept is None:
        if n_parts != 1:
            return False
        every, kept = row["verdict"], row["in_lock_verdict"]
    return every == flip.get("verdict") and kept != every


def _part_verdicts(row: Mapping, name: str) -> dict:
    """Part ``name``'s own verdicts over every run and over the runs in lock, where the row gives them (a flip of
    one part is said with its part's, not the whole claim's); ``{}`` where it gives the whole claim's only."""
    every, kept = (row.get("parts") or {}).get(name), (row.get("in_lock_parts") or {}).get(name)
    return {"verdict": every, "in_lock_verdict": kept} if every is not None and kept is not None else {}


def mark_lost_runs(record: dict, rows: Sequence[Mapping], verdict: str) -> dict:
    """Mark a claim's record with a paper's own count of the runs that lost lock, at the default and under
    named flips: where the rows' draws read the verdict over every run and another over the runs in lock, those
    runs carry it, and the claim's sentence says so (:func:`tvtrack.wording.claim_summary`).

    Parameters
    ----------
    record : dict
        The claim's robustness record (:meth:`tvtrack.explore.Exploration.record`); marked in place.
    rows : sequence of dict
        ``{"changed": {entry: value} ({} for the default), "lost": int, "runs": int, "verdict": str (over every
        run), "in_lock_verdict": str (over the runs in lock)}``, on the same draws (one replicate's), optionally
        ``"replicates"`` (how many of the claim's replicates those draws are: the sentence then says the count is
        of that many, not of the pooled verdict's); for a claim
        of several parts also ``"parts"`` and ``"in_lock_parts"``: ``{part: verdict}`` over every run and over the
        runs in lock.
    verdict : str
        The claim's verdict at the default (every replicate pooled).

    Returns
    -------
    dict
        ``record``: at the default ``lost_share``, ``in_lock_verdict`` (on the row's draws) and
        ``decided_by_lost_runs`` (those draws give ``verdict`` over every run and another over the runs in lock);
        each flip of a part whose changes a row names gains ``lost_runs`` ({lost, runs, verdict, in_lock_verdict,
        carried}; the verdicts the part's own where the row gives them): ``carried`` where the part reads the flip's verdict over every run of the row and another over
        its runs in lock (never from the whole claim's verdicts for a claim of several parts).
    """
    parts = record.get("parts") or {}
    for row in rows:
        lost, runs = int(row["lost"]), int(row["runs"])
        if runs < 1 or not 0 <= lost <= runs:
            raise ValueError(f"mark_lost_runs: lost {lost} of runs {runs}: need 0 <= lost <= runs and runs >= 1")
        info = {"lost": lost, "runs": runs, "verdict": row["verdict"], "in_lock_verdict": row["in_lock_verdict"]}
        info |= {"replicates": int(row["replicates"])} if row.get("replicates") else {}
        if not row.get("changed"):
            from .counts import proportion_ci

            e = proportion_ci(lost, runs)
            record["lost_share"] = {
                "lost": lost,
                "runs": runs,
                "value": e.value,
                "ci_low": e.ci_low,
                "ci_high": e.ci_high,
            } | ({"replicates": info["replicates"]} if "replicates" in info else {})
            record["in_lock_verdict"] = row["in_lock_verdict"]
            record["decided_by_lost_runs"] = row["verdict"] == verdict and row["in_lock_verdict"] != verdict
            continue
        for name, part in parts.items():
            for f in part.get("flips") or ():
                if dict(f.get("changed") or {}) == dict(row["changed"]):
                    f["lost_runs"] = {
                        **info,
                        **_part_verdicts(row, name),
                        "carried": _carried(row, name, f, len(parts)),
                    }
    return record
