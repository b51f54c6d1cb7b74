"""The label record's words and counts, pinned on planted part records: the coverage and runs-to-decide sentences
with their exact numbers, a fold of parts, the runs behind a pooled value, a condition row's defaults, the share's
budget count, the part record of a part not measured, and a hand-built record's checks.

Pure functions over tiny synthetic measures (exact numbers: no draw, no explorer).
"""

import math

import pytest

from tvtrack import labels
from tvtrack.labels import Robustness, label_parts, part_judgements, part_pairs, weakest_label
from tvtrack.montecarlo import Estimate
from tvtrack.register import Entry
from tvtrack.verdicts import AllOf, ByReading, InBand, Judgement, NotCheckable

BAND = InBand("mean", -0.5, 0.5, "px")
WORLD = Entry("motion", "regime", "cv", ("cv", "weave", "turn"), "a world beyond the paper")
READING = Entry("sigma", "reading", "raw", ("raw", "smoothed", "robust"), "the text reads either way")


def _reps(values=(0.0, 0.0, 0.0)):
    return [{"seed": s, "measured": Estimate.exact(v)} for s, v in zip((1, 2, 3), values)]


def _single(changed, measured, **kw):
    return {"changed": changed, "kind": "single", "measured": measured, **kw}


# --------------------------------------------------------------------------- the fold of parts that must all hold


def test_a_fold_is_the_first_failing_part_the_first_holding_one_or_the_open_parts_together():
    held = [Judgement("reproduced", "a"), Judgement("reproduced", "b")]
    assert labels._fold(held) == Judgement("reproduced", "a")
    failing = [Judgement("reproduced", "a"), Judgement("not reproduced", "b"), Judgement("not reproduced", "c")]
    assert labels._fold(failing) == Judgement("not reproduced", "b")
    open_ = [
        Judgement("reproduced", "a"),
        Judgement("undecided", "u", False, 2.0),
        Judgement("undecided", "v", False, 5.0),
    ]
    assert labels._fold(open_) == Judgement("undecided", "u; v", False, 5.0)


# --------------------------------------------------------------------------- runs to decide, in words and numbers


def test_the_runs_to_decide_say_how_many_replicates_and_runs_with_the_cap():
    rt = labels._runs_text
    assert rt(Judgement("undecided", "", False, 2.0), 3, 300, 5) == {
        "replicates": 6,
        "now": 3,
        "factor": 2.0,
        "runs": 600,
        "text": "undecided at 3 replicates: about 6 independent replicates (600 runs) are projected to decide it, beyond the "
        "cap of 5",
    }
    # at least one more replicate; runs only where a replicate pools more than one run; a cap reached is no cap passed
    assert rt(Judgement("undecided", "", False, 1.0), 3, 3, 4) == {
        "replicates": 4,
        "now": 3,
        "factor": 1.0,
        "runs": None,
        "text": "undecided at 3 replicates: about 4 independent replicates are projected to decide it",
    }
    assert rt(Judgement("undecided", "", False, 1000.0), 2, 2, None)["replicates"] == 2000  # the practical edge
    assert rt(Judgement("undecided", "", False, 1001.0), 2, 2, None) == {
        "replicates": None,
        "now": 2,
        "factor": 1001.0,
        "text": "undecided at 2 replicates: the estimate sits so close to the band edge that only over 1000 times "
        "the runs are projected to decide it",
    }
    assert rt(Judgement("undecided", "", False, math.inf), 4, 40, 9) == {
        "replicates": None,
        "now": 4,
        "factor": None,
        "text": "undecided at 4 replicates; no number of runs is projected to decide it",
    }


def test_the_runs_behind_a_pooled_value_are_its_n_the_largest_over_parts():
    est = lambda n: Estimate(0.0, 0.1, -0.2, 0.2, n, method="Student t")  # noqa: E731
    rb = labels._runs_behind
    assert rb(est(50)) == 50
    assert rb({"p1": est(10), "p2": est(30)}) == 30
    assert rb([est(4), est(9)]) == 9
    assert rb({"value": 1.0, "ci_low": 0.5, "ci_high": 1.5, "n": 7}) == 7  # an estimate's dict: one value, not parts
    assert (rb({}), rb([]), rb("text"), rb(None)) == (0, 0, 0, 0)


