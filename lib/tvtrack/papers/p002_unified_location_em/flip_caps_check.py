"""Do the flips that read capped points survive a larger EM iteration cap? A study beyond the paper, beside
:mod:`.flip_caps` (which counts them) and :mod:`.cap_check` (which reruns Fig 6b's points).

Where a claim's flipping condition (or its register default) reads simulation points at which an EM reached the
run's iteration cap, :func:`flips_at_larger_cap` measures the claim again on the same replicate seeds with that cap
:data:`.cap_check.CAP_FACTOR` times larger (``Scale.cap_factor``; a reading that sets its own lower cap, "plain EM,
cap 100", keeps it, and a trial at such a cap is not counted as at the run's) and judges it by the same rule, pooled
as the explorer pooled the same replicates. So each flip is compared at the same size on the same scenes: only the
capped trials can change, since a trial that never reached the cap gives the same estimates bit for bit at the
larger cap (:mod:`.cap_check`). The simulations with no trial at the run's cap are therefore taken from the run's
cache under the larger cap's key (:func:`_reuse_uncapped`); those with a capped trial run again, and so do those of
the MAP-ULA and of the ULA given the designated velocity, which record no cap flag (nor are their caps counted).
None of the claims' values read the larger cap's keys.

A flip stands at the larger cap where the condition's verdict and the default's (at the larger cap where the default
was rerun) are both decisive and differ, as the explorer defines a flip. Only the conditions that flipped at the run's
cap are measured again: where the default's verdict moves at the larger cap, a condition that agreed with it before
is not, and the replicates the default needs are not recomputed; the words say so.

Units: shares of trials; the verdicts are the rules'.
"""

from __future__ import annotations

from dataclasses import replace

from tvtrack.jobs import cpu_seconds
from tvtrack.labels import part_judgements
from tvtrack.numbers import percent
from tvtrack.pooling import pool
from tvtrack.projection import claim_groups
from tvtrack.verdicts import is_decisive

from . import study
from .cap_check import CAP_FACTOR
from .flip_caps import CAPPED, capped_flags, capped_shares
from .register import DEPENDS, REGISTER

__all__ = [
    "at_larger_cap",
    "flips_at_larger_cap",
    "larger_cap_sentence",
    "larger_cap_conclusion",
    "larger_cap_metrics",
    "raised_counts",
]


def _jobs(changed: dict, seed: int, scale, claim: str) -> list:
    default = REGISTER.default()
    return [
        j
        for config, claims in claim_groups({**default, **changed}, {claim}, DEPENDS, default)
        for j in study.jobs_of(config, seed, scale, claims=claims)
    ]


def _reuse_uncapped(changed: dict, seeds, scale, big, claim: str) -> set:
    """Cache, under the larger cap's job keys (``big``: the larger cap's scale), each simulation of ``claim``'s
    points that ran at the run's cap (``scale``) with no trial reaching it: its estimates are the same bit for bit.
    Returns the larger cap's jobs left to run."""
    left = set()
    for seed in seeds:
        for job, job_big in zip(_jobs(changed, seed, scale, claim), _jobs(changed, seed, big, claim)):
            if study.cached(job_big) is not None:
                continue
            result, letter = study.cached(job), job[1].algs
            if result is not None and (
                job == job_big or (letter in CAPPED and not capped_flags(result, CAPPED[letter][1]).any())
            ):
                study.remember(job_big, result)
            else:
                left.add(job_big)
    return left


def raised_counts(changed: dict, seeds, scale, big, claim: str, larger: bool = False) -> dict:
    """``{algorithm name: (trials at the cap, trials)}`` over ``claim``'s simulations (the register default changed
    by ``changed``, pooled over ``seeds``) whose cap the larger scale ``big`` raises, at the run's cap (``larger``
    False) or at the larger one; a condition's own cap, kept at both, and the algorithms that record no cap flag are
    left out. Simulations not in the cache are skipped."""
    counts: dict = {}
    for seed in seeds:
        for job, job_big in zip(_jobs(changed, seed, scale, claim), _jobs(changed, seed, big, claim)):
            letter, result = job[1].algs, study.cached(job_big if larger else job)
            if job[0].max_iter == job_big[0].max_iter or letter not in CAPPED or result is None:
                continue
            name, key = CAPPED[letter]
            hits = capped_flags(result, key)
            k, n = counts.get(name, (0, 0))
            counts[name] = (k + int(hits.sum()), n + len(hits))
    return counts


