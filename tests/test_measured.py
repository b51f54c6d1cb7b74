"""A measured value read as an estimate (:mod:`tvtrack.measured`): what it reads, the widening to its nominal coverage
(:func:`calibrated`), when it is undecided, the runs projected to decide it (:func:`runs_to_decide`, closed forms) and
its words. Every expected number is worked out by hand here, never by calling the code a second time."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.special import ndtri

from tvtrack.estimate import Estimate
from tvtrack.measured import (
    as_estimate,
    calibrated,
    decide_note,
    ends_to_decide,
    fold_about,
    interval_of,
    is_undecided,
    lost_runs,
    runs_to_decide,
    short_number,
    show_estimate,
    why_undecided,
    with_lost_runs,
)
from tvtrack.verdicts import Monotone

NAN = float("nan")
SHORT = "Student t; coverage 0.882 at n = 5 (skewed samples; heavy tails 0.815)"  # below the 0.93 floor
REACHED = "bootstrap-t; coverage 0.936 at n = 5 (skewed samples; heavy tails 0.898)"  # at the floor, short of 0.95
UNMEASURED = "Student t; coverage unmeasured at n = 3 (below n = 5, the smallest size measured)"


def _est(value, low, high, method="large-sample normal", n=10, confidence=0.95, extrapolated=False):
    return Estimate(value, NAN, low, high, n, confidence, method, extrapolated)


# --- lost runs ---------------------------------------------------------------------------------------------------


def test_with_lost_runs_keeps_both_values_and_the_counts_as_integers():
    v, lock = _est(2.0, 1.0, 3.0), _est(1.5, 1.0, 2.0)
    got = with_lost_runs(v, lock, 3.0, 10.0)
    assert got == {"value": v, "in lock": lock, "lost": 3, "runs": 10}
    assert type(got["lost"]) is int and type(got["runs"]) is int
    assert with_lost_runs(1.0, 1.0, 0, 1)["lost"] == 0  # no run lost, a single run: allowed
    assert with_lost_runs(1.0, 1.0, 1, 1)["lost"] == 1  # every run lost: allowed


@pytest.mark.parametrize("lost, runs", [(-1, 5), (6, 5), (0, 0), (1, 0)])
def test_with_lost_runs_refuses_counts_outside_0_lost_runs(lost, runs):
    with pytest.raises(ValueError, match=f"lost {lost} of runs {runs}"):
        with_lost_runs(1.0, 1.0, lost, runs)


def test_lost_runs_reads_back_only_a_value_with_all_four_keys():
    v = with_lost_runs(_est(2.0, 1.0, 3.0), 1.5, 2, 8)
    assert lost_runs(v) == {"in lock": 1.5, "lost": 2, "runs": 8}
    assert lost_runs({"value": 1.0, "in lock": 1.0, "lost": 0}) is None  # no runs: an ordinary estimate dict
    assert lost_runs(2.0) is None and lost_runs([1.0, 2.0]) is None


# --- as_estimate -------------------------------------------------------------------------------------------------


def test_a_plain_number_is_exact_its_interval_the_point():
    assert as_estimate(3) == Estimate(3.0, 0.0, 3.0, 3.0, 1, 0.95, "exact")
    assert as_estimate(2.5) == Estimate(2.5, 0.0, 2.5, 2.5, 1, 0.95, "exact")

    assert as_estimate(np.float32(2.5)) == Estimate(2.5, 0.0, 2.5, 2.5, 1, 0.95, "exact")  # not a float subclass
    assert as_estimate(np.int64(4)) == Estimate(4.0, 0.0, 4.0, 4.0, 1, 0.95, "exact")

    class Number:
        def __float__(self):
            return 7.25

    assert as_estimate(Number()) == Estimate(7.25, 0.0, 7.25, 7.25, 1, 0.95, "exact")


def test_an_estimate_is_read_as_it_is():
    e = _est(1.0, 0.5, 1.5, SHORT)
    assert as_estimate(e) is e


def test_an_estimate_dict_is_read_field_by_field_with_none_as_nan():
    d = {"value": 2.0, "stderr": None, "ci_low": 1.0, "ci_high": None, "n": 7, "confidence": 0.9, "method": "m"}
    e = as_estimate({**d, "unused": 1})
    assert (e.value, e.ci_low, e.n, e.confidence, e.method, e.extrapolated) == (2.0, 1.0, 7, 0.9, "m", False)
    assert math.isnan(e.stderr) and math.isnan(e.ci_high)
    bare = as_estimate({"value": 4.0, "ci_low": 3.0, "ci_high": 5.0})  # stderr, n, confidence, method left out
    assert (bare.value, bare.ci_low, bare.ci_high, bare.n, bare.confidence, bare.method) == (4.0, 3.0, 5.0, 1, 0.95, "")
    assert math.isnan(bare.stderr) and bare.extrapolated is False
    assert as_estimate({"value": 4.0, "stderr": 0.5, "ci_low": 3.0, "ci_high": 5.0}).stderr == 0.5
    interval = {"value": 4.0, "ci_low": 3.0, "ci_high": 5.0}
    assert as_estimate({**interval, "method": None}).method is None  # a method of None stays None, not NaN
    assert as_estimate({**interval, "extrapolated": None}).extrapolated is False
    assert as_estimate({**interval, "extrapolated": 1}).extrapolated is True


def test_a_value_with_lost_runs_is_judged_on_every_run():
    every, lock = _est(3.0, 2.0, 4.0), _est(1.0, 0.5, 1.5)
    assert as_estimate(with_lost_runs(every, lock, 2, 10)) is every
    assert as_estimate(with_lost_runs({"value": 3.0, "ci_low": 2.0, "ci_high": 4.0}, lock, 2, 10)).ci_high == 4.0
    assert as_estimate(with_lost_runs(5, lock, 0, 10)) == Estimate(5.0, 0.0, 5.0, 5.0, 1, 0.95, "exact")


@pytest.mark.parametrize(
    "bad, named", [("1.0", "str: '1.0'"), (None, "NoneType: None"), ([1.0], r"list: \[1.0\]"), ({"n": 1}, "dict")]
)
def test_what_is_no_measured_value_is_refused_naming_its_type(bad, named):
    with pytest.raises(TypeError, match=f"^cannot read a measured value from {named}"):
        as_estimate(bad)


# --- calibrated --------------------------------------------------------------------------------------------------


def test_an_interval_short_of_its_coverage_is_widened_by_the_ratio_of_normal_quantiles():
    """Coverage 0.882 stated for a 95 % interval: each side stretched about the value by z(0.975) / z(0.941)
    (linear scale: the interval reaches below zero)."""
    f = ndtri(0.975) / ndtri(0.5 + 0.882 / 2)
    assert f == pytest.approx(1.9600 / 1.5632, rel=1e-3)  # 1.254: a widening, not a narrowing
    e = calibrated(_est(1.0, -1.0, 2.0, SHORT))
    assert e.value == 1.0
    assert e.ci_low == pytest.approx(1.0 - 2.0 * f) and e.ci_high == pytest.approx(1.0 + 1.0 * f)
    assert "measured coverage 0.882" in e.method and f"widened x{f:.3f} to 95%" in e.method


def test_a_positive_interval_short_of_its_coverage_is_widened_on_the_log_scale():
    f = ndtri(0.975) / ndtri(0.5 + 0.882 / 2)
    e = calibrated({"value": 2.0, "ci_low": 1.0, "ci_high": 8.0, "n": 5, "method": SHORT})
    assert e.ci_low == pytest.approx(2.0 * 0.5**f) and e.ci_high == pytest.approx(2.0 * 4.0**f)


def test_an_interval_that_reaches_its_floor_or_states_no_coverage_is_not_widened():
    reached = _est(1.0, 0.5, 1.5, REACHED)  # 0.936 >= the 0.93 floor, though short of 0.95: decided as it is
    assert calibrated(reached) is reached
    unmeasured = _est(1.0, 0.5, 1.5, UNMEASURED)  # nothing to calibrate by (is_undecided holds it undecided)
    assert calibrated(unmeasured) is unmeasured
    plain = _est(1.0, 0.5, 1.5)  # no coverage stated: its nominal level
    assert calibrated(plain) is plain
    assert calibrated(2.0) == Estimate(2.0, 0.0, 2.0, 2.0, 1, 0.95, "exact")


# --- is_undecided, interval_of, why_undecided ---------------------------------------------------------------------


def test_a_random_quantity_with_a_proper_interval_decides():
    assert not is_undecided(_est(1.0, 0.5, 1.5))
    assert not is_undecided(_est(1.0, 0.5, 1.5, SHORT))  # short coverage: widened, still decides
    assert not is_undecided(2.0) and not is_undecided(0)  # an exact number decides, its interval the point


@pytest.mark.parametrize(
    "e, why",
    [
        (_est(1.0, 0.5, 1.5, extrapolated=True), "extrapolated beyond the data"),
        (_est(NAN, 0.5, 1.5), "not measured (NaN)"),
        (_est(1.0, 0.5, 1.5, UNMEASURED), "its interval's coverage at this sample size is unmeasured"),
        (_est(1.0, NAN, 1.5), "its interval is undefined or degenerate"),
        (_est(1.0, 0.5, NAN), "its interval is undefined or degenerate"),
        (_est(1.0, 1.0, 1.0), "its interval is undefined or degenerate"),  # degenerate, not exact: random
    ],
)
def test_each_undecided_estimate_and_its_reason(e, why):
    assert is_undecided(e) and is_undecided(e.to_dict())
    assert why_undecided(e) == why


def test_an_exact_number_is_decided_even_with_an_undefined_interval_but_not_as_nan():
    exact_nan_interval = Estimate(2.0, 0.0, NAN, NAN, 1, 0.95, "exact")
    assert not is_undecided(exact_nan_interval)
    assert interval_of(exact_nan_interval) == (2.0, 2.0)
    assert is_undecided(Estimate.exact(NAN))
    assert is_undecided(Estimate(2.0, 0.0, 2.0, 2.0, 1, 0.95, "exact", True))  # extrapolated: never decides


def test_interval_of_is_the_interval_itself_otherwise():
    assert interval_of(_est(1.0, 0.5, 1.5)) == (0.5, 1.5)
    assert interval_of(Estimate(2.0, 0.0, 1.0, 3.0, 1, 0.95, "exact")) == (1.0, 3.0)
    lo_nan = interval_of(Estimate(2.0, 0.0, NAN, 3.0, 1, 0.95, "exact"))  # one side undefined: the point
    assert lo_nan == (2.0, 2.0)
    hi_nan = interval_of(Estimate(2.0, 0.0, 1.0, NAN, 1, 0.95, "exact"))
    assert hi_nan == (2.0, 2.0)
    random = interval_of(_est(2.0, NAN, 3.0))  # a random quantity's undefined interval stays undefined
    assert math.isnan(random[0]) and random[1] == 3.0


def test_why_undecided_reads_none_as_an_empty_method():
    e = Estimate(1.0, NAN, 1.0, 1.0, 10, 0.95, None)
    assert why_undecided(e) == "its interval is undefined or degenerate"


# --- runs_to_decide: closed forms ---------------------------------------------------------------------------------


def test_a_straddled_edge_leaves_at_the_squared_ratio_of_half_width_to_distance():
    """Point 1 in [0, 4]: an edge at 0.5 is 0.5 away with the lower half-width 1 -> (1 / 0.5)^2 = 4; an edge at 2 is
    1 away with the upper half-width 3 -> (3 / 1)^2 = 9; both straddled: the larger."""
    e = _est(1.0, 0.0, 4.0)
    assert runs_to_decide(e, (0.5,)) == pytest.approx(4.0)
    assert runs_to_decide(e, (2.0,)) == pytest.approx(9.0)
    assert runs_to_decide(e, (0.5, 2.0)) == pytest.approx(9.0)
    assert runs_to_decide(e, (2.0, 0.5)) == pytest.approx(9.0)
    assert runs_to_decide(e, (None, 2.0)) == pytest.approx(9.0)  # an open band end is no edge
    assert runs_to_decide(e, (0.5, None)) == pytest.approx(4.0)


def test_the_projection_is_the_interval_width_shrinking_as_one_over_root_n():
    """Multiplying the runs by the factor shrinks the half-width by its square root: exactly onto the edge."""
    e = _est(3.0, 1.0, 4.0)  # lower half-width 2, upper 1
    for edge in (1.5, 2.0, 2.9, 3.5, 3.99):
        k = runs_to_decide(e, (edge,))
        half = (3.0 - 1.0) if edge < 3.0 else (4.0 - 3.0)
        assert half / math.sqrt(k) == pytest.approx(abs(3.0 - edge))


def test_nothing_straddled_takes_the_runs_it_has():
    e = _est(1.0, 0.0, 4.0)
    assert runs_to_decide(e, ()) == 1.0
    assert runs_to_decide(e, (None, None)) == 1.0
    assert runs_to_decide(e, (-1.0, 5.0)) == 1.0  # both edges outside the interval
    assert runs_to_decide(e, (0.0,)) == 1.0 and runs_to_decide(e, (4.0,)) == 1.0  # an edge on an end: not inside
    assert runs_to_decide(e, (math.inf, -math.inf)) == 1.0
    on_end = _est(NAN, 0.0, 4.0)  # even with no point: an edge on the interval's end is not straddled
    assert runs_to_decide(on_end, (0.0,)) == 1.0 and runs_to_decide(on_end, (4.0,)) == 1.0


def test_no_number_of_runs_decides_a_point_on_the_edge_or_an_undefined_point():
    assert runs_to_decide(_est(1.0, 0.0, 4.0), (1.0,)) == math.inf
    assert runs_to_decide(_est(1.0, 0.0, 4.0), (0.5, 1.0)) == math.inf  # one edge on the point: inf over all
    assert runs_to_decide(_est(NAN, 0.0, 4.0), (1.0,)) == math.inf
    assert runs_to_decide(Estimate(2.0, 0.0, 2.0, 2.0, 1, 0.95, "exact"), (2.0,)) == 1.0  # exact: nothing inside


def test_zero_events_certify_an_upper_edge_at_ln_alpha_over_ln_one_minus_edge_runs():
    """No loss in 6 runs certifies p <= 1 - 0.05^(1/6) = 0.393; the edge 0.1 is certified at
    ln(0.05) / ln(0.9) = 28.4 runs: 4.74 times the 6."""
    b6 = 1 - 0.05 ** (1 / 6)
    e = Estimate(0.0, NAN, 0.0, b6, 6, 0.95, "count: zero events")
    assert runs_to_decide(e, (0.1,)) == pytest.approx(math.log(0.05) / math.log(0.9) / 6)
    assert 6 * runs_to_decide(e, (0.1,)) == pytest.approx(28.433, abs=1e-3)  # 29 runs at 95 %
    # two edges straddled: the smaller rate needs more runs
    assert runs_to_decide(e, (0.2, 0.1)) == pytest.approx(math.log(0.05) / math.log(0.9) / 6)
    # the confidence sets alpha: 90 % certifies 0.1 at ln(0.1) / ln(0.9) = 21.9 runs
    e90 = Estimate(0.0, NAN, 0.0, 1 - 0.1 ** (1 / 6), 6, 0.90, "Clopper-Pearson")
    assert runs_to_decide(e90, (0.1,)) == pytest.approx(math.log(0.1) / math.log(0.9) / 6)


def test_zero_events_in_a_single_run_still_certify_by_the_count():
    """One run, no event: p <= 0.95 certified; the edge 0.1 needs 28.4 runs, not the half-width's (0.95 / 0.1)^2."""
    e = Estimate(0.0, NAN, 0.0, 0.95, 1, 0.95, "count: zero events")
    assert runs_to_decide(e, (0.1,)) == pytest.approx(math.log(0.05) / math.log(0.9))