def test_a_parts_scalar_is_its_value_or_a_curves_end_to_end_change():
    sc = labels._scalar
    assert sc([1.0, 5.0, 10.0]) == 9.0
    assert sc([Estimate.exact(2.0), Estimate.exact(-1.0)]) == -3.0
    assert all(math.isnan(sc(m)) for m in ([], [1.0], None, "text"))
    assert sc(Estimate.exact(4.5)) == 4.5


# --------------------------------------------------------------------------- the coverage sentence


def test_the_coverage_sentence_counts_each_kind_and_names_the_weakest_parts():
    conds = [{"kind": k} for k in ["single"] * 2 + ["joint"] * 3 + ["pinned"] + ["combination"] * 4]
    parts = {"p1": {"label": "limited"}, "p2": {"label": "robust"}, "p3": {"label": "limited"}}
    text = labels._coverage("limited", parts, conds, [1, 2, 3], [WORLD] * 5, False, 5, True)
    assert text == (
        "limited (weakest parts: p1, p3) over 5 distinct configurations (2 one at a time over 5 register entries, "
        "3 joint samples, 1 pinned known flip, 4 sub-combinations of flipping joint configurations); "
        "x 3 independent replicates; provisional: 5 distinct configurations are too few for a share"
    )
    one = labels._coverage("robust", {"claim": {"label": "robust"}}, conds[:2], [1], [WORLD] * 2, True, 2, False)
    assert one == (
        "robust over 2 distinct configurations (2 one at a time over 2 register entries, 0 joint samples); "
        "x deterministic (no random draw)"
    )
    two = {"p1": {"label": "robust"}, "p2": {"label": "depends"}}
    assert labels._coverage("depends", two, conds[2:5], [1, 2, 3], [], False, 3, False) == (
        "depends (weakest part: p2) over 3 distinct configurations (0 one at a time over 0 register entries, "
        "3 joint samples); x 3 independent replicates"
    )
    combos = labels._coverage("-", {"claim": {"label": "-"}}, conds[6:], [1, 2, 3], [], False, 0, False)
    assert combos == (
        "no label (no part decided at the default: nothing to flip) over 0 distinct configurations (0 one at a "
        "time over 0 register entries, 0 joint samples, 4 sub-combinations of flipping joint configurations); "
        "x 3 independent replicates"
    )


def test_label_parts_hands_the_coverage_its_design_deterministic_and_provisional():
    conds = [_single({"motion": "weave"}, 0.1), _single({"motion": "turn"}, 0.2)]
    rec = label_parts(BAND, 0.0, _reps(), conds[:1], [WORLD])
    assert rec["provisional"] is True and rec["deterministic"] is False
    assert rec["coverage"] == (
        "unexplored over 1 distinct configurations (1 one at a time over 1 register entries, 0 joint samples); "
        "x 3 independent replicates; provisional: 1 distinct configurations are too few for a share"
    )
    full = label_parts(BAND, 0.0, _reps(), conds, [WORLD])  # every combination of the one entry: not provisional
    assert full["provisional"] is False and full["label"] == "robust"
    det = label_parts(BAND, 0.0, _reps()[:1], conds[:1], [WORLD], deterministic=True)
    assert det["provisional"] is False and det["deterministic"] is True
    assert det["coverage"].endswith("0 joint samples); x deterministic (no random draw)")


def test_a_design_smaller_than_every_combination_is_provisional_unless_min_share_design_says_otherwise():
    ents = [WORLD, Entry("speed", "operating point", 1, (1, 2, 3), "a speed beyond the paper")]  # 8 combinations
    conds = [_single({"motion": "weave"}, 0.1), _single({"speed": 2}, 0.2)]
    assert label_parts(BAND, 0.0, _reps(), conds, ents)["provisional"] is True
    rec = label_parts(BAND, 0.0, _reps(), conds, ents, design={"min_share_design": 2})
    assert rec["provisional"] is False and rec["label"] == "robust"
    assert labels._n_combinations(["motion", "speed", "absent"], {e.name: e for e in ents}) == 8


def test_distinct_configurations_count_each_change_once_and_never_the_default():
    rows = [{"changed": {"a": 1}}, {"changed": {"a": 1}}, {"changed": {}}, {"changed": {"a": 2}}]
    assert labels._distinct(rows) == [rows[0], rows[3]]


# --------------------------------------------------------------------------- readings only: never robust


