"""Paper 003: the interference claims' values pinned on hand-built loss curves.

:func:`curves.interference_claims` reads the loss curves (runs lost per SIR) at the SIRs the paper names and pairs
them into threshold ratios. Here every curve is built by hand: each run keeps lock from its own grid index on, and
every curve has its own break indices, so a share read at the wrong SIR, a ratio with numerator and denominator
swapped or a curve taken for another changes the value written out here. No scene is simulated.
"""

from __future__ import annotations

import dataclasses
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from tvtrack.estimate import Estimate
from tvtrack.measured import fold_about
from tvtrack.montecarlo import mean_ci, ratio_ci, rms_ci
from tvtrack.papers.p003_rotating_marker_tracker import curves as cv
from tvtrack.papers.p003_rotating_marker_tracker import study
from tvtrack.papers.p003_rotating_marker_tracker.estimators import (
    compensation_factor,
    loss_share,
    share_difference,
    threshold_bound,
    threshold_ratio,
)
from tvtrack.papers.p003_rotating_marker_tracker.lock import LossCriterion, first_loss
from tvtrack.papers.p003_rotating_marker_tracker.loops import phase_locked_amplitude
from tvtrack.papers.p003_rotating_marker_tracker.scene import Scenario

SIRS = np.asarray(cv.SIR_GRID)  # 0.5, 0.75, 1, 4/3, 2, 3, 4.5, 6.75: indices 0..7
USIRS = np.asarray(cv.UNCOMPENSATED_GRID)


def curve(breaks, m=8):
    """Loss indicators (SIR, run) on ``m`` SIRs (the grid's 8): run j is lost below its break index, in lock from it on."""
    return np.arange(m)[:, None] < np.asarray(breaks)[None, :]


BREAKS = {
    ("rotating", 1): [3, 4, 4, 5, 3, 4, 5, 4, 3, 4],
    ("rotating", 5): [5, 5, 6, 5, 4, 6, 5, 5, 6, 5],
    ("static", 1): [2, 2, 3, 2, 3, 2, 2, 3, 2, 2],
    ("static", 5): [3, 3, 4, 3, 3, 4, 3, 3, 3, 4],
    "decoy": [6, 7, 6, 6, 7, 6, 5, 6, 7, 6],
    ("gate", 1.5): [8, 7, 6, 8, 5, 7, 6, 8, 7, 6],
    ("gate", 5.0): [4, 3, 4, 4, 3, 4, 4, 3, 4, 4],
}
CURVES = {k: curve(b) for k, b in BREAKS.items()}
CURVES["uncompensated"] = curve([2, 3, 2, 3, 3, 2, 3, 2, 2, 3], len(USIRS))
CAPT = np.arange(8)[:, None] * 7 % 10 > np.arange(10)[None, :]  # captures per SIR: 0, 7, 4, 1, 8, 5, 2, 9 of 10
BW = Estimate(0.5, 0.05, 0.4, 0.6, 10, 0.95, "hand-built")
BASE = SimpleNamespace(kappa=4.0)
ALL = ("C003-5", "C003-6", "C003-7", "C003-10", "C003-11", "C003-12")


def claims(asked=ALL):
    xc = {
        k: v
        for k, v in CURVES.items()
        if k in (("rotating", 1), ("rotating", 5), ("static", 1), ("static", 5), "decoy")
    }
    return cv.interference_claims({}, BASE, CURVES, CAPT, xc, SIRS, BW, set(asked))


def equal(got, want):
    np.testing.assert_equal(dataclasses.astuple(got), dataclasses.astuple(want))


def test_the_hand_built_curves_differ_where_the_claims_read_them():
    counts = {k: CURVES[k].sum(axis=1).tolist() for k in (("rotating", 1), ("rotating", 5))}
    assert counts[("rotating", 1)] == [10, 10, 10, 7, 2, 0, 0, 0]
    assert counts[("rotating", 5)] == [10, 10, 10, 10, 9, 3, 0, 0]
    assert CAPT.sum(axis=1).tolist() == [0, 7, 4, 1, 8, 5, 2, 9]


def test_c003_5_reads_five_interferers_and_the_captures_at_sir_3():
    got = claims(["C003-5"])
    assert list(got) == ["C003-5"]
    equal(got["C003-5"]["no_loss"], loss_share(CURVES["rotating", 5][5]))
    equal(got["C003-5"]["no_capture"], loss_share(CAPT[5]))
    assert got["C003-5"]["no_loss"].value == pytest.approx(0.3)
    assert got["C003-5"]["no_capture"].value == pytest.approx(0.5)


