"""Paper 001: the routing of the detection measurement (C001-1, C001-2, C001-3) and C001-9's computation.

``measure_detection`` draws the scenario runs, the no-manoeuvre runs and the alternative's runs and hands each claim
its share: its runs, lengths, arming, streams and null statistic. The claims' own value functions are replaced here
by recorders, so each argument is checked against what the docstring promises, rebuilt in the test from the
scenario's closed forms and the streams' contract (the seed's default stream for the scenario and alternative runs,
its children 2, 3 and 4 for C001-2's closed form, C001-3's and the no-manoeuvre runs). C001-2's value
(``_c001_2``) is written out on fakes of each statistic it passes a number through. C001-9 is pinned on the
geometry: an angle extrapolated from a crossing deviates by ``omega H - atan(omega H)``, and a target seen off its
closest approach by the same amount as one seen in azimuth or elevation from a range and heading.
"""

from __future__ import annotations

from types import SimpleNamespace

import warnings

import numpy as np
import pytest
from scipy import optimize, stats

from tvtrack.estimate import Estimate
from tvtrack.filters.alphabeta import gain_schedule, scheduled_filter
from tvtrack.papers.p001_maneuver_occlusion_kf import spherical, study
from tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector import (
    window_statistic,
    window_sum_of_squares,
)
from tvtrack.papers.p001_maneuver_occlusion_kf.register import build_register
from tvtrack.papers.p001_maneuver_occlusion_kf.scenario import (
    UMP_COMPARATORS,
    config_scenario,
    measurements,
    prefix_stable_measurements,
)

DEFAULT = build_register().default()
MEASURE = study.measure_detection.__wrapped__  # beneath the projection onto each claim's DEPENDS


def child(seed: int, key: int) -> np.random.Generator:
    """The seed's child stream ``key`` (the contract of ``measure_detection``: 2, 3 and 4)."""
    return np.random.default_rng(np.random.SeedSequence(seed).spawn(key + 1)[key])


@pytest.fixture
def claims(monkeypatch):
    """The three claims' value functions replaced by recorders that return their own tag."""
    seen = {}

    def record(cid):
        def fn(*args):
            seen[cid] = args
            return f"value of {cid}"

        return fn

    monkeypatch.setattr(study, "_c001_1", record("C001-1"))
    monkeypatch.setattr(study, "_c001_2", record("C001-2"))
    monkeypatch.setattr(study, "_c001_3", record("C001-3"))
    return seen


def sizes(fa_duration_s: float) -> dict:
    return dict(n_trials=3, n_fa_runs=6, fa_duration_s=fa_duration_s, sigma_eps=1.5, defaults=DEFAULT)


CFG = {**DEFAULT, "window_n": 10, "k_bound2": 30}


def _null(seed, T0, fps, kb2=30, n=10, arm_k=50, onset=125, sigma=1.5, noise="white Gaussian"):
    """The no-manoeuvre runs of channel x written out: 10 el/frame at every frame rate ``fps`` (the paper states it
    per frame), T0 frames, child stream 4."""
    truth0 = 10.0 * np.arange(T0)
    z0 = prefix_stable_measurements(truth0, noise, 6, child(seed, 4), sigma)
    G0 = gain_schedule(1, kb2, T0)
    v0 = scheduled_filter(z0, G0)[..., 1]
    f = np.arange(T0)
    armed = f >= arm_k - 1
    return v0, G0, (window_statistic(v0, n), armed, armed & (f < onset), T0, arm_k)


def _same(a, b):
    """Two tuples of arrays and numbers equal element by element."""
    assert len(a) == len(b)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)


