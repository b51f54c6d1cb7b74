"""What notebook 002 reports beside the claims' verdicts (studies beyond the paper): how often the algorithms fail,
swap labels or hit their iteration cap at the configurations of Figs 4-7, how often the number of objects
is chosen right by BIC when it is not known, SQUAREM against plain EM, local maxima, the cost of estimating
p_j and sigma or of a wrong Q, and the words and tables the notebook's prose is generated with.

Both read the simulation points of :func:`.study.figure_data` (``g``: named groups of configurations, ``res``: their
results). Rates are proportions of trials with Clopper-Pearson 95 % intervals.
"""

from __future__ import annotations

import numpy as np

from tvtrack.estimate import Estimate
from tvtrack.counts import proportion_ci

from .claim_values import errors, gain
from .summaries import FLAG_NAMES, gross_errors

__all__ = [
    "FAILURE_GROUPS",
    "failure_rates",
    "bic_correct_q",
    "word",
    "squarem_vs_plain",
    "estimation_cost",
    "wrong_q_cost",
    "local_maxima_rate",
    "condition_output",
    "compare",
    "flips_by_entry",
    "who_wins",
    "headline_caveat",
    "headline_comparisons",
]

#: The configurations of Figs 4-7 whose failure rates are reported: ``(group of g, key, label)``.
FAILURE_GROUPS = (
    ("4", 20, "Fig 4a (m_k = 20)"),
    ("4", 50, "Fig 4b (m_k = 50)"),
    ("5ab", 5, "Fig 5a (T = 5)"),
    ("5ab", 50, "Fig 5b (T = 50)"),
    ("6", 20, "Fig 6b (Delta = 5 sigma)"),
)
#: The algorithms whose rates are reported: name -> result key of their errors and flags.
_RATES = {"ULA": "ula", "two-stage": "em"}


def _flag(result: dict, alg: str, name: str) -> np.ndarray:
    return result[f"{alg}_flags"][:, FLAG_NAMES[alg].index(name)]


def failure_rates(g: dict, res) -> dict[str, dict[float, dict[str, Estimate]]]:
    """Failure, label-swap and iteration-cap rates of the ULA and the two-stage (iterative marks), per configuration
    of Figs 4-7 and per separation.

    Returns
    -------
    dict
        ``{figure label: {d / sigma: {"<algorithm> <rate>": Estimate}}}`` with, for ``ULA`` and ``two-stage``:
        ``failure`` (some initial-position error beyond 2 sigma), ``label swap`` (the best label order over the
        whole trajectory is not the designation's) and ``cap hit`` (the EM iteration cap reached: per-frame marks,
        in some frame); and ``"Fig 7 (plain EM)"``: the cap-hit rates alone of the plain EM whose iterations Fig 7
        counts.
    """
    out = {}
    for group, key, label in FAILURE_GROUPS:
        if group not in g or key not in g[group]:
            continue
        rows = {}
        for d, c in g[group][key].items():
            r = res[c]
            row = {}
            for name, alg in _RATES.items():
                n = len(r[alg])
                row[f"{name} failure"] = proportion_ci(int(gross_errors(r, alg).sum()), n)
                row[f"{name} label swap"] = proportion_ci(int(_flag(r, alg, "swap").sum()), n)
                row[f"{name} cap hit"] = proportion_ci(int(_flag(r, alg, "cap_hit").sum()), n)
            rows[d] = row
        out[label] = rows
    if "7" in g:  # Fig 7 counts plain-EM iterations (Fig 4a's configuration): how often they hit the cap
        out["Fig 7 (plain EM)"] = {
            d: {
                "ULA cap hit": proportion_ci(int(res[c]["plain_cap"].sum()), len(res[c]["plain_cap"])),
                "two-stage cap hit": proportion_ci(int(res[c]["em_plain_cap"].sum()), len(res[c]["em_plain_cap"])),
            }
            for d, c in g["7"].items()
        }
    return out


