"""Paper 002: the statistics every claim value passes through, pinned on their intervals as well as their values.

A claim's verdict reads the interval as much as the value: a ratio scaled at one end only, a log interval mapped
back with the wrong end, or a fold change that forgets to start at 1 when the ratio's interval holds 1 would move a
verdict while every value stays right. Each case below has its answer in closed form or from the core's own
estimators, computed independently here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tvtrack.measured import calibrated
from tvtrack.estimate import Estimate
from tvtrack.papers.p002_unified_location_em.summaries import mse_sum, variance_ratio_ci, variance_sum
from tvtrack.papers.p002_unified_location_em import claim_values as cv


def _estimate(value=2.0, stderr=0.25, low=1.5, high=2.6, n=40, method="test") -> Estimate:
    return Estimate(value, stderr, low, high, n, 0.95, method)


def test_a_scaled_estimate_scales_its_value_error_and_both_ends_and_keeps_the_rest():
    e = _estimate()
    s = cv.scaled(e, 0.5)
    assert (s.value, s.stderr, s.ci_low, s.ci_high) == (1.0, 0.125, 0.75, 1.3)
    assert (s.n, s.confidence, s.method) == (40, 0.95, "test")


def test_efficiency_is_the_spread_over_the_bound_interval_and_all():
    e = np.random.default_rng(3).standard_normal((60, 4)) * 1.3
    v = variance_sum(e)
    eff = cv.efficiency(e, 2.0, "variance")
    assert eff.value == pytest.approx(v.value / 2.0, rel=1e-12)
    assert (eff.ci_low, eff.ci_high) == pytest.approx((v.ci_low / 2.0, v.ci_high / 2.0), rel=1e-12)
    m = cv.efficiency(e, 2.0, "MSE")
    assert m.value == pytest.approx(mse_sum(e).value / 2.0, rel=1e-12) and m.value != eff.value


def test_exp_estimate_maps_a_log_interval_end_by_end():
    e = Estimate(math.log(3.0), 0.1, math.log(2.0), math.log(4.5), 12, 0.95, "log")
    x = cv.exp_estimate(e)
    assert (x.value, x.ci_low, x.ci_high) == pytest.approx((3.0, 2.0, 4.5), rel=1e-12)
    assert x.stderr == pytest.approx(0.3, rel=1e-12)  # delta method: exp(m) * se
    assert (x.n, x.confidence, x.method) == (12, 0.95, "log")


def test_the_spread_read_is_the_one_named():
    e = np.random.default_rng(5).standard_normal((80, 2)) + 0.7  # a bias: the MSE sum exceeds the variance sum
    assert cv.spread_sum(e).value == pytest.approx(variance_sum(e).value, rel=1e-12)
    assert cv.spread_sum(e, "MSE").value == pytest.approx(mse_sum(e).value, rel=1e-12)
    assert cv.spread_sum(e, "MSE").value > cv.spread_sum(e).value
    trimmed = cv.spread_sum(e, "trimmed")
    assert trimmed.value < cv.spread_sum(e).value and trimmed.ci_low < trimmed.value < trimmed.ci_high
    rows = np.stack([e, 2 * e])
    assert cv.spread_total(rows) == pytest.approx(e.var(axis=0, ddof=1).sum() * np.array([1.0, 4.0]), rel=1e-12)
    assert cv.spread_total(rows, "mse") == pytest.approx((e**2).mean(axis=0).sum() * np.array([1.0, 4.0]), rel=1e-12)


@pytest.mark.parametrize("statistic", ["variance", "MSE", "SD ratio"])
def test_a_gain_is_the_cores_variance_ratio_with_the_spread_and_root_named(statistic):
    rng = np.random.default_rng(8)
    den = rng.standard_normal((50, 2))
    num = 1.5 * rng.standard_normal((50, 2)) + 0.2
    g = cv.gain(num, den, np.random.default_rng(1), 300, statistic)
    spread = "mse" if statistic == "MSE" else "variance"
    ref = variance_ratio_ci(
        num, den, np.random.default_rng(1), 300, paired=True, spread=spread, sqrt=statistic == "SD ratio"
    )
    assert (g.value, g.ci_low, g.ci_high) == (ref.value, ref.ci_low, ref.ci_high)
    unpaired = cv.gain(num, den, np.random.default_rng(1), 300, statistic, paired=False)
    ref_u = variance_ratio_ci(
        num, den, np.random.default_rng(1), 300, paired=False, spread=spread, sqrt=statistic == "SD ratio"
    )
    assert (unpaired.ci_low, unpaired.ci_high) == (ref_u.ci_low, ref_u.ci_high)
    if statistic == "SD ratio":
        assert g.value == pytest.approx(math.sqrt(cv.gain(num, den, np.random.default_rng(1), 300).value), rel=1e-12)


def test_a_fold_change_of_a_ratio_above_one_is_the_ratio():
    e = _estimate(2.0, 0.25, 1.5, 2.6)
    c = calibrated(e)
    f = cv.fold_change(e)
    assert (f.value, f.stderr, f.ci_low, f.ci_high) == pytest.approx((c.value, c.stderr, c.ci_low, c.ci_high))
    assert (f.n, f.confidence) == (40, 0.95) and "max(q, 1/q)" in f.method


def test_a_fold_change_below_one_inverts_the_ratio_and_swaps_its_ends():
    e = _estimate(0.5, 0.05, 0.4, 0.625)
    c = calibrated(e)
    f = cv.fold_change(e)
    assert f.value == pytest.approx(1.0 / c.value)
    assert f.stderr == pytest.approx(c.stderr / c.value**2)  # delta method for 1 / q
    assert (f.ci_low, f.ci_high) == pytest.approx((1.0 / c.ci_high, 1.0 / c.ci_low))


def test_a_fold_change_whose_ratio_interval_holds_one_starts_at_one():
    e = _estimate(1.2, 0.3, 0.8, 1.9)
    c = calibrated(e)
    f = cv.fold_change(e)
    assert f.ci_low == 1.0 and f.ci_high == pytest.approx(max(c.ci_high, 1.0 / c.ci_low))
    below = cv.fold_change(_estimate(0.9, 0.2, 0.6, 1.3))
    cb = calibrated(_estimate(0.9, 0.2, 0.6, 1.3))
    assert below.value == pytest.approx(1.0 / cb.value) and below.ci_low == 1.0
    assert below.ci_high == pytest.approx(max(1.0 / cb.ci_low, cb.ci_high))


def test_a_fold_change_of_a_ratio_whose_interval_reaches_zero_is_unbounded_above():
    f = cv.fold_change(_estimate(0.5, 0.2, 0.0, 0.9))
    assert f.ci_high == np.inf and f.ci_low == pytest.approx(1.0 / calibrated(_estimate(0.5, 0.2, 0.0, 0.9)).ci_high)


def test_a_fold_change_between_one_and_two_keeps_the_ratios_error_and_one_below_inverts_it_by_the_delta_method():
    e = _estimate(1.5, 0.2, 1.2, 1.9)
    assert cv.fold_change(e).stderr == pytest.approx(calibrated(e).stderr)
    low = _estimate(0.4, 0.05, 0.3, 0.55)
    c = calibrated(low)
    assert cv.fold_change(low).stderr == pytest.approx(c.stderr / c.value**2)
    flagged = Estimate(0.4, 0.05, 0.3, 0.55, 40, 0.95, "test", True)
    assert cv.fold_change(flagged).extrapolated is True and cv.fold_change(low).extrapolated is False


def test_the_trimmed_spread_is_the_seeded_bootstrap_of_the_trimmed_variance():
    from tvtrack.papers.p002_unified_location_em.sim_config import seed_sequence
    from tvtrack.papers.p002_unified_location_em.summaries import SPREADS, bootstrap_groups

    e = np.random.default_rng(6).standard_normal((50, 2)).astype(np.float32)  # read as float64, as a scene's errors
    e64 = e.astype(float)
    ref = bootstrap_groups(
        [e64], SPREADS["trimmed_variance"], np.random.default_rng(seed_sequence(0, ("trimmed spread",))), 2000
    )
    t = cv.spread_sum(e, "trimmed")
    assert (t.value, t.ci_low, t.ci_high, t.n) == pytest.approx((ref.value, ref.ci_low, ref.ci_high, ref.n), rel=1e-12)
    assert t.value == pytest.approx(float(SPREADS["trimmed_variance"](e64[None])[0]), rel=1e-12)


def _halves(rng, n, scale_few, scale_more):
    """A group: errors at the fewer frames (2 coordinates, scale ``scale_few``) beside those at the more frames."""
    return np.concatenate([scale_few * rng.standard_normal((n, 2)), scale_more * rng.standard_normal((n, 2))], axis=1)


def _dependence(a, gap):
    """|ln(u / v)| (or |u - v|) of a group's two halves, u and v their summed variances over the trials (ddof 1)."""
    h = a.shape[-1] // 2
    u, v = a[..., :h].var(axis=-2, ddof=1).sum(axis=-1), a[..., h:].var(axis=-2, ddof=1).sum(axis=-1)
    return np.abs(u - v) if gap else np.abs(np.log(u / v))


