"""Generated prose of notebook 003: every number and every interpretive word comes from a computed test."""

from __future__ import annotations

from ...measured import as_estimate, is_undecided
from ...run_words import part_name
from .register import REGISTER

__all__ = [
    "show",
    "show_bound",
    "show_threshold",
    "relation",
    "compare",
    "dependence",
    "threshold_conditions",
    "typical_breaking",
    "typical_against_paper",
    "lost_points",
    "PART_TAGS",
    "LOSS_FREE",
    "TYPICAL",
]

# what the notebook's "threshold" is: the geometric mean of the runs' breaking SIRs (.estimators.threshold)
TYPICAL = "typical (geometric-mean) SIR at which lock breaks"
# said once where the typical value meets the paper's 2 and 3
LOSS_FREE = (
    "The paper's 2 (one interferer) and 3 (five) are loss-free thresholds: at and above them its runs kept lock. The "
    f"{TYPICAL} is where a typical run breaks, so it lies below a loss-free threshold even where the paper holds; the "
    "claims are judged on the shares of runs that lost lock at the paper's SIR, not on this typical value."
)
# the rule parts' short tags the verdicts print in brackets, in words (the tags themselves are the rules' labels)
PART_TAGS = (
    "x_r and y_r: the object centre's x and y coordinates; omega: the marker's rotation rate; r: the radius of the "
    "marker's circle"
)
_OUTSIDE = "some runs broke outside the SIR grid and are placed half a grid step beyond its edge"


def show(e, digits: int = 3) -> str:
    """``value [low, high]`` of an estimate (a bare number for an exact one)."""
    e = as_estimate(e)
    if e.method == "exact":
        return f"{e.value:.{digits}g}"
    tail = f" (extrapolated: {_OUTSIDE})" if e.extrapolated else ""
    return f"{e.value:.{digits}g} [{e.ci_low:.{digits}g}, {e.ci_high:.{digits}g}]{tail}"


def show_threshold(e, bound=None, digits: int = 3) -> str:
    """A typical breaking SIR (:func:`.estimators.threshold`) in words, with the side its censored runs certify
    (``bound``: :func:`.estimators.threshold_bound` of the same runs): where runs broke outside the SIR grid the
    estimate rests on their placement half a grid step beyond its edge, so the sentence leads with what the runs
    show (at least / at most the bound) and gives the placed estimate as extrapolated."""
    e = as_estimate(e)
    if not e.extrapolated and (bound is None or not _censored(as_estimate(bound))):
        return show(e, digits)
    if bound is None:
        return show(e, digits)
    b = as_estimate(bound)
    placed = f"{e.value:.{digits}g} [{e.ci_low:.{digits}g}, {e.ci_high:.{digits}g}], extrapolated"
    if b.extrapolated or (b.ci_low <= 0 and b.ci_high == float("inf")):
        return f"not bounded (runs broke both below and above the SIR grid; placed half a grid step beyond its edges: {placed})"
    if b.ci_high == float("inf"):
        return (
            f"at least {b.ci_low:.{digits}g} (some runs lost lock even at the highest SIR run, so only a lower bound "
            f"is known; placed half a grid step above it: {placed})"
        )
    return (
        f"at most {b.ci_high:.{digits}g} (some runs kept lock even at the lowest SIR run, so only an upper bound is "
        f"known; placed half a grid step below it: {placed})"
    )


def _censored(b) -> bool:
    return bool(b.extrapolated or b.ci_low <= 0 or b.ci_high == float("inf"))


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


def _subject(key: str) -> str:
    marker, count = key.split()
    return f"the {marker} marker's {TYPICAL} with {count} interferer{'s' if count != '1' else ''}"


def threshold_conditions(ex, key: str, paper: float) -> str:
    """The register conditions (one at a time and joint) under which the typical breaking SIR ``key`` of the ``_map``
    output (e.g. ``"rotating 5"``; :data:`TYPICAL`) is not measurably below the paper's loss-free value, with its
    estimate (:func:`show_threshold`); or say there are none.

    The word comes from ``_map_bound`` where the run has it (:func:`.study.threshold_bound`): a threshold whose runs
    broke outside the grid on one side only still lies measurably below (or above) the paper's value. Runs that
    measured no thresholds (asked only for claims without the static curves, e.g. a sizing replicate of other
    claims) are left out."""
    hits = []
    for r in ex.runs:
        if r.stage == "replicate" or "_map" not in r.outputs:
            continue
        e = r.outputs["_map"][key]
        bound = r.outputs.get("_map_bound", {}).get(key)
        word = relation(bound if bound is not None else e, paper)
        if word != "below":
            cond = REGISTER.describe(r.changed(ex.default))
            hits.append(f"{cond} ({show_threshold(e, bound)}; {word} {paper:g})")
    what = _subject(key)
    if not hits:
        return f"under no condition tried is {what} other than below the paper's loss-free {paper:g}"
    return f"{what} is not below the paper's loss-free {paper:g} under: " + " | ".join(hits)


def typical_breaking(thresholds: dict, bounds: dict | None = None) -> str:
    """One replicate's typical breaking SIRs (``_map``, with ``_map_bound`` for the censored side) in words: the
    marker and the number of interferers named, each value by :func:`show_threshold`."""
    bounds = bounds or {}
    parts = []
    for key, e in thresholds.items():
        marker, count = key.split()
        parts.append(
            f"{marker} marker, {count} interferer{'s' if count != '1' else ''}: {show_threshold(e, bounds.get(key))}"
        )
    return "; ".join(parts)


def typical_against_paper(bounds: dict, paper: dict | None = None) -> str:
    """Where the default world's typical breaking SIRs (``_map_bound``: the side the censoring certifies) lie against
    the paper's loss-free thresholds, with the reason a typical value lies below a loss-free one."""
    paper = {"rotating 5": 3.0, "rotating 1": 2.0} if paper is None else paper
    five, one = (relation(bounds[k], v) for k, v in paper.items())
    return (
        f"The rotating marker's {TYPICAL} is {five} the paper's loss-free {paper['rotating 5']:g} with five "
        f"interferers and {one} its loss-free {paper['rotating 1']:g} with one in the default world (first "
        "replicate); a typical breaking point lies below a loss-free threshold even where the paper holds, so the "
        "claims are judged on the shares of runs that lost lock at the paper's SIR"
    )


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
