"""C001-4's switch reading: the scheme's errors with its detector's switch (the default) or with the switch forced at
the paper's detection time, as Fig. 4 is computed here, and how much of the random error the detection
time's spread makes."""

import sys

import numpy as np
import pytest

from tvtrack.papers.p001_maneuver_occlusion_kf import study, tradeoff
from tvtrack.papers.p001_maneuver_occlusion_kf.curves import forced_output
from tvtrack.papers.p001_maneuver_occlusion_kf.register import DEPENDS, build_register
from tvtrack.papers.p001_maneuver_occlusion_kf.scenario import with_defaults, config_scenario, measurements, span_mask

sys.path.insert(0, str(__import__("pathlib").Path(__file__).parent))
from test_001_study import SIZES  # noqa: E402

SZ = SIZES | {"n_tradeoff_trials": 40}


def test_the_switch_reading_is_declared_with_the_forced_time():
    reg = build_register()
    assert reg["C001-4 switch"].default == "detected" and reg["C001-4 switch"].side == "reading"
    assert {"C001-4 switch", "switch_s"} <= set(DEPENDS["C001-4"])


def test_forced_reading_switches_at_switch_s_as_fig4_does():
    """Under the forced reading the scheme is the Fig. 4 filter: on the same measurements its channel-x positions
    equal curves.forced_output's (an independent path to the forced switch), and its switch frame is 5.5 s."""
    cfg = with_defaults(build_register().default() | {"C001-4 switch": "forced at the detection time"}, SZ)
    sc = config_scenario(cfg)
    z = measurements(sc.truth[:, :, 0], cfg["noise"], 5, np.random.default_rng(1), 1.0)
    got = study.run_scheme(z, sc, cfg, SZ, covariance=False, **tradeoff._switch(cfg, sc))
    ref = forced_output(sc, cfg, SZ, int(cfg["k_bound3"]), sc.visible, z=z[:, 0], covariance=False)
    np.testing.assert_allclose(got.x[:, 0, :, 0], ref.x[..., 0], atol=1e-9)
    assert tradeoff._switch(build_register().default() | {"switch_s": 5.5}, sc) == {}


def test_switch_share_is_one_minus_the_forced_over_detected_random_error():
    """The share recomputed from the two filters' errors directly (variance over runs, mean over the RMS span),
    and it is positive: the detector's random switch time adds random error to the scheme's."""
    cfg = with_defaults(build_register().default(), SZ)
    sc = config_scenario(cfg)
    got = tradeoff.switch_share({}, 9, SZ)
    z = measurements(sc.truth[:, :, 0], cfg["noise"], SZ["n_tradeoff_trials"], np.random.default_rng(9), 1.0)
    frames = span_mask(cfg["rms_span"], sc)
    var = []
    for over in (tradeoff._switch(cfg | {"C001-4 switch": "forced at the detection time"}, sc), {}):
        err = study.run_scheme(z, sc, cfg, SZ, covariance=False, **over).x[..., 0] - sc.truth[None, :, :, 0]
        var.append(err[..., frames].var(axis=0).mean())
    assert got["forced / detected"].value == pytest.approx(var[0] / var[1], rel=1e-9)
    assert got["share"] == pytest.approx(1 - var[0] / var[1], rel=1e-9) and 0 < got["share"] < 1
