"""Tyler's (1994) G-tilt spectrum of a spot centroid through Kolmogorov turbulence in frozen flow, for the beam-wander
generator of paper 004 (:mod:`.beam_wander`, ``rolloff="G-tilt"``): its shape and asymptotes, the exposure's power
gain, the spectrum as the frames sample it (folded at the frame rate) and the spectral synthesis of the paths.
Re-exported by :mod:`.beam_wander`; ``config`` is a :class:`.beam_wander.BeamWanderConfig`."""

from __future__ import annotations

from typing import Any

import numpy as np

# ``config`` below is a :class:`.beam_wander.BeamWanderConfig` (not imported: beam_wander imports this module)
BeamWanderConfig = Any

__all__ = [
    "GTILT",
    "gtilt_wander",
    "gtilt_asymptotes",
    "gtilt_shape",
    "gtilt_crossing",
    "gtilt_psd",
    "exposure_gain",
    "gtilt_discrete_psd",
    "gtilt_frame_step_rms",
]

#: Tyler's G-tilt spectrum as a value of ``BeamWanderConfig.rolloff``.
GTILT = "G-tilt"


#: Reduced frequencies ``x = f D / v`` of the tabulated G-tilt shape (beyond: the asymptotes).
_GTILT_X = np.logspace(-3.0, 3.0, 61)


def gtilt_asymptotes(axis: str = "parallel") -> tuple[float, float]:
    """Constants of the G-tilt shape's asymptotes, ``g(x) -> c_lo x^(-2/3)`` (``x -> 0``) and
    ``g(x) -> c_hi x^(-11/3)`` (``x -> inf``), in closed form (see :func:`gtilt_shape`).

    With ``int_0^inf t^m (1 + t^2)^-p dt = B((m+1)/2, p-(m+1)/2) / 2``: ``c_lo = B(1/2, 4/3)/2``
    (parallel, ``m = 0``) or ``B(3/2, 1/3)/2`` (perpendicular, ``m = 2``), ``p = 11/6``; above the corner
    the Airy filter averages to ``4 / (pi^4 u^3)``, so ``c_hi = (4/pi^4) B(1/2, 17/6)/2`` or
    ``(4/pi^4) B(3/2, 11/6)/2`` (``p = 10/3``).
    """
    from scipy.special import beta

    m = {"parallel": 0, "perpendicular": 2}[axis]
    a = (m + 1) / 2
    return 0.5 * beta(a, 11 / 6 - a), 4 / np.pi**4 * 0.5 * beta(a, 10 / 3 - a)


def _gtilt_integral(x: np.ndarray, axis: str) -> np.ndarray:
    """``g(x)`` by the trapezoid rule on a grid in ``y`` (linear on [0, x], geometric beyond)."""
    from scipy.special import j1

    out = np.empty(x.shape)
    for i, xi in enumerate(x):
        y = np.concatenate([np.linspace(0.0, xi, 400, endpoint=False), np.geomspace(xi, 21 * xi + 300.0, 12000)])
        u = np.hypot(xi, y)
        z = np.pi * u
        airy = (2 * j1(z) / z) ** 2
        w = xi**2 if axis == "parallel" else y**2
        out[i] = np.trapezoid(w * u ** (-11 / 3) * airy, y)
    return out


_GTILT_TABLE: dict = {}


def gtilt_shape(x, axis: str = "parallel") -> np.ndarray:
    """Shape of the G-tilt (gradient-tilt, i.e. centroid) temporal spectrum of one axis through Kolmogorov
    turbulence in frozen flow, as a function of the reduced frequency ``x = f D / v``.

    Tyler (1994, "Bandwidth considerations for tracking through turbulence", JOSA A 11, 358) writes the
    tilt spectrum of a layer moving at ``v`` across an aperture ``D`` as an integral over the spatial
    frequency ``kappa_y`` across the wind of the Kolmogorov phase spectrum ``kappa^(-11/3)``, the tilt
    weight (``kappa_x^2`` for the axis along the wind, ``kappa_y^2`` across it) and the aperture
    filter; for G-tilt (the mean wavefront gradient, which a centroid measures) the filter is the Airy
    function ``[2 J1(pi u) / (pi u)]^2``, ``u = kappa D / 2 pi``. In reduced units (constants dropped)::

        g(x) = int_0^inf w(x, y) u^(-11/3) [2 J1(pi u) / (pi u)]^2 dy,   u = sqrt(x^2 + y^2),

    ``w = x^2`` (parallel) or ``y^2`` (perpendicular). The form is derived here from those ingredients
    (Tyler's text was not at hand); what the tests check is its pair of asymptotes, which are Tyler's
    G-tilt ones: ``f^(-2/3)`` below the corner ``~ v/D`` and ``f^(-11/3)`` above it
    (:func:`gtilt_asymptotes`), and not the Z-tilt ``f^(-17/3)``.

    Parameters
    ----------
    x : array_like
        Reduced frequency ``f D / v`` (> 0).
    axis : {"parallel", "perpendicular"}
        The tilt axis along or across the wind.

    Returns
    -------
    ndarray, shape like ``x``
        Tabulated on :data:`_GTILT_X` and interpolated in log-log; the asymptotes beyond.
    """
    if axis not in _GTILT_TABLE:
        _GTILT_TABLE[axis] = np.log(_gtilt_integral(_GTILT_X, axis))
    x = np.asarray(x, dtype=float)
    lx = np.log(np.clip(x, 1e-300, None))
    c_lo, c_hi = gtilt_asymptotes(axis)
    lg = np.interp(lx, np.log(_GTILT_X), _GTILT_TABLE[axis])
    lg = np.where(x < _GTILT_X[0], np.log(c_lo) - 2 / 3 * lx, lg)
    return np.exp(np.where(x > _GTILT_X[-1], np.log(c_hi) - 11 / 3 * lx, lg))


