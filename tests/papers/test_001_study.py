"""Tests of paper 001's study functions (the measurements the explorer calls and the curves the verdicts rest
on): closed forms, independent computations and limits."""

import functools

import numpy as np
import pytest

from tvtrack.filters.alphabeta import gain_schedule, scheduled_filter
from tvtrack.papers.p001_maneuver_occlusion_kf import study
from tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector import (
    statistic_std,
    threshold_from_std,
    track2_thresholds,
)
from tvtrack.papers.p001_maneuver_occlusion_kf.params import RULES
from tvtrack.papers.p001_maneuver_occlusion_kf.register import DEPENDS, GROUPS, build_register, group_register
from tvtrack.filters import polynomial
from tvtrack.papers.p001_maneuver_occlusion_kf import comparators
from tvtrack.papers.p001_maneuver_occlusion_kf import curves
from tvtrack.papers.p001_maneuver_occlusion_kf import scenario
from tvtrack.papers.p001_maneuver_occlusion_kf import spherical

REG = build_register()
SIZES = dict(
    n_trials=200,
    n_fa_runs=3000,
    fa_duration_s=12.0,
    roc_delay_s=0.5,
    step_dv=1.0,
    sigma_eps=1.0,
    n_tradeoff_trials=20,
    n_train=6,
    train_seed=5,
    kb3_grid=[20, 50, 100, 200],
    loss_grid_s=[6.0, 8.0, 12.0],
    n_fig4_trials=200,
    defaults=REG.default(),
    grids=dict(
        fixed2=(2, 10, 50),
        fixed3=(3, 20, 100),
        imm_q_ca=(1e-4, 1e-3),
        imm_p_stay=(0.99,),
        vdf_q_ca=(1e-6, 1e-5),
        vdf_windows=(5,),
    ),
)


@pytest.mark.parametrize("model", scenario.NOISE_MODELS)
def test_measurement_models_have_the_stated_rms(model):
    z = study.measurements(np.zeros(400), model, 400, np.random.default_rng(1), sigma_eps=1.5)
    if model == "quantised":  # rounding of a zero truth: RMS of round(N(0, s^2 - 1/12))
        assert np.sqrt(np.mean(z**2)) == pytest.approx(1.5, rel=0.03)
    else:
        assert np.sqrt(np.mean(z**2)) == pytest.approx(1.5, rel=0.05 if "Student" in model else 0.01)
    if model.startswith("AR(1)"):
        assert np.mean(z[:, 1:] * z[:, :-1]) / np.mean(z**2) == pytest.approx(0.5, abs=0.01)
        assert np.std(z[:, 0]) == pytest.approx(1.5, rel=0.05)  # stationary from the first frame


def test_measurement_models_share_their_normal_draws():
    a = study.measurements(np.zeros(50), "white Gaussian", 3, np.random.default_rng(2))
    b = study.measurements(np.zeros(50), "AR(1), rho = 0.5", 3, np.random.default_rng(2))
    np.testing.assert_array_equal(a[:, 0], b[:, 0])


def test_threshold_readings():
    vis = np.ones(300, bool)
    K2 = gain_schedule(1, 50)[-1]
    z = threshold_from_std(1e-3, 1.0)
    np.testing.assert_array_equal(
        study.detector_threshold("exact", vis, 50, 25, 1e-3), track2_thresholds(vis, 50, 25, 1e-3)
    )
    assert study.detector_threshold("stationary", vis, 50, 25, 1e-3)[0] == pytest.approx(
        z * statistic_std(K2, 1.0, 25, "correlated")
    )
    assert study.detector_threshold("raw increments", vis, 50, 25, 1e-3)[0] == pytest.approx(z * 10.0)
    with pytest.raises(ValueError, match="threshold reading"):
        study.detector_threshold("paper", vis, 50, 25, 1e-3)


