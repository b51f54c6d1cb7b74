"""Tests of paper 003's study functions: the direct-count estimators the verdicts rest on, the register and the
measurement functions' contract."""

from dataclasses import replace

import numpy as np
import pytest
from scipy import stats

from tvtrack.explore import pool
from tvtrack.montecarlo import Estimate, zero_events_bound
from tvtrack.measured import fold_about
from tvtrack.papers.p003_rotating_marker_tracker import beyond, estimators, study
from tvtrack.papers.p003_rotating_marker_tracker.register import DEPENDS, INTERFERENCE, REGISTER, TRACKING
from tvtrack.papers.p003_rotating_marker_tracker.scene import run_scenario, state_errors
from tvtrack.verdicts import InBand, Ordering, is_undecided
from tvtrack.papers.p003_rotating_marker_tracker import memo


@pytest.fixture(autouse=True)
def _fresh_memo():
    """Tests here replace the runners: no measurement part kept from another test (memo.clear_cache)."""
    memo.clear_cache()
    yield
    memo.clear_cache()


SIRS = np.array([0.5, 0.75, 1.0, 4 / 3, 2.0, 3.0, 4.5])


def _lost_from_thresholds(thr, sirs=SIRS):
    """Runs that lose lock exactly below their threshold: lost[i, j] = sirs[i] < thr[j]."""
    return np.asarray(sirs)[:, None] < np.asarray(thr)[None, :]


def test_loss_share_counts_and_zero_events_bound():
    e = study.loss_share(np.zeros(30, bool))
    assert (e.value, e.ci_low) == (0.0, 0.0)
    assert e.ci_high == pytest.approx(zero_events_bound(30))
    assert InBand("p", high=0.1).decide(e) == "reproduced"  # 0 of 30 certifies p < 0.095
    j = InBand("p", high=0.1).judge(study.loss_share(np.zeros(20, bool)))  # 0 of 20 certifies only p < 0.139
    assert j.verdict == "undecided" and 29 <= np.ceil(20 * j.runs_factor) <= 31  # 0 of 29 certifies p < 0.1
    full = study.loss_share(np.ones(10, bool))
    assert full.ci_low == pytest.approx(1 - zero_events_bound(10)) and full.ci_high == 1.0
    mid = study.loss_share(np.r_[np.ones(3, bool), np.zeros(7, bool)])
    assert mid.value == pytest.approx(0.3) and mid.ci_low < 0.3 < mid.ci_high


def test_zero_event_shares_pool_across_replicates_as_one_count():
    p = pool([study.loss_share(np.zeros(10, bool)) for _ in range(3)])
    assert p.n == 30 and p.ci_high == pytest.approx(zero_events_bound(30))


def test_log_thresholds_are_grid_midpoints_and_flag_censoring():
    thr = np.array([0.9, 1.6, 2.5, 0.6, 10.0, 0.3])
    tau, cens = estimators.log_thresholds(_lost_from_thresholds(thr), SIRS)
    # a run with threshold in (s_{k-1}, s_k] gets the log midpoint of that step
    k = np.searchsorted(SIRS, thr)
    inside = (k > 0) & (k < SIRS.size)
    mid = (np.log(SIRS[np.maximum(k - 1, 0)]) + np.log(SIRS[np.minimum(k, SIRS.size - 1)])) / 2
    np.testing.assert_allclose(tau[inside], mid[inside])
    np.testing.assert_array_equal(cens, [False, False, False, False, True, True])


def test_threshold_estimate_covers_the_geometric_mean_and_is_extrapolated_outside_the_grid():
    rng = np.random.default_rng(0)
    true_gm = 1.6
    hits = 0
    done = 0
    for k in range(400):
        sigma = 0.3 if k % 2 else 0.05  # spread across steps, or within one grid step
        thr = np.exp(rng.normal(np.log(true_gm), sigma, 15))  # per-run thresholds, lognormal
        e = study.threshold(_lost_from_thresholds(thr), SIRS)
        assert e.extrapolated == bool(np.any((thr <= SIRS[0]) | (thr > SIRS[-1])))
        if not e.extrapolated:
            done += 1
            hits += e.ci_low <= true_gm <= e.ci_high
    assert done > 350 and hits / done >= 0.95  # covers the population's geometric mean at 15 runs
    e = study.threshold(_lost_from_thresholds([1.0, 9.0, 2.0]), SIRS)
    assert e.extrapolated and is_undecided(e)


