"""Claim records built from every paper's own claims, rules and register: each claim under each verdict, with
flips named by the register's real entries and phrases on every side (a reading of the text, an unreported
setting of the paper's experiment, a world beyond it, several changes together), shares with the agree/flip/
undecided counts and, for some, runs that lost lock. The measured values are the rules' synthetic ones (a value
each rule judges one way or the other) with a 5 % interval: what a sentence says about them is the point, not
the numbers. Used where no paper-profile run is at hand (``papermill_runs/reproduce/*/results.json``)."""

from __future__ import annotations

import importlib
from functools import lru_cache

from tvtrack.verdicts import AllOf, ByReading, NotCheckable, synthetic

PAPERS = (
    "p000_dissector_ekf",
    "p001_maneuver_occlusion_kf",
    "p002_unified_location_em",
    "p003_rotating_marker_tracker",
    "p004_laser_spot_prediction",
)
SIDES = ("reading", "setting", "world", "unattributed")


def paper_register(paper: str):
    """The paper's whole register (every entry any claim depends on)."""
    mod = importlib.import_module(f"tvtrack.papers.{paper}.register")
    for maker in ("build_register", "build"):
        if hasattr(mod, maker):
            return getattr(mod, maker)()
    return mod.REGISTER


def register_keys() -> set[str]:
    """Every entry name of every paper's register: the code names no reader should meet."""
    return {e.name for p in PAPERS for e in paper_register(p).entries}


def _widen(m):
    """A synthetic value with a 5 % interval (a part's dict, a vector or one estimate)."""
    if m is None:
        return None
    if isinstance(m, dict) and "reading" in m:
        return {"reading": m["reading"], "measured": _widen(m["measured"])}
    if isinstance(m, dict):
        return {k: _widen(v) for k, v in m.items()}
    if isinstance(m, list):
        return [_widen(v) for v in m]
    v = float(m.value)
    h = 0.05 * max(abs(v), 1e-3)
    return {"value": v, "se": h / 1.96, "ci_low": v - h, "ci_high": v + h, "n": 400}


def _measured(rule, verdict: str, register):
    if isinstance(rule, ByReading):
        value = register[rule.entry].default if rule.entry in register.names else next(iter(rule.rules), None)
        return ByReading.tag(value, _measured(rule.for_value(value), verdict, register))
    if isinstance(rule, AllOf):
        return {n: _measured(r, verdict, register) for n, r in rule.parts.items() if not isinstance(r, NotCheckable)}
    return _widen(synthetic(rule, "not reproduced" if verdict == "not reproduced" else "reproduced"))


def _flips(entries, k: int, verdict: str) -> list[dict]:
    """One flip per side, from the claim's entries (rotated by ``k`` so that every entry is named somewhere)."""
    flips = []
    for i, side in enumerate(SIDES):
        if not entries:
            break
        e = entries[(k + i) % len(entries)]
        if not e.alternatives:
            continue
        value = e.alternatives[0]
        changed = {e.name: value}
        text = e.phrase(value)
        if side == "unattributed" and len(entries) > 1:
            other = entries[(k + i + 1) % len(entries)]
            if other.alternatives:
                changed[other.name] = other.alternatives[0]
                text += " and " + other.phrase(other.alternatives[0])
        kind = "single" if len(changed) == 1 else "joint"
        flips.append({"changed": changed, "side": side, "kind": kind, "verdict": verdict, "text": text})
    return flips


def _part(verdict: str, flips: list[dict], lost: bool) -> dict:
    part = {
        "verdict": verdict,
        "label": {"reproduced": "limited", "not reproduced": "depends", "undecided": "-"}[verdict],
        "share": {"agree": 40, "flip": 8, "undecided": 4, "design": 52, "decided": 48, "value": 40 / 48,
                  "ci_low": 0.7, "ci_high": 0.93},
        "flips": flips if verdict != "undecided" else [],
        "runs_to_decide": (
            {"replicates": 320, "now": 10, "runs": 25528,
             "text": "undecided at 10 replicates: about 320 independent replicates (25528 runs) would decide it, "
                     "beyond the cap of 10"}
            if verdict == "undecided" else None
        ),
    }  # fmt: skip
    if lost:
        part.update(lost_share=0.3, in_lock_verdict="reproduced", decided_by_lost_runs=True)
    return part


def _record(paper: str, cid: str, rule, claim: dict, verdict: str, register, depends, note: str, k: int) -> dict:
    rd = rule.to_dict()
    if isinstance(rule, NotCheckable):
        return {**claim, "id": cid, "rule": rd, "acceptance": rd["text"], "measured": None, "verdict": "not checkable",
                "decision": "", "note": note, "robustness": None}  # fmt: skip
    entries = [register[n] for n in depends if n in register.names]
    flips = _flips(entries, k, "not reproduced" if verdict == "reproduced" else "reproduced")
    shown = rule.for_value(_measured(rule, verdict, register)["reading"]) if isinstance(rule, ByReading) else rule
    names = (
        [n for n, r in shown.parts.items() if not isinstance(r, NotCheckable)]
        if isinstance(shown, AllOf)
        else ["claim"]
    )
    parts = {n: _part(verdict, flips, lost=(k % 7 == 0 and i == 0)) for i, n in enumerate(names)}
    return {
        **claim,
        "id": cid,
        "rule": rd,
        "acceptance": rd["text"],
        "measured": _measured(rule, verdict, register),
        "verdict": verdict,
        "decision": "",
        "note": note,
        "robustness": {
            "label": parts[names[0]]["label"],
            "provisional": False,
            "where": [],
            "coverage": "",
            "parts": parts,
            "conditions": [],
            "register": [e.to_dict() for e in entries],
            "design": {"joint": 32, "replicates": 3},
        },
    }


@lru_cache(maxsize=1)
def paper_records() -> tuple[dict, ...]:
    """Every claim of every paper, once per verdict (reproduced, not reproduced, undecided; a not-checkable claim
    once)."""
    out = []
    k = 0
    for paper in PAPERS:
        claims_mod = importlib.import_module(f"tvtrack.papers.{paper}.claims")
        reg_mod = importlib.import_module(f"tvtrack.papers.{paper}.register")
        register = paper_register(paper)
        notes = getattr(claims_mod, "NOTES", {})
        for cid, rule in claims_mod.RULES.items():
            claim = dict(claims_mod.CLAIMS[cid])
            note = notes.get(cid, "") or (rule.reason if isinstance(rule, NotCheckable) else "")
            depends = list(getattr(reg_mod, "DEPENDS", {}).get(cid, register.names))
            verdicts = (
                ("not checkable",) if isinstance(rule, NotCheckable) else ("reproduced", "not reproduced", "undecided")
            )
            for verdict in verdicts:
                out.append(_record(paper, cid, rule, claim, verdict, register, depends, note, k))
                k += 1
    return tuple(out)
