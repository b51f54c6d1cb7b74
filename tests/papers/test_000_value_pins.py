"""Paper 000: the claim values pinned against independent computations at a small size.

Each claim's value is re-computed here from the study's raw outputs (per-run steady mean squared errors of each
filter at each operating point) or from the model's own simulator run by hand, with the reference point, the
statistic and the direction written out: a ratio to sigma_x^2* is the filter's mean square over the stationary
filter's on the same runs, C000-7's gap is the one-scan CRLB ratio at P = 0.9 (psi_A at P = 0.9 by the contrast
convention) minus that ratio with its interval ends swapped accordingly, and C000-8 is the coarse-step over the
fine-step steady variance minus one, both scored at their newest datum.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from tvtrack.papers.p000_dissector_ekf import study
from tvtrack.papers.p000_dissector_ekf.cost import run_steps_variant1, run_steps_variant2
from tvtrack.papers.p000_dissector_ekf.model import scan_at_snr, simulate_two_rates
from tvtrack.papers.p000_dissector_ekf.reference import scan_crlb
from tvtrack.papers.p000_dissector_ekf.register import REGISTER

DEFAULT = REGISTER.default()
SMALL = study.Sizes(
    n_trials=40,
    duration_T=6.0,
    window_T=3.0,
    contrast_grid=(0.0, 0.25, 0.5, 0.9),
    psi_grid=(5.0, 20.0),
    dt_points=((20.0, 0.5),),
    dt_factor=4,
    dt_trials=24,
    dt_duration_T=3.0,
)


def runs(cfg, psi, p, filt):
    return study.steady_runs(cfg, 3, SMALL, psi, p, filt)


@pytest.mark.parametrize("statistic", ["mean", "median"])
def test_ratio_to_star_is_the_statistic_of_variant_2_over_the_stationary_filter(statistic):
    cfg = {**DEFAULT, "statistic": statistic}
    a, b = runs(cfg, 20.0, 0.5, "v2"), runs(cfg, 20.0, 0.5, "stationary")
    f = np.mean if statistic == "mean" else np.median
    got = study.ratio_to_star(cfg, 3, SMALL, 0.5)
    assert got.value == pytest.approx(f(a) / f(b), rel=1e-12)
    assert got.value != pytest.approx({"mean": np.median, "median": np.mean}[statistic](a) / f(b), rel=1e-3)


@pytest.mark.parametrize("convention, factor", [("fixed N0", 1.0), ("fixed background", 9.0)])
def test_c5_c7_read_the_ratios_and_the_crlb_gap_at_p_09(convention, factor):
    # psi_A at P = 0.9 with psi_A = 20 at P = 0.5: fixed N0 keeps it, fixed background scales it by
    # (0.9 / 0.1) / (0.5 / 0.5) = 9
    cfg = {**DEFAULT, "contrast convention": convention}
    tagged, c7 = study._c5_c7(cfg, 3, SMALL)
    assert tagged["reading"] == "at P = 0.9"
    c5 = tagged["measured"]
    psi9 = 20.0 * factor
    r9 = np.mean(runs(cfg, psi9, 0.9, "v2")) / np.mean(runs(cfg, psi9, 0.9, "stationary"))
    assert c5["P=0.9"].value == pytest.approx(r9, rel=1e-12)
    assert c7["trend"][-1].value == pytest.approx(r9, rel=1e-12)
    assert c5["P=0.25"].value == pytest.approx(
        np.mean(runs(cfg, study.psi_at(20.0, 0.25, convention), 0.25, "v2"))
        / np.mean(runs(cfg, study.psi_at(20.0, 0.25, convention), 0.25, "stationary")),
        rel=1e-12,
    )
    # the measurement's own bound: the one-scan CRLB at P = 0.9 over that at P = 0, both at psi_A(0.9), each the
    # mean over the runs' 20 equally likely sample slots at switch-on
    phases = np.arange(20) * 0.05

    def bound(p):
        scan = scan_at_snr(psi9, p, 0.05, 0.5)
        return np.mean([scan_crlb(replace(scan, time_offset=scan.time_offset + phi)) for phi in phases])

    crlb = bound(0.9) / bound(0.0)
    assert 1.0 < crlb < 20.0  # the signal's own shot noise widens the one-scan bound
    gap = c7["measurement vs estimate"]
    assert gap.value == pytest.approx(crlb - r9, rel=1e-12)
    assert gap.ci_low == pytest.approx(crlb - c5["P=0.9"].ci_high, rel=1e-12)
    assert gap.ci_high == pytest.approx(crlb - c5["P=0.9"].ci_low, rel=1e-12)
    assert gap.ci_low <= gap.value <= gap.ci_high


def test_psi_at_follows_each_contrast_convention():
    assert study.psi_at(20.0, 0.9, "fixed N0") == 20.0
    assert study.psi_at(20.0, 0.9, "fixed background") == pytest.approx(180.0)
    assert study.psi_at(20.0, 0.75, "fixed total current") == pytest.approx(20.0 * (0.75 / 0.5) / np.sqrt(0.25 / 0.5))


def test_c8_is_the_coarse_over_fine_variance_minus_one_scored_at_the_newest_datum():
    got = study._c8(DEFAULT, 3, SMALL)
    scan = scan_at_snr(20.0, 0.5, 0.05, 0.5)
    d = simulate_two_rates(
        scan, study.MESSAGE, 4, np.random.default_rng([3, 8]), 24, 60, score_at="interval_end", draw_phase=True
    )  # 3 T at dt = 0.05 T; the steady window is the last third; each run's switch-on phase drawn after the rest
    wc, wf = d["t_coarse"] > 2.0, d["t_fine"] > 2.0

    def v2(s, y):
        return run_steps_variant2(s, study.MESSAGE, y, 0.2, None, None, 0, start=d["start"])[0]

    def v1(s, y):
        return run_steps_variant1(s, study.MESSAGE, y, (0.2, 1.0), None, 15.0, "paper", start=d["start"])[0]

    for name, run in (("variant 2", v2), ("variant 1", v1)):
        a = ((d["x_coarse"] - run(scan, d["y_coarse"])) ** 2)[:, wc].mean(axis=1)
        b = ((d["x_fine"] - run(d["scan_fine"], d["y_fine"])) ** 2)[:, wf].mean(axis=1)
        assert got[f"{name} at psi_A=20, P=0.5"].value == pytest.approx(a.mean() / b.mean() - 1, rel=1e-9, abs=1e-12)
