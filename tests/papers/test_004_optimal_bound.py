"""Paper 004: the optimal-predictor bound is the Kalman filter of the generator's own model.

Its empirical one-step error on data drawn from that model must equal the innovation variance the
Riccati recursion predicts (an invariant that holds only with the right noise variances; planted bug:
the measurement standard deviation passed where its square belongs moves the error by 40 %)."""

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction.beam_wander import (
    BeamWanderConfig,
    generate_traces,
    optimal_wander_forecast,
    wander_state_space,
)
from tvtrack.papers.p004_laser_spot_prediction.predictors import forecast_errors

SD = 0.1  # px: sd and sd^2 differ tenfold


def _riccati_innovation_variance(F, Q, H, P0, R, n):
    P = P0
    for _ in range(n):
        Pm = F @ P @ F.T + Q
        S = float((H @ Pm @ H.T)[0, 0]) + R
        K = Pm @ H.T / S
        P = (np.eye(len(P)) - K @ H) @ Pm
    return S


@pytest.fixture(scope="module", params=["f^-4", "f^-2"])
def wander(request):
    cfg = BeamWanderConfig(
        n_paths=40, n_frames=400, rms_min_px=5.0, rms_max_px=5.0, drift_max_px_per_frame=0.0, rolloff=request.param
    )
    tr = generate_traces(cfg, 21)
    truth = np.moveaxis(tr.centres_px, -1, -2)[None]  # (1, P, 2, T)
    z = truth + SD * np.random.default_rng(3).standard_normal(truth.shape)
    return cfg, np.asarray(tr.metadata["wander_rms_px"]), z


def test_optimal_forecast_error_equals_the_riccati_innovation_variance(wander):
    cfg, rms, z = wander
    F, Q, H, P0 = wander_state_space(cfg, rms[:1])
    S = _riccati_innovation_variance(F, Q[0], H, P0[0], SD**2, 400)
    e = forecast_errors(optimal_wander_forecast(z, cfg, rms, SD**2, 1), z, 1)[..., 100:]
    # 40 paths x 2 axes x 299 white innovations: relative standard error of the mean square ~ 0.8 %
    assert np.mean(e**2) / S == pytest.approx(1.0, abs=0.04)


def test_the_bound_is_below_a_mismatched_filter(wander):
    cfg, rms, z = wander
    mse = {
        r: np.mean(forecast_errors(optimal_wander_forecast(z, cfg, rms, r, 1), z, 1)[..., 100:] ** 2)
        for r in (SD**2, SD, SD**2 / 10)
    }
    assert mse[SD**2] < 1.005 * min(mse[SD], mse[SD**2 / 10])  # optimal, up to the sample
    if cfg.rolloff == "f^-4":  # smooth wander: the measurement noise is a large part of the error
        assert mse[SD**2] < 0.9 * mse[SD]