def gtilt_crossing() -> float:
    """Reduced frequency ``x_c`` where the parallel axis's asymptotes cross, ``(c_hi / c_lo)^(1/3)``."""
    c_lo, c_hi = gtilt_asymptotes("parallel")
    return (c_hi / c_lo) ** (1 / 3)


def gtilt_psd(f, corner_hz: float, axis: str = "parallel") -> np.ndarray:
    """One-sided G-tilt spectrum (:func:`gtilt_shape`) at frequencies ``f`` (Hz), for ``v / D`` such that
    the parallel axis's asymptotes cross at ``corner_hz``; arbitrary scale (px^2/Hz up to a constant)."""
    v_over_d = corner_hz / gtilt_crossing()
    return gtilt_shape(np.abs(np.asarray(f, dtype=float)) / v_over_d, axis) / v_over_d


def exposure_gain(f, exposure_s: float = 0.0, field_offset_s: float = 0.0) -> np.ndarray:
    """Power gain of averaging the path over the exposure: ``sinc^2(pi f tau) cos^2(pi f delta)``
    (``sinc(a) = sin(a)/a``; a boxcar of ``tau = exposure_s``, and the mean of two fields ``delta``
    apart)."""
    f = np.asarray(f, dtype=float)
    return np.sinc(f * exposure_s) ** 2 * np.cos(np.pi * f * field_offset_s) ** 2


#: Aliases summed in :func:`gtilt_discrete_psd` (the spectrum falls as f^(-11/3): the sum converges fast).
_ALIASES = 64


def gtilt_discrete_psd(config: BeamWanderConfig, n_fft: int) -> tuple[np.ndarray, np.ndarray]:
    """The G-tilt wander as the frames sample it, on the ``n_fft``-point frequency grid.

    The continuous spectrum (:func:`gtilt_psd`, corner at the highest of ``corner_frequencies_hz``)
    is cut below the record's fundamental ``f_lo = frame_rate / n_frames`` (slower content reads as the
    slow drift, which the generator draws separately), multiplied by the exposure's power gain
    (:func:`exposure_gain`) and folded at the frame rate (``S_d(f) = sum_k S(|f + k f_s|)``). It is
    scaled so that the *instant* exposure's variance ``sum_j S_d(f_j) df`` is 1 px^2 (the exposure
    then lowers it).

    Returns
    -------
    f : ndarray, shape (n_fft // 2 + 1,)
        Hz.
    S : ndarray, shape (2, n_fft // 2 + 1)
        One-sided PSD per axis (x along the wind, y across it), px^2/Hz; 0 at the DC and Nyquist bins.
    """
    fs = config.frame_rate_hz
    f = np.fft.rfftfreq(n_fft, 1.0 / fs)
    df = fs / n_fft
    corner = max(config.corner_frequencies_hz)
    nu = np.abs(f[None, :] + fs * np.arange(-_ALIASES, _ALIASES + 1)[:, None])  # (aliases, bins)
    keep = nu >= fs / config.n_frames
    out = np.zeros((2, f.size))
    for a, axis in enumerate(("parallel", "perpendicular")):
        s = np.where(keep, gtilt_psd(np.maximum(nu, 1e-12), corner, axis), 0.0)
        s[:, [0, -1]] = 0.0
        norm = s.sum() * df
        out[a] = (s * exposure_gain(nu, config.exposure_s, config.field_offset_s)).sum(axis=0) / norm
    out[:, [0, -1]] = 0.0
    return f, out


def _gtilt_fft_size(config: BeamWanderConfig) -> int:
    """FFT length of the G-tilt synthesis: four records (the record is a quarter of the period)."""
    return 4 * config.n_frames


def gtilt_wander(config: BeamWanderConfig, rms: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """G-tilt wander by spectral synthesis (:func:`gtilt_discrete_psd`), shape (P, T, 2), px: each bin
    a Gaussian of variance ``S_d df``, one period of ``4 n_frames`` frames, the first record kept."""
    M = _gtilt_fft_size(config)
    f, S = gtilt_discrete_psd(config, M)
    df = f[1] - f[0]
    P = rms.size
    z = rng.standard_normal((P, 2, f.size, 2))
    coef = (M / 2) * np.sqrt(S * df) * (z[..., 0] - 1j * z[..., 1])
    x = np.fft.irfft(coef, n=M, axis=-1)[..., : config.n_frames]  # (P, 2, T)
    return np.moveaxis(x, 1, -1) * rms[:, None, None]


def gtilt_frame_step_rms(config: BeamWanderConfig) -> float:
    """RMS per axis (mean of both) of the G-tilt wander's one-frame change at unit wander RMS,
    ``sqrt(sum_j 2 S_d(f_j) (1 - cos(2 pi f_j dt)) df)``."""
    M = _gtilt_fft_size(config)
    f, S = gtilt_discrete_psd(config, M)
    d = 2 * S * (1 - np.cos(2 * np.pi * f / config.frame_rate_hz)) * (f[1] - f[0])
    return float(np.sqrt(d.sum(axis=-1).mean()))