def test_threshold_ratio_is_paired_and_not_degenerate_when_every_run_agrees():
    a = _lost_from_thresholds([1.6] * 8)
    b = _lost_from_thresholds([0.9] * 8)
    r = estimators.threshold_ratio(a, b, SIRS)
    # all runs in the same grid steps: the ratio of the step midpoints, widened by a grid step (never degenerate)
    mid = lambda lo, hi: np.sqrt(lo * hi)
    assert r.value == pytest.approx(mid(4 / 3, 2.0) / mid(0.75, 1.0))
    assert r.ci_low < r.value < r.ci_high and not is_undecided(r)


def test_compensation_ratio_is_a_bound_when_uncompensated_runs_lose_everywhere():
    usirs = np.array(study.UNCOMPENSATED_GRID)
    comp = _lost_from_thresholds([1.2] * 6)
    unc_all = np.ones((usirs.size, 6), bool)
    e = estimators.compensation_factor(unc_all, usirs, comp, SIRS, 0.1)
    assert e.value == 0.0 and e.ci_low == 0.0 and 0 < e.ci_high < 0.05 and not e.extrapolated
    unc = _lost_from_thresholds([6.0] * 6, usirs)
    e = estimators.compensation_factor(unc, usirs, comp, SIRS, 0.1)
    assert e.ci_low < 0.1 * np.sqrt(1.0 * 4 / 3) / np.sqrt(4.0 * 8.0) < e.ci_high


def test_register_defaults_are_the_scenario_defaults_and_depends_names_known_entries():
    sc = study.scenario(REGISTER.default())
    ref = study.scenario({})
    assert sc == ref
    assert (sc.fps, sc.noise_std, sc.spot, sc.motion, sc.n_interferers) == (500.0, 0.02, "disc", "card", 0)
    assert sc.background_std == pytest.approx(0.2)  # d / (kappa sigma_f) = 50 at kappa = 0.1
    for cid, names in DEPENDS.items():
        assert set(names) <= set(TRACKING) | set(INTERFERENCE), cid
    for name in set(TRACKING) | set(INTERFERENCE):
        for v in REGISTER[name].values:  # every value maps onto a valid scenario
            study.scenario({name: v})


def test_measurement_functions_return_every_part_their_rules_read():
    sz = study.Sizes(trials=2, fig1_s=0.6, fig2_s=0.8, transient_s=0.2, horizon_s=0.4)
    t = study.measure_tracking(REGISTER.default(), 1, sz)
    assert set(t["C003-1"]) == {"x_r", "y_r", "lost"} and len(t["C003-2"]["wide_loops"]) == len(study.BXY_GRID)
    assert set(t["C003-9"]) == {"square_linear", "disc_linear", "edge_square", "edge_disc"}
    i = study.measure_interference(REGISTER.default(), 1, sz)
    assert set(i["C003-12"]) == {"one", "five", "imitator"} and len(i["C003-10"]["gate"]) == 3
    assert i["_curves"]["rotating/5"].shape == (len(study.SIR_GRID), 2)
    assert set(i["_map_bound"]) == set(i["_map"])  # the prose reads a certified side for every threshold
    assert i["C003-10"]["compensation"].n == 2  # the default (one-sided) reading shows the ratio as measured
    # C003-10's gate part: the side a grid-censored threshold certifies, not an extrapolated (undecided) point
    for got, key in zip(i["C003-10"]["gate"], ("gate/1.5", "rotating/5", "gate/5.0")):
        want = study.threshold_bound(i["_curves"][key], study.SIR_GRID)
        assert (got.value, got.ci_low, got.ci_high, got.extrapolated) == (
            want.value,
            want.ci_low,
            want.ci_high,
            want.extrapolated,
        )
    # common random numbers: the same seed gives the same runs
    again = study.measure_interference(REGISTER.default(), 1, sz)
    np.testing.assert_array_equal(again["_curves"]["rotating/5"], i["_curves"]["rotating/5"])


