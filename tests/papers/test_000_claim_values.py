"""Paper 000: each claim value's wiring pinned on hand-built filter errors whose values are known in closed form.

``study.filter_errors`` is replaced by a table: every (psi_A, P, filter, start, initial estimate) gets its own
scale, so a value read at the wrong psi_A or contrast, from the wrong filter, with numerator and denominator
swapped or with the wrong statistic differs from the value written out here. The simulation itself is pinned
elsewhere (``test_000_value_pins.py``); these tests take a second.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from tvtrack.counts import proportion_ci
from tvtrack.estimate import Estimate
from tvtrack.montecarlo import mean_square_ci, quantile_ci, ratio_ci, rms_ci
from tvtrack.papers.p000_dissector_ekf import study
from tvtrack.papers.p000_dissector_ekf.cost import operation_ratio
from tvtrack.papers.p000_dissector_ekf.model import scan_at_snr
from tvtrack.papers.p000_dissector_ekf.readings import ACCOUNTING, C2_EVERY, CS_LITERAL, ENSEMBLE_MEAN, EVERY_ABOVE
from tvtrack.papers.p000_dissector_ekf.reference import scan_crlb
from tvtrack.papers.p000_dissector_ekf.register import REGISTER
from tvtrack.papers.p000_dissector_ekf.settling import median_ratio_ci

DEFAULT = REGISTER.default()
PSI9 = study.psi_at(20.0, 0.9, "fixed background")  # 180
SIZES = study.Sizes(psi_grid=(5.0, 20.0, 50.0))  # the default contrasts (0, 0.25, 0.5, 0.7, 0.9)
FILTERS = {"v1": 3.0, "v2": 2.0, "stationary": 1.0, "ignoring": 5.0}
#: per-run shapes whose mean and median ratios differ between every two filters
SHAPES = {
    "v1": np.array([1.0, 2.0, 3.0, 4.0, 10.0]),
    "v2": np.array([1.0, 1.0, 2.0, 3.0, 8.0]),
    "stationary": np.array([2.0, 2.0, 3.0, 3.0, 5.0]),
    "ignoring": np.array([1.0, 3.0, 3.0, 3.0, 4.0]),
}


def steady(psi, p, filt, offset=None, init="process means"):
    """The table's per-run steady mean squared errors: one scale per operating point, filter and start."""
    scale = FILTERS[filt] * (1 + psi / 7) * (1 + 3 * p) * (1.5 if offset else 1.0)
    return scale * (1.25 if init != "process means" else 1.0) * SHAPES[filt]


def d_steady(psi, p, filt):
    """The filters' own steady D11 in the table: another shape, so that the two fields' ratios differ."""
    return FILTERS[filt] * (1 + psi / 7) * (1 + 3 * p) * np.sqrt(SHAPES[filt][::-1])


@pytest.fixture
def table(monkeypatch):
    calls = []

    def fake(cfg, seed, sizes, psi, contrast, filt, offset=None, init="process means"):
        assert isinstance(cfg, dict) and seed == 3 and sizes == SIZES  # the run's own configuration, seed, sizes
        calls.append((psi, contrast, filt, offset, init))
        return {"steady": steady(psi, contrast, filt, offset, init), "d_steady": d_steady(psi, contrast, filt)}

    monkeypatch.setattr(study, "filter_errors", fake)
    monkeypatch.setattr(study, "_MEMO", {})
    return calls


def same(got: Estimate, want: Estimate):
    assert (got.value, got.ci_low, got.ci_high, got.n) == pytest.approx((want.value, want.ci_low, want.ci_high, want.n))


def mean_ratio(a, b):
    return float(np.mean(a) / np.mean(b))


# --- psi_A by the contrast convention, and the ratio -------------------------------------------------------------


def test_psi_at_is_the_anchor_times_the_conventions_factor_over_its_value_at_p_05():
    assert study.psi_at(20.0, 0.9, "fixed N0") == 20.0
    assert study.psi_at(20.0, 0.9, "fixed total current") == pytest.approx(20.0 * (0.9 / np.sqrt(0.1)) / np.sqrt(0.5))
    assert study.psi_at(20.0, 0.9, "fixed background") == pytest.approx(20.0 * 9.0)
    assert study.psi_at(20.0, 0.25, "fixed background") == pytest.approx(20.0 / 3.0)
    for convention in study.CONTRAST_CONVENTIONS:
        assert study.psi_at(20.0, 0.0, convention) == 20.0
        assert study.psi_at(20.0, 0.5, convention) == pytest.approx(20.0)
    with pytest.raises(ValueError, match=r"parameter 'convention' = 'fixed P'; it must be one of \('fixed N0'"):
        study.psi_at(20.0, 0.5, "fixed P")


