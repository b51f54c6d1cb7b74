"""Notebook 004: the trace data set, its loader, and the beam-wander generator."""

import io
import json
import zipfile

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction.traces import DATA_DIR
from tvtrack.papers.p004_laser_spot_prediction.beam_wander import (
    BeamWanderConfig,
    component_sigmas,
    component_table,
    gauss_markov_discrete,
    generate_traces,
    one_frame_motion_rms,
    optimal_wander_forecast,
    scaled_config,
    wander_state_space,
)
from tvtrack.papers.p004_laser_spot_prediction.traces import TraceSet, load_traces, save_traces, sha256_file

SHIPPED = DATA_DIR / "laser_traces" / "traces.npz"


def _small(n_paths=2, n_frames=50):
    return generate_traces(BeamWanderConfig(n_paths=n_paths, n_frames=n_frames), seed=4)


@pytest.mark.determinism
def test_roundtrip_and_deterministic_bytes(tmp_path):
    tr = _small()
    p1 = save_traces(tmp_path / "a.npz", tr)
    p2 = save_traces(tmp_path / "b", tr)
    assert p2.suffix == ".npz"
    assert sha256_file(p1) == sha256_file(p2)
    back = load_traces(p1)
    np.testing.assert_array_equal(back.centres_px, tr.centres_px)
    np.testing.assert_array_equal(back.intensity, tr.intensity)
    assert back.frame_rate_hz == 25.0 and back.image_size_px == 128
    assert back.metadata == json.loads(json.dumps(tr.metadata))


def _write_npz(path, arrays):
    with zipfile.ZipFile(path, "w") as zf:
        for k, a in arrays.items():
            buf = io.BytesIO()
            np.lib.format.write_array(buf, np.asarray(a), allow_pickle=True)
            zf.writestr(f"{k}.npy", buf.getvalue())


def _valid_arrays():
    return {
        "centres_px": np.full((2, 5, 2), 60.0),
        "intensity": np.ones((2, 5)),
        "frame_rate_hz": np.float64(25),
        "image_size_px": np.int64(128),
        "metadata_json": np.asarray("{}"),
        "format": np.asarray("tvtrack-traces-v1"),
    }


@pytest.mark.parametrize(
    "change, message",
    [
        (lambda a: a.pop("intensity"), "missing entries"),
        (lambda a: a.update(centres_px=np.full((2, 5, 2), 60, dtype=np.int32)), "float64"),
        (lambda a: a.update(centres_px=np.full((2, 5, 3), 60.0)), "shape"),
        (lambda a: a.update(intensity=np.ones((2, 4))), "intensity"),
        (lambda a: a.update(intensity=-np.ones((2, 5))), "> 0"),
        (lambda a: a.update(centres_px=np.full((2, 5, 2), np.nan)), "non-finite"),
        (lambda a: a.update(centres_px=np.full((2, 5, 2), 200.0)), "leave the sensor"),
        (lambda a: a.update(format=np.asarray("other")), "format"),
        (lambda a: a.update(metadata_json=np.asarray("{not json")), "JSON"),
        (lambda a: a.update(frame_rate_hz=np.float64(-1)), "frame_rate_hz"),
        (lambda a: a.update(metadata_json=np.array([{"a": 1}], dtype=object)), "pickle"),
    ],
)
def test_bad_files_give_clear_errors(tmp_path, change, message):
    arrays = _valid_arrays()
    change(arrays)
    p = tmp_path / "bad.npz"
    _write_npz(p, arrays)
    with pytest.raises(ValueError, match=message) as info:
        load_traces(p)
    assert "bad.npz" in str(info.value)


def test_not_an_archive_and_missing_file(tmp_path):
    p = tmp_path / "junk.npz"
    p.write_bytes(b"this is not a zip file")
    with pytest.raises(ValueError, match="junk.npz"):
        load_traces(p)
    with pytest.raises(FileNotFoundError, match="nope.npz"):
        load_traces(tmp_path / "nope.npz")


def test_traceset_validates_in_memory():
    with pytest.raises(ValueError, match="centres_px"):
        TraceSet(np.zeros((2, 5)), np.ones((2, 5)), 25.0, 128)


# Regenerating on another machine may differ in the last bits: NumPy and its BLAS pick kernels by CPU.
# The file is pinned by its checksum; the regeneration must agree to this relative tolerance.
REGENERATION_RTOL = 1e-12