def test_c003_6_reads_one_interferer_at_sir_05_2_and_4_3():
    got = claims(["C003-6"])["C003-6"]
    assert [got[k].value for k in ("finite", "loss_free", "not_lower")] == pytest.approx([1.0, 0.2, 0.7])
    equal(got["loss_free"], loss_share(CURVES["rotating", 1][4]))


def test_c003_7_reads_five_interferers_at_sir_3_and_2_and_the_rise_five_over_one():
    got = claims(["C003-7"])["C003-7"]
    assert got["loss_free"].value == pytest.approx(0.3)
    assert got["not_lower"].value == pytest.approx(0.9)
    equal(got["rise"], threshold_ratio(CURVES["rotating", 5], CURVES["rotating", 1], SIRS))
    assert got["rise"].value > 1  # five interferers break at a higher SIR than one


def test_c003_10_reads_the_gates_in_order_and_the_compensation_against_kappa():
    got = claims(["C003-10"])["C003-10"]
    want = [threshold_bound(CURVES[k], SIRS) for k in (("gate", 1.5), ("rotating", 5), ("gate", 5.0))]
    assert len(got["gate"]) == 3
    for g, w in zip(got["gate"], want):
        equal(g, w)
    equal(got["compensation"], compensation_factor(CURVES["uncompensated"], USIRS, CURVES["rotating", 5], SIRS, 4.0))


def test_c003_11_reads_the_narrow_gate_at_the_top_sir_the_wide_gates_ratio_and_the_bandwidths_fold():
    got = claims(["C003-11"])["C003-11"]
    equal(got["dynamics"], loss_share(CURVES["gate", 1.5][-1]))
    assert got["dynamics"].value == pytest.approx(0.3)  # three runs of the 1.5 D gate lost even at SIR 6.75
    equal(got["selection"], threshold_ratio(CURVES["gate", 5.0], CURVES["rotating", 5], SIRS))
    assert got["selection"].value < 1
    equal(got["bandwidth"], fold_about(BW, 1.0))
    assert got["bandwidth"].value == pytest.approx(2.0)  # 0.5 is a factor 2 from 1


def test_c003_12_reads_the_static_and_decoy_thresholds_over_the_rotating_markers():
    got = claims(["C003-12"])["C003-12"]
    equal(got["one"], threshold_ratio(CURVES["static", 1], CURVES["rotating", 1], SIRS))
    equal(got["five"], threshold_ratio(CURVES["static", 5], CURVES["rotating", 5], SIRS))
    equal(got["imitator"], threshold_ratio(CURVES["decoy"], CURVES["rotating", 1], SIRS))
    assert got["one"].value < 1 < got["imitator"].value


def test_every_claim_asked_is_returned_with_the_value_it_has_alone():
    together = claims()
    assert list(together) == list(ALL)
    for c in ALL:
        alone = claims([c])[c]
        for k, v in alone.items():
            if isinstance(v, list):
                for a, b in zip(v, together[c][k]):
                    equal(a, b)
            else:
                equal(v, together[c][k])


def test_loss_mechanisms_count_the_losses_and_each_criterion_met_by_a_loss():
    lost = np.array([[True, False, True], [True, True, False]])
    met = np.zeros((2, 3, 3), bool)
    met[0, 0] = [True, True, False]  # a loss meeting capture and drift
    met[0, 1] = [True, False, False]  # not a loss: not counted
    met[1, 1] = [False, False, True]
    met[1, 0] = [True, False, False]
    got = cv.loss_mechanisms(lost, met)
    assert got == {"losses": 4, "capture": 2, "drift among several": 1, "frequency": 1, "none (drift)": 1}
    # indicators given as 0/1 numbers are read as the same booleans
    assert cv.loss_mechanisms(lost.astype(int), met.astype(int)) == got


# --- the tracking claims' values from hand-built runs (study.py) --------------------------------------------------

CRIT = LossCriterion(12.0, 4, 0.5)


