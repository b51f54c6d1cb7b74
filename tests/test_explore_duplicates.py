"""The explorer measures nothing twice: no claim is measured again at a configuration (as its ``DEPENDS`` sees it)
and seed it already measured, through every stage (replicates, sizing, one at a time, joint, pinned, condition
sizing, the subset search's pairs and triples and their sizing); and the subset search's bookkeeping, which keeps
each run's flips between rounds, decides exactly what the plain recomputation decides.
"""

import collections
import zlib

import numpy as np
import pytest

from tvtrack import conditions
from tvtrack.conditions import Run, _flips, unexplained_flips
from tvtrack.explore import explore
from tvtrack.montecarlo import Estimate, mean_ci
from tvtrack.register import Entry, Register, project
from tvtrack.verdicts import AllOf, InBand, Judgement

BAND = InBand("mean", -0.5, 0.5, "px")
REG = Register(
    [
        Entry("a", "regime", 0, (0, 1, 2), "world a"),
        Entry("b", "operating point", 0, (0, 1), "world b"),
        Entry("c", "reading", "x", ("x", "y"), "reading c"),
        Entry("d", "regime", 0, (0, 1), "world d"),
        Entry("e", "unreported setting", 0, (0, 1), "setting e"),
        Entry("f", "model", 0, (0, 1), "world f"),
    ],
    pinned=[{"a": 2, "b": 1, "c": "y", "d": 1, "e": 1, "f": 1}],
)
#: Overlapping DEPENDS: a condition's projection differs by claim, and many subsets of one claim's flip project onto
#: the same configuration for another.
DEPENDS = {"P": ["a", "b", "c", "d", "e"], "Q": ["a", "c", "d", "f"], "R": ["b", "d", "e", "f"]}
RULES = {"P": BAND, "Q": AllOf({"lo": BAND, "hi": BAND}), "R": BAND}


def _shift(cid: str, cfg: dict) -> float:
    """Planted effects: small single ones, a pair that flips Q's ``hi`` part, triples that flip P and R."""
    on = {k for k in DEPENDS[cid] if cfg[k] != REG.default()[k]}
    s = 0.1 * len(on)
    if cid == "P" and {"a", "c", "e"} <= on:
        s += 2.0
    if cid == "Q" and {"c", "f"} <= on:
        s += 2.0
    if cid == "R" and {"b", "d", "f"} <= on:
        s += 2.0
    return s


def _counting_measure():
    seen = collections.Counter()

    def measure(config, seed, claims=None):
        out = {}
        for cid in sorted(claims if claims is not None else DEPENDS):
            proj = project(config, DEPENDS[cid], REG.default())
            seen[(cid, tuple(sorted((k, repr(v)) for k, v in proj.items())), seed)] += 1
            rng = np.random.default_rng([seed, zlib.crc32(cid.encode())])
            m = mean_ci(rng.normal(_shift(cid, proj), 3.0, 80))  # one replicate decides nothing: conditions are sized
            out[cid] = {"lo": mean_ci(rng.normal(0.0, 3.0, 80)), "hi": m} if cid == "Q" else m
        return out

    return measure, seen


def _explore(measure):
    # a seed whose subset search reaches triples (the test needs every path that could repeat a run)
    return explore(measure, REG, RULES, seed=3, replicates=3, max_replicates=6, joint=8, depends=DEPENDS)


def _reference_unexplained_flips(rules, depends, default_j, runs, default, n_default, cache=None):
    """The search's bookkeeping as it was: every run's flips recomputed and every condition compared on each call."""
    explainers = [r for r in runs if r.stage != "replicate"]
    flips_of = {id(r): _flips(rules, default_j, r, n_default) for r in runs if r.stage != "replicate"}
    out = []
    for r in runs:
        if r.stage not in ("joint", "pinned"):
            continue
        ch = set(r.changed(default).items())
        todo, claims = set(), set()
        for key in flips_of[id(r)]:
            explained = any(key in flips_of[id(s)] and set(s.changed(default).items()) < ch for s in explainers)
            if not explained:
                todo |= {k for k, _ in ch if k in depends[key[0]]}
                claims.add(key[0])
        if len(todo) > 2:
            out.append((r, todo, frozenset(claims)))
    return out