def test_all_events_certify_a_lower_edge_by_its_complement():
    b10 = 1 - 0.05 ** (1 / 10)
    e = Estimate(1.0, NAN, 1.0 - b10, 1.0, 10, 0.95, "Clopper-Pearson")
    # the complement 0.2 must be certified: ln(0.05) / ln(1 - 0.2) = 13.4 runs, 1.34 times the 10
    assert runs_to_decide(e, (0.8,)) == pytest.approx(math.log(0.05) / math.log(0.8) / 10)
    assert runs_to_decide(e, (0.8,)) == pytest.approx(1.3425, abs=1e-4)


def test_a_count_with_some_events_or_none_counted_is_projected_by_its_half_width():
    """Only zero (or all) events in a direct count certify a bound; a count of 1 in 10 whose interval reaches 0, an
    interval of no count method, or a count over no runs is read by its half-width: (0.3 / 0.2)^2 = 2.25."""
    assert runs_to_decide(Estimate(0.1, NAN, 0.0, 0.4, 10, 0.95, "Clopper-Pearson"), (0.3,)) == pytest.approx(2.25)
    assert runs_to_decide(Estimate(0.0, NAN, 0.0, 0.4, 10, 0.95, "bootstrap"), (0.2,)) == pytest.approx(4.0)
    assert runs_to_decide(Estimate(0.0, NAN, 0.0, 0.4, 0, 0.95, "count: zero events"), (0.2,)) == pytest.approx(4.0)
    # "count" must open the method; a method merely mentioning counts is no count
    assert runs_to_decide(Estimate(0.0, NAN, 0.0, 0.4, 10, 0.95, "mean of counts"), (0.2,)) == pytest.approx(4.0)
    # all events but an interval not reaching 1: no certified bound either
    assert runs_to_decide(Estimate(1.0, NAN, 0.6, 0.9, 10, 0.95, "count: 10 of 10"), (0.8,)) == pytest.approx(4.0)
    assert runs_to_decide(Estimate(0.0, NAN, -0.2, 0.4, 10, 0.95, "count: 0 of 10"), (0.2,)) == pytest.approx(4.0)


