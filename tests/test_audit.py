"""The label audit (tvtrack.pipeline.audit): a record the label machinery writes passes it, and each way a label can
say more than its record shows is found, one planted fault at a time."""

import copy

import pytest

from tvtrack.run_words import share_counts
from tvtrack.labels import label_parts
from tvtrack.montecarlo import Estimate
from tvtrack.pipeline.audit import audit_claim, audit_markdown, audit_runs
from tvtrack.register import Entry
from tvtrack.verdicts import InBand

BAND = InBand("mean", -0.5, 0.5, "px")
READING = Entry("sigma", "reading", "raw", ("raw", "smoothed"), "the text reads either way")
SETTING = Entry("law", "unreported setting", "linear", ("linear", "step"), "the paper used one and never said which")
WORLD = Entry("motion", "regime", "cv", ("cv", "turn"), "a world beyond the paper")
LOUD = Entry("noise", "regime", "low", ("low", "high"), "a world beyond the paper")
ENTRIES = (READING, SETTING, WORLD, LOUD)
IN, OUT = Estimate.exact(0.0), Estimate.exact(3.0)
MOVED = Estimate.exact(0.1)  # agrees with IN (inside the band), but the condition moved the value: it reached it
SINGLES_THAT_AGREE = ({"law": "step"}, {"motion": "turn"}, {"noise": "high"})


def _cond(changed, measured, kind="single", runs=2):
    return {"changed": changed, "kind": kind, "measured": measured, "runs": runs, "config": changed}


def _claim():
    """A claim the default needs 2 replicates to decide: the reading flips it alone, the setting agrees, the world
    agrees alone and flips together with the loud world (a combination isolates the pair); one joint configuration
    has a single replicate."""
    return _recorded(
        _cond({"sigma": "raw", "law": "step", "motion": "turn", "noise": "high"}, OUT, "joint"),
        _cond({"motion": "turn", "noise": "high"}, OUT, "combination"),
        _cond({"law": "step", "motion": "turn"}, IN, "joint", runs=1),  # smaller than the default needed: undecided
    )


def _recorded(*extra):
    """The record of a claim the default needs 2 replicates to decide, over the four single conditions (the reading
    flips it alone, the others agree) and ``extra`` conditions."""
    reps = [{"seed": s, "measured": IN} for s in (1, 2, 3)]
    singles = [_cond({"sigma": "smoothed"}, OUT), *(_cond(c, IN) for c in SINGLES_THAT_AGREE)]
    rb = label_parts(BAND, IN, reps, [*singles, *extra], ENTRIES, design={"min_share_design": 4}, needed=2)
    rb["register"] = [e.to_dict() for e in ENTRIES]
    rb["design"] = {"replicates_needed": {"C9-1": 2}, "min_share_design": 4}
    return {"id": "C9-1", "robustness": rb}


def _flip(claim, changed_keys):
    return next(f for f in claim["robustness"]["parts"]["claim"]["flips"] if set(f["changed"]) == set(changed_keys))


def test_the_machinery_s_own_record_passes_with_its_flips_on_their_sides():
    claim = _claim()
    part = claim["robustness"]["parts"]["claim"]
    assert part["label"] == "depends"
    assert {tuple(sorted(f["changed"])): f["side"] for f in part["flips"]} == {
        ("sigma",): "reading",
        ("motion", "noise"): "world",
    }
    assert audit_claim(claim) == []


def test_a_decisive_condition_smaller_than_the_default_needed_is_found():
    claim = _claim()
    claim["robustness"]["conditions"][1]["runs"] = 1
    assert audit_claim(claim) == [
        f"C9-1: {claim['robustness']['conditions'][1]['text']} counts at 1 replicates, the default needed 2"
    ]


def test_an_entry_the_claim_does_not_declare_is_found():
    claim = _claim()
    claim["robustness"]["register"] = [e.to_dict() for e in ENTRIES if e.name != "noise"]
    problems = audit_claim(claim)
    assert sum("changes ['noise'], not in the claim's register" in p for p in problems) == 3  # single, joint, combo


