"""Paper 001: the values of C001-4, C001-7 and C001-8 pinned on hand-built curves and errors.

C001-7 reads the dynamic error along the loss times in units of the sweep's smallest random error, and the earliest
loss's |dynamic| / RMS; C001-8 reads the RMS along k_b3, curve 3's ends over its inside minimum, and |dynamic| from
the optimum on; C001-4 reads each comparator's error functional over the scheme's, the compensation over the frames
from the onset to ``compensation_end_s``. Each is written out here on numbers whose answer is known, so a moved
reference point, an inverted ratio or a moved start changes a value. No filter is run.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import scipy.stats
import pytest

from tvtrack.estimate import Estimate
from tvtrack.papers.p001_maneuver_occlusion_kf import curves, study, tradeoff
from tvtrack.papers.p001_maneuver_occlusion_kf.register import build_register
from tvtrack.papers.p001_maneuver_occlusion_kf.scenario import (
    COMPARATORS,
    COMPENSATION_COMPARATORS,
    config_scenario,
    measurements,
    span_mask,
)

from tvtrack.papers.p001_maneuver_occlusion_kf import REGISTER
from tvtrack.papers.p001_maneuver_occlusion_kf.curves import optimum_location

REG = build_register()

DEFAULT = REG.default()
SIZES = dict(sigma_eps=1.0, kb3_grid=[20, 50, 100], loss_grid_s=[6.0, 8.0, 12.0], defaults=DEFAULT)


def same_world(sc, config) -> bool:
    """``sc`` is the configuration's scenario (its frame rate and truth)."""
    want = config_scenario(config)
    return sc.fps == want.fps and np.array_equal(sc.truth, want.truth)


# --- C001-7 and C001-8 from their curves -------------------------------------------------------------------------


def test_c001_7_is_the_dynamic_error_over_the_sweeps_smallest_rms_and_the_earliest_loss_ratio():
    got = curves.c7_parts({"dyn": [-6.0, 4.0, 2.0, 1.0], "rms": [3.0, 2.0, 4.0, 5.0]})
    assert got == {"decreasing": [3.0, 2.0, 1.0, 0.5], "dominates early": 2.0}
    assert all(type(v) is float for v in got["decreasing"])


def test_c001_8_reads_the_rms_the_ends_over_the_inside_minimum_and_the_dynamic_error_from_the_optimum():
    cur = {
        "sum": np.array([5.0, 3.0, 2.0, 4.0, 6.0]),
        "dyn": np.array([4.0, -2.0, 1.0, -3.0, 5.0]),
        "rms": [1.0, 0.5, 0.25, 0.2, 0.1],
    }
    got = curves.c8_parts(cur)
    assert got == {
        "RMS decreasing": [1.0, 0.5, 0.25, 0.2, 0.1],
        "interior minimum": 3.0,  # min(5, 6) - min(3, 2, 4)
        "dynamic grows beyond the optimum": [1.0, 3.0, 5.0],  # from the smallest sum (index 2) on
    }
    end = curves.c8_parts(
        {"sum": np.array([5.0, 4.0, 3.0, 2.0]), "dyn": np.array([1.0, 2.0, 3.0, -7.0]), "rms": [1.0] * 4}
    )
    assert end["dynamic grows beyond the optimum"] == [7.0, 7.0]  # the optimum at the last point: one value, twice
    assert end["interior minimum"] == 2.0 - 3.0  # the smaller end is below the inside: no interior minimum
    two = curves.c8_parts(
        {"sum": np.array([5.0, 4.0, 3.0, 2.0, 6.0]), "dyn": np.array([1.0, 2.0, 3.0, -7.0, 8.0]), "rms": [1.0] * 5}
    )
    assert two["dynamic grows beyond the optimum"] == [7.0, 8.0]