def _comparable(ex) -> dict:
    """Every claim's record (its design's timing aside) and every run as measured."""
    recs = {}
    for cid in RULES:
        rec = ex.record(cid)
        rec["design"] = {k: v for k, v in rec["design"].items() if k != "timing"}
        recs[cid] = rec
    runs = [
        (
            r.stage,
            sorted(r.config.items(), key=repr),
            r.seed,
            repr(r.outputs),
            [(s.seed, repr(s.outputs)) for s in r.sized],
        )
        for r in ex.runs
    ]
    return {"records": recs, "runs": runs}


@pytest.fixture(scope="module")
def explored():
    measure, seen = _counting_measure()
    return _explore(measure), seen


def test_no_claim_is_measured_twice_at_a_configuration_and_seed(explored):
    ex, seen = explored
    combos = [r for r in ex.runs if r.stage == "combination"]
    # the search ran through pairs and triples, and sized some of them: every path that could repeat a run was taken
    assert {len(r.changed(ex.default)) for r in combos} == {2, 3}
    assert any(s.stage == "condition sizing" for r in combos for s in r.sized)
    assert sum(seen.values()) > 150
    assert max(seen.values()) == 1, [k for k, n in seen.items() if n > 1][:3]
    # the triples the measure plants are the ones the records name
    named = {
        cid: {tuple(sorted(f["changed"])) for p in ex.record(cid)["parts"].values() for f in p["flips"]}
        for cid in RULES
    }
    assert ("a", "c", "e") in named["P"] and ("c", "f") in named["Q"] and ("b", "d", "f") in named["R"]


def test_the_kept_flips_decide_what_the_plain_recomputation_decides(explored, monkeypatch):
    ex, _ = explored
    monkeypatch.setattr(conditions, "unexplained_flips", _reference_unexplained_flips)
    measure, seen = _counting_measure()
    reference = _explore(measure)
    assert _comparable(ex) == _comparable(reference)
    assert sum(seen.values()) == sum(explored[1].values())


def _exact_run(config, value, stage="joint"):
    return Run(dict(config), 1, stage, outputs={"X": Estimate.exact(value)}, scope=frozenset({"X"}))


def test_a_kept_flip_is_recomputed_once_the_run_it_belongs_to_grows():
    """A condition that agreed at its first run and flips once sized explains the joint flip from then on."""
    default = {"a": 0, "b": 0, "c": 0}
    rules, depends = {"X": BAND}, {"X": ["a", "b", "c"]}
    default_j = {("X", "claim"): Judgement("reproduced", "")}
    joint = _exact_run({"a": 1, "b": 1, "c": 1}, 3.0)
    joint.sized.append(Run(dict(joint.config), 2, "condition sizing", outputs={"X": Estimate.exact(3.0)}))
    pair = _exact_run({"a": 1, "b": 1, "c": 0}, 3.0, "combination")  # one replicate of the two needed: undecided
    runs = [joint, pair]
    kept: dict = {}
    first = unexplained_flips(rules, depends, default_j, runs, default, {"X": 2}, kept)
    assert [(r is joint, names) for r, names, _ in first] == [(True, {"a", "b", "c"})]
    pair.sized.append(Run(dict(pair.config), 2, "condition sizing", outputs={"X": Estimate.exact(3.0)}))
    # on the two replicates the default needed the pair flips too, and explains the joint flip
    assert unexplained_flips(rules, depends, default_j, runs, default, {"X": 2}, kept) == []
    assert unexplained_flips(rules, depends, default_j, runs, default, {"X": 2}) == []
