"""003's register read into the simulated scene: each entry's values change exactly the :class:`Scenario` fields
their descriptions name, by the amounts the paper's numbers give (marker diameter D = 8 px, the residual share
kappa = 0.1 of the static scene, the coordinate loop's B_xy = 10 Hz, the radius loop's 0.2 Hz, the phase loop's 6 Hz,
500 frames a second), and nothing else. An entry the scene does not read (a loss criterion's, a statistic's, the
static baseline's, Fig. 2's law) changes no field."""

from __future__ import annotations

import dataclasses
import math

import pytest

from tvtrack.papers.p003_rotating_marker_tracker import study
from tvtrack.papers.p003_rotating_marker_tracker.register import REGISTER

D = 8.0  # marker diameter, px

#: entry -> {value: the scene fields it changes, with their values}; values absent from an entry's map change none
SCENE = {
    "motion": {"sinusoids": {"motion": "sinusoids"}, "random": {"motion": "random"}},
    "motion_scale": {0.25: {"x_std": 2.5, "y_amplitude": 5.0}, 2.0: {"x_std": 20.0, "y_amplitude": 40.0}},
    "interference_motion": {"hovering": {}},  # read by interference_scenario only (below)
    "sinusoid_hz": {1.5: {"y_freq": 1.5}},
    "rotation_rate": {
        "modulated": {"omega_mod": 0.1},  # depth 10 % at the default's 0.5 Hz
        "modulated fast": {"omega_mod": 0.15, "omega_mod_hz": 1.0},
        "modulated strong": {"omega_mod": 0.2, "omega_mod_hz": 1.0},
    },
    "bandwidth_reading": {  # the noise-equivalent bandwidth: first-order loops 2/pi of the -3 dB, omega's 0.617
        "noise-equivalent": {"b_xy": 10.0 * 2 / math.pi, "b_r": 0.2 * 2 / math.pi, "b_omega": 6.0 * 0.617}
    },
    "phase_loop": {"realised": {"realise_phase_bandwidth": True}},
    "noise": {0.01: {"noise_std": 0.01}, 0.05: {"noise_std": 0.05}},
    "fps": {50.0: {"fps": 50.0}, 250.0: {"fps": 250.0}, 1000.0: {"fps": 1000.0}},
    "exposure": {"integrated": {"exposure": "integrated"}},
    "spot": {"square": {"spot": "square"}},
    "compensation": {"temporal median": {"compensation": "median"}},
    # the residual background's std is 1 / (kappa * contrast): 0.2 at the default 50, 0.1 at 100
    "residual_background": {100.0: {"background_std": 0.1}},
    "interferer_radius": {
        "r0 - D/2": {"interferer_radius_offset": -D / 2},
        "r0 + D/2": {"interferer_radius_offset": D / 2},
        "jitter D/2": {"interferer_jitter": D / 2},
    },
    "interferer_layout": {"independent": {"interferer_layout": "independent"}},
    "interferer_size": {"2D": {"interferer_diameter": 2 * D}},
    "placement": {"image": {"interferer_centre": "image"}, "trace": {"interferer_centre": "trace"}},
    "horizon": {"2T": {"duration_s": 10.0}},  # twice the interference runs' 5 s
    "edge_norm": {"slew": {"edge_norm": "slew"}},
    "decoy_brightness": {"emitted": {"decoy_gain": 10.0}},  # 1 / kappa: compensation cannot remove a moving decoy
}
#: entries read outside the scene: the loss criterion (below), the statistic, the static baseline, Fig. 2's law
NOT_IN_SCENE = {"fig2_law", "slope_range", "loss_window_s", "loss_radius", "static_gate", "static_form"}


def _fields(sc) -> dict:
    return {f.name: getattr(sc, f.name) for f in dataclasses.fields(sc)}


SIZES = study.Sizes()


def _changed(config: dict, make=study.scenario, sizes=SIZES) -> dict:
    base, got = _fields(make(REGISTER.default(), sizes)), _fields(make(config, sizes))
    return {k: v for k, v in got.items() if v != base[k]}


def _approx(d: dict) -> dict:
    return {k: pytest.approx(v) if isinstance(v, float) else v for k, v in d.items()}


def test_every_register_entry_is_mapped_here():
    assert set(SCENE) | NOT_IN_SCENE == set(REGISTER.names) and not set(SCENE) & NOT_IN_SCENE


