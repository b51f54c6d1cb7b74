"""Verdicts decided by the data and labels noise cannot make, on constructed claims.

Each test builds a claim whose truth is known: a power-limited claim, a zero-events part, a straddling
condition, a planted single-entry flip, a planted pair interaction, a reading against a world.
"""

import math

import numpy as np
import pytest

from tvtrack.explore import explore
from tvtrack.labels import attribute, label_parts, sensitivity, share
from tvtrack.montecarlo import Estimate, mean_ci, rate_from_counts, zero_events_bound
from tvtrack.register import Entry, Register
from tvtrack.verdicts import InBand, Monotone, Ordering, runs_to_decide


def _mean(seed, shift, n=100, sd=1.0):
    return mean_ci(np.random.default_rng(seed).normal(shift, sd, n))


BAND = InBand("mean", -0.5, 0.5, "px")


# --------------------------------------------------------------------------- undecided and runs to decide


def test_a_straddling_interval_is_undecided_with_the_runs_that_would_decide_it():
    j = BAND.judge(Estimate(0.56, 0.05, 0.46, 0.66, 100, method="Student t"))
    assert j.verdict == "undecided" and not j.settled
    assert j.runs_factor == pytest.approx((0.10 / 0.06) ** 2)  # (half-width / distance to the edge) squared
    assert "times the runs are projected to decide it" in j.why
    # decided verdicts need no more runs
    assert BAND.judge(Estimate(0.0, 0.05, -0.1, 0.1, 100, method="Student t")).runs_factor == 1.0
    # a point on the edge is never projected to leave it
    assert not math.isfinite(runs_to_decide(Estimate(0.5, 0.05, 0.4, 0.6, 100, method="t"), (-0.5, 0.5)))


def test_a_pool_on_the_log_scale_is_projected_on_the_log_scale():
    """A ratio pooled on the log scale shrinks about its log: 1.5 [1.2, 2.1] against "at least 2" leaves the edge at
    (ln(2.1/1.5) / ln(2/1.5))^2 = 1.37 times the runs (1.44 on the linear scale); a linear pool stays linear."""
    log_pool = Estimate(
        1.5, 0.2, 1.2, 2.1, 18, method="pooled over 3 independent replicates (equal weights, log scale)"
    )
    assert runs_to_decide(log_pool, (2.0,)) == pytest.approx((math.log(2.1 / 1.5) / math.log(2.0 / 1.5)) ** 2)
    linear = Estimate(1.5, 0.2, 1.2, 2.1, 18, method="pooled over 3 independent replicates (equal weights)")
    assert runs_to_decide(linear, (2.0,)) == pytest.approx((0.6 / 0.5) ** 2)
    assert runs_to_decide(log_pool, (1.3,)) == pytest.approx((math.log(1.5 / 1.2) / math.log(1.5 / 1.3)) ** 2)


def test_zero_events_are_sized_to_certify_the_limit():
    # 0 losses in 24 runs certify p <= 0.117: undecided against 0.1; 29 runs of zero events certify it
    rule = InBand("share of runs that lost lock", high=0.1)
    j = rule.judge(rate_from_counts(0, 24))
    assert j.verdict == "undecided"
    assert math.ceil(24 * j.runs_factor) == 29 == math.ceil(math.log(0.05) / math.log(0.9))
    assert rule.decide(rate_from_counts(0, 29)) == "reproduced"
    assert zero_events_bound(29) <= 0.1 < zero_events_bound(28)


def test_the_explorer_sizes_a_zero_events_part_until_it_decides():
    reg = Register([Entry("a", "regime", 0, (0, 1), "w")])
    rule = InBand("share of runs that lost lock", high=0.1)
    ex = explore(lambda c, s: {"L": rate_from_counts(0, 6)}, reg, {"L": rule}, seed=1, replicates=3, max_replicates=8)
    assert ex.settings["replicates"] == 5  # 30 runs of zero events >= 29: stops as soon as it decides
    rec = ex.record("L")
    assert rec["parts"]["claim"]["verdict"] == "reproduced" and rec["parts"]["claim"]["runs_to_decide"] is None
    short = explore(lambda c, s: {"L": rate_from_counts(0, 6)}, reg, {"L": rule}, seed=1, replicates=3)
    runs = short.record("L")["parts"]["claim"]["runs_to_decide"]
    assert runs["replicates"] == 5 and runs["runs"] == 29 and "beyond the cap of 3" in runs["text"]


def test_monotone_tolerance_makes_a_rounding_wiggle_flat():
    pts = [Estimate.exact(v) for v in (7.60, 7.59, 7.5965, 7.50)]  # one step up by 0.0065
    assert Monotone("RMS", "k", "decreasing").decide(pts) == "not reproduced"
    tol = Monotone("RMS", "k", "decreasing", unit="el", tolerance=0.01)
    assert tol.decide(pts) == "reproduced" and "by more than 0.01 el" in tol.text()


def test_partly_only_when_decided_parts_disagree():
    from tvtrack.verdicts import AllOf

    rule = AllOf({"a": BAND, "b": Ordering("x", "y", ">")})
    straddle = Estimate(0.0, 0.1, -0.1, 0.2, 50, method="t")
    assert rule.decide({"a": Estimate.exact(0.0), "b": straddle}) == "undecided"  # too small, not "partly"
    assert rule.decide({"a": Estimate.exact(3.0), "b": straddle}) == "undecided"
    assert rule.decide({"a": Estimate.exact(3.0), "b": Estimate(0.3, 0.1, 0.1, 0.5, 50, method="t")}) == "partly"


# --------------------------------------------------------------------------- labels noise cannot make


def test_a_power_limited_claim_is_not_unstable():
    # the truth 0.3 sits inside the band, near its edge: single replicates of 100 straddle, the pool decides
    reg = Register([Entry("a", "regime", 0, (0, 1), "w")])
    ex = explore(lambda c, s: {"X": _mean(s, 0.3)}, reg, {"X": BAND}, seed=4, replicates=3, max_replicates=20)
    rec = ex.record("X")
    reps = rec["parts"]["claim"]["replicate_verdicts"]
    assert set(reps) == {"undecided", "reproduced"}  # replicates differ, but none decisively against another
    assert rec["label"] != "unstable" and rec["parts"]["claim"]["verdict"] == "reproduced"


def test_a_straddling_condition_is_not_a_flip_and_a_real_flip_still_is():
    entries = {"a": Entry("a", "regime", 0, (0, 1, 2), "w")}
    rows = [
        {"changed": {"a": 1}, "kind": "single", "verdict": "undecided"},  # straddles: no evidence
        {"changed": {"a": 2}, "kind": "single", "verdict": "not reproduced"},
    ]
    flips = attribute("reproduced", rows, entries)
    assert [f["changed"] for f in flips] == [{"a": 2}] and flips[0]["side"] == "world"
    assert attribute("undecided", rows, entries) == []  # an undecided default has nothing to flip
    # a condition that repeats its own replicate's verdict is no flip
    assert attribute("reproduced", rows, entries, same_seed="not reproduced") == []


