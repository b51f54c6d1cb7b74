"""000's register read into one filter run (``study.filter_errors`` and the world it draws).

Each filter is handed what the paper gives it (Martyshevsky 1995, "Results of the modelling": ``D(0) = diag(0.2,
1)``, ``beta_0 T = 15``, a pulse of ``T_u = T/2``, the message ``sigma_1 = 0.1 T``, ``alpha_0 T = 0.15``) and what
the register's readings change: the scan's sigma_sh convention, variant 1's G22 form and signal-noise scale,
variant 2's noise evaluation, the filter ignoring the signal noise (variant 2 assuming P = 0), the stationary
reference (variant 2 on P = 0 data), a random initial estimate of N(0, D(0)), the truth's start, the sample model,
the scoring time, the manoeuvre, the photon model and the drifting background. The runs are memoised on the entries
each filter reads: an entry a filter does not read returns the same run, one it reads runs it again. The filters
themselves are replaced by spies that record their arguments and return known estimates, so the summaries are
checked against sums written out here.
"""

import numpy as np
import pytest

from tvtrack.papers.p000_dissector_ekf import REGISTER, study
from tvtrack.papers.p000_dissector_ekf.model import GaussMarkovMessage
from tvtrack.papers.p000_dissector_ekf.settling import scan_averages

DEFAULT = REGISTER.default()
SIZES = study.Sizes(n_trials=6, duration_T=6.0, window_T=2.0, dt=0.05, substeps=3)
K = 120  # steps of 0.05 T in 6 T


@pytest.fixture
def spy(monkeypatch):
    """The filters replaced by recorders returning estimate ``e = 0.01 k`` and ``D11 = 0.001 k + 0.0001 i`` at step
    k of run i."""
    calls = []
    monkeypatch.setattr(study, "_MEMO", {})

    def fake(name):
        def run(scan, message, y, *args):
            calls.append((name, scan, message, y, args))
            k = np.arange(K + 1, dtype=float)
            runs = np.arange(y.shape[0], dtype=float)[:, None]
            return 0.01 * k + 0.0 * runs, 0.001 * k + 0.0001 * runs

        return run

    monkeypatch.setattr(study, "run_steps_variant1", fake("v1"))
    monkeypatch.setattr(study, "run_steps_variant2", fake("v2"))
    return calls


def _run(cfg=None, filt="v1", psi=20.0, contrast=0.5, **kw):
    return study.filter_errors({**DEFAULT, **(cfg or {})}, 7, SIZES, psi, contrast, filt, **kw)


def test_variant1_is_handed_the_paper_s_start_gains_and_the_readings(spy):
    _run()
    (name, scan, message, y, args), = spy  # fmt: skip
    assert name == "v1" and message == GaussMarkovMessage(0.1, 0.15)
    assert scan == study.scan_at_snr(20.0, 0.5, 0.05, 0.5, "per_sample")  # psi_A 20, P 0.5, T_u = T/2
    d0, start, beta, g22, compiled, cs, phi = args
    assert d0 == (0.2, 1.0) and start is None and beta == 15.0 and g22 == "paper" and compiled is None
    assert cs == "consistent"
    np.testing.assert_array_equal(phi, study.switch_on_phases(7, SIZES))
    assert y.shape == (6, K + 1)


@pytest.mark.parametrize("value,g22", [("euler", "euler"), ("matched", "matched")])
def test_variant1_reads_the_g22_form(spy, value, g22):
    _run({"G22": value})
    assert spy[0][4][3] == g22


def test_variant1_reads_the_printed_signal_noise_scale(spy):
    _run({"signal-noise scale": "c_s = A, as printed"})
    assert spy[0][4][5] == "literal"


def test_a_random_initial_estimate_is_drawn_from_n0_d0_on_the_common_draws(spy):
    _run(init="random N(0, D11(0))")
    _run(filt="v2", init="random N(0, D11(0))")
    draws = study.common_draws(7, SIZES)["init"]
    np.testing.assert_allclose(spy[0][4][1], np.stack([np.sqrt(0.2) * draws[:, 0], draws[:, 1]], 1), rtol=1e-15)
    np.testing.assert_allclose(spy[1][4][1], np.sqrt(0.2) * draws[:, 0], rtol=1e-15)


