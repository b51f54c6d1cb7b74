"""Do the flips that read capped points survive a larger EM iteration cap? A study beyond the paper, beside
:mod:`.flip_caps` (which counts them) and :mod:`.cap_check` (which reruns Fig 6b's points).

Where a claim's flipping condition (or its register default) reads simulation points at which an EM reached the
run's iteration cap, :func:`flips_at_larger_cap` measures the claim again on the same replicate seeds with a cap
:data:`.cap_check.CAP_FACTOR` times larger (``Scale.cap_factor``; a reading that sets its own cap, "plain EM, cap
100", keeps it) and judges it by the same rule, pooled as the explorer pools a condition's replicates. So the flip
is compared at the same size on the same scenes: only the capped trials can change, since a trial that never reached
the cap gives the same estimates bit for bit at the larger cap (:mod:`.cap_check`). The simulations whose trials at
the run's cap never reached it are therefore taken from the run's cache under the larger cap's key
(:func:`_reuse_uncapped`), and only those with a capped trial run again (and are cached; none of the claims' values
read the larger cap's keys).

Units: shares of trials; the verdicts are the rules'.
"""

from __future__ import annotations

from dataclasses import replace

from tvtrack.jobs import cpu_seconds
from tvtrack.labels import part_judgements
from tvtrack.pooling import pool
from tvtrack.projection import claim_groups

from . import study
from .cap_check import CAP_FACTOR
from .flip_caps import CAPPED, cap_counts, capped_flags, capped_shares
from .register import DEPENDS, REGISTER

__all__ = ["at_larger_cap", "flips_at_larger_cap", "larger_cap_sentence", "larger_cap_metrics"]


def _jobs(changed: dict, seed: int, scale, claim: str) -> list:
    default = REGISTER.default()
    return [
        j
        for config, claims in claim_groups({**default, **changed}, {claim}, DEPENDS, default)
        for j in study.jobs_of(config, seed, scale, claims=claims)
    ]


def _reuse_uncapped(changed: dict, seeds, scale, big, claim: str) -> int:
    """Cache, under the larger cap's job keys (``big``: the larger cap's scale), each simulation of ``claim``'s
    points that ran at the run's cap (``scale``) with no trial reaching it: its estimates are the same bit for bit.
    Returns the number of simulations left to run."""
    left = 0
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
                left += 1
    return left


def _measure_all(tasks: list, scale, factor: int) -> list[dict]:
    """Each task ``(claim, changed, seeds)`` measured at the larger cap, every task's simulations in one batch (the
    scale's worker processes): per task ``pooled`` (the claim's value pooled over the seeds, as the explorer pools a
    condition's replicates), ``counts`` (:func:`.flip_caps.cap_counts` at the larger cap) and ``rerun``
    (simulations run again, the others reused)."""
    big = replace(scale, cap_factor=int(factor) * scale.cap_factor)
    rerun = [_reuse_uncapped(changed, seeds, scale, big, cid) for cid, changed, seeds in tasks]
    default = REGISTER.default()
    configs = [{**default, **changed} for _, changed, seeds in tasks for _ in seeds]
    asked = [{cid} for cid, _, seeds in tasks for _ in seeds]
    ms = iter(study.measure_batch(configs, [s for *_, seeds in tasks for s in seeds], big, asked))
    return [
        {
            "pooled": pool([next(ms)[cid] for _ in seeds]),
            "counts": cap_counts(changed, seeds, big, cid),
            "rerun": k,
        }
        for (cid, changed, seeds), k in zip(tasks, rerun)
    ]


def at_larger_cap(changed: dict, seeds, scale, claim: str, rule, factor: int = CAP_FACTOR) -> dict:
    """``claim`` measured with the register default changed by ``changed`` on ``seeds`` with the run's EM iteration
    cap ``factor`` times larger, pooled over the seeds (:func:`tvtrack.pooling.pool`).

    Returns
    -------
    dict
        ``pooled`` (the claim's measured value), ``verdicts`` (``{part: verdict}`` by ``rule``), ``counts``
        (:func:`.flip_caps.cap_counts` at the larger cap), ``rerun`` (simulations run again).
    """
    out = _measure_all([(claim, changed, list(seeds))], scale, factor)[0]
    return {**out, "verdicts": _verdicts(rule, out["pooled"])}


def _run_cap_hit(counts: dict | None, cap: int) -> bool:
    """Whether some trial of ``counts`` reached the run's cap ``cap`` (not only a cap a condition sets)."""
    return bool(capped_shares(counts)) and cap in (counts or {}).get("caps", ())


def _verdicts(rule, measured) -> dict:
    return {p: j.verdict for p, j in part_judgements(rule, measured).items()}