def test_a_reading_flip_is_depends_a_world_flip_is_limited():
    reg = [
        Entry("sigma", "reading", "raw", ("raw", "smoothed"), "w"),
        Entry("motion", "regime", "cv", ("cv", "weave"), "w"),
    ]
    reps = [{"seed": s, "measured": Estimate.exact(0.0)} for s in (1, 2, 3)]
    flip = Estimate.exact(3.0)
    reading = label_parts(
        BAND,
        0.0,
        reps,
        [
            {"changed": {"sigma": "smoothed"}, "kind": "single", "measured": flip},
            {"changed": {"motion": "weave"}, "kind": "single", "measured": 0.0},
        ],
        reg,
    )
    world = label_parts(
        BAND,
        0.0,
        reps,
        [
            {"changed": {"sigma": "smoothed"}, "kind": "single", "measured": 0.0},
            {"changed": {"motion": "weave"}, "kind": "single", "measured": flip},
        ],
        reg,
    )
    assert reading["label"] == "depends" and world["label"] == "limited"
    assert world["parts"]["claim"]["flips"][0]["side"] == "world"


def test_an_unreported_setting_flip_is_depends_and_said_as_a_setting():
    """A setting of the paper's own experiment that the paper never printed is neither a reading nor a world: its
    flip makes ``depends`` (not ``limited``), its side is ``setting``, and the summary does not call it a world the
    claim does not extend to."""
    from tvtrack.register import side_of
    from tvtrack.wording import _flip_sentence

    reg = [
        Entry("where in band", "unreported setting", "middle", ("middle", "low end"), "w"),
        Entry("motion", "regime", "cv", ("cv", "weave"), "w"),
    ]
    assert side_of("unreported setting") == "setting" and reg[0].side == "setting"
    reps = [{"seed": s, "measured": Estimate.exact(0.0)} for s in (1, 2, 3)]
    rec = label_parts(
        BAND,
        0.0,
        reps,
        [
            {"changed": {"where in band": "low end"}, "kind": "single", "measured": Estimate.exact(3.0)},
            {"changed": {"motion": "weave"}, "kind": "single", "measured": 0.0},
        ],
        reg,
    )
    flips = rec["parts"]["claim"]["flips"]
    assert rec["label"] == "depends" and [f["side"] for f in flips] == ["setting"]
    text = _flip_sentence({"text": "low end", "side": "setting", "verdict": "not reproduced"})
    assert "setting of the paper's own experiment" in text and "does not extend" not in text


def test_an_entry_marks_the_values_that_leave_the_papers_operating_point():
    e = Entry("bandwidth", "regime", "calibrated", ("calibrated", 1.0, 8.0), "w", off_operating_point=(1.0, 8.0))
    assert e.to_dict()["off_operating_point"] == [1.0, 8.0]
    assert "off_operating_point" not in Entry("m", "regime", 0, (0, 1), "w").to_dict()  # records unchanged elsewhere
    with pytest.raises(ValueError, match="off_operating_point"):
        Entry("bandwidth", "regime", 3.0, (3.0, 8.0), "w", off_operating_point=(3.0,))  # never the default
    with pytest.raises(ValueError, match="off_operating_point"):
        Entry("bandwidth", "regime", 3.0, (3.0, 8.0), "w", off_operating_point=(9.0,))


def test_phrases_name_the_flip_in_plain_words():
    e = Entry(
        "paper_sigma",
        "reading",
        "sd",
        ("sd", "raw"),
        "w",
        title="sigma of the motion model",
        phrases={"raw": "sigma read as the SD of the raw velocity increments"},
    )
    reps = [{"seed": s, "measured": 0.0} for s in (1, 2, 3)]
    rec = label_parts(BAND, 0.0, reps, [{"changed": {"paper_sigma": "raw"}, "kind": "single", "measured": 3.0}], [e])
    assert rec["where"] == ["not reproduced when sigma read as the SD of the raw velocity increments"]
    assert "paper_sigma" not in rec["where"][0]


# --------------------------------------------------------------------------- attribution and sensitivity


REG5 = Register([Entry(k, "regime", 0, (0, 1, 2), f"test entry {k}") for k in "abcde"])


def _pair(config, seed):
    """Flips when a = 2 and b = 2 together, whatever the others: a planted pair interaction."""
    return {"X": _mean(seed, 3.0 if (config["a"] == 2 and config["b"] == 2) else 0.0, n=400)}


def _single(config, seed):
    """Flips when c = 1, whatever the others: a planted single-entry flip; e moves the value a little."""
    return {"X": _mean(seed, 3.0 * (config["c"] == 1) + 0.05 * config["e"], n=400)}


def test_attribution_names_a_planted_pair_and_never_a_larger_set():
    ex = explore(_pair, REG5, {"X": BAND}, seed=4, replicates=3, joint=40)
    flips = ex.record("X")["parts"]["claim"]["flips"]
    assert flips, "the joint design must reach a = b = 2"
    assert all(f["changed"] == {"a": 2, "b": 2} for f in flips)
    assert flips[0]["kind"] == "combination" and ex.settings["combinations"] > 0


def test_attribution_names_a_planted_single_and_never_a_joint_sample():
    ex = explore(_single, REG5, {"X": BAND}, seed=4, replicates=3, joint=40)
    rec = ex.record("X")
    flips = rec["parts"]["claim"]["flips"]
    assert [f["changed"] for f in flips] == [{"c": 1}] and flips[0]["kind"] == "single"
    assert rec["parts"]["claim"]["sensitivity"][0]["entry"] == "c"  # the entry that moves it most ranks first
    sh = rec["parts"]["claim"]["share"]
    assert sh["decided"] >= 32 and sh["ci_low"] <= sh["value"] <= sh["ci_high"]


def test_screened_joint_configurations_are_confirmed_at_full_size():
    calls = {"screen": 0, "full": 0}

    def full(config, seed):
        calls["full"] += 1
        return _single(config, seed)

    def small(config, seed):
        calls["screen"] += 1
        return {"X": _mean(seed, 3.0 * (config["c"] == 1) + 0.05 * config["e"], n=40)}

    ex = explore(full, REG5, {"X": BAND}, seed=4, replicates=3, joint=40, screen=small)
    joint = [r for r in ex.runs if r.stage == "joint"]
    assert calls["screen"] == len(joint) and ex.settings["screened"]
    assert ex.settings["confirmed_at_full_size"] < len(joint)  # the clear agreements stay screened
    assert all(r.outputs["X"].n == 400 for r in joint if r.config["c"] == 1)  # every flip confirmed at full size
    assert [f["changed"] for f in ex.record("X")["parts"]["claim"]["flips"]] == [{"c": 1}]


def test_share_interval_covers_at_the_design_size():
    rng = np.random.default_rng(0)
    hits = 0
    for _ in range(400):
        v = ["reproduced" if x else "not reproduced" for x in rng.random(32) < 0.8]
        s = share(v, "reproduced")
        hits += s["ci_low"] <= 0.8 <= s["ci_high"]
    assert hits / 400 >= 0.93


def test_sensitivity_needs_a_design_and_ranks_by_main_effect():
    rng = np.random.default_rng(1)
    rows = [{"config": {"a": a, "b": b}, "value": 2.0 * a + 0.1 * rng.normal()} for a in (0, 1) for b in (0, 1, 2)]
    ents = {k: Entry(k, "regime", 0, (0, 1, 2), "w") for k in "ab"}
    ranked = sensitivity(rows * 2, ["a", "b"], ents, {"a": 0, "b": 0})
    assert [r["entry"] for r in ranked] == ["a", "b"] and ranked[0]["score"] > 0.9
    no_default = [r for r in rows if r["config"] != {"a": 0, "b": 0}]
    assert sensitivity(no_default, ["a", "b"], ents, {"a": 0, "b": 0}) == []  # nothing to compare the values with


