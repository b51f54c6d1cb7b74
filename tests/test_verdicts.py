"""Rule objects decide what their text says; robustness labels follow the verdicts."""

import math

import pytest

from tvtrack.montecarlo import Estimate
from tvtrack.register import Entry
from tvtrack.labels import Condition, Robustness, label_parts
from tvtrack.verdicts import (
    AllOf,
    InBand,
    Monotone,
    NotCheckable,
    Ordering,
    WithinFactor,
    as_estimate,
    is_undecided,
)


def est(lo, hi, value=None):
    return Estimate((lo + hi) / 2 if value is None else value, 0.1, lo, hi, 100)


@pytest.mark.parametrize(
    "ci, expected",
    [
        ((1.2, 1.8), "reproduced"),
        ((0.8, 1.2), "undecided"),
        ((1.8, 2.3), "undecided"),
        ((2.1, 2.5), "not reproduced"),
        ((0.2, 0.5), "not reproduced"),
    ],
)
def test_in_band_is_two_sided(ci, expected):
    assert InBand("rms", 1.0, 2.0, "px").decide(est(*ci)) == expected


def test_better_than_the_paper_is_not_the_papers_number():
    rule = InBand("rms", 1.0, 2.0, "px", better="lower")
    verdict, why = rule.explain(est(0.4, 0.6))
    assert verdict == "not reproduced" and "better than the paper" in why  # a decided verdict, never partly
    assert rule.decide(est(2.1, 2.5)) == "not reproduced" and "better" not in rule.explain(est(2.1, 2.5))[1]
    assert "better than the paper's number" in rule.text()


def test_one_sided_band_and_exact_numbers():
    rule = InBand("relative difference", high=1e-10)
    assert rule.decide(3e-14) == "reproduced" and rule.decide(1e-6) == "not reproduced"
    assert "at most 1e-10" in rule.text()
    assert as_estimate(2.0).ci_low == 2.0 and as_estimate({"value": 1.0, "ci_low": None, "ci_high": None}).value == 1.0


def test_within_factor_band_and_text():
    rule = WithinFactor("gain", 4.0, 1.5)
    assert (rule.low, rule.high) == pytest.approx((4 / 1.5, 6.0))
    assert rule.decide(est(3.0, 5.0)) == "reproduced"
    assert rule.decide(est(0.7, 0.9)) == "not reproduced"
    assert rule.decide(est(2.0, 3.0)) == "undecided"
    assert "factor 1.5 of the paper's 4" in rule.text()
    d = rule.to_dict()
    assert d["kind"] == "within_factor" and d["paper_value"] == 4.0 and d["text"] == rule.text()


def test_ordering_uses_the_interval_of_the_paired_difference():
    rule = Ordering("error of A", "error of B", "<")
    assert rule.decide(est(-0.5, -0.1)) == "reproduced"
    assert rule.decide(est(-0.1, 0.2)) == "undecided"  # no measurable difference is not evidence either way
    assert rule.decide(est(0.1, 0.2)) == "not reproduced"
    ratio = Ordering("A", "B", ">", measure="ratio")
    assert ratio.decide(est(1.1, 1.3)) == "reproduced" and ratio.decide(est(0.9, 1.3)) == "undecided"
    # a point difference without an interval is no evidence of an ordering: undecided, never decisive
    assert rule.decide(Estimate(-0.3, float("nan"), float("nan"), float("nan"), 1)) == "undecided"


def test_monotone_needs_separated_ends_and_no_contrary_step():
    rule = Monotone("gain", "separation", "decreasing")
    down = [est(4, 5), est(3, 4.2), est(2, 3), est(1, 1.5)]
    assert rule.decide(down) == "reproduced"
    assert rule.decide(down[::-1]) == "not reproduced"
    flat = [est(1, 2), est(1.1, 2.1), est(0.9, 1.9)]
    assert rule.decide(flat) == "undecided"  # no measurable trend: undecided, not evidence against the trend
    wiggle = [est(4, 5), est(5.5, 6), est(1, 2)]  # ends separated but one step measurably up
    assert rule.decide(wiggle) == "not reproduced"  # decisively not monotone


def test_all_of_combines_parts():
    rule = AllOf({"a": InBand("a", 0, 1), "b": Ordering("x", "y", ">")})
    assert rule.decide({"a": 0.5, "b": est(0.1, 0.2)}) == "reproduced"
    assert rule.decide({"a": 0.5, "b": est(-0.2, -0.1)}) == "partly"
    assert rule.decide({"a": 2.0, "b": est(-0.2, -0.1)}) == "not reproduced"
    with pytest.raises(ValueError, match="lacks the parts"):
        rule.decide({"a": 0.5})
    assert "(a)" in rule.text() and "(b)" in rule.text()


def test_not_checkable_says_why():
    rule = NotCheckable("SIR0 = kappa SIR by construction")
    assert rule.decide(None) == "not checkable" and "by construction" in rule.text()


