"""Paper 004: each claim value's wiring pinned on a hand-built run whose forecasts and centres are known.

:func:`study.claim_values` reduces a run to what each rule reads. Here the run is built by hand (random but fixed
centres and forecasts, one scale per method), and every value is written out from its definition: the forecast
``m`` frames ahead against the reading's reference centre from ``eval_start`` on, the baseline's mean square over
the paper's filter's (never the other way), the quantile the reading names, C004-6's late window from half the run,
C004-8's time over the frame interval. A slip of the horizon, the reference, the start, a ratio's direction or a
statistic changes a number here. No scene is rendered: the file takes about a second.
"""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import predictors as pr
from tvtrack.papers.p004_laser_spot_prediction import study
from tvtrack.papers.p004_laser_spot_prediction.intervals import mean_ci_t, ratio_of_means_ci, root_mean_ci
from tvtrack.papers.p004_laser_spot_prediction.prediction_study import CLASSICAL, PAPER, VARIANT
from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT
from tvtrack.papers.p004_laser_spot_prediction.sizes import StudySize

P, T, START = 6, 48, 10
SIZE = replace(StudySize(), eval_start=START, n_mc_variance=1000)
METHODS = (PAPER, VARIANT, *CLASSICAL, study.LSQ_CUBIC, study.NATURAL_SPLINE, *study.NETWORKS)


def _run(config=None, **over) -> study.StudyRun:
    rng = np.random.default_rng(4)
    truth = np.cumsum(rng.normal(0, 1, (1, P, 2, T)), axis=-1)
    z_meas = truth + rng.normal(0, 0.5, truth.shape)
    z = z_meas + 0.25  # what the predictors see differs from the measured centres the claims are scored on
    # each method: the truth one frame on plus its own error, scaled per method and per path (paths differ)
    path = np.linspace(0.5, 2.0, P)[None, :, None, None]
    fc = {name: truth + (1 + k) * 0.3 * path * rng.normal(0, 1, truth.shape) for k, name in enumerate(METHODS)}
    fixed = {name: f + 0.7 * rng.normal(0, 1, truth.shape) for name, f in fc.items()}
    run = study.StudyRun(
        config={**DEFAULT, **(config or {})},
        size=SIZE,
        scene=SimpleNamespace(frame_rate_hz=50.0),
        camera=None,
        truth=truth,
        z_meas=z_meas,
        z=z,
        path_rms=np.ones(P),
        jitter_rms=np.zeros(P),
        centroid_rms=0.0,
        lost_share=0.0,
        clipped_share=0.0,
        intensity=None,
        forecasts=fc,
        fixed_forecasts=fixed,
    )
    return replace(run, **over)


def path_mse(forecast, ref, m, start=START):
    """Per path: the mean over axes and frames n >= start of (forecast[n - m] - ref[n])^2, written out."""
    e = forecast[0, :, :, : T - m] - ref[0, :, :, m:]  # e at frame n = m .. T-1
    frames = np.arange(m, T)
    return np.mean(e[:, :, frames >= start] ** 2, axis=(1, 2))


def path_abs(forecast, ref, m, start=START):
    e = np.abs(forecast[0, :, :, : T - m] - ref[0, :, :, m:])
    return e[:, :, np.arange(m, T) >= start]


def same(got, want):
    assert (got.value, got.ci_low, got.ci_high, got.n) == pytest.approx((want.value, want.ci_low, want.ci_high, want.n))


@pytest.mark.parametrize("m", [1, 3])
def test_c004_2_is_the_rms_of_the_papers_filter_per_axis_against_the_measured_centre(m):
    run = _run({"horizon": m})
    got = study.claim_values(run, claims=["C004-2"])["C004-2"]
    want = path_mse(run.forecasts[PAPER], run.z_meas, m)
    assert got.value == pytest.approx(np.sqrt(np.mean(want)), rel=1e-12)
    same(got, root_mean_ci(want))
    radial = study.claim_values(_run({"horizon": m, "C004-2 statistic": "radial RMS"}), claims=["C004-2"])["C004-2"]
    assert radial.value == pytest.approx(np.sqrt(2 * np.mean(want)), rel=1e-12)


def test_c004_2_reads_the_true_centre_the_fixed_tuning_and_the_variant_floor_when_asked():
    run = _run({"reference": "true centre"})
    got = study.claim_values(run, claims=["C004-2"])["C004-2"]
    assert got.value == pytest.approx(np.sqrt(np.mean(path_mse(run.forecasts[PAPER], run.truth, 1))), rel=1e-12)
    run = _run({"tuning": "fixed"})
    got = study.claim_values(run, claims=["C004-2"])["C004-2"]
    assert got.value == pytest.approx(np.sqrt(np.mean(path_mse(run.fixed_forecasts[PAPER], run.z_meas, 1))))
    run = _run({"floor form": study.VARIANT_FLOOR})
    got = study.claim_values(run, claims=["C004-2"])["C004-2"]
    assert got.value == pytest.approx(np.sqrt(np.mean(path_mse(run.forecasts[VARIANT], run.z_meas, 1))))