# --------------------------------------------------------------------------- every reading can decide


def test_a_reading_is_judged_by_its_own_rule():
    from tvtrack.verdicts import ByReading

    share_rule = InBand("share of runs late after 5 T", high=0.1)
    ratio_rule = InBand("ensemble mean / steady mean after 5 T", 1 / 1.1, 1.1)
    rule = ByReading("acquisition criterion", {"ensemble mean": ratio_rule}, default=share_rule)
    ratio = Estimate(1.003, 0.04, 0.922, 1.087, 600, method="t")
    assert rule.decide(ByReading.tag("ensemble mean", ratio)) == "reproduced"  # judged by the ratio's rule
    assert share_rule.decide(ratio) == "not reproduced"  # what the share's rule made of it (the bug class)
    assert rule.decide(ByReading.tag("share late", Estimate(0.02, 0.01, 0.0, 0.05, 600, method="t"))) == "reproduced"
    with pytest.raises(ValueError, match="needs ByReading.tag"):
        rule.decide(ratio)


@pytest.mark.parametrize(
    "rule",
    [
        InBand("q", 1.0, 2.0),
        InBand("q", high=0.1),
        InBand("q", low=0.0),
        Ordering("a", "b", ">", measure="ratio"),
        Ordering("a", "b", "<"),
        Monotone("g", "x", "decreasing", tolerance=0.5),
    ],
)
def test_synthetic_measurements_reach_both_verdicts(rule):
    from tvtrack.verdicts import AllOf, synthetic

    for r in (rule, AllOf({"p": rule, "q": InBand("z", 0, 1)})):
        assert r.decide(synthetic(r, "reproduced")) == "reproduced"
        assert r.decide(synthetic(r, "not reproduced")) == "not reproduced"


def test_a_part_undecided_at_the_default_sends_no_screened_configuration_to_full_size():
    from tvtrack.verdicts import AllOf

    rule = AllOf({"edge": InBand("m", -0.5, 0.5), "clear": BAND})

    def measure(config, seed, n=400):
        flip = 3.0 * (config["c"] == 1)
        return {"X": {"edge": _mean(seed, 0.5, n=n), "clear": _mean(seed + 1, flip, n=n)}}

    ex = explore(measure, REG5, {"X": rule}, seed=4, replicates=3, joint=40, screen=lambda c, s: measure(c, s, 40))
    joint = [r for r in ex.runs if r.stage == "joint"]
    rec = ex.record("X")
    assert rec["parts"]["edge"]["verdict"] == "undecided"  # the truth sits on the edge: nothing to flip there
    # only the configurations whose decided part may flip go to full size (c = 1 flips "clear"), not every one
    assert 0 < ex.settings["confirmed_at_full_size"] <= sum(r.config["c"] == 1 for r in joint) < len(joint)


def test_screened_singles_are_confirmed_at_full_size_where_they_may_flip():
    ex = explore(_single, REG5, {"X": BAND}, seed=4, replicates=3, screen=_small_single, screen_singles=True)
    singles = {tuple(r.config.items()): r for r in ex.runs if r.stage == "single"}
    assert ex.settings["screened_singles"] and "one at a time, screened" in ex.settings["timing"]
    flip = next(r for r in singles.values() if r.config["c"] == 1)
    assert flip.outputs["X"].n == 400  # the flip was confirmed at full size
    assert sum(r.outputs["X"].n == 40 for r in singles.values()) >= 8  # the clear agreements stay screened
    assert [f["changed"] for f in ex.record("X")["parts"]["claim"]["flips"]] == [{"c": 1}]


def _small_single(config, seed):
    return {"X": _mean(seed, 3.0 * (config["c"] == 1) + 0.05 * config["e"], n=40)}


def test_a_by_reading_claim_keeps_its_parts_and_judges_each_condition_by_its_reading():
    from tvtrack.verdicts import AllOf, ByReading

    share = AllOf({f"variant {v}": InBand(f"late share {v}", high=0.1) for v in (1, 2)})
    ratio = AllOf({f"variant {v}": InBand(f"ratio {v}", 0.9, 1.1) for v in (1, 2)})
    rule = ByReading("criterion", {"ratio": ratio}, default=share)
    reg = [Entry("criterion", "reading", "share", ("share", "ratio"), "w"), Entry("w", "regime", 0, (0, 1), "w")]
    late = {f"variant {v}": Estimate.exact(0.02) for v in (1, 2)}
    reps = [{"seed": s, "measured": ByReading.tag("share", late)} for s in (1, 2, 3)]
    near_one = {"variant 1": Estimate.exact(1.003), "variant 2": Estimate.exact(1.5)}
    rec = label_parts(
        rule,
        reps[0]["measured"],
        reps,
        [{"changed": {"criterion": "ratio"}, "kind": "single", "measured": ByReading.tag("ratio", near_one)}],
        reg,
    )
    assert set(rec["parts"]) == {"variant 1", "variant 2"}
    # the ratio 1.003 is judged by the ratio's rule (reproduced), 1.5 by it too (not reproduced): one flip, named
    assert rec["conditions"][0]["parts"] == {"variant 1": "reproduced", "variant 2": "not reproduced"}
    assert rec["parts"]["variant 1"]["flips"] == [] and rec["parts"]["variant 2"]["label"] == "depends"


def test_a_part_on_the_edge_says_no_practical_run_decides_it_instead_of_a_huge_number():
    reps = [{"seed": s, "measured": Estimate(0.5000001, 0.05, 0.4, 0.6, 100, method="t")} for s in (1, 2, 3)]
    runs = label_parts(BAND, reps[0]["measured"], reps, [], [])["parts"]["claim"]["runs_to_decide"]
    assert runs["replicates"] is None and "over 1000 times the runs" in runs["text"]


def test_a_claim_with_no_decided_part_has_no_label_not_unexplored(tmp_path):
    from tvtrack.results import Results
    from tvtrack.verdicts import NotCheckable
    from tvtrack.wording import shown_label

    edge = explore(lambda c, s: {"E": _mean(s, 0.5, n=100)}, REG5, {"E": BAND}, seed=4, replicates=3, joint=8)
    rec = edge.record("E")
    edge_c = explore(lambda c, s: {"C000-1": _mean(s, 0.5, n=100)}, REG5, {"C000-1": BAND}, seed=4, replicates=3)
    assert rec["parts"]["claim"]["verdict"] == "undecided"
    assert rec["label"] == "-" and rec["coverage"].startswith("no label")
    assert shown_label({"robustness": rec}) == "—"
    res = Results("000_x", "c", {"seed": 1, "output_dir": str(tmp_path)})
    claim = res.claim("C000-1", "s", "p", BAND, exploration=edge_c)  # an undecided claim is accepted unlabelled
    assert claim.verdict == "undecided" and claim.robustness["label"] == "-"
    nc = label_parts(NotCheckable("no data"), None, [], [], [])
    assert nc["label"] == "-"


