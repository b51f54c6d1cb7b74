"""Paper 003: the direct-count estimators every interference value passes through (estimators.py), written out.

A loss share is a count with its Clopper-Pearson interval (zero or all events: the one-sided bound they certify); a
run's log threshold is the middle of the grid step where it broke; a threshold is the geometric mean of the runs'
with a Student t interval widened by half the widest step; one-sided censoring certifies a bound; a ratio of two
curves' thresholds is paired run by run; the grid is extended while a curve breaks outside it. Each is computed here
from its definition on hand-written runs on a grid whose steps all differ (so a step read at the wrong index shows),
with loss indicators given as 0/1 numbers as well as truth values.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy import stats

from tvtrack.montecarlo import ratio_ci
from tvtrack.papers.p003_rotating_marker_tracker import estimators as est
from tvtrack.papers.p003_rotating_marker_tracker.curves import SIR_GRID

GRID = [1, 2, 3, 6, 15]  # log steps ln 2, ln 1.5, ln 2, ln 2.5: each its own (an integer grid, as a list)
LS = np.log(np.array(GRID, float))
H = np.log(2.5) / 2  # half the widest step


def runs(*rows, ints=False):
    """Loss indicators (SIR, run) from one string per run: 'L' lost, '.' in lock, along the grid."""
    L = np.array([[c == "L" for c in r] for r in rows]).T
    return L.astype(int).tolist() if ints else L


def half_steps(*rows, bound=""):
    """Half the log width of the grid step each run (a string as :func:`runs`) is read in, counted by hand: a run
    lost at its first k SIRs broke between SIRs k-1 and k (kept lock at the bottom: the first step; lost at the top:
    the last); 0 for a run whose side ``bound`` says is a bound ("bottom": kept lock at the bottom, "top": lost at
    the top)."""
    out = []
    for r in rows:
        k = len(r) - len(r.lstrip("L"))
        if (bound == "bottom" and r[0] == ".") or (bound == "top" and r[-1] == "L"):
            out.append(0.0)
        else:
            k = min(max(k, 1), len(r) - 1)
            out.append((LS[k] - LS[k - 1]) / 2)
    return np.array(out)


def t_interval(x):
    x = np.asarray(x, float)
    m, se = x.mean(), x.std(ddof=1) / np.sqrt(x.size)
    half = stats.t.ppf(0.975, x.size - 1) * se
    return m, m - half, m + half


def fields(e):
    return dataclasses.astuple(e)


def test_an_interval_estimate_has_no_standard_error_and_95_percent():
    e = est.interval_estimate(np.float64(2.5), 1, 4, np.int64(7), "how", extrapolated=np.bool_(True))
    assert fields(e)[:1] + fields(e)[2:8] == (2.5, 1, 4, 7, 0.95, "how", True) and np.isnan(e.stderr)
    assert type(e.value) is float and type(e.n) is int and type(e.extrapolated) is bool
    assert est.interval_estimate(1, 0, 2, 3, "m").extrapolated is False and not e.has_allowance
    s = est.interval_estimate(2.5, 1, 4, 7, "grid", sampling=(np.float64(2.0), 3))
    assert (s.sampling_low, s.sampling_high) == (2.0, 3.0) and type(s.sampling_high) is float and s.has_allowance


def test_a_threshold_carries_its_t_interval_as_its_sampling_interval_and_the_half_step_beside_it():
    """Six runs that broke at grid steps 2, 2, 3, 3, 3 and 4 of a grid of step 1.5: the threshold's sampling
    interval is exp of the t interval of their log thresholds, and its interval that widened by half a step."""
    sirs = 1.5 ** np.arange(8)
    steps = np.array([2, 2, 3, 3, 3, 4])
    lost = np.arange(8)[:, None] < steps[None, :]
    tau = np.log(sirs[steps]) - np.log(1.5) / 2  # each run half a step below the first SIR it kept lock at
    m, h = tau.mean(), math.log(1.5) / 2
    half = stats.t.ppf(0.975, 5) * tau.std(ddof=1) / math.sqrt(6)
    e = est.threshold(lost, sirs)
    assert (e.sampling_low, e.sampling_high) == pytest.approx((math.exp(m - half), math.exp(m + half)))
    assert (e.ci_low, e.ci_high) == pytest.approx((math.exp(m - half - h), math.exp(m + half + h)))


def test_a_loss_share_is_the_count_with_clopper_pearson_and_the_zero_event_bounds():
    b = 1 - 0.05 ** (1 / 8)
    none, every = est.loss_share(np.zeros(8, bool)), est.loss_share(np.ones((2, 4), bool))
    assert (none.value, none.ci_low, none.ci_high, none.n) == (0.0, 0.0, pytest.approx(b), 8)
    assert (every.value, every.ci_low, every.ci_high, every.n) == (1.0, pytest.approx(1 - b), 1.0, 8)
    assert none.method == "count: zero events, one-sided 95 % bound"
    assert every.method == "count: all events, one-sided 95 % bound"
    some = est.loss_share([1, 0, 0, 1, 0, 0, 0, 0])
    lo, hi = stats.binomtest(2, 8).proportion_ci(0.95, method="exact")
    assert (some.value, some.ci_low, some.ci_high, some.n) == (0.25, pytest.approx(lo), pytest.approx(hi), 8)


@pytest.mark.parametrize("ints", [False, True])
def test_each_runs_log_threshold_is_the_middle_of_the_grid_step_where_it_broke(ints):
    L = runs("LL...", ".....", "LLLLL", "L.L..", "L....", "LLLL.", "LLL..", ints=ints)
    tau, cens = est.log_thresholds(L, GRID)
    want = [
        (np.log(2) + np.log(3)) / 2,  # lost at 1 and 2, in lock from 3
        -np.log(2) / 2,  # in lock at the bottom: half the first step below it
        np.log(15) - np.log(2.5) / 2,  # lost at the top: half the last step below it
        np.log(4) - np.log(1.5) / 2,  # non-monotone: ln 1 + ln 2 + ln 2 climbed, minus half the step below
        np.log(2) / 2,
        (np.log(6) + np.log(15)) / 2,  # broke in the last step
        (np.log(3) + np.log(6)) / 2,
    ]
    np.testing.assert_allclose(tau, want, rtol=1e-12, atol=1e-15)
    assert cens.tolist() == [False, True, True, False, False, False, False]


def test_a_threshold_is_the_geometric_mean_with_a_t_interval_widened_by_half_the_widest_step():
    L = runs("LL...", "L....", "LLL..", "LLLL.", "L....")
    tau = np.array([np.log(6) / 2, np.log(2) / 2, np.log(18) / 2, np.log(90) / 2, np.log(2) / 2])
    m, lo, hi = t_interval(tau)
    got = est.threshold(L, GRID)
    assert (got.value, got.ci_low, got.ci_high) == pytest.approx((np.exp(m), np.exp(lo - H), np.exp(hi + H)))
    assert got.n == 5 and got.extrapolated is False and np.isnan(got.stderr)
    assert got.method == "geometric mean of per-run breaking SIRs (grid-censored), t interval + half a grid step"
    assert est.threshold(runs("LL...", "....."), GRID).extrapolated is True
    same = est.threshold_bound(runs("LL...", "L....", "LLL..", "LLLL.", "L....", ints=True), GRID)
    np.testing.assert_equal(fields(same), fields(got))  # no run broke outside the grid: the threshold itself


def test_a_threshold_censored_on_one_side_certifies_a_bound_on_the_other():
    below = runs("LL...", ".....", "LLL..", "LLLL.", ints=True)  # one run kept lock at the bottom: broke below 1
    tau = np.array([np.log(6) / 2, LS[0], np.log(18) / 2, np.log(90) / 2])  # that run at the grid's bottom
    got = est.threshold_bound(below, GRID)
    assert (got.value, got.ci_low) == (est.threshold(below, GRID).value, 0.0) and got.extrapolated is False
    assert got.ci_high == pytest.approx(np.exp(t_interval(tau)[2] + H))
    assert got.method == (
        "bound certified by the censoring: 1 run(s) broke below the grid, 0 above it; t bound + half a grid step"
    )
    above = runs("LL...", "LLLLL", "LLLLL", "LLLL.", "L....", ints=True)  # two runs lost at the top: above 15
    tau = np.array([np.log(6) / 2, LS[-1], LS[-1], np.log(90) / 2, np.log(2) / 2])
    got = est.threshold_bound(above, GRID)
    assert (got.ci_low, got.ci_high) == (pytest.approx(np.exp(t_interval(tau)[1] - H)), np.inf)
    assert "0 run(s) broke below the grid, 2 above it" in got.method and got.extrapolated is False
    both = est.threshold_bound(runs("LL...", ".....", "LLLLL"), GRID)
    assert (both.ci_low, both.ci_high, both.extrapolated) == (0.0, np.inf, True)


def test_a_threshold_ratio_pairs_the_runs_and_is_extrapolated_where_either_curve_is_censored():
    a, b = runs("LL...", "L....", "LLL..", "LLLL."), runs("L....", "L....", "LL...", "LLL..")
    ta, _ = est.log_thresholds(a, GRID)
    tb, _ = est.log_thresholds(b, GRID)
    m, lo, hi = t_interval(ta - tb)
    got = est.threshold_ratio(np.array(a).astype(int), np.array(b).astype(int), GRID)
    # each curve's runs are read to within half their own step: the ratio to within the mean of the two halves' sum
    h = np.mean(half_steps("LL...", "L....", "LLL..", "LLLL.") + half_steps("L....", "L....", "LL...", "LLL.."))
    assert h == pytest.approx((2 * np.log(1.5) + 5 * np.log(2) + np.log(2.5)) / 8)  # a: 1.5 2 2 2.5; b: 2 2 1.5 2
    assert (got.value, got.ci_low, got.ci_high) == pytest.approx((np.exp(m), np.exp(lo - h), np.exp(hi + h)))
    assert (got.sampling_low, got.sampling_high) == pytest.approx((np.exp(lo), np.exp(hi)))  # the steps beside it
    assert got.extrapolated is False and got.n == 4
    assert got.method == "paired ratio of geometric-mean thresholds, t interval + the runs' grid steps"
    both = runs(".....", "LLLLL", "LL...", "L....")  # censored at both ends: no bound either way
    assert est.threshold_ratio(both, b, GRID).extrapolated is True
    assert est.threshold_ratio(a, both, GRID).extrapolated is True


def _bounded(a, b, lower):
    """The bound of a ratio whose censored runs sit at the grid's edges: a's below the bottom, b's above the top
    (``lower``: a's above the top, b's below the bottom)."""
    La, Lb = np.asarray(a, bool), np.asarray(b, bool)
    ta, _ = est.log_thresholds(La, GRID)
    tb, _ = est.log_thresholds(Lb, GRID)
    if lower:
        d = np.where(La[-1], LS[-1], ta) - np.where(~Lb[0], LS[0], tb)
    else:
        d = np.where(~La[0], LS[0], ta) - np.where(Lb[-1], LS[-1], tb)
    return t_interval(d)


@pytest.mark.parametrize(
    "a, b, counts",
    [
        ((".....", "LLLL.", "LL...", "L...."), ("LLLLL", "LL...", "LLLL.", "LLLLL"), (1, 2)),  # both censored
        (("LLLL.", "LL...", "L...."), ("LLLLL", "LLLL.", "LLL.."), (0, 1)),  # only b censored
    ],
)
def test_a_ratio_whose_censoring_certifies_a_side_is_a_bound(a, b, counts):
    got = est.threshold_ratio(runs(*a, ints=True), runs(*b, ints=True), GRID)
    m, lo, hi = _bounded(runs(*a), runs(*b), lower=False)
    h = np.mean(half_steps(*a, bound="bottom") + half_steps(*b, bound="top"))  # a bound at an edge reads no error
    assert 0 < h < 2 * H
    assert (got.value, got.ci_low, got.ci_high) == pytest.approx((np.exp(m), 0.0, np.exp(hi + h)))
    assert got.method == (
        f"upper bound: {counts[0]} run(s) of the first curve kept lock at the grid's bottom, {counts[1]} of the second "
        "lost it at its top; paired t bound + the runs' grid steps"
    )
    got = est.threshold_ratio(runs(*b, ints=True), runs(*a, ints=True), GRID)  # the mirror: a lower bound
    m, lo, hi = _bounded(runs(*b), runs(*a), lower=True)
    h = np.mean(half_steps(*b, bound="top") + half_steps(*a, bound="bottom"))
    assert (got.value, got.ci_low, got.ci_high) == pytest.approx((np.exp(m), np.exp(lo - h), np.inf))
    assert got.method.startswith(
        f"lower bound: {counts[1]} run(s) of the first curve lost lock at the grid's top, {counts[0]} of the second"
    )


def test_the_bounds_read_the_bottom_and_top_sirs_only():
    a, b = runs(".....", "LLLL.", "LL..."), runs("LLLLL", "L....", "LLL..")  # b in lock at its second SIR once
    up, down = est.threshold_ratio(a, b, GRID), est.threshold_ratio(b, a, GRID)
    assert (up.ci_low, down.ci_high) == (0.0, np.inf) and up.method.startswith("upper bound: 1 run(s)")
    assert down.method.startswith("lower bound: 1 run(s)") and not (up.extrapolated or down.extrapolated)


def test_the_grid_is_extended_a_step_below_or_above_while_a_curve_breaks_outside_it():
    calls = []
    rows = {("A", 1 / 1.5): [0, 1], ("A", 1 / 2.25): [1, 1], ("B", 22.5): [1, 0], ("B", 33.75): [0, 0]}

    def run(keys, sir):
        calls.append((sorted(keys), round(sir, 9)))
        return {k: rows[next(x for x in rows if x[0] == k and abs(x[1] - sir) < 1e-9)] for k in keys}

    curves = {"A": runs("LL...", ".LLL.", ints=True), "B": runs("LLLLL", "LLL..", ints=True)}
    curves["C"] = runs("LL...", "LLL..", ints=True)
    sirs, out = est.extend_grid(curves, GRID, run)  # a step of 1.5, two points a side by default
    np.testing.assert_allclose(sirs, [1 / 2.25, 1 / 1.5, *GRID, 22.5, 33.75])
    assert calls == [(["A"], round(1 / 1.5, 9)), (["A"], round(1 / 2.25, 9)), (["B"], 22.5), (["B"], 33.75)]
    assert {k: v.dtype for k, v in out.items()} == dict.fromkeys("ABC", np.dtype(bool))
    np.testing.assert_array_equal(out["A"][:2], [[True, True], [False, True]])
    np.testing.assert_array_equal(out["B"][:2], [[True, True], [True, True]])  # lost below its old bottom
    np.testing.assert_array_equal(out["C"][-2:], [[False, False], [False, False]])  # in lock above its old top
    np.testing.assert_array_equal(out["B"][-2:], [[True, False], [False, False]])
    np.testing.assert_array_equal(out["A"][2:-2], np.array(curves["A"], bool))
    calls.clear()
    rows[("A", 1 / 2.25)] = [0, 1]  # still in lock at the second point below: no third point by default
    sirs, _ = est.extend_grid({"A": curves["A"]}, GRID, run)
    assert len(calls) == 2 and len(sirs) == 7
    calls.clear()
    sirs, out = est.extend_grid(curves, GRID, run, step=1.5, max_points=1, trigger=["B"])
    assert calls == [(["B"], 22.5)] and list(sirs) == [*GRID, 22.5]  # A's bottom is not a trigger's
    assert est.extend_grid({"C": curves["C"]}, GRID, run)[0].tolist() == GRID  # nothing outside: as it was


def test_a_paired_share_difference_is_t_on_the_runs_or_the_zero_event_bound_without_discordant_runs():
    a = np.array([1, 1, 0, 1, 0, 1], bool)
    b = np.array([0, 1, 0, 0, 0, 0], bool)
    m, lo, hi = t_interval(a.astype(float) - b)
    got = est.share_difference(a, b)
    assert (got.value, got.ci_low, got.ci_high, got.n) == (pytest.approx(m), pytest.approx(lo), 1.0, 6)  # hi clipped
    assert got.method == "paired t on per-run differences" and hi > 1
    low = est.share_difference(b, a)
    assert (low.ci_low, low.ci_high) == (-1.0, pytest.approx(-lo))  # clipped at -1
    bnd = 1 - 0.05 ** (1 / 6)
    same = est.share_difference(a, a)
    assert (same.value, same.ci_low, same.ci_high) == (0.0, pytest.approx(-bnd), pytest.approx(bnd))
    assert same.method == "every run the same difference: the zero-events bound on the others, one-sided 95 %"
    # every run +1: the runs not +1 are zero events (share <= bnd), and the worst case puts them all at -1, so the
    # difference is only certified >= 1 - 2 bnd
    every = est.share_difference(np.ones(6, bool), np.zeros(6, bool))
    assert (every.value, every.ci_low, every.ci_high) == (1.0, pytest.approx(1 - 2 * bnd), 1.0)
    none = est.share_difference(np.zeros(6, bool), np.ones(6, bool))  # every run lost lock in b only
    assert (none.value, none.ci_low, none.ci_high) == (-1.0, -1.0, pytest.approx(-1 + 2 * bnd))  # a share's floor
    one = est.share_difference(np.ones(1, bool), np.zeros(1, bool))  # one run: 1 - 2 x 0.95
    assert (one.value, one.ci_low, one.ci_high, one.n) == (1.0, pytest.approx(-0.9), 1.0, 1)


@pytest.mark.parametrize("n", [1, 3, 6, 30])
def test_the_all_discordant_bound_covers_the_worst_case_it_cannot_tell_apart(n):
    """Runs are +1 with probability 1 - b and -1 with probability b (b = 1 - 0.05^(1/n)): every run is +1 with
    probability exactly 0.05, and the true difference is 1 - 2b. A 95 % interval from that outcome must reach it."""
    b = 1 - 0.05 ** (1 / n)
    assert (1 - b) ** n == pytest.approx(0.05)
    got = est.share_difference(np.ones(n, bool), np.zeros(n, bool))
    assert got.ci_low <= 1 - 2 * b + 1e-12 <= got.ci_high


def test_the_compensation_factor_is_kappa_times_the_compensated_threshold_over_the_uncompensated():
    comp = runs("LL...", "L....", "LLL..", "LL...")
    unc = runs("LL...", "LLLL.", "L....", "LL...")  # lost up to the top's neighbour, never at the top
    usirs = [2 * x for x in GRID]
    c, u = est.threshold(comp, GRID), est.threshold(unc, usirs)
    got = est.compensation_factor(unc, usirs, comp, GRID, 10.0)
    assert (got.value, got.ci_low, got.ci_high) == pytest.approx(
        (10 * c.value / u.value, 10 * c.ci_low / u.ci_high, 10 * c.ci_high / u.ci_low)
    )
    assert got.n == 4 and got.extrapolated is False and got.method == "ratio of thresholds, interval from their bounds"
    assert est.compensation_factor(runs(".....", "LL...", "L....", "L...."), GRID, comp, GRID, 10.0).extrapolated
    top = runs("LLLLL", "LL...", "LLLL.", "L....")  # one uncompensated run lost even at the grid's top
    got = est.compensation_factor(top, usirs, comp, GRID, 10.0)
    assert (got.value, got.ci_low, got.ci_high, got.n) == (0.0, 0.0, pytest.approx(10 * c.ci_high / 30.0), 4)
    assert got.method == "1 of 4 uncompensated runs lost even at SIR_0 30: bound from the grid's top"
    assert est.compensation_factor(top, GRID, runs("LL...", "....."), GRID, 10.0).extrapolated is True


def test_a_trend_in_lock_reads_each_point_on_its_runs_in_lock_and_says_why_it_is_not_read():
    n = 10
    lost = np.zeros((3, n), bool)
    lost[0, :1] = True  # one run of ten lost: the limit itself, still read
    lost[1, :2] = True  # two of ten: above the limit, left out
    lost[2, 5:] = True
    ripple, control = np.arange(1.0, 31.0).reshape(3, n), np.full((3, n), 2.0)
    got = est.grid_in_lock(lost, ripple, control, (2.0, 5.0, 10.0), (10.0, 2.0), limit=0.5)
    assert got["read"] == [2.0, 5.0, 10.0] and len(got["trend"]) == 3
    got = est.grid_in_lock(lost, ripple, control, (2.0, 5.0, 10.0), (10.0, 2.0))
    assert got["read"] == [2.0] and len(got["trend"]) == 2  # one point in lock: two points not read
    for e in got["trend"]:
        assert fields(e)[4:8] == (n, 0.95, "fewer than two grid points keep lock", False) and type(e.n) is int
        assert all(np.isnan(fields(e)[:4]))
    assert np.isnan(got["pair"].value) and got["pair"].method == "the tracker lost lock at one of the two bandwidths"
    assert all(np.isnan(fields(got["pair"])[:4])) and fields(got["pair"])[4:6] == (n, 0.95)
    assert [e.value for e in got["lost"].values()] == [0.1, 0.2, 0.5] and list(got["lost"]) == ["2 Hz", "5 Hz", "10 Hz"]
    pair = np.zeros((2, 4), bool)
    pair[0, :2], pair[1, 2:] = True, True  # in lock at both points in no run; each point alone in two
    got = est.grid_in_lock(pair.astype(int), np.ones((2, 4)), np.ones((2, 4)), (5.0, 20.0), (20.0, 5.0), limit=0.5)
    assert got["read"] == [5.0, 20.0] and np.isnan(got["pair"].value)
    pair[1, 2:] = False  # two runs in lock at both: the pair is read on them
    r = np.arange(1.0, 9.0).reshape(2, 4)
    got = est.grid_in_lock(pair.astype(int), r, np.ones((2, 4)), (5.0, 20.0), (20.0, 5.0), limit=0.5)
    want = ratio_ci(r[1][2:], r[0][2:])
    assert (got["pair"].value, got["pair"].ci_low, got["pair"].ci_high) == (want.value, want.ci_low, want.ci_high)


def _lost(thresholds, sirs):
    """Loss of lock at each SIR of ``sirs`` for runs breaking at ``thresholds`` (lost below, kept from it on)."""
    return np.asarray(sirs, float)[:, None] < np.asarray(thresholds, float)[None, :]


def test_a_threshold_ratio_covers_paired_runs_that_break_within_one_step_wherever_they_sit_in_it():
    """Six runs of each curve breaking at one place within the same grid step read the same midpoint, so the ratio
    reads 1 whatever their true ratio, up to a whole step away: its allowance is that step, not half of the widest
    (with half, the pair high and low in the step was missed); and it is that step, not the widest one."""
    sirs = np.array(SIR_GRID)
    ls = np.log(sirs)
    for i in range(sirs.size - 1):
        step = ls[i + 1] - ls[i]
        for fa, fb in [(0.98, 0.02), (0.02, 0.98), (0.7, 0.3), (0.5, 0.5)]:
            ta, tb = np.exp(ls[i] + fa * step), np.exp(ls[i] + fb * step)
            got = est.threshold_ratio(_lost([ta] * 6, sirs), _lost([tb] * 6, sirs), sirs)
            assert got.value == pytest.approx(1.0) and not got.extrapolated
            assert got.ci_low <= ta / tb <= got.ci_high, (i, fa, fb, got.ci_low, ta / tb, got.ci_high)
            assert (got.ci_low, got.ci_high) == pytest.approx((np.exp(-step), np.exp(step)))  # this step, no wider


def test_a_threshold_ratio_of_six_paired_runs_covers_at_least_as_stated_where_runs_scatter_less_than_a_step():
    """Coverage of the paired ratio at 003's six runs a replicate on its own grid, runs' log thresholds scattered
    by 0.02 (normal, independent between the curves), the place in the grid and the true ratio (within +-0.3 on the
    log scale) at random: 400 seeded experiments. With half a step it covered 0.87 (4,000 experiments)."""
    rng = np.random.default_rng(3)
    sirs = np.array(SIR_GRID)
    ls = np.log(sirs)
    hits = 0
    for _ in range(400):
        mu, d = rng.uniform(ls[2], ls[-3]), rng.uniform(-0.3, 0.3)
        ta = np.exp(mu + d / 2 + 0.02 * rng.standard_normal(6))
        tb = np.exp(mu - d / 2 + 0.02 * rng.standard_normal(6))
        got = est.threshold_ratio(_lost(ta, sirs), _lost(tb, sirs), sirs)
        hits += got.ci_low <= np.exp(d) <= got.ci_high
    assert hits / 400 >= 0.95