@pytest.mark.parametrize("alternative", ["ramp", "step"])
def test_detection_hands_each_claim_its_runs_lengths_arming_and_streams(claims, alternative):
    cfg = {**CFG, "alternative": alternative, "roc_delay_s": 1.0, "step_dv": 2.0}
    got = MEASURE(cfg, 11, sizes(2.0))
    assert got == {c: f"value of {c}" for c in ("C001-1", "C001-2", "C001-3")}
    sc = config_scenario({**DEFAULT, **cfg})
    rng = np.random.default_rng(11)
    z = measurements(sc.truth[:, : sc.f_loss, 0], "white Gaussian", 3, rng, 1.5)  # up to the loss at 12 s
    config, sc1, z1, arm_k, sigma = claims["C001-1"]
    assert config == {**DEFAULT, **cfg} and np.array_equal(sc1.truth, sc.truth)
    np.testing.assert_array_equal(z1, z)
    assert (arm_k, sigma) == (30 + 2 * 10, 1.5)  # the gains at their bound and both windows full
    # C001-2: the alternative's runs end roc_delay_s = 1 s after the onset at 5 s: 125 + 25 + 1 frames
    Tr = 151
    t = np.arange(Tr)
    step = np.stack([10.0 * t + 2.0 * np.maximum(t - 125, 0), -6.0 * t - 2.0 * np.maximum(t - 125, 0)])
    za = z[..., :Tr] if alternative == "ramp" else measurements(step, "white Gaussian", 3, rng, 1.5)
    shift = 50 * rng.standard_normal((5, 10))
    v0, G0, null = _null(11, Tr, 25.0)  # 2 s of no-manoeuvre runs (51 frames, the arming's) are shorter than Tr
    c2 = claims["C001-2"]
    assert c2[0] == {**DEFAULT, **cfg} and np.array_equal(c2[1].truth, sc.truth) and c2[2] == 1.5
    np.testing.assert_array_equal(c2[3], za)
    np.testing.assert_array_equal(c2[4], v0)
    np.testing.assert_array_equal(c2[5], G0)
    _same(c2[6], null)
    np.testing.assert_array_equal(c2[7], shift)
    assert c2[8] == Tr
    truth, rng2 = c2[9]
    np.testing.assert_array_equal(truth, sc.truth[:, :Tr, 0] if alternative == "ramp" else step)
    assert rng2.random() == child(11, 2).random()
    # C001-3: the first T3 = max(2 s, arm_k + 1) = 51 frames of the same no-manoeuvre runs, child stream 3
    config3, sigma3, G3, null3, rng3 = claims["C001-3"]
    assert config3 == {**DEFAULT, **cfg} and sigma3 == 1.5
    np.testing.assert_array_equal(G3, G0[:51])
    _same(null3, (null[0][:, :51], null[1][:51], null[2][:51], 51, 50))
    assert rng3.random() == child(11, 3).random()


def test_a_long_null_run_sets_the_length_and_the_step_is_per_frame_at_the_frame_rate(claims):
    cfg = {**CFG, "alternative": "step", "roc_delay_s": 0.5, "step_dv": 1.0, "frame_rate_hz": 50.0}
    MEASURE(cfg, 3, sizes(8.0))
    sc = config_scenario({**DEFAULT, **cfg})
    assert (sc.onset, sc.f_loss) == (250, 600)
    rng = np.random.default_rng(3)
    measurements(sc.truth[:, :600, 0], "white Gaussian", 3, rng, 1.5)
    Tr = 250 + 25 + 1  # 0.5 s at 50 Hz after the onset
    t = np.arange(Tr)
    # 10 and -6 el/frame and the 1 el/frame step, per frame at 50 Hz as at 25 Hz, the step away from the manoeuvre
    step = np.stack([10.0 * t + 1.0 * np.maximum(t - 250, 0), -6.0 * t - 1.0 * np.maximum(t - 250, 0)])
    np.testing.assert_array_equal(claims["C001-2"][3], measurements(step, "white Gaussian", 3, rng, 1.5))
    np.testing.assert_array_equal(claims["C001-2"][9][0], step)
    v0, G0, null = _null(3, 400, 50.0, onset=250)  # 8 s of null runs, longer than the alternative's 276 frames
    np.testing.assert_array_equal(claims["C001-2"][4], v0)
    _same(claims["C001-2"][6], null)
    assert claims["C001-2"][8] == Tr
    _same(claims["C001-3"][3], null)
    np.testing.assert_array_equal(claims["C001-3"][2], G0)