def test_sensitivity_scores_do_not_depend_on_the_string_hash_seed():
    """The between-group sum runs over the entry's levels in a fixed order: Python's per-process string hashing
    (PYTHONHASHSEED) once set the order, and the scores of two runs of one seed differed in the last digit."""
    import os
    import subprocess
    import sys
    import textwrap

    code = textwrap.dedent(
        """
        import numpy as np
        from tvtrack.labels import sensitivity
        rng = np.random.default_rng(5)
        rows = [{"config": {"a": f"level-{i % 7}", "b": float(i % 3)}, "value": float(v)}
                for i, v in enumerate(rng.normal(size=40))]
        default = {"a": "level-0", "b": 0.0}
        print(repr([float(d["score"]) for d in sensitivity(rows, ["a", "b"], {}, default)]))
        """
    )
    outs = {
        subprocess.run(
            [sys.executable, "-c", code],
            capture_output=True,
            text=True,
            check=True,
            env={**os.environ, "PYTHONHASHSEED": str(seed)},
        ).stdout
        for seed in (0, 1, 5)  # 5 ordered the levels differently from 0 and 1 before the fix
    }
    assert len(outs) == 1, outs


# --------------------------------------------------------------------------- labels that check what they say


def _reps(value=0.0):
    return [{"seed": s, "measured": Estimate.exact(value)} for s in (1, 2, 3)]


def _kinds3():
    return [
        Entry("sigma", "reading", "raw", ("raw", "smoothed"), "the text reads either way"),
        Entry("law", "unreported setting", "linear", ("linear", "sine"), "the rotation-rate law is not printed"),
        Entry("motion", "regime", "cv", ("cv", "weave"), "a world beyond the paper"),
    ]


def test_an_unreported_setting_flip_depends_a_mixed_joint_flip_is_unattributed_only_a_world_is_limited():
    def rec(*flipping):
        conds = [{"changed": ch, "kind": "single" if len(ch) == 1 else "joint", "measured": 3.0} for ch in flipping]
        return label_parts(BAND, 0.0, _reps(), conds, _kinds3())

    setting = rec({"law": "sine"})
    assert setting["label"] == "depends" and setting["parts"]["claim"]["flips"][0]["side"] == "setting"
    both = rec({"sigma": "smoothed", "law": "sine"})  # readings and settings together: a setting
    assert both["parts"]["claim"]["flips"][0]["side"] == "setting" and both["label"] == "depends"
    mixed = rec({"sigma": "smoothed", "motion": "weave"})  # a reading with a world, no subset measured alone
    assert mixed["parts"]["claim"]["flips"][0]["side"] == "unattributed" and mixed["label"] == "depends"
    assert "no subset of them was found to flip it" in mixed["parts"]["claim"]["flips"][0]["note"]
    world = rec({"motion": "weave"})
    assert world["label"] == "limited" and world["parts"]["claim"]["flips"][0]["side"] == "world"


def test_a_condition_smaller_than_the_default_neither_flips_nor_agrees():
    ents = [Entry("motion", "regime", "cv", ("cv", "weave", "turn"), "w")]
    conds = [
        {"changed": {"motion": "weave"}, "kind": "single", "measured": 3.0, "runs": 1},  # decisive, but one run
        {"changed": {"motion": "turn"}, "kind": "single", "measured": 0.0, "runs": 3},
    ]
    rec = label_parts(BAND, 0.0, _reps(), conds, ents)
    part = rec["parts"]["claim"]
    assert part["flips"] == [] and rec["conditions"][0]["parts"] == {"claim": "undecided"}
    assert rec["conditions"][0]["undersized"] == {"claim": "not reproduced"}
    assert (part["share"]["agree"], part["share"]["undecided"]) == (1, 1)
    conds[0]["runs"] = 3  # sized like the default: now a flip
    assert label_parts(BAND, 0.0, _reps(), conds, ents)["label"] == "limited"


def test_the_share_counts_every_explored_configuration_agree_flip_and_undecided():
    s = share(["reproduced", "not reproduced", "undecided", "reproduced"], "reproduced")
    assert (s["agree"], s["flip"], s["undecided"], s["design"], s["decided"]) == (2, 1, 1, 4, 3)
    assert s["value"] == 0.5 and s["ci_low"] < 0.5 < s["ci_high"]  # 2 of 4, not 2 of the 3 decided
    none_decided = share(["undecided"] * 10, "reproduced")
    assert none_decided["value"] == 0.0 and none_decided["design"] == 10 and none_decided["ci_high"] < 0.31


REG_READINGS = Register([Entry(k, "reading", 0, (0, 1), f"reading {k}") for k in "abcdef"])


def _triple(config, seed, claims=None):
    """Flips only when readings a, b and c change together (a three-way interaction)."""
    return {"X": _mean(seed, 3.0 if config["a"] == config["b"] == config["c"] == 1 else 0.0, n=400)}


def test_the_subset_search_has_no_run_cap_and_names_a_planted_pair():
    ex = explore(_pair, REG5, {"X": BAND}, seed=4, replicates=3, joint=40, combinations=0)  # a cap of 0 runs
    flips = ex.record("X")["parts"]["claim"]["flips"]
    assert flips and all(f["changed"] == {"a": 2, "b": 2} and f["kind"] == "combination" for f in flips)
    assert ex.settings["combinations"] > 0 and ex.settings["max_subset"] == 3


def test_a_triple_of_readings_is_found_and_depends():
    ex = explore(_triple, REG_READINGS, {"X": BAND}, seed=2, replicates=3, joint=40)
    rec = ex.record("X")
    flips = rec["parts"]["claim"]["flips"]
    assert flips and {tuple(f["changed"]) for f in flips} == {("a", "b", "c")}
    assert flips[0]["side"] == "reading" and rec["label"] == "depends"


def test_a_search_stopped_at_pairs_tries_no_triple_and_says_so_where_it_leaves_a_flip_unattributed():
    reg = Register([Entry(k, "reading", 0, (0, 1), f"reading {k}") for k in "abcdefgh"])

    def four(config, seed):
        return {"X": _mean(seed, 3.0 if all(config[k] == 1 for k in "abcd") else 0.0, n=400)}

    def sizes(ex):
        return {len(r.changed(ex.register.default())) for r in ex.runs if r.stage == "combination"}

    full = explore(four, reg, {"X": BAND}, seed=3, replicates=3, joint=40)
    pairs = explore(four, reg, {"X": BAND}, seed=3, replicates=3, joint=40, max_subset=2)
    assert 3 in sizes(full) and sizes(pairs) == {2} and pairs.settings["max_subset"] == 2
    flips = pairs.record("X")["parts"]["claim"]["flips"]
    assert flips and all(f["side"] == "unattributed" and "no subset of up to 2 of them" in f["note"] for f in flips)
    none = explore(four, reg, {"X": BAND}, seed=3, replicates=3, joint=40, max_subset=1)
    assert none.settings["combinations"] == 0 and none.record("X")["label"] == "depends"
    for bad in (4, 2.5, True, "2"):  # never truncated or coerced to another size than the one stated
        with pytest.raises(ValueError, match=rf"max_subset must be an integer in \[1, 3\], got {bad!r}"):
            explore(four, reg, {"X": BAND}, seed=3, replicates=3, max_subset=bad)


def test_a_joint_flip_one_entry_beyond_the_search_is_its_own_smallest_and_more_is_unattributed():
    def flips_when_all_change(names):
        reg = Register([Entry(k, "regime", 0, (0, 1), f"world {k}") for k in names])

        def measure(config, seed):
            return {"X": _mean(seed, 3.0 if all(config[k] == 1 for k in names) else 0.0, n=400)}

        return explore(measure, reg, {"X": BAND}, seed=3, replicates=3, joint=40).record("X")

    four = flips_when_all_change("abcd")  # every pair and triple tried: the four worlds are the smallest
    (flip,) = four["parts"]["claim"]["flips"]
    assert flip["changed"] == dict.fromkeys("abcd", 1) and flip["side"] == "world" and four["label"] == "limited"
    five = flips_when_all_change("abcde")  # no subset of four was tried: the five are not shown to be the smallest
    (flip,) = five["parts"]["claim"]["flips"]
    assert flip["changed"] == dict.fromkeys("abcde", 1) and flip["side"] == "unattributed"
    assert "no subset of up to 3" in flip["note"] and five["label"] == "depends"  # never limited