def test_the_loss_criterion_reads_the_gate_or_half_the_diameter_and_the_window_in_frames():
    sc = Scenario()  # gate half-size 12 px, D = 8 px, 500 frames a second
    assert study.criterion({}, sc) == LossCriterion(12.0, 250, 0.5)
    assert study.criterion({"loss_radius": "D/2", "loss_window_s": 0.1}, sc) == LossCriterion(4.0, 50, 0.5)
    assert study.criterion({"loss_window_s": 0.0001}, sc).window == 1


def _history(miss):
    miss = np.asarray(miss, float)
    return SimpleNamespace(miss=miss, inside=np.ones(miss.shape, bool))


def test_miss_stats_are_the_mean_square_from_k0_and_the_runs_lost():
    miss = np.array([[100.0, 1.0, 2.0, 2.0, 1.0, 3.0], [1.0, 1.0, 20.0, 20.0, 20.0, 1.0]])
    ms, lost = study._miss_stats(_history(miss), 1, CRIT)
    assert ms == pytest.approx(
        [np.mean(np.array([1, 2, 2, 1, 3.0]) ** 2), np.mean(np.array([1, 20, 20, 20, 1.0]) ** 2)]
    )
    np.testing.assert_array_equal(lost, [False, True])
    h = _history(miss)
    h.inside[0, 0] = False  # the gate outside the image at the first frame: a loss at frame 0
    np.testing.assert_array_equal(study._miss_stats(h, 1, CRIT)[1], [True, True])


def test_c003_4_spread_is_the_largest_over_the_smallest_case_rms_and_compensation_the_ablation_minus_the_first():
    n, k0 = 6, 2
    rng = np.random.default_rng(3)
    scale = [2.0, 30.0, 2.0, 1.0, 1.0]  # four compensated cases, then the ablation without compensation
    miss = np.concatenate([s * (1 + rng.random((n, 10))) for s in scale])
    miss[4 * n : 4 * n + 3, 5:] = 40.0  # three ablation runs lose lock
    miss[1, 7:] = 40.0  # one run of the first case too
    got, rms = study._background_outcome(_history(miss), 5, n, k0, CRIT)
    ms = np.mean(miss[:, k0:] ** 2, axis=1).reshape(5, n)
    want = [mean_ci(np.sqrt(m)) for m in ms[:-1]]
    assert rms == pytest.approx([w.value for w in want])
    big, small = want[1], want[3]  # the largest and the smallest case, not the first and last
    assert got["spread"].value == pytest.approx(big.value / small.value)
    assert (got["spread"].ci_low, got["spread"].ci_high) == pytest.approx(
        (big.ci_low / small.ci_high, big.ci_high / small.ci_low)
    )
    assert got["spread"].method == "max/min of per-case RMS miss; interval from the per-case 95 % bounds (conservative)"
    lo = (first_loss(miss, CRIT) >= 0).reshape(5, n)
    equal(got["compensation"], share_difference(lo[-1], lo[0]))
    assert got["compensation"].value == pytest.approx(3 / 6 - 1 / 6)


def test_c003_4_spread_of_close_small_cases_keeps_its_interval_ends_below_one():
    n, k0 = 6, 2
    rng = np.random.default_rng(8)
    miss = np.concatenate(
        [s * (0.6 + 0.8 * rng.random((n, 1))) * (1 + 0.1 * rng.random((n, 10))) for s in (0.3, 0.36, 0.33, 0.31, 0.3)]
    )
    got, rms = study._background_outcome(_history(miss), 5, n, k0, CRIT)
    want = [mean_ci(np.sqrt(m)) for m in np.mean(miss[:, k0:] ** 2, axis=1).reshape(5, n)[:-1]]
    big, small = max(want, key=lambda w: w.value), min(want, key=lambda w: w.value)
    assert 0 < small.ci_low < 1 and big.ci_low / small.ci_high < 1  # the bounds the code must not floor at 1
    assert (got["spread"].ci_low, got["spread"].ci_high) == pytest.approx(
        (big.ci_low / small.ci_high, big.ci_high / small.ci_low)
    )


