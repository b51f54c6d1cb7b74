"""A part's share, its flips and the entries that move it (:mod:`tvtrack.attribution`), on hand-built rows.

Every explored row here is written by hand, so the right share, the right smallest flipping subset, its side
and its place in the list are known by construction; the share's interval is the Clopper-Pearson one from
the beta quantiles computed here, and the sensitivity scores are variances worked out by hand.
"""

import math

import pytest
from scipy import stats

from tvtrack.attribution import attribute, beside_operating_point, flip_side, paired_rows, phrase, sensitivity, share
from tvtrack.register import Entry

NO = "not reproduced"
YES = "reproduced"
MIXED = "readings or unreported settings changed together with worlds; no subset of them was found to flip it"

ENTRIES = {
    "r1": Entry("r1", "reading", 0, (0, 1, 2), "test reading", title="first reading", phrases={2: "r1 read as two"}),
    "r2": Entry("r2", "statistic", 0, (0, 1, 2), "test reading"),
    "r3": Entry("r3", "comparator", 0, (0, 1, 2), "test reading"),
    "s1": Entry("s1", "unreported setting", 0, (0, 1, 2), "test setting", title="drift spread"),
    "w1": Entry("w1", "regime", 0, (0, 1, 2), "test world"),
    "w2": Entry("w2", "model", 0, (0, 1, 2), "test world"),
}


def _row(kind, verdict=NO, runs=3, **changed):
    return {"changed": changed, "kind": kind, "verdict": verdict, "runs": runs}


def _names(flips):
    return [(f["kind"], f["side"], f["changed"]) for f in flips]


# --------------------------------------------------------------------------- share


def test_share_counts_every_configuration_and_its_interval_is_clopper_pearson():
    verdicts = [YES] * 5 + [NO] * 2 + ["partly"] + ["undecided", "not checkable"]
    s = share(verdicts, YES)
    assert {k: s[k] for k in ("agree", "flip", "undecided", "design", "decided")} == {
        "agree": 5,
        "flip": 3,  # "partly" is decisive and differs from the default
        "undecided": 2,
        "design": 10,
        "decided": 8,
    }
    assert s["value"] == 0.5  # of all ten, not of the eight decided
    assert s["ci_low"] == pytest.approx(stats.beta.ppf(0.025, 5, 6), abs=1e-10)
    assert s["ci_high"] == pytest.approx(stats.beta.ppf(0.975, 6, 5), abs=1e-10)


def test_share_interval_follows_the_confidence_asked():
    s = share([YES] * 7 + [NO] * 3, YES, confidence=0.8)
    assert s["ci_low"] == pytest.approx(stats.beta.ppf(0.1, 7, 4), abs=1e-10)
    assert s["ci_high"] == pytest.approx(stats.beta.ppf(0.9, 8, 3), abs=1e-10)
    full = share([NO] * 20, NO)  # all agree: [(alpha/2)^(1/n), 1]
    assert (full["value"], full["flip"], full["ci_high"]) == (1.0, 0, 1.0)
    assert full["ci_low"] == pytest.approx(0.025 ** (1 / 20), rel=1e-9)


def test_share_of_no_configuration_is_nan_in_the_whole_unit_interval():
    s = share([], YES)
    assert set(s) == {"agree", "flip", "undecided", "design", "decided", "value", "ci_low", "ci_high"}
    assert (s["agree"], s["flip"], s["undecided"], s["design"], s["decided"]) == (0, 0, 0, 0, 0)
    assert math.isnan(s["value"]) and (s["ci_low"], s["ci_high"]) == (0.0, 1.0)


def test_share_needs_a_decisive_default():
    assert share([YES, NO], "undecided") is None
    assert share([YES, NO], "not checkable") is None


# --------------------------------------------------------------------------- phrase and flip_side


def test_phrase_reads_each_change_and_the_default():
    assert phrase({}, ENTRIES) == "the default reading"
    assert phrase({"r1": 2, "s1": 1, "zz": 3}, ENTRIES) == "r1 read as two and drift spread = 1 and zz = 3"