@pytest.mark.determinism
def test_shipped_data_set_matches_checksum_and_regenerates():
    expected = (SHIPPED.parent / "checksums.sha256").read_text().split()[0]
    assert sha256_file(SHIPPED) == expected
    assert expected in (SHIPPED.parent / "README.md").read_text()
    tr = load_traces(SHIPPED)
    assert tr.centres_px.shape == (15, 1000, 2)
    assert SHIPPED.stat().st_size < 2_000_000
    cfg = dict(tr.metadata["config"])
    cfg["corner_frequencies_hz"] = tuple(cfg["corner_frequencies_hz"])
    again = generate_traces(BeamWanderConfig(**cfg), tr.metadata["seed"])
    np.testing.assert_allclose(again.centres_px, tr.centres_px, rtol=REGENERATION_RTOL, atol=0)
    np.testing.assert_allclose(again.intensity, tr.intensity, rtol=REGENERATION_RTOL, atol=0)


def test_generator_statistics():
    """Stationary per-axis variance = the drawn RMS^2; the discrete model keeps it stationary."""
    cfg = BeamWanderConfig(
        n_paths=300,
        n_frames=200,
        rms_min_px=4.0,
        rms_max_px=4.0,
        drift_max_px_per_frame=0.0,
        scintillation_sigma_ln=0.3,
    )
    tr = generate_traces(cfg, seed=1)
    d = tr.centres_px - 63.5
    # samples of one frame across 300 paths x 2 axes are independent: variance within ~8%
    assert abs(np.var(d[:, 0]) / 16 - 1) < 0.25 and abs(np.var(d[:, -1]) / 16 - 1) < 0.25
    assert abs(np.mean(tr.intensity) - 1) < 0.01
    assert abs(np.std(np.log(tr.intensity)) - 0.3) < 0.01
    sig = component_sigmas(cfg, np.array([4.0]))
    np.testing.assert_allclose((sig**2).sum(), 16.0)
    w = 2 * np.pi * np.array(cfg.corner_frequencies_hz)
    Phi, Q = gauss_markov_discrete(w, sig, 0.04)
    P = np.zeros((3, 2, 2))
    P[:, 0, 0], P[:, 1, 1] = sig[0] ** 2, (sig[0] * w) ** 2
    np.testing.assert_allclose(Phi @ P @ np.swapaxes(Phi, -1, -2) + Q[0], P, rtol=1e-10, atol=1e-12)


def test_state_space_reproduces_wander_variance():
    cfg = BeamWanderConfig()
    F, Q, H, P0 = wander_state_space(cfg, np.array([5.0]))
    n = F.shape[0] - 2
    Pw = P0[0, :n, :n]
    np.testing.assert_allclose(F[:n, :n] @ Pw @ F[:n, :n].T + Q[0, :n, :n], Pw, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(H[0, :n] @ Pw @ H[0, :n], 25.0)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"n_paths": 0}, "n_paths"),
        ({"frame_rate_hz": -1.0}, "frame_rate_hz"),
        ({"corner_frequencies_hz": (20.0,)}, "corner_frequencies_hz"),
        ({"rms_max_px": 100.0}, "rms_max_px"),
        ({"drift_max_px_per_frame": 1.0}, "drift_max_px_per_frame"),
    ],
)
def test_config_rejects_bad_values(kwargs, name):
    with pytest.raises(ValueError, match=name):
        BeamWanderConfig(**kwargs)


def test_seed_reproduces_and_differs():
    a, b, c = _small(), _small(), generate_traces(BeamWanderConfig(n_paths=2, n_frames=50), seed=5)
    np.testing.assert_array_equal(a.centres_px, b.centres_px)
    assert not np.array_equal(a.centres_px, c.centres_px)
    with pytest.raises(ValueError, match="seed"):
        generate_traces(BeamWanderConfig(), seed=-1)


def test_scaled_config_scales_amplitude_and_bandwidth():
    cfg = BeamWanderConfig()
    c = scaled_config(cfg, 2.0, 3.0)
    assert (c.rms_min_px, c.rms_max_px) == (6.0, 16.0)
    np.testing.assert_allclose(c.corner_frequencies_hz, [0.06, 0.3, 1.5])
    assert scaled_config(cfg) == cfg
    with pytest.raises(ValueError, match="wander_scale"):
        scaled_config(cfg, 0.0)