def test_each_claim_asked_alone_gets_what_it_gets_with_the_others(claims, monkeypatch):
    cfg = {**CFG, "arming": "windows full"}
    MEASURE(cfg, 5, sizes(3.0))
    full = dict(claims)
    assert full["C001-1"][3] == 2 * 10 + 1  # the windows-full arming
    claims.clear()
    assert MEASURE(cfg, 5, sizes(3.0), claims=["C001-3"]) == {"C001-3": "value of C001-3"}
    assert list(claims) == ["C001-3"]
    np.testing.assert_array_equal(claims["C001-3"][2], full["C001-3"][2])
    _same(claims["C001-3"][3], full["C001-3"][3])  # the first 75 frames of the same no-manoeuvre runs
    claims.clear()
    assert MEASURE(cfg, 5, sizes(3.0), claims=["C001-2", "C001-9"]) == {"C001-2": "value of C001-2"}
    _same(claims["C001-2"][3:6], full["C001-2"][3:6])
    claims.clear()

    def no_null_runs(*a, **k):
        raise AssertionError("C001-1 alone draws no no-manoeuvre runs")

    monkeypatch.setattr(study, "prefix_stable_measurements", no_null_runs)
    assert MEASURE(cfg, 5, sizes(3.0), claims=["C001-1"]) == {"C001-1": "value of C001-1"}
    np.testing.assert_array_equal(claims["C001-1"][2], full["C001-1"][2])
    claims.clear()
    assert MEASURE(cfg, 5, sizes(3.0), claims=["C001-9"]) == {} and claims == {}


# --- C001-2's value on fakes of its statistics ----------------------------------------------------------------------


@pytest.fixture
def c2(monkeypatch):
    """Every statistic ``_c001_2`` passes a number through, replaced by a recorder with a known answer."""
    seen = {"nq": [], "first": []}
    rng = np.random.default_rng(7)
    sig = np.r_[np.nan, np.inf, np.linspace(0.5, 6.0, 10)]  # the first two frames have no finite sigma_S
    H = rng.normal(size=(12, 12))
    H[:, 7] = np.nan  # frame 7's impulse response not finite: not a frame of the unbiasedness rate
    Q0, Qa = rng.uniform(1, 2, (7, 12)), rng.uniform(1, 3, (3, 2, 12))
    hits = {1.25: rng.random((40, 2)) > 0.5, 2.5: rng.random((40, 2)) > 0.3}
    fakes = dict(
        detector_threshold=lambda *a: seen.setdefault("threshold", a) and "c exact",
        false_alarm_rates=lambda *a: (
            seen.setdefault("fa", a) and {"per_test_pooled": Estimate(0.03, 0.002, 0.025, 0.035, 100, 0.95, "cp")}
        ),
        scheduled_statistic_std=lambda *a: seen.setdefault("std", a) is not None and sig,
        _ump_comparator_statistics=lambda *a: seen.setdefault("ump", a) and (Q0, Qa),
        window_statistic=fake_window_statistic,  # not invariant: the invariance part is a number
        null_quantile_threshold=lambda *a: seen["nq"].append(a) or 1.25 * len(seen["nq"]),
        first_alarm_within=lambda *a: seen["first"].append(a) or hits[a[1]],
        mean_ci=lambda x: seen.setdefault("counted", x) is not None and "counted",
        statistic_impulse_response=lambda *a: seen.setdefault("H args", a) and H,
        closed_form_rate=lambda *a, **k: (
            seen.setdefault("cf", (a, k)) and Estimate(0.04, 0.004, 0.03, 0.05, 200, 0.95, "closed form")
        ),
        paired_difference=lambda a, b: seen.setdefault("ump_pair", (a, b)) and "paired",
    )
    for name, fake in fakes.items():
        monkeypatch.setattr(study, name, fake)
    seen.update(sig=sig, H=H, Q0=Q0, Qa=Qa, hits=hits)
    return seen


def fake_window_statistic(v, n):
    return n * np.cumsum(v + 0.1 * v**2, axis=-1)


def _c2_inputs():
    rng = np.random.default_rng(3)
    G0 = gain_schedule(1, 5, 15)
    S0, armed0, pre0 = rng.normal(size=(7, 15)), np.arange(15) >= 2, np.arange(15) < 5
    return dict(
        sc=SimpleNamespace(onset=6),
        sigma=1.5,
        za=rng.normal(0, 2.0, (40, 2, 12)),
        v0_hat=rng.normal(size=(7, 15)),
        G0=G0,
        null=(S0, armed0, pre0, 15, 4),
        shift=rng.normal(size=(5, 2)),
        Tr=12,
        alt=(rng.normal(size=(2, 12)), "closed form's generator"),
    )


