"""Claim-level pins of paper 000's default data path: each test kills a planted bug that no
earlier test caught, by checking what a claim rests on against an independent small computation.

Mutations killed (each seen failing with the mutation planted):
- the sample noise law with P instead of P/(1-P) (every sample of the notebook);
- the Fisher information's variance term (dropped, halved or doubled) and the scan CRLB at psi_A = 2, P = 0.9;
- sigma_x^2* from another filter (the filter ignoring the signal noise, or the P > 0 data);
- a study function feeding a claim the wrong inputs (C000-7's gap at another P, C000-2's P = 0.5 part on P = 0
  data, C000-3 / C000-9 / C000-5 on another filter or point).
"""

import numpy as np
import pytest

from tvtrack.papers.p000_dissector_ekf import study
from tvtrack.papers.p000_dissector_ekf.ekf import run_variant1, run_variant2, variant1_filter, variant2_filter
from tvtrack.papers.p000_dissector_ekf.model import (
    GaussMarkovMessage,
    draw_noises,
    on_sample_clock,
    samples_from_pulse,
    scan_at_snr,
    truth_and_pulse,
)
from tvtrack.papers.p000_dissector_ekf.reference import fisher_information, scan_crlb
from tvtrack.papers.p000_dissector_ekf.register import REGISTER

MSG = GaussMarkovMessage(0.1, 0.15)
SMALL = study.Sizes(
    n_trials=24,
    duration_T=6.0,
    window_T=2.0,
    substeps=2,
    psi_grid=(5.0, 50.0),
    contrast_grid=(0.0, 0.5, 0.9),
    dt_points=((20.0, 0.5),),
    dt_factor=2,
    dt_trials=20,
    dt_duration_T=4.0,
    grid_trials=10,
    grid_points=61,
    acquire_by_T=2.0,
)
DEFAULT = REGISTER.default()


def test_samples_carry_the_noise_variance_of_eq_2_at_high_contrast():
    """Kills: the truth noise law with P instead of P/(1-P). With unit draws, a sample minus its mean is the
    noise standard deviation sqrt(N0 (1 + P/(1-P) S) / dt), N0 = dt (A / psi_A)^2 (per-sample sigma_sh)."""
    psi, p, dt = 20.0, 0.9, 0.05
    scan = scan_at_snr(psi, p, dt)
    pulse = np.array([[0.0, 0.3, 0.7, 1.0]])
    y = samples_from_pulse(scan, pulse, np.ones_like(pulse))
    n0 = dt / psi**2
    closed = np.sqrt(n0 * (1.0 + 9.0 * pulse) / dt)  # P / (1 - P) = 9 at P = 0.9
    np.testing.assert_allclose(y[:, 1:] - pulse, closed, rtol=1e-12)
    assert closed[0, -1] / closed[0, 0] == pytest.approx(np.sqrt(10.0))


def test_the_default_data_path_draws_samples_with_the_closed_form_noise_law():
    """The same law where the notebook's samples are made (study's default path, P = 0.9): the residual over the
    stored unit draws is the closed-form standard deviation of each sample's mean pulse."""
    x, pulse, xi, _ = study.truth_paths(DEFAULT, 11, SMALL)
    scan = study.operating_scan(DEFAULT, 20.0, 0.9, SMALL)
    y = study.photon_samples(DEFAULT, 11, scan, pulse, xi)
    sd = np.sqrt((0.05 / 400.0) * (1.0 + 9.0 * pulse) / 0.05)
    np.testing.assert_allclose((y[:, 1:] - pulse) / sd, xi, rtol=1e-9, atol=1e-12)


def _fisher_by_quadrature(scan, x, k, h=1e-5):
    """J(x) = E[(d/dx log p(z | x))^2] by Gauss-Hermite quadrature over z and a central difference in x: no use
    of the closed form's terms."""
    nodes, weights = np.polynomial.hermite_e.hermegauss(60)
    mu = lambda s: scan.amplitude * scan.shape(s, k)
    var = lambda s: scan.sample_variance(s, k)
    z = mu(x) + np.sqrt(var(x)) * nodes

    def logp(s):
        return -0.5 * (z - mu(s)) ** 2 / var(s) - 0.5 * np.log(var(s))

    score = (logp(x + h) - logp(x - h)) / (2 * h)
    return float(np.sum(weights * score**2) / np.sqrt(2 * np.pi))


