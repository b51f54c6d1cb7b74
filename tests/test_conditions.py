"""The explorer's conditions (:mod:`tvtrack.conditions`) on hand-built runs and rules whose answer is known by
construction: the projection to each claim's entries, a condition decided only on at least the default's replicates
and sized to them on the default's seeds, what leans towards a flip, the sizing budget, and the smallest subset that
explains a joint flip.

The rule throughout is ``Ordering("a", "b")`` on a difference (reproduced when the interval lies above 0). A
replicate measures ``v +- h`` (a large-sample interval, nominal coverage); ``k`` equal replicates pool on the linear
scale to ``v +- h / sqrt(k)`` whenever ``v - h <= 0``. So ``-0.3 +- 0.5`` is undecided on 1 and 2 replicates (half
width 0.354) and not reproduced from 3 (0.289 < 0.3): a flip that needs 3 replicates; ``-1 +- 0.5`` flips on one."""

from __future__ import annotations

import math

import pytest

from tvtrack.conditions import (
    SUBSET_ROUND,
    Run,
    SizingBudget,
    condition_verdicts,
    lean_of_singles,
    leans_flip,
    point,
    projected_runs,
    search_subsets,
    size_conditions,
    subset_configs,
    unexplained_flips,
)
from tvtrack.conditions import _target
from tvtrack.estimate import Estimate
from tvtrack.verdicts import AllOf, ByReading, InBand, Judgement, Ordering, Rule

NAN = float("nan")
RULE = Ordering("a", "b")
RULES = {"X": RULE}
DEFAULT = {"a": 0, "b": 0, "c": 0, "d": 0}
SEEDS = [100, 101, 102, 103, 104, 105, 106, 107]
REPRODUCED = Judgement("reproduced", "default")
NOT_REPRODUCED = Judgement("not reproduced", "default")
UNDECIDED = Judgement("undecided", "default", False, math.inf)
DEFAULT_J = {("X", "claim"): REPRODUCED}


def est(v: float, h: float = 0.5) -> Estimate:
    return Estimate(v, NAN, v - h, v + h, 10, 0.95, "large-sample normal")


AGREE, FLIP, SLOW_FLIP, FAR = est(1.0), est(-1.0), est(-0.3), est(-0.05)  # FAR: projected at (0.5/0.05)^2 = 100x


def cond(config: dict, outputs: dict, stage: str = "single", scope=("X",), seed: int = SEEDS[0]) -> Run:
    r = Run({**DEFAULT, **config}, seed, stage, scope=None if scope is None else frozenset(scope))
    r.outputs = dict(outputs)
    return r


def stage_runner(measure, log: list | None = None):
    """A ``run_stage`` that measures each job's asked claims at its configuration and seed (and logs the call)."""

    def run_stage(m, jobs, stage):
        assert m is measure
        if log is not None:
            log.append((stage, [(j.seed, j.claims) for j in jobs]))
        for j in jobs:
            out = measure(j.config, j.seed)
            j.outputs.update({c: v for c, v in out.items() if j.claims is None or c in j.claims})

    return run_stage


def const(**values):
    """A measure whose every claim is the same at every seed (its value at the configuration given)."""

    def measure(config, seed):
        return {cid: f(config) for cid, f in values.items()}

    return measure


# --- Run ---------------------------------------------------------------------------------------------------------


def test_a_run_knows_its_changes_its_claims_and_its_replicates():
    r = Run({"a": 1, "b": 0, "e": 5}, 7, "single", outputs={"X": AGREE, "Y": FLIP}, scope=frozenset({"X"}))
    assert r.changed({"a": 0, "b": 0}) == {"a": 1, "e": 5}  # an entry the default lacks counts as changed
    assert r.counts_for("X") and not r.counts_for("Y") and not r.counts_for("Z")  # Y is out of scope, Z unmeasured
    assert r.replicates("Y") == [] and r.pooled("Y") is None and r.n_runs("Y") == 0
    everyone = Run({"a": 1}, 7, "joint", outputs={"Y": FLIP})
    assert everyone.counts_for("Y") and everyone.n_runs("Y") == 1  # no scope: every measured claim counts
    more = Run({"a": 1}, 8, "condition sizing", outputs={"X": est(1.0, 0.4)}, claims=frozenset({"X"}))
    other = Run({"a": 1}, 9, "condition sizing", outputs={"X": est(9.0)}, claims=frozenset({"Y"}))  # not asked for X
    anyone = Run({"a": 1}, 10, "condition sizing", outputs={"X": est(1.0, 0.3)}, claims=None)
    r.sized += [more, other, anyone]
    assert r.replicates("X") == [AGREE, est(1.0, 0.4), est(1.0, 0.3)] and r.n_runs("X") == 3
    assert r.pooled("X").value == pytest.approx(1.0) and r.pooled("X").n == 30


def test_a_screened_value_is_no_replicate_but_stands_alone_until_sized():
    screen = est(-1.0, 2.0)
    r = Run({"a": 1}, 7, "joint", outputs={"X": screen}, scope=frozenset({"X"}), screened=frozenset({"X"}))
    assert r.replicates("X") == [] and r.n_runs("X") == 0 and r.pooled("X") is screen
    r.sized.append(Run({"a": 1}, 7, "condition sizing", outputs={"X": FLIP}, claims=frozenset({"X"})))
    assert r.replicates("X") == [FLIP] and r.pooled("X") is FLIP and r.n_runs("X") == 1


# --- projection ----------------------------------------------------------------------------------------------------


DEPENDS = {"A": ["a"], "B": ["b"], "C": ["a", "b"]}


def test_each_claim_runs_at_its_projection_and_claims_sharing_one_share_a_run():
    have: dict = {}
    runs = projected_runs([{**DEFAULT, "a": 1, "b": 1, "c": 1}], "joint", DEPENDS, DEFAULT, 42, have)
    got = {(tuple(sorted(r.changed(DEFAULT).items())), r.claims, r.scope, r.seed, r.stage) for r in runs}
    assert got == {
        ((("a", 1),), frozenset({"A"}), frozenset({"A"}), 42, "joint"),
        ((("b", 1),), frozenset({"B"}), frozenset({"B"}), 42, "joint"),
        ((("a", 1), ("b", 1)), frozenset({"C"}), frozenset({"C"}), 42, "joint"),
    }
    assert all(r.config["c"] == 0 and r.config["d"] == 0 for r in runs)  # c is no claim's: never changed
    shared = projected_runs([{**DEFAULT, "a": 2}], "single", DEPENDS, DEFAULT, 42, have)
    assert len(shared) == 1 and shared[0].claims == shared[0].scope == frozenset({"A", "C"})  # same projection
    assert shared[0].config == {**DEFAULT, "a": 2}