def test_a_zero_count_edge_outside_the_rates_is_never_certified():
    e = Estimate(0.0, NAN, 0.0, 2.0, 6, 0.95, "count: zero events")  # an interval beyond 1: no rate there
    assert runs_to_decide(e, (1.5,)) == math.inf
    assert runs_to_decide(e, (1.0,)) == math.inf
    e1 = Estimate(1.0, NAN, -1.0, 1.0, 6, 0.95, "count: 6 of 6")
    assert runs_to_decide(e1, (0.0,)) == math.inf


# --- words -------------------------------------------------------------------------------------------------------


def test_short_number_is_four_significant_digits():
    assert short_number(3.14159) == "3.142" and short_number(123456.0) == "1.235e+05" and short_number(0.5) == "0.5"


def test_show_estimate_gives_value_interval_unit_and_a_widening_note():
    e = _est(1.23456, 0.5, 2.0)
    assert show_estimate(e) == "1.235 [0.5, 2]"
    assert show_estimate(e, "px") == "1.235 [0.5, 2] px"
    widened = calibrated(_est(1.0, -1.0, 2.0, SHORT))
    assert show_estimate(widened, "s").endswith(" s (interval widened to its nominal coverage)")
    assert show_estimate(_est(1.0, -1.0, 2.0, None)) == "1 [-1, 2]"