def test_flip_side_of_each_mix_and_of_an_entry_of_no_register():
    assert flip_side({"zz": 1}, ENTRIES) == "reading"  # no register: read as a reading
    assert flip_side({"zz": 1, "s1": 1}, ENTRIES) == "setting"
    assert flip_side({"r1": 1, "r2": 1, "r3": 1}, ENTRIES) == "reading"
    assert flip_side({"r1": 1, "s1": 1}, ENTRIES) == "setting"
    assert flip_side({"w1": 1, "w2": 1}, ENTRIES) == "world"
    assert flip_side({"zz": 1, "w1": 1}, ENTRIES) == "unattributed"
    assert flip_side({"s1": 1, "w1": 1}, ENTRIES) == "unattributed"


# --------------------------------------------------------------------------- attribute


def test_singles_come_first_sorted_reading_setting_world_with_their_whole_record():
    rows = [
        _row("single", w1=1),
        _row("single", s1=1),
        {"changed": {"r1": 2}, "kind": "single", "verdict": NO},  # no runs: one run, not the default's
        _row("single", YES, r2=1),  # agrees
        _row("single", "undecided", r3=1),  # too small to decide
    ]
    assert attribute(YES, rows, ENTRIES) == [
        {"changed": {"r1": 2}, "side": "reading", "kind": "single", "verdict": NO, "text": "r1 read as two", "runs": 1},
        {
            "changed": {"s1": 1},
            "side": "setting",
            "kind": "single",
            "verdict": NO,
            "text": "drift spread = 1",
            "runs": 3,
        },
        {"changed": {"w1": 1}, "side": "world", "kind": "single", "verdict": NO, "text": "w1 = 1", "runs": 3},
    ]
    assert attribute("undecided", rows, ENTRIES) == []


def test_two_values_of_one_entry_are_two_flips():
    flips = attribute(YES, [_row("single", r1=1), _row("single", r1=2)], ENTRIES)
    assert [f["changed"] for f in flips] == [{"r1": 1}, {"r1": 2}]


def test_a_one_run_flip_must_differ_from_the_defaults_run_on_the_same_numbers():
    rows = [_row("single", runs=1, r1=1), _row("single", runs=3, r2=1)]
    # the default's own first run already read "not reproduced": one run saying so is no flip
    assert [f["changed"] for f in attribute(YES, rows, ENTRIES, same_seed=NO)] == [{"r2": 1}]
    # a same-seed run that is not decisive is no reference: the default's pooled verdict is
    assert [f["changed"] for f in attribute(YES, rows, ENTRIES, same_seed="undecided")] == [{"r1": 1}, {"r2": 1}]


def test_a_combination_names_the_joints_it_explains_once_before_a_joint_no_subset_explains():
    rows = [
        _row("joint", w1=2, w2=2),  # no subset flips it: its own entry, after every named combination
        _row("joint", r1=1, r2=1, w1=1),
        _row("joint", r1=1, r2=1, s1=1),
        _row("combination", r1=1, r2=1),  # flips alone: names both joints above, once
    ]
    assert attribute(YES, rows, ENTRIES) == [
        {
            "changed": {"r1": 1, "r2": 1},
            "side": "reading",
            "kind": "combination",
            "verdict": NO,
            "text": "first reading = 1 and r2 = 1",
            "runs": 3,
        },
        {
            "changed": {"w1": 2, "w2": 2},
            "side": "world",
            "kind": "joint",
            "verdict": NO,
            "text": "w1 = 2 and w2 = 2",
            "runs": 3,
        },
    ]


def test_the_smallest_flipping_subset_is_a_combination_even_beside_a_larger_joint_subset():
    rows = [
        _row("joint", r1=1, r2=1, r3=1, s1=1),
        _row("joint", r2=1, r3=1, s1=1),  # a smaller joint flip inside it, but not the smallest subset
        _row("combination", r1=1, r2=1),  # the smallest: names the four-entry joint
    ]
    assert _names(attribute(YES, rows, ENTRIES)) == [
        ("combination", "reading", {"r1": 1, "r2": 1}),
        ("joint", "setting", {"r2": 1, "r3": 1, "s1": 1}),
    ]