def test_arming_rules_and_the_onset_fallback():
    assert study.arming_count("gains at bound", 50, 25, 125) == (100, "gains at bound")
    assert study.arming_count("windows full", 50, 25, 125) == (51, "windows full")
    arm, rule = study.arming_count("gains at bound", 100, 25, 125)  # 150 would test after the onset
    assert arm == 51 and rule.startswith("windows full")


def test_detection_measurement_matches_the_closed_forms():
    m = study.measure_detection({}, 3, SIZES)
    # the paper's independence threshold at stationarity: 2 Phi(-c_ind / sigma_S) per test (Gaussian)
    expected = study.sigma_s_readings({}, SIZES)["pfa_independent"] / 1e-3
    assert m["C001-3"].value == pytest.approx(expected, rel=0.05)
    assert 0.6 < m["C001-2"]["size"].value < 1.5
    assert m["C001-2"]["invariance"] < 1e-9
    assert m["C001-1"]["median"].ci_high - m["C001-1"]["median"].ci_low >= 1 / 25 - 1e-9  # a frame of resolution
    assert 5.0 < m["C001-1"]["median"].value < 6.0


def test_tradeoff_parts_are_the_dynamic_and_random_errors_of_the_figure_study_runs():
    """C001-4: the 'min RMS' parts read the register's rms_statistic on the same runs as the figure
    study: the random error (variance over runs, mean over the span), the total mean square, or |bias| + SD at
    the last frame before the loss; the compensation part is the dynamic (mean) error's mean square."""
    from tvtrack.papers.p001_maneuver_occlusion_kf.tradeoff import error_functional

    cfg = {"rms_span": "onset to loss"}
    tr = study.tradeoff_runs(cfg, 4, SIZES)
    sc = tr["scenario"]
    mask = scenario.span_mask("onset to loss", sc)
    err = {k: (p - sc.truth[None, :, :, 0])[..., mask] for k, p in tr["positions"].items()}
    var = {k: e.var(axis=0).mean() for k, e in err.items()}
    ms = {k: (e**2).mean() for k, e in err.items()}
    m = study.measure_tradeoff(cfg, 4, SIZES)["C001-4"]
    t = study.measure_tradeoff(cfg | {"rms_statistic": "total mean square"}, 4, SIZES)["C001-4"]
    for name in scenario.COMPARATORS:
        assert m[f"min RMS vs {name}"].value == pytest.approx(var[name] / var["adaptive"], rel=1e-9)
        assert t[f"min RMS vs {name}"].value == pytest.approx(ms[name] / ms["adaptive"], rel=1e-9)
        assert m[f"min RMS vs {name}"].ci_low < m[f"min RMS vs {name}"].value < m[f"min RMS vs {name}"].ci_high
    # the compensation part: mean square of the per-frame mean error from the onset to 8 s
    f = sc.frames
    cm = (f >= sc.onset) & (f < 200)
    bias2 = {k: ((p - sc.truth[None, :, :, 0])[..., cm].mean(axis=0) ** 2).mean() for k, p in tr["positions"].items()}
    assert m["faster compensation"].value == pytest.approx(
        bias2["2nd order without the switch"] / bias2["adaptive"], rel=1e-9
    )
    # the '|bias| + RMS at 12 s' reading: |mean| + SD at 12 s (the last frame before the loss), channels averaged
    e12 = np.random.default_rng(0).normal(2.0, 3.0, (4000, 2))
    assert error_functional(e12.mean(0), (e12**2).mean(0), "|bias| + SD") == pytest.approx(5.0, rel=0.05)