@pytest.mark.parametrize(
    "filt,cfg,assumed,iterations,contrast",
    [
        ("v2", {}, None, 0, 0.5),
        ("v2", {"v2 noise at": "updated estimate"}, None, 1, 0.5),
        ("ignoring", {"v2 noise at": "updated estimate"}, 0.0, 0, 0.5),  # the filter that assumes P = 0
        ("stationary", {}, None, 0, 0.0),  # variant 2 on data of P = 0
    ],
)
def test_variant2_and_its_relatives_are_handed_their_contrast_and_noise_evaluation(
    spy, filt, cfg, assumed, iterations, contrast
):
    _run(cfg, filt=filt)
    (name, scan, message, y, args), = spy  # fmt: skip
    assert name == "v2" and scan.contrast == contrast and message == GaussMarkovMessage(0.1, 0.15)
    d0, start, a, it, compiled, phi = args
    assert (d0, start, a, it, compiled) == (0.2, None, assumed, iterations, None)
    np.testing.assert_array_equal(phi, study.switch_on_phases(7, SIZES))


def test_the_scan_reads_the_sigma_sh_convention_and_the_pulse_of_half_a_scan(spy):
    per = study.operating_scan(DEFAULT, 20.0, 0.5, SIZES)
    unit = study.operating_scan({**DEFAULT, "sigma_sh": "unit bandwidth"}, 20.0, 0.5, SIZES)
    want = study.scan_at_snr(20.0, 0.5, 0.05, 0.5, "per_sample")
    assert per == want and unit == study.scan_at_snr(20.0, 0.5, 0.05, 0.5, "unit_bandwidth") and unit != per
    _run({"sigma_sh": "unit bandwidth"})
    assert spy[0][1] == unit


def test_the_summaries_are_the_squared_errors_against_the_truth(spy):
    out = _run()
    x = study.truth_paths(DEFAULT, 7, SIZES)[0]
    k = np.arange(K + 1)
    sq = (x - 0.01 * k) ** 2
    window = k * 0.05 > 4.0  # the last 2 T
    np.testing.assert_allclose(out["steady"], sq[:, window].mean(1), rtol=1e-13)
    np.testing.assert_allclose(out["d_steady"], (0.001 * k[window]).mean() + 0.0001 * np.arange(6), rtol=1e-13)
    np.testing.assert_allclose(out["steady_after"], sq[:, k * 0.05 > 5.0].mean(1), rtol=1e-13)
    np.testing.assert_allclose(out["curve"], sq.mean(0), rtol=1e-13)
    np.testing.assert_allclose(out["d_curve"], 0.001 * k + 0.00025, rtol=1e-13)  # the runs' mean
    np.testing.assert_allclose(out["scans"], scan_averages(sq, 20), rtol=1e-13)
    assert window.sum() == 40 and (k * 0.05 > 5.0).sum() == 20


def test_the_steady_window_reading_scores_every_sample_after_5_scans(spy):
    out = _run({"steady window": "after 5 T"}, filt="v2")
    base = _run(filt="v2")
    x = study.truth_paths(DEFAULT, 7, SIZES)[0]
    k = np.arange(K + 1)
    sq = (x - 0.01 * k) ** 2
    np.testing.assert_allclose(out["steady"], sq[:, k * 0.05 > 5.0].mean(1), rtol=1e-13)
    np.testing.assert_allclose(base["steady"], sq[:, k * 0.05 > 4.0].mean(1), rtol=1e-13)
    assert len(spy) == 1  # the reading re-scores the same run


def test_a_run_from_a_fixed_start_scores_against_the_truth_from_that_start(spy):
    out = _run(offset=0.3)
    x = study.truth_paths(DEFAULT, 7, SIZES, offset=0.3)[0]
    np.testing.assert_allclose(x[:, 0], 0.3, rtol=1e-12)
    k = np.arange(K + 1)
    np.testing.assert_allclose(out["steady"], ((x - 0.01 * k) ** 2)[:, k * 0.05 > 4.0].mean(1), rtol=1e-13)