@pytest.mark.parametrize("statistic, q", [("95th percentile", 0.95), ("99th percentile", 0.99)])
def test_c004_1_is_the_mean_over_paths_of_each_paths_quantile_of_the_per_axis_error(statistic, q):
    run = _run({"C004-1 statistic": statistic, "horizon": 2})
    got = study.claim_values(run, claims=["C004-1"])["C004-1"]
    e = path_abs(run.forecasts[PAPER], run.z_meas, 2)
    per_path = np.quantile(e.reshape(P, -1), q, axis=1)
    assert got.value == pytest.approx(np.mean(per_path), rel=1e-12)
    same(got, mean_ci_t(per_path))


def test_c004_1_radial_reading_is_the_95th_percentile_of_the_distance():
    run = _run({"C004-1 statistic": "radial 95th percentile"})
    got = study.claim_values(run, claims=["C004-1"])["C004-1"]
    e = path_abs(run.forecasts[PAPER], run.z_meas, 1)
    radial = np.sqrt(e[:, 0] ** 2 + e[:, 1] ** 2)  # (P, frames)
    assert got.value == pytest.approx(np.mean(np.quantile(radial, 0.95, axis=1)), rel=1e-12)


def test_c004_3_is_each_baselines_mean_square_over_the_papers_filters():
    run = _run({"horizon": 2})
    got = study.claim_values(run, claims=["C004-3"])["C004-3"]
    assert list(got) == list(CLASSICAL)
    paper = path_mse(run.forecasts[PAPER], run.z_meas, 2)
    for b in CLASSICAL:
        base = path_mse(run.forecasts[b], run.z_meas, 2)
        assert got[b].value == pytest.approx(np.mean(base) / np.mean(paper), rel=1e-12)
        same(got[b], ratio_of_means_ci(base, paper))
    assert got["cubic spline"].value > 1  # a larger error than the paper's filter (its scale in _run)


def test_c004_3_tail_reading_is_the_ratio_of_per_path_95th_percentiles():
    run = _run({"C004-3 statistic": "95th percentile"})
    got = study.claim_values(run, claims=["C004-3"])["C004-3"]
    q = lambda f: np.quantile(path_abs(f, run.z_meas, 1).reshape(P, -1), 0.95, axis=1)  # noqa: E731
    for b in CLASSICAL:
        assert got[b].value == pytest.approx(np.mean(q(run.forecasts[b])) / np.mean(q(run.forecasts[PAPER])))


@pytest.mark.parametrize(
    "reading, name", [("least-squares cubic", study.LSQ_CUBIC), ("natural cubic", study.NATURAL_SPLINE)]
)
def test_c004_3_spline_reading_replaces_the_cubic_spline_only(reading, name):
    run = _run({"spline": reading})
    got = study.claim_values(run, claims=["C004-3"])["C004-3"]
    paper = np.mean(path_mse(run.forecasts[PAPER], run.z_meas, 1))
    assert got["cubic spline"].value == pytest.approx(np.mean(path_mse(run.forecasts[name], run.z_meas, 1)) / paper)
    got_lr = got["linear regression deg 1"].value
    assert got_lr == pytest.approx(np.mean(path_mse(run.forecasts["linear regression deg 1"], run.z_meas, 1)) / paper)


def test_c004_3b_is_each_networks_mean_square_over_the_papers_filters():
    run = _run({"reference": "true centre"})
    got = study.claim_values(run, claims=["C004-3b"])["C004-3b"]
    assert list(got) == list(study.NETWORKS)
    paper = path_mse(run.forecasts[PAPER], run.truth, 1)
    for b in study.NETWORKS:
        assert got[b].value == pytest.approx(np.mean(path_mse(run.forecasts[b], run.truth, 1)) / np.mean(paper))


def test_c004_6_is_the_late_rms_without_the_floor_over_the_papers_filter_from_half_the_run():
    run = _run({"horizon": 2})
    got = study.claim_values(run, claims=["C004-6"])["C004-6"]
    nofloor = pr.growing_memory_forecast(run.z, 2, 2, None)
    late = T // 2  # half the run, after eval_start = 10
    a = path_mse(nofloor, run.z_meas, 2, late)
    b = path_mse(run.forecasts[PAPER], run.z_meas, 2, late)
    assert got.value == pytest.approx(np.sqrt(np.mean(a) / np.mean(b)), rel=1e-12)
    r = ratio_of_means_ci(a, b)
    assert (got.ci_low, got.ci_high) == pytest.approx((np.sqrt(r.ci_low), np.sqrt(r.ci_high)), rel=1e-12)
    # a start past half the run takes over
    later = study.claim_values(_run({"horizon": 2}, size=replace(SIZE, eval_start=30)), claims=["C004-6"])["C004-6"]
    a, b = path_mse(nofloor, run.z_meas, 2, 30), path_mse(run.forecasts[PAPER], run.z_meas, 2, 30)
    assert later.value == pytest.approx(np.sqrt(np.mean(a) / np.mean(b)), rel=1e-12)