def test_tuning_picks_the_grid_minimum():
    t = comparators.tuned_comparators(25.0, 6, 5, 1e-3, 1.0, tuple((k, tuple(v)) for k, v in SIZES["grids"].items()))
    sc = scenario.scenario()
    z = study.measurements(sc.truth[:, :, 0], "white Gaussian", 6, np.random.default_rng(5))
    mask = scenario.span_mask("4 s to loss", sc)
    rms = {
        kb: np.sqrt(
            np.mean(
                ((study.comparator_positions("fixed 3rd order", (kb,), z, sc, 1.0) - sc.truth[None, :, :, 0]) ** 2)[
                    ..., mask
                ]
            )
        )
        for kb in (3, 20, 100)
    }
    best, train_rms, _ = t["4 s to loss"]["fixed 3rd order"]
    assert best == (min(rms, key=rms.get),) and train_rms == pytest.approx(min(rms.values()))


def test_unbiased_bound_at_zero_lead_is_the_growing_memory_variance():
    sc = scenario.scenario()
    for n in (5, 40, 150):
        b = curves.unbiased_prediction_bound(sc, 0, n - 1, n - 1)
        assert b**2 == pytest.approx(3 * (3 * n**2 - 3 * n + 2) / (n * (n + 1) * (n + 2)), rel=1e-9)
    # one frame ahead: the growing-memory 3rd-order filter's own prediction variance (independent recursion)
    G = gain_schedule(2, 10_000, 60)
    e = scheduled_filter(np.random.default_rng(0).standard_normal((20000, 60)), G)
    pred = e[:, -1, 0] + e[:, -1, 1] + 0.5 * e[:, -1, 2]
    assert np.std(pred) == pytest.approx(curves.unbiased_prediction_bound(sc, 0, 59, 60), rel=0.03)


def test_curve_agreement_and_its_word():
    cur = {"dyn": np.array([1.0, 2.0]), "rms": np.array([1.0, 1.0])}
    mc = {"mean": np.array([1.0, 2.0]), "se": np.array([0.1, 0.1]), "sd": np.array([1.0, 1.0])}
    a = curves.curve_agreement(cur, mc, 1000)
    assert a["p_mean"] == 1.0 and a["p_var"] > 0.5
    mc["mean"] = np.array([2.0, 3.0])
    assert curves.curve_agreement(cur, mc, 1000)["p_mean"] < 1e-6
    assert curves.agreement_word(0.2) == "are not shown to differ from" and curves.agreement_word(0.01) == "differ from"


def test_a_test_that_does_not_reject_is_not_worded_as_agreement():
    """Fig. 4's Monte Carlo check at p = 0.06: a chi-square test at 5 % does not reject, which says the means are not
    shown to differ, never that they agree; the words come from the p-value."""
    assert "agree" not in curves.agreement_word(0.06) and curves.agreement_word(0.06) == "are not shown to differ from"
    assert (
        curves.chi2_words(0.06)
        == "χ² p = 0.06 ≥ 0.05: not rejected at the 5 % level, which is not evidence of agreement"
    )
    assert curves.chi2_words(0.0017) == "χ² p = 0.0017 < 0.05: rejected at the 5 % level"
    assert curves.agreement_word(0.049) == "differ from" and curves.agreement_word(0.05) != "differ from"
    from pathlib import Path

    import nbformat

    nb = nbformat.read(Path(__file__).parents[2] / "notebooks" / "001_maneuver_occlusion_kf.ipynb", as_version=4)
    cell = next(c.source for c in nb.cells if "curve_agreement(" in c.source)
    assert "agree with" not in cell and "χ² p =" not in cell and "(p = " not in cell  # no words typed by hand
    assert cell.count("curve_study.chi2_words(agree[") == 2 and cell.count("curve_study.agreement_word(agree[") == 2


def test_curve_parts_on_a_constructed_curve():
    cur = {"dyn": np.array([0.0, 1.0, 2.0, 4.0]), "rms": np.array([9.0, 4.0, 2.0, 1.0])}
    cur["sum"] = np.abs(cur["dyn"]) + cur["rms"]
    p = curves.c8_parts(cur)
    assert p["interior minimum"] == pytest.approx(min(9.0, 5.0) - 4.0)
    assert p["dynamic grows beyond the optimum"] == [2.0, 4.0]