def test_a_share_of_the_decided_configurations_only_is_found():
    claim = _claim()
    share = claim["robustness"]["parts"]["claim"]["share"]
    assert (share["agree"], share["flip"], share["undecided"], share["design"]) == (3, 2, 1, 6)
    share["undecided"], share["design"] = 0, share["decided"]  # the decided configurations only
    assert audit_claim(claim) == ["C9-1: the share reads (3, 2, 0) of 5, its configurations give (3, 2, 1) of 6"]


@pytest.mark.parametrize("side", ["world", "setting", "unattributed"])
def test_a_flip_filed_on_another_side_than_its_entries_is_found(side):
    claim = _claim()
    _flip(claim, ["sigma"])["side"] = side
    assert f"the flip at sigma = smoothed is filed as {side}, its entries make it reading" in audit_claim(claim)[0]


def test_a_flip_mixing_a_reading_with_worlds_filed_as_world_is_found():
    claim = _claim()
    f = _flip(claim, ["motion", "noise"])
    f["changed"] = {"sigma": "raw", "motion": "turn", "noise": "high"}
    problems = audit_claim(claim)
    assert any("is filed as world, its entries make it unattributed" in p for p in problems)


def test_a_flip_named_by_more_than_the_smallest_configuration_is_found():
    claim = _claim()
    f = _flip(claim, ["motion", "noise"])
    f["changed"] = {"sigma": "raw", "law": "step", "motion": "turn", "noise": "high"}
    f["side"] = "unattributed"
    problems = audit_claim(claim)
    assert any("is not the smallest" in p and "turn" in p for p in problems)


def test_a_flip_the_record_drops_is_found():
    claim = _claim()
    part = claim["robustness"]["parts"]["claim"]
    part["flips"] = [f for f in part["flips"] if f["side"] != "reading"]
    problems = audit_claim(claim)
    assert any("flips the part and no named flip explains it" in p and "smoothed" in p for p in problems)
    assert "C9-1: labelled depends without a flip by a reading, a setting or an unattributed mix" in problems


def test_a_flip_smaller_than_the_default_needed_is_found():
    claim = _claim()
    _flip(claim, ["sigma"])["runs"] = 1
    assert "C9-1: the flip at sigma = smoothed ran 1 replicates, the default needed 2" in audit_claim(claim)


@pytest.mark.parametrize(
    "label, words",
    [
        ("limited", "labelled limited, but its flips are on the sides ['reading', 'world']"),
        ("robust", "labelled robust with 2 flip(s)"),
        ("unexplored", "labelled unexplored with 2 flip(s)"),
    ],
)
def test_a_label_stronger_than_its_flips_is_found(label, words):
    claim = _claim()
    claim["robustness"]["parts"]["claim"]["label"] = label
    claim["robustness"]["parts"]["claim"]["share"]["unchanged"] = 0  # every configuration reached it: decided 5
    assert audit_claim(claim) == [f"C9-1: {words}"]


def test_the_audit_reads_finished_runs_and_writes_its_section():
    good, bad = _claim(), copy.deepcopy(_claim())
    bad["robustness"]["parts"]["claim"]["label"] = "robust"
    bad["robustness"]["parts"]["claim"]["share"]["unchanged"] = 0
    runs = {"a": ({}, {"claims": [good]}), "b": ({}, {"claims": [bad]}), "c": ({"status": "failed"}, None)}
    problems = audit_runs(runs)
    assert problems == {"a": [], "b": ["C9-1: labelled robust with 2 flip(s)"]}
    text = "\n".join(audit_markdown(problems))
    assert "1 problem(s):" in text and "- `b`: C9-1: labelled robust with 2 flip(s)" in text
    assert "No problem in 1 notebook(s)." in "\n".join(audit_markdown({"a": []}))