def _measure_all(tasks: list, scale, factor: int) -> tuple[list[dict], int]:
    """Each task ``(claim, changed, seeds)`` measured at the larger cap, every task's simulations in one batch (the
    scale's worker processes): per task ``pooled`` (the claim's value pooled over the seeds, as the explorer pools a
    condition's replicates) and ``counts`` (:func:`raised_counts` at the larger cap); and the simulations run again
    (the others reused)."""
    big = replace(scale, cap_factor=int(factor) * scale.cap_factor)
    left = set().union(*(_reuse_uncapped(changed, seeds, scale, big, cid) for cid, changed, seeds in tasks))
    default = REGISTER.default()
    configs = [{**default, **changed} for _, changed, seeds in tasks for _ in seeds]
    asked = [{cid} for cid, _, seeds in tasks for _ in seeds]
    ms = iter(study.measure_batch(configs, [s for *_, seeds in tasks for s in seeds], big, asked))
    out = [
        {
            "pooled": pool([next(ms)[cid] for _ in seeds]),
            "counts": raised_counts(changed, seeds, scale, big, cid, larger=True),
        }
        for cid, changed, seeds in tasks
    ]
    return out, len(left)


def at_larger_cap(changed: dict, seeds, scale, claim: str, rule, factor: int = CAP_FACTOR) -> dict:
    """``claim`` measured with the register default changed by ``changed`` on ``seeds`` with the run's EM iteration
    cap ``factor`` times larger, pooled over the seeds (:func:`tvtrack.pooling.pool`).

    Returns
    -------
    dict
        ``pooled`` (the claim's measured value), ``verdicts`` (``{part: verdict}`` by ``rule``), ``counts``
        (:func:`raised_counts` at the larger cap), ``rerun`` (simulations run again).
    """
    (out,), rerun = _measure_all([(claim, changed, list(seeds))], scale, factor)
    return {**out, "verdicts": _verdicts(rule, out["pooled"]), "rerun": rerun}


def _verdicts(rule, measured) -> dict:
    return {p: j.verdict for p, j in part_judgements(rule, measured).items()}


def flips_at_larger_cap(exploration, caps: dict, rules: dict, scale, cap: int, factor: int = CAP_FACTOR) -> dict:
    """Per claim of :func:`.flip_caps.flip_caps`' result ``caps`` whose default or flipping conditions read points
    where some trial reached the run's cap ``cap`` (:func:`raised_counts`): ``{"default": {...} or None, "flips":
    [{...}], "reference": {part: verdict}}``. Each measurement has ``changed``, ``parts`` (the parts the condition
    flips; at the default every part), ``seeds`` (the replicates the explorer pooled for the claim), ``before``
    (``{part: verdict}`` at the run's cap, those replicates pooled), ``capped`` (:func:`raised_counts` there),
    ``pooled``, ``verdicts`` and ``counts`` (at the larger cap); ``reference`` is the default's verdicts a flip is
    judged against (at the larger cap where the default was rerun, else the run's). Also ``cap``, ``larger cap``,
    ``rerun`` (simulations run again) and ``cpu_s`` (this process and its workers). Every measurement runs in one
    batch."""
    t0 = cpu_seconds()
    big = replace(scale, cap_factor=int(factor) * scale.cap_factor)
    entries, tasks = {}, []  # tasks: (claim, changed, seeds, the record the measurement completes)
    for cid, c in caps.items():
        rule = rules[cid]
        reps = [r.seed for r in exploration.replicates() if r.outputs.get(cid) is not None]  # sized: some lack it
        before = _verdicts(rule, exploration.measured(cid))
        entry = entries[cid] = {"default": None, "flips": [], "reference": before}
        hit = raised_counts({}, reps, scale, big, cid)
        if capped_shares(hit):
            entry["default"] = {"changed": {}, "parts": list(before), "seeds": reps, "before": before, "capped": hit}
            tasks.append((cid, {}, reps, entry["default"]))
        for f in c["flips"]:
            run = _run_of(exploration, cid, f["changed"])
            seeds = _seeds(run, cid)
            hit = raised_counts(f["changed"], seeds, scale, big, cid)
            if not capped_shares(hit):
                continue
            g = {"changed": f["changed"], "parts": f["parts"], "seeds": seeds, "capped": hit}
            entry["flips"].append({**g, "before": _verdicts(rule, run.pooled(cid))})
            tasks.append((cid, f["changed"], seeds, entry["flips"][-1]))
    measured, rerun = _measure_all([t[:3] for t in tasks], scale, factor) if tasks else ([], 0)
    for (cid, *_, record), m in zip(tasks, measured):
        record.update(m, verdicts=_verdicts(rules[cid], m["pooled"]))
    for e in entries.values():
        if e["default"]:
            e["reference"] = e["default"]["verdicts"]
    out = {cid: e for cid, e in entries.items() if e["default"] or e["flips"]}
    return {"claims": out, "cap": cap, "larger cap": cap * int(factor), "rerun": rerun, "cpu_s": cpu_seconds() - t0}