def test_fig4s_optimum_sits_at_the_smallest_sum_next_to_the_dynamic_errors_zero_crossing():
    got = curves.optimum_location(
        {"kb3": [1, 2, 3, 4], "dyn": [3.0, 1.0, -1.0, -2.0], "rms": [1.0, 1.0, 1.0, 2.0], "sum": [4.0, 2.0, 2.5, 4.0]}
    )
    assert got == {
        "kb3": 2,
        "sum": 2.0,
        "dyn": 1.0,
        "rms": 1.0,
        "crossings": [2.5],
        "nearest_crossing": 2.5,
        "at_crossing": True,
        "rms_share": 0.5,
    }
    far = curves.optimum_location(
        {"kb3": [1, 2, 3, 4, 5], "dyn": [1.0, 2.0, 2.0, 1.0, -1.0], "rms": [1.0] * 5, "sum": [1.0, 3.0, 3.0, 2.0, 2.0]}
    )
    assert (far["kb3"], far["crossings"], far["at_crossing"]) == (1, [4.5], False)
    left = curves.optimum_location(
        {"kb3": [1, 2, 3], "dyn": [-1.0, 1.0, 2.0], "rms": [1.0] * 3, "sum": [3.0, 2.0, 3.0]}
    )
    assert (left["kb3"], left["nearest_crossing"], left["at_crossing"]) == (2, 1.5, True)  # the crossing below it
    flat = curves.optimum_location({"kb3": [1, 2], "dyn": [0.0, 1.0], "rms": [1.0, 1.0], "sum": [1.0, 2.0]})
    assert (flat["crossings"], flat["nearest_crossing"], flat["at_crossing"]) == ([], None, False)


def test_the_occlusion_reading_places_the_loss_at_12_s_or_10_s_for_its_length():
    sc = SimpleNamespace(f_loss=300, fps=25.0)
    assert curves.occlusion_frames("scenario 12-22 s", sc) == (300, 550)
    assert curves.occlusion_frames("from 10 s", sc) == (250, 500)
    assert curves.occlusion_frames("scenario 12-22 s", sc, 4.0) == (300, 400)
    with pytest.raises(ValueError, match="occlusion reading 'at 5 s'"):
        curves.occlusion_frames("at 5 s", sc)


@pytest.fixture
def errors(monkeypatch):
    """prediction_error replaced by a table of (k_b3, loss start, reappearance): each point its own numbers."""
    seen = []

    def fake(sc, config, sizes, kb3, f_loss, f_back):
        assert same_world(sc, config) and sizes is SIZES
        seen.append((kb3, f_loss, f_back, config["restart"]))
        return float(kb3 + f_loss / 1000 - f_back / 1e6), float(f_back - f_loss) / 100

    monkeypatch.setattr(curves, "prediction_error", fake)
    return seen


def test_fig4_curves_run_each_grid_bound_at_the_occlusion_readings_loss(errors):
    sc = config_scenario(DEFAULT)
    cfg = {**DEFAULT, "occlusion": "from 10 s", "loss_length_s": 8.0}
    got = curves.fig4_curves(cfg, SIZES)
    fl, fb = int(round(10 * sc.fps)), int(round(18 * sc.fps))
    assert [e[:3] for e in errors] == [(kb, fl, fb) for kb in (20, 50, 100)]
    np.testing.assert_array_equal(got["kb3"], [20, 50, 100])
    dyn = np.array([kb + fl / 1000 - fb / 1e6 for kb in (20, 50, 100)])
    np.testing.assert_allclose(got["dyn"], dyn)
    np.testing.assert_allclose(got["rms"], (fb - fl) / 100)
    np.testing.assert_allclose(got["sum"], np.abs(dyn) + (fb - fl) / 100)


