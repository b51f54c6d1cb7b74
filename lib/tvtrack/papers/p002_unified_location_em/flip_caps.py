"""Which claims read simulation points where an EM stopped at its iteration cap: at the register default, and under
each condition that flips a claim (a study beyond the paper, beside :mod:`.cap_check`).

An EM that reaches the run's iteration cap stops before its stopping rule is met. :mod:`.cap_check` reruns Fig 6b's
points with a larger cap; this module says, from the run's own simulations, which claims' verdicts (and which of
their flips, :meth:`tvtrack.explore.Exploration.record`'s ``parts[].flips``) read points where that happened, and
in what share of the trials there. The points a claim reads under a configuration are :func:`.study.jobs_of`'s
(projected onto the claim's declared entries, as :func:`.study.measure_batch` runs them); their results are the
exploration's, cached in this process (:func:`.study.cached`). Cap flags are recorded by the ULA (``u``; ``p``: Fig 7's plain EM) and the
two-stage's per-frame marks (``e``; ``q``: plain EM), a trial counting when the cap was reached in some frame; the
MAP-ULA and the ULA given the designated velocity record none.

Units: shares of trials (per cent in the words).
"""

from __future__ import annotations

from tvtrack.numbers import percent
from tvtrack.projection import claim_groups

from . import study
from .register import DEPENDS, REGISTER

__all__ = ["CAPPED", "cap_counts", "capped_flags", "capped_shares", "flip_caps", "flip_caps_sentence"]

#: Algorithm letter -> (its name in the words, the result key of its per-trial cap flag).
CAPPED = {
    "u": ("the ULA", "ula_flags"),
    "p": ("the ULA's plain EM of the iteration counts", "plain_cap"),
    "e": ("the two-stage's per-frame marks", "em_flags"),
    "q": ("the marks' plain EM of the iteration counts", "em_plain_cap"),
}
_CAP_COLUMN = 2  # the cap-hit column of ula_flags and em_flags (.summaries.FLAG_NAMES)


def capped_flags(result: dict, key: str):
    """Per trial, whether an EM of ``result`` reached its cap (``key``: the result's cap flags, :data:`CAPPED`)."""
    a = result[key]
    return a[:, _CAP_COLUMN] if a.ndim == 2 else a


def cap_counts(changed: dict, seeds, scale, claim: str, cache=None) -> dict | None:
    """``{algorithm name: (trials at the cap, trials)}`` over the points ``claim`` reads with the register default
    changed by ``changed``, pooled over ``seeds``; only algorithms that record a cap (:data:`CAPPED`) are counted,
    and the key ``"caps"`` holds the iteration caps (EM steps) of the points where some trial reached one. ``None``
    where none of those points is in ``cache`` (a mapping job -> result; default: the study's cache,
    :func:`.study.cached`, which holds none where e.g. the simulations ran on a scheduler's workers)."""
    look = study.cached if cache is None else cache.get
    default = REGISTER.default()
    counts, found, caps = {}, False, set()
    for seed in seeds:
        for config, claims in claim_groups({**default, **changed}, {claim}, DEPENDS, default):
            for job in study.jobs_of(config, seed, scale, claims=claims):
                result = look(job)
                if result is None:
                    continue
                found = True
                letter = job[1].algs
                if letter in CAPPED:
                    name, key = CAPPED[letter]
                    hits = capped_flags(result, key)
                    k, n = counts.get(name, (0, 0))
                    counts[name] = (k + int(hits.sum()), n + len(hits))
                    if hits.any():
                        caps.add(int(job[0].max_iter))
    return {**counts, "caps": caps} if found else None


def _seeds(exploration, claim: str, changed: dict) -> list:
    """The seeds of the runs of a flip's condition (its own and its further replicates) for ``claim``."""
    reads, default = set(exploration.depends[claim]), exploration.default
    for r in exploration.runs:
        if r.stage == "replicate" or not r.counts_for(claim):
            continue
        if {k: v for k, v in r.changed(default).items() if k in reads} == changed:
            return [r.seed, *(s.seed for s in r.sized if claim in s.outputs)]
    return [exploration.replicates()[0].seed]


