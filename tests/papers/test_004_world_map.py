"""004's register read into the world of a run (``world``): the generator, the camera, the exposure, the vibration
and the redraws that keep the spot on the sensor.

Every register value is checked against the generator and camera fields its description names, and every other
field is checked to stay at the shipped data set's generator (15 paths of 1000 frames at 25 frames/s on a 128 px
sensor, corners 0.02, 0.1 and 0.5 Hz, wander RMS 3-8 px, drift up to 0.02 px a frame, scintillation 0.3) and this
project's camera (a Gaussian spot of 4 px, 200 DN peak on 10 DN background, 2 DN read noise, 8 bits, a 31 px gate,
a 21 px window, a 3 sigma threshold). The wander's corners carry the bandwidth factor that keeps the paper's filter
at the paper's operating point (:func:`.operating.bandwidth_for`), or the factor a bandwidth value sets by hand.
"""

from dataclasses import fields, replace

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import REGISTER, world
from tvtrack.papers.p004_laser_spot_prediction.beam_wander import BeamWanderConfig
from tvtrack.papers.p004_laser_spot_prediction.camera import SpotCamera
from tvtrack.papers.p004_laser_spot_prediction.operating import bandwidth_for
from tvtrack.papers.p004_laser_spot_prediction.sizes import StudySize
from tvtrack.papers.p004_laser_spot_prediction.traces import TraceSet

DEFAULT = REGISTER.default()
SIZE = StudySize(n_paths=5, n_frames=300)
SHIPPED = dict(
    n_paths=15, n_frames=1000, frame_rate_hz=25.0, image_size_px=128, corner_frequencies_hz=(0.02, 0.1, 0.5),
    spectral_index=2.0 / 3.0, rms_min_px=3.0, rms_max_px=8.0, drift_max_px_per_frame=0.02,
    scintillation_sigma_ln=0.3, aliased_corners=False, rolloff="f^-4", exposure_s=0.0, field_offset_s=0.0,
)  # fmt: skip
CAMERA = dict(
    spot_sigma_px=4.0, peak_dn=200.0, background_dn=10.0, read_noise_dn=2.0, gain_e_per_dn=1.0, bit_depth=8,
    gate_size_px=31, threshold_sigma=3.0, centroid_mode="windowed", centroid_window_px=21.0,
)  # fmt: skip


def test_the_base_world_is_the_shipped_generator_and_this_projects_camera():
    assert {f.name: getattr(world.BASE_SCENE, f.name) for f in fields(BeamWanderConfig)} == SHIPPED
    assert {f.name: getattr(world.BASE_CAMERA, f.name) for f in fields(SpotCamera)} == CAMERA


def _scene_fields(config):
    s = world.scene_config(config, SIZE)
    return {f.name: getattr(s, f.name) for f in fields(BeamWanderConfig)}


def _want_scene(config, **moved):
    k = bandwidth_for(config)
    return {
        **SHIPPED,
        "n_paths": 5,
        "n_frames": 300,
        "corner_frequencies_hz": (0.02 * k, 0.1 * k, 0.5 * k),
        **moved,
    }


def test_the_default_world_is_the_shipped_one_at_the_calibrated_bandwidth_and_the_runs_sizes():
    k = bandwidth_for(DEFAULT)
    assert k != 1.0  # calibrated: the wander's corners move to the paper's operating point
    got = _scene_fields(DEFAULT)
    assert got == _want_scene(DEFAULT)
    assert got["corner_frequencies_hz"] == pytest.approx((0.02 * k, 0.1 * k, 0.5 * k), rel=1e-15)


SCENE_MOVES = {  # register entry -> the generator fields a value of it sets
    "spectral index": lambda v: {"spectral_index": float(v)},
    "roll-off": lambda v: {"rolloff": v},
    "amplitude": lambda v: {"rms_min_px": 3.0 * v, "rms_max_px": 8.0 * v},
    "frame rate": lambda v: {"frame_rate_hz": v, "drift_max_px_per_frame": 0.02 * 25.0 / v},  # the drift in px/s
    "scintillation": lambda v: {"scintillation_sigma_ln": v},
}
CAMERA_MOVES = {  # register entry -> the camera fields a value of it sets
    "read noise": lambda v: {"read_noise_dn": float(v)},
    "saturation": lambda v: {"bit_depth": {"8-bit": 8, "none": 16}[v]},
    "energy centre": lambda v: {"centroid_mode": {"windowed": "windowed", "whole gate": "gate"}[v]},
    "spot size": lambda v: {"spot_sigma_px": float(v)},
}


def _values():
    for name in REGISTER.names:
        for v in REGISTER[name].values:
            if v != REGISTER[name].default:
                yield pytest.param(name, v, id=f"{name}={v}")


@pytest.mark.parametrize("name,value", list(_values()))
def test_each_register_value_sets_the_generator_and_camera_fields_it_names_and_no_other(name, value):
    config = {**DEFAULT, name: value}
    assert _scene_fields(config) == _want_scene(config, **SCENE_MOVES.get(name, lambda v: {})(value))
    cam = world.camera_for(config)
    assert {f.name: getattr(cam, f.name) for f in fields(SpotCamera)} == {
        **CAMERA,
        **CAMERA_MOVES.get(name, lambda v: {})(value),
    }
    assert type(cam.read_noise_dn) is float and type(cam.spot_sigma_px) is float