def test_a_joint_flip_that_is_its_own_smallest_subset_comes_before_a_larger_combination():
    """Pairs before triples whichever search found them: a two-world joint configuration no subset of which flips
    is listed before a three-world combination found inside another joint configuration."""
    entries = {**ENTRIES, "w3": Entry("w3", "regime", 0, (0, 1, 2), "test world")}
    rows = [
        _row("joint", r1=1, w1=2, w2=2, w3=2),
        _row("combination", w1=2, w2=2, w3=2),  # names the four-entry joint
        _row("joint", w1=1, w3=1),  # its own smallest subset
    ]
    assert _names(attribute(YES, rows, entries)) == [
        ("joint", "world", {"w1": 1, "w3": 1}),
        ("combination", "world", {"w1": 2, "w2": 2, "w3": 2}),
    ]


def test_only_the_smallest_of_the_flipping_subsets_is_named():
    rows = [
        _row("joint", r1=1, r2=1, r3=1, w1=1),
        _row("combination", r1=1, r2=1, r3=1),
        _row("combination", r1=1, r2=1),
    ]
    assert _names(attribute(YES, rows, ENTRIES)) == [("combination", "reading", {"r1": 1, "r2": 1})]


def test_a_smaller_joint_flip_is_named_in_its_own_right_with_the_mixed_sides_note():
    rows = [_row("joint", r1=1, w1=1, s1=1), _row("joint", r1=1, w1=1)]
    assert attribute(YES, rows, ENTRIES) == [
        {
            "changed": {"r1": 1, "w1": 1},
            "side": "unattributed",
            "kind": "joint",
            "verdict": NO,
            "text": "first reading = 1 and w1 = 1",
            "runs": 3,
            "note": MIXED,
        }
    ]


def test_a_joint_a_single_explains_is_skipped_and_the_next_joint_still_read():
    rows = [_row("single", r1=1), _row("joint", r1=1, w1=1), _row("joint", w1=2, w2=2)]
    assert _names(attribute(YES, rows, ENTRIES)) == [
        ("single", "reading", {"r1": 1}),
        ("joint", "world", {"w1": 2, "w2": 2}),
    ]


def test_joints_of_one_size_are_sorted_reading_setting_unattributed_world():
    rows = [
        _row("joint", w1=2, w2=2),
        _row("joint", r1=1, w1=1),
        _row("joint", r1=2, s1=1),
        _row("joint", r2=1, r3=1),
    ]
    assert [f["side"] for f in attribute(YES, rows, ENTRIES)] == ["reading", "setting", "unattributed", "world"]


def test_a_joint_beyond_the_searched_size_is_unattributed_with_its_count_after_the_others():
    big = {"r1": 1, "r2": 1, "r3": 1, "s1": 1, "w1": 1}  # five entries: more than max_subset + 1 = 4
    rows = [_row("joint", **big), _row("joint", w1=2, w2=2)]
    flips = attribute(YES, rows, ENTRIES)
    assert _names(flips) == [("joint", "world", {"w1": 2, "w2": 2}), ("joint", "unattributed", big)]
    assert "note" not in flips[0]
    assert (
        flips[1]["note"]
        == "5 entries changed together and no subset of up to 3 of them, at the paper's operating point, was found to "
        "flip it: unattributed"
    )
    # searched up to four: the five entries are their own smallest subset (mixed sides: the mixed note)
    wider = attribute(YES, rows, ENTRIES, max_subset=4)
    assert _names(wider) == [("joint", "world", {"w1": 2, "w2": 2}), ("joint", "unattributed", big)]
    assert wider[1]["note"] == MIXED


def test_at_pairs_only_a_triple_of_readings_is_unattributed_after_a_pair_of_worlds():
    rows = [_row("joint", r1=1, r2=1, r3=1), _row("joint", w1=1, w2=1)]
    flips = attribute(YES, rows, ENTRIES, max_subset=1)
    assert _names(flips) == [
        ("joint", "world", {"w1": 1, "w2": 1}),
        ("joint", "unattributed", {"r1": 1, "r2": 1, "r3": 1}),
    ]
    assert (
        flips[1]["note"]
        == "3 entries changed together and no subset of up to 1 of them, at the paper's operating point, was found to "
        "flip it: unattributed"
    )