@pytest.mark.parametrize("named", [True, False])
def test_c001_2_is_size_unbiasedness_and_power_in_units_of_alpha_and_the_shift_invariance(c2, named):
    cfg = {**DEFAULT, "window_n": 2, "k_bound2": 5, "alpha": 0.02, "noise": "quantised"}
    if named:
        cfg["ump_comparator"] = UMP_COMPARATORS[1]
    else:
        cfg.pop("ump_comparator")  # the sum of squares Q where the configuration names none
    x = _c2_inputs()
    got = study._c001_2(cfg, x["sc"], x["sigma"], x["za"], x["v0_hat"], x["G0"], x["null"], x["shift"], 12, x["alt"])
    S0, armed0, pre0, _, _ = x["null"]
    reading, vis, *rest = c2["threshold"]
    assert reading == "exact" and vis.dtype == bool and vis.all() and vis.size == 15 and rest == [5, 2, 0.02, 1.5]
    assert c2["fa"][1:] == ("c exact", armed0, pre0, 14, 3) and c2["fa"][0] is S0
    assert (got["size"].value, got["size"].ci_low, got["size"].ci_high) == pytest.approx((1.5, 1.25, 1.75))
    np.testing.assert_array_equal(c2["std"][0], x["G0"][:12])
    assert c2["std"][1:] == (2, 1.5)
    va = scheduled_filter(x["za"], x["G0"][:12])[..., 1]
    name, v_null, v_alt, G, n, sigma = c2["ump"]
    assert (name, n, sigma) == (UMP_COMPARATORS[1] if named else UMP_COMPARATORS[0], 2, 1.5) and G is x["G0"]
    np.testing.assert_array_equal(v_null, x["v0_hat"][:, :12])
    np.testing.assert_array_equal(v_alt, va)
    sig = np.r_[np.inf, np.inf, c2["sig"][2:]]
    arm = np.arange(12) >= 3  # armed from frame arm_k - 1
    q_scale = np.where(arm, c2["Q0"].mean(axis=0), np.inf)
    stat_S = np.abs(fake_window_statistic(va, 2)) / sig
    (s0, a0, p0), (q0, a1, p1) = c2["nq"]
    np.testing.assert_allclose(s0, np.abs(S0[:, :12]) / sig)
    np.testing.assert_allclose(q0, c2["Q0"] / q_scale)
    assert np.array_equal(a0, arm) and np.array_equal(a1, arm) and p0 == p1 == 0.02
    (st_s, t_s, b_s, o_s), (st_q, t_q, b_q, o_q) = c2["first"]
    np.testing.assert_allclose(st_s, stat_S)
    np.testing.assert_allclose(st_q, c2["Qa"] / q_scale)
    assert (t_s, t_q, o_s, o_q) == (1.25, 2.5, 6, 6) and np.array_equal(b_s, arm) and np.array_equal(b_q, arm)
    post = arm & (np.arange(12) >= 6)
    sample = (stat_S[..., post] > stats.norm.isf(0.01)).mean(axis=-1).reshape(-1)
    assert 0 < sample.mean() < 1  # the counted alarm rate is a rate, not all or nothing
    between = (stat_S[..., post] > stats.norm.isf(0.01)) & (stat_S[..., post] < stats.norm.isf(0.02 / 3))
    assert between.any()  # frames between the two-sided alpha's quantile and another's: the quantile matters
    np.testing.assert_array_equal(c2["counted"], sample)
    np.testing.assert_array_equal(c2["H args"][0], x["G0"][:12])
    assert c2["H args"][1] == 2
    (H, c_t, post_cf, noise, sigma_cf), kw = c2["cf"]
    assert H is c2["H"] and (noise, sigma_cf) == ("quantised", 1.5)
    np.testing.assert_allclose(c_t, stats.norm.isf(0.01) * sig)
    np.testing.assert_array_equal(post_cf, post & (np.arange(12) != 7))
    assert (kw["rng"], kw["mc"]) == ("closed form's generator", "counted")
    np.testing.assert_allclose(kw["mean"], x["alt"][0] @ np.nan_to_num(c2["H"]))
    assert (got["unbiased"].value, got["unbiased"].ci_low, got["unbiased"].ci_high) == pytest.approx((2.0, 1.5, 2.5))
    v, s = x["v0_hat"][:5, -4:], np.hstack([x["shift"], x["shift"]])  # the last 2n frames of five null runs
    change = fake_window_statistic(v + s, 2)[:, -1] - fake_window_statistic(v, 2)[:, -1]
    assert got["invariance"] == pytest.approx(float(np.max(np.abs(change))), rel=1e-12)
    a, b = c2["ump_pair"]
    np.testing.assert_array_equal(a, c2["hits"][1.25].reshape(-1).astype(float))
    np.testing.assert_array_equal(b, c2["hits"][2.5].reshape(-1).astype(float))
    assert got["UMP"] == "paired" and list(got) == ["size", "invariance", "unbiased", "UMP"]