def _run_of(exploration, claim: str, changed: dict):
    """The exploration's run of the condition ``changed`` that counts for ``claim`` (:func:`.flip_caps._seeds`)."""
    reads, default = set(exploration.depends[claim]), exploration.default
    for r in exploration.runs:
        if r.stage != "replicate" and r.counts_for(claim):
            if {k: v for k, v in r.changed(default).items() if k in reads} == changed:
                return r
    raise KeyError(f"{claim}: no run of the condition {changed}")


def _seeds(run, claim: str) -> list:
    """The seeds of a condition's full-size replicates of ``claim``, as :meth:`tvtrack.conditions.Run.replicates`
    reads them."""
    more = [s.seed for s in run.sized if claim in s.outputs and (s.claims is None or claim in s.claims)]
    return more if claim in run.screened else [run.seed, *more]


def _outcome(f: dict, ref: dict) -> list:
    """Per flipped part of ``f``: ``(part, verdict at the run's cap, at the larger cap, outcome)``, the outcome
    ``"stands"`` where the larger cap's verdict and the default's (``ref``) are both decisive and differ (a flip as
    the explorer defines one), ``"no default"`` where the default's is not decisive, else ``"gone"`` (undecided, or
    the default's verdict)."""
    rows = []
    for p in f["parts"]:
        after, r = f["verdicts"].get(p, "undecided"), ref.get(p, "undecided")
        outcome = "no default" if not is_decisive(r) else "stands" if is_decisive(after) and after != r else "gone"
        rows.append((p, f["before"].get(p, "undecided"), after, outcome))
    return rows


def _part(p: str) -> str:
    return "its verdict" if p == "claim" else f'part "{p}"'


def _still(counts: dict) -> str:
    """``, the ULA still at the larger cap in 3% of its trials``: the algorithms some of whose trials reach it."""
    return "".join(
        f", {n} still at the larger cap in {percent(s)} of its trials" for n, s in capped_shares(counts).items()
    )


def _default_words(d: dict) -> str:
    """At the default: whether any part's verdict moves at the larger cap (``d``: the default's entry)."""
    moved = [p for p in d["parts"] if d["before"].get(p) != d["verdicts"].get(p)]
    head = f"at the default ({len(d['seeds'])} replicates pooled, as for the run's verdict) "
    if moved:
        words = "; ".join(f"{_part(p)} {d['before'][p]} -> {d['verdicts'][p]}" for p in moved)
        words += " (the conditions that agreed with the default at the run's cap were not measured again)"
    elif all(v == "undecided" for v in d["verdicts"].values()):
        words = "undecided at both caps"
    else:
        words = "every verdict the same as at the run's cap"
    return head + words + _still(d["counts"])


def _flip_words(f: dict, ref: dict) -> str:
    return (
        REGISTER.describe(f["changed"])
        + " ("
        + ", ".join(f"{_part(p)}: {a} -> {b}" for p, a, b, _ in _outcome(f, ref))
        + _still(f["counts"])
        + ")"
    )