def test_fig4_monte_carlo_checks_the_noise_free_curve():
    cfg = {"restart": "A"}
    cur = curves.fig4_curves(cfg, SIZES)
    mc = curves.fig4_monte_carlo(cfg, SIZES, np.random.default_rng(9))
    a = curves.curve_agreement(cur, mc, SIZES["n_fig4_trials"])
    assert a["p_mean"] > 1e-3 and a["p_var"] > 1e-3


def test_scenario_checks_hold_for_every_restart():
    r = study.scenario_runs({}, 1, SIZES | {"n_trials": 20})
    for o in r["outs"].values():
        assert study.gain_checks(o, r["scenario"], 100)["increases_outside_switches"] == 0
        c = study.coast_check(o, r["scenario"])
        assert c["max_abs_deviation"] < 1e-8 * max(c["error_scale"], 1.0)


def test_every_claim_depends_on_register_entries_and_the_rules_name_the_notebook_parameters():
    for group, ids in GROUPS.items():
        names = group_register(REG, group).names
        assert all(set(DEPENDS[c]) <= set(names) for c in ids)
    import ast
    from pathlib import Path

    import nbformat

    nb = nbformat.read(Path(__file__).parents[2] / "notebooks" / "001_maneuver_occlusion_kf.ipynb", as_version=4)
    cell = next(c for c in nb.cells if "parameters" in c.metadata.get("tags", []))
    assigned = {n.targets[0].id for n in ast.parse(cell.source).body}
    assert set(RULES) <= assigned


def test_spherical_measurement_by_target_set():
    sz = SIZES | {"prediction_rms": 4.0}
    near = spherical.measure_spherical({}, 0, sz)["C001-9"]["geometries"]
    far = spherical.measure_spherical({"targets": "20-100 km, 50-250 m/s"}, 0, sz)["C001-9"]["geometries"]
    assert 0 <= near < far <= 1  # farther, slower targets curve less in angle


def test_explorer_runs_the_curves_group():
    from tvtrack.explore import explore
    from tvtrack.papers.p001_maneuver_occlusion_kf.claims import RULES as CLAIM_RULES

    ex = explore(
        functools.partial(curves.measure_curves, sizes=SIZES),
        group_register(REG, "curves"),
        {c: CLAIM_RULES[c] for c in GROUPS["curves"]},
        seed=1,
        joint=4,
        depends=DEPENDS,
    )
    rec = ex.record("C001-8")
    assert len(ex.replicates()) == 3 and rec["conditions"]
    assert rec["parts"]["RMS decreasing"]["verdict"] == "reproduced" and ex.table("C001-8")
    # the tolerance reading is explored: every value of curve_tolerance was measured and judged by its own rule
    tol = {c["changed"]["curve_tolerance"] for c in rec["conditions"] if set(c["changed"]) == {"curve_tolerance"}}
    assert tol == {0.001, 0.1}


def test_detector_benchmark_arms_every_detector_before_the_onset():
    """With the stated arming k_b2 + 2n, the n = 50 window first tested after the onset and its
    delay row was flat (every run 'detected' at the first test). Each detector now tests before the onset, and a
    higher false-alarm target never lengthens the median delay."""
    sz = SIZES | {"n_trials": 150, "n_fa_runs": 1500}
    b = study.detector_benchmark({}, 2, sz)
    onset = scenario.scenario().onset
    assert all(f < onset for f in b["arming_frame"].values())
    for name, cur in b.items():
        if name != "arming_frame":
            d = cur["median_delay_s"]
            assert np.all(np.diff(d) <= 1e-12), name
    assert np.ptp(b["|S|, n=50"]["median_delay_s"]) > 0