def test_a_flip_of_more_entries_than_the_subset_search_tries_filed_as_a_world_is_found():
    claim = _claim()
    claim["robustness"]["design"]["max_subset"] = 1  # singles tried: a pair is its own smallest, a world
    assert audit_claim(claim) == []
    claim["robustness"]["design"]["max_subset"] = 0  # nothing tried, not even singles: the pair is not isolated
    problems = audit_claim(claim)
    assert problems == [
        "C9-1: the flip at motion = turn, noise = high changes 2 entries, more than one beyond the 0 the subset "
        "search tried, and is filed as world"
    ]


def test_a_flip_named_as_its_own_smallest_whose_subsets_were_never_measured_is_found():
    """A flip one entry beyond the searched size is its own smallest only where every smaller subset was measured:
    the pairs and triples the search tries, and each single entry where the one-at-a-time stage ran."""
    claim = _claim()
    claim["robustness"]["design"] |= {"max_subset": 1, "one_at_a_time": True}
    assert audit_claim(claim) == []  # both single entries of the named pair were measured
    claim["robustness"]["conditions"] = [
        c for c in claim["robustness"]["conditions"] if c["changed"] != {"noise": "high"}
    ]
    untried = "C9-1: the flip at motion = turn, noise = high is named with noise = 'high' never measured"
    assert untried in audit_claim(claim)
    claim["robustness"]["design"]["one_at_a_time"] = False  # no single entry tried: none is missing, none shown
    assert not any("never measured" in p for p in audit_claim(claim))


def test_the_explorer_measures_every_subset_of_a_flip_one_entry_beyond_its_search():
    """Four worlds that flip the claim only together, measured as a pinned joint condition (no joint design): the
    search measures every pair and triple of them, so the four are named as their own smallest flip (a world) and
    the audit finds nothing; stopped at pairs, the record holds no triple and the four read unattributed."""
    import numpy as np

    from tvtrack.explore import explore
    from tvtrack.montecarlo import mean_ci
    from tvtrack.register import Register

    four = dict.fromkeys("abcd", 1)
    reg = Register([Entry(k, "regime", 0, (0, 1), f"world {k}") for k in "abcde"], pinned=[four])

    def measure(config, seed):
        shift = 3.0 if all(config[k] == 1 for k in "abcd") else 0.0
        return {"X": mean_ci(np.random.default_rng(seed).normal(shift, 1.0, 400))}

    for max_subset, side in ((3, "world"), (2, "unattributed")):
        ex = explore(measure, reg, {"X": BAND}, seed=3, replicates=3, max_subset=max_subset)
        claim = {"id": "X", "robustness": ex.record("X")}
        (flip,) = claim["robustness"]["parts"]["claim"]["flips"]
        assert flip["changed"] == four and flip["side"] == side
        assert audit_claim(claim) == []
        combos = [c["changed"] for c in claim["robustness"]["conditions"] if c["kind"] == "combination"]
        assert sorted(map(len, combos)) == [2] * 6 + [3] * 4 * (max_subset == 3)  # every pair (and triple) of four


def _claim_with_pinned():
    """:func:`_claim`'s single conditions with two pinned configurations (outside the design): one flips, one agrees."""
    return _recorded(
        _cond({"law": "step", "noise": "high"}, OUT, "pinned"),
        _cond({"law": "step", "motion": "turn"}, IN, "pinned"),
        _cond({"noise": "high", "law": "linear"}, OUT, "combination"),
    )


def test_pinned_configurations_are_counted_beside_the_share_and_a_share_that_drops_them_is_found():
    claim = _claim_with_pinned()
    share = claim["robustness"]["parts"]["claim"]["share"]
    # the share stays over the design (4 one-at-a-time configurations); the two pinned ones are counted beside it
    assert (share["agree"], share["flip"], share["undecided"], share["design"]) == (3, 1, 0, 4)
    assert share["pinned"] == {"agree": 1, "flip": 1, "undecided": 0}
    assert audit_claim(claim) == []
    del share["pinned"]  # a record whose share hides the pinned flip beside it
    assert audit_claim(claim) == [
        "C9-1: the pinned beside the share read {'agree': 0, 'flip': 0, 'undecided': 0}, "
        "their verdicts give {'agree': 1, 'flip': 1, 'undecided': 0}"
    ]
    share["pinned"] = {"agree": 2, "flip": 0, "undecided": 0}  # the flip counted as agreeing
    assert len(audit_claim(claim)) == 1


