"""What a rule hands on besides its verdict: the composite's judgement in every branch, the runs projected to
decide a trend, and the record a rule writes of itself (its parameters and text), each checked against the value it
must have. Written to kill the mutants of ``tvtrack.verdicts`` that survived ``make mutate`` (docs/mutation.md)."""

import math

import pytest

from tvtrack.montecarlo import Estimate
from tvtrack.verdicts import AllOf, InBand, Judgement, Monotone, NotCheckable, Ordering, WithinFactor


def est(lo, hi, value=None):
    return Estimate((lo + hi) / 2 if value is None else value, 0.1, lo, hi, 100)


YES, NO, OPEN = est(1.2, 1.8), est(2.1, 2.5), est(1.8, 2.3)  # for InBand("q", 1, 2)
BAND = InBand("q", 1.0, 2.0)


def test_all_of_every_branch_gives_its_verdict_why_and_settledness():
    nc = NotCheckable("identity")
    j = AllOf({"a": nc, "b": NotCheckable("no data")}).judge({"a": 1, "b": 2})
    assert j == Judgement("not checkable", "(a) not checkable: identity; (b) not checkable: no data", True, 1.0)
    j = AllOf({"a": BAND, "b": BAND}).judge({"a": YES, "b": NO})
    assert (j.verdict, j.settled) == ("partly", True)
    assert j.why.startswith("(a) reproduced: q = ") and "; (b) not reproduced: q = " in j.why
    j = AllOf({"a": BAND, "b": BAND, "c": BAND}).judge({"a": YES, "b": NO, "c": OPEN})
    assert (j.verdict, j.settled) == ("partly", False)
    j = AllOf({"a": BAND, "b": BAND}).judge({"a": YES, "b": OPEN})
    want = BAND.judge(OPEN).runs_factor
    assert (j.verdict, j.settled, j.runs_factor) == ("undecided", False, want) and 1 < want < math.inf
    j = AllOf({"a": BAND, "b": nc}).judge({"a": NO, "b": 0})
    assert (j.verdict, j.settled, j.runs_factor) == ("not reproduced", True, 1.0)


def test_a_partly_part_makes_the_whole_partly_even_beside_an_undecided_one():
    inner = AllOf({"x": BAND, "y": BAND})
    j = AllOf({"inner": inner, "open": BAND}).judge({"inner": {"x": YES, "y": NO}, "open": OPEN})
    assert (j.verdict, j.settled) == ("partly", False)


def test_all_of_the_largest_runs_factor_of_its_open_parts():
    near, far = est(1.9, 2.05), est(1.5, 2.5)
    j = AllOf({"a": BAND, "b": BAND}).judge({"a": near, "b": far})
    assert j.runs_factor == max(BAND.judge(near).runs_factor, BAND.judge(far).runs_factor)


@pytest.mark.parametrize("tolerance", [0.0, 0.5])
def test_monotone_projects_the_runs_that_separate_its_ends(tolerance):
    """((r0 + r1) / (|v1 - v0| - tolerance))^2, r the facing reaches (the first end's up, the last's down): ends
    1 +- 1 and 2.5 +- 0.5 overlap."""
    rule = Monotone("g", "x", tolerance=tolerance)
    j = rule.judge([est(0.0, 2.0), est(2.0, 3.0)])
    assert j.verdict == "undecided" and not j.settled
    assert j.runs_factor == pytest.approx(((1.0 + 0.5) / (1.5 - tolerance)) ** 2)


def test_monotone_runs_factor_is_at_least_one_and_infinite_without_a_trend():
    rule = Monotone("g", "x")
    assert rule._ends_factor(est(0.0, 1.0), est(1.2, 2.2)) == 1.0  # (0.5 + 0.5) / 1.2 < 1: runs enough
    assert rule._ends_factor(est(0.0, 2.0), est(0.0, 2.0)) == math.inf  # no difference: no number of runs
    assert Monotone("g", "x", tolerance=3.0)._ends_factor(est(0.0, 2.0), est(1.0, 3.0)) == math.inf
    assert rule._ends_factor(Estimate(1.0, 0.1, -1.0, math.inf, 100), est(1.5, 2.5)) == math.inf  # open towards
    far = rule._ends_factor(Estimate(1.0, 0.1, -math.inf, 3.0, 100), est(1.5, 2.5))  # open away: its facing reach
    assert far == pytest.approx(((3.0 - 1.0 + 2.0 - 1.5) / (2.0 - 1.0)) ** 2)
    assert rule._ends_factor(est(0.0, 0.1), est(10.0, 10.1)) == 1.0