def test_readings_alone_agreeing_leave_the_claim_unexplored_not_robust():
    conds = [_single({"sigma": "smoothed"}, 0.0), _single({"sigma": "robust"}, 0.0)]
    rec = label_parts(BAND, 0.0, _reps(), conds, [READING])
    assert rec["provisional"] is False and rec["label"] == "unexplored"  # no world was varied
    assert rec["parts"]["claim"]["share"]["agree"] == 2


# --------------------------------------------------------------------------- condition rows


def test_a_condition_row_defaults_to_one_at_a_time_keeps_its_configuration_and_its_budget_mark():
    ents = [WORLD, READING]
    conds = [
        {"changed": {"motion": "weave"}, "measured": 0.0},  # no kind: one at a time
        {"changed": {"sigma": "smoothed"}, "config": {"sigma": "smoothed", "motion": "turn"}, "measured": 0.0},
        {"changed": {"motion": "turn"}, "kind": "joint", "measured": 0.0, "runs": 1, "left_by_budget": 4.0},
    ]
    rec = label_parts(BAND, 0.0, _reps(), conds, ents, needed=1)
    rows = rec["conditions"]
    assert [r["kind"] for r in rows] == ["single", "single", "joint"]
    assert rows[0]["config"] == {"motion": "weave", "sigma": "raw"}
    assert rows[1]["config"] == {"motion": "turn", "sigma": "smoothed"}
    assert rows[2]["left_by_budget"] == 4 and isinstance(rows[2]["left_by_budget"], int)
    assert "left_by_budget" not in rows[0] and "runs" not in rows[0]
    assert [r["text"] for r in rows] == ["motion = weave", "sigma = smoothed", "motion = turn"]
    assert [r["seed"] for r in rec["replicates"]] == [1, 2, 3]
    assert rec["coverage"].startswith("unexplored over 3 distinct configurations (2 one at a time")
    assert all("part_measured" not in r for r in (*rec["replicates"], *rows))


def test_the_share_counts_the_undecided_configurations_left_by_the_budget():
    rows = [
        {"verdict": "undecided", "left_by_budget": 3},
        {"verdict": "undecided", "left_by_budget": 2},
        {"verdict": "undecided"},
        {"verdict": "reproduced", "left_by_budget": 1},
    ]
    out = labels._share(rows, "reproduced")
    assert (out["left_by_budget"], out["agree"], out["undecided"]) == (2, 1, 3)
    assert labels._share(rows, "undecided") is None  # an undecided default has no share


# --------------------------------------------------------------------------- a part's record


def test_a_part_not_measured_is_undecided_with_no_projection_share_or_label():
    # the reading measured names only p1: the default's p2 has no value there
    rule = ByReading("scope", {"short": AllOf({"p1": BAND})}, default=AllOf({"p1": BAND, "p2": BAND}))
    m = ByReading.tag("short", {"p1": 0.0})
    reps = [{"seed": s, "measured": m} for s in (1, 2, 3)]
    rec = label_parts(rule, m, reps, [_single({"motion": "weave"}, m)], [WORLD])
    p2 = rec["parts"]["p2"]
    assert (p2["verdict"], p2["label"], p2["share"]) == ("undecided", "-", None)
    assert p2["runs_to_decide"] == {
        "replicates": None,
        "now": 3,
        "factor": None,
        "text": "undecided at 3 replicates; no number of runs is projected to decide it",
    }
    assert rec["where"] == ["(p2) undecided at 3 replicates; no number of runs is projected to decide it"]
    assert rec["parts"]["p1"]["share"]["agree"] == 1
    assert (rec["parts"]["p1"]["n_conditions"], p2["n_conditions"]) == (1, 0)


def test_every_parts_where_lines_are_kept_each_named_by_its_part():
    rule = AllOf({"p1": BAND, "p2": BAND})
    reps = [{"seed": s, "measured": {"p1": 0.0, "p2": 0.0}} for s in (1, 2, 3)]
    conds = [_single({"motion": "weave"}, {"p1": 3.0, "p2": 0.0}), _single({"motion": "turn"}, {"p1": 0.0, "p2": 3.0})]
    rec = label_parts(rule, {"p1": 0.0, "p2": 0.0}, reps, conds, [WORLD])
    assert rec["where"] == ["(p1) not reproduced when motion = weave", "(p2) not reproduced when motion = turn"]
    assert rec["parts"]["p1"]["where"] == ["not reproduced when motion = weave"]


