"""How often the armed detector decides (register entry ``test_cadence``, an unreported setting of paper 001: the
paper observes the velocities 'on an interval 2T' at the frame rate and never says how often (14) is taken)."""

import numpy as np
import pytest

from tvtrack.papers.p001_maneuver_occlusion_kf import study
from tvtrack.papers.p001_maneuver_occlusion_kf.register import DEPENDS, build_register

REG = build_register()
SIZES = dict(n_trials=120, n_fa_runs=300, fa_duration_s=12.0, sigma_eps=1.0, defaults=REG.default())


def test_cadence_tests_every_step_from_the_first_armed_frame():
    thr = np.full(300, 2.0)
    arm_k = 100  # TRACK2 count: first tested frame 99
    for cadence, step in (("every frame", 1), ("every n frames", 25), ("every 2n frames", 50)):
        out = study.cadence_threshold(thr, cadence, 25, arm_k)
        tested = np.flatnonzero(np.isfinite(out[99:])) + 99
        np.testing.assert_array_equal(tested, np.arange(99, 300, step))
        assert np.all(out[:99] == 2.0) and np.all(thr == 2.0)  # untouched before arming; input not changed
    with pytest.raises(ValueError, match="test cadence"):
        study.cadence_threshold(thr, "hourly", 25, arm_k)


def test_a_detector_deciding_once_per_interval_2t_detects_at_its_first_decision_after_the_onset():
    """Armed at k_b2 + 2n = 100 (frame 99), deciding once per 2T = 50 frames: decisions at frames 99, 149, 199 ...;
    the manoeuvre at frame 125 is found at frame 149 (5.96 s), outside C001-1's 5.25-5.75 s, while the sliding
    detector finds it at 5.52 s. Every detection sits on a decision frame."""
    rule = REG.default()
    assert rule["test_cadence"] == "every frame" and REG["test_cadence"].kind == "unreported setting"
    slide = study.measure_detection({}, 1, SIZES, claims={"C001-1"})["C001-1"]
    block = study.measure_detection({"test_cadence": "every 2n frames"}, 1, SIZES, claims={"C001-1"})["C001-1"]
    assert slide["median"].value == pytest.approx(5.52, abs=0.03)
    assert block["median"].value == pytest.approx(149 / 25, abs=1e-9)
    assert block["early"].value <= slide["early"].value
    from tvtrack.papers.p001_maneuver_occlusion_kf.claims import RULES

    assert RULES["C001-1"].parts["median"].decide(block["median"]) == "not reproduced"
    sc = study.config_scenario(rule)
    z = study.measurements(sc.truth[:, :, 0], "white Gaussian", 30, np.random.default_rng(3), 1.0)
    det = study.run_scheme(z, sc, rule | {"test_cadence": "every 2n frames"}, SIZES, covariance=False)
    d = det.detection_frame[det.detection_frame >= 0]
    assert d.size and np.all((d - 99) % 50 == 0)


def test_cadence_is_declared_only_by_the_claims_of_the_schemes_detection():
    """C001-1 and C001-4 read the scheme's detection; C001-2 and C001-3 judge the rule per test, C001-7 to -9 force
    the switch or have no detector."""
    assert [c for c, names in DEPENDS.items() if "test_cadence" in names] == ["C001-1", "C001-4"]