def test_robustness_labels():
    rule = InBand("ratio", 3.6, 5.4)
    rob = Robustness(
        choices=[
            Entry("epoch", "operating point", "first", ("first", "mid", "last"), "the paper does not say"),
            Entry("designation_sd", "reading", 0.3, (0.3, 1.0), "not given"),
        ],
        conditions=[
            Condition({"epoch": "mid"}, est(0.5, 0.9)),
            Condition({"epoch": "last", "designation_sd": 1.0}, est(4.0, 5.0)),
        ],
        seeds={1: est(0.6, 0.9), 2: est(0.7, 1.0), 3: est(0.5, 0.8)},
    )
    rec = rob.record(rule, est(0.6, 0.9))
    # the flip changes an operating point (a world) and a reading together, and no subset of them was measured
    # alone: it is unattributed, and an unattributed flip labels nothing stronger than depends
    assert rec["label"] == "depends" and rec["parts"]["claim"]["flips"][0]["side"] == "unattributed"
    assert rec["where"] == ["reproduced when epoch = last and designation_sd = 1"]
    assert [c["verdict"] for c in rec["conditions"]] == ["not reproduced", "reproduced"]
    rob.seeds = {1: est(0.6, 0.9), 2: est(3.8, 4.0), 3: est(0.5, 0.8)}
    unstable = rob.record(rule, est(0.6, 0.9))
    assert unstable["label"] == "unstable"
    # the seeds disagree, and the condition that flips is still reported
    assert any("replicates" in w for w in unstable["where"]) and any("epoch = last" in w for w in unstable["where"])
    reps = [{"seed": s, "measured": 1.0} for s in (1, 2, 3)]
    assert label_parts(InBand("x", 0, 2), 1.0, reps, [])["label"] == "unexplored"  # nothing of the world varied
    with pytest.raises(ValueError, match="not among"):
        Entry("epoch", "reading", "middle", ("first", "last"), "w")
    with pytest.raises(ValueError, match="not among"):
        Robustness([Entry("e", "reading", 1, (1, 2), "w")], [Condition({"e": 3}, 1.0)], {1: 1, 2: 1, 3: 1}).validate()
    with pytest.raises(ValueError, match="needs a note"):
        Robustness(seeds={1: 1, 2: 1, 3: 1}).validate()
    assert math.isfinite(rob.record(rule, est(0.6, 0.9))["conditions"][0]["measured"].value)


def test_undecided_never_decides():
    nan = Estimate(1.0, float("nan"), float("nan"), float("nan"), 40, method="BCa bootstrap")
    degenerate = Estimate(1.0, 0.0, 1.0, 1.0, 40, method="BCa bootstrap")
    tail = Estimate(1e-13, 1e-14, 1e-14, 1e-12, 40, method="logistic fit", extrapolated=True)
    assert is_undecided(nan) and is_undecided(degenerate) and is_undecided(tail)
    assert not is_undecided(2.0) and not is_undecided(Estimate.exact(2.0))
    for e in (nan, degenerate, tail):
        assert InBand("q", high=0.05).decide(e) == "undecided"
        assert Ordering("a", "b", ">").decide(e) == "undecided"
    both = AllOf({"a": InBand("a", 0, 2), "b": InBand("b", 0, 2)})
    assert both.decide({"a": est(0.5, 1.5), "b": nan}) == "undecided"  # cannot be reproduced on it
    assert both.decide({"a": est(3.0, 4.0), "b": nan}) == "undecided"  # nor not reproduced
    assert both.decide({"a": est(0.5, 1.5), "b": est(3.0, 4.0)}) == "partly"
    assert not both.judge({"a": est(0.5, 1.5), "b": nan}).settled
    mono = Monotone("g", "x", "increasing")
    assert mono.decide([nan, est(2, 3), est(4, 5)]) == "undecided"
    assert mono.decide([est(0, 1), nan, est(4, 5)]) == "reproduced"


def test_an_interval_short_of_its_coverage_is_widened_before_it_decides():
    # a Student-t interval over 10 skewed samples covers about 0.90 (tvtrack.montecarlo.COVERAGE): the rule widens it
    short = Estimate(1.0, 0.05, 0.9, 1.1, 10, method="Student t; coverage 0.904 at n = 10 (skewed samples)")
    rule = InBand("q", 0.0, 1.105)
    assert rule.decide(Estimate(1.0, 0.05, 0.9, 1.1, 10, method="Student t")) == "reproduced"
    assert rule.decide(short) == "undecided"  # widened past 1.105
    assert "widened" in rule.explain(short)[1]
    unmeasured = Estimate(1.0, 0.05, 0.9, 1.1, 3, method="bootstrap-t; coverage unmeasured at n = 3")
    assert rule.decide(unmeasured) == "undecided"