def test_a_reading_that_adds_a_part_to_the_rule_can_flip_the_claim():
    from tvtrack.verdicts import AllOf, ByReading

    at_zero = AllOf({"P = 0": BAND})
    every = AllOf({"P = 0": BAND, "every P > 0.5": BAND})  # the reading "at every P > 0.5" adds a part
    rule = ByReading("scope", {"every P": every}, default=at_zero)
    ents = [Entry("scope", "reading", "P = 0", ("P = 0", "every P"), "the sentence reads either way")]
    reps = [{"seed": s, "measured": ByReading.tag("P = 0", {"P = 0": Estimate.exact(0.0)})} for s in (1, 2, 3)]
    fails = ByReading.tag("every P", {"P = 0": Estimate.exact(0.0), "every P > 0.5": Estimate.exact(3.0)})
    holds = ByReading.tag("every P", {"P = 0": Estimate.exact(0.0), "every P > 0.5": Estimate.exact(0.1)})
    cond = {"changed": {"scope": "every P"}, "kind": "single"}
    rec = label_parts(rule, reps[0]["measured"], reps, [{**cond, "measured": fails}], ents)
    assert rec["label"] == "depends" and rec["conditions"][0]["parts"] == {"P = 0": "not reproduced"}
    assert rec["parts"]["P = 0"]["flips"][0]["text"] == "scope = every P"
    assert label_parts(rule, reps[0]["measured"], reps, [{**cond, "measured": holds}], ents)["label"] != "depends"


def test_sensitivity_ranks_the_one_at_a_time_cause_first_not_an_entry_that_co_occurs_with_it():
    ents = [Entry(k, "regime", 0, (0, 1), f"world {k}") for k in "bcd"] + [Entry("e", "regime", 0, range(8), "w")]
    one = [{"changed": {k: 1}, "kind": "single", "measured": 3.0 * (k == "c")} for k in "bcd"]
    one += [{"changed": {"e": i}, "kind": "single", "measured": 0.0} for i in range(1, 8)]  # e moves nothing
    # in the joint design b = 1 always comes with c = 1 and a large value; c = 1 with d = 1 cancels
    joint = [{"changed": {"b": 1, "c": 1, "e": i}, "kind": "joint", "measured": 3.0} for i in range(8)]
    joint += [{"changed": {"c": 1, "d": 1, "e": i}, "kind": "joint", "measured": 0.0} for i in range(8)]
    rec = label_parts(InBand("m", -10, 10), 0.0, _reps(), one + joint, ents)
    sens = rec["parts"]["claim"]["sensitivity"]
    assert [s["entry"] for s in sens][0] == "c" and sens[0]["score"] == 1.0
    assert "one at a time" in rec["parts"]["claim"]["sensitivity_method"]


def test_a_value_carried_by_runs_that_lost_lock_says_so():
    from tvtrack.explore import pool
    from tvtrack.measured import with_lost_runs

    every = Estimate(0.9, 0.1, 0.7, 1.1, 60, method="Student t")  # outside [-0.5, 0.5]: not reproduced
    in_lock = Estimate(0.1, 0.1, -0.1, 0.3, 57, method="Student t")  # the runs in lock: reproduced
    m = with_lost_runs(every, in_lock, lost=3, runs=60)
    assert BAND.decide(m) == "not reproduced"  # the rule judges every run
    pooled = pool([m, m])
    assert (pooled["lost"], pooled["runs"]) == (6, 120) and pooled["value"].n == 120
    part = label_parts(BAND, pooled, [{"seed": s, "measured": m} for s in (1, 2)], [], [])["parts"]["claim"]
    lost = part["lost_share"]
    assert (lost["lost"], lost["runs"], lost["value"]) == (6, 120, 0.05) and lost["ci_low"] < 0.05 < lost["ci_high"]
    assert part["in_lock_verdict"] == "reproduced" and part["decided_by_lost_runs"] is True
    plain = label_parts(BAND, in_lock, [{"seed": 1, "measured": in_lock}], [], [])["parts"]["claim"]
    assert "lost_share" not in plain
    with pytest.raises(ValueError, match="lost 7 of runs 5"):
        with_lost_runs(every, in_lock, lost=7, runs=5)


def test_a_screened_value_is_no_replicate_a_counted_condition_is_sized_at_full_size():
    ex = explore(_single, REG5, {"X": BAND}, seed=4, replicates=3, joint=40, screen=_small_single)
    screened = [r for r in ex.runs if r.stage == "joint" and "X" in r.screened]
    assert screened and all(r.outputs["X"].n == 40 for r in screened)  # clear agreements kept the screen's value
    k = ex.settings["replicates_needed"]["X"]  # the replicates the default needed to decide
    for r in screened:  # ... and were sized at full size from the first seed on, the screen's value left out
        assert [s.seed for s in r.sized][:k] == [rep.seed for rep in ex.replicates()][:k]
        assert r.n_runs("X") >= k and all(s.outputs["X"].n == 400 for s in r.sized)
    rows = [c for c in ex.record("X")["conditions"] if c["kind"] == "joint"]
    assert all(c["runs"] >= k and c["measured"].n >= 400 * k for c in rows)


def test_a_part_no_explored_configuration_decided_is_unexplored_never_robust():
    """A register whose every combination was explored (no share needed beyond it) but whose only other value
    leaves the part undecided (no interval: C004-5's heavy-tailed noise) has shown nothing beyond the default: the
    part is unexplored, and becomes robust only once a configuration decides and agrees."""
    reg = Register([Entry("noise", "regime", "gaussian", ("gaussian", "heavy"), "w")])
    inside = Estimate(0.0, 0.05, -0.1, 0.1, 100, method="Student t")
    straddles = Estimate(0.5, 0.5, -0.5, 1.5, 100, method="Student t")

    def measure(config, seed):
        return {"C": inside if config["noise"] == "gaussian" else straddles}

    rec = explore(measure, reg, {"C": BAND}, seed=1, replicates=3).record("C")
    part = rec["parts"]["claim"]
    assert part["verdict"] == "reproduced" and not rec["provisional"]
    assert (part["share"]["agree"], part["share"]["flip"], part["share"]["undecided"]) == (0, 0, 1)
    assert part["label"] == rec["label"] == "unexplored"
    moved = Estimate(0.02, 0.05, -0.08, 0.12, 100, method="Student t")  # the heavy noise moves it, inside the band

    def agrees(config, seed):
        return {"C": inside if config["noise"] == "gaussian" else moved}

    agreed = explore(agrees, reg, {"C": BAND}, seed=1, replicates=3).record("C")
    assert agreed["parts"]["claim"]["share"]["agree"] == 1 and agreed["label"] == "robust"