def flip_caps(exploration, rules: dict, scale, cache=None) -> dict:
    """Per claim of ``rules``: ``{"default": cap_counts at the first replicate, "flips": [{"changed", "parts",
    "counts"}]}``, one entry per distinct flipping condition (the parts it flips listed)."""
    out = {}
    seed0 = exploration.replicates()[0].seed
    for cid, rule in rules.items():
        flips: dict = {}
        for part, rec in (exploration.record(cid, rule).get("parts") or {}).items():
            for f in rec.get("flips") or []:
                key = tuple(sorted((k, str(v)) for k, v in f["changed"].items()))
                flips.setdefault(key, {"changed": dict(f["changed"]), "parts": []})["parts"].append(part)
        for f in flips.values():
            f["counts"] = cap_counts(f["changed"], _seeds(exploration, cid, f["changed"]), scale, cid, cache)
        out[cid] = {"default": cap_counts({}, [seed0], scale, cid, cache), "flips": list(flips.values())}
    return out


def capped_shares(counts: dict | None) -> dict:
    """``{algorithm name: share of trials at the cap}`` of :func:`cap_counts`' result, those that reached it only."""
    return {name: kn[0] / kn[1] for name, kn in (counts or {}).items() if name != "caps" and kn[0]}


def _caps_words(counts: list, cap: int) -> str:
    """`` (at a cap of 100 iterations in 2 of them)``: where some of ``counts`` reached a cap other than the run's."""
    other = sorted({c for k in counts for c in k.get("caps", ()) if c != cap})
    if not other:
        return ""
    n = sum(1 for k in counts if set(k.get("caps", ())) - {cap})
    caps = " or ".join(str(c) for c in other)
    return f", at a cap of {caps} iterations set by the condition in {n} of them"


def _span(shares: list) -> str:
    lo, hi = min(shares), max(shares)
    return percent(lo) if percent(lo) == percent(hi) else f"{percent(lo)} to {percent(hi)}"


def flip_caps_sentence(caps: dict, cap: int) -> str:
    """The words of :func:`flip_caps`' result ``caps`` (``cap``: the run's EM iteration cap): per claim, whether
    its points at the default and how many of its flipping conditions read points where an EM reached the cap, by
    algorithm, with the share of the trials read there (from the counts; a span over the flips)."""
    said, clean, unknown = [], [], []
    for cid, c in caps.items():
        bits = []
        at_default = capped_shares(c["default"])
        if at_default:
            bits.append(
                "at the default (first replicate: "
                + ", ".join(f"{name} in {percent(share)} of its trials" for name, share in at_default.items())
                + ")"
            )
        flips = c["flips"]
        counted = [f for f in flips if f["counts"] is not None]
        capped = [f for f in counted if capped_shares(f["counts"])]
        if len(counted) < len(flips):
            unknown.append(cid)
        if capped:
            names = dict.fromkeys(n for f in capped for n in capped_shares(f["counts"]))
            spans = ", ".join(
                f"{name} in {_span([capped_shares(f['counts'])[name] for f in capped if name in capped_shares(f['counts'])])}"
                for name in names
            )
            bits.append(
                f"in {len(capped)} of its {len(flips)} flipping conditions ({spans} of the trials each reads"
                f"{_caps_words([f['counts'] for f in capped], cap)})"
            )
        if bits:
            said.append(f"{cid} " + " and ".join(bits))
        elif flips:
            clean.append(cid)
    if not said and not clean:
        return ""
    text = (
        f"Beyond Fig 6b: the claims that read points where an EM stopped at its iteration cap ({cap} iterations "
        "unless a condition sets another), at the register default or under a condition that flips them (share "
        "of the trials at those points in which it did): " + ("; ".join(said) if said else "none") + "."
    )
    if clean:
        text += f" The flipping conditions of {', '.join(clean)} read no point where an EM reached the cap."
    if unknown:
        text += (
            f" Some flipping conditions of {', '.join(unknown)} ran outside this process (a scheduler's workers) and"
            " are not counted."
        )
    return text