def test_a_claim_is_never_measured_twice_at_a_projection_and_a_change_it_does_not_read_runs_nothing():
    have: dict = {}
    first = projected_runs([{**DEFAULT, "a": 1}], "single", DEPENDS, DEFAULT, 1, have)
    assert [r.claims for r in first] == [frozenset({"A", "C"})]
    # a joint whose projection for A equals the single's: A is not measured again there, B and C are new
    again = projected_runs([{**DEFAULT, "a": 1, "b": 1}], "joint", DEPENDS, DEFAULT, 1, have)
    assert sorted(sorted(r.claims) for r in again) == [["B"], ["C"]]
    assert projected_runs([{**DEFAULT, "c": 1}, {**DEFAULT, "a": 1}], "joint", DEPENDS, DEFAULT, 1, have) == []
    # two configurations in one call with the same projection: one run
    one = projected_runs(
        [{**DEFAULT, "b": 2, "c": 1}, {**DEFAULT, "b": 2, "d": 1}], "joint", {"B": ["b"]}, DEFAULT, 1, {}
    )
    assert len(one) == 1 and one[0].config == {**DEFAULT, "b": 2}


def test_only_restricts_each_configuration_to_its_claims():
    cfgs = [{**DEFAULT, "a": 1, "b": 1}, {**DEFAULT, "a": 3}]
    runs = projected_runs(cfgs, "combination", DEPENDS, DEFAULT, 1, {}, only=[frozenset({"C"}), None])
    got = sorted((tuple(sorted(r.changed(DEFAULT).items())), tuple(sorted(r.claims))) for r in runs)
    assert got == [((("a", 1), ("b", 1)), ("C",)), ((("a", 3),), ("A", "C"))]


# --- decided only on the default's replicates ----------------------------------------------------------------------


def test_a_condition_decides_only_on_at_least_the_replicates_the_default_needed():
    r = cond({"a": 1}, {"X": FLIP, "Y": FLIP}, scope=("X", "Y"))
    rules = {"X": RULE, "Y": RULE, "Z": RULE}  # Z is not measured here: no verdict for it
    assert condition_verdicts(rules, r, {"X": 1, "Y": 2}) == {
        ("X", "claim"): "not reproduced",
        ("Y", "claim"): "undecided",
    }
    r.sized.append(Run(r.config, SEEDS[1], "condition sizing", outputs={"Y": FLIP}, claims=frozenset({"Y"})))
    assert condition_verdicts(rules, r, {"X": 1, "Y": 2})[("Y", "claim")] == "not reproduced"  # 2 of 2: decided
    assert condition_verdicts(rules, r, {"X": 2, "Y": 3}) == {("X", "claim"): "undecided", ("Y", "claim"): "undecided"}
    assert condition_verdicts(rules, r, {})[("X", "claim")] == "not reproduced"  # no count stated: none needed
    screened = cond({"a": 1}, {"X": FLIP})
    screened.screened = frozenset({"X"})  # no full-size replicate: decides only where no count is stated
    assert condition_verdicts(rules, screened, {}) == {("X", "claim"): "not reproduced"}
    assert condition_verdicts(rules, screened, {"X": 1}) == {("X", "claim"): "undecided"}
    out_of_scope = cond({"a": 1}, {"X": FLIP, "Y": FLIP}, scope=("Y",))
    assert condition_verdicts(rules, out_of_scope, {}) == {("Y", "claim"): "not reproduced"}


def test_each_part_of_a_condition_is_judged_and_held_to_the_count():
    rule = AllOf({"gap": RULE, "level": InBand("level", 0.0, 2.0)})
    r = cond({"a": 1}, {"X": {"gap": FLIP, "level": est(1.0, 0.5)}})
    assert condition_verdicts({"X": rule}, r, {"X": 1}) == {
        ("X", "gap"): "not reproduced",
        ("X", "level"): "reproduced",
    }
    assert condition_verdicts({"X": rule}, r, {"X": 2}) == {("X", "gap"): "undecided", ("X", "level"): "undecided"}


# --- the replicates a condition should reach next (_target) -------------------------------------------------------


def test_the_target_is_the_defaults_count_while_smaller_capped():
    r = cond({"a": 1}, {"X": AGREE})  # decided on one replicate, but the default needed 4
    assert _target(RULE, r, "X", DEFAULT_J, 4, 8) == 4
    assert _target(RULE, r, "X", DEFAULT_J, 10, 8) == 8  # never beyond the cap
    assert _target(RULE, r, "X", DEFAULT_J, 1, 8) == 1  # decided on as many as the default: nothing to add
    assert _target(RULE, r, "X", DEFAULT_J, 4, 1) == 1  # at the cap already


def test_the_target_is_one_more_while_undecided_and_projected_within_the_cap():
    slow = cond({"a": 1}, {"X": SLOW_FLIP})  # projected at (0.5/0.3)^2 = 2.78 times one replicate
    assert _target(RULE, slow, "X", DEFAULT_J, 1, 8) == 2
    assert _target(RULE, slow, "X", DEFAULT_J, 1, 3) == 2  # ceil(2.78) = 3 fits a cap of 3
    assert _target(RULE, slow, "X", DEFAULT_J, 1, 2) == 1  # but not a cap of 2
    near = cond({"a": 1}, {"X": est(-0.4)})  # (0.5 / 0.4)^2 = 1.56: two replicates, exactly a cap of 2
    assert _target(RULE, near, "X", DEFAULT_J, 1, 2) == 2
    assert _target(RULE, cond({"a": 1}, {"X": FAR}), "X", DEFAULT_J, 1, 99) == 1  # 100 > 99
    assert _target(RULE, cond({"a": 1}, {"X": FAR}), "X", DEFAULT_J, 1, 100) == 2  # 100 fits exactly
    on_edge = cond({"a": 1}, {"X": est(0.0)})  # the point on the reference: no number of runs decides it
    assert _target(RULE, on_edge, "X", DEFAULT_J, 1, 8) == 1
    assert _target(RULE, on_edge, "X", DEFAULT_J, 3, 8) == 3  # yet it is held to the default's count


def test_the_target_leaves_a_condition_alone_where_the_default_decides_no_part():
    slow = cond({"a": 1}, {"X": SLOW_FLIP})
    assert _target(RULE, slow, "X", {("X", "claim"): UNDECIDED}, 4, 8) == 1
    assert _target(RULE, slow, "X", {("Y", "claim"): REPRODUCED}, 4, 8) == 1
    assert _target(RULE, slow, "X", {("X", "claim"): NOT_REPRODUCED}, 4, 8) == 4  # either decisive verdict counts


def test_a_part_the_default_leaves_undecided_asks_nothing_of_the_condition():
    rule = AllOf({"gap": RULE, "level": InBand("level", 0.0, 2.0)})
    r = cond({"a": 1}, {"X": {"gap": AGREE, "level": est(1.8, 0.3)}})  # level straddles 2: (0.3 / 0.2)^2 = 2.25
    only_level = {("X", "level"): REPRODUCED, ("X", "gap"): UNDECIDED}
    assert _target(rule, r, "X", only_level, 1, 8) == 2
    only_gap = {("X", "gap"): REPRODUCED, ("X", "level"): UNDECIDED}
    assert _target(rule, r, "X", only_gap, 1, 8) == 1