def test_validation_refuses_a_rotation_at_or_above_the_frame_rate_nyquist():
    from tvtrack.papers.p003_rotating_marker_tracker.params import RULES, check_consistency
    from tvtrack.parameters import validate_parameters

    ns = dict(
        seed=3,
        n_trials=5,
        loss_trials=6,
        replicates=3,
        max_replicates=5,
        sizing_budget=150,
        max_subset=2,
        joint=3,
        screen_joint=False,
        n_workers=2,
        rotation_hz=8.0,
        transient_s=2.0,
        fig1_duration_s=5.0,
        fig2_duration_s=10.0,
        loss_duration_s=5.0,
        probe_sir=2.0,
        probe_n_interferers=1,
        probe_kappa=0.1,
        probe_marker="rotating",
        full_analysis=True,
        record_seconds=1.0,
        record_full_every=10,
        output_dir="/tmp/x",
        rerun_mode="off",
        scheduler="",
    )
    lowest = min(REGISTER["fps"].values)
    check_consistency(validate_parameters(ns, RULES), lowest)
    for f in (lowest / 2, lowest / 2 + 1, 300.0):
        with pytest.raises(ValueError, match="Nyquist"):
            check_consistency(validate_parameters({**ns, "rotation_hz": f}, RULES), lowest)


def test_prose_words_follow_the_intervals():
    from tvtrack.papers.p003_rotating_marker_tracker import prose

    e = lambda v, lo, hi, x=False: Estimate(v, float("nan"), lo, hi, 10, 0.95, "t", x)
    assert prose.relation(e(1.0, 0.8, 1.2), 2.0) == "below"
    assert prose.relation(e(3.0, 2.5, 3.5), 2.0) == "above"
    assert prose.relation(e(2.0, 1.5, 2.5), 2.0) == "indistinguishable from"
    assert prose.relation(e(3.0, 2.5, 3.5, True), 2.0) == "undecided against"
    assert prose.compare(e(1.0, 0.9, 1.1), e(2.0, 1.9, 2.1)) == "below"
    assert prose.compare(e(1.0, 0.9, 1.1), e(1.05, 0.95, 1.2)) == "overlapping"
    assert prose.show_bound(e(0.0, 0.0, 0.009)) == "at most 0.009"
    assert prose.show_bound(e(1.0, 0.8, 1.2)) == "1 [0.8, 1.2]"


def _toy(config, seed):
    v = {"gentle": 1.0, "fast": 3.0}[config["motion"]] + (0.5 if config["radius"] == "outside" else 0.0)
    e = Estimate(v, 0.01, v - 0.05, v + 0.05, 30, 0.95, "toy")
    return {"C": {"value": e, "other": e}, "_map": {"rotating 5": e}}


def test_dependence_names_only_the_single_entry_flips_it_is_asked_about():
    from tvtrack.explore import explore
    from tvtrack.papers.p003_rotating_marker_tracker import prose
    from tvtrack.register import Entry, Register
    from tvtrack.verdicts import AllOf

    reg = Register(
        [
            Entry("motion", "regime", "gentle", ("gentle", "fast"), "toy"),
            Entry("radius", "regime", "on", ("on", "outside"), "toy"),
        ]
    )
    rule = AllOf({"value": InBand("v", high=2.0), "other": InBand("v", high=1.2)})
    ex = explore(_toy, reg, {"C": rule}, seed=1, replicates=3, joint=4)
    rec = {"C": ex.record("C")}
    # entries are named in plain words (003's register titles; an entry it lacks by its name)
    motion = "law of the object's motion (Fig. 1 and the interference runs)"
    assert prose.dependence(rec, ("motion",)) == (
        f"changing one of these alone ({motion}) flips C (value, reproduced by default): not reproduced with {motion} "
        f"= fast | C (other, reproduced by default): not reproduced with {motion} = fast"
    )
    assert prose.dependence(rec, ("radius",)) == (
        "changing one of these alone (radius) flips C (other, reproduced by default): not reproduced with radius = "
        "outside"
    )
    assert (
        prose.dependence(rec, ("placement",))
        == "where the interferers sit along the object's path: not explored in this run"
    )
    assert "radius = outside (1.5" in prose.threshold_conditions(ex, "rotating 5", 1.2)