def test_a_configuration_without_the_later_entries_runs_as_the_default(spy):
    """Entries added after the first records (the message, the manoeuvre, the background, the signal-noise scale,
    the steady window) read their defaults where a configuration lacks them."""
    base = _run()
    older = {k: v for k, v in DEFAULT.items() if k not in ("sigma_1", "manoeuvre")}
    assert study.filter_errors(older, 7, SIZES, 20.0, 0.5, "v1") is base  # the same data: the run is reused
    older = {k: v for k, v in DEFAULT.items() if k not in ("background", "signal-noise scale", "steady window")}
    again = study.filter_errors(older, 7, SIZES, 20.0, 0.5, "v1")
    assert len(spy) == 2 and spy[-1][4][5] == "consistent"  # run again (its key lacks two entries); the same scale
    np.testing.assert_array_equal(spy[-1][3], spy[0][3])  # the same samples: a stationary background
    np.testing.assert_array_equal(again["steady"], base["steady"])  # scored in the final window


READS = {  # the entries each filter's run reads besides the data's (sample model, scoring time, sigma_1, manoeuvre)
    "v1": ("sigma_sh", "G22", "photon model", "background", "signal-noise scale"),
    "v2": ("sigma_sh", "v2 noise at", "photon model", "background"),
    "ignoring": ("sigma_sh", "photon model", "background"),
    "stationary": ("sigma_sh", "background"),
}
DATA = ("sample model", "scoring time", "sigma_1", "manoeuvre")


@pytest.mark.parametrize("filt", sorted(READS))
def test_a_run_is_reused_exactly_where_its_filter_does_not_read_the_changed_entry(spy, filt):
    base = _run(filt=filt)
    for name in REGISTER.names:
        value = next(v for v in REGISTER[name].values if v != DEFAULT[name])
        n = len(spy)
        again = _run({name: value}, filt=filt)
        reran = len(spy) > n
        assert reran == (name in READS[filt] + DATA), (filt, name)
        if not reran and name != "steady window":
            assert again is base


def test_the_truth_starts_where_the_initial_position_reading_puts_it(monkeypatch):
    monkeypatch.setattr(study, "_MEMO", {})
    seen = []
    real = study.truth_and_pulse

    def spy(geometry, message, noises, model, score, drift, phases):
        seen.append((geometry, message, noises, model, score, drift, phases))
        return real(geometry, message, noises, model, score, drift, phases)

    monkeypatch.setattr(study, "truth_and_pulse", spy)
    draws = study.common_draws(7, SIZES)
    study.truth_paths(DEFAULT, 7, SIZES)
    study.truth_paths(DEFAULT, 7, SIZES, offset="uniform")
    study.truth_paths(DEFAULT, 7, SIZES, offset=0.3)
    study.truth_paths({**DEFAULT, "sigma_1": "0.2 T"}, 7, SIZES, offset=0.3)
    (g, m, n0, model, score, drift, ph) = seen[0]
    assert g == study.scan_at_snr(1.0, 0.0, 0.05, 0.5) and m == GaussMarkovMessage(0.1, 0.15)
    assert (model, score, drift) == ("integrated", "interval_end", None)
    np.testing.assert_array_equal(n0["x0"], draws["x0"])
    np.testing.assert_array_equal(ph, study.switch_on_phases(7, SIZES))
    from scipy import stats

    np.testing.assert_allclose(seen[1][2]["x0"] * 0.1, stats.norm.cdf(draws["x0"]) - 0.5, rtol=1e-13)
    np.testing.assert_allclose(seen[2][2]["x0"], np.full_like(draws["x0"], 3.0), rtol=1e-13)  # 0.3 T / sigma_1
    np.testing.assert_allclose(seen[3][2]["x0"], np.full_like(draws["x0"], 1.5), rtol=1e-13)  # 0.3 T / 0.2 T
    assert seen[3][1] == GaussMarkovMessage(0.2, 0.15)
    study.truth_paths({**DEFAULT, "sample model": "point", "scoring time": "interval centre"}, 7, SIZES)
    assert seen[4][3:5] == ("point", "interval_centre")
    weave = {**DEFAULT, "manoeuvre": "weave 0.1 T / 2 T"}
    study.truth_paths(weave, 7, SIZES)
    t = np.linspace(0.0, 3.0, 7)
    np.testing.assert_array_equal(seen[5][5](t), study._drift(weave, 7, 6)(t))


