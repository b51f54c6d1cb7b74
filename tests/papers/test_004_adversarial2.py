"""Notebook 004: the second adversarial pass's register rows (C004-8 pipeline and statistic, lost frames for
C004-4, heavy-tailed noise for C004-5), each measured by the study."""

import numpy as np
import pytest

from tvtrack.filters.polynomial import growing_memory_filter
from tvtrack.papers.p004_laser_spot_prediction import predictors as pr
from tvtrack.papers.p004_laser_spot_prediction import derivation, study, timing
from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT, DEPENDS

SIZE = study.StudySize(
    n_paths=6,
    n_frames=200,
    floor_grid=(3, 10),
    window_grid=(4, 10),
    mlp_hidden_units=4,
    rbf_centres=20,
    train_samples=300,
    n_mc_variance=2000,
    timing_frames=60,
    lag_grid=(1, 4),
)


@pytest.fixture(scope="module")
def scene():
    return study.study_run(dict(DEFAULT), 3, SIZE)


def test_streaming_pipeline_runs_the_paper_recursion_frame_by_frame(scene):
    """The timed streaming loop is the real filter: its states equal growing_memory_filter (fixed floor) on the
    centres it was fed (a wrong gain index or a missing prediction step fails), and its gates follow the spot
    (the measured centres lie within 0.5 px of the truth)."""
    times, states, z = timing.streaming_frame_times(scene, np.random.default_rng(0))
    ref = growing_memory_filter(z.T, 2, SIZE.fixed_floor)  # (2 axes, T, 3)
    np.testing.assert_allclose(states[2:], np.moveaxis(ref, 0, 1)[2:], rtol=0, atol=1e-9)
    assert np.all(np.isnan(states[:2]))
    truth = np.moveaxis(scene.truth[0, 0, :, : len(z)], 0, -1)
    assert np.max(np.abs(z - truth)) < 0.5
    assert np.all(times > 0)


def _scripted_clock(steps):
    """A clock that advances by ``steps[k]`` s at its k-th reading: every interval it times is known exactly, and
    the load of the machine cannot move it."""
    ticks = iter(np.cumsum(steps))
    return lambda: float(next(ticks))


def test_c004_8_readings_change_what_is_timed(scene, monkeypatch):
    """The C004-8 readings decide what is timed and how it is summarised, read on a scripted clock: the default
    times the batched pipeline once over all the timed frames (two readings, divided by the frames); the
    streaming reading times each frame (two readings a frame) and takes the mean or the 99th percentile over the
    frames after the first. A swapped statistic, a kept warm-up frame or a wrong divisor fails. The readings are
    in the claim's dependencies."""
    steps = np.random.default_rng(5).uniform(1e-4, 1e-2, 10_000)
    nt = min(SIZE.timing_frames, scene.truth.shape[-1])
    per_frame = steps[3 : 2 * nt : 2] * 1e3  # frame t lasts the clock's step at reading 2t + 1; frame 0 dropped
    readings = {
        (): steps[1] / nt * 1e3,
        (("C004-8 pipeline", "streaming, the study's energy centre"),): per_frame.mean(),
        (("C004-8 statistic", "99th percentile"),): np.quantile(per_frame, 0.99),
        (("C004-8 pipeline", "streaming, the study's energy centre"), ("C004-8 statistic", "99th percentile")): (
            np.quantile(per_frame, 0.99)
        ),
    }
    for config, expected in readings.items():
        monkeypatch.setitem(timing.CLOCKS, "CPU", _scripted_clock(steps))
        got = timing.frame_time_ms(scene, np.random.default_rng(1), dict(config))
        assert got == pytest.approx(expected, rel=1e-12), config
    assert np.quantile(per_frame, 0.99) > 1.5 * per_frame.mean()  # the statistics differ on these steps
    assert {"energy centre", "C004-8 pipeline", "C004-8 statistic"} <= set(DEPENDS["C004-8"])


def test_lost_frames_skipped_break_the_equality_only_where_a_frame_is_lost():
    """Eq. (4) on the samples present (NaN skipped, true times kept) equals lstsq on those rows; on a gap-free
    series the recursion matches it to 1e-9, with one lost sample it does not (the coasting recursion keeps the
    gains of consecutive samples)."""
    rng = np.random.default_rng(2)
    z = 50 + np.cumsum(np.cumsum(0.05 * rng.standard_normal(120))) + 0.3 * rng.standard_normal(120)
    gap = z.copy()
    gap[60] = np.nan
    b = pr.batch_least_squares_states(gap)
    keep = np.isfinite(gap[:81])
    lags = np.arange(80, -1, -1.0)[keep]
    H = np.stack([np.ones_like(lags), -lags, lags**2 / 2], axis=1)
    np.testing.assert_allclose(b[80], np.linalg.lstsq(H, gap[:81][keep], rcond=None)[0], rtol=1e-10)
    assert derivation.recursion_vs_batch(z)[0] < 1e-9
    assert derivation.recursion_vs_batch(gap)[0] > 1e-6


def test_heavy_tailed_noise_is_a_reading_the_rule_cannot_decide():
    """Student t3 noise of unit variance: Var(x_est) / g_N1 is still 1 (a linear estimator) and the point values
    show it, but the squared error has infinite variance (no fourth moment), so each part carries no interval and
    the rule reads it undecided: a heavy tail never decides a part (nor flips a label). The Gaussian reading keeps
    the chi-square intervals and decides."""
    from tvtrack.verdicts import InBand, is_undecided

    out = study.variance_ratios(np.random.default_rng(4), 20000, noise="Student t3")
    rule = InBand("variance ratio", low=0.9, high=1.1)
    for n in derivation._CHECK_N:
        e = out[f"variance at N={n}"]
        assert abs(e.value - 1) < 0.15 and "fourth moment" in e.method
        assert is_undecided(e) and rule.judge(e).verdict == "undecided"
    gauss = study.variance_ratios(np.random.default_rng(4), 20000)
    assert rule.judge(gauss["variance at N=10"]).verdict == "reproduced"
    assert "chi-square" in study.variance_ratios(np.random.default_rng(4), 2000)["variance at N=3"].method
    with pytest.raises(ValueError, match="noise"):
        study.variance_ratios(np.random.default_rng(4), 100, noise="Cauchy")


def test_c004_8_times_the_energy_centre_of_every_frame(scene, monkeypatch):
    """The default pipeline's time per frame includes the energy centre: with the batched centre costing one scripted
    second and nothing else costing any, the time per frame is that second over the frames timed."""
    now = [0.0]
    real = timing.centroid

    def slow_centroid(*args, **kwargs):
        now[0] += 1.0
        return real(*args, **kwargs)

    monkeypatch.setattr(timing, "centroid", slow_centroid)
    monkeypatch.setitem(timing.CLOCKS, "CPU", lambda: now[0])
    got = timing.frame_time_ms(scene, np.random.default_rng(1), {})
    nt = min(SIZE.timing_frames, scene.truth.shape[-1])
    assert nt > 1 and got == pytest.approx(1e3 / nt, rel=1e-12)