def test_a_combination_that_flips_a_part_its_joint_configuration_did_not_is_named():
    # the combination was searched for another part's joint flip (or a joint a single explains): it flips this part
    # on its own, sized, so it is a flip of this part and is named, after the flips that explain their joints
    entries = {
        "sigma": Entry("sigma", "reading", "raw", ("raw", "smoothed"), "w"),
        "motion": Entry("motion", "regime", "cv", ("cv", "weave"), "w"),
        "noise": Entry("noise", "regime", "low", ("low", "high"), "w"),
    }
    rows = [
        {"changed": {"sigma": "smoothed"}, "kind": "single", "verdict": "not reproduced", "runs": 2},
        {"changed": {"motion": "weave"}, "kind": "single", "verdict": "reproduced", "runs": 2},
        {
            "changed": {"sigma": "smoothed", "motion": "weave", "noise": "high"},
            "kind": "joint",
            "verdict": "not reproduced",
            "runs": 2,
        },
        {
            "changed": {"motion": "weave", "noise": "high"},
            "kind": "combination",
            "verdict": "not reproduced",
            "runs": 2,
        },
        {
            "changed": {"sigma": "smoothed", "noise": "high"},
            "kind": "combination",
            "verdict": "not reproduced",
            "runs": 2,
        },
    ]
    flips = attribute("reproduced", rows, entries)
    assert [(f["changed"], f["kind"], f["side"]) for f in flips] == [
        ({"sigma": "smoothed"}, "single", "reading"),
        ({"motion": "weave", "noise": "high"}, "combination", "world"),
    ]  # the pair with the reading is explained by the reading alone
    # an unsized combination (one run repeating the default's own replicate) stays no flip
    rows[3] = {**rows[3], "runs": 1}
    assert [f["changed"] for f in attribute("reproduced", rows, entries, same_seed="not reproduced")] == [
        {"sigma": "smoothed"}
    ]


def test_an_entry_that_chooses_another_rule_is_not_ranked_on_the_default_s_scale():
    """A reading under which the claim measures another quantity (a share of runs against a variance ratio) has
    values on another scale: the sensitivity leaves it out instead of ranking it first by the gap between scales."""
    from tvtrack.verdicts import ByReading

    share_rule = InBand("share of runs not in lock", high=0.1)
    rule = ByReading("criterion", {"ensemble": InBand("variance ratio", high=20.0)}, share_rule)
    entries = (
        Entry("criterion", "reading", "share", ("share", "ensemble"), "the text reads either way"),
        Entry("noise", "regime", "low", ("low", "high"), "a world beyond the paper"),
    )
    at = ByReading.tag
    reps = [
        {"seed": s, "measured": at("share", Estimate(0.01, 0.002, 0.006, 0.014, 600, method="t"))} for s in (1, 2, 3)
    ]
    conds = [
        {
            "changed": {"criterion": "ensemble"},
            "kind": "single",
            "runs": 3,
            "measured": at("ensemble", Estimate(11.4, 5.3, 2.8, 19.9, 600, method="t")),
        },
        {
            "changed": {"noise": "high"},
            "kind": "single",
            "runs": 3,
            "measured": at("share", Estimate(0.03, 0.004, 0.022, 0.038, 600, method="t")),
        },
    ]
    for c in conds:
        c["config"] = c["changed"]
    rec = label_parts(rule, reps[0]["measured"], reps, conds, entries, design={"min_share_design": 2}, needed=1)
    ranked = rec["parts"]["claim"]["sensitivity"]
    assert [r["entry"] for r in ranked] == ["noise"] and ranked[0]["score"] == pytest.approx(1.0)
    assert "not ranked" in rec["parts"]["claim"]["sensitivity_method"]


def test_an_unranked_reading_never_joins_the_default_s_values():
    """The rows of a reading that chooses another rule are left out of the sensitivity's rows, not counted as the
    default's: its 11.4 (a variance ratio) would otherwise swamp the default's 0.01 (a share) and tie the entries."""
    from tvtrack.verdicts import ByReading

    rule = ByReading("criterion", {"ensemble": InBand("ratio", high=20.0)}, InBand("share", high=0.1))
    entries = (
        Entry("criterion", "reading", "share", ("share", "ensemble"), "the text reads either way"),
        Entry("noise", "regime", "low", ("low", "high"), "a world beyond the paper"),
        Entry("law", "unreported setting", "linear", ("linear", "step"), "never printed"),
    )
    at, est = ByReading.tag, (lambda v: Estimate(v, 0.001, v - 0.002, v + 0.002, 600, method="t"))
    reps = [{"seed": s, "measured": at("share", est(0.01))} for s in (1, 2, 3)]
    conds = [
        {"changed": {"criterion": "ensemble"}, "measured": at("ensemble", est(11.4))},
        {"changed": {"noise": "high"}, "measured": at("share", est(0.03))},
        {"changed": {"law": "step"}, "measured": at("share", est(0.012))},
    ]
    for c in conds:
        c.update(kind="single", runs=3, config=c["changed"])
    rec = label_parts(rule, reps[0]["measured"], reps, conds, entries, design={"min_share_design": 3}, needed=1)
    ranked = {r["entry"]: r["score"] for r in rec["parts"]["claim"]["sensitivity"]}
    assert set(ranked) == {"noise", "law"}
    assert ranked["noise"] == pytest.approx(0.01**2 / (0.01**2 + 0.001**2))  # (0.03 - 0.01)^2 against (0.002)^2


def test_a_part_whose_own_rule_is_chosen_by_a_reading_leaves_that_reading_unranked():
    from tvtrack.verdicts import AllOf, ByReading

    part = ByReading("criterion", {"ensemble": InBand("ratio", high=20.0)}, InBand("share", high=0.1))
    rule = AllOf({"a": part, "b": InBand("other", high=1.0)})
    entries = (
        Entry("criterion", "reading", "share", ("share", "ensemble"), "the text reads either way"),
        Entry("noise", "regime", "low", ("low", "high"), "a world beyond the paper"),
    )
    at, est = ByReading.tag, (lambda v: Estimate(v, 0.001, v - 0.002, v + 0.002, 600, method="t"))
    reps = [{"seed": s, "measured": {"a": at("share", est(0.01)), "b": est(0.5)}} for s in (1, 2, 3)]
    conds = [
        {"changed": {"criterion": "ensemble"}, "measured": {"a": at("ensemble", est(11.4)), "b": est(0.5)}},
        {"changed": {"noise": "high"}, "measured": {"a": at("share", est(0.03)), "b": est(0.6)}},
    ]
    for c in conds:
        c.update(kind="single", runs=3, config=c["changed"])
    rec = label_parts(rule, reps[0]["measured"], reps, conds, entries, design={"min_share_design": 2}, needed=1)
    assert [r["entry"] for r in rec["parts"]["a"]["sensitivity"]] == ["noise"]


def test_mark_lost_runs_takes_every_run_lost_and_says_the_default_is_decided_by_them_only_where_it_is():
    from tvtrack.lost_labels import mark_lost_runs

    row = {"changed": {}, "lost": 6, "runs": 6, "verdict": "not reproduced", "in_lock_verdict": "reproduced"}
    rec = mark_lost_runs({"parts": {}}, [row], "not reproduced")  # every run lost: a count it takes
    assert rec["lost_share"]["lost"] == rec["lost_share"]["runs"] == 6 and rec["decided_by_lost_runs"] is True
    with pytest.raises(ValueError, match="need 0 <= lost <= runs"):
        mark_lost_runs({"parts": {}}, [{**row, "lost": 7}], "not reproduced")
    # the rows' draws read another verdict over every run than the pooled one: the lost runs decide nothing
    other = mark_lost_runs({"parts": {}}, [{**row, "verdict": "reproduced"}], "not reproduced")
    assert other["decided_by_lost_runs"] is False
    # the same verdict over the runs in lock: nothing carried by the lost runs either
    same = mark_lost_runs({"parts": {}}, [{**row, "in_lock_verdict": "not reproduced"}], "not reproduced")
    assert same["decided_by_lost_runs"] is False


