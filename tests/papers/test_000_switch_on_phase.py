"""Paper 000: where the sweep is when the filter switches on. The paper does not say, so each run draws its phase
uniform over the scan interval from the run's seeded generator; the truth's pulse and every filter's model of it
use that phase."""

import numpy as np
import pytest
from scipy import stats

from tvtrack import jit
from tvtrack.papers.p000_dissector_ekf import lock_loss, studies, study
from tvtrack.papers.p000_dissector_ekf.cost import run_steps_variant1, run_steps_variant2
from tvtrack.papers.p000_dissector_ekf.ekf import run_variant1, run_variant2, variant1_filter, variant2_filter
from tvtrack.papers.p000_dissector_ekf.model import (
    GaussMarkovMessage,
    draw_noises,
    samples_from_pulse,
    scan_at_snr,
    simulate_two_rates,
    truth_and_pulse,
)
from tvtrack.papers.p000_dissector_ekf.reference import pcrlb_variance, scan_crlb
from tvtrack.papers.p000_dissector_ekf.register import REGISTER

DEFAULT = REGISTER.default()
MSG = GaussMarkovMessage(0.1, 0.15)
SMALL = study.Sizes(n_trials=60, duration_T=6.0, window_T=2.0, substeps=2, acquire_by_T=2.0)


def _peak_phase(x, pulse, dt):
    """Each run's switch-on phase read back from its first scan: the pulse peaks at scan phase 1/2 + x, i.e. at the
    sample time (k - 1/2) dt = (1/2 + x - phase) mod 1."""
    k = np.argmax(pulse[:, : int(round(1 / dt))], axis=1) + 1
    rows = np.arange(len(k))
    return np.mod(0.5 + x[rows, k] - (k - 0.5) * dt, 1.0)


def _circular_distance(a, b):
    d = np.mod(a - b, 1.0)
    return np.minimum(d, 1.0 - d)


def test_each_run_draws_its_switch_on_phase_uniform_over_the_scan_after_the_other_draws():
    noises = draw_noises(np.random.default_rng(5), 4000, 3, 2)
    rng = np.random.default_rng(5)  # the same generator, replayed in the documented order
    for key, shape in (
        ("x0", (4000,)),
        ("w", (4000, 3)),
        ("xi", (4000, 3)),
        ("init", (4000, 2)),
        ("w_sub", (4000, 12)),
    ):
        np.testing.assert_array_equal(noises[key], rng.standard_normal(shape))
    np.testing.assert_array_equal(noises["phase"], rng.uniform(0.0, 1.0, 4000))
    assert stats.kstest(noises["phase"], "uniform").pvalue > 0.01
    assert 0.0 <= noises["phase"].min() and noises["phase"].max() < 1.0


def test_the_studys_runs_start_at_their_own_drawn_phases():
    """The study's truth: each run's first pulse peaks where its drawn phase puts it. With one phase for every run
    (the sweep at 0 whenever a filter switches on) every run's read-back phase is within dt of 0."""
    x, pulse, _, _ = study.truth_paths(DEFAULT, 3, SMALL)
    got = _peak_phase(x, pulse, SMALL.dt)
    assert 0.3 < np.mean(_circular_distance(got, 0.0) > 0.25) < 0.7  # half the runs start in the far half
    assert np.all(
        _circular_distance(got, study.switch_on_phases(3, SMALL)) < 0.05
    )  # dt/2, the motion, a truncated pulse
    assert len(np.unique(np.round(study.switch_on_phases(3, SMALL), 6))) >= 15  # of the 20 sample slots
    other = study.Sizes(n_trials=60, duration_T=6.0, window_T=2.0, substeps=2, acquire_by_T=2.0, lock_factor=4.0)
    np.testing.assert_array_equal(
        study.switch_on_phases(3, other), study.switch_on_phases(3, SMALL)
    )  # a seed's runs, not a reading's
    assert not np.allclose(study.switch_on_phases(4, SMALL), study.switch_on_phases(3, SMALL))


def test_the_studys_phases_sit_on_the_sample_clock_and_reach_every_slot():
    """The sample clock is synchronous with the sweep (T = 20 dt): a run switches on at one of the scan's 20 sample
    slots, so every sample's interval ends at or before the flyback, as the filters' model of a sample assumes."""
    sizes = study.Sizes(n_trials=400, duration_T=6.0, window_T=2.0, substeps=2)
    start = study.switch_on_phases(8, sizes)
    slots = start / sizes.dt
    np.testing.assert_allclose(slots, np.round(slots), atol=1e-9)
    assert set(np.round(slots).astype(int)) == set(range(20))
    np.testing.assert_array_equal(study.phase_nodes(sizes), np.arange(20) * sizes.dt)