# --- leaning towards a flip -------------------------------------------------------------------------------------------


def test_what_leans_towards_a_flip():
    lean = lambda out, dj=DEFAULT_J: leans_flip(RULE, cond({"a": 1}, {"X": out}), "X", dj)  # noqa: E731
    assert lean(FLIP)  # decisive the other way
    assert not lean(AGREE)  # decisive the same way
    assert lean(SLOW_FLIP)  # undecided, its point on the other side
    assert not lean(est(0.3))  # undecided, its point on the default's side
    assert not lean(FLIP, {("X", "claim"): UNDECIDED})  # nothing decided at the default to flip
    assert not lean(FLIP, {})
    assert not lean(AGREE, {("X", "claim"): REPRODUCED, ("Y", "claim"): NOT_REPRODUCED})
    assert lean(AGREE, {("X", "claim"): NOT_REPRODUCED})
    assert not lean(est(-0.3), {("X", "claim"): NOT_REPRODUCED})


def test_every_part_is_read_for_a_lean_not_only_the_first():
    rule = AllOf({"gap": RULE, "level": InBand("level", 0.0, 2.0)})
    dj = {("X", "gap"): REPRODUCED, ("X", "level"): REPRODUCED}
    r = cond({"a": 1}, {"X": {"gap": AGREE, "level": est(2.2, 0.5)}})  # level undecided, point above the band
    assert leans_flip(rule, r, "X", dj)
    r = cond({"a": 1}, {"X": {"gap": AGREE, "level": est(1.8, 0.5)}})  # level undecided, point inside
    assert not leans_flip(rule, r, "X", dj)
    r = cond({"a": 1}, {"X": {"gap": SLOW_FLIP, "level": est(1.0, 0.5)}})
    assert leans_flip(rule, r, "X", dj)
    only_level = {("X", "level"): REPRODUCED}  # gap's lean counts only if the default decides it
    assert not leans_flip(rule, r, "X", only_level)
    r = cond({"a": 1}, {"X": {"gap": SLOW_FLIP, "level": est(2.2, 0.5)}})  # level, after gap, leans
    assert leans_flip(rule, r, "X", {("X", "gap"): UNDECIDED, ("X", "level"): REPRODUCED})


class _OnlyIntervals(Rule):
    """A rule that cannot judge an exact point (raises), undecided on any interval."""

    def text(self):
        return "only intervals"

    def judge(self, measured):
        if isinstance(measured, Estimate) and measured.method == "exact":
            raise ValueError("cannot judge a point")
        return Judgement("undecided", "never decides", False)


class _DecidesIntervals(_OnlyIntervals):
    """A rule that reproduces every interval and cannot judge a point."""

    def judge(self, measured):
        super().judge(measured)
        return Judgement("reproduced", "every interval")


def test_a_value_that_cannot_be_judged_as_a_point_leans_towards_a_flip():
    assert leans_flip(_OnlyIntervals(), cond({"a": 1}, {"X": SLOW_FLIP}), "X", DEFAULT_J)


def test_a_part_decided_the_defaults_way_leans_towards_agreement_without_reading_its_point():
    assert not leans_flip(_DecidesIntervals(), cond({"a": 1}, {"X": SLOW_FLIP}), "X", DEFAULT_J)


# A reading of the paper whose rule has a part the default reading's lacks ("at every P > 0.5"): that part must hold
# too, so where it fails the claim's labelled part flips (labels.part_judgements); the lean must read it the same way.
READING = ByReading("reading", {"every": AllOf({"p": InBand("p", 0.0, 2.0), "q": InBand("q", 0.0, 2.0)})},
                    AllOf({"p": InBand("p", 0.0, 2.0)}))  # fmt: skip
READING_J = {("X", "p"): REPRODUCED}


def _reading(p, q):
    return cond({"d": 1}, {"X": ByReading.tag("every", {"p": p, "q": q})})


def test_a_part_that_flips_through_a_readings_extra_part_leans_towards_the_flip():
    """p holds, the reading's extra part q lies wholly above its band: the labelled part p is not reproduced (a
    flip, decisive on one replicate), so the condition leans towards it, however p alone reads."""
    r = _reading(AGREE, est(5.0))
    assert condition_verdicts({"X": READING}, r, {"X": 1}) == {("X", "p"): "not reproduced"}
    assert leans_flip(READING, r, "X", READING_J)
    assert leans_flip(READING, _reading(AGREE, est(2.2, 0.5)), "X", READING_J)  # q undecided, its point outside
    assert not leans_flip(READING, _reading(AGREE, est(1.8, 0.5)), "X", READING_J)  # q undecided, its point inside
    assert not leans_flip(READING, _reading(AGREE, AGREE), "X", READING_J)  # both hold: agreement
    assert leans_flip(READING, _reading(est(5.0), AGREE), "X", READING_J)  # p itself fails


def test_a_flip_through_a_readings_extra_part_is_sized_to_the_defaults_count_whatever_the_budget():
    """The default needed 3 replicates: the flipping condition is sized to 3 with no budget for agreement, and then
    flips; it is never left by the budget as one leaning towards agreement."""
    flipping = ByReading.tag("every", {"p": AGREE, "q": est(5.0)})
    measure = const(X=lambda c: flipping)
    r = cond({"d": 1}, {"X": flipping})
    budget = SizingBudget(0)
    added = size_conditions(measure, {"X": READING}, [r], READING_J, {"X": 3}, SEEDS, 8, stage_runner(measure), budget)
    assert added == 2 and r.n_runs("X") == 3 and r.left == {} and budget.left == 0
    assert condition_verdicts({"X": READING}, r, {"X": 3}) == {("X", "p"): "not reproduced"}


def test_a_numeric_reading_is_kept_when_its_parts_are_read_at_their_points():
    """Readings named by numbers (a threshold P = 0.9): the point check must still judge under the reading's rule,
    whose extra part q is undecided with its point above the band: a lean towards the flip."""
    parts = AllOf({"p": InBand("p", 0.0, 2.0), "q": InBand("q", 0.0, 2.0)})
    rule = ByReading("P", {0.9: parts}, AllOf({"p": InBand("p", 0.0, 2.0)}))
    leaning = cond({"d": 1}, {"X": ByReading.tag(0.9, {"p": AGREE, "q": est(2.2, 0.5)})})
    assert leans_flip(rule, leaning, "X", READING_J)
    agreeing = cond({"d": 1}, {"X": ByReading.tag(0.9, {"p": AGREE, "q": est(1.8, 0.5)})})
    assert not leans_flip(rule, agreeing, "X", READING_J)
    # a reading within a reading, each named by a number
    nested = ByReading("mode", {"every": rule}, AllOf({"p": InBand("p", 0.0, 2.0)}))
    tagged = ByReading.tag("every", ByReading.tag(0.9, {"p": AGREE, "q": est(2.2, 0.5)}))
    assert leans_flip(nested, cond({"d": 1}, {"X": tagged}), "X", READING_J)