def test_the_manoeuvre_is_a_weave_of_sigma_1_with_a_drawn_phase_per_run():
    assert study._drift(DEFAULT, 7, 5) is None
    f = study._drift({**DEFAULT, "manoeuvre": "weave 0.1 T / 2 T"}, 7, 5)
    phase = np.random.default_rng([7, 57]).uniform(0.0, 2 * np.pi, (5, 1))
    t = np.linspace(0.0, 4.0, 9)
    np.testing.assert_allclose(f(t), 0.1 * np.sin(2 * np.pi * t / 2.0 + phase), rtol=1e-13)
    g = study._drift({**DEFAULT, "manoeuvre": "weave 0.1 T / 5 T"}, 7, 5)
    np.testing.assert_allclose(g(t), 0.1 * np.sin(2 * np.pi * t / 5.0 + phase), rtol=1e-13)
    assert study._drift({k: v for k, v in DEFAULT.items() if k != "manoeuvre"}, 7, 5) is None


def test_the_photon_model_and_the_drifting_background_reach_the_samples():
    x, pulse, xi, _ = study.truth_paths(DEFAULT, 7, SIZES)
    scan = study.operating_scan(DEFAULT, 20.0, 0.5, SIZES)
    gauss = study.photon_samples(DEFAULT, 7, scan, pulse, xi)
    np.testing.assert_array_equal(gauss, study.samples_from_pulse(scan, pulse, xi))
    poisson = study.photon_samples({**DEFAULT, "photon model": "Poisson counts"}, 7, scan, pulse, xi)
    want = study.counts_from_pulse(scan, pulse, np.random.default_rng([7, 31]))[0]
    np.testing.assert_array_equal(poisson, want)
    flat = study.operating_scan(DEFAULT, 20.0, 0.0, SIZES)  # no signal current to count: Gaussian
    np.testing.assert_array_equal(
        study.photon_samples({**DEFAULT, "photon model": "Poisson counts"}, 7, flat, pulse, xi),
        study.samples_from_pulse(flat, pulse, xi),
    )
    drift = study.photon_samples({**DEFAULT, "background": "drifting +-50 %"}, 7, scan, pulse, xi)
    phase = np.random.default_rng([7, 41]).uniform(0.0, 2 * np.pi, (6, 1))
    t = (np.arange(1, K + 1) - 0.5) * 0.05
    b = 1.0 + 0.5 * np.sin(2 * np.pi * t / 10.0 + phase)
    mean = scan.amplitude * pulse
    scale = np.sqrt((b + scan.signal_noise_ratio * pulse) / (1 + scan.signal_noise_ratio * pulse))
    np.testing.assert_allclose(drift[:, 1:], mean + (gauss[:, 1:] - mean) * scale, rtol=1e-12)
    np.testing.assert_array_equal(drift[:, 0], gauss[:, 0])


def test_the_bound_refers_to_the_time_the_errors_are_scored_at():
    at = {
        (m, s): study.bound_time({**DEFAULT, "sample model": m, "scoring time": s})
        for m in ("integrated", "point")
        for s in ("interval end", "interval centre")
    }
    assert at == {
        ("integrated", "interval end"): "interval_end",
        ("integrated", "interval centre"): "sample",
        ("point", "interval end"): "sample",
        ("point", "interval centre"): "sample",
    }


def test_the_message_and_the_signal_noise_scale_of_a_configuration():
    assert study.cfg_message(DEFAULT) == GaussMarkovMessage(0.1, 0.15)
    assert study.cfg_message({**DEFAULT, "sigma_1": "0.2 T"}) == GaussMarkovMessage(0.2, 0.15)
    assert study.cfg_message({}) == GaussMarkovMessage(0.1, 0.15)
    assert study._cs(DEFAULT) == "consistent" and study._cs({}) == "consistent"
    assert study._cs({"signal-noise scale": "c_s = A, as printed"}) == "literal"


def test_a_start_anywhere_in_the_micro_raster_is_a_world_beyond_the_paper():
    """«адекватной моделью сообщения является стационарный марковский гауссов процесс» (eq. (3)): the message is
    stationary, so the object starts from its own law N(0, sigma_1^2); «наличие изображения ТСО в пределах
    микрорастра» motivates the filters' D11(0) = 0.2, not the truth's start. A uniform start over the micro-raster is
    not the paper's model: a world beyond it, not a reading of its text."""
    from tvtrack.papers.p000_dissector_ekf.register import REGISTER

    entry = REGISTER["initial position"]
    assert entry.default == "stationary N(0, sigma_1^2)"
    assert entry.side == "world"