def test_a_phase_between_sample_slots_puts_one_sample_per_scan_across_the_flyback():
    """Why the phase is drawn on the sample clock: off it, the interval that holds the flyback averages the pulse's
    two far tails, which the filters' model (the pulse at the interval centre) does not describe."""
    still = GaussMarkovMessage(1e-9, 0.15)
    noises = {**draw_noises(np.random.default_rng(1), 1, 40, 8), "x0": np.full(1, 0.1 / 1e-9)}
    geometry = scan_at_snr(1.0, 0.0, 0.05)
    gaps = {}
    for start in (0.35, 0.375):  # on the clock; half a sample off it
        x, pulse = truth_and_pulse(geometry, still, noises, "integrated", "interval_centre", None, start)
        gaps[start] = np.sort(np.abs(pulse[0] - geometry.shape(x[0, 1:], np.arange(1, 41), start)))
    assert gaps[0.35][-1] < 0.002  # the midpoint rule's second-order error only
    assert gaps[0.375][-3] < 0.002 and gaps[0.375][-2] > 0.05  # two scans, one sample each across the flyback


def _data(start, psi=20.0, p=0.5, n=12, n_steps=120, seed=7):
    noises = draw_noises(np.random.default_rng(seed), n, n_steps, 2)
    x, pulse = truth_and_pulse(scan_at_snr(1.0, 0.0, 0.05), MSG, noises, "integrated", "interval_end", None, start)
    scan = scan_at_snr(psi, p, 0.05)
    return scan, x, samples_from_pulse(scan, pulse, noises["xi"])


def test_a_switch_on_phase_of_whole_samples_is_the_phase_0_data_moved_by_those_samples():
    """The truth's sweep: starting j samples into the sweep, sample k sees the pulse phase-0 sample k + j sees (a
    still object, so only the phase moves)."""
    still = GaussMarkovMessage(1e-9, 0.15)
    noises = draw_noises(np.random.default_rng(1), 3, 60, 2)
    base = truth_and_pulse(scan_at_snr(1.0, 0.0, 0.05), still, noises, "integrated", "interval_end")[1]
    moved = truth_and_pulse(scan_at_snr(1.0, 0.0, 0.05), still, noises, "integrated", "interval_end", None, 0.35)[1]
    np.testing.assert_allclose(moved[:, :-7], base[:, 7:], atol=1e-12)
    assert np.max(np.abs(moved - base)) > 0.5


@pytest.mark.parametrize("compiled", [False, True])
def test_the_step_runners_and_the_ekf_filters_agree_under_per_run_phases(compiled):
    if compiled and not jit.enabled():
        pytest.skip("numba is not enabled")
    start = np.random.default_rng(2).uniform(0.0, 1.0, 12)
    scan, x, y = _data(start)
    e2 = run_steps_variant2(scan, MSG, y, 0.2, None, None, 0, compiled, start)[0]
    np.testing.assert_allclose(e2, run_variant2(variant2_filter(scan, MSG, None, 0, start), y, 0.2)[0], atol=1e-9)
    e1 = run_steps_variant1(scan, MSG, y, (0.2, 1.0), None, 15.0, "paper", compiled, "consistent", start)[0]
    f1 = variant1_filter(scan, MSG, 15.0, "consistent", "paper", start)
    np.testing.assert_allclose(e1, run_variant1(f1, y, (0.2, 1.0))[0], atol=1e-9)


def test_a_filter_told_another_phase_than_the_truths_loses_the_target():
    """The truth and the filters read the phase the same way: told the runs' phases, variant 2 tracks to about
    2 % of T; told phase 0 on the same data, it does not."""
    start = np.random.default_rng(3).uniform(0.25, 0.75, 12)
    scan, x, y = _data(start, n_steps=200)
    right = run_steps_variant2(scan, MSG, y, 0.2, start=start)[0]
    wrong = run_steps_variant2(scan, MSG, y, 0.2)[0]
    rms = lambda e: float(np.sqrt(np.mean(((x - e) ** 2)[:, -60:])))  # noqa: E731
    assert rms(right) < 0.03
    assert rms(wrong) > 3 * rms(right)


def test_the_pcrlb_over_phases_is_the_mean_of_each_phases_bound_and_the_steady_bound_does_not_depend_on_it():
    scan = scan_at_snr(20.0, 0.9, 0.05)
    each = [pcrlb_variance(scan, MSG, 200, "interval_end", phi) for phi in (0.0, 0.5)]
    np.testing.assert_allclose(pcrlb_variance(scan, MSG, 200, "interval_end", np.array([0.0, 0.5])), np.mean(each, 0))
    # switched on at the pulse's peak, the first samples see the flat top (no information on x): twice the bound
    assert each[1][2] / each[0][2] > 1.8
    np.testing.assert_allclose(each[0][-40:].mean(), each[1][-40:].mean(), rtol=1e-9)  # two whole scans