def test_the_default_scene_has_the_papers_numbers():
    sc = study.scenario(REGISTER.default())
    assert (sc.diameter, sc.kappa, sc.fps, sc.rotation_hz, sc.gate_half) == (D, 0.1, 500.0, 8.0, 1.5 * D)
    assert (sc.b_xy, sc.b_r, sc.b_omega) == (10.0, 0.2, 6.0)
    assert (sc.background_std, sc.noise_std, sc.duration_s, sc.x_std, sc.y_amplitude) == (0.2, 0.02, 5.0, 10.0, 20.0)
    assert (sc.omega_mod, sc.interferer_radius_offset, sc.interferer_jitter, sc.decoy_gain) == (0.0, 0.0, 0.0, 1.0)
    assert (sc.realise_phase_bandwidth, sc.interferer_diameter, sc.compensation) == (False, None, "kappa")


@pytest.mark.parametrize("entry", sorted(SCENE))
def test_each_value_changes_the_fields_it_names_and_no_other(entry):
    e = REGISTER[entry]
    for value in e.alternatives:
        want = SCENE[entry].get(value, {})
        assert _changed({**REGISTER.default(), entry: value}) == _approx(want), (entry, value)


@pytest.mark.parametrize("entry", sorted(NOT_IN_SCENE))
def test_an_entry_read_elsewhere_leaves_the_scene_as_it_was(entry):
    for value in REGISTER[entry].alternatives:
        assert _changed({**REGISTER.default(), entry: value}) == {}, (entry, value)


def test_an_absent_entry_reads_its_default():
    assert _fields(study.scenario({})) == _fields(study.scenario(REGISTER.default()))
    assert _fields(study.interference_scenario({})) == _fields(study.interference_scenario(REGISTER.default()))


def test_the_interference_runs_hold_the_object_still_only_when_hovering():
    hover = {**REGISTER.default(), "interference_motion": "hovering"}
    assert _changed(hover, study.interference_scenario) == {"x_std": 0.0, "y_amplitude": 0.0}
    both = {**hover, "motion_scale": 2.0, "noise": 0.05}  # hovering wins over the scale; the rest is read as before
    assert _changed(both, study.interference_scenario) == {"x_std": 0.0, "y_amplitude": 0.0, "noise_std": 0.05}
    moving = {**REGISTER.default(), "motion_scale": 2.0}
    assert _changed(moving, study.interference_scenario) == {"x_std": 20.0, "y_amplitude": 40.0}
    assert _fields(study.interference_scenario(hover, study.Sizes(), x_std=3.0))["x_std"] == 3.0  # an override wins


def test_the_sizes_set_the_run_length_and_rotation_and_an_override_wins():
    sizes = dataclasses.replace(study.Sizes(), horizon_s=2.0, rotation_hz=4.0)
    assert _fields(study.scenario({}, sizes))["duration_s"] == 2.0
    assert _fields(study.interference_scenario({}, sizes))["duration_s"] == 2.0  # the interference runs' too
    hover = {"interference_motion": "hovering"}
    assert _fields(study.interference_scenario(hover, sizes))["rotation_hz"] == 4.0
    assert _fields(study.scenario({"horizon": "2T"}, sizes))["duration_s"] == 4.0
    assert _fields(study.scenario({}, sizes))["rotation_hz"] == 4.0
    assert _fields(study.scenario({"fps": 50.0}, sizes, fps=100.0, n_interferers=5))["fps"] == 100.0
    assert _fields(study.scenario({}, sizes, n_interferers=5))["n_interferers"] == 5


def test_two_entries_together_change_both_fields():
    cfg = {**REGISTER.default(), "motion_scale": 0.25, "bandwidth_reading": "noise-equivalent", "fps": 250.0}
    want = {**SCENE["motion_scale"][0.25], **SCENE["bandwidth_reading"]["noise-equivalent"], "fps": 250.0}
    assert _changed(cfg) == _approx(want)


@pytest.mark.parametrize(
    "config, radius, frames",
    [
        ({}, 1.5 * D, 250),  # the gate half-size, 0.5 s at 500 frames a second
        ({"loss_radius": "D/2"}, D / 2, 250),
        ({"loss_window_s": 0.25}, 1.5 * D, 125),
        ({"loss_window_s": 1.0, "loss_radius": "D/2"}, D / 2, 500),
        ({"fps": 50.0}, 1.5 * D, 25),  # the window is in seconds: fewer frames at a lower rate
        ({"loss_window_s": 0.001}, 1.5 * D, 1),  # never shorter than one frame
    ],
)
def test_the_loss_criterion_reads_its_window_in_seconds_and_its_radius(config, radius, frames):
    for cfg in ({**REGISTER.default(), **config}, config):  # an entry left out reads its default
        crit = study.criterion(cfg, study.scenario(cfg))
        assert (crit.threshold, crit.window, crit.fraction, crit.kind) == (pytest.approx(radius), frames, 0.5, "window")