def flips_at_larger_cap(exploration, caps: dict, rules: dict, scale, cap: int, factor: int = CAP_FACTOR) -> dict:
    """Per claim of :func:`.flip_caps.flip_caps`' result ``caps`` that reads points where some trial reached the
    run's cap ``cap``: ``{"default": {...} or None, "flips": [{...}]}``, each with ``changed``, ``parts`` (the parts
    the condition flips; at the default every part), ``seeds``, ``before`` (``{part: verdict}`` at the run's cap,
    the run's own replicates pooled) and :func:`at_larger_cap`'s keys, and ``reference`` (the default's ``{part:
    verdict}`` a flip is judged against: at the larger cap where the default was rerun, else the run's); and
    ``cap``, ``larger cap``, ``cpu_s`` (this process and its workers). Every measurement runs in one batch."""
    t0 = cpu_seconds()
    reps = [r.seed for r in exploration.replicates()]
    entries, tasks = {}, []  # tasks: (claim, changed, seeds, the record the measurement completes)
    for cid, c in caps.items():
        rule = rules[cid]
        before = _verdicts(rule, pool([r.outputs[cid] for r in exploration.replicates()]))
        entry = entries[cid] = {"default": None, "flips": [], "reference": before}
        if _run_cap_hit(cap_counts({}, reps, scale, cid), cap):  # every replicate of the default, not the first
            entry["default"] = {"changed": {}, "parts": list(before), "seeds": reps, "before": before}
            tasks.append((cid, {}, reps, entry["default"]))
        for f in c["flips"]:
            if not _run_cap_hit(f["counts"], cap):
                continue
            run = _run_of(exploration, cid, f["changed"])
            g = {"changed": f["changed"], "parts": f["parts"], "seeds": _seeds(run, cid)}
            entry["flips"].append({**g, "before": _verdicts(rule, run.pooled(cid))})
            tasks.append((cid, f["changed"], g["seeds"], entry["flips"][-1]))
    for (cid, *_, record), m in zip(tasks, _measure_all([t[:3] for t in tasks], scale, factor)):
        record.update(m, verdicts=_verdicts(rules[cid], m["pooled"]))
    for e in entries.values():
        if e["default"]:
            e["reference"] = e["default"]["verdicts"]
    out = {cid: e for cid, e in entries.items() if e["default"] or e["flips"]}
    return {"claims": out, "cap": cap, "larger cap": cap * int(factor), "cpu_s": cpu_seconds() - t0}


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
    """Per flipped part of ``f``: ``(part, verdict at the run's cap, at the larger cap, whether it still flips)``,
    a flip still standing where the larger cap's verdict is decisive and not the default's (``ref``)."""
    rows = []
    for p in f["parts"]:
        after = f["verdicts"].get(p, "undecided")
        rows.append((p, f["before"].get(p, "undecided"), after, after not in ("undecided", ref.get(p))))
    return rows


def _part(p: str) -> str:
    return "its verdict" if p == "claim" else f'part "{p}"'


def _default_words(d: dict) -> str:
    """At the default: whether any part's verdict moves at the larger cap (``d``: the default's entry)."""
    moved = [p for p in d["parts"] if d["before"].get(p) != d["verdicts"].get(p)]
    head = f"at the default ({len(d['seeds'])} replicates pooled) "
    if not moved:
        return head + "every verdict is the same as at the run's cap"
    return head + "; ".join(f"{_part(p)} {d['before'][p]} -> {d['verdicts'][p]}" for p in moved)


def _flip_words(f: dict, ref: dict) -> str:
    rows = _outcome(f, ref)
    still = capped_shares(f["counts"])  # the algorithms still at the (larger) cap, share of their trials
    return (
        REGISTER.describe(f["changed"])
        + " ("
        + ", ".join(f"{_part(p)}: {a} -> {b}" for p, a, b, _ in rows)
        + "".join(f", {n} still at the cap in {s:.0%} of its trials" for n, s in still.items())
        + ")"
    )


def larger_cap_sentence(out: dict) -> str:
    """The words of :func:`flips_at_larger_cap`' result ``out``: per claim, the default's verdicts where it was
    rerun, each flipping condition's verdicts at the run's cap and at the larger one, whether the flip stands, and the
    share of trials still at the larger cap."""
    if not out["claims"]:
        return ""
    said = []
    for cid, e in out["claims"].items():
        bits = [_default_words(e["default"])] if e["default"] else []
        if e["flips"]:
            stands = [all(r[3] for r in _outcome(f, e["reference"])) for f in e["flips"]]
            bits.append(
                f"{sum(stands)} of the {len(stands)} flipping conditions that read capped points still flip it, "
                f"{len(stands) - sum(stands)} do not: " + "; ".join(_flip_words(f, e["reference"]) for f in e["flips"])
            )
        said.append(f"{cid} " + "; ".join(bits))
    return (
        f"Rerun with the run's EM iteration cap {out['larger cap'] // out['cap']} times larger ({out['cap']:,} -> "
        f"{out['larger cap']:,} iterations; a condition's own cap kept) on the same replicate seeds, the claims and "
        "flipping conditions that read points where an EM reached the cap (verdict at the run's cap -> at the "
        "larger one, the replicates pooled as before): " + ". ".join(said) + "."
    )


def larger_cap_metrics(out: dict) -> dict:
    """``{metric name: value}`` of :func:`flips_at_larger_cap`' result, for ``results.metric``."""
    m = {"flip_caps/cap": out["cap"], "flip_caps/larger_cap": out["larger cap"], "flip_caps/cpu_s": out["cpu_s"]}
    for cid, e in out["claims"].items():
        named = ([("default", e["default"])] if e["default"] else []) + [
            (f"flip {i + 1}", f) for i, f in enumerate(e["flips"])
        ]
        for key, f in named:
            for p in f["parts"]:
                m[f"flip_caps/{cid}/{key}/{p}/verdicts"] = [f["before"].get(p), f["verdicts"].get(p)]
            m[f"flip_caps/{cid}/{key}/measured"] = f["pooled"]
    return m