def test_a_combinations_flip_is_counted_beside_the_share_and_a_share_that_drops_it_is_found():
    # the pair (motion, noise) flips the claim alone: a flip the part names, so the share says it beside its design
    claim = _claim()
    part = claim["robustness"]["parts"]["claim"]
    assert {tuple(sorted(f["changed"])) for f in part["flips"]} >= {("motion", "noise")}
    assert part["share"]["combinations"] == {"agree": 0, "flip": 1, "undecided": 0}
    assert "of 1 combination of entries searched inside flipping joint ones, 1 flips" in share_counts(part["share"])
    assert audit_claim(claim) == []
    del part["share"]["combinations"]
    assert audit_claim(claim) == [
        "C9-1: the combinations beside the share read {'agree': 0, 'flip': 0, 'undecided': 0}, "
        "their verdicts give {'agree': 0, 'flip': 1, 'undecided': 0}"
    ]


def test_a_claim_without_pinned_configurations_has_no_pinned_count():
    share = _claim()["robustness"]["parts"]["claim"]["share"]
    assert "pinned" not in share


def test_the_share_words_say_the_pinned_configurations_beside_the_design():
    from tvtrack.wording import share_counts

    share = _claim_with_pinned()["robustness"]["parts"]["claim"]["share"]
    assert share_counts(share) == (
        "3 agree, 1 flips and 0 stay undecided of 4 explored configurations; of 2 pinned configurations measured "
        "beside them (joint configurations every run measures), 1 flips, 1 agrees and 0 stay undecided; of 1 "
        "combination of entries searched inside flipping joint ones, 1 flips, 0 agree and 0 stay undecided"
    )
    one = share_counts({**share, "pinned": {"agree": 0, "flip": 1, "undecided": 0}, "combinations": None})
    assert one.endswith(
        "of 1 pinned configuration measured beside them (joint configurations every run measures), "
        "1 flips, 0 agree and 0 stay undecided"
    )


def _off_point_claim():
    """A claim whose world entry has a value off the paper's operating point that flips it alone, and a setting
    that agrees: the machinery keeps the flip out of the label and counts it beside."""
    fast = Entry("speed", "unreported setting", 3.0, (1.0, 3.0, 8.0), "never printed", off_operating_point=(8.0,))
    reps = [{"seed": s, "measured": IN} for s in (1, 2, 3)]
    conds = [_cond({"speed": 8.0}, OUT), _cond({"speed": 1.0}, IN), _cond({"law": "step"}, IN)]
    rb = label_parts(BAND, IN, reps, conds, (fast, SETTING), design={"min_share_design": 2}, needed=2)
    rb["register"] = [fast.to_dict(), SETTING.to_dict()]
    rb["design"] = {"replicates_needed": {"C9-2": 2}}
    return {"id": "C9-2", "robustness": rb}


def test_a_flip_off_the_operating_point_is_counted_beside_the_label_and_the_audit_checks_it():
    claim = _off_point_claim()
    part = claim["robustness"]["parts"]["claim"]
    assert part["flips"] == [] and part["label"] == "unexplored"  # no world varied at the operating point
    assert {k: part["off_operating_point"][k] for k in ("agree", "flip", "undecided")} == {
        "agree": 0,
        "flip": 1,
        "undecided": 0,
    }
    assert part["share"]["design"] == 2 and part["share"]["off_operating_point"]["flip"] == 1
    assert audit_claim(claim) == []
    planted = copy.deepcopy(claim)  # the flip filed in the label, as the records before counted it
    p = planted["robustness"]["parts"]["claim"]
    p["flips"] = [
        {
            "changed": {"speed": 8.0},
            "side": "setting",
            "kind": "single",
            "verdict": "not reproduced",
            "text": "speed = 8",
        }
    ]
    p["label"] = "depends"
    assert any("leaves the paper's operating point and is counted in the label" in m for m in audit_claim(planted))
    miscounted = copy.deepcopy(claim)
    miscounted["robustness"]["parts"]["claim"]["off_operating_point"]["flip"] = 0
    assert any("outside the operating point the record counts" in m for m in audit_claim(miscounted))