def test_a_ratio_is_exact_only_for_the_same_runs_and_reads_the_statistic():
    a = np.array([0.1, 0.2, 0.4, 0.8])
    exact = study._ratio(a, a.copy(), "median")
    assert exact == Estimate(1.0, 0.0, 1.0, 1.0, 4, 0.95, "exact")
    near = study._ratio(a * 1.01, a, "mean")  # close in absolute terms, 1 % apart: not the same filter
    assert near.value == pytest.approx(1.01, rel=1e-12)
    closer = study._ratio(a * (1 + 1e-7), a, "mean")  # within numpy's default rtol, not within 1e-9
    assert closer.method != "exact" and closer.value == pytest.approx(1 + 1e-7, rel=1e-12)
    tiny = study._ratio(a * 2e-9, a * 1e-9, "mean")  # within numpy's default atol, twice as large
    assert tiny.method != "exact" and tiny.value == pytest.approx(2.0)
    b = np.array([0.3, 0.2, 0.1, 0.9])
    assert study._ratio(b, a, "mean").value == pytest.approx(np.mean(b) / np.mean(a))
    assert study._ratio(b, a, "median").value == pytest.approx(np.median(b) / np.median(a))
    same(study._ratio(b, a, "median"), median_ratio_ci(b, a))


@pytest.mark.parametrize("statistic, f", [("mean", np.mean), ("median", np.median)])
def test_ratio_to_star_is_the_filter_over_the_stationary_filter_at_psi_a_of_p(table, statistic, f):
    cfg = {**DEFAULT, "statistic": statistic, "contrast convention": "fixed background", "psi_A": 20.0}
    got = study.ratio_to_star(cfg, 3, SIZES, 0.9)
    assert got.value == pytest.approx(f(steady(180.0, 0.9, "v2")) / f(steady(180.0, 0.9, "stationary")))
    got = study.ratio_to_star(cfg, 3, SIZES, 0.25, filt="v1")
    assert got.value == pytest.approx(f(steady(20 / 3, 0.25, "v1")) / f(steady(20 / 3, 0.25, "stationary")))
    same(study.ratio_to_star({**cfg, "statistic": "mean"}, 3, SIZES, 0.7), ratio_ci(
        steady(20 * 7 / 3, 0.7, "v2"), steady(20 * 7 / 3, 0.7, "stationary")
    ))  # fmt: skip


def test_the_accounting_ratio_is_the_filter_ignoring_the_signal_noise_over_variant_2(table):
    cfg = {**DEFAULT, "contrast convention": "fixed background", "psi_A": 20.0}
    got = study._ratio_to_accounting(cfg, 3, SIZES, 0.9)
    assert got.value == pytest.approx(mean_ratio(steady(180.0, 0.9, "ignoring"), steady(180.0, 0.9, "v2")))
    median = study._ratio_to_accounting({**cfg, "statistic": "median"}, 3, SIZES, 0.9)
    assert median.value == pytest.approx(
        np.median(steady(180.0, 0.9, "ignoring")) / np.median(steady(180.0, 0.9, "v2"))
    )


# --- C000-1: runs acquired by acquire_by_T, or the ensemble mean at that scan -----------------------------------

#: per run: the scans far out of lock (above 25 x the steady level), then those out only against 4 x it
FAR, NEAR = [0, 3, 5, 6, 8, 10], [0, 5, 6, 6, 9, 10]


def _scans(level, far, near, n_scans=10):
    s = np.ones((len(far), n_scans))
    for i, (f, g) in enumerate(zip(far, near)):
        s[i, f:g] = 6.0  # out of lock against 2 x steady RMS (4 x its mean square), in against 3 x and 5 x
        s[i, :f] = 30.0
    return level * s * (1 + 0.01 * np.arange(n_scans))  # each scan its own level, inside the same bands