def test_threshold_ratio_covers_the_population_ratio_of_paired_runs():
    rng = np.random.default_rng(1)
    hits = done = 0
    for _ in range(300):
        tb = np.exp(rng.normal(np.log(1.0), 0.25, 15))
        ta = tb * 1.5 * np.exp(rng.normal(0.0, 0.1, 15))  # the same runs, 1.5 times harder to break
        r = estimators.threshold_ratio(_lost_from_thresholds(ta), _lost_from_thresholds(tb), SIRS)
        if not r.extrapolated:
            done += 1
            hits += r.ci_low <= 1.5 <= r.ci_high
    assert done > 250 and hits / done >= 0.95


def test_adversarial_register_values_reach_the_scenario():
    """Each adversarial entry changes exactly the scenario property its row names (a key the scenario ignored would
    leave the explorer measuring the default under another name)."""
    base = study.scenario({})
    assert study.scenario({"rotation_rate": "modulated fast"}).omega_mod == pytest.approx(0.15)
    assert study.scenario({"rotation_rate": "modulated fast"}).omega_mod_hz == pytest.approx(1.0)
    assert study.scenario({"sinusoid_hz": 1.5}).y_freq == pytest.approx(1.5)
    ne = study.scenario({"bandwidth_reading": "noise-equivalent"})
    assert ne.b_xy == pytest.approx(base.b_xy * 2 / np.pi) and ne.b_r == pytest.approx(base.b_r * 2 / np.pi)
    assert ne.b_omega == pytest.approx(base.b_omega * 0.617)
    assert study.scenario({"motion_scale": 0.25}).y_amplitude == pytest.approx(0.25 * base.y_amplitude)
    still = study.interference_scenario({"interference_motion": "hovering", "motion_scale": 2.0})
    assert still.y_amplitude == 0.0 and still.x_std == 0.0  # a hovering object, whatever the Fig. 1 amplitude
    assert study.interference_scenario({}) == base
    assert study.scenario({"fps": 50.0}).fps == 50.0


def test_tracking_judges_c003_1_on_the_configured_coordinate_loop():
    """C003-1 must be measured on the runs whose loop is the configured one, also when the bandwidth reading moves
    it off BXY_GRID (the old `BXY_GRID.index(b) if b in BXY_GRID else 0` silently used the 2 Hz loop's runs). With
    the same draws, C003-1's y error equals that of a separate run of the configured scenario."""
    sz = study.Sizes(trials=2, fig1_s=0.8, fig2_s=0.6, transient_s=0.2, horizon_s=0.4)
    cfg = {**REGISTER.default(), "bandwidth_reading": "noise-equivalent", "slope_range": "small errors"}
    t = study.measure_tracking(cfg, 1, sz)
    # the slope reading reaches C003-9: the disc's slope at small errors is 0.96 of 2dD, over +-D/2 only 0.84
    assert t["C003-9"]["disc_linear"] == pytest.approx(0.960, abs=0.005)
    assert t["C003-9"]["square_linear"] == pytest.approx(1.0, abs=1e-9)
    sc = study.scenario(cfg)
    tr, _, h = run_scenario([study.stream_rng(1, 1)], sz.trials, replace(sc, duration_s=sz.fig1_s))
    k0 = int(round(sz.transient_s * sc.fps))
    y = np.sqrt(np.mean(state_errors(tr, h)[:, k0:, 1] ** 2))
    assert t["C003-1"]["y_r"].value == pytest.approx(y, rel=1e-9)


def test_extend_grid_decides_thresholds_outside_the_grid_and_fills_by_monotonicity():
    sirs = np.array([1.0, 1.5, 2.25])
    thr = {"a": np.array([0.7, 1.2, 2.0]), "b": np.array([1.2, 1.3, 1.7]), "c": np.array([1.2, 1.8, 3.0])}
    calls = []

    def run(keys, sir):
        calls.append((tuple(keys), sir))
        return {k: sir < thr[k] for k in keys}

    curves = {k: _lost_from_thresholds(v, sirs) for k, v in thr.items()}
    assert study.threshold(curves["a"], sirs).extrapolated and study.threshold(curves["c"], sirs).extrapolated
    xs, xc = study.extend_grid(curves, sirs, run)
    np.testing.assert_allclose(xs, [1 / 1.5, 1.0, 1.5, 2.25, 3.375])
    assert calls == [(("a",), 1 / 1.5), (("c",), 3.375)]  # only the censored curves are run
    for k, v in thr.items():  # the filled rows are what the curve would have measured there
        np.testing.assert_array_equal(xc[k], _lost_from_thresholds(v, xs))
        assert not study.threshold(xc[k], xs).extrapolated
    # a threshold beyond two extra points stays undecided
    far = {"d": _lost_from_thresholds([0.1, 1.2, 1.3], sirs)}
    xs2, xc2 = study.extend_grid(far, sirs, lambda keys, sir: {k: sir < np.array([0.1, 1.2, 1.3]) for k in keys})
    assert xs2.size == 5 and study.threshold(xc2["d"], xs2).extrapolated