def test_the_loss_sweep_starts_each_loss_at_its_grid_time_for_the_registers_length_and_bound(errors):
    sc = config_scenario(DEFAULT)
    cfg = {**DEFAULT, "loss_length_s": 4.0, "k_bound3": 70}
    got = curves.loss_sweep(cfg, SIZES)
    want = [(70, int(round(s * sc.fps)), int(round((s + 4.0) * sc.fps))) for s in (6.0, 8.0, 12.0)]
    assert [e[:3] for e in errors] == want
    np.testing.assert_array_equal(got["loss_s"], [6.0, 8.0, 12.0])
    np.testing.assert_allclose(got["rms"], [(b - a) / 100 for _, a, b in want])


def test_measure_curves_tags_c001_8_with_the_curve_tolerance_and_measures_only_the_claims_asked(errors):
    cfg = {**DEFAULT, "curve_tolerance": 0.001}
    got = curves.measure_curves.__wrapped__(cfg, 0, SIZES)
    assert list(got) == ["C001-7", "C001-8"]
    assert got["C001-8"]["reading"] == 0.001 and type(got["C001-8"]["reading"]) is float
    assert got["C001-8"]["measured"] == curves.c8_parts(curves.fig4_curves(cfg, SIZES))
    assert got["C001-7"] == curves.c7_parts(curves.loss_sweep(cfg, SIZES))
    assert list(curves.measure_curves.__wrapped__(cfg, 0, SIZES, claims=["C001-8"])) == ["C001-8"]
    assert list(curves.measure_curves.__wrapped__(cfg, 0, SIZES, claims=["C001-7"])) == ["C001-7"]


# --- C001-4: error functionals and their paired ratios ------------------------------------------------------------


def test_the_error_functionals_are_written_out_from_the_mean_and_second_moment():
    m1, m2 = np.array([1.0, -2.0]), np.array([5.0, 4.0])  # variances 4 and 0
    assert tradeoff.error_functional(m1, m2, "bias²") == pytest.approx(2.5)
    assert tradeoff.error_functional(m1, m2, "random") == pytest.approx(2.0)
    assert tradeoff.error_functional(m1, m2, "total") == pytest.approx(4.5)
    assert tradeoff.error_functional(m1, m2, "|bias| + SD") == pytest.approx((1 + 2 + 2 + 0) / 2)
    assert tradeoff.error_functional(np.array([2.0]), np.array([3.0]), "random") == 0.0  # a negative variance: 0
    with pytest.raises(ValueError, match="error functional 'rms'"):
        tradeoff.error_functional(m1, m2, "rms")


def test_a_paired_functional_ratio_is_the_first_filters_functional_over_the_seconds():
    rng = np.random.default_rng(2)
    a, b = rng.normal(1.0, 2.0, (30, 4)), rng.normal(0.5, 1.0, (30, 4))
    f = lambda x: tradeoff.error_functional(x.mean(0), (x**2).mean(0), "random")  # noqa: E731
    got = tradeoff.paired_functional_ratio(a, b, "random", np.random.default_rng(0), n_boot=200)
    assert got.value == pytest.approx(f(a) / f(b), rel=1e-12)
    assert got.ci_low < got.value < got.ci_high and got.n == 30 and got.confidence == 0.95
    # written out: 200 resamples of the runs (rows), the same rows for both filters, each functional recomputed
    picks = np.random.default_rng(0).integers(0, 30, size=(200, 30))
    boot = np.array([f(a[i]) / f(b[i]) for i in picks])
    tail = scipy.stats.norm.cdf(np.sqrt(30 / 29) * scipy.stats.t.ppf(0.025, 29))  # expanded percentile at 30 runs
    assert (got.ci_low, got.ci_high) == pytest.approx(tuple(np.quantile(boot, [tail, 1 - tail])), rel=1e-12)
    assert got.stderr == pytest.approx(np.std(boot, ddof=1), rel=1e-12)
    assert got.method == "expanded percentile bootstrap over 30 runs (200 resamples, paired)"


