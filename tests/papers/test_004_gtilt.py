"""Notebook 004: Tyler's G-tilt wander spectrum and its exposure averaging (beam_wander.gtilt_*)."""

from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import quad

from tvtrack.papers.p004_laser_spot_prediction.beam_wander import (
    GTILT,
    BeamWanderConfig,
    generate_traces,
    one_frame_motion_rms,
)
from tvtrack.papers.p004_laser_spot_prediction.gtilt import (
    exposure_gain,
    gtilt_asymptotes,
    gtilt_crossing,
    gtilt_psd,
    gtilt_shape,
)

#: Slope tolerance of a periodogram fit: the shape itself departs from its asymptote by up to 0.04 over the
#: fitted bands (perpendicular axis, low band), and the averaged periodogram's fit scatters by about 0.03.
SLOPE_TOL = 0.1


def _unit(**kw):
    base = dict(rms_min_px=1.0, rms_max_px=1.0, drift_max_px_per_frame=0.0, rolloff=GTILT)
    return BeamWanderConfig(**{**base, **kw})


def _periodogram_slopes(cfg, f_lo, f_hi, seed=3):
    """Log-log slope of the path-averaged Hann periodogram over [f_lo, f_hi], per axis."""
    x = generate_traces(cfg, seed).centres_px - (cfg.image_size_px - 1) / 2
    p = np.abs(np.fft.rfft(x * np.hanning(cfg.n_frames)[None, :, None], axis=1)) ** 2
    f = np.fft.rfftfreq(cfg.n_frames, 1 / cfg.frame_rate_hz)
    m = (f >= f_lo) & (f <= f_hi)
    return [np.polyfit(np.log(f[m]), np.log(p[:, m, a].mean(axis=0)), 1)[0] for a in (0, 1)]


@pytest.mark.parametrize("axis", ["parallel", "perpendicular"])
def test_shape_meets_its_closed_form_asymptotes(axis):
    """The quadrature of g(x) approaches Tyler's G-tilt asymptotes c_lo x^-2/3 and c_hi x^-11/3 (constants
    in closed form by Beta functions): a wrong aperture filter (Z-tilt's falls as x^-17/3) or tilt weight fails."""
    c_lo, c_hi = gtilt_asymptotes(axis)
    assert gtilt_shape(1e-3 * 1.001, axis) == pytest.approx(c_lo * (1e-3 * 1.001) ** (-2 / 3), rel=0.03)
    assert gtilt_shape(300.0, axis) == pytest.approx(c_hi * 300.0 ** (-11 / 3), rel=0.05)
    # and the crossing sets the corner: below it the low asymptote, above it the high one, dominates
    xc = gtilt_crossing()
    assert gtilt_shape(xc / 30, "parallel") == pytest.approx(gtilt_asymptotes()[0] * (xc / 30) ** (-2 / 3), rel=0.1)


def test_generated_paths_follow_the_low_frequency_asymptote():
    """Periodogram slope of generated paths well below the corner (x = f D/v in [0.002, 0.02]): -2/3."""
    v_over_d = 12.5
    cfg = _unit(n_paths=96, n_frames=16384, frame_rate_hz=100.0, corner_frequencies_hz=(v_over_d * gtilt_crossing(),))
    for s in _periodogram_slopes(cfg, 0.002 * v_over_d, 0.02 * v_over_d):
        assert s == pytest.approx(-2 / 3, abs=SLOPE_TOL)


def test_generated_paths_follow_the_high_frequency_asymptote():
    """Periodogram slope well above the corner (x in [30, 150], below half the Nyquist frequency): -11/3."""
    v_over_d = 5.0 / 30
    cfg = _unit(n_paths=40, n_frames=8192, frame_rate_hz=100.0, corner_frequencies_hz=(v_over_d * gtilt_crossing(),))
    for s in _periodogram_slopes(cfg, 5.0, 25.0):
        assert s == pytest.approx(-11 / 3, abs=SLOPE_TOL)


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("exposure_s,field_offset_s", [(0.2, 0.0), (0.04, 0.02)])
def test_exposure_lowers_the_variance_by_the_integral_of_the_spectrum_times_sinc_squared(exposure_s, field_offset_s):
    """Mean square of the exposed wander / instant (same draws) = int S sinc^2(pi f tau) cos^2(pi f delta) df /
    int S df over f >= the record's fundamental, by independent adaptive quadrature of the continuous spectrum
    (no folding, no frequency bins). Tolerance 1 % (the draws' spread is about 0.1 %): a missing square (sinc
    instead of sinc^2) moves the 5-frame exposure's ratio by far more."""
    fs, corner = 25.0, 5.0
    cfg = _unit(n_paths=400, n_frames=1000, frame_rate_hz=fs, corner_frequencies_hz=(corner,))
    exp = replace(cfg, exposure_s=exposure_s, field_offset_s=field_offset_s)
    x0 = generate_traces(cfg, 5).centres_px - 63.5
    x1 = generate_traces(exp, 5).centres_px - 63.5
    edges = [fs / cfg.n_frames, corner, fs, 4 * fs, 40 * fs, 1e5]
    for a, axis in enumerate(("parallel", "perpendicular")):

        def integral(gain, axis=axis):
            return sum(
                quad(lambda f: gtilt_psd(f, corner, axis) * gain(f), lo, hi, limit=500)[0]
                for lo, hi in zip(edges[:-1], edges[1:])
            )

        expected = integral(lambda f: exposure_gain(f, exposure_s, field_offset_s)) / integral(lambda f: 1.0)
        assert expected < 0.97  # the exposure matters here
        assert np.mean(x1[..., a] ** 2) / np.mean(x0[..., a] ** 2) == pytest.approx(expected, rel=0.01)


def test_exposure_gain_is_sinc_squared():
    f = np.array([0.0, 5.0, 12.5, 25.0])
    np.testing.assert_allclose(
        exposure_gain(f, 0.04), [1.0, (np.sin(np.pi * 0.2) / (np.pi * 0.2)) ** 2, 4 / np.pi**2, 0.0], atol=1e-15
    )
    np.testing.assert_allclose(exposure_gain(f, 0.0, 0.02), np.cos(np.pi * f * 0.02) ** 2)


def test_gtilt_paths_have_the_drawn_rms_and_a_one_frame_step_from_the_spectrum():
    """Instant G-tilt wander: mean square per axis = the drawn RMS^2 (the instant spectrum is normalised to
    it); the one-frame step RMS used for the jitter regime matches the paths' own differences."""
    cfg = _unit(n_paths=300, n_frames=1000, corner_frequencies_hz=(0.5,))
    x = generate_traces(cfg, 2).centres_px - 63.5
    assert np.mean(x**2) == pytest.approx(1.0, rel=0.1)
    step = np.sqrt(np.mean(np.diff(x, axis=1) ** 2))
    assert step == pytest.approx(float(one_frame_motion_rms(cfg, 1.0)), rel=0.03)
    assert "rolloff" in generate_traces(replace(cfg, n_paths=1, n_frames=20), 0).metadata["config"]
    with pytest.raises(ValueError, match="exposure_s"):
        _unit(exposure_s=-1.0)