def test_optimal_wander_forecast_beats_the_paper_filter_and_last_value():
    from tvtrack.papers.p004_laser_spot_prediction.predictors import forecast_errors, growing_memory_forecast

    cfg = BeamWanderConfig(n_paths=3, n_frames=400)
    tr = generate_traces(cfg, 11)
    truth = np.moveaxis(tr.centres_px, -1, -2)[None]  # (1, P, 2, T)
    z = truth + 0.05 * np.random.default_rng(2).standard_normal(truth.shape)
    rms = lambda fc: np.sqrt(np.nanmean(forecast_errors(fc, truth, 1)[..., 50:] ** 2))
    opt = rms(optimal_wander_forecast(z, cfg, np.asarray(tr.metadata["wander_rms_px"]), 0.05**2, 1))
    assert opt < rms(growing_memory_forecast(z, 1, 2, 10)) and opt < rms(z)


def test_one_frame_motion_matches_the_generated_increments():
    cfg = BeamWanderConfig(n_paths=200, n_frames=300, rms_min_px=5.0, rms_max_px=5.0, drift_max_px_per_frame=0.0)
    tr = generate_traces(cfg, 3)
    d = np.diff(tr.centres_px, axis=1)
    expected = float(one_frame_motion_rms(cfg, 5.0))
    assert abs(np.sqrt(np.mean(d**2)) / expected - 1) < 0.03  # 120k increments, correlated over ~1 s
    shares = [c["variance_share"] for c in component_table(cfg)]
    np.testing.assert_allclose(sum(shares), 1.0)


def test_aliased_corners_only_on_request_and_not_recorded_by_default():
    with pytest.raises(ValueError, match="corner_frequencies_hz"):
        BeamWanderConfig(corner_frequencies_hz=(0.5, 30.0))
    cfg = BeamWanderConfig(n_paths=50, n_frames=400, corner_frequencies_hz=(30.0,), aliased_corners=True)
    tr = generate_traces(cfg, 2)
    d = tr.centres_px - tr.centres_px.mean(axis=1, keepdims=True)
    rho = component_table(cfg)[0]["frame_correlation"]
    assert rho < 0.01
    assert abs(np.mean(d[:, 1:] * d[:, :-1]) / np.mean(d * d)) < 0.05  # nearly white at 25 frames/s
    assert tr.metadata["config"]["aliased_corners"] is True
    assert "aliased_corners" not in generate_traces(BeamWanderConfig(n_paths=1, n_frames=5), 0).metadata["config"]


def test_first_order_rolloff_is_an_ornstein_uhlenbeck_process_and_stays_out_of_the_default_metadata():
    """roll-off f^-2: each component is first-order (lag-one correlation exp(-w dt), stationary variance
    sigma^2); the optimal model's wander block keeps that variance; the default records nothing new."""
    cfg = BeamWanderConfig(
        n_paths=400,
        n_frames=300,
        rms_min_px=4.0,
        rms_max_px=4.0,
        drift_max_px_per_frame=0.0,
        corner_frequencies_hz=(0.5,),
        rolloff="f^-2",
    )
    tr = generate_traces(cfg, seed=2)
    d = tr.centres_px - 63.5
    assert abs(np.var(d[:, -1]) / 16 - 1) < 0.1
    rho = np.exp(-2 * np.pi * 0.5 / 25)
    r1 = np.mean(d[:, 1:] * d[:, :-1]) / np.mean(d * d)
    assert abs(r1 - rho) < 0.01 and component_table(cfg)[0]["frame_correlation"] == pytest.approx(rho)
    F, Q, H, P0 = wander_state_space(cfg, np.array([4.0]))
    Pw = P0[0, :2, :2]
    np.testing.assert_allclose(F[:2, :2] @ Pw @ F[:2, :2].T + Q[0, :2, :2], Pw, rtol=1e-9, atol=1e-12)
    assert (
        "rolloff" in tr.metadata["config"]
        and "rolloff" not in generate_traces(BeamWanderConfig(), 1).metadata["config"]
    )
    with pytest.raises(ValueError, match="rolloff"):
        BeamWanderConfig(rolloff="f^-3")