@pytest.fixture
def c1_table(monkeypatch):
    """Scans of the uniform start (levels 1.5 and 2 against the paper's start's steady 1 and 2), so a threshold
    read from the wrong start moves the count."""
    level = {"v1": 1.0, "v2": 2.0}

    def fake(cfg, seed, sizes, psi, contrast, filt, offset=None, init="process means"):
        assert (psi, contrast) == (cfg["psi_A"], cfg["contrast"]) and seed == 3 and isinstance(sizes, study.Sizes)
        k = level[filt] * (1.5 if offset == "uniform" else 1.0) * (1.25 if init != "process means" else 1.0)
        far, near = (FAR, NEAR) if filt == "v1" else (FAR[::-1], NEAR[::-1])
        scans = _scans(k, far, near) if offset == "uniform" else _scans(k, [0] * 6, [0] * 6)
        return {"scans": scans, "steady": level[filt] * np.array([0.5, 1.5, 1.0, 1.0, 0.5, 1.5]) * (2 if offset else 1)}

    monkeypatch.setattr(study, "filter_errors", fake)


def test_c000_1_counts_the_runs_not_in_lock_for_good_after_acquire_by_t_per_variant(c1_table):
    cfg = {**DEFAULT, "initial position": "uniform in the micro-raster"}
    got = study._c1(cfg, 3, SIZES)
    assert got["reading"] == DEFAULT["convergence criterion"]
    # the lock threshold is 25 x the paper's start's steady level: acquired at the end of the last scan above it,
    # 1, 3, 5, 6, 8 and never (the last scan out): three runs later than 5 T
    assert got["measured"]["variant 1"] == proportion_ci(3, 6)
    assert got["measured"]["variant 2"] == proportion_ci(3, 6)
    strict = study._c1({**cfg, "lock threshold": "2 x steady RMS"}, 3, SIZES)["measured"]
    assert strict["variant 1"] == proportion_ci(4, 6)  # 0, 5, 6, 6, 9, never: 6, 6, 9 and never are late
    assert study._c1(DEFAULT, 3, SIZES)["measured"]["variant 1"] == proportion_ci(0, 6)  # the paper's start


def test_c000_1_acquisition_window_is_acquire_by_t(c1_table):
    cfg = {**DEFAULT, "initial position": "uniform in the micro-raster"}
    late = study._c1(cfg, 3, study.Sizes(acquire_by_T=7.0))["measured"]["variant 1"]
    assert late == proportion_ci(2, 6)  # 8 and never are later than 7 T; 6 T is not


def test_c000_1_ensemble_mean_is_the_scan_ending_at_acquire_by_t_over_the_steady_level(c1_table):
    cfg = {**DEFAULT, "initial position": "uniform in the micro-raster", "convergence criterion": ENSEMBLE_MEAN}
    cfg["initial estimate"] = "random N(0, D11(0))"
    got = study._c1(cfg, 3, SIZES)
    assert got["reading"] == ENSEMBLE_MEAN
    k = 1.5 * 1.25
    scans = _scans(k, FAR, NEAR)
    run_steady = np.array([0.5, 1.5, 1.0, 1.0, 0.5, 1.5]) * 2
    same(got["measured"]["variant 1"], ratio_ci(scans[:, 4], run_steady))  # the scan ending at 5 T: the fifth
    assert got["measured"]["variant 1"].value == pytest.approx(np.mean(scans[:, 4]) / np.mean(run_steady))
    v2 = _scans(2 * k, FAR[::-1], NEAR[::-1])[:, 4]
    assert got["measured"]["variant 2"].value == pytest.approx(np.mean(v2) / np.mean(2 * run_steady))


# --- C000-2: RMS over the micro-raster at psi_A = 20 -------------------------------------------------------------


@pytest.mark.parametrize("size, over", [("T", 1.0), ("T_u", 0.5)])
def test_c000_2_is_the_steady_rms_at_psi_a_20_over_the_micro_raster(table, size, over):
    cfg = {**DEFAULT, "psi_A": 50.0, "micro-raster size": size}
    got = study._c2(cfg, 3, SIZES)
    assert got["reading"] == DEFAULT["C000-2 contrasts"]
    assert list(got["measured"]) == ["P=0", "P=0.5 variant 1", "P=0.5 variant 2"]
    for name, p, filt in [("P=0", 0.0, "stationary"), ("P=0.5 variant 1", 0.5, "v1"), ("P=0.5 variant 2", 0.5, "v2")]:
        e = got["measured"][name]
        want = rms_ci(np.sqrt(steady(20.0, p, filt))[:, None])
        assert e.value == pytest.approx(np.sqrt(np.mean(steady(20.0, p, filt))) / over)
        assert (e.stderr, e.ci_low, e.ci_high) == pytest.approx(
            (want.stderr / over, want.ci_low / over, want.ci_high / over)
        )
        assert (e.n, e.confidence, e.method) == (want.n, want.confidence, want.method)