@pytest.mark.parametrize("gap", [False, True])
def test_the_frame_dependence_contrast_is_the_hi_groups_mean_dependence_minus_the_lo_groups(gap):
    from tvtrack.papers.p002_unified_location_em.summaries import bootstrap_groups

    rng = np.random.default_rng(12)
    hi = [_halves(rng, 30, 2.0, 1.0), _halves(rng, 30, 3.0, 1.0)]  # the spread falls with the frames
    lo = [_halves(rng, 30, 1.1, 1.0), _halves(rng, 30, 1.0, 1.2)]
    value = np.mean([_dependence(a, gap) for a in hi]) - np.mean([_dependence(a, gap) for a in lo])
    got = cv.frame_dependence(hi, lo, np.random.default_rng(2), 400, gap=gap)
    assert got.value == pytest.approx(value, rel=1e-9) and got.value > 0

    def stat(*gr):
        return np.mean([_dependence(a, gap) for a in gr[:2]], axis=0) - np.mean(
            [_dependence(a, gap) for a in gr[2:]], axis=0
        )

    ref = bootstrap_groups(hi + lo, stat, np.random.default_rng(2), 400)
    if gap:  # the absolute contrast is the bootstrap's own interval
        assert (got.ci_low, got.ci_high) == pytest.approx((ref.ci_low, ref.ci_high), rel=1e-9)
    else:  # the relative one states its measured coverage, widening the same bootstrap's interval if anything
        assert got.ci_low <= ref.ci_low + 1e-12 and got.ci_high >= ref.ci_high - 1e-12