def test_in_band_and_within_factor_write_every_parameter():
    assert InBand("rms", 1.0, 2.0, "px", "lower").to_dict() == {
        "kind": "in_band",
        "text": InBand("rms", 1.0, 2.0, "px", "lower").text(),
        "quantity": "rms",
        "low": 1.0,
        "high": 2.0,
        "unit": "px",
        "better": "lower",
    }
    w = WithinFactor("rate", 2.0, 1.5, "x alpha", "higher")
    assert w.params() == {
        "quantity": "rate",
        "low": 2.0 / 1.5,
        "high": 3.0,
        "unit": "x alpha",
        "better": "higher",
        "paper_value": 2.0,
        "factor": 1.5,
    }
    assert w._band() == "within a factor 1.5 of the paper's 2 x alpha ([1.333, 3])"
    assert WithinFactor("rate", 2.0, 1.5)._band() == "within a factor 1.5 of the paper's 2 ([1.333, 3])"


def test_ordering_writes_every_parameter_and_says_its_side():
    o = Ordering("MSE of A", "MSE of B", "<", "ratio", paired=False, unit="px^2")
    assert o.params() == {
        "a": "MSE of A",
        "b": "MSE of B",
        "relation": "<",
        "measure": "ratio",
        "paired": False,
        "quantity": "ratio of MSE of A to MSE of B",
        "unit": "ratio of MSE of A to MSE of B",
    }
    assert o.text() == (
        "MSE of A < MSE of B, judged on the unpaired (independent samples) ratio MSE of A / MSE of B: reproduced if "
        "its 95 % interval lies wholly below 1, not reproduced if wholly on the other side, undecided if it "
        "contains 1"
    )
    d = Ordering("a", "b", ">", unit="px")
    assert d.params()["unit"] == "px" and d.quantity == "difference a minus b (px)"
    assert "lies wholly above 0" in d.text() and "paired difference a - b" in d.text()


_TAIL = (
    ": reproduced if the whole 95 % interval lies inside, not reproduced if it lies wholly outside, undecided if "
    "it straddles a bound"
)


def test_in_band_text_says_its_band_unit_and_better_side():
    assert InBand("rms", None, 2.0).text() == "rms at most 2" + _TAIL
    assert InBand("rms", 1.0, 2.0, "px", "lower").text() == (
        "rms in [1, 2] px" + _TAIL + " (wholly below the band is better than the paper's number, and still not the "
        "paper's number)"
    )
    assert InBand("rms", 1.0, None, "px", "higher").text() == (
        "rms at least 1 px" + _TAIL + " (wholly above the band is better than the paper's number, and still not the "
        "paper's number)"
    )


def test_monotone_text_and_parameters():
    m = Monotone("g", "x", "decreasing", "el", 0.01)
    assert m.text() == (
        "g is decreasing in x: reproduced if the first and last 95 % intervals are separated by more than 0.01 el in "
        "that direction and no neighbouring pair is separated the other way; not reproduced if the ends, or any "
        "neighbouring pair, are separated against the trend; undecided if nothing along the grid resolves the trend"
    )
    assert Monotone("g", "x").text().startswith("g is increasing in x: reproduced if the first and last 95 % "
                                                "intervals are separated in that direction")  # fmt: skip
    assert Monotone("g", "x", tolerance=0.5).text().startswith("g is increasing in x: reproduced if the first and "
                                                               "last 95 % intervals are separated by more than 0.5 in")  # fmt: skip
    assert m.to_dict() == {"kind": "monotone", "text": m.text(), "quantity": "g", "over": "x",
                           "direction": "decreasing", "unit": "el", "tolerance": 0.01}  # fmt: skip
    for bad in ({"direction": "up"}, {"tolerance": -0.1}, {"tolerance": math.nan}):
        with pytest.raises(ValueError, match=next(iter(bad))):
            Monotone("g", "x", **bad)


def test_composites_and_not_checkable_write_their_parts():
    nc = NotCheckable("r")
    assert nc.to_dict() == {"kind": "not_checkable", "text": "not checkable: r", "reason": "r"}
    a = AllOf({"p": nc, "q": InBand("rms", None, 2.0)})
    assert a.text() == "all of: (p) not checkable: r; (q) rms at most 2" + _TAIL
    assert a.to_dict() == {
        "kind": "all_of",
        "text": a.text(),
        "parts": {"p": nc.to_dict(), "q": a.parts["q"].to_dict()},
    }
    with pytest.raises(ValueError, match="AllOf needs at least one part"):
        AllOf({})
    with pytest.raises(ValueError, match=r"AllOf: measured lacks the parts \['q'\]"):
        a.judge({"p": 1})