def test_c003_4_sweeps_the_papers_residuals_and_correlation_lengths_then_the_ablation():
    sc = Scenario()
    _, (rngs, runs, sc_arg), kw, _ = study._background_spec(sc, 3, 5, 10, CRIT)
    assert len(rngs) == 5 and runs == 15 and sc_arg is sc
    cases = [x for b in kw["blocks"] for x in (b["kappa"], b["background_std"], b["corr_length"])]
    k = sc.kappa
    assert cases == pytest.approx(
        [k, 1 / (k * 50), 8.0, k, 1 / (k * 100), 8.0, k, 1 / (k * 50), 4.0, k, 1 / (k * 50), 16.0, 1.0, 0.2, 8.0]
    )
    assert kw["n_common"] == 3 and kw["keep_full"] is False
    from tvtrack.papers.p003_rotating_marker_tracker.draws import stream_rng

    assert rngs[0].random() == stream_rng(3, 5).random()  # the sweep's own stream
    miss = np.arange(150.0).reshape(15, 10) % 7
    finish = study._background_spec(sc, 3, 5, 4, CRIT)[3]
    got, rms = finish(None, _history(miss))
    want, want_rms = study._background_outcome(_history(miss), 5, 3, 4, CRIT)
    assert rms == want_rms
    equal(got["spread"], want["spread"])


def test_c003_11_bandwidth_ratio_is_the_wider_loops_mean_square_over_the_narrower():
    assert study.BANDWIDTH_PAIR == (5.0, 20.0)
    miss = np.vstack([np.full((3, 8), 2.0), np.full((3, 8), 3.0)])
    miss[0, 2:] = 4.0
    miss[4, 1:] = 1.0
    got = study._bandwidth_outcome(_history(miss), 3, 1)
    ms = np.mean(miss[:, 1:] ** 2, axis=1).reshape(2, 3)
    equal(got, ratio_ci(ms[1], ms[0]))


def test_c003_3_is_the_rms_of_omegas_error_over_omega0_and_of_rs_error_from_k2(monkeypatch):
    e = np.random.default_rng(1).normal(size=(4, 12, 5))
    monkeypatch.setattr(study, "state_errors", lambda tr, h: e)
    tr = SimpleNamespace(t=np.arange(12), omega=np.ones((4, 12)), r=np.ones((4, 12)))
    h = SimpleNamespace(estimate=np.zeros((4, 12, 5)))
    sc2 = Scenario()
    got = study._fig2_outcome(sc2, 3, tr, h)["C003-3"]
    equal(got["omega"], rms_ci(e[:, 3:, 4] / sc2.omega0))
    equal(got["r"], rms_ci(e[:, 3:, 2]))
    fig = study._fig2_outcome(sc2, 3, tr, h)["figure"]
    assert list(fig) == ["t2", "omega", "omega_hat", "r", "r_hat"]
    np.testing.assert_array_equal(fig["t2"], tr.t)


@pytest.mark.parametrize("reading, key", [("+-D/2", "fit_slope_halfD"), ("small errors", "slope_at_zero")])
def test_c003_9_is_the_slope_over_2dd_and_the_edge_forms_mean_square_over_the_quadrants(monkeypatch, reading, key):
    fits = {"fit_slope_halfD": 3.0, "slope_at_zero": 5.0}

    def fit(renderer, d, g):
        assert callable(renderer) and g == Scenario().gate_half
        return {k: v * d for k, v in fits.items()}

    monkeypatch.setattr(study, "quadrant_slope_fit", fit)
    ms = {
        ("square", "quadrant"): np.array([1.0, 2.0, 3.0]),
        ("square", "edge"): np.array([2.0, 2.0, 5.0]),
        ("disc", "edge"): np.array([4.0, 1.0, 1.0]),
    }

    def miss_ms(s, n, seed, k0, crit):
        assert (n, seed, k0, crit) == (3, 7, 10, CRIT)
        return ms[s.spot, s.form]

    monkeypatch.setattr(study, "_miss_ms", miss_ms)
    quad = {"disc": np.array([1.0, 1.0, 2.0])}
    sc = Scenario()
    config = {"slope_range": reading} if reading != "+-D/2" else {}  # the default reading when none is given
    got = study._discriminator_forms(config, sc, 3, 7, 10, CRIT, quad)
    assert list(got) == ["square_linear", "edge_square", "disc_linear", "edge_disc"]
    for spot in ("square", "disc"):
        s = replace(sc, spot=spot)
        assert got[f"{spot}_linear"] == pytest.approx(fits[key] * s.diameter / s.slope())
    equal(got["edge_square"], ratio_ci(ms["square", "edge"], ms["square", "quadrant"]))
    equal(got["edge_disc"], ratio_ci(ms["disc", "edge"], quad["disc"]))
    assert quad["square"] is ms["square", "quadrant"]  # the quadrant runs made here are kept for the caller