# --------------------------------------------------------------------------- sensitivity


def test_sensitivity_scores_are_one_at_a_time_variances_as_shares():
    entries = {
        "a": Entry("a", "regime", 0, (0, 1, 2), "w", title="sensor noise"),
        "b": Entry("b", "regime", 0, (0, 1), "w"),
    }
    rows = [
        {"config": {"a": 0, "b": 0, "c": 0}, "value": 0.0},
        {"config": {"a": 1, "b": 0, "c": 0}, "value": 2.0},
        {"config": {"a": 2, "b": 0, "c": 0}, "value": -2.0},
        {"config": {"a": 0, "b": 1, "c": 0}, "value": 0.5},
        {"config": {"a": 0, "b": 1, "c": 0}, "value": 1.5},  # b = 1 averages to 1.0
        {"config": {"a": 1, "b": 1, "c": 0}, "value": 100.0},  # joint: left out
        {"config": {"a": 0, "b": 0, "c": 1}, "value": math.nan},  # not finite: left out
    ]
    # a: var(0, 2, -2) = 8/3; b: var(0, 1) = 1/4; c: never moved alone, 0; total 35/12
    out = sensitivity(rows, ["a", "b", "c"], entries, {"a": 0, "b": 0, "c": 0})
    assert [(d["entry"], d["title"]) for d in out] == [("a", "sensor noise"), ("b", "b"), ("c", "c")]
    assert [d["score"] for d in out] == pytest.approx([32 / 35, 3 / 35, 0.0], rel=1e-12, abs=1e-15)
    assert all(set(d) == {"entry", "title", "score"} for d in out)


def test_sensitivity_reads_an_entry_missing_from_a_row_as_its_default():
    rows = [{"config": {}, "value": 0.0}, {"config": {"a": 1}, "value": 3.0}, {"config": {"b": 1}, "value": 1.0}]
    out = sensitivity(rows, ["a", "b"], {}, {"a": 0, "b": 0})  # var(0, 3) = 9/4, var(0, 1) = 1/4
    assert [(d["entry"], d["title"]) for d in out] == [("a", "a"), ("b", "b")]
    assert [d["score"] for d in out] == pytest.approx([0.9, 0.1], rel=1e-12)


def test_sensitivity_keeps_a_value_of_none_apart_from_the_default():
    rows = [
        {"config": {"cap": 5, "b": 0}, "value": 0.0},
        {"config": {"cap": None, "b": 0}, "value": 10.0},  # e.g. "no cap"
        {"config": {"cap": 10, "b": 0}, "value": 4.0},
        {"config": {"cap": 5, "b": 1}, "value": 3.0},
    ]
    # cap: var(0, 10, 4) = 152/9; b: var(0, 3) = 9/4; total 689/36
    out = sensitivity(rows, ["cap", "b"], {}, {"cap": 5, "b": 0})
    assert [d["entry"] for d in out] == ["cap", "b"]
    assert [d["score"] for d in out] == pytest.approx([608 / 689, 81 / 689], rel=1e-12)


def test_sensitivity_needs_the_default_and_some_spread():
    flat = [{"config": {"a": a}, "value": 1.0} for a in (0, 1, 2)]
    assert sensitivity(flat, ["a"], {}, {"a": 0}) == []
    assert sensitivity(flat[1:], ["a"], {}, {"a": 0}) == []


def test_sensitivity_ranks_no_entry_whose_moves_stay_under_the_floor():
    """Round-off far inside a band (C004-4's identity: values of 1e-13 against a bound of 1e-9) ranks nothing;
    a move above the floor ranks as before."""
    d = {"a": 0, "b": 0}
    rows = [
        {"config": d, "value": 1.00e-13},
        {"config": {"a": 1, "b": 0}, "value": 1.12e-13},
        {"config": {"a": 0, "b": 1}, "value": 0.93e-13},
    ]
    assert [r["entry"] for r in sensitivity(rows, ["a", "b"], {}, d)] == ["a", "b"]  # no floor: the old ranking
    assert sensitivity(rows, ["a", "b"], {}, d, floor=1e-11) == []
    rows[2]["value"] = 5e-11  # b moves by more than the floor, a does not
    out = sensitivity(rows, ["a", "b"], {}, d, floor=1e-11)
    assert [(r["entry"], r["score"]) for r in out] == [("b", 1.0), ("a", 0.0)]