def _flips_words(e: dict) -> str:
    """How many of a claim's rerun flips stand, are gone, or have no decisive default verdict to flip against."""
    outcomes = [{o for *_, o in _outcome(f, e["reference"])} for f in e["flips"]]
    n, stands = len(outcomes), sum(o == {"stands"} for o in outcomes)
    lost = sum("no default" in o for o in outcomes)
    gone = n - stands - lost
    no_default = "no decisive default verdict to flip at the larger cap"
    if n == 1:
        head = "the flipping condition that reads capped points " + (
            "still flips it" if stands else "no longer does" if gone else f"has {no_default}"
        )
    else:
        bits = [f"{stands} still flip{'s' if stands == 1 else ''} it"] if stands else []
        bits += [f"{gone} no longer do{'es' if gone == 1 else ''}"] if gone else []
        bits += [f"{lost} ha{'s' if lost == 1 else 've'} {no_default}"] if lost else []
        head = f"of the {n} flipping conditions that read capped points, " + ", ".join(bits)
    return head + ": " + "; ".join(_flip_words(f, e["reference"]) for f in e["flips"])


def larger_cap_sentence(out: dict) -> str:
    """The words of :func:`flips_at_larger_cap`' result ``out``: per claim, the default's verdicts where it was
    rerun, each flipping condition's verdicts at the run's cap and at the larger one, whether the flip stands, and the
    share of trials still at the larger cap."""
    if not out["claims"]:
        return ""
    said = []
    for cid, e in out["claims"].items():
        bits = [_default_words(e["default"])] if e["default"] else []
        bits += [_flips_words(e)] if e["flips"] else []
        said.append(f"{cid}: " + "; ".join(bits))
    return (
        f"Measured again with the run's EM iteration cap {out['larger cap'] // out['cap']} times larger "
        f"({out['cap']:,} -> {out['larger cap']:,} iterations; a condition's own lower cap kept) on the same "
        "replicate seeds, the claims whose default or flipping conditions read points where an EM reached the run's "
        "cap give (verdict at the run's cap -> at the larger cap): " + ". ".join(said) + "."
    )


def larger_cap_conclusion(out: dict) -> str:
    """One line for the conclusions: of the flips that read capped points, how many still stand at the larger cap,
    the claims whose flips do not (and how many), and the defaults whose verdict moves; ``""`` where nothing read a
    capped point."""
    if not out["claims"]:
        return ""
    total = stand = 0
    gone, moved = [], []
    for cid, e in out["claims"].items():
        ok = [{o for *_, o in _outcome(f, e["reference"])} == {"stands"} for f in e["flips"]]
        total, stand = total + len(ok), stand + sum(ok)
        if len(ok) > sum(ok):
            gone.append(f"{cid} ({len(ok) - sum(ok)} of {len(ok)})")
        d = e["default"]
        moved += [
            f"{cid} ({_part(p)} {d['before'][p]} -> {d['verdicts'][p]})"
            for p in (d or {}).get("parts", ())
            if d["before"].get(p) != d["verdicts"].get(p)
        ]
    head = f"- The EM iteration cap (a study beyond the paper): measured again with the run's cap {out['larger cap'] // out['cap']} times larger, "
    words = head + (
        f"{stand} of the {total} flips that read points where an EM reached it still stand"
        if total
        else "at the defaults whose points an EM reached it at (no flip read such a point)"
    )
    words += (
        f"; those that no longer do (undecided, or no decisive default to flip against): {', '.join(gone)}"
        if gone
        else ""
    )
    words += f"; the default's verdict moves for {', '.join(moved)}" if moved else "; no default's verdict moves"
    return words + "."


def larger_cap_metrics(out: dict) -> dict:
    """``{metric name: value}`` of :func:`flips_at_larger_cap`' result, for ``results.metric``: per claim and
    measurement (``default``, ``flip 1`` ...) each part's verdicts at both caps (with a flip's outcome) and the
    value at the larger cap."""
    m = {
        "flip_caps/cap": out["cap"],
        "flip_caps/larger_cap": out["larger cap"],
        "flip_caps/rerun": out.get("rerun", 0),
        "flip_caps/cpu_s": out["cpu_s"],
    }
    for cid, e in out["claims"].items():
        named = [("default", e["default"])] if e["default"] else []
        named += [(f"flip {i + 1}", f) for i, f in enumerate(e["flips"])]
        for key, f in named:
            outcome = {} if key == "default" else {p: o for p, *_, o in _outcome(f, e["reference"])}
            for p in f["parts"]:
                both = [f["before"].get(p), f["verdicts"].get(p)]
                m[f"flip_caps/{cid}/{key}/{p}/verdicts"] = both + ([outcome[p]] if p in outcome else [])
            m[f"flip_caps/{cid}/{key}/measured"] = f["pooled"]
    return m