def test_a_pool_widened_to_its_replicates_spread_is_not_said_to_reach_its_nominal_coverage():
    """A pool of replicates that disagree is widened to Student's t over their values (``tvtrack.pooling``): that is
    no calibration to the nominal coverage, and the note says what was done."""
    spread = "pooled over 3 independent replicates that disagree beyond their own intervals (agreement test p = 0.01)"
    pooled = _est(1.0, 0.5, 2.0, spread + ": widened to Student's t over their values")
    text = show_estimate(pooled)
    assert "nominal coverage" not in text
    assert text == "1 [0.5, 2] (interval widened to the replicates' spread, since they disagree)"
    both = calibrated(_est(1.0, -1.0, 2.0, SHORT))
    both = _est(both.value, both.ci_low, both.ci_high, both.method + "; " + pooled.method)
    assert show_estimate(both).endswith(
        "(interval widened to its nominal coverage and to the replicates' spread, since they disagree)"
    )


def test_show_estimate_gives_the_bare_value_for_a_point_or_an_undefined_interval():
    assert show_estimate(Estimate.exact(2.5), "px") == "2.5 px"
    assert show_estimate(Estimate.exact(2.5)) == "2.5"
    assert show_estimate(_est(2.5, NAN, 3.0), "px") == "2.5 px"
    assert show_estimate(_est(2.5, 2.0, NAN)) == "2.5"
    assert show_estimate(_est(2.5, 2.5, 2.5)) == "2.5"
    assert show_estimate(_est(2.5, 2.0, 2.0)) == "2.5 [2, 2]"  # degenerate away from the point: shown as it is
    assert show_estimate(_est(2.5, 2.5, 3.0)) == "2.5 [2.5, 3]"


def test_decide_note_gives_the_factor_or_says_none_decides():
    assert decide_note(4.0) == "about 4 times the runs are projected to decide it"
    assert decide_note(28.433) == "about 28 times the runs are projected to decide it"
    assert decide_note(1.26) == "about 1.3 times the runs are projected to decide it"
    no = "no number of runs is projected to decide it"
    assert decide_note(math.inf) == no and decide_note(NAN) == no
    assert decide_note(math.inf, "the point sits on the edge") == no + " (the point sits on the edge)"
    assert decide_note(2.0, "the point sits on the edge") == "about 2 times the runs are projected to decide it"


def test_an_envelope_of_certified_bounds_is_never_projected_to_decide_and_says_why():
    """The pool of replicates some of which are certified bounds is their envelope: more replicates only widen it,
    so no number of runs decides an edge it straddles (it was projected from its width as if it shrank)."""
    from tvtrack.estimate import Estimate
    from tvtrack.measured import is_envelope, why_no_runs
    from tvtrack.pooling import pool

    bound = Estimate(0.0, math.nan, 0.0, 0.095, 30, 0.95, "zero events: one-sided bound")
    other = Estimate(1.4, 0.3, 0.9, 1.9, 30, 0.95, "t interval")
    env = pool([bound, other])
    assert is_envelope(env) and (env.ci_low, env.ci_high) == (0.0, 1.9)
    assert runs_to_decide(env, (1.0,)) == math.inf
    assert (
        why_no_runs(env, (1.0,))
        == "an envelope of the replicates' certified bounds, which more replicates do not narrow"
    )
    plain = Estimate(1.4, 0.3, 0.9, 1.9, 30, 0.95, "t interval")
    assert not is_envelope(plain) and runs_to_decide(plain, (1.0,)) == pytest.approx((0.5 / 0.4) ** 2)
    assert why_no_runs(plain, (1.4,)) == "the point sits on the edge"
    assert why_no_runs(Estimate(NAN, NAN, NAN, NAN, 0, 0.95, "none"), (1.0,)) == "the interval is undefined"
    unbounded = Estimate(1.2, 0.3, 0.8, math.inf, 30, 0.95, "bootstrap")  # it read "about 4 times the runs"
    assert runs_to_decide(unbounded, (1.0, 2.0)) == math.inf == runs_to_decide(unbounded, (2.0,))
    assert why_no_runs(unbounded, (2.0,)) == "the interval is unbounded on a side it straddles an edge"
    assert runs_to_decide(unbounded, (1.0,)) == pytest.approx((0.4 / 0.2) ** 2)  # the bounded side still projects
    grid = Estimate(2.4, 0.1, 2.0, 3.0, 18, 0.95, "pooled; allowance", sampling_low=2.3, sampling_high=2.5)
    assert runs_to_decide(grid, (2.6,)) == math.inf
    assert why_no_runs(grid, (2.6,)).startswith("the edge lies within the resolution of the grid")


def test_a_difference_is_widened_on_the_linear_scale_and_may_reach_zero():
    """A positive interval of a ratio is stretched on the log scale (it stays positive); a difference's on the
    linear scale, each side by the same factor, so a change whose lower end was just above 0 may reach below it."""
    from tvtrack.estimate import Estimate
    from tvtrack.measured import calibrated

    e = Estimate(0.04, 0.02, 0.004, 0.088, 80, 0.95, "bootstrap; coverage 0.895 at n = 80")
    ratio, diff = calibrated(e), calibrated(e, difference=True)
    f = ndtri(0.975) / ndtri(0.9475)  # z of the nominal 95 % over z of the measured 89.5 %
    assert ratio.ci_low > 0 and ratio.ci_low == pytest.approx(0.04 * (0.004 / 0.04) ** f)
    assert diff.ci_low == pytest.approx(0.04 - f * 0.036) and diff.ci_low < 0
    assert diff.ci_high == pytest.approx(0.04 + f * 0.048) and "widened x1.209 to 95%" in diff.method


# --------------------------------------------------------------------------- a ratio's fold distance either way