def test_a_joint_the_exploration_could_not_keep_at_the_operating_point_is_counted_beside_and_audited():
    # a joint world that no re-calibration brings back to the paper's error: no register value alone marks it, the
    # exploration's reason does; its flip must stay out of the label as a marked value's does
    reps = [{"seed": s, "measured": IN} for s in (1, 2, 3)]
    lost = {**_cond({"law": "step", "motion": "turn"}, OUT, kind="joint"), "operating_point_lost": "no bandwidth fits"}
    conds = [lost, _cond({"law": "step"}, MOVED), _cond({"motion": "turn"}, MOVED)]
    rb = label_parts(BAND, IN, reps, conds, (SETTING, WORLD), design={"min_share_design": 2}, needed=2)
    rb["register"] = [SETTING.to_dict(), WORLD.to_dict()]
    rb["design"] = {"replicates_needed": {"C9-3": 2}}
    claim = {"id": "C9-3", "robustness": rb}
    part = rb["parts"]["claim"]
    assert part["flips"] == [] and part["label"] == "robust" and part["share"]["design"] == 2
    assert part["off_operating_point"]["flip"] == 1 and part["off_operating_point"]["flips"][0]["why"]
    assert any(w.endswith("(outside the paper's operating point: no bandwidth fits)") for w in part["where"])
    assert audit_claim(claim) == []
    planted = copy.deepcopy(claim)  # the flip filed in the label
    p = planted["robustness"]["parts"]["claim"]
    p["flips"] = [dict(part["off_operating_point"]["flips"][0], side="unattributed", kind="joint")]
    p["label"] = "depends"
    assert any("leaves the paper's operating point and is counted in the label" in m for m in audit_claim(planted))


def test_the_share_words_say_the_configurations_outside_the_operating_point_beside_the_design():
    from tvtrack.wording import share_counts

    share = _off_point_claim()["robustness"]["parts"]["claim"]["share"]
    assert share_counts(share) == (
        "2 agree, 0 flip and 0 stay undecided of 2 explored configurations; of 1 configuration outside the paper's "
        "operating point (counted beside the label, not in it), 1 flips, 0 agree and 0 stay undecided"
    )


def test_configurations_outside_the_operating_point_do_not_make_a_design_look_larger_or_vary_the_world():
    """The design's size, its coverage line and whether it varied the world read only the configurations at the
    paper's operating point: a register-marked value and a configuration the exploration reported are counted beside,
    never twice (a marked value is no reachable configuration to begin with), and a design whose every reachable
    configuration was reported stays provisional."""
    w = Entry("speed", "regime", 0, (0, 1, 9), "w", off_operating_point=(9,))
    v = Entry("gust", "regime", 0, (0, 1), "w")
    reps = [{"seed": s, "measured": IN} for s in (1, 2, 3)]
    marked = _cond({"speed": 9}, OUT)
    lost = {**_cond({"speed": 1, "gust": 1}, OUT, kind="joint"), "operating_point_lost": "outside 1-2 px"}
    # 3 reachable configurations, 1 reported: 2 needed, 1 explored at the operating point
    rb = label_parts(BAND, IN, reps, [_cond({"speed": 1}, IN), marked, lost], (w, v), needed=2)
    assert rb["provisional"] and rb["coverage"].startswith("unexplored over 1 distinct configurations (1 one at a time")
    assert "2 outside the paper's operating point, counted beside the label" in rb["coverage"]
    rb = label_parts(
        BAND, IN, reps, [_cond({"speed": 1}, MOVED), _cond({"gust": 1}, MOVED), marked, lost], (w, v), needed=2
    )
    assert not rb["provisional"] and rb["label"] == "robust"
    every = [
        {**_cond(ch, OUT, kind="joint" if len(ch) > 1 else "single"), "operating_point_lost": "outside 1-2 px"}
        for ch in ({"speed": 1}, {"gust": 1}, {"speed": 1, "gust": 1})
    ]
    rb = label_parts(BAND, IN, reps, every, (w, v), needed=2)
    assert rb["provisional"] and rb["parts"]["claim"]["off_operating_point"]["flip"] == 3
    one_lost = [every[0], _cond({"gust": 1}, IN), _cond({"speed": 1, "gust": 1}, IN, kind="joint")]
    assert not label_parts(BAND, IN, reps, one_lost, (w, v), needed=2)["provisional"]  # a reported single counts too
    world_only_beside = label_parts(
        BAND,
        IN,
        reps,
        [_cond({"sigma": "smoothed"}, IN), _cond({"speed": 9}, IN)],
        (READING, w),
        design={"min_share_design": 1},
        needed=2,
    )
    assert not world_only_beside["provisional"] and world_only_beside["label"] == "unexplored"  # no world varied