def test_a_bandwidth_set_by_hand_scales_every_corner_by_it():
    for k in (1.0, 8.0, 3.0):
        corners = world.scene_config({**DEFAULT, "bandwidth": k}, SIZE).corner_frequencies_hz
        assert corners == pytest.approx((0.02 * k, 0.1 * k, 0.5 * k), rel=1e-15)


def test_a_world_entry_moves_the_calibrated_bandwidth_with_it():
    """The operating point is kept: a world whose wander is faster for the filter gets slower corners."""
    base = world.scene_config(DEFAULT, SIZE).corner_frequencies_hz[0]
    for name in ("spectral index", "roll-off", "error in the band", "amplitude"):
        for v in REGISTER[name].values:
            c = {**DEFAULT, name: v}
            got = world.scene_config(c, SIZE).corner_frequencies_hz[0]
            assert got == pytest.approx(0.02 * bandwidth_for(c), rel=1e-15)
            if v != DEFAULT[name] and (name, v) != ("roll-off", "G-tilt"):
                assert got != pytest.approx(base, rel=1e-6), (name, v)


def test_a_base_passed_in_is_the_one_scaled():
    base = replace(world.BASE_SCENE, rms_min_px=1.0, rms_max_px=2.0, drift_max_px_per_frame=0.01, frame_rate_hz=50.0,
                   corner_frequencies_hz=(0.1,))  # fmt: skip
    s = world.scene_config({**DEFAULT, "amplitude": 2.0, "frame rate": 200.0, "bandwidth": 2.0}, SIZE, base)
    assert (s.rms_min_px, s.rms_max_px, s.corner_frequencies_hz) == (2.0, 4.0, (0.2,))
    assert s.drift_max_px_per_frame == pytest.approx(0.01 * 50.0 / 200.0, rel=1e-15)
    cam = world.camera_for({**DEFAULT, "spot size": 0.6}, replace(world.BASE_CAMERA, gate_size_px=41))
    assert (cam.gate_size_px, cam.spot_sigma_px) == (41, 0.6)
    no_spot = {k: v for k, v in DEFAULT.items() if k != "spot size"}
    assert world.camera_for(no_spot, replace(world.BASE_CAMERA, spot_sigma_px=2.5)).spot_sigma_px == 2.5


def test_the_exposure_weights_newest_first():
    np.testing.assert_array_equal(world.exposure_weights("instant"), [1.0])
    np.testing.assert_array_equal(world.exposure_weights("full frame"), [0.25] * 4)
    # two fields of one frame interval each, the second half a frame earlier; the frame is their mean
    np.testing.assert_array_equal(
        world.exposure_weights("interlaced, frame integration"), [0.125, 0.125, 0.25, 0.25, 0.125, 0.125]
    )
    np.testing.assert_array_equal(world.exposure_weights("full frame", 2), [0.5, 0.5])
    np.testing.assert_array_equal(world.exposure_weights("interlaced, frame integration", 2), [0.25, 0.5, 0.25])
    with pytest.raises(ValueError, match="parameter 'exposure' = 'open'; it must be one of"):
        world.exposure_weights("open")


def _fake_generator(monkeypatch, seen):
    def generate(scene, seed):
        seen.append((scene, seed))
        n = scene.n_frames
        t = np.arange(n, dtype=float)
        xy = np.stack([t, 100.0 + 0.5 * t], axis=-1)[None].repeat(scene.n_paths, 0)
        meta = {"wander_rms_px": [3.0] * scene.n_paths}
        return TraceSet(xy, 1.0 + t[None].repeat(scene.n_paths, 0), scene.frame_rate_hz, scene.image_size_px, meta)

    monkeypatch.setattr(world, "generate_traces", generate)


@pytest.mark.parametrize(
    "exposure,weights",
    [("full frame", [0.25] * 4), ("interlaced, frame integration", [0.125, 0.125, 0.25, 0.25, 0.125, 0.125])],
)
def test_an_exposure_averages_the_sub_samples_up_to_each_frame_time(monkeypatch, exposure, weights):
    seen = []
    _fake_generator(monkeypatch, seen)
    scene = replace(world.BASE_SCENE, n_paths=2, n_frames=6)
    tr = world.exposed_traces(scene, 9, exposure)
    (fine, seed), = seen  # fmt: skip
    assert seed == 9 and (fine.n_frames, fine.frame_rate_hz) == (24, 100.0)
    assert fine.drift_max_px_per_frame == pytest.approx(0.005, rel=1e-15)  # the same px/s
    w = np.asarray(weights)
    for t in range(6):
        idx = np.maximum(4 * t + 3 - np.arange(w.size), 0)  # newest (the frame time) first, the start padded
        assert tr.centres_px[0, t, 0] == pytest.approx(float(w @ idx), rel=1e-12)
        assert tr.centres_px[1, t, 1] == pytest.approx(float(w @ (100.0 + 0.5 * idx)), rel=1e-12)
        assert tr.intensity[0, t] == pytest.approx(float(w @ (1.0 + idx)), rel=1e-12)
    assert tr.centres_px.shape == (2, 6, 2) and tr.metadata["exposure"] == exposure
    assert (tr.frame_rate_hz, tr.image_size_px) == (25.0, 128) and tr.metadata["wander_rms_px"] == [3.0, 3.0]