def test_a_single_rule_claim_flips_through_a_readings_parts():
    """The default reading is one rule ("claim"); the reading's rule has parts of its own, all of which must hold."""
    rule = ByReading("reading", {"every": AllOf({"q": InBand("q", 0.0, 2.0)})}, InBand("p", 0.0, 2.0))
    r = cond({"d": 1}, {"X": ByReading.tag("every", {"q": est(5.0)})})
    assert condition_verdicts({"X": rule}, r, {"X": 1}) == {("X", "claim"): "not reproduced"}
    assert leans_flip(rule, r, "X", DEFAULT_J)
    assert not leans_flip(rule, cond({"d": 1}, {"X": ByReading.tag("every", {"q": AGREE})}), "X", DEFAULT_J)
    two = ByReading("reading", {"every": AllOf({"q": InBand("q", 0.0, 2.0)})}, AllOf({"p": RULE, "r": RULE}))
    unmeasured = cond({"d": 1}, {"X": ByReading.tag("every", {"q": est(5.0)})})  # neither labelled part measured
    assert not leans_flip(two, unmeasured, "X", {("X", "p"): REPRODUCED, ("X", "r"): REPRODUCED})


def test_the_lean_of_a_single_reading_counts_its_extra_parts():
    r = cond({"d": "every"}, {"X": ByReading.tag("every", {"p": AGREE, "q": est(5.0)})})
    assert lean_of_singles({"X": READING}, [r], DEFAULT, READING_J) == {("X", "d", "'every'"): True}


def test_a_point_is_the_value_as_an_exact_number_element_by_element():
    assert point(est(-0.3)) == Estimate.exact(-0.3)
    assert point(2) == Estimate.exact(2.0)
    assert point([est(1.0), 3]) == [Estimate.exact(1.0), Estimate.exact(3.0)]
    assert point((est(1.0),)) == [Estimate.exact(1.0)]
    assert point({"gap": est(1.0), "level": [2]}) == {"gap": Estimate.exact(1.0), "level": [Estimate.exact(2.0)]}
    assert point({"value": 4.0, "ci_low": 3.0, "ci_high": 5.0}) == Estimate.exact(4.0)  # an estimate dict
    assert point("no number") == "no number" and point(None) is None  # what cannot be read stays as it is
    assert point({"value": "x", "ci_low": 0.0, "ci_high": 1.0}) == {"value": "x", "ci_low": 0.0, "ci_high": 1.0}


# --- the sizing budget ----------------------------------------------------------------------------------------------


def test_the_budget_grants_up_to_its_runs_exactly():
    b = SizingBudget(4)
    assert b.grant(3) and b.used == 3
    assert not b.grant(2) and b.used == 3  # refused: nothing taken
    assert b.grant(1) and b.used == 4  # exactly the budget
    assert not b.grant(1) and b.used == 4
    unlimited = SizingBudget()
    assert unlimited.grant(10**6) and unlimited.grant(10**6) and unlimited.used == 2 * 10**6
    assert SizingBudget(0).grant(0) and not SizingBudget(0).grant(1)
    assert SizingBudget().left == 0 and SizingBudget().used == 0


# --- size_conditions: sized like the default --------------------------------------------------------------------


def test_a_condition_decided_on_fewer_replicates_than_the_default_is_sized_up_to_the_defaults_count():
    """Decided on one replicate, but the default needed 4: sized to exactly 4, on the default's seeds 1-3 (common
    random numbers), in one round, asking only X; before that it neither flips nor agrees."""
    measure, log = const(X=lambda c: FLIP if c["a"] == 1 else AGREE), []
    r = cond({"a": 1}, {"X": FLIP})
    assert condition_verdicts(RULES, r, {"X": 4}) == {("X", "claim"): "undecided"}
    added = size_conditions(measure, RULES, [r], DEFAULT_J, {"X": 4}, SEEDS, 8, stage_runner(measure, log))
    assert added == 3 and r.n_runs("X") == 4
    assert [s.seed for s in r.sized] == SEEDS[1:4] and all(s.config == r.config for s in r.sized)
    assert all(s.stage == "condition sizing" and s.claims == s.scope == frozenset({"X"}) for s in r.sized)
    assert log == [("condition sizing", [(s, frozenset({"X"})) for s in SEEDS[1:4]])]
    assert condition_verdicts(RULES, r, {"X": 4}) == {("X", "claim"): "not reproduced"}


def test_a_condition_agreeing_on_fewer_replicates_is_sized_too_and_never_beyond_the_cap():
    measure = const(X=lambda c: AGREE)
    r = cond({"a": 1}, {"X": AGREE})
    assert size_conditions(measure, RULES, [r], DEFAULT_J, {"X": 6}, SEEDS, 5, stage_runner(measure)) == 4
    assert r.n_runs("X") == 5 and [s.seed for s in r.sized] == SEEDS[1:5]
    assert condition_verdicts(RULES, r, {"X": 6})[("X", "claim")] == "undecided"  # the cap stopped it short


def test_an_undecided_condition_is_sized_one_replicate_a_round_until_it_decides():
    """-0.3 +- 0.5: undecided on 1 and 2 replicates, projected within the cap: a round each, then decided on 3."""
    measure, log = const(X=lambda c: SLOW_FLIP), []
    r = cond({"a": 1}, {"X": SLOW_FLIP})
    assert size_conditions(measure, RULES, [r], DEFAULT_J, {"X": 1}, SEEDS, 8, stage_runner(measure, log)) == 2
    assert [s.seed for s in r.sized] == SEEDS[1:3] and len(log) == 2
    assert condition_verdicts(RULES, r, {"X": 1}) == {("X", "claim"): "not reproduced"}


def test_a_condition_projected_beyond_the_cap_or_decided_is_left_as_it_is():
    measure, log = const(X=lambda c: FAR), []
    far, agree = cond({"a": 1}, {"X": FAR}), cond({"a": 2}, {"X": AGREE})
    added = size_conditions(measure, RULES, [far, agree], DEFAULT_J, {"X": 1}, SEEDS, 8, stage_runner(measure, log))
    assert added == 0 and log == [] and far.sized == [] and agree.sized == []