def test_a_curve_run_at_one_more_sir_repeats_the_grid_runs_draws():
    """extend_grid pairs the extra point with the grid runs: the same draws at any SIR list (common random numbers),
    so the runs at a SIR are identical whether it is run alone or within the grid."""
    from tvtrack.papers.p003_rotating_marker_tracker.scene import interference_runs

    sc = study.scenario({}, study.Sizes(trials=2, horizon_s=0.3), n_interferers=1)
    grid = interference_runs([study.stream_rng(10, 5)], 2, sc, [0.5, 1.0])
    one = interference_runs([study.stream_rng(10, 5)], 2, sc, [1.0])
    np.testing.assert_array_equal(one["miss"], grid["miss"][2:])
    assert np.ptp(grid["miss"][:2] - grid["miss"][2:]) > 0  # the SIR does change the runs


def test_threshold_ratio_is_an_upper_bound_when_the_first_curve_breaks_below_the_grid():
    thr_a = np.array([0.4, 0.3, 0.6, 0.45, 0.8])  # static marker: three runs keep lock at the bottom 0.5
    thr_b = np.array([2.1, 1.9, 2.4, 2.2, 2.0])
    e = estimators.threshold_ratio(_lost_from_thresholds(thr_a), _lost_from_thresholds(thr_b), SIRS)
    assert not e.extrapolated and e.ci_low == 0.0
    ls = np.log(SIRS)
    tau_b = estimators.log_thresholds(_lost_from_thresholds(thr_b), SIRS)[0]
    ub_a = np.where(thr_a < SIRS[0], ls[0], estimators.log_thresholds(_lost_from_thresholds(thr_a), SIRS)[0])
    d = ub_a - tau_b
    t = stats.t.ppf(0.975, d.size - 1)
    # + half of each run's step, per curve (a's three runs below the grid are bounds at its bottom, read with no error
    # there; its 0.6 broke in 0.5-0.75, its 0.8 in 0.75-1; b's all in 4/3-2 or 2-3, steps of 1.5)
    h = (np.log(1.5) + np.log(4 / 3) + 5 * np.log(1.5)) / 2 / 5
    assert e.ci_high == pytest.approx(np.exp(d.mean() + t * d.std(ddof=1) / np.sqrt(d.size) + h))
    assert e.ci_high < 1  # the static marker's threshold is certainly below the rotating one's
    # the mirror (a above the grid, b inside it): a lower bound, at the grid's top over b's breaking SIRs
    hi = estimators.threshold_ratio(_lost_from_thresholds(thr_b * 5), _lost_from_thresholds(thr_b), SIRS)
    assert not hi.extrapolated and hi.ci_high == np.inf
    d = ls[-1] - tau_b
    # a's runs all above the grid are bounds at its top (no error there); b's read in steps of 1.5: half of one
    assert hi.ci_low == pytest.approx(np.exp(d.mean() - t * d.std(ddof=1) / np.sqrt(d.size) - np.log(1.5) / 2))
    assert hi.ci_low > 1 and Ordering("decoy", "stationary", ">", measure="ratio").decide(hi) == "reproduced"
    # censored on the same side in both curves: undecided
    both = estimators.threshold_ratio(_lost_from_thresholds(thr_b * 5), _lost_from_thresholds(thr_b * 4), SIRS)
    assert both.extrapolated