def _default_points():
    from tvtrack.papers.p002_unified_location_em import study
    from tvtrack.papers.p002_unified_location_em.register import REGISTER

    config = REGISTER.default()
    g, _ = study._points(config, study.Scale())
    return config, g, list(study.Scale().separations)


@pytest.mark.parametrize(
    "cid, letters, narrower",
    [
        ("C002-7", "ue", True),
        ("C002-8", "ue", True),
        ("C002-11", "ue", False),  # its points hold the ULA and the marks only at the default
        ("C002-13", "p", True),
        ("C002-14", "pq", True),
        ("C002-2", None, False),
    ],
)
def test_a_claim_asked_alone_runs_the_algorithms_it_reads_and_no_other(cid, letters, narrower):
    """The algorithms a measurement of one claim runs at each of its points: the letters the claim reads where it
    reads fewer than the point holds (C002-7 and -8 the ULA and the iterative marks, C002-13 plain EM, C002-14 plain
    EM and its marks, C002-11 the ULA with the marks), else every letter of the point; a point none of whose letters
    it reads is left out, and every point it reads is there."""
    config, g, D = _default_points()
    points = cv.NEEDS[cid](config, g, D)
    got = cv.needed_letters(config, g, D, claims=[cid])
    want = {p: "".join(a for a in p.algs if letters is None or a in letters) for p in points}
    assert got == {p: s for p, s in want.items() if s}
    assert list(got) == list(dict.fromkeys(p for p in points if want[p]))
    assert all(got.values()) and got  # the claim reads something at every point kept
    assert any(set(p.algs) - set(letters or p.algs) for p in points) == narrower  # points hold more than it reads


def test_every_claim_asked_together_runs_the_union_of_their_algorithms_in_each_points_order():
    config, g, D = _default_points()
    every = cv.needed_letters(config, g, D)
    alone = [cv.needed_letters(config, g, D, claims=[c]) for c in cv.NEEDS]
    union: dict = {}
    for one in alone:
        for p, s in one.items():
            union.setdefault(p, set()).update(s)
    assert set(every) == set(union) and every == {p: "".join(a for a in p.algs if a in union[p]) for p in every}
    assert list(every) == cv.needed_points(config, g, D)  # every point read, in the claims' order
    pair = cv.needed_letters(config, g, D, claims={"C002-13", "C002-14"})
    assert set(pair.values()) == {"pq"}  # C002-13's p within C002-14's pq at the same points


def test_c002_11_under_the_map_ula_reads_the_marks_and_the_map_twin_instead_of_the_ula():
    config, g, D = _default_points()
    assert cv._c11_letters(config) == "ue"
    assert cv._c11_letters({**config, "ULA": "MAP (designation prior)"}) == "emk"
    assert cv._c11_letters({**config, "velocity knowledge": "designated"}) == "emk"


def test_the_claim_context_gain_is_paired_and_not_rooted_unless_asked():
    """``_Ctx.gain``'s defaults: a paired ratio of the statistic the configuration reads, not its square root."""
    rng = np.random.default_rng(11)
    den = rng.standard_normal((40, 2))
    num = 1.4 * rng.standard_normal((40, 2)) + 0.1
    ctx = cv._Ctx({"epoch": "first", "statistic": "MSE"}, {}, None, np.random.default_rng(2), 200, [1.0])
    got = ctx.gain(num, den)
    ref = variance_ratio_ci(num, den, np.random.default_rng(2), 200, paired=True, spread=ctx.sp, sqrt=False)
    assert ctx.sp == "mse" and (got.value, got.ci_low, got.ci_high) == (ref.value, ref.ci_low, ref.ci_high)
    ctx = cv._Ctx({"epoch": "first", "statistic": "MSE"}, {}, None, np.random.default_rng(2), 200, [1.0])
    rooted = ctx.gain(num, den, paired=False, sd=True)
    ref = variance_ratio_ci(num, den, np.random.default_rng(2), 200, paired=False, spread="mse", sqrt=True)
    assert (rooted.value, rooted.ci_low, rooted.ci_high) == (ref.value, ref.ci_low, ref.ci_high)