def _j(verdict, why, settled=True, runs=1.0):
    return Judgement(verdict, why, settled, runs)


def test_monotone_judgements_say_the_ends_and_the_steps():
    m, nan = Monotone("g", "x", unit="el"), Estimate(math.nan, 0.1, 0.0, 1.0, 100)
    head = "g: 0.5 [0, 1] el at the first point, 4.5 [4, 5] el at the last; "
    assert m.judge([est(0, 1), est(2, 3), est(4, 5)]) == _j(
        "reproduced", head + "2 of 2 steps measurably increasing, 0 the other way"
    )
    assert m.judge([est(0, 1), est(2, 3), est(1.2, 1.8), est(4, 5)]) == _j(
        "not reproduced", head + "2 of 3 steps measurably increasing, 1 the other way (measurably not monotone)"
    )
    assert m.judge([est(4, 5), est(2, 3)]) == _j(
        "not reproduced",
        "g: 4.5 [4, 5] el at the first point, 2.5 [2, 3] el at the last; 0 of 1 steps measurably increasing, 1 the "
        "other way (the ends go against the trend)",
    )
    assert m.judge([est(0, 2), est(1, 3)]) == _j(
        "undecided",
        "g: 1 [0, 2] el at the first point, 2 [1, 3] el at the last; 0 of 1 steps measurably increasing, 0 the other "
        "way (no measurable trend yet; about 4 times the runs are projected to decide it)",
        False,
        4.0,
    )
    assert m.judge([est(0, 1), nan, est(4, 5)]) == _j(
        "reproduced", head + "1 of 1 steps measurably increasing, 0 the other way (1 undecided points left out)"
    )
    for points, bad in (([nan, est(4, 5)], [0]), ([est(0, 1), est(2, 3), nan], [2])):
        assert m.judge(points) == _j(
            "undecided",
            f"g: points {bad} along x are undecided (NaN, degenerate or extrapolated), so the trend cannot be decided",
            False,
            math.inf,
        )
    with pytest.raises(ValueError, match="Monotone needs at least two points"):
        m.judge([est(0, 1)])


def test_a_decreasing_trend_is_the_mirror_of_an_increasing_one():
    down = Monotone("g", "x", "decreasing")
    assert down.decide([est(4, 5), est(2, 3), est(0, 1)]) == "reproduced"
    assert down.decide([est(0, 1), est(2, 3)]) == "not reproduced"
    assert down.decide([est(4, 5), est(0, 1), est(2, 3), est(-1, -0.5)]) == "not reproduced"


def test_by_reading_judges_each_reading_by_its_own_rule():
    from tvtrack.verdicts import ByReading, for_config, is_decisive

    inside, default = InBand("q", 1.0, 2.0), InBand("q", 0.0, 1.0)
    b = ByReading("e", {"a": inside}, default)
    assert ByReading.tag("a", 3) == {"reading": "a", "measured": 3}
    assert b.judge(ByReading.tag("a", est(1.2, 1.8))).verdict == "reproduced"
    assert b.judge(ByReading.tag("z", est(1.2, 1.8))).verdict == "not reproduced"  # the default reading's rule
    assert b.for_value("a") is inside and b.for_value("z") is default
    assert for_config(b, {"e": "a"}) is inside and for_config(b, {}) is default and for_config(inside, {}) is inside
    with pytest.raises(ValueError, match=r"ByReading\('e'\) needs ByReading.tag\(value, measured\), got 1.5"):
        b.judge(1.5)
    with pytest.raises(ValueError, match="needs ByReading.tag"):
        b.judge({"reading": "a"})
    with pytest.raises(ValueError, match="ByReading needs the default reading's rule"):
        ByReading("e", {"a": inside})
    assert b.text() == default.text() + " (under e = a: " + inside.text() + ")"
    assert ByReading("e", {"a": default}, default).text() == default.text()
    assert b.to_dict() == {
        "kind": "by_reading",
        "text": b.text(),
        "entry": "e",
        "default": default.to_dict(),
        "rules": {"a": inside.to_dict()},
    }
    assert [is_decisive(v) for v in ("reproduced", "not reproduced", "partly", "undecided", "not checkable")] == [
        True,
        True,
        True,
        False,
        False,
    ]