def bic_correct_q(g: dict, res) -> dict[float, dict[str, Estimate]]:
    """Share of trials in which BIC over ULA fits with Q' = 1, 2, 3 objects (weights estimated) picks each order,
    per separation; the true order is 2.

    Returns
    -------
    dict
        ``{d / sigma: {"Q' = 1": Estimate, "Q' = 2 (correct)": Estimate, "Q' = 3": Estimate}}``.
    """
    out = {}
    for d, c in g["bic"].items():
        pick = np.argmin(res[c]["bic"], axis=1) + 1
        n = len(pick)
        out[d] = {
            "Q' = 1": proportion_ci(int((pick == 1).sum()), n),
            "Q' = 2 (correct)": proportion_ci(int((pick == 2).sum()), n),
            "Q' = 3": proportion_ci(int((pick == 3).sum()), n),
        }
    return out


def word(
    est: Estimate, ref: float = 1.0, above: str = "above", below: str = "below", same: str = "not distinguishable from"
) -> str:
    """The word a 95 % interval supports about ``ref``: ``above`` / ``below`` when it excludes ``ref``, else
    ``same``; ``"undetermined against"`` for an undefined interval."""
    if not (np.isfinite(est.ci_low) and np.isfinite(est.ci_high)):
        return "undetermined against"
    return above if est.ci_low > ref else below if est.ci_high < ref else same


def squarem_vs_plain(g: dict, res) -> dict:
    """How far SQUAREM's estimates are from plain EM's on the same trials (Fig 7's points): the largest absolute
    difference of any initial position (sigma) and the share of trials where it exceeds 0.01 sigma, per d."""
    out = {}
    for d, c in g["7"].items():
        r = res[c]
        diff = np.abs(r["plain"][..., :2] - r["ula"][..., :2]).max(axis=(1, 2))
        out[d] = {"max_sigma": float(diff.max()), "share_over_0.01": proportion_ci(int((diff > 0.01).sum()), len(diff))}
    return out


def estimation_cost(g: dict, res, rng, n_bootstrap: int) -> dict:
    """The accuracy cost of estimating p_j and sigma as well (an extension the paper calls feasible): Sigma^2 with
    them estimated over Sigma^2 with them known, paired on the same trials, per separation."""
    return {d: gain(errors(res[c], "ula_w"), errors(res[c], "ula"), rng, n_bootstrap) for d, c in g["w"].items()}


def wrong_q_cost(g: dict, res, rng, n_bootstrap: int) -> dict:
    """The cost of a wrong number of objects (a study beyond the paper): the variance sum of the group's mean
    initial position when one track is fitted to the pair (Q' = 1) over the same with Q = 2 known, paired on the
    same trials, per d."""
    out = {}
    for d, c in g["w"].items():
        r = res[c]
        mid2 = r["ula"][..., :2].mean(axis=1)  # (n, 2): labels do not matter for the mean
        out[d] = gain(r["ula_q1"][:, 0, :2], mid2, rng, n_bootstrap)
    return out


def local_maxima_rate(g: dict, res, gap: float = 1e-3) -> dict:
    """Share of trials (with its interval) in which the ULA started at the designation stops at a local maximum
    more than ``gap`` (log-likelihood) below the best of four starts, per separation."""
    return {d: proportion_ci(int((res[c]["ms_gap"] > gap).sum()), len(res[c]["ms_gap"])) for d, c in g["ms"].items()}


def condition_output(exploration, claim_id: str, changed: dict):
    """What ``claim_id`` measured in the run (one at a time or joint) that changed exactly ``changed`` from the
    default (None if no run did)."""
    default = exploration.default
    for r in exploration.runs:
        if r.stage != "replicate" and r.changed(default) == changed:
            return r.outputs.get(claim_id)
    return None


def compare(a: Estimate, b: Estimate) -> str:
    """``a`` against ``b`` by their 95 % intervals: "larger than" / "smaller than" when they do not overlap, else
    "not distinguishable from" (a conservative comparison of two estimates from the same scenes)."""
    if a.ci_low > b.ci_high:
        return "larger than"
    if a.ci_high < b.ci_low:
        return "smaller than"
    return "not distinguishable from"