def test_ordering_says_paired_only_when_paired():
    from tvtrack.verdicts import Ordering

    assert "paired ratio" in Ordering("a", "b", ">", "ratio").text()
    unpaired = Ordering("a", "b", ">", "ratio", paired=False)
    assert "unpaired (independent samples) ratio" in unpaired.text() and unpaired.to_dict()["paired"] is False


def test_an_identity_inside_a_composite_claim_takes_no_label():
    # C000-3's P = 0 ratio is 1 by construction: as a NotCheckable part it neither decides nor labels the claim
    from tvtrack.register import Entry

    rule = AllOf({"identity": NotCheckable("1 by construction"), "x": InBand("x", 0, 2)})
    reps = [{"seed": s, "measured": {"identity": 1.0, "x": est(0.5, 1.5)}} for s in (1, 2, 3)]
    conds = [{"changed": {"world": "b"}, "kind": "single", "measured": {"identity": 1.0, "x": est(0.5, 1.5)}}]
    rec = label_parts(rule, reps[0]["measured"], reps, conds, [Entry("world", "regime", "a", ("a", "b"), "w")])
    assert rec["parts"]["identity"]["label"] == "-" and rec["parts"]["x"]["label"] == "robust"
    assert rec["label"] == "robust" and "weakest part: x" in rec["coverage"]  # every combination of one entry
    assert rule.decide({"identity": 1.0, "x": est(3.0, 4.0)}) == "not reproduced"


def test_an_undecided_trend_or_ordering_read_on_an_envelope_projects_no_runs_and_says_why():
    """An end or a comparison that is an envelope of certified bounds never narrows: the judgement projects no runs
    (it read 5.3e+04 times the runs from the envelope's width) and says why."""
    import math

    from tvtrack.verdicts import Monotone, Ordering

    env = Estimate(1.0, 0.5, 0.0, 1.9, 30, method="envelope of 5 independent replicates' intervals (some are ...)")
    plain = Estimate(1.0, 0.5, 0.0, 1.9, 30, method="t interval")
    j = Ordering("decoy", "stationary", ">", measure="ratio").judge(
        Estimate(1.004, 0.5, 0.0, 1.9, 30, method=env.method)
    )
    assert j.runs_factor == math.inf and j.why.endswith(
        "no number of runs is projected to decide it (an envelope of the replicates' certified bounds, which more "
        "replicates do not narrow)"
    ), j.why
    mono = Monotone("g", "x", "increasing")
    assert mono.judge([env, Estimate(1.5, 0.5, 0.5, 2.5, 30, method="t")]).runs_factor == math.inf
    assert math.isfinite(mono.judge([plain, Estimate(1.5, 0.5, 0.5, 2.5, 30, method="t")]).runs_factor)


def test_an_undecided_band_and_trend_say_why_no_runs_decide_them_and_the_trend_projects_from_its_ends():
    import math

    from tvtrack.verdicts import InBand, Monotone

    env = Estimate(1.0, 0.5, 0.4, 1.9, 30, method="envelope of 3 independent replicates' intervals (some are ...)")
    j = InBand("share", 0.0, 1.5).judge(env)
    assert j.runs_factor == math.inf and j.why.endswith(
        "no number of runs is projected to decide it (an envelope of the replicates' certified bounds, which more "
        "replicates do not narrow)"
    ), j.why
    mono = Monotone("g", "x", "increasing")
    first = Estimate(1.0, 0.5, 0.2, 1.8, 30, method="t")
    j = mono.judge([first, Estimate(1.5, 0.5, 0.5, 2.5, 30, method="t"), env])
    assert j.runs_factor == math.inf and j.why.endswith(
        "no number of runs is projected to decide it (an end is an envelope of the replicates' certified bounds, "
        "which more replicates do not narrow))"
    ), j.why
    flat = mono.judge([first, Estimate(1.0, 0.5, 0.3, 1.7, 30, method="t")])
    assert (
        flat.runs_factor == math.inf and "(the ends' values are not apart by more than the flat tolerance)" in flat.why
    )
    wide = mono.judge([Estimate(1.0, 0.5, 0.2, math.inf, 30, method="t"), Estimate(1.5, 0.5, 0.5, 2.5, 30, method="t")])
    assert wide.runs_factor == math.inf and "(an end's interval is unbounded)" in wide.why  # open towards the last
    away = mono.judge([first, Estimate(1.5, 0.5, 0.5, math.inf, 30, method="t")])  # open away from the first
    assert away.runs_factor == pytest.approx(((1.8 - 1.0 + 1.5 - 0.5) / (1.5 - 1.0)) ** 2)
    # three points, nothing separated: ((r_first + r_last) / |v_last - v_first|)^2 from the ends' facing reaches
    last = Estimate(1.6, 0.5, 1.0, 2.4, 30, method="t")
    f = mono.judge([first, Estimate(5.0, 5.0, -4.0, 14.0, 30, method="t"), last]).runs_factor
    assert f == pytest.approx(((0.8 + 0.6) / 0.6) ** 2)