@pytest.fixture
def c4(monkeypatch):
    """The scheme, the compensation comparator and every tuned comparator replaced by errors of known size."""
    seen = {}
    sc = config_scenario(DEFAULT)
    T = sc.T

    def scheme(z, sc_, config, sizes, covariance, **switch):
        assert same_world(sc_, config) and sizes["n_tradeoff_trials"] == z.shape[0] and covariance is False
        seen["z"], seen["switch"] = z, switch
        x = sc_.truth[None, :, :, 0, None] + np.array([1.0, 5.0, 7.0]) + np.zeros((z.shape[0], 2, T, 3))
        return SimpleNamespace(x=x, detection_frame="det")

    def comparator(name, z, sc_, config, sizes, det):
        assert isinstance(config, dict) and "n_tradeoff_trials" in sizes and z is seen["z"]
        seen["compensation"] = (name, det)
        return sc_.truth[None, :, :, 0] + 2.0 + np.zeros((z.shape[0], 2, T))

    def errs(name, setting, seed, noise, fps, n, sigma, world):
        seen.setdefault("comparators", []).append((name, setting, seed, noise, fps, n, sigma, world))
        return np.full((n, 2, T), 3.0 + COMPARATORS.index(name))

    monkeypatch.setattr(tradeoff, "run_scheme", scheme)
    monkeypatch.setattr(tradeoff, "compensation_comparator", comparator)
    monkeypatch.setattr(tradeoff, "_comparator_errors", errs)

    def tuning(config, sizes):
        assert config["rms_span"] and "n_tradeoff_trials" in sizes
        spans = ("4 s to loss", "onset to loss", "visible after 4 s", "end of the loss", "last frame before the loss")
        return {s: {c: ((s, c), None) for c in COMPARATORS} for s in spans}

    monkeypatch.setattr(tradeoff, "comparator_tuning", tuning)
    monkeypatch.setattr(tradeoff, "paired_functional_ratio", lambda a, b, kind, rng: (a, b, kind, rng.random()))
    return seen


def test_c001_4_compensation_is_the_comparators_bias_over_the_schemes_from_the_onset_to_its_end(c4):
    cfg = {**DEFAULT, "compensation_end_s": 9.0, "C001-4 switch": "forced at the detection time", "switch_s": 5.5}
    sizes = {**SIZES, "n_tradeoff_trials": 4}
    got = tradeoff.measure_tradeoff(cfg, 5, sizes)["C001-4"]
    sc = config_scenario(cfg)
    a, b, kind, draw = got["faster compensation"]
    frames = int(round(9.0 * sc.fps)) - sc.onset  # the frames from the onset to 9 s, both channels
    assert a.shape == b.shape == (4, 2 * frames) and kind == "bias²"
    assert np.all(a == 2.0) and np.all(b == 1.0)  # the comparator's error over the scheme's
    assert draw == np.random.default_rng([5, 4]).random()
    assert c4["compensation"] == (DEFAULT["compensation_comparator"], "det")
    z = measurements(sc.truth[:, :, 0], DEFAULT["noise"], 4, np.random.default_rng(5), 1.0)
    np.testing.assert_array_equal(c4["z"], z)  # the runs of the seed, channel x's truth, sigma_eps
    assert c4["switch"] == {"force_switch_k": int(round(5.5 * sc.fps)) + 1}  # the reading's forced switch
    other = [c for c in COMPENSATION_COMPARATORS if c != DEFAULT["compensation_comparator"]][0]
    tradeoff.measure_tradeoff({**cfg, "compensation_comparator": other}, 5, sizes)
    assert c4["compensation"] == (other, "det")