@pytest.mark.parametrize("x, k", [(0.0, 8), (0.03, 10), (-0.05, 12), (0.1, 7)])
def test_fisher_information_at_low_snr_and_high_contrast_matches_quadrature(x, k):
    """Kills: the variance term dropped, halved, doubled or without P/(1-P). At psi_A = 2, P = 0.9 the variance
    term is not negligible (checked), so the total must match the score's second moment."""
    scan = scan_at_snr(2.0, 0.9, 0.05)
    total, mean_part = fisher_information(scan, x, k)
    assert (total - mean_part) / total > 0.3  # the term the mutations touch carries a third of the information
    assert float(total) == pytest.approx(_fisher_by_quadrature(scan, x, k), rel=1e-6)


def test_scan_crlb_at_low_snr_and_high_contrast_is_the_inverse_summed_quadrature_information():
    scan = scan_at_snr(2.0, 0.9, 0.05)
    independent = 1.0 / sum(_fisher_by_quadrature(scan, 0.0, k) for k in range(1, 21))
    assert scan_crlb(scan) == pytest.approx(independent, rel=1e-6)
    mean_only = 1.0 / sum(float(fisher_information(scan, 0.0, k)[1]) for k in range(1, 21))
    assert mean_only > 1.4 * independent  # the variance term's share: a dropped term moves the bound by > 40 %


# ---------------------------------------------------------------- independent small computation of the inputs


def _independent_steady(seed, psi, p, filt, cfg=DEFAULT, sizes=SMALL):
    """Per-run steady mean squared error of one filter, computed from the model and filter functions alone:
    ``filt`` "v1", "v2", or "star" (variant 2 with P = 0 on P = 0 data); each run's sweep starts at its drawn
    phase (the truth's and the filter's)."""
    noises = draw_noises(np.random.default_rng(seed), sizes.n_trials, sizes.n_steps, sizes.substeps)
    score = "interval_centre" if cfg["scoring time"] == "interval centre" else "interval_end"
    phi = on_sample_clock(noises["phase"], sizes.dt)  # the run's sample slot
    x, pulse = truth_and_pulse(scan_at_snr(1.0, 0.0, sizes.dt, 0.5), MSG, noises, "integrated", score, None, phi)
    scan = scan_at_snr(psi, 0.0 if filt == "star" else p, sizes.dt, 0.5)
    y = samples_from_pulse(scan, pulse, noises["xi"])
    if filt == "v1":
        est = run_variant1(variant1_filter(scan, MSG, 15.0, "consistent", "paper", phi), y, (0.2, 1.0))[0]
    else:
        est = run_variant2(variant2_filter(scan, MSG, None, 0, phi), y, 0.2)[0]
    k = np.arange(sizes.n_steps + 1)
    window = k * sizes.dt > sizes.duration_T - sizes.window_T
    return ((x - est) ** 2)[:, window].mean(axis=1)


@pytest.fixture(scope="module")
def measured():
    study._MEMO.clear()
    return study.measure(DEFAULT, 21, SMALL)


def test_sigma_x2_star_is_variant_2_on_stationary_noise_data(measured):
    """Kills: sigma_x^2* from the filter ignoring the signal noise on P > 0 data, or from variant 1: C000-5's
    ratio at P = 0.9 (and C000-7's at 0.5) is the independent v2 error over the independent stationary error on the same runs."""
    star = _independent_steady(21, 20.0, 0.9, "star")
    ratio = _independent_steady(21, 20.0, 0.9, "v2").mean() / star.mean()
    assert measured["C000-5"]["measured"]["P=0.9"].value == pytest.approx(ratio, rel=1e-9)
    half = _independent_steady(21, 20.0, 0.5, "v2").mean() / star.mean()  # P = 0.5: C000-7's trend only
    assert measured["C000-7"]["trend"][list(SMALL.contrast_grid).index(0.5)].value == pytest.approx(half, rel=1e-9)
    np.testing.assert_allclose(study.steady_runs(DEFAULT, 21, SMALL, 20.0, 0.9, "stationary"), star, rtol=1e-9)