def test_a_not_checkable_part_has_no_label_and_no_projection():
    rule = AllOf({"p1": BAND, "p2": NotCheckable("needs data the paper does not give")})
    reps = [{"seed": s, "measured": {"p1": 0.0, "p2": 0.0}} for s in (1, 2, 3)]
    rec = label_parts(rule, {"p1": 0.0, "p2": 0.0}, reps, [], [WORLD])
    p2 = rec["parts"]["p2"]
    assert (p2["label"], p2["runs_to_decide"], p2["where"], p2["share"]) == ("-", None, [], None)
    # no verdict to move, so nothing ranks what moves it (a round-off of 1e-13 once ranked an entry first)
    moved = [
        _single({"motion": "weave"}, {"p1": 0.1, "p2": 1e-13}),
        _single({"motion": "turn"}, {"p1": 0.2, "p2": 0.0}),
    ]
    rec = label_parts(rule, {"p1": 0.0, "p2": 0.0}, reps, moved, [WORLD])
    assert rec["parts"]["p2"]["sensitivity"] == [] and rec["parts"]["p1"]["sensitivity"]


def test_a_one_run_condition_agreeing_with_the_first_replicates_run_is_no_flip():
    # the first replicate's run is not reproduced, the pooled default reproduced: unstable, and a condition of one
    # run on the first replicate's random numbers that reads not reproduced is that run's draw, not a flip
    rec = label_parts(BAND, 0.0, _reps((3.0, 0.0, 0.0)), [_single({"motion": "weave"}, 3.0)], [WORLD])
    part = rec["parts"]["claim"]
    assert part["label"] == "unstable" and part["flips"] == []
    assert part["where"] == ["independent replicates disagree: not reproduced in 1, reproduced in 2 of 3"]


def test_lost_runs_that_do_not_change_the_verdict_do_not_decide_it():
    from tvtrack.measured import with_lost_runs

    every = Estimate(0.9, 0.1, 0.7, 1.1, 60, method="Student t")
    in_lock = Estimate(0.8, 0.1, 0.6, 1.0, 57, method="Student t")  # also outside [-0.5, 0.5]
    m = with_lost_runs(every, in_lock, lost=3, runs=60)
    part = label_parts(BAND, m, [{"seed": 1, "measured": m}], [], [])["parts"]["claim"]
    assert part["in_lock_verdict"] == "not reproduced" and part["decided_by_lost_runs"] is False


def test_the_sensitivity_of_a_part_reads_that_parts_value_in_each_condition():
    rule = AllOf({"p1": InBand("m", -10, 10), "p2": InBand("m", -10, 10)})
    reps = [{"seed": s, "measured": {"p1": 0.0, "p2": 0.0}} for s in (1, 2, 3)]
    conds = [_single({"motion": "weave"}, {"p1": 3.0, "p2": 0.0}), _single({"motion": "turn"}, {"p1": 6.0, "p2": 0.0})]
    rec = label_parts(rule, {"p1": 0.0, "p2": 0.0}, reps, conds, [WORLD])
    assert [(s["entry"], s["score"]) for s in rec["parts"]["p1"]["sensitivity"]] == [("motion", 1.0)]


# --------------------------------------------------------------------------- parts and readings


def test_part_pairs_skip_what_was_not_measured():
    rule = AllOf({"p1": BAND, "p2": BAND})
    assert part_pairs(rule, {"p1": 0.0, "p2": None}) == {"p1": (BAND, 0.0)}
    assert part_pairs(rule, {"p2": 1.0}) == {"p2": (BAND, 1.0)}
    assert part_pairs(BAND, None) == {} and part_pairs(BAND, 0.0) == {"claim": (BAND, 0.0)}
    by = ByReading("scope", {}, default=BAND)
    assert part_pairs(by, {"measured": 0.0}) == {} and part_pairs(by, {"reading": "x"}) == {}
    assert part_pairs(by, 0.0) == {}
    assert part_pairs(by, ByReading.tag("x", 0.0)) == {"claim": (BAND, 0.0)}