@pytest.mark.parametrize(
    "q, lo, hi, k, want",
    [
        (2.0, 1.5, 3.0, 1.0, (2.0, 1.5, 3.0)),  # above the reference: itself
        (0.5, 0.25, 0.8, 1.0, (2.0, 1.25, 4.0)),  # below it: k^2 / q, the ends swapped
        (1.2, 0.5, 2.5, 1.0, (1.2, 1.0, 2.5)),  # straddling k: from k
        (0.9, 0.6, 1.3, 1.0, (1 / 0.9, 1.0, 1 / 0.6)),  # straddling k from below: from k, to the farther end's fold
        (0.3, 0.0, 0.5, 1.0, (1 / 0.3, 2.0, np.inf)),  # a bound [0, b]: at least fold(b)
        (0.0, 0.0, 0.5, 1.0, (2.0, 2.0, np.inf)),  # an infinite value reads its interval's near end
        (1.0, 0.8, 1.6, 2.0, (4.0, 2.5, 5.0)),  # about k = 2
    ],
)
def test_a_fold_distance_is_the_ratio_or_k_squared_over_it_with_the_interval_mapped_end_by_end(q, lo, hi, k, want):
    ratio = Estimate(q, 0.1, lo, hi, 9, 0.95, "ratio", sampling_low=lo * 1.1, sampling_high=hi / 1.1)
    got = fold_about(ratio, k)
    assert (got.value, got.ci_low, got.ci_high) == pytest.approx(want)
    assert got.n == 9 and got.signed == ratio and got.fold_reference == k  # the signed ratio kept, for pooling
    # a ratio's resolution allowance does not map through the fold: the fold carries no sampling interval
    assert math.isnan(got.sampling_low) and math.isnan(got.sampling_high)
    assert got.method.startswith(f"ratio; fold distance from {k:g} either way, max(q, {k * k:g}/q)")
    assert f"q = {q:.4g} [{lo:.4g}, {hi:.4g}]" in got.method


def test_a_fold_distance_keeps_the_ratios_error_above_the_reference_and_inverts_it_by_the_delta_method_below():
    assert fold_about(Estimate(1.5, 0.2, 1.2, 1.9, 40, 0.95, "t")).stderr == 0.2
    assert fold_about(Estimate(0.4, 0.05, 0.3, 0.55, 40, 0.95, "t")).stderr == pytest.approx(0.05 / 0.4**2)
    assert fold_about(Estimate(1.0, 0.1, 0.8, 1.6, 40, 0.95, "t"), 2.0).stderr == pytest.approx(0.1 * 4.0)  # (k/q)^2
    flagged = fold_about(Estimate(0.4, 0.05, 0.3, 0.55, 40, 0.95, "t", True))
    assert (
        flagged.extrapolated is True and fold_about(Estimate(0.4, 0.05, 0.3, 0.55, 40, 0.95, "t")).extrapolated is False
    )
    ratio = Estimate(0.4, 0.05, float("nan"), 0.55, 40, 0.9, "t", True)
    undefined = fold_about(ratio, 2.0)  # an undefined end: nothing to fold, every field but the numbers kept
    assert all(math.isnan(x) for x in (undefined.value, undefined.stderr, undefined.ci_low, undefined.ci_high))
    assert (undefined.n, undefined.confidence, undefined.extrapolated) == (40, 0.9, True)
    assert undefined.signed == ratio and undefined.fold_reference == 2.0 and is_undecided(undefined)
    assert undefined.method.startswith("t; fold distance from 2 either way")


def test_a_fold_distance_is_written_with_its_signed_ratio_and_read_back_whole():
    ratio = Estimate(0.5, 0.05, 0.4, 0.625, 40, 0.95, "t", sampling_low=0.45, sampling_high=0.6)
    got = fold_about(ratio)
    d = got.to_dict()
    assert d["signed"] == ratio.to_dict() and d["fold_reference"] == 1.0
    assert as_estimate(d) == got and as_estimate(json.loads(json.dumps(d))) == got
    plain = Estimate(2.0, 0.1, 1.8, 2.2, 40).to_dict()
    assert "signed" not in plain and "fold_reference" not in plain and as_estimate(plain).signed is None


# --------------------------------------------------------------------------- a trend's ends with a resolution allowance


def test_the_runs_to_separate_a_trends_ends_shrink_only_their_sampling_parts():
    """Two thresholds read on a grid (half a step, 0.1, each side beyond their sampling intervals): of the gap 0.3
    between their values the facing allowances take 0.2, which no number of runs shrinks, so the sampling parts
    (0.1 a side) must fit in the 0.1 left: ((0.4 - 0.2) / (0.3 - 0.2))^2 = 4 times the runs, not (0.4 / 0.3)^2."""
    e0 = Estimate(1.0, 0.05, 0.8, 1.2, 18, 0.95, "t; allowance", sampling_low=0.9, sampling_high=1.1)
    e1 = Estimate(1.3, 0.05, 1.1, 1.5, 18, 0.95, "t; allowance", sampling_low=1.2, sampling_high=1.4)
    assert ends_to_decide(e0, e1) == (pytest.approx(4.0), "")
    assert ends_to_decide(e1, e0) == (pytest.approx(4.0), "")  # a decreasing trend faces the other sides
    plain = [Estimate(e.value, 0.05, e.ci_low, e.ci_high, 18, 0.95, "t") for e in (e0, e1)]
    assert ends_to_decide(*plain) == (pytest.approx((0.4 / 0.3) ** 2), "")
    one_sided = Estimate(1.3, 0.05, 1.1, 1.5, 18, 0.95, "t; allowance", sampling_low=1.1, sampling_high=1.4)
    assert ends_to_decide(e0, one_sided)[0] == pytest.approx(((0.4 - 0.1) / (0.3 - 0.1)) ** 2)  # e1's far side: none
    near = Estimate(1.2, 0.05, 1.0, 1.4, 18, 0.95, "t; allowance", sampling_low=1.1, sampling_high=1.3)
    f, why = ends_to_decide(e0, near)  # 0.2 apart: within the two allowances, never separated by more runs
    assert f == math.inf and "resolution of the grid" in why


def test_a_fold_distance_about_another_reference_reads_back_about_it_and_a_reference_must_be_positive():
    got = fold_about(Estimate(1.0, 0.1, 0.8, 1.6, 40, 0.95, "t"), 2.0)
    back = as_estimate(json.loads(json.dumps(got.to_dict())))
    assert back.fold_reference == 2.0 and back == got
    for bad in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="parameter 'reference'"):
            fold_about(Estimate(1.0, 0.1, 0.8, 1.6, 40, 0.95, "t"), bad)