@pytest.mark.parametrize(
    "statistic, span, kind",
    [
        ("random error (SD)", None, "random"),
        ("total mean square", None, "total"),
        ("|bias| + RMS at 12 s", "last frame before the loss", "|bias| + SD"),
    ],
)
def test_c001_4_min_rms_is_each_comparators_functional_over_the_schemes_on_the_span(c4, statistic, span, kind):
    other = [v for v in REG["manoeuvre"].values if v != DEFAULT["manoeuvre"]][0]  # another world: its own comparators
    cfg = {**DEFAULT, "rms_statistic": statistic, "rms_span": "onset to loss", "manoeuvre": other}
    got = tradeoff.measure_tradeoff(cfg, 5, {**SIZES, "n_tradeoff_trials": 3})["C001-4"]
    assert list(got) == ["faster compensation"] + [f"min RMS vs {c}" for c in COMPARATORS]
    span = span or "onset to loss"
    n_frames = int(span_mask(span, config_scenario(cfg)).sum())
    for c in COMPARATORS:
        a, b, k, _ = got[f"min RMS vs {c}"]
        assert k == kind and a.shape == b.shape == (3, 2 * n_frames)
        assert np.all(a == 3.0 + COMPARATORS.index(c)) and np.all(b == 1.0)
    fps = float(DEFAULT["frame_rate_hz"])
    world = (cfg["manoeuvre"], DEFAULT["accel_unit"], DEFAULT["channel_y"])
    assert c4["comparators"] == [(c, (span, c), 5, DEFAULT["noise"], fps, 3, 1.0, world) for c in COMPARATORS]


# --- C001-1 and C001-3 (study.py): the detection time at frame resolution, rates in units of alpha ---------------


def test_a_detection_time_quantile_is_widened_by_half_a_frame_each_side():
    e = Estimate(5.6, 0.1, 5.5, 5.8, 40, 0.95, "order statistics")
    got = study._frame_resolution(e, 25.0)
    assert got == Estimate(
        5.6,
        0.1,
        5.5 - 0.02,
        5.8 + 0.02,
        40,
        0.95,
        "order statistics, widened by half a frame each side (time resolution)",
        sampling_low=5.5,  # the order statistics' interval: the half frame is the allowance a pool adds back
        sampling_high=5.8,
    )


def test_a_per_test_rate_is_divided_by_alpha_and_a_closed_form_stays_exact():
    e = Estimate(0.002, 0.0004, 0.001, 0.003, 500, 0.95, "Clopper-Pearson")
    got = study._per_alpha(e, 0.01)
    assert (got.value, got.stderr, got.ci_low, got.ci_high) == pytest.approx((0.2, 0.04, 0.1, 0.3))
    assert (got.n, got.confidence, got.method) == (500, 0.95, "Clopper-Pearson, divided by alpha")
    assert study._per_alpha(Estimate(0.002, 0.0, 0.002, 0.002, 1, 0.95, "exact"), 0.01).method == "exact"


def test_c001_1_reads_the_detection_summary_of_the_scheme_at_the_readings_threshold(monkeypatch):
    sc = config_scenario(DEFAULT)
    cfg = {**DEFAULT, "window_n": 7, "k_bound2": 30, "alpha": 0.02, "threshold": "exact", "test_cadence": "every frame"}
    calls = {}

    def threshold(reading, visible, kb2, n, alpha, sigma):
        assert visible.dtype == bool and visible.all()
        calls["threshold"] = (reading, visible.size, kb2, n, alpha, sigma)
        return 2.5

    def cadence(c1, cadence_, n, arm_k):
        calls["cadence"] = (c1, cadence_, n, arm_k)
        return 3.25

    def track(z, visible, tcfg, sigma, covariance):
        assert visible.dtype == bool and visible.all()
        calls["track"] = (z, visible.size, tcfg, sigma, covariance)
        return SimpleNamespace(detection_frame="frames")

    def summary(det, onset, f_loss, fps):
        calls["summary"] = (det, onset, f_loss, fps)
        return {
            "median_s": Estimate(5.6, 0.1, 5.5, 5.8, 40, 0.95, "q"),
            "false_alarm_before_onset": "early",
            "missed_by_loss": "missed",
        }

    monkeypatch.setattr(study, "detector_threshold", threshold)
    monkeypatch.setattr(study, "cadence_threshold", cadence)
    monkeypatch.setattr(study, "run_track_modes", track)
    monkeypatch.setattr(study, "detection_time_summary", summary)
    got = study._c001_1(cfg, sc, "z", 40, 1.5)
    assert calls["threshold"] == ("exact", sc.f_loss, 30, 7, 0.02, 1.5)
    assert calls["cadence"] == (2.5, "every frame", 7, 40)
    z, size, tcfg, sigma, cov = calls["track"]
    assert (z, size, sigma, cov) == ("z", sc.f_loss, 1.5, False)
    assert (tcfg.k_bound2, tcfg.window, tcfg.threshold, tcfg.threshold_index, tcfg.arm_k) == (30, 7, 3.25, "frame", 40)
    assert calls["summary"] == ("frames", sc.onset, sc.f_loss, sc.fps)
    assert got == {
        "median": study._frame_resolution(Estimate(5.6, 0.1, 5.5, 5.8, 40, 0.95, "q"), sc.fps),
        "early": "early",
        "missed": "missed",
    }
    monkeypatch.setattr(
        study,
        "detection_time_summary",
        lambda *a: {"median_s": None, "false_alarm_before_onset": 1, "missed_by_loss": 2},
    )
    none = study._c001_1(cfg, sc, "z", 40, 1.5)["median"]
    assert np.isnan(none.value) and none.n == 0 and none.method == "fewer than two detections"