def test_replicates_measure_every_part_afresh():
    """C001-2's replicate entries once reused the pooled value. Each replicate is a full run of its own seed:
    every Monte Carlo part differs between seeds and repeats for the same seed; the 'unbiased' part is the exact
    rate of the Gaussian statistic (no draw), the same for every seed."""
    sz = SIZES | {"n_trials": 60, "n_fa_runs": 600}
    a, b, a2 = (study.measure_detection({}, s, sz)["C001-2"] for s in (11, 12, 11))
    for part in ("size", "UMP"):
        assert a[part].value != b[part].value and a[part].value == a2[part].value, part
    assert a["unbiased"].method.startswith("exact") and a["unbiased"].value == b["unbiased"].value


def test_a_manoeuvre_that_ends_continues_uniformly():
    const, short = scenario.scenario(), scenario.scenario(accel_duration_s=2.0)
    end = short.onset + 50  # 2 s at 25 Hz
    np.testing.assert_array_equal(short.truth[:, : end + 1, :2], const.truth[:, : end + 1, :2])
    a = np.array([m[1] for m in study.MOTION])[:, None]
    v_end = np.array([m[0] for m in study.MOTION])[:, None] + 50 * a
    np.testing.assert_allclose(short.truth[:, end:, 1], np.broadcast_to(v_end, short.truth[:, end:, 1].shape))
    np.testing.assert_allclose(np.diff(short.truth[:, end:, 0], axis=-1), short.truth[:, end + 1 :, 1])  # uniform
    assert np.all(short.truth[:, end:, 2] == 0) and np.all(short.truth[:, short.onset : end, 2] == a)


def test_adversarial_regimes_reach_the_measurements():
    # the manoeuvre that ends makes C001-7's dynamic error rise again after the acceleration stops (restart A)
    const = curves.measure_curves({}, 0, SIZES)["C001-7"]["decreasing"]
    short = curves.measure_curves({"manoeuvre": "2 s acceleration"}, 0, SIZES)["C001-7"]["decreasing"]
    assert np.all(np.diff(const) < 0) and short[1] > short[0]
    # a weaker second channel is detected later (pooled median); a 4 s horizon curves less than a 10 s one
    weak = study.measure_detection({"channel_y": "v -6, a -0.05"}, 1, SIZES)["C001-1"]["median"].value
    paper = study.measure_detection({}, 1, SIZES)["C001-1"]["median"].value
    assert weak > paper
    sz = SIZES | {"prediction_rms": 4.0}
    assert (
        spherical.measure_spherical({"horizon": "k_b3 filter memory"}, 0, sz)["C001-9"]["geometries"]
        > spherical.measure_spherical({}, 0, sz)["C001-9"]["geometries"]
    )
    assert spherical.measure_spherical({"targets": "50-100 km, 100-300 m/s"}, 0, sz)["C001-9"]["geometries"] == 1.0


def test_raised_second_order_limits():
    sc = scenario.scenario()
    truth = sc.truth[:, :, 0]
    never = comparators.raised_second_order(truth, sc, np.full(2, -1), 50, 3)
    np.testing.assert_array_equal(never, study.comparator_positions("fixed 2nd order", (50,), truth, sc, 1.0))
    # raised at the onset and frozen at k = 3 (alpha 5/6, beta 1/2): the alpha-beta lag under constant
    # acceleration a is a (1 - alpha) / beta (Kalata), reached well before the loss
    x = comparators.raised_second_order(truth, sc, np.full(2, sc.onset), 50, 3)
    a = np.array([m[1] for m in study.MOTION])
    np.testing.assert_allclose(x[:, sc.f_loss - 1] - truth[:, sc.f_loss - 1], -a * (1 / 6) / 0.5, rtol=1e-6)


def test_compensation_comparator_reaches_the_measurement():
    base = study.measure_tradeoff({}, 1, SIZES)["C001-4"]["faster compensation"].value
    raised = study.measure_tradeoff({"compensation_comparator": scenario.COMPENSATION_COMPARATORS[1]}, 1, SIZES)[
        "C001-4"
    ]["faster compensation"].value
    assert raised < 1 < base  # raising the 2nd-order gains at the detection compensates faster than the switch