def test_each_claim_is_asked_only_for_the_replicates_it_lacks():
    """X needs 4 (default), Y 2: replicate 1 asks X and Y, replicates 2 and 3 X alone; Z is out of the scope, W has
    no rule, V was left by the budget."""
    rules = {"X": RULE, "Y": RULE, "Z": RULE, "V": RULE}
    measure = const(X=lambda c: FLIP, Y=lambda c: FLIP, Z=lambda c: FLIP, W=lambda c: FLIP, V=lambda c: FLIP)
    r = cond({"a": 1}, {"X": FLIP, "Y": FLIP, "Z": FLIP, "W": FLIP, "V": FLIP}, scope=("X", "Y", "W", "V"))
    r.left["V"] = 4
    dj = {(c, "claim"): REPRODUCED for c in rules}
    nd = {"X": 4, "Y": 2, "Z": 4, "V": 4}
    added = size_conditions(measure, rules, [r], dj, nd, SEEDS, 8, stage_runner(measure))
    assert added == 3
    assert [(s.seed, s.claims) for s in r.sized] == [
        (SEEDS[1], frozenset({"X", "Y"})),
        (SEEDS[2], frozenset({"X"})),
        (SEEDS[3], frozenset({"X"})),
    ]
    assert (r.n_runs("X"), r.n_runs("Y"), r.n_runs("V")) == (4, 2, 1) and r.left == {"V": 4}


def test_a_condition_with_no_scope_sizes_every_claim_with_a_rule():
    """X is decided on as many replicates as its default needed (nothing to add); Y, after it, needs 3."""
    measure = const(X=lambda c: FLIP, Y=lambda c: FLIP)
    r = cond({"a": 1}, {"X": FLIP, "Y": FLIP}, scope=None)
    dj = {("X", "claim"): REPRODUCED, ("Y", "claim"): REPRODUCED}
    added = size_conditions(measure, {"X": RULE, "Y": RULE}, [r], dj, {"X": 1, "Y": 3}, SEEDS, 8, stage_runner(measure))
    assert added == 2 and (r.n_runs("X"), r.n_runs("Y")) == (1, 3)


def test_with_no_count_stated_only_an_undecided_condition_is_sized():
    measure = const(X=lambda c: SLOW_FLIP)
    slow = cond({"a": 1}, {"X": SLOW_FLIP})
    assert size_conditions(measure, RULES, [slow], DEFAULT_J, {}, SEEDS, 8, stage_runner(measure)) == 2
    screened = cond({"a": 1}, {"X": FLIP})
    screened.screened = frozenset({"X"})  # decided on its screen, no replicate: nothing asked
    assert size_conditions(measure, RULES, [screened], DEFAULT_J, {}, SEEDS, 8, stage_runner(measure)) == 0


def test_a_condition_leaning_towards_a_flip_is_sized_whatever_the_budget():
    measure = const(X=lambda c: FLIP if c["a"] == 1 else AGREE)
    flip, agree = cond({"a": 1}, {"X": FLIP}), cond({"a": 2}, {"X": AGREE})
    budget = SizingBudget(0)
    added = size_conditions(measure, RULES, [agree, flip], DEFAULT_J, {"X": 3}, SEEDS, 8, stage_runner(measure), budget)
    assert added == 2 and flip.n_runs("X") == 3 and agree.n_runs("X") == 1
    assert agree.left == {"X": 3} and flip.left == {} and budget.left == 1 and budget.used == 0
    assert condition_verdicts(RULES, agree, {"X": 3}) == {("X", "claim"): "undecided"}  # left: never an agreement


def test_the_budget_is_spent_in_the_order_of_the_conditions():
    measure = const(X=lambda c: AGREE)
    first, second, third, fourth = (cond({"a": a}, {"X": AGREE}) for a in (1, 2, 3, 4))
    budget = SizingBudget(5)  # 2 for the first (1 -> 3), 2 for the second, 1 short for the third and the fourth
    added = size_conditions(
        measure, RULES, [first, second, third, fourth], DEFAULT_J, {"X": 3}, SEEDS, 8, stage_runner(measure), budget
    )
    assert added == 4 and [r.n_runs("X") for r in (first, second, third, fourth)] == [3, 3, 1, 1]
    assert third.left == fourth.left == {"X": 3} and budget.used == 4 and budget.left == 2


def test_an_unlimited_budget_is_the_default():
    measure = const(X=lambda c: AGREE)
    r = cond({"a": 1}, {"X": AGREE})
    assert size_conditions(measure, RULES, [r], DEFAULT_J, {"X": 3}, SEEDS, 8, stage_runner(measure)) == 2


# --- unexplained joint flips -------------------------------------------------------------------------------------


def _needs(*entries):
    """A measure of X that flips (on one replicate) only where every entry of ``entries`` is changed."""
    return const(X=lambda c: FLIP if all(c[k] == 1 for k in entries) else AGREE)


def _measured(measure, config, stage, scope=("X",)):
    full = {**DEFAULT, **config}
    return cond(config, {c: v for c, v in measure(full, SEEDS[0]).items() if scope is None or c in scope}, stage, scope)


def test_a_joint_flip_no_single_entry_explains_is_unexplained_with_the_entries_the_claim_reads():
    m = _needs("a", "b")
    singles = [_measured(m, {k: 1}, "single") for k in "abc"]
    joint = _measured(m, {"a": 1, "b": 1, "c": 1, "d": 1}, "joint")
    replicate = Run(
        dict(DEFAULT), SEEDS[0], "replicate", outputs={"X": FLIP}
    )  # one replicate disagreeing: no condition
    depends = {"X": ["a", "b", "c"]}  # d is no entry of X's
    got = unexplained_flips(RULES, depends, DEFAULT_J, [replicate, *singles, joint], DEFAULT, {"X": 1})
    assert got == [(joint, {"a", "b", "c"}, frozenset({"X"}))]


def test_a_joint_flip_a_smaller_flipping_run_explains_is_not_searched():
    m = _needs("a", "b")
    joint = _measured(m, {"a": 1, "b": 1, "c": 1}, "joint")
    pair = _measured(m, {"a": 1, "b": 1}, "combination")
    depends = {"X": ["a", "b", "c"]}
    assert unexplained_flips(RULES, depends, DEFAULT_J, [joint, pair], DEFAULT, {"X": 1}) == []
    # a flipping run is no explanation of itself, nor is an equal one
    twin = _measured(m, {"a": 1, "b": 1, "c": 1}, "pinned")
    got = unexplained_flips(RULES, depends, DEFAULT_J, [joint, twin], DEFAULT, {"X": 1})
    assert [(r.stage, todo) for r, todo, _ in got] == [("joint", {"a", "b", "c"}), ("pinned", {"a", "b", "c"})]
    # a pair changing other values of the same entries explains nothing
    other = cond({"a": 2, "b": 2}, {"X": FLIP}, "combination")
    assert len(unexplained_flips(RULES, depends, DEFAULT_J, [joint, other], DEFAULT, {"X": 1})) == 1


def test_a_flip_decided_on_fewer_replicates_than_the_default_is_no_flip_to_search_or_to_explain():
    m = _needs("a", "b")
    joint = _measured(m, {"a": 1, "b": 1, "c": 1}, "joint")
    depends = {"X": ["a", "b", "c"]}
    assert unexplained_flips(RULES, depends, DEFAULT_J, [joint], DEFAULT, {"X": 2}) == []
    joint.sized.append(Run(joint.config, SEEDS[1], "condition sizing", outputs={"X": FLIP}, claims=frozenset({"X"})))
    pair = _measured(m, {"a": 1, "b": 1}, "combination")  # one replicate: cannot explain at a count of 2
    assert [r for r, _, _ in unexplained_flips(RULES, depends, DEFAULT_J, [joint, pair], DEFAULT, {"X": 2})] == [joint]