@pytest.mark.parametrize("spot", ["disc", "square"])
def test_c003_1_and_2_read_the_papers_bandwidth_and_the_ripple_over_its_controls(monkeypatch, spot):
    sc1 = replace(Scenario(), spot=spot)  # 8 rev/s, B_xy 10 Hz: the third bandwidth of BXY_GRID
    n, T, k0 = 4, 60, 10
    N = n * len(study.BXY_GRID)
    rng = np.random.default_rng(5)
    t = np.arange(T) / sc1.fps
    theta = 2 * np.pi * sc1.rotation_hz * t + rng.uniform(0, 6, (N, 1))
    e = rng.normal(0, 1, (N, T, 5))
    e[..., 0] += np.arange(N)[:, None] * 0.1 * np.cos(theta)  # each run its own locked ripple
    miss = np.where(np.arange(N)[:, None] % 3 == 0, 30.0, 1.0) * np.ones((N, T))  # runs 0, 3, 6, ... lose lock
    tr = SimpleNamespace(t=t, theta=theta, xr=rng.normal(size=(N, T)), yr=rng.normal(size=(N, T)))
    inside = np.ones((N, T), bool)
    inside[10, 0] = False  # run 10 (of the 10 Hz block) leaves the image at its first frame: lost at frame 0
    h = SimpleNamespace(miss=miss, inside=inside, estimate=rng.normal(size=(N, T, 5)))
    seen = {}

    def grid(lost, locked, near, bxy, trend):
        seen["grid"] = (lost, locked, near, bxy, trend)
        return {"trend": "trend", "pair": "pair", "lost": "lost"}

    monkeypatch.setattr(study, "state_errors", lambda tr_, h_: e)
    monkeypatch.setattr(study, "grid_in_lock", grid)
    got = study._fig1_outcome(sc1, n, k0, CRIT, tr, h)
    j = study.BXY_GRID.index(10.0)
    sel = slice(j * n, (j + 1) * n)
    ex, th = e[:, k0:, 0], theta[:, k0:]
    locked = phase_locked_amplitude(ex, th).reshape(len(study.BXY_GRID), n)
    near = phase_locked_amplitude(ex, (9.0 / 8.0) * th).reshape(len(study.BXY_GRID), n)  # f_rot + 1 Hz
    far = phase_locked_amplitude(ex[sel], 1.5 * th[sel])
    equal(got["C003-1"]["x_r"], rms_ci(e[sel, k0:, 0]))
    equal(got["C003-1"]["y_r"], rms_ci(e[sel, k0:, 1]))
    lost = (first_loss(miss, CRIT, inside) >= 0).reshape(len(study.BXY_GRID), n)
    assert lost[j].tolist() == [False, True, True, False]  # run 9 lost on the marker, run 10 at frame 0
    equal(got["C003-1"]["lost"], loss_share(lost[j]))
    equal(got["C003-2"]["far"], ratio_ci(locked[j], far))
    equal(got["C003-2"]["near"], ratio_ci(locked[j], near[j]))
    assert (
        got["C003-2"]["wide_loops"] == "trend"
        and got["_ripple_trend"] == "pair"
        and got["_lock_by_bandwidth"] == "lost"
    )
    g_lost, g_locked, g_near, bxy, trend = seen["grid"]
    np.testing.assert_array_equal(g_lost, lost)
    np.testing.assert_allclose(g_locked, locked)
    np.testing.assert_allclose(g_near, near)
    assert (bxy, trend) == (study.BXY_GRID, study.RIPPLE_TREND)
    assert list(got["quad_ms"]) == [spot]
    np.testing.assert_allclose(got["quad_ms"][spot], np.mean(miss[sel, k0:] ** 2, axis=1))
    fig = got["figure"]
    assert list(fig) == ["t", "xr", "yr", "est", "err", "locked"]
    np.testing.assert_array_equal(fig["t"], t)
    np.testing.assert_array_equal(fig["xr"], tr.xr[j * n])
    np.testing.assert_array_equal(fig["yr"], tr.yr[j * n])
    np.testing.assert_array_equal(fig["est"], h.estimate[j * n, :, :2])
    np.testing.assert_array_equal(fig["err"], e[j * n, :, :2])
    np.testing.assert_allclose(fig["locked"], locked.mean(axis=1))