def test_c000_2_every_contrast_adds_both_variants_at_the_other_fig3_contrasts(table):
    got = study._c2({**DEFAULT, "C000-2 contrasts": C2_EVERY}, 3, SIZES)
    assert got["reading"] == C2_EVERY
    assert list(got["measured"]) == ["P=0", "P=0.5 variant 1", "P=0.5 variant 2"] + [
        f"P={p} variant {v}" for p in ("0.25", "0.7", "0.9") for v in (1, 2)
    ]
    assert got["measured"]["P=0.7 variant 1"].value == pytest.approx(np.sqrt(np.mean(steady(20.0, 0.7, "v1"))))


# --- C000-3: v1 / v2 over Fig. 3's contrasts and Fig. 2's SNRs ---------------------------------------------------


@pytest.mark.parametrize("statistic, f", [("mean", np.mean), ("median", np.median)])
def test_c000_3_is_variant_1_over_variant_2_at_each_contrast_and_snr(table, statistic, f):
    cfg = {**DEFAULT, "statistic": statistic, "contrast convention": "fixed background", "contrast": 0.7}
    got = study._c3(cfg, 3, SIZES)
    assert got["reading"] == 0.7 and got["measured"]["reading"] == DEFAULT["signal-noise scale"]
    m = got["measured"]["measured"]
    # Fig. 2's psi_A = 20 at P = 0.5 is Fig. 3's point, left out
    assert list(m) == ["P=0", "P=0.25", "P=0.5", "P=0.7", "P=0.9", "psi_A=5", "psi_A=50"]
    for p in SIZES.contrast_grid:
        psi = study.psi_at(20.0, p, "fixed background")
        assert m[f"P={p:g}"].value == pytest.approx(f(steady(psi, p, "v1")) / f(steady(psi, p, "v2")))
    for psi in (5.0, 50.0):  # at the configuration's contrast, the psi_A as given
        assert m[f"psi_A={psi:g}"].value == pytest.approx(f(steady(psi, 0.7, "v1")) / f(steady(psi, 0.7, "v2")))


def test_c000_3_own_d11_reading_and_zero_contrast(table):
    cfg = {**DEFAULT, "C000-3 accuracy": "filters' own D11"}
    got = study._c3(cfg, 3, SIZES)["measured"]["measured"]
    assert got["P=0.9"].value == pytest.approx(mean_ratio(d_steady(20.0, 0.9, "v1"), d_steady(20.0, 0.9, "v2")))
    assert got["psi_A=5"].value == pytest.approx(mean_ratio(d_steady(5.0, 0.5, "v1"), d_steady(5.0, 0.5, "v2")))
    zero = study._c3({**DEFAULT, "contrast": 0.0}, 3, SIZES)
    assert zero["reading"] == 0.0
    assert list(zero["measured"]["measured"]) == ["P=0", "P=0.25", "P=0.5", "P=0.7", "P=0.9"]


# --- C000-5 and C000-7: the ratios to sigma_x^2*, their reading of "substantially", the CRLB gap -----------------


def _crlb_ratio(psi):
    nodes = np.arange(20) * 0.05
    return scan_crlb(scan_at_snr(psi, 0.9, 0.05, 0.5), nodes) / scan_crlb(scan_at_snr(psi, 0.0, 0.05, 0.5), nodes)