def test_extend_grid_with_a_trigger_runs_only_when_the_trigger_curves_are_censored():
    sirs = np.array([1.0, 1.5, 2.25])
    thr = {"rot": np.array([1.2, 1.3, 1.7]), "static": np.array([0.7, 1.2, 2.0])}
    curves = {k: _lost_from_thresholds(v, sirs) for k, v in thr.items()}
    calls = []
    xs, _ = study.extend_grid(curves, sirs, lambda keys, sir: calls.append(sir) or {}, trigger=["rot"])
    assert calls == [] and xs.size == 3  # only the static curve breaks below: no extra point
    thr["rot"][0] = 0.8
    curves = {k: _lost_from_thresholds(v, sirs) for k, v in thr.items()}
    xs, xc = study.extend_grid(
        curves, sirs, lambda keys, sir: {k: sir < thr[k] for k in keys}, max_points=1, trigger=["rot"]
    )
    np.testing.assert_allclose(xs, [1 / 1.5, 1.0, 1.5, 2.25])
    np.testing.assert_array_equal(xc["static"][0], 1 / 1.5 < thr["static"])  # run too, for the pairing


def test_threshold_bound_certifies_the_side_of_a_grid_censored_threshold():
    """A threshold whose runs all kept lock down to the grid's bottom is certainly below a paper value above the grid
    (a paper-profile run listed the temporal median's 0.27 as 'not below the paper's 2'); all lost at the top: above."""
    sirs = np.array([0.5, 0.75, 1.0, 4 / 3, 2.0, 3.0, 4.5, 6.75])
    none_lost = np.zeros((sirs.size, 6), bool)
    low = study.threshold_bound(none_lost, sirs)
    assert study.threshold(none_lost, sirs).extrapolated and not low.extrapolated
    assert low.ci_low == 0.0 and low.ci_high == pytest.approx(0.5 * np.sqrt(1.5))
    high = study.threshold_bound(np.ones((sirs.size, 6), bool), sirs)
    assert high.ci_high == np.inf and high.ci_low == pytest.approx(6.75 / np.sqrt(1.5))
    inside = _lost_from_thresholds([0.9, 1.1, 1.6, 1.2, 0.8, 2.5], sirs)
    b, t = study.threshold_bound(inside, sirs), study.threshold(inside, sirs)
    assert (b.value, b.ci_low, b.ci_high, b.extrapolated) == (t.value, t.ci_low, t.ci_high, False)  # no censoring
    both = _lost_from_thresholds([0.1, 1.1, 9.0], sirs)
    assert study.threshold_bound(both, sirs).extrapolated  # censored on both sides: still undecided


def _censored(config, seed):
    sirs = np.array([0.5, 0.75, 1.0, 4 / 3, 2.0, 3.0, 4.5, 6.75])
    thr = [0.3] * 6 if config["comp"] == "median" else [2.5, 3.1, 2.8, 4.0, 3.3, 2.6]
    lost = _lost_from_thresholds(thr, sirs)
    e = study.threshold(lost, sirs)
    return {
        "C": e,
        "_map": {"rotating 1": e},
        "_map_bound": {"rotating 1": study.threshold_bound(lost, sirs)},
    }


def test_threshold_conditions_does_not_list_a_threshold_certified_below_the_paper():
    from tvtrack.explore import explore
    from tvtrack.papers.p003_rotating_marker_tracker import prose
    from tvtrack.register import Entry, Register

    reg = Register([Entry("comp", "model", "kappa", ("kappa", "median"), "toy")])
    ex = explore(_censored, reg, {"C": InBand("t", high=10.0)}, seed=1, replicates=3, joint=0)
    assert prose.threshold_conditions(ex, "rotating 1", 2.0) == (
        "under no condition tried is the rotating marker's typical (geometric-mean) SIR at which lock breaks with 1 "
        "interferer other than below the paper's loss-free 2"
    )


def _spy_curves(monkeypatch):
    """Replace the loss curves and the bandwidth runs of measure_interference by stubs that record each scenario
    (every run keeps lock), so the scenarios the rules read can be checked without running them."""
    seen = []

    def curve(sc, sirs, n, seed, crit, counts=None, criteria=False):
        seen.append(sc)
        shape = (len(sirs), n) if counts is None else (len(counts), len(sirs), n)
        return np.zeros(shape, bool), (np.zeros(shape + (3,), bool) if criteria else None)

    class _H:
        def __init__(self, n, frames):
            self.miss = np.ones((n, frames))

    monkeypatch.setattr(study, "_curve", curve)
    monkeypatch.setattr(study, "_together", lambda parts: None)  # the curves and runs come from the stubs
    monkeypatch.setattr(study, "run_scenario", lambda rng, n, sc, **kw: (None, None, _H(n, sc.n_frames)))
    return seen