def test_the_centroid_error_is_the_rms_of_the_measured_against_the_true_centres_from_eval_start():
    run = _run()
    got = study.claim_values(run, claims=[])
    assert list(got) == [study.CENTROID]
    per_path = np.mean((run.z_meas - run.truth)[0, :, :, START:] ** 2, axis=(1, 2))
    same(got[study.CENTROID], root_mean_ci(per_path))


def test_c004_4_5_8_read_their_series_streams_and_frame_interval(monkeypatch):
    seen = {}
    monkeypatch.setattr(
        study, "recursion_check", lambda z4, seeds, loss, held: seen.setdefault("4", (z4, seeds, loss, held)) and "c4"
    )
    monkeypatch.setattr(study, "frame_time_ms", lambda run, rng, c: seen.setdefault("8", rng.random()) and 5.0)

    def ratios(rng, n, noise):
        seen.setdefault("5", []).append((rng.random(), n, noise))
        return {"variance": 1.0}

    monkeypatch.setattr(study, "variance_ratios", ratios)
    monkeypatch.setattr(study, "_VARIANCE", {})
    run = _run({"frame loss": 0.1})
    got = study.claim_values(run, seed=9, claims=["C004-4", "C004-5", "C004-8"])
    assert got["C004-4"] == "c4" and got["C004-5"] == {"variance": 1.0}
    assert got["C004-8"] == pytest.approx(5.0 / 20.0)  # 5 ms over the 20 ms frame interval at 50 Hz
    z4, seeds, loss, held = seen["4"]
    np.testing.assert_array_equal(z4, run.z[0, :, 0, :T])
    assert (seeds, loss, held) == ([9, 4004], 0.1, True)
    streams = study.run_streams(9)
    assert seen["8"] == np.random.default_rng(streams[5]).random()
    assert seen["5"] == [(np.random.default_rng(streams[4]).random(), 1000, "Gaussian")]
    # the check is computed once per (seed, series, noise law): a second run of the same seed reads it back
    study.claim_values(run, seed=9, claims=["C004-5"])
    assert len(seen["5"]) == 1
    study.claim_values(_run({"C004-5 noise": "Student t3"}), seed=9, claims=["C004-5"])
    assert seen["5"][-1][2] == "Student t3"
    seen.pop("4")
    study.claim_values(_run({"lost frames": "skipped (coast)"}), seed=9, claims=["C004-4"])
    np.testing.assert_array_equal(seen["4"][0], run.z_meas[0, :, 0, :T])
    assert seen["4"][3] is False


def test_a_claim_asked_alone_has_the_value_it_has_among_all():
    run = _run()
    alone = {c: study.claim_values(run, claims=[c])[c] for c in ("C004-1", "C004-2", "C004-3", "C004-6")}
    together = study.claim_values(run, claims=["C004-1", "C004-2", "C004-3", "C004-6"])
    for c, v in alone.items():
        assert v == together[c]
    assert "C004-3b" not in together and "C004-4" not in together


def test_parts_for_reads_the_methods_each_claim_needs():
    assert study.parts_for(["C004-3"]) == frozenset({"classical"})
    assert study.parts_for(["C004-3b", "C004-2"]) == frozenset({"learned"})
    assert study.parts_for(["C004-1", "C004-6"]) == frozenset()
    assert study.parts_for(["C004-4", "C004-5"]) is None
    assert study.parts_for(None) == frozenset({"classical", "learned"})


def test_c004_4_reads_the_first_200_frames_of_the_first_axis(monkeypatch):
    seen = []
    monkeypatch.setattr(study, "recursion_check", lambda z4, seeds, loss, held: seen.append(z4) or "c4")
    long = np.arange(1 * P * 2 * 260, dtype=float).reshape(1, P, 2, 260)
    run = _run(truth=long, z=long + 1.0, z_meas=long + 2.0)
    study.claim_values(run, seed=1, claims=["C004-4"])
    np.testing.assert_array_equal(seen[0], long[0, :, 0, :200] + 1.0)


def test_the_readings_of_c004_4_and_5_missing_from_the_configuration_are_the_papers_and_the_seed_defaults_to_0(
    monkeypatch,
):
    seen = {}
    monkeypatch.setattr(
        study, "recursion_check", lambda z4, seeds, loss, held: seen.setdefault("4", (z4, seeds, loss, held)) and "c4"
    )
    monkeypatch.setattr(study, "variance_ratios", lambda rng, n, noise: seen.setdefault("5", noise) and {})
    monkeypatch.setattr(study, "_VARIANCE", {})
    run = _run()
    run = replace(
        run, config={k: v for k, v in run.config.items() if k not in ("lost frames", "frame loss", "C004-5 noise")}
    )
    study.claim_values(run, claims=["C004-4", "C004-5"])
    z4, seeds, loss, held = seen["4"]
    np.testing.assert_array_equal(z4, run.z[0, :, 0, :T])  # held frames
    assert (seeds, loss, held) == ([0, 4004], 0.0, True)
    assert type(loss) is float
    assert seen["5"] == "Gaussian"