def test_c000_7_gap_is_the_crlb_ratio_at_p09_minus_the_estimate_ratio_at_p09(measured):
    """Kills: C000-7's gap taken at another P (its CRLB or its estimate ratio)."""
    from dataclasses import replace

    def bound(p):  # the one-scan bound over the runs' 20 sample slots
        scan = scan_at_snr(20.0, p, SMALL.dt)
        return np.mean([scan_crlb(replace(scan, time_offset=scan.time_offset + 0.05 * i)) for i in range(20)])

    crlb = bound(0.9) / bound(0.0)
    r9 = _independent_steady(21, 20.0, 0.9, "v2").mean() / _independent_steady(21, 20.0, 0.9, "star").mean()
    assert measured["C000-7"]["measurement vs estimate"].value == pytest.approx(crlb - r9, rel=1e-9)
    trend = [e.value for e in measured["C000-7"]["trend"]]
    star = _independent_steady(21, 20.0, 0.0, "star").mean()
    expect = [_independent_steady(21, 20.0, p, "v2").mean() / star for p in SMALL.contrast_grid]
    np.testing.assert_allclose(trend, expect, rtol=1e-9)


def test_c000_2_parts_are_the_rms_errors_of_their_own_contrast_and_filter(measured):
    """Kills: C000-2's P = 0.5 parts measured on P = 0 data (or the P = 0 part on P = 0.5 data)."""
    got = measured["C000-2"]["measured"]
    assert got["P=0"].value == pytest.approx(np.sqrt(_independent_steady(21, 20.0, 0.0, "star").mean()), rel=1e-9)
    for name, filt in (("P=0.5 variant 1", "v1"), ("P=0.5 variant 2", "v2")):
        rms = np.sqrt(_independent_steady(21, 20.0, 0.5, filt).mean())
        assert got[name].value == pytest.approx(rms, rel=1e-9)
    assert abs(got["P=0.5 variant 2"].value / got["P=0"].value - 1) > 1e-3  # the two data sets differ here


def test_c000_3_and_c000_9_read_their_own_filters_and_points(measured):
    """Kills: C000-3's ratio or C000-9's curve taken from another filter or another operating point."""
    v1 = _independent_steady(21, 20.0, 0.9, "v1").mean()
    v2 = _independent_steady(21, 20.0, 0.9, "v2").mean()
    assert measured["C000-3"]["measured"]["measured"]["P=0.9"].value == pytest.approx(v1 / v2, rel=1e-9)
    # C000-3 (card): "Ratio sigma_x^2(v1)/sigma_x^2(v2) in [0.8, 1.25]" over the psi_A grid too: each Fig. 2 part
    # (psi_A of the grid at the register's contrast P = 0.5) is variant 1 over variant 2, never its inverse (the band
    # is symmetric on the log scale, so only the number tells the two apart)
    for psi in SMALL.psi_grid:
        ratio = _independent_steady(21, psi, 0.5, "v1").mean() / _independent_steady(21, psi, 0.5, "v2").mean()
        assert measured["C000-3"]["measured"]["measured"][f"psi_A={psi:g}"].value == pytest.approx(ratio, rel=1e-9)
        assert abs(np.log(ratio)) > 1e-3  # v1 / v2 and v2 / v1 differ here
    for v, filt in ((1, "v1"), (2, "v2")):
        expect = [_independent_steady(21, psi, 0.5, filt).mean() for psi in SMALL.psi_grid]
        np.testing.assert_allclose([e.value for e in measured["C000-9"][f"variant {v}"]], expect, rtol=1e-9)