@pytest.mark.parametrize("static_gate, half_in_d", [(None, 1.5), ("3D", 1.5), ("2D", 1.0)])
def test_static_comparator_runs_the_rotating_markers_gate_by_default(monkeypatch, static_gate, half_in_d):
    """C003-12 compares the markers at the paper's 3D gate (half-size 1.5 D = 12 px, the rotating marker's) unless
    the register's static_gate comparator asks for 2D (pins the default a planted bug changed unseen)."""
    seen = _spy_curves(monkeypatch)
    cfg = {} if static_gate is None else {"static_gate": static_gate}
    sz = study.Sizes(trials=2, horizon_s=0.2, transient_s=0.05)
    study.measure_interference(cfg, 1, sz)
    static = [sc for sc in seen if not sc.rotating]
    rotating = [sc for sc in seen if sc.rotating and sc.n_interferers == 0 and sc.decoy_offset == 0]
    assert static and rotating
    D = rotating[0].diameter
    assert {sc.gate_half for sc in static} == {half_in_d * D}
    assert {sc.gate_half for sc in rotating} == {1.5 * D} == {study.scenario({}).gate_half}


@pytest.mark.parametrize("rotation_hz", [8.0, 5.0])
def test_c003_2_near_control_sits_one_hertz_above_the_rotation(monkeypatch, rotation_hz):
    """C003-2's near control demodulates at f_rot + 1 Hz (and the far one at 1.5 f_rot): the phases handed to the
    synchronous demodulator are the marker's phase times (f_rot + 1) / f_rot and 1.5 (pins the control frequency a
    planted bug changed unseen)."""
    phases = []
    real = study.phase_locked_amplitude

    def spy(err, theta):
        phases.append(np.asarray(theta))
        return real(err, theta)

    monkeypatch.setattr(study, "phase_locked_amplitude", spy)
    sz = study.Sizes(trials=2, fig1_s=0.5, fig2_s=0.4, transient_s=0.1, rotation_hz=rotation_hz)
    study.measure_tracking({}, 1, sz)
    locked, near, far = phases[:3]
    ok = np.abs(locked) > 1e-9
    np.testing.assert_allclose(near[ok] / locked[ok], (rotation_hz + 1.0) / rotation_hz, rtol=1e-12)
    n = sz.trials
    j = study.BXY_GRID.index(10.0)
    np.testing.assert_allclose(far, 1.5 * locked[j * n : (j + 1) * n], rtol=1e-12)


def test_fold_distance_is_two_sided_about_its_reference():
    e = Estimate(0.5, float("nan"), 0.4, 0.625, 6, 0.95, "t")
    f = fold_about(e, 1.0)
    assert (f.value, f.ci_low, f.ci_high) == pytest.approx((2.0, 1.6, 2.5))
    up = fold_about(Estimate(2.0, float("nan"), 1.6, 2.5, 6, 0.95, "t"), 1.0)
    assert (up.value, up.ci_low, up.ci_high) == pytest.approx((2.0, 1.6, 2.5))
    straddle = fold_about(Estimate(1.1, float("nan"), 0.5, 1.5, 6, 0.95, "t"), 1.0)
    assert (straddle.ci_low, straddle.ci_high) == pytest.approx((1.0, 2.0))
    rule = InBand("fold change", low=1.25)
    assert rule.decide(f) == rule.decide(up) == "reproduced"