def test_the_ump_comparators_are_the_sum_of_squares_or_the_gls_taps_of_the_frozen_filter():
    rng = np.random.default_rng(1)
    v0, va = rng.normal(size=(4, 30)), rng.normal(size=(3, 30))
    G = gain_schedule(1, 12, 30)
    q = study._ump_comparator_statistics(UMP_COMPARATORS[0], v0, va, G, 3, 1.0)
    np.testing.assert_array_equal(q[0], window_sum_of_squares(v0, 3))
    np.testing.assert_array_equal(q[1], window_sum_of_squares(va, 3))
    w = study._ump_comparator_statistics(UMP_COMPARATORS[1], v0, va, G, 3, 1.0)
    taps = study.gls_window_taps(gain_schedule(1, 12)[-1], 3)  # the frozen TRACK2 filter's gains
    np.testing.assert_allclose(w[0], np.abs(study.tapped_window_statistic(v0, taps)))
    np.testing.assert_allclose(w[1], np.abs(study.tapped_window_statistic(va, taps)))
    assert not np.allclose(study.gls_window_taps(G[4], 3), taps)  # earlier gains would weigh otherwise
    mixed = np.vstack([gain_schedule(1, 40, 29), gain_schedule(1, 12)[-1:]])  # the frozen gains only at the end
    w = study._ump_comparator_statistics(UMP_COMPARATORS[1], v0, va, mixed, 3, 1.0)
    np.testing.assert_allclose(w[1], np.abs(study.tapped_window_statistic(va, taps)))  # the last frame's filter


# --- C001-9 (spherical.py) -----------------------------------------------------------------------------------------

EL = 6.0 / 712  # degrees per raster element


@pytest.mark.parametrize("rate, H", [(2.107, 10.0), (0.5, 10.0), (3.0, 4.0), (0.1, 4.0)])  # 0.1: under an element
def test_an_angle_extrapolated_from_the_crossing_deviates_by_omega_h_minus_atan_omega_h(rate, H):
    w = np.deg2rad(rate)
    closed = np.degrees(w * H - np.arctan(w * H)) / EL
    for extrapolation in ("linear", "quadratic"):  # no angular acceleration at the crossing: both the same
        got = spherical.paper_rate_deviation(rate, H, extrapolation)
        assert got["deviation_el"] == pytest.approx(closed, rel=1e-5)
        assert got["end_angle_deg"] == pytest.approx(np.degrees(np.arctan(w * H)), rel=1e-12)
        assert got["within_20deg"] is bool(np.degrees(np.arctan(w * H)) <= 20)
        assert spherical.start_deviation(rate, 0.0, H, extrapolation)[0] == pytest.approx(closed, rel=1e-5)
    assert spherical.paper_rate_deviation(rate)["deviation_el"] == pytest.approx(
        np.degrees(w * 10 - np.arctan(w * 10)) / EL, rel=1e-5
    )  # a 10 s horizon and the quadratic extrapolation by default


