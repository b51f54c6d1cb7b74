"""Tests of the detector summaries in tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector and of manoeuvre_truth (notebook 001)."""

import numpy as np
import pytest

from tvtrack.papers.p001_maneuver_occlusion_kf.maneuver_detector import (
    detection_time_summary,
    false_alarm_rates,
)
from tvtrack.papers.p001_maneuver_occlusion_kf.track_modes import manoeuvre_truth


def test_false_alarm_rates_count_alarms_per_test_and_per_run():
    S = np.array(
        [[0.0, 3.0, 0.0, 0.0], [0.0, 0.0, 0.0, -3.0], [0.0, 0.0, 0.0, 0.0], [9.0, 0.0, 0.0, 0.0]]
    )  # frame 0 is not armed: its alarm never counts
    armed = np.array([False, True, True, True])
    pre = np.array([False, True, False, False])
    r = false_alarm_rates(S, 2.0, armed, pre, test_frame=3, arming_frame=1)
    assert r["per_test_fixed_frame"].value == 0.25
    assert r["per_test_at_arming"].value == 0.25
    assert r["per_test_pooled"].value == pytest.approx(2 / 12)
    assert r["per_run_before_onset"].value == 0.25
    assert r["per_run_whole"].value == 0.5
    assert false_alarm_rates(S, 2.0, armed, np.zeros(4, bool), 3, 1)["per_run_before_onset"] is None
    with pytest.raises(ValueError, match="'S'"):
        false_alarm_rates(S[0], 2.0, armed, pre, 3, 1)


def test_detection_time_summary_splits_early_hits_and_misses():
    d = np.array([[-1, 5], [12, 13], [14, 30], [12, 12]])  # onset 10, loss 20, 10 frames/s
    s = detection_time_summary(d, onset=10, loss_frame=20, frame_rate_hz=10.0)
    assert s["false_alarm_before_onset"].value == 1 / 8
    assert s["missed_by_loss"].value == 2 / 8  # never, and after the loss
    assert s["median_s"].value == pytest.approx(1.25)  # hits at 1.2 1.2 1.2 1.3 1.4 3.0 s (after the loss too)
    assert s["mean_s"].value == pytest.approx(np.mean([1.2, 1.3, 1.4, 3.0, 1.2, 1.2]))
    assert detection_time_summary(np.array([-1, -1]), 10, 20, 10.0)["median_s"] is None


def test_manoeuvre_truth_is_uniform_then_quadratic():
    tr = manoeuvre_truth(10.0, 0.2, 5, 12)
    f = np.arange(12)
    np.testing.assert_allclose(tr[:6, 0], 10.0 * f[:6])
    np.testing.assert_allclose(np.diff(tr[:, 0], 2)[5:], 0.2)  # second difference = acceleration after onset
    np.testing.assert_allclose(np.diff(tr[:, 0])[4:], tr[4:-1, 1] + 0.1 * (f[4:-1] >= 5))
    assert tr[4, 2] == 0.0 and tr[5, 2] == 0.2
    with pytest.raises(ValueError, match="n_frames"):
        manoeuvre_truth(1.0, 0.1, 0, 0)