@pytest.mark.parametrize("factor", [0.5, 2.0])
def test_c003_11_bandwidth_part_is_two_sided(monkeypatch, factor):
    """l. 192 says errors depend substantially on the loop bandwidths, not which way: a miss that halves or doubles
    from 5 to 20 Hz gives the same fold distance 4 in mean square (and the signed ratio is kept for the prose)."""
    _spy_curves(monkeypatch)

    class _H:
        def __init__(self, n, frames):
            ramp = 1.0 + 0.1 * np.arange(n // 2)[:, None] * np.ones((1, frames))
            self.miss = np.concatenate([ramp, factor * ramp])  # rows: 5 Hz runs, then 20 Hz runs

    monkeypatch.setattr(study, "run_scenario", lambda rng, n, sc, **kw: (None, None, _H(n, sc.n_frames)))
    out = study.measure_interference({}, 1, study.Sizes(trials=4, horizon_s=0.2, transient_s=0.05))
    assert out["_bandwidth_ratio"].value == pytest.approx(factor**2)
    assert out["C003-11"]["bandwidth"].value == pytest.approx(4.0)
    assert out["C003-11"]["bandwidth"].ci_low >= 1.0


def test_decoy_brightness_convention_sets_the_decoys_brightness_at_the_tracker():
    """What SIR means for C003-12's decoy: 'residual' puts it at d / SIR (a stationary interferer's brightness after
    compensation, the paper's SIR of l. 198), 'emitted' at what a stationary interferer emits, d / (kappa SIR)."""
    assert study.scenario({}).decoy_gain == 1.0
    em = study.scenario({"decoy_brightness": "emitted"})
    assert em.decoy_gain == pytest.approx(1 / em.kappa) == pytest.approx(10.0)
    for cfg, want in (({}, 0.5), ({"decoy_brightness": "emitted"}, 5.0)):
        sc = replace(study.scenario(cfg), decoy_offset=16.0, duration_s=0.02)
        _, scene, _ = run_scenario(np.random.default_rng(1), 2, sc, 2.0)
        np.testing.assert_allclose(scene.decoy_brightness, want)
    assert "decoy_brightness" in DEPENDS["C003-12"] and "decoy_brightness" not in DEPENDS["C003-7"]


def test_every_register_entry_and_value_reads_in_plain_words():
    for e in REGISTER:
        assert e.title and e.title != e.name, e.name
        for v in e.values:
            assert v in e.phrases and len(e.phrases[v]) > 10, (e.name, v)


def test_exposure_study_runs_both_exposures_on_the_same_draws():
    sz = study.Sizes(trials=2, fig1_s=0.6, fig2_s=0.5, transient_s=0.2, horizon_s=0.4)
    res = beyond.exposure_study(1, sz, sz, 50.0)
    assert res["arc_px"] == pytest.approx(2 * np.pi * 8 * 12 / 50)
    assert set(res["instant"]["thresholds"]) == {"rotating 1", "rotating 5", "static 1", "static 5"}
    direct = study.measure_tracking({"fps": 50.0, "exposure": "integrated"}, 1, sz)["C003-1"]["x_r"]
    assert res["integrated"]["x_r_rms_px"].value == pytest.approx(direct.value, rel=1e-12)
    assert res["integrated"]["x_r_rms_px"].value != pytest.approx(res["instant"]["x_r_rms_px"].value, rel=1e-6)


def test_paper_profile_sizes_the_loss_parts_to_certify_the_rules_limit_and_runs_32_joint_configurations():
    """Zero losses must be able to certify P(loss) <= 0.1 (29 runs, zero-events bound) under the sizing cap, in both
    studies, and the joint design must hold at least 32 configurations per notebook (16 per study)."""
    from pathlib import Path

    import papermill

    nb = Path(__file__).resolve().parents[2] / "notebooks" / "003_rotating_marker_tracker.ipynb"
    p = {k: v["default"] for k, v in papermill.inspect_notebook(str(nb)).items()}
    cap = int(p["max_replicates"])
    assert zero_events_bound(29) < 0.1 < zero_events_bound(28)
    for runs in ("loss_trials", "n_trials"):
        assert zero_events_bound(cap * int(p[runs])) < 0.1, runs
    assert 2 * int(p["joint"]) >= 32


def test_screen_sizes_halve_the_runs_but_keep_the_measured_coverage_and_a_steady_state():
    full = study.Sizes(trials=6, fig1_s=5.0, fig2_s=8.0, transient_s=2.0, horizon_s=5.0)
    s = study.screen_sizes(full)
    assert s.trials == 5 and s.horizon_s == 2.5 and s.fig1_s == 3.0 and s.fig2_s == 4.0
    assert s.fig1_s > s.transient_s and s.rotation_hz == full.rotation_hz
    big = study.screen_sizes(replace(full, trials=20))
    assert big.trials == 10