def test_paired_rows_compare_each_condition_with_the_default_over_its_own_replicates():
    """A condition run on the first replicate's seed alone is compared with that replicate, not with the pool: a
    condition that equals its own replicate's value moves nothing."""
    reps = [-0.679, -0.55, -0.532]  # the default's replicates; their mean is -0.587
    conds = [{"config": {"a": 1}, "runs": 1}, {"config": {"b": 1}, "runs": 3}, {"config": {"c": 1}}]
    out = paired_rows(conds, [-0.679, -0.4, -0.3], reps)
    mean = sum(reps) / 3
    assert out[0]["value"] == pytest.approx(mean)  # the same as its own replicate: no move from the default
    assert out[1]["value"] == pytest.approx(-0.4) and out[2]["value"] == pytest.approx(-0.3)  # every replicate
    nan = paired_rows(conds[:1], [-0.679], [-0.679, math.nan])  # a replicate without a value: compared as it is
    assert nan[0]["value"] == pytest.approx(-0.679)


def test_beside_operating_point_counts_each_configuration_once_and_lists_its_flips():
    rows = [
        {"changed": {"w": 8}, "verdict": "reproduced", "text": "w = 8", "off_operating_point": True},
        {"changed": {"w": 8}, "verdict": "reproduced", "text": "w = 8", "off_operating_point": True},
        {"changed": {"w": 8, "r": 1}, "verdict": "undecided", "text": "w = 8, r = 1", "off_operating_point": True},
        {"changed": {"w": 1, "r": 1}, "verdict": "not reproduced", "text": "w = 1, r = 1", "off_operating_point": True},
        {"changed": {"r": 1}, "verdict": "reproduced", "text": "r = 1"},
    ]
    out = beside_operating_point(rows, "not reproduced")
    assert (out["agree"], out["flip"], out["undecided"]) == (1, 1, 1)
    assert out["flips"] == [{"changed": {"w": 8}, "verdict": "reproduced", "text": "w = 8"}]
    assert beside_operating_point(rows[4:], "not reproduced") is None


def test_beside_operating_point_counts_every_agreeing_configuration_and_lists_smaller_flips_first():
    rows = [
        {"changed": {"w": 8, "r": 1}, "verdict": "reproduced", "text": "w = 8, r = 1", "off_operating_point": True},
        {"changed": {"w": 8}, "verdict": "reproduced", "text": "w = 8", "off_operating_point": True},
        {"changed": {"w": 1}, "verdict": "not reproduced", "text": "w = 1", "off_operating_point": True},
        {"changed": {"w": 1, "r": 1}, "verdict": "not reproduced", "text": "w = 1, r = 1", "off_operating_point": True},
    ]
    out = beside_operating_point(rows, "not reproduced")
    assert (out["agree"], out["flip"]) == (2, 2)
    assert [f["text"] for f in out["flips"]] == ["w = 8", "w = 8, r = 1"]


def test_sensitivity_floor_is_a_distance_from_the_default_and_a_move_at_the_floor_does_not_count():
    d = {"a": 0}
    rows = [{"config": d, "value": -1.0}, {"config": {"a": 1}, "value": -1.0005}]
    assert sensitivity(rows, ["a"], {}, d, floor=0.001) == []  # moved 0.0005 from -1.0, not 2.0005
    rows = [{"config": d, "value": 0.0}, {"config": {"a": 1}, "value": 0.25}]
    assert sensitivity(rows, ["a"], {}, d, floor=0.25) == []  # exactly the floor: not more than it
    assert [r["entry"] for r in sensitivity(rows, ["a"], {}, d, floor=0.2)] == ["a"]