def test_c000_5_reads_p_below_05_and_p_09_and_c000_7_the_trend_and_the_crlb_gap(table):
    cfg = {**DEFAULT, "contrast convention": "fixed background"}
    c5, c7 = study._c5_c7(cfg, 3, SIZES)
    assert c5["reading"] == DEFAULT["substantially determines"]
    assert list(c5["measured"]) == ["P=0.25", "P=0.9"]  # P = 0.5: in neither strict half
    for p in (0.25, 0.9):
        psi = study.psi_at(20.0, p, "fixed background")
        want = mean_ratio(steady(psi, p, "v2"), steady(psi, p, "stationary"))
        assert c5["measured"][f"P={p:g}"].value == pytest.approx(want)
    trend = [e.value for e in c7["trend"]]
    assert trend == pytest.approx([
        mean_ratio(steady(study.psi_at(20.0, p, "fixed background"), p, "v2"),
                   steady(study.psi_at(20.0, p, "fixed background"), p, "stationary"))
        for p in SIZES.contrast_grid
    ])  # fmt: skip
    r9 = c7["trend"][-1]
    gap = c7["measurement vs estimate"]
    crlb = _crlb_ratio(180.0)
    assert gap.value == pytest.approx(crlb - r9.value, rel=1e-12)
    assert (gap.ci_low, gap.ci_high) == pytest.approx((crlb - r9.ci_high, crlb - r9.ci_low), rel=1e-12)
    assert (gap.stderr, gap.n, gap.confidence, gap.method) == (r9.stderr, r9.n, r9.confidence, r9.method)


def test_c000_5_every_contrast_above_05_and_the_accounting_comparison(table):
    c5, c7 = study._c5_c7(
        {**DEFAULT, "substantially determines": EVERY_ABOVE, "C000-5 comparison": ACCOUNTING}, 3, SIZES
    )
    assert c5["reading"] == EVERY_ABOVE
    assert list(c5["measured"]) == ["P=0.25", "P=0.7", "P=0.9"]
    for p in (0.25, 0.7, 0.9):
        want = mean_ratio(steady(20.0, p, "ignoring"), steady(20.0, p, "v2"))
        assert c5["measured"][f"P={p:g}"].value == pytest.approx(want)
    # C000-7 reads Fig. 3's ratio to sigma_x^2* under every reading of C000-5
    assert c7["trend"][-1].value == pytest.approx(mean_ratio(steady(20.0, 0.9, "v2"), steady(20.0, 0.9, "stationary")))
    assert c7["measurement vs estimate"].value == pytest.approx(_crlb_ratio(20.0) - c7["trend"][-1].value)


# --- C000-6: the reading's filter over the reading's achievable accuracy at P = 0.9 ------------------------------


@pytest.mark.parametrize(
    "reading, filt", [("variant 2", "v2"), ("variant 1", "v1"), ("ignoring the signal noise", "ignoring")]
)
def test_c000_6_is_the_readings_filter_over_sigma_x2_star_at_p_09(table, reading, filt):
    cfg = {**DEFAULT, "C000-6 filter": reading, "contrast convention": "fixed background", "statistic": "median"}
    got = study._c6(cfg, 3, SIZES)
    assert got.value == pytest.approx(np.median(steady(180.0, 0.9, filt)) / np.median(steady(180.0, 0.9, "stationary")))


@pytest.mark.parametrize("statistic", ["mean", "median"])
def test_c000_6_over_the_pcrlb_is_the_statistic_over_the_bounds_window_mean(table, monkeypatch, statistic):
    seen = []

    def pcrlb(scan, message, n_steps, at, nodes):
        assert scan == study.operating_scan(DEFAULT, 20.0, 0.9, SIZES) and message == study.MESSAGE
        seen.append((n_steps, at, len(nodes)))
        out = np.full(n_steps + 1, 100.0)
        out[SIZES.window()] = np.linspace(3.0, 5.0, int(SIZES.window().sum()))  # window mean 4
        return out

    monkeypatch.setattr(study, "pcrlb_variance", pcrlb)
    got = study._c6({**DEFAULT, "potentially achievable": "PCRLB", "statistic": statistic}, 3, SIZES)
    a = steady(20.0, 0.9, "v2")
    want = mean_square_ci(a) if statistic == "mean" else quantile_ci(a, 0.5)
    assert got.value == pytest.approx(want.value / 4.0)
    assert (got.ci_low, got.ci_high) == pytest.approx((want.ci_low / 4.0, want.ci_high / 4.0))
    if statistic == "mean":
        assert got.stderr == pytest.approx(want.stderr / 4.0)
    assert (got.n, got.confidence, got.method) == (want.n, want.confidence, want.method + " over the PCRLB (exact)")
    assert seen[0] == (SIZES.n_steps, "interval_end", 20)


# --- C000-9 and the measurement's routing -----------------------------------------------------------------------