def test_a_flip_of_one_part_of_several_is_never_carried_on_the_whole_claim_s_verdicts():
    from tvtrack.lost_labels import mark_lost_runs

    flip = {"changed": {"noise": "high"}, "verdict": "not reproduced"}
    row = {
        "changed": {"noise": "high"},
        "lost": 3,
        "runs": 6,
        "verdict": "not reproduced",
        "in_lock_verdict": "reproduced",
        "parts": {"a": "not reproduced"},
    }  # no in-lock verdict of part a
    rec = mark_lost_runs({"parts": {"a": {"flips": [dict(flip)]}, "b": {"flips": []}}}, [row], "reproduced")
    assert rec["parts"]["a"]["flips"][0]["lost_runs"]["carried"] is False
    both = {**row, "in_lock_parts": {"a": "reproduced"}}
    rec = mark_lost_runs({"parts": {"a": {"flips": [dict(flip)]}, "b": {"flips": []}}}, [both], "reproduced")
    assert rec["parts"]["a"]["flips"][0]["lost_runs"]["carried"] is True


def test_a_flip_of_one_part_is_said_with_that_part_s_verdicts_in_lock():
    """The note on a flip of part ``a`` quoted the whole claim's verdict over the runs in lock, which part ``b``
    may set: the part's own verdicts are kept where the row gives them, and the report's note says the part's."""
    from tvtrack.lost_labels import mark_lost_runs
    from tvtrack.part_lines import hold_note

    flip = {"changed": {"noise": "high"}, "verdict": "not reproduced", "text": "high noise", "side": "world"}
    row = {"changed": {"noise": "high"}, "lost": 3, "runs": 600, "verdict": "partly", "in_lock_verdict": "partly"}
    row |= {"parts": {"a": "not reproduced", "b": "reproduced"}, "in_lock_parts": {"a": "reproduced", "b": "partly"}}
    rec = mark_lost_runs({"parts": {"a": {"flips": [dict(flip)]}, "b": {"flips": []}}}, [row], "reproduced")
    lost = rec["parts"]["a"]["flips"][0]["lost_runs"]
    assert (lost["verdict"], lost["in_lock_verdict"], lost["carried"]) == ("not reproduced", "reproduced", True)
    claim = {"id": "C000-9", "verdict": "reproduced", "robustness": rec}
    assert hold_note(claim).endswith("over the runs in lock alone it is reproduced")


def test_the_ranking_counts_no_round_off_far_inside_the_band_and_pairs_each_condition_with_its_replicates():
    """C004-4's shape: a relative deviation of 1e-13 against a bound of 1e-9 moves by round-off only under every
    entry, and nothing is ranked. C002-1's shape: conditions on the first replicate's seed alone are compared with
    that replicate, so the replicates' scatter is no entry's effect."""
    from tvtrack.register import Entry
    from tvtrack.verdicts import InBand

    a = Entry("a", "regime", 0, (0, 1), "a world beyond the paper")
    b = Entry("b", "regime", 0, (0, 1), "a world beyond the paper")
    rule = InBand("deviation", None, 1e-9, "relative")
    reps = [{"seed": s, "measured": Estimate.exact(v)} for s, v in ((1, 1.0e-13), (2, 1.02e-13))]
    conds = [
        {"changed": {"a": 1}, "kind": "single", "runs": 2, "measured": Estimate.exact(1.12e-13)},
        {"changed": {"b": 1}, "kind": "single", "runs": 2, "measured": Estimate.exact(0.93e-13)},
    ]
    rb = label_parts(rule, Estimate.exact(1.01e-13), reps, conds, [a, b], design={"min_share_design": 2})
    assert rb["parts"]["claim"]["sensitivity"] == []
    band = InBand("gain", -1.0, 0.0, "")
    reps = [{"seed": s, "measured": Estimate.exact(v)} for s, v in ((1, -0.679), (2, -0.55), (3, -0.532))]
    conds = [  # a: the first replicate's own value (no effect); b: 0.1 above its replicate (an effect)
        {"changed": {"a": 1}, "kind": "single", "runs": 1, "measured": Estimate.exact(-0.679)},
        {"changed": {"b": 1}, "kind": "single", "runs": 1, "measured": Estimate.exact(-0.579)},
    ]
    rb = label_parts(band, Estimate.exact(-0.587), reps, conds, [a, b], design={"min_share_design": 2}, needed=1)
    ranked = rb["parts"]["claim"]["sensitivity"]
    assert ranked[0]["entry"] == "b" and ranked[0]["score"] > 0.99


def test_the_moving_floor_is_a_hundredth_of_the_distance_to_the_nearest_edge():
    from tvtrack.labels import _moving_floor

    assert _moving_floor(InBand("x", None, 2.0, ""), Estimate.exact(1.0)) == pytest.approx(0.01)
    assert _moving_floor(InBand("x", 1.0, 10.0, ""), Estimate.exact(1.5)) == pytest.approx(0.005)
    assert _moving_floor(InBand("x", 1.0, 10.0, ""), Estimate.exact(math.nan)) == 0.0
    assert _moving_floor(Ordering("a", "b"), Estimate.exact(1.5)) == 0.0


def test_configurations_off_the_operating_point_are_counted_only_beside_a_decided_default():
    from tvtrack.register import Entry

    fast = Entry("speed", "regime", 3.0, (3.0, 8.0, 9.0), "a world beyond the paper", off_operating_point=(8.0, 9.0))
    other = Entry("law", "unreported setting", "a", ("a", "b"), "never printed")
    band = InBand("mean", -0.5, 0.5, "px")
    inside, outside, edge = Estimate.exact(0.0), Estimate.exact(3.0), Estimate(0.5, 0.1, 0.3, 0.7, 10)
    reps = [{"seed": s, "measured": inside} for s in (1, 2)]
    conds = [
        {"changed": {"speed": 8.0}, "kind": "single", "runs": 2, "measured": inside},
        {"changed": {"speed": 9.0}, "kind": "single", "runs": 2, "measured": inside},
        {"changed": {"law": "b"}, "kind": "single", "runs": 2, "measured": outside},
    ]
    part = label_parts(band, inside, reps, conds, [fast, other], design={"min_share_design": 1})["parts"]["claim"]
    assert {k: part["off_operating_point"][k] for k in ("agree", "flip", "undecided")} == {
        "agree": 2,
        "flip": 0,
        "undecided": 0,
    }
    undecided = label_parts(band, edge, [{"seed": 1, "measured": edge}], conds, [fast, other])["parts"]["claim"]
    assert "off_operating_point" not in undecided  # nothing to flip: nothing counted beside
    plain = label_parts(band, inside, reps, conds[2:], [fast, other], design={"min_share_design": 1})
    assert "off_operating_point" not in plain["parts"]["claim"]


def _world_design(n_agree: int, n_open: int) -> dict:
    """A reproduced part over ``n_agree + n_open`` explored world values, ``n_open`` of which leave it undecided."""
    values = tuple(range(n_agree + n_open + 1))
    e = Entry("w", "regime", 0, values, "a world")
    inside = Estimate(0.0, 0.05, -0.1, 0.1, 100, method="Student t")
    straddles = Estimate(0.5, 0.5, -0.5, 1.5, 100, method="Student t")
    conds = [
        {"changed": {"w": v}, "kind": "single", "measured": inside if v <= n_agree else straddles, "runs": 3}
        for v in values[1:]
    ]
    reps = [{"seed": s, "measured": inside} for s in (1, 2, 3)]
    return label_parts(BAND, inside, reps, conds, [e], needed=3)