def test_only_a_decisive_default_can_be_flipped():
    m = _needs("a", "b")
    joint = _measured(m, {"a": 1, "b": 1, "c": 1}, "joint")
    depends = {"X": ["a", "b", "c"]}
    for dj in ({("X", "claim"): UNDECIDED}, {("X", "claim"): NOT_REPRODUCED}, {}):
        assert unexplained_flips(RULES, depends, dj, [joint], DEFAULT, {"X": 1}) == []
    assert len(unexplained_flips(RULES, depends, DEFAULT_J, [joint], DEFAULT, {"X": 1})) == 1


def test_a_flip_of_two_entries_is_already_the_smallest_and_is_not_searched():
    m = _needs("a", "b")
    joint = _measured(m, {"a": 1, "b": 1}, "joint")
    assert unexplained_flips(RULES, {"X": ["a", "b", "c"]}, DEFAULT_J, [joint], DEFAULT, {"X": 1}) == []
    wide = _measured(m, {"a": 1, "b": 1, "c": 1}, "joint")  # three changed, but X reads two of them
    assert unexplained_flips(RULES, {"X": ["a", "b"]}, DEFAULT_J, [wide], DEFAULT, {"X": 1}) == []
    single = _measured(m, {"a": 1, "b": 1, "c": 1}, "combination")  # a combination is searched for, not searched
    assert unexplained_flips(RULES, {"X": ["a", "b", "c"]}, DEFAULT_J, [single], DEFAULT, {"X": 1}) == []


def test_the_claims_and_entries_are_those_of_the_unexplained_flips_only():
    """Y flips at the joint but its single on a explains it; X's flip is unexplained: X alone, X's entries."""
    rules = {"X": RULE, "Y": RULE}
    dj = {("X", "claim"): REPRODUCED, ("Y", "claim"): REPRODUCED}
    joint = cond({"a": 1, "b": 1, "c": 1, "d": 1}, {"X": FLIP, "Y": FLIP}, "joint", scope=("X", "Y"))
    single = cond({"a": 1}, {"X": AGREE, "Y": FLIP}, "single", scope=("X", "Y"))
    depends = {"X": ["a", "b", "c"], "Y": ["a", "d"]}
    got = unexplained_flips(rules, depends, dj, [joint, single], DEFAULT, {"X": 1, "Y": 1})
    assert got == [(joint, {"a", "b", "c"}, frozenset({"X"}))]


def test_the_entries_of_every_unexplained_claim_of_a_joint_are_searched_together():
    """X reads a and b, Y reads c and d: each flip alone is a pair, together four entries to search."""
    rules = {"X": RULE, "Y": RULE}
    dj = {("X", "claim"): REPRODUCED, ("Y", "claim"): REPRODUCED}
    joint = cond({"a": 1, "b": 1, "c": 1, "d": 1}, {"X": FLIP, "Y": FLIP}, "joint", scope=("X", "Y"))
    depends = {"X": ["a", "b"], "Y": ["c", "d"]}
    got = unexplained_flips(rules, depends, dj, [joint], DEFAULT, {"X": 1, "Y": 1})
    assert got == [(joint, {"a", "b", "c", "d"}, frozenset({"X", "Y"}))]


def test_the_kept_answer_follows_a_run_that_grows_and_trusts_no_entry_of_another_run():
    m = _needs("a", "b")
    joint = _measured(m, {"a": 1, "b": 1, "c": 1}, "joint")
    depends = {"X": ["a", "b", "c"]}
    cache: dict = {}
    assert len(unexplained_flips(RULES, depends, DEFAULT_J, [joint], DEFAULT, {"X": 2}, cache)) == 0
    joint.sized.append(Run(joint.config, SEEDS[1], "condition sizing", outputs={"X": FLIP}, claims=frozenset({"X"})))
    assert len(unexplained_flips(RULES, depends, DEFAULT_J, [joint], DEFAULT, {"X": 2}, cache)) == 1  # grown
    # entries kept under this run's id by another run (an id reused after the first was dropped): recomputed
    stranger = Run({**DEFAULT, "a": 1}, 0, "single")
    cache[("changed", id(joint))] = (stranger, frozenset({("a", 1)}))
    cache[("flips", id(joint))] = (stranger, cache[("flips", id(joint))][1], set())
    got = unexplained_flips(RULES, depends, DEFAULT_J, [joint], DEFAULT, {"X": 2}, cache)
    assert [(r, todo) for r, todo, _ in got] == [(joint, {"a", "b", "c"})]


# --- the subsets tried ---------------------------------------------------------------------------------------------


def test_subsets_are_tried_most_leaning_first_then_by_name_each_once():
    joint = cond({"a": 1, "b": 1, "c": 1, "d": 1}, {"X": FLIP}, "joint")
    flips = [(joint, {"a", "b", "c", "d"}, frozenset({"X"}))]
    lean = {("X", "c", "1"): True, ("X", "d", "1"): True, ("Y", "a", "1"): True, ("X", "b", "2"): True}
    tried: dict = {}
    cfgs, only = subset_configs(flips, DEFAULT, 2, tried, lean, 4)
    pairs = [tuple(k for k in "abcd" if c[k] == 1) for c in cfgs]
    # c and d lean for X (2), then pairs with one of them by name, then (a, b): Y's lean and b's other value count not
    assert pairs == [("c", "d"), ("a", "c"), ("a", "d"), ("b", "c")]
    assert all(set(c) == set(DEFAULT) for c in cfgs) and only == [frozenset({"X"})] * 4
    cfgs, only = subset_configs(flips, DEFAULT, 2, tried, lean, 4)
    assert [tuple(k for k in "abcd" if c[k] == 1) for c in cfgs] == [("b", "d"), ("a", "b")]
    assert subset_configs(flips, DEFAULT, 2, tried, lean, 4) == ([], [])
    assert tried == {id(joint): set(itertools_pairs("abcd"))}


def test_a_flip_with_no_subset_of_the_size_leaves_the_others_searched():
    three = cond({"a": 1, "b": 1, "c": 1}, {"X": FLIP}, "joint")
    four = cond({"a": 1, "b": 1, "c": 1, "d": 1}, {"X": FLIP}, "pinned")
    flips = [(three, {"a", "b", "c"}, frozenset({"X"})), (four, {"a", "b", "c", "d"}, frozenset({"X"}))]
    cfgs, only = subset_configs(flips, DEFAULT, 3)
    assert [tuple(k for k in "abcd" if c[k] == 1) for c in cfgs] == [
        ("a", "b", "c"),
        ("a", "b", "d"),
        ("a", "c", "d"),
        ("b", "c", "d"),
    ]
    # the same subsets of two flips are tried for each
    tried: dict = {}
    cfgs, _ = subset_configs(flips, DEFAULT, 2, tried)
    assert len(cfgs) == 3 + 6 and set(tried) == {id(three), id(four)} and len(tried[id(three)]) == 3