def test_a_readings_extra_parts_fold_into_each_labelled_part():
    every = AllOf({"p1": BAND, "p2": BAND, "p3": BAND})
    rule = ByReading("scope", {"every": every}, default=AllOf({"p1": BAND, "p2": BAND}))
    js = part_judgements(rule, ByReading.tag("every", {"p1": 3.0, "p2": None, "p3": 0.0}))
    assert {n: j.verdict for n, j in js.items()} == {"p1": "not reproduced"}  # p2 not measured: no verdict
    js = part_judgements(rule, ByReading.tag("every", {"p1": 0.0, "p2": 0.0, "p3": 3.0}))
    assert {n: j.verdict for n, j in js.items()} == {"p1": "not reproduced", "p2": "not reproduced"}
    # a one-part default: the reading's parts together are the claim
    one = ByReading("scope", {"every": AllOf({"a": BAND, "b": BAND})}, default=BAND)
    assert {n: j.verdict for n, j in part_judgements(one, ByReading.tag("every", {"a": 0.0, "b": 3.0})).items()} == {
        "claim": "not reproduced"
    }
    assert part_judgements(one, ByReading.tag("every", {"a": 0.0, "b": 0.0}))["claim"].verdict == "reproduced"


def test_the_weakest_label_follows_the_labels_order_not_the_alphabet():
    assert weakest_label(["robust", "unstable"]) == "unstable"
    assert weakest_label(["unexplored", "limited", "robust"]) == "limited"
    assert weakest_label([]) == "unexplored"


# --------------------------------------------------------------------------- the hand-built record


def test_a_hand_built_record_checks_its_seeds_note_and_choices_in_words():
    ok = dict(choices=[WORLD], seeds={1: 0.0, 2: 0.0, 3: 0.0})
    with pytest.raises(ValueError, match="^a robustness record without unstated choices needs a note"):
        Robustness(seeds=ok["seeds"]).validate()
    with pytest.raises(ValueError, match="^a deterministic robustness record needs a note saying why the seed"):
        Robustness(choices=[WORLD], deterministic=True).validate()
    Robustness(choices=[WORLD], seeds={1: 0.0}, deterministic=True, note="a closed form").validate()
    with pytest.raises(ValueError, match=r"^a robustness record needs the claim under at least 3 seeds, got 2$"):
        Robustness(choices=[WORLD], seeds={1: 0.0, 2: 0.0}).validate()
    bad = Robustness(**ok, conditions=[labels.Condition({"speed": 2}, 0.0)])
    with pytest.raises(ValueError, match=r"^condition \{'speed': 2\} names unknown choices \['speed'\]$"):
        bad.validate()
    off = Robustness(**ok, conditions=[labels.Condition({"motion": "fly"}, 0.0)])
    with pytest.raises(ValueError, match=r"motion = 'fly' is not among \['cv', 'weave', 'turn'\]"):
        off.validate()


def test_a_hand_built_record_names_single_and_joint_conditions_and_keeps_deterministic():
    conds = [labels.Condition({"motion": "weave"}, 0.0), labels.Condition({"motion": "turn", "sigma": "raw"}, 0.0)]
    rec = Robustness([WORLD, READING], conds, {1: 0.0, 2: 0.0, 3: 0.0}).record(BAND, 0.0)
    assert [c["kind"] for c in rec["conditions"]] == ["single", "joint"]
    assert rec["deterministic"] is False and rec["built"] == "by hand" and rec["note"] == ""
    assert rec["register"] == [WORLD.to_dict(), READING.to_dict()]
    det = Robustness([WORLD], conds[:1], {1: 0.0}, note="a closed form", deterministic=True).record(BAND, 0.0)
    assert det["deterministic"] is True and det["coverage"].endswith("x deterministic (no random draw)")


def test_a_part_the_measurement_left_out_is_undecided_in_the_claim_and_its_record():
    rule = AllOf({"a": BAND, "b": BAND})
    j = rule.judge({"a": Estimate.exact(0.0), "b": None})
    assert (j.verdict, j.settled, j.runs_factor) == ("undecided", False, math.inf)
    assert "(b) undecided: not measured" in j.why
    assert rule.judge({"a": Estimate.exact(3.0), "b": None}).verdict == "undecided"  # the open part could be partly
    with_reason = AllOf({"a": BAND, "why": NotCheckable("true by construction")})  # needs no value
    assert with_reason.judge({"a": Estimate.exact(0.0), "why": None}).verdict == "reproduced"
    reps = [{"seed": s, "measured": {"a": Estimate.exact(0.0), "b": Estimate.exact(0.0)}} for s in (1, 2, 3)]
    cond = _single({"motion": "weave"}, {"a": Estimate.exact(0.0), "b": None}, runs=3)
    rec = label_parts(rule, reps[0]["measured"], reps, [cond], [WORLD])
    assert rec["conditions"][0]["verdict"] == "undecided" and rec["conditions"][0]["parts"] == {"a": "reproduced"}