def test_one_scans_bound_depends_on_the_phase_within_a_sample_and_is_averaged_over_it():
    scan = scan_at_snr(20.0, 0.9, 0.05)
    half, whole = scan_crlb(scan, 0.025), scan_crlb(scan, 0.3)  # half a sample, six samples
    assert whole == pytest.approx(scan_crlb(scan), rel=1e-12)  # the same phases, in another order
    assert abs(half / scan_crlb(scan) - 1) > 1e-3  # the scan truncates the pulse's tails
    assert scan_crlb(scan, np.array([0.0, 0.025])) == pytest.approx((scan_crlb(scan) + half) / 2, rel=1e-12)


def test_the_discretisation_check_draws_one_phase_per_run_for_both_rates():
    scan = scan_at_snr(20.0, 0.5, 0.05)
    fixed = simulate_two_rates(scan, MSG, 4, np.random.default_rng(8), 10, 40, "interval_end")
    drawn = simulate_two_rates(scan, MSG, 4, np.random.default_rng(8), 10, 40, "interval_end", draw_phase=True)
    np.testing.assert_array_equal(fixed["start"], 0.0)
    np.testing.assert_array_equal(drawn["x_fine"], fixed["x_fine"])  # the phase is drawn after the rest
    assert np.ptp(drawn["start"]) > 0.3
    est = run_steps_variant2(scan, MSG, drawn["y_coarse"], 0.2, start=drawn["start"])[0]
    fine = run_steps_variant2(drawn["scan_fine"], MSG, drawn["y_fine"], 0.2, start=drawn["start"])[0]
    slots = drawn["start"] / 0.05
    np.testing.assert_allclose(slots, np.round(slots), atol=1e-9)  # on the coarse (and so the fine) sample clock
    rms = lambda e: np.median(np.sqrt(np.mean(e**2, axis=1)))  # noqa: E731  (the median run: one may lose lock)
    assert rms((drawn["x_coarse"] - est)[:, -20:]) < 0.03
    assert rms((drawn["x_fine"] - fine)[:, -80:]) < 0.03


def test_acquisition_from_an_offset_reads_each_runs_phase():
    """The pull-in study's runs are the claims' runs: from a zero offset the acquisition runs are the stationary
    ones with the truth at 0, each at its own phase (a filter told phase 0 loses a share of them)."""
    acq = studies.acquisition_vs_offset(DEFAULT, 4, SMALL, [-0.3, 0.3])
    x, pulse, xi, _ = study.truth_paths(DEFAULT, 4, SMALL, 0.3)
    scan = study.operating_scan(DEFAULT, 20.0, DEFAULT["contrast"], SMALL)
    y = study.photon_samples(DEFAULT, 4, scan, pulse, xi)
    est = run_steps_variant2(scan, study.MESSAGE, y, 0.2, start=study.switch_on_phases(4, SMALL))[0]
    run = study.filter_errors(DEFAULT, 4, SMALL, 20.0, DEFAULT["contrast"], "v2", offset=0.3)
    np.testing.assert_allclose(run["curve"], ((x - est) ** 2).mean(axis=0), rtol=1e-9)
    assert acq["v2"]["late"][1].value <= 0.2


def test_c000_2_over_the_runs_in_lock_drops_the_runs_lost_at_switch_on():
    """C000-2's RMS error over all runs carries the runs lost at switch-on (3 of these 100 in each filter); over the
    runs in lock it is the RMS of the others, about 2 % of T, and the lock report covers the claim."""
    sizes = study.Sizes(n_trials=100, duration_T=8.0, window_T=3.0, substeps=2, psi_grid=(5.0, 20.0))
    m = lock_loss.measure_in_lock(study.measure, DEFAULT, 1, sizes, "C000-2")
    assert m["lost_runs"] == 3 and m["runs"] == 100
    for name, filt, p in (("P=0", "stationary", 0.0), ("P=0.5 variant 2", "v2", 0.5)):
        runs = study.steady_runs(DEFAULT, 1, sizes, 20.0, p, filt)
        kept = runs[~lock_loss.lost(runs, sizes.lock_factor)]
        assert m["all"]["measured"][name].value == pytest.approx(np.sqrt(runs.mean()), rel=1e-9)
        assert m["in lock"]["measured"][name].value == pytest.approx(np.sqrt(kept.mean()), rel=1e-9)
        assert 0.015 < m["in lock"]["measured"][name].value < 0.025 < m["all"]["measured"][name].value
    assert "C000-2" in lock_loss.LOCK_CLAIMS