def test_a_fold_distance_widens_its_ratio_to_its_nominal_coverage_before_it_folds():
    """A ratio whose helper covers 0.90 at its size is widened first: folded after, a widened end could cross the
    reference (a fold distance below 1)."""
    ratio = Estimate(0.9, 0.05, 0.75, 1.2, 5, 0.95, "t; coverage 0.90 at n = 5")
    got = fold_about(ratio)
    assert got.signed == calibrated(ratio) and got.ci_low == 1.0
    assert got.ci_high == pytest.approx(max(1 / calibrated(ratio).ci_low, calibrated(ratio).ci_high))


@pytest.mark.parametrize("stated", ["coverage 0.9 at n = 5", "coverage 0.90 at n = 5", "coverage 0.900 at n = 5"])
def test_an_interval_widened_to_its_nominal_coverage_is_not_widened_again(stated):
    """However many digits the helper stated its coverage with, a widened interval is at its nominal coverage: a
    second reading (a rule's, after a fold that widened first) leaves it as it is."""
    once = calibrated(Estimate(0.9, 0.05, 0.75, 1.2, 5, 0.95, f"t; {stated}"))
    assert "widened x" in once.method and calibrated(once) == once
    folded = fold_about(Estimate(0.9, 0.05, 0.75, 1.2, 5, 0.95, f"t; {stated}"))
    assert calibrated(folded) == folded


def test_an_open_end_written_to_a_record_reads_back_open():
    """JSON has no infinity: a bound's open end is written as null with its sign named beside it, and read back as
    the infinity it was (read as NaN, a certified bound re-judged from its record would read undecided)."""
    from tvtrack.results import to_jsonable

    bound = Estimate(2.0, 0.5, 1.5, math.inf, 6, 0.95, "bound")
    written = json.loads(json.dumps(to_jsonable({"part": bound, "rows": [{"measured": bound.to_dict()}]})))
    assert written["part"]["ci_high"] is None and written["part"]["infinite"] == {"ci_high": "+inf"}
    for d in (written["part"], written["rows"][0]["measured"]):
        back = as_estimate(d)
        assert (back.value, back.ci_low, back.ci_high) == (2.0, 1.5, math.inf)
    below = as_estimate(json.loads(json.dumps(to_jsonable(Estimate(-math.inf, 0.1, -math.inf, 1.0, 6)))))
    assert (below.value, below.ci_low, below.ci_high) == (-math.inf, -math.inf, 1.0)
    finite = to_jsonable(Estimate(2.0, 0.5, 1.5, 2.5, 6))
    assert "infinite" not in finite and math.isnan(as_estimate({**finite, "ci_high": None}).ci_high)


def test_a_trends_facing_allowances_are_the_first_ends_side_towards_the_last_and_the_last_ends_towards_the_first():
    """Allowances that differ on every side: the lower end's upper allowance (0.1) and the higher end's lower one
    (0.12) face each other, whichever end comes first; the far sides (0.05, 0.15) take nothing off the gap."""
    low, high = (
        Estimate(1.0, 0.05, 0.8, 1.2, 18, 0.95, "t; allowance", sampling_low=0.85, sampling_high=1.1),
        Estimate(1.4, 0.05, 1.1, 1.6, 18, 0.95, "t; allowance", sampling_low=1.22, sampling_high=1.45),
    )
    s = (1.1 - 1.0) + (1.4 - 1.22)  # the facing sampling parts: the lower end's upward, the higher end's downward
    assert ends_to_decide(low, high)[0] == pytest.approx((s / (0.4 - 0.22)) ** 2)  # 2.42, not the mean half-widths'
    assert ends_to_decide(high, low)[0] == pytest.approx((s / (0.4 - 0.22)) ** 2)


def test_a_trends_ends_that_already_touch_beyond_their_allowances_need_no_more_runs():
    """Wide allowances on the facing sides and narrow sampling parts: the intervals [0.95, 1.5] and [1.5, 2.05]
    touch, so the runs already there separate them (a factor of 1), whatever the far sides hold."""
    e0 = Estimate(1.0, 0.05, 0.95, 1.5, 18, 0.95, "t; allowance", sampling_low=0.95, sampling_high=1.05)
    e1 = Estimate(2.0, 0.05, 1.5, 2.05, 18, 0.95, "t; allowance", sampling_low=1.95, sampling_high=2.05)
    assert ends_to_decide(e0, e1) == (pytest.approx(1.0), "")


@pytest.mark.parametrize("tolerance", [0.0, 0.05])
@pytest.mark.parametrize("up", [True, False])
def test_at_the_projected_runs_a_trends_facing_ends_lie_just_the_tolerance_apart(up, tolerance):
    """The projection's meaning: shrink each end's sampling parts by 1/sqrt(f) about its value, keep its
    allowances, and the facing ends of the two intervals are then exactly ``tolerance`` apart."""
    from dataclasses import replace

    e0 = Estimate(1.0, 0.05, 0.7, 1.25, 18, 0.95, "t; allowance", sampling_low=0.8, sampling_high=1.18)
    e1 = Estimate(1.5, 0.05, 1.12, 1.9, 18, 0.95, "t; allowance", sampling_low=1.2, sampling_high=1.75)
    first, last = (e0, e1) if up else (e1, e0)
    f, why = ends_to_decide(first, last, tolerance)
    assert why == "" and f > 1.0

    def shrunk(e):
        lo, hi = e.value - (e.value - e.sampling_low) / f**0.5, e.value + (e.sampling_high - e.value) / f**0.5
        return replace(e, ci_low=lo - (e.sampling_low - e.ci_low), ci_high=hi + (e.ci_high - e.sampling_high))

    assert shrunk(e1).ci_low - shrunk(e0).ci_high == pytest.approx(tolerance)