def test_c000_6_readings_are_their_filter_over_their_reference(measured):
    """Kills: C000-6's reading taken from another filter or another reference (the PCRLB at another P, the
    ignoring filter replaced by variant 2)."""
    from tvtrack.papers.p000_dissector_ekf.cost import run_steps_variant2
    from tvtrack.papers.p000_dissector_ekf.reference import pcrlb_variance

    star = _independent_steady(21, 20.0, 0.9, "star").mean()
    v2 = _independent_steady(21, 20.0, 0.9, "v2")
    assert measured["C000-6"].value == pytest.approx(v2.mean() / star, rel=1e-9)
    window = np.arange(SMALL.n_steps + 1) * SMALL.dt > SMALL.duration_T - SMALL.window_T
    scan = scan_at_snr(20.0, 0.9, SMALL.dt)
    phases = np.arange(20) * 0.05  # the bound over the runs' 20 equally likely sample slots
    bound = np.mean([pcrlb_variance(scan, MSG, SMALL.n_steps, "interval_end", phi) for phi in phases], 0)[window].mean()
    pcrlb = study.measure({**DEFAULT, "potentially achievable": "PCRLB"}, 21, SMALL)["C000-6"]
    assert pcrlb.value == pytest.approx(v2.mean() / bound, rel=1e-9)
    noises = draw_noises(np.random.default_rng(21), SMALL.n_trials, SMALL.n_steps, SMALL.substeps)
    phi = on_sample_clock(noises["phase"], SMALL.dt)
    x, pulse = truth_and_pulse(scan_at_snr(1.0, 0.0, SMALL.dt), MSG, noises, "integrated", "interval_end", None, phi)
    y = samples_from_pulse(scan, pulse, noises["xi"])
    est = run_steps_variant2(scan, MSG, y, 0.2, None, 0.0, start=phi)[0]
    ignoring = ((x - est) ** 2)[:, window].mean()
    got = study.measure({**DEFAULT, "C000-6 filter": "ignoring the signal noise"}, 21, SMALL)["C000-6"]
    assert got.value == pytest.approx(ignoring / star, rel=1e-9)


def test_c000_1_share_is_the_runs_out_of_lock_after_the_acquisition_time():
    """Kills: C000-1's share from another filter, threshold or time: a run is late when a scan from acquire_by_T on
    has a mean squared error above (the reading's factor)^2 times the filter's steady mean squared error; psi_A = 2
    and the strict reading, a factor 2, where some runs are late."""
    from dataclasses import replace

    from tvtrack.papers.p000_dissector_ekf.cost import run_steps_variant2

    sizes = replace(SMALL, acquire_by_T=1.0)  # here the share changes from one scan to the next

    noises = draw_noises(np.random.default_rng(21), SMALL.n_trials, SMALL.n_steps, SMALL.substeps)
    phi = on_sample_clock(noises["phase"], SMALL.dt)
    x, pulse = truth_and_pulse(scan_at_snr(1.0, 0.0, SMALL.dt), MSG, noises, "integrated", "interval_end", None, phi)
    scan = scan_at_snr(2.0, 0.5, SMALL.dt)
    y = samples_from_pulse(scan, pulse, noises["xi"])
    sq = (x - run_steps_variant2(scan, MSG, y, 0.2, start=phi)[0]) ** 2
    per_scan = sq[:, 1:].reshape(SMALL.n_trials, -1, 20).mean(axis=2)
    threshold = 2.0**2 * _independent_steady(21, 2.0, 0.5, "v2").mean()
    late = (per_scan[:, 1:] > threshold).any(axis=1).mean()
    got = study._c1({**DEFAULT, "psi_A": 2.0, "lock threshold": "2 x steady RMS"}, 21, sizes)
    assert got["reading"] == "90 % of runs acquired"
    assert got["measured"]["variant 2"].value == pytest.approx(late, abs=1e-12)
    lower, later = (
        (per_scan[:, 1:] > threshold / 4).any(axis=1).mean(),
        (per_scan[:, 2:] > threshold).any(axis=1).mean(),
    )
    assert lower > late > later > 0  # the threshold and the time matter on these runs (the test is not vacuous)