def test_ar1_prediction_rms_matches_monte_carlo():
    sc = scenario.scenario()
    cfg = REG.default() | {"noise": "AR(1), rho = 0.5"}
    _, rms_white = curves.prediction_error(sc, REG.default(), SIZES, 100, sc.f_loss, sc.f_back)
    dyn, rms = curves.prediction_error(sc, cfg, SIZES, 100, sc.f_loss, sc.f_back)
    z = study.measurements(sc.truth[0, :, 0], "AR(1), rho = 0.5", 3000, np.random.default_rng(3), 1.0)
    o = curves.forced_output(sc, cfg, SIZES, 100, sc.visible, z=z, covariance=False)
    e = polynomial.predict_ahead(o.x[:, sc.f_back - 1], 1) - sc.truth[0, sc.f_back, 0]
    assert abs(e.mean() - dyn) < 4 * e.std() / np.sqrt(e.size)
    assert abs(e.std(ddof=1) / rms - 1) < 4 / np.sqrt(2 * e.size)  # SD of an SD estimate ~ 1/sqrt(2n)
    assert rms > 1.2 * rms_white  # positively correlated errors average out less


def test_tapped_statistic_and_gls_taps():
    from tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector import window_statistic

    v = np.random.default_rng(4).standard_normal((3, 80))
    n = 7
    np.testing.assert_allclose(
        study.tapped_window_statistic(v, np.r_[np.ones(n), -np.ones(n)])[:, 2 * n - 1 :],
        window_statistic(v, n)[:, 2 * n - 1 :],
        atol=1e-12,
    )
    taps = study.gls_window_taps(gain_schedule(1, 50)[-1], 25)
    np.testing.assert_allclose(taps[:25], -taps[25:])  # a contrast of the two windows: invariant to common shifts
    np.testing.assert_allclose(taps[:25], taps[:25][::-1])  # stationary covariance: symmetric in time
    assert taps[0] > 10 * taps[12]  # strongly correlated outputs: the window ends carry the information


def test_acceleration_unit_reading_scales_the_manoeuvre():
    paper = study.config_scenario(REG.default())
    per_s = study.config_scenario(REG.default() | {"accel_unit": "el/frame per s"})
    np.testing.assert_allclose(per_s.truth[:, :, 2], paper.truth[:, :, 2] / 25)
    np.testing.assert_allclose(
        per_s.truth[:, :, 1] - paper.truth[:, :1, 1], (paper.truth[:, :, 1] - paper.truth[:, :1, 1]) / 25
    )
    # C001-7: the dynamic error scales with the acceleration, the RMS does not
    sz = SIZES | {"loss_grid_s": [6.0, 8.0]}
    a = curves.measure_curves({}, 0, sz)["C001-7"]
    b = curves.measure_curves({"accel_unit": "el/frame per s"}, 0, sz)["C001-7"]
    np.testing.assert_allclose(b["dominates early"], a["dominates early"] / 25, rtol=1e-4)


def test_fig4_monte_carlo_runs_the_curves_grid_at_another_frame_rate():
    """At 50 frames/s Fig. 4's curves run the grid stretched to the same seconds (kb3_grid); the Monte Carlo check
    must run the same gain bounds, or it compares each curve point with another bound's runs."""
    cfg = {"restart": "A", "frame_rate_hz": 50.0}
    cur = curves.fig4_curves(cfg, SIZES)
    assert list(cur["kb3"]) == [40, 100, 200, 400]
    mc = curves.fig4_monte_carlo(cfg, SIZES, np.random.default_rng(9))
    a = curves.curve_agreement(cur, mc, SIZES["n_fig4_trials"])
    assert a["p_mean"] > 1e-3 and a["p_var"] > 1e-3