def itertools_pairs(names):
    return [(x, y) for i, x in enumerate(names) for y in names[i + 1 :]]


def test_subsets_take_the_joint_values_and_stop_below_the_joints_size():
    joint = cond({"a": 2, "b": 3, "c": 1}, {"X": FLIP}, "joint")
    flips = [(joint, {"a", "b", "c"}, frozenset({"X", "Y"}))]
    cfgs, only = subset_configs(flips, DEFAULT, 2)  # no lean, no limit, nothing tried
    assert cfgs == [{**DEFAULT, "a": 2, "b": 3}, {**DEFAULT, "a": 2, "c": 1}, {**DEFAULT, "b": 3, "c": 1}]
    assert only == [frozenset({"X", "Y"})] * 3
    assert subset_configs(flips, DEFAULT, 3) == ([], [])  # the joint itself is no subset of it
    cfgs, _ = subset_configs(flips, DEFAULT, 2, lean={("X", "c", "1"): True, ("Y", "b", "3"): True})
    assert cfgs[0] == {**DEFAULT, "b": 3, "c": 1}  # both lean: first


def test_the_lean_of_singles_is_that_of_each_one_at_a_time_condition_at_its_final_size():
    rules = {"X": RULE, "Y": RULE}
    dj = {("X", "claim"): REPRODUCED, ("Y", "claim"): REPRODUCED}
    runs = [
        cond({"a": 1}, {"X": SLOW_FLIP, "Y": AGREE}, "single", scope=("X", "Y")),
        cond({"b": 2}, {"X": AGREE, "Y": FLIP}, "single", scope=("X",)),  # Y out of scope
        cond({"c": 1}, {"X": FLIP}, "joint"),  # not a single
        cond({"c": 1, "d": 1}, {"X": FLIP}, "single"),  # two changes: no single entry's lean
        cond({"d": "x"}, {"Y": FLIP}, "single", scope=("Y",)),
        Run(dict(DEFAULT), 0, "single", outputs={"X": FLIP}),  # nothing changed
    ]
    assert lean_of_singles(rules, runs, DEFAULT, dj) == {("X", "a", "1"): True, ("Y", "d", "'x'"): True}


# --- the search ----------------------------------------------------------------------------------------------------


def _search(measure, runs, depends, n_default=None, max_subset=None, log=None):
    have: dict = {}
    nd = n_default or {"X": 1}

    def conditions(cfgs, stage, only=None):
        return projected_runs(cfgs, stage, depends, DEFAULT, SEEDS[0], have, only)

    return search_subsets(
        measure,
        RULES,
        depends,
        DEFAULT_J,
        nd,
        DEFAULT,
        SEEDS,
        8,
        stage_runner(measure, log),
        conditions,
        runs,
        max_subset,
    )


def test_a_flip_that_needs_two_entries_is_explained_by_that_pair_and_no_triple_is_tried():
    m = _needs("b", "c")
    depends = {"X": ["a", "b", "c", "d"]}
    singles = [_measured(m, {k: 1}, "single") for k in "abcd"]
    joint = _measured(m, {"a": 1, "b": 1, "c": 1, "d": 1}, "joint")
    runs, combos, sized = _search(m, [*singles, joint], depends)
    tried = [tuple(k for k in "abcd" if r.config[k] == 1) for r in combos]
    assert tried == [("a", "b"), ("a", "c"), ("a", "d"), ("b", "c")]  # one round of SUBSET_ROUND, by name
    assert SUBSET_ROUND == 4 and sized == 0 and runs[: len(singles) + 1] == [*singles, joint]
    flipping = [r for r in combos if condition_verdicts(RULES, r, {"X": 1}) == {("X", "claim"): "not reproduced"}]
    assert [r.changed(DEFAULT) for r in flipping] == [{"b": 1, "c": 1}]
    assert all(condition_verdicts(RULES, s, {"X": 1}) == {("X", "claim"): "reproduced"} for s in singles)
    assert unexplained_flips(RULES, depends, DEFAULT_J, runs, DEFAULT, {"X": 1}) == []
    assert all(r.stage == "combination" and r.claims == frozenset({"X"}) for r in combos)


def test_a_pair_leaning_alone_is_tried_first():
    m = _needs("c", "d")
    depends = {"X": ["a", "b", "c", "d"]}
    singles = [_measured(m, {k: 1}, "single") for k in "abc"]
    singles.append(cond({"d": 1}, {"X": SLOW_FLIP}, "single"))  # d leans towards the flip alone
    joint = _measured(m, {"a": 1, "b": 1, "c": 1, "d": 1}, "joint")
    _, combos, _ = _search(m, [*singles, joint], depends)
    assert [r.changed(DEFAULT) for r in combos][0] in ({"a": 1, "d": 1}, {"b": 1, "d": 1}, {"c": 1, "d": 1})
    assert {"c": 1, "d": 1} in [r.changed(DEFAULT) for r in combos[:3]]  # found in the first round: all d's pairs


def test_a_flip_that_needs_three_entries_goes_on_to_triples_and_is_named_by_one():
    """Every pair of a..d tried (two rounds: 4 then 2) without a flip, then the four triples (one round): (a, b, c)
    alone flips, and nothing is left unexplained."""
    m, log = _needs("a", "b", "c"), []
    depends = {"X": ["a", "b", "c", "d"]}
    joint = _measured(m, {"a": 1, "b": 1, "c": 1, "d": 1}, "joint")
    runs, combos, _ = _search(m, [joint], depends, log=log)
    assert [len(r.changed(DEFAULT)) for r in combos] == [2] * 6 + [3] * 4
    flipping = [
        r.changed(DEFAULT) for r in combos if condition_verdicts(RULES, r, {"X": 1})[("X", "claim")] != "reproduced"
    ]
    assert flipping == [{"a": 1, "b": 1, "c": 1}]
    assert [stage for stage, _ in log] == ["combinations"] * 3 and [len(jobs) for _, jobs in log] == [4, 2, 4]
    assert unexplained_flips(RULES, depends, DEFAULT_J, runs, DEFAULT, {"X": 1}) == []


def test_the_search_stops_at_the_largest_subset_stated():
    m = _needs("a", "b", "c")
    depends = {"X": ["a", "b", "c", "d"]}
    joint = _measured(m, {"a": 1, "b": 1, "c": 1, "d": 1}, "joint")
    _, combos, _ = _search(m, [joint], depends, max_subset=2)
    assert len(combos) == 6 and all(len(r.changed(DEFAULT)) == 2 for r in combos)
    assert len(unexplained_flips(RULES, depends, DEFAULT_J, [joint, *combos], DEFAULT, {"X": 1})) == 1  # unattributed
    _, none, _ = _search(m, [joint], depends, max_subset=1)
    assert none == []