@pytest.mark.parametrize(
    "paper_sigma, reading", [("filter-output velocity", "independent"), ("raw increments", "raw increments")]
)
def test_c001_3_is_the_papers_thresholds_closed_form_rate_in_units_of_alpha(monkeypatch, paper_sigma, reading):
    if paper_sigma not in REG["paper_sigma"].values:
        paper_sigma = [v for v in REG["paper_sigma"].values if v != "filter-output velocity"][0]
    cfg = {
        **DEFAULT,
        "window_n": 7,
        "k_bound2": 30,
        "alpha": 0.01,
        "paper_sigma": paper_sigma,
        "noise": "white Gaussian",
    }
    seen = {}

    def threshold(r, vis, kb2, n, alpha, sigma):
        assert vis.dtype == bool and vis.all()
        seen["c"] = (r, vis.size, kb2, n, alpha, sigma)
        return "c_paper"

    monkeypatch.setattr(study, "detector_threshold", threshold)
    monkeypatch.setattr(study, "statistic_impulse_response", lambda G0, n: ("H", G0, n))
    monkeypatch.setattr(
        study,
        "false_alarm_rates",
        lambda S0, c, armed, pre, last, first: (
            seen.setdefault("mc", (S0, c, armed, pre, last, first)) and {"per_test_pooled": "mc3"}
        ),
    )

    def closed_form(H, c, armed, noise, sigma, rng, runs, mc):
        seen["cf"] = (H, c, armed, noise, sigma, rng, runs, mc)
        return Estimate(0.02, 0.001, 0.018, 0.022, 2000, 0.95, "closed form")

    monkeypatch.setattr(study, "closed_form_rate", closed_form)
    null = ("S0", "armed0", "pre0", 120, 40)
    got = study._c001_3(cfg, 1.5, "G0", null, "rng")
    assert seen["c"] == (reading, 120, 30, 7, 0.01, 1.5)
    assert seen["mc"] == ("S0", "c_paper", "armed0", "pre0", 119, 39)
    assert seen["cf"] == (("H", "G0", 7), "c_paper", "armed0", "white Gaussian", 1.5, "rng", 2000, "mc3")
    assert (got.value, got.ci_low, got.ci_high) == pytest.approx((2.0, 1.8, 2.2))  # 0.02 in units of alpha = 0.01