def _independent_v2_scans(seed, psi, p, truth_start=None, sizes=SMALL):
    """Variant 2 from the paper's start (estimate 0, D11(0) = 0.2) on runs made from the model's functions alone:
    each scan's mean squared error per run (n_trials, n_scans; scan j holds the samples in (j T, (j + 1) T]) and the
    per-run steady mean squared error. ``truth_start``: None (the truth from its stationary law N(0, sigma_1^2)) or a
    map from the run's standard normal draw to its starting coordinate (T)."""
    noises = draw_noises(np.random.default_rng(seed), sizes.n_trials, sizes.n_steps, sizes.substeps)
    if truth_start is not None:
        noises = {**noises, "x0": truth_start(noises["x0"]) / MSG.sigma}
    phi = on_sample_clock(noises["phase"], sizes.dt)
    x, pulse = truth_and_pulse(scan_at_snr(1.0, 0.0, sizes.dt), MSG, noises, "integrated", "interval_end", None, phi)
    scan = scan_at_snr(psi, p, sizes.dt)
    y = samples_from_pulse(scan, pulse, noises["xi"])
    from tvtrack.papers.p000_dissector_ekf.cost import run_steps_variant2

    sq = (x - run_steps_variant2(scan, MSG, y, 0.2, start=phi)[0]) ** 2
    per_scan = sq[:, 1:].reshape(sizes.n_trials, -1, sizes.steps_per_scan).mean(axis=2)
    window = np.arange(sizes.n_steps + 1) * sizes.dt > sizes.duration_T - sizes.window_T
    return per_scan, sq[:, window].mean(axis=1), x[:, 0]


def test_c000_1_ensemble_reading_is_the_scan_ending_at_5_t_over_the_steady_variance():
    """C000-1 (card): "sigma_x^2 within 10 % of its steady state after <= 5 T". Under the register's reading
    "ensemble mean within 10 %" each variant's part is the ensemble error variance over the scan that ends at 5 T
    (the samples in (4 T, 5 T]) over the steady error variance of the same runs; not the scan after it."""
    from dataclasses import replace

    from tvtrack.papers.p000_dissector_ekf.readings import ENSEMBLE_MEAN

    sizes = replace(SMALL, acquire_by_T=5.0)
    per_scan, steady, _ = _independent_v2_scans(21, 20.0, 0.5)
    got = study._c1({**DEFAULT, "convergence criterion": ENSEMBLE_MEAN}, 21, sizes)
    assert got["reading"] == ENSEMBLE_MEAN
    expect = per_scan[:, 4].mean() / steady.mean()
    assert got["measured"]["variant 2"].value == pytest.approx(expect, rel=1e-9)
    assert per_scan[:, 5].mean() / steady.mean() != pytest.approx(expect, rel=1e-3)  # the next scan differs


def test_c000_1_runs_start_the_object_where_the_initial_position_reading_says():
    """C000-1 is measured from the paper's start, 'the image is within the micro-raster' (its motivation of
    D11(0) = 0.2), which the register reads two ways ("initial position"): the message's own law N(0, sigma_1^2)
    (default), or anywhere in the raster with equal probability, uniform over [-T/2, T/2]. Under each reading the
    measured runs start the object there (ensemble reading, the scan ending at 2 T over the steady variance)."""
    from scipy.stats import norm

    from tvtrack.papers.p000_dissector_ekf.readings import ENSEMBLE_MEAN

    cfg = {**DEFAULT, "convergence criterion": ENSEMBLE_MEAN}
    uniform = {**cfg, "initial position": "uniform in the micro-raster"}
    got = {name: study._c1(c, 21, SMALL)["measured"] for name, c in (("default", cfg), ("uniform", uniform))}
    for name, start in (("default", None), ("uniform", lambda z: norm.cdf(z) - 0.5)):
        per_scan, steady, x0 = _independent_v2_scans(21, 20.0, 0.5, start)
        assert got[name]["variant 2"].value == pytest.approx(per_scan[:, 1].mean() / steady.mean(), rel=1e-9)
        if name == "uniform":  # the object anywhere in the raster: within +-T/2, spread T / sqrt(12)
            assert np.abs(x0).max() <= 0.5 and x0.std() > 2 * MSG.sigma
    for v in (1, 2):  # the start reaches the measurement of both variants
        assert got["uniform"][f"variant {v}"].value != pytest.approx(got["default"][f"variant {v}"].value, rel=1e-3)