@pytest.mark.parametrize("statistic", ["mean", "median"])
def test_c000_9_is_each_variants_steady_variance_over_the_fig2_snrs_at_the_contrast(table, statistic):
    got = study._c9({**DEFAULT, "contrast": 0.7, "statistic": statistic}, 3, SIZES)
    assert list(got) == ["variant 1", "variant 2"]
    for v, filt in (("variant 1", "v1"), ("variant 2", "v2")):
        want = [
            (
                mean_square_ci(steady(psi, 0.7, filt))
                if statistic == "mean"
                else quantile_ci(steady(psi, 0.7, filt), 0.5)
            )
            for psi in SIZES.psi_grid
        ]
        for g, w in zip(got[v], want):
            same(g, w)


def test_measure_returns_the_claims_asked_in_the_papers_order_from_their_own_reads(table, monkeypatch):
    seen = {}
    for name in ("_c1", "_c2", "_c3", "_c6", "_c8", "_c9"):
        monkeypatch.setattr(
            study, name, lambda cfg, seed, sizes, name=name: seen.setdefault(name, (cfg, seed, sizes)) and name
        )
    monkeypatch.setattr(study, "_c5_c7", lambda cfg, seed, sizes: ("c5", ("c7", cfg["psi_A"])))
    cfg = {**DEFAULT, "psi_A": 50.0, "micro-raster size": "T"}
    out = study.measure(cfg, 7, SIZES, claims=frozenset({"C000-9", "C000-7", "C000-2"}))
    assert list(out) == ["C000-2", "C000-7", "C000-9"]
    assert out["C000-2"] == "_c2" and out["C000-9"] == "_c9" and out["C000-7"] == ("c7", 50.0)
    assert seen["_c2"][1:] == (7, SIZES)
    full = study.measure(cfg, 7, SIZES)
    assert list(full) == list(study.MEASURED_CLAIMS)
    assert full["C000-5"] == "c5"


def test_c000_4_reads_the_operation_count_or_the_timed_batch(monkeypatch):
    assert study.measure_cost(DEFAULT, 1, 4) == {
        "C000-4": {"reading": "operation count", "measured": operation_ratio(0)}
    }
    updated = {**DEFAULT, "v2 noise at": "updated estimate"}
    assert study.measure_cost(updated, 1, 4)["C000-4"]["measured"] == operation_ratio(1)
    assert operation_ratio(1) != operation_ratio(0)
    seen = []
    monkeypatch.setattr(study, "cost_ratio", lambda *a, **k: seen.append((a, k)) or "timed")
    timed = {**updated, "C000-4 cost measure": "CPU time", "C000-4 batch": "one trial"}
    assert study.measure_cost(timed, 5, 4, 30) == {"C000-4": {"reading": "CPU time", "measured": "timed"}}
    assert seen[-1] == ((4, 30, 5), {"noise_iterations": 1, "one_trial": True})
    study.measure_cost({**timed, "C000-4 batch": "all trials"}, 5, 4)
    assert seen[-1] == ((4, 200, 5), {"noise_iterations": 1, "one_trial": False})


def test_an_entry_missing_from_the_configuration_reads_the_papers_default_reading(table):
    def without(*names):
        return {k: v for k, v in DEFAULT.items() if k not in names}

    c2 = study._c2(without("C000-2 contrasts"), 3, SIZES)
    assert c2["reading"] == DEFAULT["C000-2 contrasts"] and len(c2["measured"]) == 3
    c5, _ = study._c5_c7(without("substantially determines", "C000-5 comparison"), 3, SIZES)
    assert c5["reading"] == DEFAULT["substantially determines"]
    assert list(c5["measured"]) == ["P=0.25", "P=0.9"]
    assert study.measure_cost(without("C000-4 cost measure"), 1, 4)["C000-4"] == {
        "reading": "operation count",
        "measured": operation_ratio(0),
    }