def test_a_flip_with_an_undecided_smaller_subset_says_it_is_the_smallest_found_not_shown():
    # the pair flips; one of its entries alone was left smaller than the default needed (undecided): the pair is
    # the smallest found, and the flip records which smaller subset stays open
    rows = [
        _row("combination", s1=1, w1=1),
        _row("single", "undecided", runs=1, s1=1),
        _row("single", YES, w1=1),
    ]
    (flip,) = attribute(YES, rows, ENTRIES)
    assert flip["changed"] == {"s1": 1, "w1": 1} and flip["undecided_subsets"] == ["drift spread = 1"]
    rows[1] = _row("single", YES, s1=1)  # every smaller subset decided: the smallest shown
    (flip,) = attribute(YES, rows, ENTRIES)
    assert "undecided_subsets" not in flip


def test_the_undecided_subsets_are_the_strict_subsets_of_the_flip_each_named_once():
    rows = [
        _row("combination", s1=1, w1=1, r1=1),  # the flip: a triple
        _row("single", "undecided", runs=1, s1=1),
        _row("pinned", "undecided", runs=1, s1=1),  # the same subset measured twice: named once
        _row("combination", "undecided", runs=1, s1=1, w1=1),
        _row("single", "undecided", runs=1, w2=1),  # another entry: no subset
        _row("single", "undecided", runs=1, r1=2),  # the same entry at another value: no subset
        _row("combination", "undecided", runs=1, s1=1, w1=1, r1=2),  # as many changes, another value
        _row("joint", "undecided", runs=1, s1=1, w1=1, r1=1),  # the flip's own changes again: no smaller subset
        {"changed": {}, "kind": "replicate", "verdict": "undecided", "runs": 1},  # the default: changes nothing
        _row("single", YES, w1=1),
        _row("single", YES, r1=1),
    ]
    (flip,) = attribute(YES, rows, ENTRIES)
    assert flip["changed"] == {"s1": 1, "w1": 1, "r1": 1}
    assert flip["undecided_subsets"] == ["drift spread = 1", "drift spread = 1 and w1 = 1"]


def test_the_where_line_and_the_bracket_say_a_flip_may_not_be_the_smallest():
    from tvtrack.flip_words import label_basis
    from tvtrack.labels import label_parts
    from tvtrack.montecarlo import Estimate
    from tvtrack.verdicts import InBand

    band = InBand("mean", -0.5, 0.5)
    ents = [ENTRIES["s1"], Entry("s2", "unreported setting", 0, (0, 1), "test setting", title="gain law")]
    reps = [{"seed": s, "measured": Estimate.exact(0.0)} for s in (1, 2, 3)]
    conds = [
        {"changed": {"s1": 1, "s2": 1}, "kind": "joint", "measured": Estimate.exact(3.0), "runs": 3},
        {"changed": {"s1": 1}, "kind": "single", "measured": Estimate.exact(3.0), "runs": 1},  # below the size
        {"changed": {"s2": 1}, "kind": "single", "measured": Estimate.exact(0.1), "runs": 3},
    ]
    rb = label_parts(band, Estimate.exact(0.0), reps, conds, ents, needed=3)
    part = rb["parts"]["claim"]
    assert part["where"] == [
        "not reproduced when drift spread = 1 and gain law = 1 (the smallest found: drift spread = 1 stays undecided)"
    ]
    rb["register"] = [e.to_dict() for e in ents]
    claim = {"id": "C9-9", "verdict": "reproduced", "robustness": rb}
    assert label_basis(claim).startswith(
        "two unprinted settings together (or fewer: a smaller part of them stays undecided)"
    )
    conds[2] = {"changed": {"s2": 1}, "kind": "single", "measured": Estimate.exact(3.0), "runs": 1}  # both open
    part = label_parts(band, Estimate.exact(0.0), reps, conds, ents, needed=3)["parts"]["claim"]
    assert part["where"] == [
        "not reproduced when drift spread = 1 and gain law = 1 (the smallest found: drift spread = 1; gain law = 1 "
        "stay undecided)"
    ]
    conds.pop(1), conds.pop(1)  # no smaller subset measured: the pair is the smallest there is, no suffix
    part = label_parts(band, Estimate.exact(0.0), reps, conds, ents, needed=3)["parts"]["claim"]
    assert part["where"] == ["not reproduced when drift spread = 1 and gain law = 1"]
