"""Paper 004: the values the claims read, pinned against their derivations and hand-made cases.

The calibration target is the middle of the paper's "1...2 pixels"; the tuning grid's extension is checked on a
method whose error has a known optimum past the grid; the model-order summary is read from a hand-made study run
whose per-method errors and Singer fits are known.
"""

from __future__ import annotations

import inspect
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction import calibration, operating
from tvtrack.papers.p004_laser_spot_prediction.prediction_study import FADING, PAPER, SINGER, tuned_forecast
from tvtrack.papers.p004_laser_spot_prediction.register import DEFAULT
from tvtrack.papers.p004_laser_spot_prediction.side_studies import model_order_summary
from tvtrack.papers.p004_laser_spot_prediction.study import OPTIMAL, StudySize


def test_calibration_aims_at_the_middle_of_the_papers_band():
    # the paper: one-step error "1...2 pixels" (abstract, conclusions); the target is its middle, 1.5 px per axis
    assert operating.BAND_PX == (1.0, 2.0)
    assert calibration.TARGET_PX == pytest.approx(1.5)
    assert inspect.signature(calibration.calibrate_bandwidth).parameters["target_px"].default == 1.5


FOLDS = [(np.setdiff1d(np.arange(4), [p]), np.array([p])) for p in range(4)]
SETUP = SimpleNamespace(steps=1, start=0)


def _maker(optimum):
    """A method whose forecast errs ``1 + |ln(c / optimum)|`` px at every frame (per-path MSE its square)."""

    def make(c):
        return np.full((1, 4, 2, 12), 1.0 + abs(np.log(c / optimum)))

    return make


def test_tuning_extends_the_grid_while_the_last_value_wins():
    # optimum 70 beyond the grid (5, 10, 20): 45 is tried (the last won), then 70 (45 won), then 100 (70 won);
    # 100 loses, so the extension stops there and every fold picks 70
    z = np.zeros((1, 4, 2, 12))
    fc, mse, chosen, fcs, all_mse = tuned_forecast(
        (5, 10, 20), _maker(70.0), z, 0.0, FOLDS, SETUP, more=(10, 45, 70, 100)
    )
    assert all_mse.shape[0] == 6 and len(fcs) == 6  # 5, 10, 20, 45, 70, 100 (10 is already in the grid)
    np.testing.assert_array_equal(chosen, [70, 70, 70, 70])
    np.testing.assert_allclose(mse, 1.0)
    # an optimum inside the grid: nothing is added
    _, _, chosen_in, fcs_in, _ = tuned_forecast((5, 10, 20), _maker(10.0), z, 0.0, FOLDS, SETUP, more=(45, 70, 100))
    assert len(fcs_in) == 3
    np.testing.assert_array_equal(chosen_in, [10, 10, 10, 10])


def test_tuning_extends_the_grid_when_any_fold_picks_the_last_value():
    # paths 0-2 err least at 70 (weight 1), path 3 at 10 (weight 10): the fold tested on path 3 trains on paths
    # 0-2 and picks the grid's last value (20), the others pick 10; one such fold is enough to try 45, 70, 100
    opt, w = np.array([70.0, 70.0, 70.0, 10.0]), np.array([1.0, 1.0, 1.0, 10.0])

    def make(c):
        return np.broadcast_to((1.0 + w * np.abs(np.log(c / opt)))[None, :, None, None], (1, 4, 2, 12)).copy()

    z = np.zeros((1, 4, 2, 12))
    _, _, chosen, fcs, _ = tuned_forecast((5, 10, 20), make, z, 0.0, FOLDS, SETUP, more=(45, 70, 100))
    assert len(fcs) == 6
    np.testing.assert_array_equal(chosen, [10, 10, 10, 70])


def _run():
    """A study run: 2 trials x 4 paths x 2 axes x 20 frames; each method errs a constant per path (trial 0) and
    twice that in trial 1; the Singer fits per fold are (tau frames, accel var, meas var)."""
    level = {
        PAPER: 1.0,
        "finite differences, 2 points": 1.3,
        "linear regression deg 1": 1.1,
        "finite differences, 3 points": 1.6,
        "linear regression deg 2": 0.9,
        FADING: 1.2,
        SINGER: 0.95,
        OPTIMAL: 0.5,
    }
    scale = np.array([1.0, 1.5, 0.8, 1.2])[None, :, None, None] * np.array([1.0, 2.0])[:, None, None, None]
    forecasts = {n: v * scale * np.ones((2, 4, 2, 20)) for n, v in level.items()}
    fits = [(3.0, 0.02, 0.4), (5.0, 0.03, 0.5), (4.0, 0.02, 0.45), (6.0, 0.01, 0.6)]
    return SimpleNamespace(
        config={**DEFAULT, "horizon": 1},
        forecasts=forecasts,
        z_meas=np.zeros((2, 4, 2, 20)),
        size=replace(StudySize(), eval_start=2),
        comparison=SimpleNamespace(chosen={SINGER: fits}),
        scene=SimpleNamespace(frame_rate_hz=25.0),
    ), level


def test_model_order_summary_reads_trial_zero_and_the_singer_tau_column():
    run, level = _run()
    s = model_order_summary(run)
    ms_path = np.array([1.0, 1.5, 0.8, 1.2]) ** 2  # trial 0's per-path mean square per unit level
    for name, v in level.items():
        assert s["rms"][name] == pytest.approx(v * np.sqrt(ms_path.mean()), rel=1e-12)
    assert s["best"] == "linear regression deg 2"  # the optimal predictor is left out
    assert (s["best_order1"], s["best_order2"]) == ("linear regression deg 1", "linear regression deg 2")
    assert s["ratio_2_over_1"].value == pytest.approx((0.9 / 1.1) ** 2, rel=1e-12)
    np.testing.assert_array_equal(s["singer_tau_frames"], [3.0, 5.0, 4.0, 6.0])
    assert s["tau_over_horizon"] == pytest.approx(4.5)
    assert s["frame_ms"] == pytest.approx(40.0)