def test_measure_hands_each_claim_its_projected_configuration_and_measures_c000_5_and_7_only_when_asked(
    table, monkeypatch
):
    got = []
    monkeypatch.setattr(study, "_c5_c7", lambda cfg, seed, sizes: got.append((cfg, seed, sizes)) or ("c5", "c7"))
    monkeypatch.setattr(study, "_c2", lambda cfg, seed, sizes: cfg["micro-raster size"])
    cfg = {**DEFAULT, "substantially determines": EVERY_ABOVE, "micro-raster size": "T_u"}
    assert study.measure(cfg, 7, SIZES, claims=frozenset({"C000-2"})) == {"C000-2": "T_u"}
    assert got == []  # C000-5 and C000-7 not asked: not measured
    assert study.measure(cfg, 7, SIZES, claims=frozenset({"C000-7"})) == {"C000-7": "c7"}
    assert got[-1][0]["substantially determines"] == DEFAULT["substantially determines"]  # C000-7 does not read it
    assert got[-1][1:] == (7, SIZES)
    assert study.measure(cfg, 7, SIZES, claims=frozenset({"C000-5"})) == {"C000-5": "c5", "C000-7": "c7"}
    assert got[-1][0]["substantially determines"] == EVERY_ABOVE  # C000-5's own reading


def test_c000_6_over_the_grid_filter_is_the_filter_over_the_grid_filters_steady_error(table, monkeypatch):
    m = 3
    sizes = study.Sizes(psi_grid=(5.0, 20.0, 50.0), grid_trials=m, grid_points=11)
    n = sizes.n_steps + 1
    x = np.outer(np.arange(1.0, 6.0), np.linspace(0.0, 1.0, n))  # 5 runs' truth
    made = []

    def truth_paths(cfg, seed, sz):
        assert isinstance(cfg, dict) and seed == 3 and sz is sizes
        return x, "pulse", "xi", None

    def photon_samples(cfg, seed, scan, pulse, xi):
        assert seed == 3 and scan == study.operating_scan(cfg, PSI9, 0.9, sizes) and (pulse, xi) == ("pulse", "xi")
        k = {"Gaussian": 0.5, "Poisson counts": 0.25}[cfg["photon model"]] * (
            2.0 if cfg.get("background") != "stationary" else 1.0
        )
        return x * k + 0.1 * ({"per sample": 1.0}.get(cfg["sigma_sh"], 3.0))

    class Grid:
        def __init__(self, scan, message, half, points, phi):
            assert scan == study.operating_scan(now[0], PSI9, 0.9, sizes) and message == study.MESSAGE
            assert (half, points) == (0.5, 11) and np.array_equal(phi, study.switch_on_phases(3, sizes)[:m])

        def run(self, y, mean0, var0):
            assert y.shape[0] == m and (mean0, var0) == (0.0, pytest.approx(0.01))
            made.append(1)
            return SimpleNamespace(mean=y)

    monkeypatch.setattr(study, "truth_paths", truth_paths)
    monkeypatch.setattr(study, "photon_samples", photon_samples)
    monkeypatch.setattr(study, "grid_filter", Grid)
    monkeypatch.setattr(
        study, "filter_errors", lambda cfg, seed, sz, psi, p, filt, **k: {"steady": steady(psi, p, filt)[:4].repeat(2)}
    )
    cfg = {**DEFAULT, "potentially achievable": "grid filter", "contrast convention": "fixed background"}
    now = [cfg]
    got = study._c6(cfg, 3, sizes)
    w = sizes.window()
    g = ((x[:m] - (0.5 * x[:m] + 0.1)) ** 2)[:, w].mean(axis=1)  # each run's steady squared error of the grid filter
    a = steady(180.0, 0.9, "v2")[:4].repeat(2)[:m]
    assert got.value == pytest.approx(np.mean(a) / np.mean(g), rel=1e-12)
    assert study._c6({**cfg, "statistic": "median"}, 3, sizes).value == pytest.approx(np.median(a) / np.median(g))
    # the grid's runs are kept per data model, photon model, background and sigma_sh: each change recomputes them
    for change in ({"photon model": "Poisson counts"}, {"background": "drifting"}, {"sigma_sh": "unit bandwidth"}):
        before = len(made)
        now[0] = {**cfg, **change}
        other = study._c6(now[0], 3, sizes)
        assert len(made) == before + 1 and other.value != pytest.approx(got.value)
    now[0] = cfg
    study._c6(cfg, 3, sizes)
    assert len(made) == 4  # the default's grid runs read back