def flips_by_entry(exploration, rules, names, kinds=("single",)) -> dict:
    """``{entry name: [claim ids]}``: the claims some part of whose verdict differs, in a run of a kind in ``kinds``
    (``"single"``: one at a time, the entry alone; ``"joint"``, ``"pinned"``: joint conditions, where the entry is
    one of several changed) that changed that entry, from the first replicate (the run it shares its random numbers
    with)."""
    out = {n: [] for n in names}
    for cid, rule in rules.items():
        rec = exploration.record(cid, rule)
        ref = rec["replicates"][0]["parts"] if rec["replicates"] else {}
        for c in rec["conditions"]:
            if c["kind"] not in kinds:
                continue
            for k in c["changed"]:
                if k in out and c["parts"] != ref and cid not in out[k]:
                    out[k].append(cid)
    return out


def who_wins(rho: Estimate) -> str:
    """The direction a 95 % interval of rho = Sigma^2_two-stage / Sigma^2_ULA supports: ``"above 1: the ULA more
    accurate"``, ``"below 1: the two-stage more accurate"`` or ``"not distinguishable from 1"`` (:func:`word`)."""
    w = word(rho)
    if w == "above":
        return "above 1: the ULA more accurate"
    if w == "below":
        return "below 1: the two-stage more accurate"
    return f"{w} 1"


def _band_side(rho: Estimate, low: float, high: float) -> str:
    """Where a 95 % interval lies against the band [low, high]: wholly below, wholly above, inside, or across."""
    if rho.ci_high < low:
        return "wholly below"
    if rho.ci_low > high:
        return "wholly above"
    if rho.ci_low >= low and rho.ci_high <= high:
        return "inside"
    return "reaching into"


def headline_comparisons(rows: dict, part: str, band: tuple, fmt=None) -> str:
    """C002-11's direction for every comparison the run made, from the numbers: ``rows`` maps each comparison's
    words (the first: the published ML ULA against the designation-started marks) to its measured parts (``None``
    where no run made it), ``part`` the part read (e.g. d = 1 sigma), ``band`` the rule's ``(low, high)`` around
    the paper's number, ``fmt`` the notebook's formatter of an estimate. The direction word of each comparison
    comes from its own 95 % interval (:func:`who_wins`), and so does its place against the band."""
    fmt = fmt or (lambda e: f"{e.value:.3g} [{e.ci_low:.3g}, {e.ci_high:.3g}]")
    low, high = band
    made = [(name, m[part]) for name, m in rows.items() if m and part in m]
    if not made:
        return ""
    said = [
        f"{name}: {fmt(e)}, {who_wins(e)}, {_band_side(e, low, high)} the paper's band [{low:g}, {high:g}]"
        for name, e in made
    ]
    sides = {word(e) for _, e in made}
    if {"above", "below"} <= sides:
        end = "so which algorithm is more accurate here depends on what the ULA is given"
    elif len(sides) == 1:
        end = (
            "the same direction in every comparison"
            if sides & {"above", "below"}
            else "no comparison tells the algorithms apart"
        )
    else:
        end = "not every comparison tells the algorithms apart"
    head = part.split(" (")[0]
    return (
        f"At {head}, T = 50, rho = Sigma^2_two-stage / Sigma^2_ULA in each comparison the run made (the claim's "
        "sentence reads the first comparison only): " + "; ".join(said) + f"; {end}."
    )


def headline_caveat(rows: dict, parts: list, fmt=None, unit: str = "variance ratio") -> str:
    """C002-11's caveat, from the numbers: at each part (of ``parts``) where the comparisons the run made point
    opposite ways (:func:`headline_comparisons`' "depends on what the ULA is given"), the ULA's other givens with
    their rho in ``unit`` and its direction (the claim's sentence reads the first comparison only); ``""`` where
    none does."""
    fmt = fmt or (lambda e: f"{e.value:.3g} [{e.ci_low:.3g}, {e.ci_high:.3g}]")
    said = []
    for part in parts:
        made = [(name, m[part]) for name, m in rows.items() if m and part in m]
        if {"above", "below"} <= {word(e) for _, e in made}:
            others = "; ".join(f"{name}: {fmt(e)} {unit}, {who_wins(e)}" for name, e in made[1:])
            said.append(f"At {part} which algorithm is more accurate depends on what the ULA is given: {others}")
    return ". ".join(said)