def test_a_subset_leaning_towards_the_flip_is_sized_like_the_default_before_it_explains():
    """The default needed 3 replicates: the pair (b, c) flips on one but is sized to 3 (2 runs added) before it
    explains the joint; the pairs that agree are not sized (no budget for agreement in the search)."""
    m = _needs("b", "c")
    depends = {"X": ["a", "b", "c"]}
    joint = _measured(m, {"a": 1, "b": 1, "c": 1}, "joint")
    for s in SEEDS[1:3]:
        joint.sized.append(Run(joint.config, s, "condition sizing", outputs={"X": FLIP}, claims=frozenset({"X"})))
    runs, combos, sized = _search(m, [joint], depends, n_default={"X": 3})
    by_pair = {tuple(k for k in "abc" if r.config[k] == 1): r for r in combos}
    assert set(by_pair) == {("a", "b"), ("a", "c"), ("b", "c")}
    assert by_pair[("b", "c")].n_runs("X") == 3 and [s.seed for s in by_pair[("b", "c")].sized] == SEEDS[1:3]
    assert by_pair[("a", "b")].n_runs("X") == 1 and by_pair[("a", "b")].left == {"X": 3}
    assert sized == 2
    assert unexplained_flips(RULES, depends, DEFAULT_J, runs, DEFAULT, {"X": 3}) == []


def test_a_joint_decided_on_fewer_replicates_than_the_default_needed_is_not_searched():
    m = _needs("a", "b")
    joint = _measured(m, {"a": 1, "b": 1, "c": 1}, "joint")  # flips on one replicate, the default needed 2
    runs, combos, sized = _search(m, [joint], {"X": ["a", "b", "c"]}, n_default={"X": 2})
    assert combos == [] and sized == 0 and runs == [joint]


def test_the_runs_added_by_sizing_are_counted_over_every_round():
    """The default needed 3. Pairs (a, b) (first round) and (c, d) (second round) flip on their first replicate and
    agree on the next two: each is sized by 2 and explains nothing; the triple (a, b, c) flips on all three (2 more).
    6 runs added in all."""
    first_only = {("a", "b"), ("c", "d")}

    def measure(config, seed):
        on = tuple(k for k in "abcd" if config[k] == 1)
        if on[:3] == ("a", "b", "c") or (on in first_only and seed == SEEDS[0]):
            return {"X": FLIP}
        return {"X": AGREE}

    depends = {"X": ["a", "b", "c", "d"]}
    joint = _measured(measure, {"a": 1, "b": 1, "c": 1, "d": 1}, "joint")
    for s in SEEDS[1:3]:
        joint.sized.append(Run(joint.config, s, "condition sizing", outputs={"X": FLIP}, claims=frozenset({"X"})))
    runs, combos, sized = _search(measure, [joint], depends, n_default={"X": 3})
    by = {tuple(k for k in "abcd" if r.config[k] == 1): r for r in combos}
    assert {k: r.n_runs("X") for k, r in by.items() if r.n_runs("X") > 1} == {
        ("a", "b"): 3,
        ("c", "d"): 3,
        ("a", "b", "c"): 3,
    }
    # one replicate flips and two agree, far beyond their intervals: the pool is widened and decides nothing
    assert condition_verdicts(RULES, by[("a", "b")], {"X": 3}) == {("X", "claim"): "undecided"}
    assert sized == 6
    assert unexplained_flips(RULES, depends, DEFAULT_J, runs, DEFAULT, {"X": 3}) == []


def test_the_search_computes_each_runs_flips_and_changes_once_while_it_is_unchanged(monkeypatch):
    """Three rounds (4 pairs, 2 pairs, 4 triples) ask for the unexplained flips four times; the joint and each
    combination (none sized: the default needed one replicate) have their flips, and each flipping run its changed
    entries, worked out once."""
    import tvtrack.conditions as conditions

    flips_of, changed_of = [], []
    plain_flips, plain_changed = conditions._flips, Run.changed

    def counted_flips(rules, default_j, run, n_default):
        flips_of.append(id(run))
        return plain_flips(rules, default_j, run, n_default)

    def counted_changed(self, default):
        changed_of.append(id(self))
        return plain_changed(self, default)

    monkeypatch.setattr(conditions, "_flips", counted_flips)
    monkeypatch.setattr(Run, "changed", counted_changed)
    m = _needs("a", "b", "c")
    joint = _measured(m, {"a": 1, "b": 1, "c": 1, "d": 1}, "joint")
    _, combos, _ = _search(m, [joint], {"X": ["a", "b", "c", "d"]})
    assert len(combos) == 10
    assert sorted(flips_of) == sorted(id(r) for r in (joint, *combos))
    # changed entries are asked of the flipping runs only: the joint (every round) and the triple (a, b, c)
    abc = next(r for r in combos if [r.config[k] for k in "abcd"] == [1, 1, 1, 0])
    assert sorted(changed_of) == sorted([id(joint), id(abc)])


def test_a_joint_flip_outside_the_operating_point_starts_no_subset_search():
    # its flips are counted beside the labels, where no flip is named by a subset: searching it only costs runs
    m = _needs("a", "b", "c")
    depends = {"X": ["a", "b", "c", "d"]}
    joint = _measured(m, {"a": 1, "b": 1, "c": 1, "d": 1}, "joint")
    assert unexplained_flips(RULES, depends, DEFAULT_J, [joint], DEFAULT, {"X": 1}) == [
        (joint, {"a", "b", "c", "d"}, frozenset({"X"}))
    ]
    joint.off_point = "the joint world leaves the paper's band"
    assert unexplained_flips(RULES, depends, DEFAULT_J, [joint], DEFAULT, {"X": 1}) == []
    _, combos, _ = _search(m, [joint], depends)
    assert combos == []


def test_a_flip_outside_the_operating_point_explains_no_joint_flip_and_the_next_one_still_does():
    m = _needs("a", "b")
    depends = {"X": ["a", "b", "c", "d"]}
    lost = _measured(m, {"a": 1, "b": 1}, "combination")
    lost.off_point = "outside the paper's band"
    joint = _measured(m, {"a": 1, "b": 1, "c": 1, "d": 1}, "joint")
    got = unexplained_flips(RULES, depends, DEFAULT_J, [lost, joint], DEFAULT, {"X": 1})
    assert got == [(joint, {"a", "b", "c", "d"}, frozenset({"X"}))]  # the lost pair explains nothing
    kept = _measured(m, {"a": 1, "b": 1, "c": 1}, "combination")  # after the lost one in the list: still read
    assert unexplained_flips(RULES, depends, DEFAULT_J, [lost, kept, joint], DEFAULT, {"X": 1}) == []