def test_c000_8_is_the_coarse_over_the_fine_steady_variance_minus_one_per_variant(monkeypatch):
    monkeypatch.setattr(study, "_MEMO", {})
    sizes = study.Sizes(dt_points=((20.0, 0.5), (5.0, 0.9)), dt_factor=4, dt_trials=3, dt_duration_T=3.0)
    nc = 61
    tc, tf = np.arange(nc) * 0.05, np.arange(4 * (nc - 1) + 1) * 0.0125
    xc, xf = np.outer([1.0, 2.0, 4.0], np.cos(tc)), np.outer([1.0, 3.0, 2.0], np.sin(tf) + 1)
    runs = []

    def two_rates(scan, message, factor, rng, trials, steps, score_at, draw_phase):
        psi, p = sizes.dt_points[len(runs) % 2]  # each point at its own psi_A
        assert scan == study.operating_scan(current[0], psi, p, sizes)
        assert (factor, trials, steps, score_at, draw_phase) == (4, 3, 60, "interval_end", True)
        assert message == study.cfg_message(current[0])
        runs.append(rng.random())
        return {
            "t_coarse": tc,
            "t_fine": tf,
            "x_coarse": xc,
            "x_fine": xf,
            "y_coarse": xc * 0.0,
            "y_fine": xf * 0.0,
            "scan_fine": "fine",
            "start": "phases",
        }

    def v1(s, message, y, d0, a, beta, g22, b, cs, phi):
        assert (d0, a, beta, g22, b, cs, phi) == (
            (0.2, 1.0),
            None,
            15.0,
            current[0]["G22"],
            None,
            study._cs(current[0]),
            "phases",
        )
        return (y + (0.5 if s == "fine" else 0.25),)

    def v2(s, message, y, d11, a, b, iterations, c, phi):
        assert (d11, a, b, c, phi) == (0.2, None, None, None, "phases")
        return (y + (0.75 if s == "fine" else 0.5) * (1 + iterations),)

    monkeypatch.setattr(study, "simulate_two_rates", two_rates)
    monkeypatch.setattr(study, "run_steps_variant1", v1)
    monkeypatch.setattr(study, "run_steps_variant2", v2)
    current = [DEFAULT]
    got = study._c8(DEFAULT, 3, sizes)
    assert list(got) == [
        "variant 1 at psi_A=20, P=0.5", "variant 2 at psi_A=20, P=0.5",
        "variant 1 at psi_A=5, P=0.9", "variant 2 at psi_A=5, P=0.9",
    ]  # fmt: skip
    assert runs[0] == np.random.default_rng([3, 8]).random()
    wc, wf = tc > 2.0, tf > 2.0

    def want(shift_c, shift_f):
        a = ((xc - shift_c) ** 2)[:, wc].mean(axis=1)
        b = ((xf - shift_f) ** 2)[:, wf].mean(axis=1)
        return ratio_ci(a, b)

    for name, (sc_, sf_) in (("variant 1", (0.25, 0.5)), ("variant 2", (0.5, 0.75))):
        r, e = want(sc_, sf_), got[f"{name} at psi_A=20, P=0.5"]
        assert (e.value, e.stderr, e.ci_low, e.ci_high) == pytest.approx(
            (r.value - 1, r.stderr, r.ci_low - 1, r.ci_high - 1)
        )
        assert (e.n, e.confidence, e.method) == (r.n, r.confidence, r.method)
    # variant 2's noise re-evaluated at the updated estimate, variant 1's literal signal-noise scale, another sigma_1
    for change in ({"v2 noise at": "updated estimate"}, {"signal-noise scale": CS_LITERAL}, {"sigma_1": "0.2 T"}):
        current[0] = {**DEFAULT, **change}
        before = len(runs)
        other = study._c8(current[0], 3, sizes)
        assert len(runs) > before
        if "v2 noise at" in change:
            r = want(1.0, 1.5)
            assert other["variant 2 at psi_A=20, P=0.5"].value == pytest.approx(r.value - 1)


def test_out_of_lock_is_above_the_lock_factor_squared_times_the_paper_starts_steady_mean_square(table):
    ref = np.mean(steady(20.0, 0.5, "v2"))  # the paper's start, the configuration's psi_A and contrast
    run = {"scans": ref * np.array([[30.0, 20.0, 1.0], [1.0, 5.0, 1.0], [3.0, 3.0, 1.0]])}
    t = study.acquired_at(DEFAULT, 3, SIZES, "v2", run)  # 25 x: only the first scan of run 0 is out
    np.testing.assert_array_equal(t, [1.0, 1.0, 1.0])
    t2 = study.acquired_at({**DEFAULT, "lock threshold": "2 x steady RMS"}, 3, SIZES, "v2", run)  # 4 x
    np.testing.assert_array_equal(t2, [2.0, 2.0, 1.0])