def test_a_part_decided_in_fewer_configurations_than_a_share_needs_is_unexplored_not_robust():
    """Robust says no explored change flips the part; where most of the design stayed undecided, the runs did not
    check that: 31 decided of 40 explored is fewer than the 32 a share needs (unexplored, the number recorded),
    32 decided is enough (robust), whatever the undecided ones beside them."""
    thin = _world_design(31, 9)["parts"]["claim"]
    assert (thin["share"]["agree"], thin["share"]["undecided"]) == (31, 9)
    assert thin["label"] == "unexplored" and thin["share"]["decided_needed"] == 32
    enough = _world_design(32, 30)
    assert enough["parts"]["claim"]["label"] == enough["label"] == "robust" and not enough["provisional"]
    assert "decided_needed" not in enough["parts"]["claim"]["share"]
    every = _world_design(40, 0)["parts"]["claim"]
    assert every["label"] == "robust" and every["share"]["agree"] == 40


def test_a_configuration_lost_at_a_marked_value_does_not_shrink_what_a_share_needs():
    """The configurations a share needs are those the paper's operating point admits (3 here: the marked value 2 of
    ``a`` is not among them). A joint configuration at that marked value that the exploration also reports lost was
    never among them, so it does not lower the 3 to 2: two explored configurations stay too few (provisional)."""
    a = Entry("a", "reading", 0, (0, 1, 2), "a reading", off_operating_point=(2,))
    b = Entry("b", "regime", 0, (0, 1), "a world")
    inside = Estimate(0.0, 0.05, -0.1, 0.1, 100, method="Student t")
    conds = [
        {"changed": {"a": 1}, "kind": "single", "measured": inside, "runs": 3},
        {"changed": {"b": 1}, "kind": "single", "measured": inside, "runs": 3},
        {"changed": {"a": 2, "b": 1}, "kind": "joint", "measured": inside, "runs": 3, "operating_point_lost": "off"},
    ]
    reps = [{"seed": s, "measured": inside} for s in (1, 2, 3)]
    rec = label_parts(BAND, inside, reps, conds, [a, b], needed=3)
    assert rec["provisional"] is True and rec["parts"]["claim"]["share"]["design"] == 2
    kept = label_parts(
        BAND, inside, reps, [*conds[:2], {**conds[0], "changed": {"a": 1, "b": 1}, "kind": "joint"}], [a, b], needed=3
    )
    assert kept["provisional"] is False and kept["label"] == "robust"  # all three reachable explored and decided


def test_a_configuration_that_decided_the_other_way_on_the_defaults_own_draws_counts_as_decided():
    """A one-run configuration whose verdict differs from the pooled default but equals the default's own run on
    the same draws (the first replicate) is no flip, yet it decided: with 31 agreeing ones it makes the 32 decided
    configurations a robust part needs."""
    e = Entry("w", "regime", 0, tuple(range(34)), "a world")
    inside = Estimate(0.0, 0.05, -0.1, 0.1, 100, method="Student t")
    outside = Estimate(0.9, 0.05, 0.8, 1.0, 100, method="Student t")
    straddles = Estimate(0.5, 0.5, -0.5, 1.5, 100, method="Student t")
    conds = [{"changed": {"w": v}, "kind": "single", "measured": inside, "runs": 1} for v in range(1, 32)]
    conds.append({"changed": {"w": 32}, "kind": "single", "measured": outside, "runs": 1})
    reps = [{"seed": 1, "measured": outside}, {"seed": 2, "measured": straddles}, {"seed": 3, "measured": straddles}]
    part = label_parts(BAND, inside, reps, conds, [e], needed=1)["parts"]["claim"]
    assert (part["share"]["agree"], part["share"]["flip"], part["flips"]) == (31, 1, [])
    assert part["label"] == "robust"
    conds[-1]["measured"] = straddles  # undecided instead: 31 decided are too few
    assert label_parts(BAND, inside, reps, conds, [e], needed=1)["parts"]["claim"]["label"] == "unexplored"


def test_a_part_without_random_draws_needs_as_many_decided_configurations_as_a_share():
    """A deterministic claim has no replicate noise, but its configurations are still a sample of its register's:
    one configuration that decided and agreed, of the two it explores (one left undecided), leaves it unexplored, as a
    random one (robust only on as many decided configurations as a share needs, ``docs/verdicts.md``)."""
    e = Entry("w", "regime", 0, (0, 1, 2), "a world")
    exact = Estimate.exact(0.0)
    straddles = Estimate(0.5, 0.5, -0.5, 1.5, 100, method="Student t")
    conds = [
        {"changed": {"w": 1}, "kind": "single", "measured": Estimate.exact(0.1), "runs": 3},
        {"changed": {"w": 2}, "kind": "single", "measured": straddles, "runs": 3},
    ]
    reps = [{"seed": s, "measured": exact} for s in (1, 2, 3)]
    rec = label_parts(BAND, exact, reps, conds, [e], deterministic=True)
    assert rec["parts"]["claim"]["share"]["agree"] == 1 and rec["label"] == "unexplored"
    assert rec["parts"]["claim"]["share"]["decided_needed"] == 2  # the two configurations besides the default


def test_an_edge_within_a_resolution_allowance_is_never_decided_by_more_runs():
    """Of an interval with a resolution allowance only the sampling part shrinks. 2.45 [2, 3] with sampling
    [2.3, 2.6]: an edge at 2.2 or 2.8 lies within the allowance (2 to 2.3 below, 2.6 to 3 above), and no number of
    runs decides it; with sampling [2.3, 2.9] (allowance 0.1 above) the edge at 2.8 is left when the 0.45 of
    sampling half-width above shrinks to 0.25: (0.45 / 0.25)^2 times the runs."""
    e = Estimate(2.45, 0.1, 2.0, 3.0, 18, 0.95, "pooled", False, 2.3, 2.6)
    assert not math.isfinite(runs_to_decide(e, (2.2,))) and not math.isfinite(runs_to_decide(e, (2.8,)))
    f = Estimate(2.45, 0.1, 2.0, 3.0, 18, 0.95, "pooled", False, 2.3, 2.9)
    assert runs_to_decide(f, (2.8,)) == pytest.approx(((0.55 - 0.1) / (0.35 - 0.1)) ** 2)
    plain = Estimate(2.45, 0.1, 2.0, 3.0, 18, 0.95, "pooled")  # no allowance: the whole half-width shrinks
    assert runs_to_decide(plain, (2.8,)) == pytest.approx((0.55 / 0.35) ** 2)
    # each side its own allowance: 0.05 below (sampling from 2.05), 0.4 above; an edge at the sampling end stays
    g = Estimate(2.45, 0.1, 2.0, 3.0, 18, 0.95, "pooled", False, 2.05, 2.6)
    assert runs_to_decide(g, (2.2,)) == pytest.approx(((0.45 - 0.05) / (0.25 - 0.05)) ** 2)
    assert not math.isfinite(runs_to_decide(Estimate(2.45, 0.1, 2.0, 3.0, 18, 0.95, "p", False, 2.25, 2.6), (2.2,)))