def test_an_exposure_of_other_sub_samples_per_frame(monkeypatch):
    seen = []
    _fake_generator(monkeypatch, seen)
    scene = replace(world.BASE_SCENE, n_paths=2, n_frames=6)
    tr = world.exposed_traces(scene, 9, "full frame", k=2)
    assert (seen[0][0].n_frames, seen[0][0].frame_rate_hz) == (12, 50.0)
    for t in range(6):
        assert tr.centres_px[0, t, 0] == pytest.approx(0.5 * (2 * t + 1) + 0.5 * (2 * t), rel=1e-12)


def test_an_instant_exposure_is_the_generator_itself(monkeypatch):
    seen = []
    _fake_generator(monkeypatch, seen)
    scene = replace(world.BASE_SCENE, n_paths=2, n_frames=6)
    tr = world.exposed_traces(scene, 4, "instant")
    assert seen == [(scene, 4)] and tr.centres_px[0, 5, 0] == 5.0


@pytest.mark.parametrize(
    "exposure,tau,delta",
    [("instant", 0.0, 0.0), ("full frame", 0.04, 0.0), ("interlaced, frame integration", 0.04, 0.02)],
)
def test_under_the_g_tilt_spectrum_the_exposure_is_exact(monkeypatch, exposure, tau, delta):
    seen = []
    _fake_generator(monkeypatch, seen)
    scene = replace(world.BASE_SCENE, n_paths=2, n_frames=6, rolloff="G-tilt")
    tr = world.exposed_traces(scene, 5, exposure)
    (got, seed), = seen  # fmt: skip
    assert got == replace(scene, exposure_s=tau, field_offset_s=delta) and seed == 5
    assert tr.metadata["exposure"] == exposure and tr.centres_px.shape == (2, 6, 2)
    assert tr.metadata["wander_rms_px"] == [3.0, 3.0]
    assert (tr.frame_rate_hz, tr.image_size_px) == (25.0, 128)


def test_the_vibration_is_an_8_hz_sinusoid_of_the_amplitude_with_drawn_phases():
    rng = np.random.default_rng(3)
    v = world.vibration(1.5, 25.0, (3, 400, 2), rng)
    phases = np.random.default_rng(3).uniform(0, 2 * np.pi, (3, 1, 2))
    t = np.arange(400)[None, :, None] / 25.0
    np.testing.assert_allclose(v, 1.5 * np.sin(2 * np.pi * 8.0 * t + phases), rtol=0, atol=1e-12)
    assert world.VIBRATION_HZ == 8.0 < 25.0 / 2  # below the Nyquist frequency of 25 frames/s
    a, b = np.random.default_rng(4), np.random.default_rng(4)
    assert not world.vibration(0.0, 25.0, (2, 10, 2), a).any()
    world.vibration(1.0, 25.0, (2, 10, 2), b)
    assert a.uniform() == b.uniform()  # the phases are drawn whatever the amplitude (common random numbers)


def test_a_set_that_leaves_the_sensor_is_drawn_again_from_the_streams_children(monkeypatch):
    calls = []

    def exposed(scene, seed, exposure):
        assert scene is world.BASE_SCENE and exposure == "full frame"
        calls.append(seed)
        if len(calls) < 3:
            raise ValueError("the spot would leave the sensor on path 2")
        return "traces"

    monkeypatch.setattr(world, "exposed_traces", exposed)
    stream = np.random.SeedSequence(12)
    assert world.traces_on_sensor(world.BASE_SCENE, stream, "full frame") == ("traces", 3)
    first = int(np.random.SeedSequence(12).generate_state(1)[0])
    assert calls[0] == first and len(set(calls)) == 3
    again = np.random.SeedSequence(12)
    again.generate_state(1)
    children = again.spawn(2)  # one child per redraw, in turn
    assert calls[1:] == [int(c.generate_state(1)[0]) for c in children]


def test_a_set_that_never_stays_on_the_sensor_or_another_error_is_refused(monkeypatch):
    calls = []

    def off(scene, seed, exposure):
        calls.append(seed)
        raise ValueError("the spot would leave the sensor")

    monkeypatch.setattr(world, "exposed_traces", off)
    with pytest.raises(ValueError, match="left the 128 px sensor on every one of 50 draws"):
        world.traces_on_sensor(world.BASE_SCENE, np.random.SeedSequence(1), "instant")
    assert len(calls) == world.MAX_DRAWS == 50

    def broken(scene, seed, exposure):
        raise ValueError("parameter 'n_paths' = 0")

    monkeypatch.setattr(world, "exposed_traces", broken)
    with pytest.raises(ValueError, match="n_paths"):
        world.traces_on_sensor(world.BASE_SCENE, np.random.SeedSequence(1), "instant")