@pytest.mark.parametrize("difference", [False, True])
def test_an_interval_widened_to_its_coverage_widens_its_sampling_part_and_keeps_its_allowances(difference):
    """Widened to nominal coverage, an interval with a resolution allowance stretches its sampling interval (the
    helper's stated coverage is its own) and adds each side's allowance back unchanged: stretched with it, the
    allowance no number of runs shrinks would grow, and the runs projected to decide with it (to never)."""
    e = Estimate(
        2.0, 0.1, 1.5, 2.6, 5, 0.95, "t; allowance; coverage 0.90 at n = 5", sampling_low=1.7, sampling_high=2.4
    )
    w = calibrated(e, difference=difference)
    f = float(w.method.split("widened x")[1].split(" ")[0])
    assert f > 1.0 and w.has_allowance
    if difference:
        lo, hi = (2.0 + f * (x - 2.0) for x in (1.7, 2.4))
    else:
        lo, hi = (2.0 * (x / 2.0) ** f for x in (1.7, 2.4))
    got = [w.sampling_low, w.sampling_high, w.sampling_low - w.ci_low, w.ci_high - w.sampling_high]
    assert got == pytest.approx([lo, hi, 0.2, 0.2], rel=2e-3)  # f is read back at three decimals
    assert runs_to_decide(w, (2.5,)) == pytest.approx(((w.sampling_high - 2.0) / (2.5 - 2.0 - 0.2)) ** 2)
    plain = calibrated(Estimate(2.0, 0.1, 1.5, 2.6, 5, 0.95, "t; coverage 0.90 at n = 5"), difference=difference)
    whole = 2.0 + f * 0.6 if difference else 2.0 * 1.3**f  # without an allowance the whole side stretches
    assert not plain.has_allowance and plain.ci_high == pytest.approx(whole, rel=2e-3)


def test_a_marker_word_other_than_plus_or_minus_inf_reads_no_infinity():
    """Only the two words :func:`tvtrack.results.to_jsonable` writes mark an open end; another leaves the null as NaN
    (undecided), never the infinity of the other sign."""
    for word in ("inf", "+Inf", "", None):
        back = as_estimate({"value": 2.0, "ci_low": 1.5, "ci_high": None, "n": 6, "infinite": {"ci_high": word}})
        assert math.isnan(back.ci_high)
    assert (
        as_estimate({"value": 2.0, "ci_low": None, "ci_high": 3.0, "infinite": {"ci_low": "-inf"}}).ci_low == -math.inf
    )
    from tvtrack.measured import record_end

    marked = {"value": 2.0, "ci_low": None, "ci_high": None, "infinite": {"ci_low": "-inf", "ci_high": "+inf"}}
    assert (record_end(marked, "ci_low"), record_end(marked, "ci_high")) == (-math.inf, math.inf)
    assert record_end({"ci_low": 1.5, "infinite": {"ci_high": "+inf"}}, "ci_low") == 1.5  # the other end's marker
    assert record_end({"ci_high": None, "infinite": {"ci_high": "inf"}}, "ci_high") is None  # not a marker word
    assert record_end({"ci_high": 3.0}, "ci_high") == 3.0 and record_end({"infinite": None}, "ci_high") is None


@pytest.mark.parametrize("tolerance", [0.0, 0.02])
@pytest.mark.parametrize("up", [True, False])
def test_a_trends_log_scale_ends_shrink_and_keep_their_allowances_on_the_log_scale(up, tolerance):
    """Two pools made on the log scale (003's thresholds): their sampling parts shrink about the log of their
    values and their allowances are factors. Shrunk so by 1/sqrt(f) at the projected f, the facing ends lie just
    ``tolerance`` apart. Read on the linear scale, the first end's upper allowance (1.5 of its 3.0) would put the
    facing ends at 2.5 and 2.45, never apart; as the factor it is (2), they reach 2.0 and 2.45."""
    from dataclasses import replace

    e0 = Estimate(1.0, 0.1, 0.8, 3.0, 18, 0.95, "t, log scale; allowance", sampling_low=0.9, sampling_high=1.5)
    e1 = Estimate(2.5, 0.1, 2.35, 3.0, 18, 0.95, "t, log scale; allowance", sampling_low=2.4, sampling_high=2.8)
    first, last = (e0, e1) if up else (e1, e0)
    f, why = ends_to_decide(first, last, tolerance)
    assert why == "" and 1.0 < f < math.inf

    def shrunk(e):
        lo = e.value * (e.sampling_low / e.value) ** f**-0.5 * (e.ci_low / e.sampling_low)
        hi = e.value * (e.sampling_high / e.value) ** f**-0.5 * (e.ci_high / e.sampling_high)
        return replace(e, ci_low=lo, ci_high=hi)

    assert shrunk(e1).ci_low - shrunk(e0).ci_high == pytest.approx(tolerance, abs=1e-9)
    linear = [replace(e, method="t; allowance") for e in (first, last)]
    never, why = ends_to_decide(*linear, tolerance)
    assert never == math.inf and "resolution of the grid" in why


def test_a_trends_log_scale_ends_within_their_allowance_factors_are_never_separated():
    """On the log scale the allowances are factors: ends whose values lie within them stay unseparated however
    many runs are added, and a value that is not positive is read on the linear scale."""
    e0 = Estimate(1.0, 0.1, 0.8, 2.4, 18, 0.95, "t, log scale; allowance", sampling_low=0.9, sampling_high=1.2)
    e1 = Estimate(2.0, 0.1, 1.5, 2.6, 18, 0.95, "t, log scale; allowance", sampling_low=1.8, sampling_high=2.2)
    f, why = ends_to_decide(e0, e1)  # at f -> inf: 1.0 x 2 = 2.0 against 2.0 x 1.5 / 1.8 = 1.67
    assert f == math.inf and "resolution of the grid" in why
    below_zero = Estimate(-0.2, 0.1, -0.5, 0.3, 18, 0.95, "t, log scale")
    plain = Estimate(0.5, 0.1, 0.1, 0.9, 18, 0.95, "t")
    assert ends_to_decide(below_zero, plain) == (pytest.approx((0.9 / 0.7) ** 2), "")


def test_ends_apart_by_a_rounding_margin_beyond_the_tolerance_give_a_huge_factor_not_an_error():
    """Ends 0.2 and 0.1 + 0.2 with a tolerance of 0.1 are 2.8e-17 apart beyond it in floating point: the factor is
    of the order of ((0.5 + 0.5) / 2.8e-17)^2, far beyond any practical number of runs (a root finder on the
    sampling scale itself returned 0 there and divided by it), and the trend reads undecided."""
    e0 = Estimate(0.2, 0.1, -0.3, 0.7, 30, 0.95, "t")
    e1 = Estimate(0.1 + 0.2, 0.1, -0.2, 0.8, 30, 0.95, "t")
    f, why = ends_to_decide(e0, e1, 0.1)
    assert why == "" and 1e32 < f < 1e34
    j = Monotone("q", "x", tolerance=0.1).judge([e0, e1])
    assert j.verdict == "undecided" and j.runs_factor == pytest.approx(f)