@pytest.mark.parametrize("extrapolation, col", [("linear", 5), ("quadratic", 6)])
def test_a_target_off_its_closest_approach_deviates_as_one_seen_from_its_range_and_heading(extrapolation, col):
    """Azimuth: heading h from the line of sight at range R is a start 90 - h from the closest approach at a rate
    V sin h / R; elevation: a target flying radially away at elevation e0 is a start 90 - e0 from the vertical at a
    rate V sin e0 / R."""
    R, V, H = 8e3, 250.0, 6.0
    rows = spherical.spherical_deviations([R], [V], [60.0, 90.0], [0.0], horizon_s=H)
    for h, row in zip((60.0, 90.0), rows):
        assert list(row[:4]) == pytest.approx([R, V, h, 0.0], rel=1e-12)
        want, _ = spherical.start_deviation(np.degrees(V * np.sin(np.deg2rad(h)) / R), 90.0 - h, H, extrapolation)
        assert row[col] == pytest.approx(want, rel=2e-3)
    (row,) = spherical.spherical_deviations([R], [V], [0.0], [12.0], horizon_s=H)
    want, _ = spherical.start_deviation(np.degrees(V * np.sin(np.deg2rad(12.0)) / R), 78.0, H, extrapolation)
    assert row[col] == pytest.approx(want, rel=2e-3) and row[col] > 0.1
    quad = spherical.start_deviation(1.0, 15.0, 10.0, "quadratic")[0]
    assert spherical.start_deviation(1.0, 15.0, 10.0)[0] == quad  # the quadratic extrapolation by default
    assert quad < spherical.start_deviation(1.0, 15.0, 10.0, "linear")[0]  # the acceleration term helps here


def test_the_20_degree_field_is_read_in_azimuth_and_elevation_and_in_elements():
    # 300 m/s across at 2 km: atan(1.5) = 56 deg at 10 s, outside; at 20 km atan(0.15) = 8.5 deg, inside
    rows = spherical.spherical_deviations([2e3, 20e3], [300.0], [90.0], [0.0])
    assert list(rows[:, 4]) == [0.0, 1.0]
    (up,) = spherical.spherical_deviations([2e3], [100.0], [0.0], [21.0])  # flying away above 20 deg of elevation
    (low,) = spherical.spherical_deviations([2e3], [100.0], [0.0], [19.0])
    assert (up[4], low[4]) == (0.0, 1.0)
    w = 300.0 / 20e3
    coarse = spherical.spherical_deviations([20e3], [300.0], [90.0], [0.0], deg_per_element=2 * EL)[0]
    assert coarse[5] == pytest.approx(np.degrees(10 * w - np.arctan(10 * w)) / (2 * EL), rel=1e-5)
    assert spherical.start_deviation(0.2, 5.0, 10.0)[1] is True and spherical.start_deviation(1.5, 15.0)[1] is False


def test_the_field_deviation_is_the_worst_start_whose_path_stays_within_20_degrees(monkeypatch):
    seen = []

    def fake(rate, start, H, extrapolation):
        seen.append((rate, start, H, extrapolation))
        return 100.0 - abs(start), abs(start - 2.0) <= 4.0  # worst at 0 deg; the starts -2 to 6 stay inside

    monkeypatch.setattr(spherical, "start_deviation", fake)
    got = spherical.field_deviation(0.5, 4.0, "linear", step_deg=2.0)
    assert [s for _, s, _, _ in seen] == list(np.arange(-20.0, 21.0, 2.0))  # -20 to 20 inclusive
    assert {(r, h, e) for r, _, h, e in seen} == {(0.5, 4.0, "linear")}
    assert got == {"deviation_el": 100.0, "start_deg": 0.0, "starts_within": 5, "starts": 21}
    seen.clear()
    assert spherical.field_deviation(0.5)["starts"] == 81  # every 0.5 deg by default, 10 s, quadratic
    assert {(h, e) for _, _, h, e in seen} == {(10.0, "quadratic")}
    monkeypatch.setattr(spherical, "start_deviation", lambda *a: (1.0, False))
    none = spherical.field_deviation(0.5, step_deg=10.0)
    assert np.isnan(none["deviation_el"]) and np.isnan(none["start_deg"]) and none["starts_within"] == 0