def test_a_robust_part_decided_in_fewer_configurations_than_a_share_needs_is_found():
    """Robust over a design most of whose configurations stayed undecided says more than the runs checked: the
    machinery labels such a part unexplored, and a record that calls it robust is found. A share needs the record's
    stated number (else 32), or every configuration its register reaches at the paper's operating point where there
    are fewer: here 15 (four entries of two values), so six explored configurations are too few even all decided."""
    claim = _claim()
    part = claim["robustness"]["parts"]["claim"]
    part["label"], part["flips"] = "robust", []
    part["share"].update(agree=3, flip=0, undecided=3, design=6, decided=3, unchanged=0)
    words = "C9-1: labelled robust, but only 3 of its 6 explored configurations decided it (a share needs {})"
    assert words.format(4) in audit_claim(claim)
    part["share"].update(agree=6, undecided=0, decided=6)
    assert not any("labelled robust" in p for p in audit_claim(claim))
    del claim["robustness"]["design"]["min_share_design"]
    problems = audit_claim(claim)
    assert "C9-1: labelled robust over 6 explored configurations (a share needs 15)" in problems
    assert "C9-1: labelled robust, but only 6 of its 6 explored configurations decided it (a share needs 15)" in (
        problems
    )
    part["share"] = None
    assert "C9-1: labelled robust without a share of explored configurations" in audit_claim(claim)


def test_a_deterministic_robust_part_needs_as_many_decided_configurations_as_a_share():
    """No random draw spares a design its configurations: a deterministic part labelled robust on one decided
    configuration of six explored, where a share needs four, is found; on four it is not."""
    claim = _claim()
    claim["robustness"]["deterministic"] = True
    part = claim["robustness"]["parts"]["claim"]
    part["label"], part["flips"] = "robust", []
    part["share"].update(agree=1, flip=0, undecided=5, design=6, decided=1, unchanged=0)
    assert "C9-1: labelled robust, but only 1 of its 6 explored configurations decided it (a share needs 4)" in (
        audit_claim(claim)
    )
    part["share"].update(agree=4, undecided=2, decided=4)
    assert not any("labelled robust" in p for p in audit_claim(claim))


def test_configurations_that_never_reached_a_robust_part_are_not_counted_as_deciding_it():
    """Six agreeing configurations of which three left the part's value as the default's (``unchanged``: they never
    reached it) decide it in three, fewer than the four a share needs: a record calling it robust is found."""
    claim = _claim()
    part = claim["robustness"]["parts"]["claim"]
    part["label"], part["flips"] = "robust", []
    part["share"].update(agree=6, flip=0, undecided=0, design=6, decided=6, unchanged=3)
    assert "C9-1: labelled robust, but only 3 of its 6 explored configurations decided it (a share needs 4)" in (
        audit_claim(claim)
    )
    part["share"]["unchanged"] = 2
    assert not any("labelled robust" in p for p in audit_claim(claim))