def test_log_scale_ends_a_rounding_step_apart_never_read_a_grid_they_were_not_read_on():
    """Two log-scale pools without allowances whose values are one floating-point step apart: no grid is involved,
    so the reason no practical number of runs separates them is never the grid's resolution; a factor, where one is
    given, is huge."""
    for v0 in (1.0, 2.719609804902451):
        v1 = float(np.nextafter(v0, 10.0))
        e0 = Estimate(
            v0, 0.1, v0 / 2, v0 * 2, 30, 0.95, "pooled over 3 independent replicates (equal weights, log scale)"
        )
        e1 = Estimate(
            v1, 0.1, v1 / 2, v1 * 2, 30, 0.95, "pooled over 3 independent replicates (equal weights, log scale)"
        )
        f, why = ends_to_decide(e0, e1)
        assert "grid" not in why and f > 1e30
        assert Monotone("q", "x").judge([e0, e1]).verdict == "undecided"


def test_a_trend_end_of_zero_events_is_projected_by_the_bound_its_runs_certify():
    """A share of zero events in 30 runs ([0, 0.095], the one-sided bound) certifies p <= 0.05 at ln(0.05) /
    ln(0.95) = 58.4 runs of zero events: the trend's ends projection towards an exact 0.05 is that, as
    runs_to_decide's for a band edge at 0.05, not a sampling part shrinking as 1/sqrt(n); all events likewise."""
    b = 1 - 0.05 ** (1 / 30)
    none = Estimate(0.0, math.nan, 0.0, b, 30, 0.95, "count over 3 replicates: 0 of 30, one-sided bound")
    edge = runs_to_decide(none, [0.05])
    assert edge == pytest.approx(math.log(0.05) / math.log(0.95) / 30)
    assert ends_to_decide(none, Estimate.exact(0.05)) == (pytest.approx(edge, rel=1e-9), "")
    every = Estimate(1.0, math.nan, 1 - b, 1.0, 30, 0.95, "count over 3 replicates: 30 of 30, one-sided bound")
    assert ends_to_decide(every, Estimate.exact(0.95)) == (pytest.approx(edge, rel=1e-9), "")


def test_a_trends_end_open_towards_the_other_is_unbounded_whatever_its_sampling_part():
    """An end whose interval is open towards the other end never separates from it, and the reason says so even
    where its sampling part is finite."""
    e0 = Estimate(1.0, 0.1, 0.8, math.inf, 30, 0.95, "t; allowance", sampling_low=0.9, sampling_high=1.1)
    e1 = Estimate(3.0, 0.1, 2.8, 3.2, 30, 0.95, "t")
    assert ends_to_decide(e0, e1) == (math.inf, "an end's interval is unbounded")


@pytest.mark.parametrize("second", [1.05, 1.25])
def test_trend_ends_not_apart_beyond_the_tolerance_say_so_even_with_allowances(second):
    """Values 1.0 and 1.05 (or exactly 1.25) against a flat tolerance of 0.25: no number of runs separates them by
    more than it, and the reason is the tolerance, not the grid their allowances come from."""
    e0 = Estimate(1.0, 0.05, 0.8, 1.2, 18, 0.95, "t; allowance", sampling_low=0.9, sampling_high=1.1)
    e1 = Estimate(
        second,
        0.05,
        second - 0.2,
        second + 0.2,
        18,
        0.95,
        "t; allowance",
        sampling_low=second - 0.1,
        sampling_high=second + 0.1,
    )
    for pair in ((e0, e1), (e1, e0)):
        assert ends_to_decide(*pair, 0.25) == (
            math.inf,
            "the ends' values are not apart by more than the flat tolerance",
        )


@pytest.mark.parametrize("lowest", [0.0, -0.1])
def test_an_interval_reaching_zero_is_projected_on_the_linear_scale_whatever_its_method_says(lowest):
    """A pool whose method says "log scale" but whose interval reaches 0 or below (its allowance below a positive
    sampling interval) has no log to shrink about: its runs to decide, for a trend's end and for a band edge, are
    the linear ones."""
    e0 = Estimate(0.5, 0.05, lowest, 0.7, 18, 0.95, "t, log scale; allowance", sampling_low=0.05, sampling_high=0.6)
    e1 = Estimate(1.0, 0.05, 0.55, 1.2, 18, 0.95, "t; allowance", sampling_low=0.7, sampling_high=1.1)
    s, d = (0.6 - 0.5) + (1.0 - 0.7), 0.5 - 0.1 - 0.15  # the facing sampling parts; the gap less the allowances
    f, why = ends_to_decide(e0, e1)
    linear = [
        Estimate(
            e.value,
            0.05,
            e.ci_low,
            e.ci_high,
            18,
            0.95,
            "t; allowance",
            sampling_low=e.sampling_low,
            sampling_high=e.sampling_high,
        )
        for e in (e0, e1)
    ]
    assert why == "" and f == pytest.approx((s / d) ** 2) and f == pytest.approx(ends_to_decide(*linear)[0])
    assert ends_to_decide(e1, e0)[0] == pytest.approx(f)  # a decreasing trend on the same ends
    below = 0.05 - lowest  # the allowance below the sampling interval
    assert runs_to_decide(e0, [0.3]) == pytest.approx(((0.5 - lowest - below) / (0.2 - below)) ** 2)  # linear


def test_a_value_that_is_not_an_estimate_is_no_envelope():
    """A part measured as a plain number, a list of points or nothing is not an envelope of certified bounds (only
    a pool's method names one), and asking never fails."""
    from tvtrack.measured import is_envelope

    for value in (2.0, [Estimate(1.0, 0.1, 0.8, 1.2, 10)], None, {"value": 1.0}):
        assert is_envelope(value) is False
    assert is_envelope(Estimate(1.0, 0.1, 0.8, 1.2, 10, 0.95, "envelope of 3 replicates' intervals")) is True


def test_a_record_whose_method_is_null_projects_its_runs_on_the_linear_scale():
    """A record may hold ``"method": null``: read back, its runs to decide a band edge or a trend are the linear
    ones, and reading it never fails."""
    e = as_estimate({"value": 1.0, "ci_low": 0.6, "ci_high": 1.4, "n": 20, "method": None})
    assert e.method is None
    assert runs_to_decide(e, [1.2]) == pytest.approx((0.4 / 0.2) ** 2)
    assert ends_to_decide(e, Estimate.exact(1.6)) == (1.0, "")  # already apart
    assert ends_to_decide(e, Estimate.exact(1.3))[0] == pytest.approx((0.4 / 0.3) ** 2)