def test_synthetic_values_reach_the_verdict_asked_for_and_nothing_else():
    from tvtrack.verdicts import synthetic

    rules = [
        InBand("q", 1.0, 2.0),
        InBand("q", None, -3.0),
        InBand("q", 4.0),
        Ordering("a", "b", ">"),
        Ordering("a", "b", "<", "ratio"),
        Monotone("g", "x", tolerance=2.0),
        Monotone("g", "x", "decreasing"),
    ]
    for rule in rules:
        for verdict in ("reproduced", "not reproduced"):
            m = synthetic(rule, verdict)
            assert rule.decide(m) == verdict, (rule, verdict, m)
            points = m if isinstance(m, list) else [m]
            assert all(p.ci_high - p.ci_low < 1e-8 * max(1.0, abs(p.value)) for p in points)
    both = AllOf({"p": InBand("q", 1.0, 2.0), "n": NotCheckable("r")})
    assert synthetic(both, "reproduced")["p"].value == 1.5 and synthetic(both, "reproduced")["n"] is None
    assert synthetic(NotCheckable("r"), "reproduced") is None
    assert synthetic(AllOf({"p": InBand("q", 1.0, 2.0), "o": Ordering("a", "b")}), "not reproduced")["o"].value < 0
    assert synthetic(Ordering("a", "b", "<", "ratio"), "reproduced").value == 0.5
    assert synthetic(Ordering("a", "b", ">", "ratio"), "reproduced").value == 1.5
    assert synthetic(Ordering("a", "b", ">"), "not reproduced").value == -0.5
    assert [p.value for p in synthetic(Monotone("g", "x", tolerance=2.0), "reproduced")] == [0.0, 30.0]
    assert [p.value for p in synthetic(Monotone("g", "x"), "not reproduced")] == [0.0, -10.0]
    assert synthetic(InBand("q", None, -3.0), "reproduced").value == -7.0
    assert synthetic(InBand("q", 4.0), "reproduced").value == 9.0
    assert synthetic(InBand("q", 4.0), "not reproduced").value == -1.0
    assert synthetic(InBand("q", 1.0, 2.0), "not reproduced").value == 5.0


def test_band_ends_are_closed_and_an_ordering_reference_is_not_on_either_side():
    band = InBand("q", 1.0, 2.0)
    assert band.decide(est(1.0, 1.5)) == "reproduced" and band.decide(est(1.5, 2.0)) == "reproduced"
    assert band.decide(est(0.5, 1.0)) == "undecided" and band.decide(est(2.0, 2.5)) == "undecided"
    for relation in (">", "<"):
        o = Ordering("a", "b", relation)
        assert o.decide(est(0.0, 1.0)) == "undecided" and o.decide(est(-1.0, 0.0)) == "undecided"
    up = Monotone("g", "x", tolerance=1.0)
    assert up.decide([est(2.0, 3.0), est(0.0, 1.0)]) == "undecided"  # separated by exactly the tolerance: flat


def test_an_undecided_judgement_is_never_settled_and_says_why():
    nan = Estimate(math.nan, 0.1, 0.0, 1.0, 100)
    for rule in (InBand("q", 1.0, 2.0, "px"), Ordering("a", "b")):
        j = rule.judge(nan)
        assert (j.verdict, j.settled) == ("undecided", False) and "so it cannot decide" in j.why
    j = InBand("q", 1.0, 2.0, "px").judge(est(1.5, 2.5))
    assert (j.verdict, j.settled) == ("undecided", False) and j.why.startswith("q = 2 [1.5, 2.5] px straddles")
    assert (
        InBand("q", 1.0, 2.0).judge(est(0.2, 0.5)).why == "q = 0.35 [0.2, 0.5] lies wholly below the band (in [1, 2])"
    )
    j = AllOf({"a": InBand("q", 1.0, 2.0)}).judge({"a": est(1.2, 1.8)})
    assert j == Judgement("reproduced", "(a) reproduced: q = 1.5 [1.2, 1.8] lies in [1, 2]", True, 1.0)


def test_ordering_judgements_say_the_difference_and_the_runs_to_decide():
    o = Ordering("a", "b", ">")
    assert o.judge(est(0.5, 1.5)) == Judgement("reproduced", "a - b = 1 [0.5, 1.5]: a > b", True, 1.0)
    assert o.judge(est(-1.5, -0.5)) == Judgement(
        "not reproduced", "a - b = -1 [-1.5, -0.5]: the opposite ordering holds", True, 1.0
    )
    assert o.judge(est(-0.5, 1.5)) == Judgement(
        "undecided",
        "a - b = 0.5 [-0.5, 1.5] contains 0: no measurable difference yet; about 4 times the runs are projected to decide it",
        False,
        4.0,
    )