def test_fig4s_optimum_reads_the_crossing_nearest_the_minimum_interpolated_linearly():
    got = curves.optimum_location(
        {"kb3": [10, 20, 30, 40], "dyn": [3.0, 2.0, -2.0, -4.0], "rms": [1.0] * 4, "sum": [4.0, 3.0, 3.5, 5.0]}
    )
    assert got["crossings"] == [25.0]  # 20 + 10 x 2 / (2 - (-2))
    two = curves.optimum_location(
        {
            "kb3": [10, 20, 30, 40, 50],
            "dyn": [1.0, -1.0, -2.0, -1.0, 1.0],
            "rms": [1.0] * 5,
            "sum": [3.0, 3.0, 4.0, 1.0, 3.0],
        }
    )
    assert two["crossings"] == [15.0, 45.0] and two["nearest_crossing"] == 45.0 and two["at_crossing"] is True
    zero = curves.optimum_location(
        {"kb3": [1, 2, 3], "dyn": [-1.0, 0.0, 1.0], "rms": [1.0] * 3, "sum": [2.0, 1.0, 2.0]}
    )
    assert zero["crossings"] == []  # an exact zero of the rounded curve is no sign change


@pytest.mark.parametrize(
    "dyn, total, at",
    [
        ([1.0, -1.0, -2.0, -3.0, -4.0], [3.0, 1.0, 3.0, 4.0, 5.0], True),  # the crossing just below the minimum
        ([1.0, 2.0, 2.0, 1.0, -1.0], [3.0, 1.0, 3.0, 3.0, 3.0], False),  # far above it
        ([1.0, -1.0, -2.0, -3.0, -4.0], [5.0, 4.0, 3.0, 2.0, 1.0], False),  # the minimum at the top, far
        ([1.0, 2.0, 3.0, 1.0, -1.0], [5.0, 4.0, 3.0, 1.0, 3.0], True),  # just above, in the grid's last step
        ([1.0, 1.0, -1.0, -2.0, -3.0], [1.0, 3.0, 3.0, 3.0, 3.0], False),  # two steps above the first point
    ],
)
def test_fig4s_optimum_is_at_the_crossing_only_next_to_it(dyn, total, at):
    got = curves.optimum_location({"kb3": [1, 2, 3, 4, 5], "dyn": dyn, "rms": [1.0] * 5, "sum": total})
    assert got["at_crossing"] is at


def test_the_error_functionals_are_means_over_the_columns_of_each_row():
    m1 = np.array([[1.0, -2.0], [0.0, 1.0]])
    m2 = np.array([[5.0, 4.0], [1.0, 2.0]])
    np.testing.assert_allclose(tradeoff.error_functional(m1, m2, "bias²"), [2.5, 0.5])
    np.testing.assert_allclose(tradeoff.error_functional(m1, m2, "random"), [2.0, 1.0])
    np.testing.assert_allclose(tradeoff.error_functional(m1, m2, "total"), [4.5, 1.5])
    np.testing.assert_allclose(tradeoff.error_functional(m1, m2, "|bias| + SD"), [2.5, 1.5])


def test_the_bias_plus_sd_ratio_reads_each_columns_own_second_moment():
    a = np.array([[1.0, 3.0], [3.0, 3.0], [2.0, 6.0]])
    b = np.array([[1.0, 1.0], [1.0, 2.0], [1.0, 3.0]])

    def f(x):  # mean over columns of |mean| + SD (population), written out
        return np.mean(np.abs(x.mean(axis=0)) + x.std(axis=0))

    got = tradeoff.paired_functional_ratio(a, b, "|bias| + SD", np.random.default_rng(0), n_boot=50)
    assert got.value == pytest.approx(f(a) / f(b), rel=1e-12)


def test_the_trade_off_runs_carry_the_sigma_eps_of_the_sizes(c4):
    sizes = {**SIZES, "n_tradeoff_trials": 3, "sigma_eps": 2.0}
    tradeoff.measure_tradeoff(DEFAULT, 5, sizes)
    sc = config_scenario(DEFAULT)
    np.testing.assert_array_equal(
        c4["z"], measurements(sc.truth[:, :, 0], DEFAULT["noise"], 3, np.random.default_rng(5), 2.0)
    )


