"""Generated prose of notebook 003: every number and every interpretive word comes from a computed test."""

from __future__ import annotations

from ...measured import as_estimate, is_undecided
from ...run_words import part_name
from .register import REGISTER

__all__ = ["show", "show_bound", "relation", "compare", "dependence", "threshold_conditions", "lost_points"]


def show(e, digits: int = 3) -> str:
    """``value [low, high]`` of an estimate (a bare number for an exact one)."""
    e = as_estimate(e)
    if e.method == "exact":
        return f"{e.value:.{digits}g}"
    tail = " (extrapolated)" if e.extrapolated else ""
    return f"{e.value:.{digits}g} [{e.ci_low:.{digits}g}, {e.ci_high:.{digits}g}]{tail}"


def show_bound(e, digits: int = 3) -> str:
    """``at most b`` for a one-sided bound ``0 [0, b]`` (the estimators' form of a bound from censored runs), else
    :func:`show`."""
    e = as_estimate(e)
    if e.value == 0 and e.ci_low == 0 and e.method != "exact":
        return f"at most {e.ci_high:.{digits}g}"
    return show(e, digits)


def relation(e, ref: float, above: str = "above", below: str = "below", same: str = "indistinguishable from") -> str:
    """The word for where an estimate's 95 % interval lies relative to ``ref`` (``undecided`` when it cannot say)."""
    e = as_estimate(e)
    if is_undecided(e):
        return "undecided against"
    if e.ci_low > ref:
        return above
    if e.ci_high < ref:
        return below
    return same


def _title(name: str) -> str:
    return REGISTER[name].title if name in REGISTER else name


def dependence(records: dict, entries=("motion", "motion_scale", "interference_motion")) -> str:
    """Which parts of which claims flip when one of the named register entries alone changes: the records' named flips
    of one-at-a-time conditions (:func:`tvtrack.verdicts.label_parts`: decisive the other way on at least the
    replicates the default needed, against the part's pooled verdict), never a condition set beside one replicate.
    Each entry is named by its title and each value by its phrase (:class:`tvtrack.register.Entry`), never by code
    names."""
    explored = {e["name"] for rec in records.values() for e in rec.get("register", [])} & set(entries)
    if not explored:
        return f"{'; '.join(_title(e) for e in entries)}: not explored in this run"
    hits = []
    for cid, rec in records.items():
        for name, part in rec["parts"].items():
            flips = [
                f"{f['verdict']} with {REGISTER.describe(f['changed'])}"
                for f in part.get("flips") or []
                if f.get("kind") == "single" and set(f["changed"]) <= explored
            ]
            if flips:
                hits.append(f"{cid} ({part_name(name)}, {part['verdict']} by default): {'; '.join(flips)}")
    names = "; ".join(_title(e) for e in sorted(explored))
    if not hits:
        return f"no part of these claims flips when one of these alone changes: {names}"
    return f"changing one of these alone ({names}) flips " + " | ".join(hits)


def threshold_conditions(ex, key: str, paper: float) -> str:
    """The register conditions (one at a time and joint) under which the threshold ``key`` of the ``_map`` output
    (e.g. ``"rotating 5"``) is not measurably below the paper's value, with its estimate; or say there are none.

    The word comes from ``_map_bound`` where the run has it (:func:`.study.threshold_bound`): a threshold whose runs
    broke outside the grid on one side only still lies measurably below (or above) the paper's value. Runs that
    measured no thresholds (asked only for claims without the static curves, e.g. a sizing replicate of other
    claims) are left out."""
    hits = []
    for r in ex.runs:
        if r.stage == "replicate" or "_map" not in r.outputs:
            continue
        e = r.outputs["_map"][key]
        word = relation(r.outputs.get("_map_bound", r.outputs["_map"])[key], paper)
        if word != "below":
            cond = REGISTER.describe(r.changed(ex.default))
            hits.append(f"{cond} ({show(e)}, {word} {paper:g})")
    marker, count = key.split()
    what = f"the {marker} marker's threshold with {count} interferer{'s' if count != '1' else ''}"
    if not hits:
        return f"under no condition tried is {what} other than below the paper's {paper:g}"
    return f"{what} is not below the paper's {paper:g} under: " + " | ".join(hits)


def compare(a, b) -> str:
    """Where the interval of ``a`` lies against that of ``b``: "above", "below" or "overlapping" ("undecided
    against" when either cannot decide)."""
    a, b = as_estimate(a), as_estimate(b)
    if is_undecided(a) or is_undecided(b):
        return "undecided against"
    if a.ci_low > b.ci_high:
        return "above"
    if a.ci_high < b.ci_low:
        return "below"
    return "overlapping"


def lost_points(lock_by_bandwidth: dict, limit: float = 0.1) -> str:
    """The loop bandwidths at which the tracker lost lock in more than ``limit`` of the runs, in words, with the
    share of lost runs (Clopper-Pearson; replicates pooled as summed counts): the points a trend leaves out."""
    lost = {b: as_estimate(e) for b, e in lock_by_bandwidth.items() if as_estimate(e).value > limit}
    if not lost:
        return "The tracker kept lock at every loop bandwidth of the grid."
    bits = [f"{b} (share of runs that lost lock {show(e)}, {e.n} runs)" for b, e in lost.items()]
    return (
        "The tracker lost lock at " + "; ".join(bits) + ": its error there is the distance to the marker it left, "
        "not a ripple, so the trend is read over the other bandwidths only."
    )