@pytest.fixture
def c9(monkeypatch):
    seen = {"field": []}
    rows = np.array(
        [
            [1, 1, 1, 1, 1.0, 0.5, 0.5],  # inside: both within 1 element
            [1, 1, 1, 1, 1.0, 0.5, 2.0],  # inside: linear within 1, quadratic at 2 exactly (not within 2)
            [1, 1, 1, 1, 0.0, 0.1, 0.1],  # outside the field: not counted
            [1, 1, 1, 1, 1.0, 1.0, 2.5],  # inside: linear at 1 exactly (not within 1), quadratic beyond 2
        ]
    )

    def field(rate, H, extrapolation):
        seen["field"].append((rate, H, extrapolation))
        return {"deviation_el": 10.0 * rate}

    def grid(*sets, horizon_s):
        seen["grid"] = (sets, horizon_s)
        return rows

    monkeypatch.setattr(spherical, "field_deviation", field)
    monkeypatch.setattr(spherical, "spherical_deviations", grid)
    return seen


def test_c001_9_reads_each_rate_in_tolerances_and_the_share_of_geometries_within(c9):
    cfg = {**DEFAULT, "tolerance": "1 element", "extrapolation": "linear", "horizon": "k_b3 filter memory"}
    cfg["targets"] = "20-100 km, 50-250 m/s"
    got = spherical.measure_spherical(cfg, 0, {"defaults": DEFAULT, "prediction_rms": 2.0})["C001-9"]
    rates = list(spherical.PAPER_RATES.values())
    assert c9["field"] == [(r, 4.0, "linear") for r in rates]
    assert c9["grid"] == (spherical.TARGET_SETS["20-100 km, 50-250 m/s"], 4.0)
    assert got == {**{k: 10.0 * r for k, r in spherical.PAPER_RATES.items()}, "geometries": 2 / 3}
    cfg |= {"tolerance": "prediction RMS at k_b3", "extrapolation": "quadratic"}
    cfg.pop("horizon")  # the 10 s loss where the configuration names no horizon
    got = spherical.measure_spherical(cfg, 0, {"defaults": DEFAULT, "prediction_rms": 2.0})["C001-9"]
    assert c9["field"][-1] == (rates[-1], 10.0, "quadratic") and c9["grid"][1] == 10.0
    assert got == {**{k: 5.0 * r for k, r in spherical.PAPER_RATES.items()}, "geometries": 1 / 3}
    assert spherical.measure_spherical(cfg, 0, {"defaults": DEFAULT, "prediction_rms": 2.0}, claims=["C001-8"]) == {}
    assert list(
        spherical.measure_spherical(cfg, 0, {"defaults": DEFAULT, "prediction_rms": 2.0}, claims=["C001-9"])
    ) == ["C001-9"]


def test_c001_9_with_no_geometry_inside_the_field_is_nan(c9, monkeypatch):
    monkeypatch.setattr(spherical, "spherical_deviations", lambda *a, horizon_s: np.zeros((3, 7)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no mean of an empty selection
        got = spherical.measure_spherical(DEFAULT, 0, {"defaults": DEFAULT})["C001-9"]
    assert np.isnan(got["geometries"])


def test_a_path_is_within_the_field_up_to_its_edge_and_the_deviation_is_the_largest_over_the_horizon():
    edge = np.degrees(np.tan(np.deg2rad(20.0)) / 10.0)  # a crossing at this rate ends at 20 deg after 10 s
    assert spherical.start_deviation(edge, 0.0)[1] is True
    assert spherical.start_deviation(edge * 1.04, 0.0)[1] is False  # about 20.7 deg at the end
    w = np.deg2rad(1.0)
    assert spherical.start_deviation(1.0, 0.0)[0] == pytest.approx(
        np.degrees(10 * w - np.arctan(10 * w)) / EL, rel=1e-9
    )
    # approaching its closest point, a path's linear extrapolation errs most inside the horizon: the largest
    # deviation over the horizon, found here by a bounded search on the closed form
    a, w = np.deg2rad(-8.0), np.deg2rad(2.107)
    k = w / np.cos(a) ** 2
    err = lambda t: -abs(a + w * t - np.arctan(np.tan(a) + k * t))  # noqa: E731
    t_max = optimize.minimize_scalar(err, bounds=(0.0, 10.0), method="bounded", options={"xatol": 1e-10}).x
    assert 7.0 < t_max < 8.0
    got = spherical.start_deviation(2.107, -8.0, 10.0, "linear")[0]
    assert got == pytest.approx(np.degrees(-err(t_max)) / EL, rel=1e-5)