def test_c001_4_reads_the_papers_defaults_where_the_configuration_and_the_sizes_leave_an_entry_out(c4):
    """``with_defaults`` completes a configuration from ``sizes["defaults"]`` only; sizes without them (``Sizes`` is
    total=False) leave the statistic, the compensation comparator and the comparators' world to the function's own
    defaults, which must be the register's: random error (SD), the 2nd-order filter without the switch, and the
    paper's manoeuvre, acceleration unit and second channel."""
    left_out = ("rms_statistic", "compensation_comparator", "manoeuvre", "accel_unit", "channel_y")
    cfg = {k: v for k, v in DEFAULT.items() if k not in left_out}
    sizes = {k: v for k, v in {**SIZES, "n_tradeoff_trials": 3}.items() if k != "defaults"}
    got = tradeoff.measure_tradeoff(cfg, 5, sizes)["C001-4"]
    assert c4["compensation"] == (DEFAULT["compensation_comparator"], "det")
    assert DEFAULT["compensation_comparator"] == COMPENSATION_COMPARATORS[0] == "2nd order without the switch"
    assert {got[f"min RMS vs {c}"][2] for c in COMPARATORS} == {"random"}  # random error (SD)
    world = (DEFAULT["manoeuvre"], DEFAULT["accel_unit"], DEFAULT["channel_y"])
    assert world == ("constant acceleration", "el/frame²", "v -6, a -0.2")
    assert [w[-1] for w in c4["comparators"]] == [world] * len(COMPARATORS)


# A crossing that rounds onto a grid point, and sizes without defaults (an adversarial review of the equivalents)


def _cur(dyn, rms):
    dyn, rms = np.array(dyn, float), np.array(rms, float)
    return {"kb3": [10, 11, 12], "dyn": dyn, "rms": rms, "sum": np.abs(dyn) + rms}


@pytest.mark.parametrize(
    "dyn, rms, near, kb3",
    [
        ([1e-20, -1.0, -2.0], [5, 0.1, 5], 10.0, 11),  # kills `kb[i - 1] < near`
        ([2.0, 1.0, -1e-20], [5, 5, 0.1], 12.0, 12),  # kills `near < kb[i]` (minimum at the last point)
        ([1e-20, -1.0, -2.0], [0.1, 5, 5], 10.0, 10),  # kills `kb[i] < near`
        ([1.0, -1e-20, -1.0], [0.1, 5, 5], 11.0, 10),  # kills `near < kb[i + 1]`
    ],
)
def test_a_crossing_rounded_onto_a_grid_point_is_adjacent_to_the_minimum(dyn, rms, near, kb3):
    o = optimum_location(_cur(dyn, rms))
    assert o["nearest_crossing"] == near and o["kb3"] == kb3  # the interpolated crossing IS a grid point
    assert o["at_crossing"]  # the minimum is the grid point at / next to the crossing


def test_fig4_and_loss_sweep_read_the_papers_10_s_loss_when_sizes_carry_no_defaults(monkeypatch):
    seen = []

    def fake(sc, config, sizes, kb3, f_loss, f_back):
        seen.append((f_loss, f_back, sc.fps))
        return 0.0, 1.0

    monkeypatch.setattr(curves, "prediction_error", fake)
    cfg = {k: v for k, v in REGISTER.default().items() if k != "loss_length_s"}
    sizes = {"sigma_eps": 1.0, "kb3_grid": [100], "loss_grid_s": [8.0]}  # no "defaults": with_defaults adds nothing
    curves.fig4_curves({**cfg, "occlusion": "from 10 s"}, sizes)
    curves.loss_sweep(cfg, sizes)
    fps = config_scenario(cfg).fps
    assert len(seen) == 2
    for f_loss, f_back, _ in seen:
        assert f_back - f_loss == int(round(10.0 * fps))  # the paper's 10 s loss (11.0 in the mutant: 11 s)
