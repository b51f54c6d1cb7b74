"""Notebook 004: the scintillation model (whole-spot log-normal fading) and its register sweep."""

import numpy as np
import pytest

from tvtrack.papers.p004_laser_spot_prediction.beam_wander import BeamWanderConfig, generate_traces
from tvtrack.papers.p004_laser_spot_prediction.camera import SpotCamera, track_spot
from tvtrack.papers.p004_laser_spot_prediction.params import check_consistency
from tvtrack.papers.p004_laser_spot_prediction.register import explored


@pytest.mark.parametrize("sigma", [0.3, 0.8])
def test_irradiance_is_log_normal_with_the_register_s_index(sigma):
    """ln I ~ N(-sigma^2/2, sigma^2): mean 1, scintillation index Var(I)/E(I)^2 = exp(sigma^2) - 1. On 200 000
    frames the sample index is within 5 % (its spread: 1.3 % at sigma = 0.8, log-normal kurtosis 34) and the
    sample sd of ln I within 1 %."""
    tr = generate_traces(BeamWanderConfig(n_paths=200, n_frames=1000, scintillation_sigma_ln=sigma), 11)
    i = tr.intensity.ravel()
    assert np.var(i) / np.mean(i) ** 2 == pytest.approx(np.expm1(sigma**2), rel=0.05)
    assert np.mean(i) == pytest.approx(1.0, abs=0.01)
    assert np.std(np.log(i)) == pytest.approx(sigma, rel=0.01)
    assert abs(np.corrcoef(i[:-1], i[1:])[0, 1]) < 0.01  # i.i.d. per frame


def test_the_rendered_spot_fades_as_a_whole():
    """Whole-spot fading: the background-subtracted sum of each rendered gate is the spot's flux times the
    frame's factor (sample scintillation index of the gate sums = exp(0.09) - 1 within 10 %: 5000 gates, Poisson
    and read noise add 0.1 % of it); the spot's shape (its second moment) does not fade."""
    T, sigma = 5000, 0.3
    tr = generate_traces(
        BeamWanderConfig(
            n_paths=1,
            n_frames=T,
            rms_min_px=0.0,
            rms_max_px=0.0,
            drift_max_px_per_frame=0.0,
            scintillation_sigma_ln=sigma,
        ),
        3,
    )
    cam = SpotCamera(bit_depth=16, centroid_window_px=21.0)
    trk = track_spot(tr.centres_px, tr.intensity, np.random.default_rng(1), cam, 128, keep=(0,))
    signal = trk.gates.sum(axis=(1, 2)) - cam.background_dn * cam.gate_size_px**2
    assert np.var(signal) / np.mean(signal) ** 2 == pytest.approx(np.expm1(sigma**2), rel=0.1)
    expected = cam.flux_e * tr.intensity[0]
    noise_sd = np.sqrt(expected + cam.gate_size_px**2 * (cam.background_dn + cam.read_noise_dn**2))  # Poisson + read
    z = (signal - expected) / noise_sd
    assert np.max(np.abs(z)) < 5 and np.std(z) == pytest.approx(1.0, rel=0.1)
    g = cam.gate_size_px
    r2 = ((np.arange(g) - (g - 1) / 2) ** 2)[None, :] + ((np.arange(g) - (g - 1) / 2) ** 2)[:, None]
    bright, dim = np.argsort(tr.intensity[0])[[-1, 0]]
    width = [np.sum(r2 * (trk.gates[k] - cam.background_dn)) / signal[k] for k in (bright, dim)]
    assert width[0] == pytest.approx(width[1], rel=0.1)  # same shape at the brightest and the dimmest frame


def test_a_moved_scintillation_default_is_explored_and_joins_the_values():
    reg, _ = explored(["scintillation"], {"scintillation": 1.2})
    assert reg["scintillation"].default == 1.2 and set(reg["scintillation"].values) == {0.3, 0.8, 1.2}
    with pytest.raises(ValueError, match="not explored"):
        explored(["horizon"], {"scintillation": 1.2})
    base = {"max_replicates": 3, "n_trials": 3, "n_folds": 2, "n_paths": 6}
    with pytest.raises(ValueError, match="scintillation_sigma_ln"):
        check_consistency({**base, "explore_entries": ["horizon"], "scintillation_sigma_ln": 1.2})
    check_consistency({**base, "explore_entries": [], "scintillation_sigma_ln": 1.2})


def test_overlapping_intervals_are_not_called_no_change(monkeypatch):
    """The table's sentence says "grows" or "shrinks" only where the two levels' 95 % intervals are disjoint; where
    they overlap it says the change is not shown, and that a change of the measured size stays possible (overlap of
    two unpaired intervals is no evidence of no change)."""
    from tvtrack.estimate import Estimate
    from tvtrack.papers.p004_laser_spot_prediction import findings, side_studies

    est = lambda v, lo, hi: Estimate(v, (hi - lo) / 4, lo, hi, 15, method="t")  # noqa: E731
    values = {
        findings.CENTROID: {0.3: est(0.04, 0.039, 0.041), 0.8: est(0.06, 0.058, 0.062)},  # disjoint: grows
        "C004-2": {0.3: est(1.438, 1.167, 1.879), 0.8: est(1.343, 1.187, 1.557)},  # the record's: overlapping
    }
    monkeypatch.setattr(side_studies, "single_values", lambda ex, cid, entry: values[cid])
    text = findings.scintillation_table(None)
    assert "the centroid error grows (x1.50)" in text
    assert "the prediction error is not shown to change (x0.93; the intervals overlap, which leaves" in text
    assert "does not change" not in text
