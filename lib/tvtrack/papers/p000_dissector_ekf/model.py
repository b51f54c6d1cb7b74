"""The model of paper 000: an image-dissector micro-raster scan of one axis (Martyshevsky 1995).

The dissector aperture sweeps a micro-raster across a point object; within each scan interval
``T`` the object coordinate ``x`` is the time shift of a Gaussian video pulse. Time is normalised
to ``T = 1`` and the coordinate is in units of ``T`` (micro-raster size). The dissector current is

    Y(t) = A S(x, t) + sqrt(N(t)) n0(t),   N(t) = N0 (1 + P/(1-P) S(x, t))          (eqs. (2), (5))

with unit-intensity white noise ``n0``; sampled with interval ``dt`` this is
``Y(k) = A S(x_k, t_k) + sqrt(N(t_k)/dt) xi_k``, ``xi_k ~ N(0, 1)``. The message ``x`` is a
first-order Gauss-Markov process (eqs. (3), (4)).

The paper's two filters are in :mod:`.ekf`, the Bayesian references (grid filter, PCRLB) in
:mod:`.reference`, the classical centroid tracker in :mod:`.baseline`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "check_real",
    "check_choice",
    "DissectorScan",
    "GaussMarkovMessage",
    "SIGMA_SH_DEFINITIONS",
    "SIGNAL_NOISE_SCALES",
    "G22_MODES",
    "SAMPLE_PHASES",
    "SCORING_TIMES",
    "SAMPLE_MODELS",
    "truth_and_pulse",
    "samples_from_pulse",
    "counts_from_pulse",
    "background_intensity",
    "scan_at_snr",
    "draw_noises",
    "on_sample_clock",
    "simulate",
    "simulate_integrated",
    "simulate_photon_counts",
    "simulate_two_rates",
]

#: Readings of the paper's ``sigma_sh`` in ``psi_A = A / sigma_sh``.
SIGMA_SH_DEFINITIONS = ("per_sample", "unit_bandwidth")
#: Readings of the signal-noise scale ``c_s`` of variant 1: eq. (2)-consistent or the literal ``A``.
SIGNAL_NOISE_SCALES = ("consistent", "literal")
#: Readings of ``G22`` (process-noise variance of ``X2`` per step).
G22_MODES = ("paper", "euler", "matched")
#: Where in its interval a sample sees the pulse: the centre ``(k - 1/2) dt`` or the end ``k dt``.
SAMPLE_PHASES = ("interval_centre", "interval_end")
#: The time an integrated sample's truth is scored at: the interval centre (where the filters, the grid filter and
#: the PCRLB evaluate the pulse: the time their model of the sample refers to) or its end (the newest datum).
SCORING_TIMES = ("interval_centre", "interval_end")
#: What one sample is: the current integrated over its interval (integrate and dump) or one instant of it.
SAMPLE_MODELS = ("integrated", "point")


def check_real(name, value, low=None, high=None, low_open=False, high_open=False):
    """Refuse a parameter that is not a finite number in ``[low, high]`` (each end open where flagged, unbounded
    where None): ``ValueError`` naming the parameter and the interval allowed."""
    ok = np.isfinite(value)
    if ok and low is not None:
        ok = value > low if low_open else value >= low
    if ok and high is not None:
        ok = value < high if high_open else value <= high
    if not ok:
        left = "(" if low_open else "["
        right = ")" if high_open else "]"
        raise ValueError(f"parameter {name!r} = {value!r}; it must be in {left}{low}, {high}{right}")


def check_choice(name, value, options):
    """Refuse a parameter that is not one of ``options``: ``ValueError`` naming the parameter and the choices."""
    if value not in options:
        raise ValueError(f"parameter {name!r} = {value!r}; it must be one of {options}")


def background_intensity(psi_a: float, amplitude: float, dt: float, sigma_sh: str = "per_sample") -> float:
    """Background noise intensity ``N0`` that gives ``psi_A = A / sigma_sh``.

    Parameters
    ----------
    psi_a : float          signal-to-noise ratio ``psi_A`` (> 0)
    amplitude : float      pulse peak ``A``
    dt : float             sampling interval (units of ``T``)
    sigma_sh : {"per_sample", "unit_bandwidth"}
        ``"per_sample"``: ``sigma_sh = sqrt(N0/dt)``, the RMS of one sample, so ``N0 = dt (A/psi)^2``;
        ``"unit_bandwidth"``: ``sigma_sh = sqrt(N0)``, the RMS in a unit (1/T) bandwidth, so
        ``N0 = (A/psi)^2``.
    """
    check_real("psi_a", psi_a, 0.0, None, low_open=True)
    check_real("amplitude", amplitude, 0.0, None, low_open=True)
    check_real("dt", dt, 0.0, None, low_open=True)
    check_choice("sigma_sh", sigma_sh, SIGMA_SH_DEFINITIONS)
    n0 = (amplitude / psi_a) ** 2
    return n0 * dt if sigma_sh == "per_sample" else n0


@dataclass(frozen=True)
class DissectorScan:
    """Sampled micro-raster scan of one axis.

    Parameters
    ----------
    n0 : float              background noise intensity ``N0`` (per unit time, units of ``A^2 T``)
    contrast : float        electrical contrast ``P`` in [0, 1)
    amplitude : float       pulse peak ``A``
    dt : float              sampling interval, units of ``T`` (``1/dt`` samples per scan)
    pulse_sigma : float     pulse standard deviation ``sigma_t = T_u / 2`` (``T_u`` at level 0.606 A)
    pulse_centre : float    scan phase of the pulse for ``x = 0`` (``tau_c``)
    time_offset : float     time of sample ``k`` is ``t_k = k dt + time_offset`` (units of ``T``)
    """

    n0: float
    contrast: float = 0.0
    amplitude: float = 1.0
    dt: float = 0.05
    pulse_sigma: float = 0.25
    pulse_centre: float = 0.5
    time_offset: float = 0.0

    def __post_init__(self):
        check_real("n0", self.n0, 0.0, None, low_open=True)
        check_real("contrast", self.contrast, 0.0, 1.0, high_open=True)
        check_real("amplitude", self.amplitude, 0.0, None, low_open=True)
        check_real("dt", self.dt, 0.0, 1.0, low_open=True)
        check_real("pulse_sigma", self.pulse_sigma, 0.0, None, low_open=True)
        check_real("pulse_centre", self.pulse_centre, 0.0, 1.0)
        check_real("time_offset", self.time_offset, -1.0, 1.0)

    @property
    def signal_noise_ratio(self) -> float:
        """``P / (1 - P)``: signal-noise intensity per unit ``S`` relative to ``N0`` (eq. (2))."""
        return self.contrast / (1.0 - self.contrast)

    def phase(self, k, start=0.0):
        """Scan phase ``tau = (t + start) mod T`` of sample ``k`` (``t_k = k dt + time_offset``); ``start`` is the
        sweep's phase when the filter switches on (``t = 0``; units of ``T``, a float or an array broadcast
        against ``k``, e.g. one phase per run of shape (n_trials, 1))."""
        return np.mod(np.asarray(k) * self.dt + self.time_offset + start, 1.0)

    def offset(self, x, k, start=0.0):
        """``u = tau_k - tau_c - x``, the pulse argument (units of ``T``)."""
        return self.phase(k, start) - self.pulse_centre - x

    def shape(self, x, k, start=0.0):
        """Normalised pulse ``S(x, t_k) = exp(-u^2 / (2 sigma_t^2))`` (peak 1)."""
        u = self.offset(x, k, start)
        return np.exp(-0.5 * (u / self.pulse_sigma) ** 2)

    def shape_derivative(self, x, k, start=0.0):
        """``dS/dx = S u / sigma_t^2``."""
        u = self.offset(x, k, start)
        return np.exp(-0.5 * (u / self.pulse_sigma) ** 2) * u / self.pulse_sigma**2

    def noise_intensity(self, x, k, contrast: float | None = None, start=0.0):
        """``N(t_k) = N0 (1 + P/(1-P) S(x, t_k))`` (eq. (2)); ``contrast`` overrides ``P``."""
        p = self.contrast if contrast is None else contrast
        return self.n0 * (1.0 + p / (1.0 - p) * self.shape(x, k, start))

    def sample_variance(self, x, k, contrast: float | None = None, start=0.0):
        """Variance of one sample's noise, ``N(t_k) / dt``."""
        return self.noise_intensity(x, k, contrast, start) / self.dt


@dataclass(frozen=True)
class GaussMarkovMessage:
    """Stationary first-order Gauss-Markov coordinate (eqs. (3), (4)).

    Parameters
    ----------
    sigma : float   standard deviation ``sigma_1`` (units of ``T``)
    alpha : float   inverse correlation time ``alpha_0`` (units of ``1/T``)
    """

    sigma: float = 0.1
    alpha: float = 0.15

    def __post_init__(self):
        check_real("sigma", self.sigma, 0.0, None, low_open=True)
        check_real("alpha", self.alpha, 0.0, None, low_open=True)

    def euler(self, dt):
        """Euler discretisation used by the paper's filters: ``(1 - alpha dt, 2 alpha sigma^2 dt)``
        (eqs. (E4), (E8))."""
        return 1.0 - self.alpha * dt, 2.0 * self.alpha * self.sigma**2 * dt

    def exact(self, dt):
        """Exact discretisation ``(exp(-alpha dt), sigma^2 (1 - exp(-2 alpha dt)))``."""
        f = np.exp(-self.alpha * dt)
        return f, self.sigma**2 * (1.0 - f * f)


def scan_at_snr(
    psi_a: float,
    contrast: float,
    dt: float,
    pulse_duration: float = 0.5,
    sigma_sh: str = "per_sample",
    sample_at: str = "interval_centre",
    amplitude: float = 1.0,
) -> DissectorScan:
    """The scan of an operating point given by its SNR ``psi_A`` and contrast ``P``.

    Parameters
    ----------
    psi_a : float            ``psi_A = A / sigma_sh`` (> 0); sets ``N0`` via :func:`background_intensity`
    contrast : float         electrical contrast ``P`` in [0, 1)
    dt : float               sampling interval, units of ``T``
    pulse_duration : float   pulse duration ``T_u`` at level 0.606 A, units of ``T`` (pulse sigma ``T_u / 2``)
    sigma_sh : {"per_sample", "unit_bandwidth"}   reading of ``sigma_sh`` (see :func:`background_intensity`)
    sample_at : {"interval_centre", "interval_end"}
        Pulse phase seen by sample ``k``: ``(k - 1/2) dt`` (the centre of its integration interval) or ``k dt``.
    amplitude : float        pulse peak ``A``

    Returns
    -------
    DissectorScan  with the pulse centred in the scan (``tau_c = T/2``)
    """
    check_choice("sample_at", sample_at, SAMPLE_PHASES)
    offset = -0.5 * dt if sample_at == "interval_centre" else 0.0
    return DissectorScan(
        background_intensity(psi_a, amplitude, dt, sigma_sh), contrast, amplitude, dt, 0.5 * pulse_duration, 0.5, offset
    )


def draw_noises(rng: np.random.Generator, n_trials: int, n_steps: int, substeps: int = 0) -> dict:
    """Unit normal draws for one Monte Carlo experiment (common random numbers).

    Parameters
    ----------
    substeps : int
        With ``substeps >= 1`` also draws ``w_sub`` for :func:`simulate_integrated` (after the other
        draws, so they do not change).

    Returns
    -------
    dict with ``x0`` (n_trials,), ``w`` (n_trials, n_steps) process noise, ``xi`` (n_trials, n_steps)
    observation noise, ``init`` (n_trials, 2) for random initial estimates, with ``substeps``
    ``w_sub`` (n_trials, 2 substeps n_steps) process noise on half sub-steps, and ``phase`` (n_trials,) each run's
    sweep phase at switch-on, uniform over the scan interval [0, T) (drawn last, so the other draws do not change;
    the paper does not say where the sweep is when the filter starts); :func:`on_sample_clock` puts it on the
    sample clock.
    """
    if n_trials < 1 or n_steps < 1:
        raise ValueError(f"parameters 'n_trials' = {n_trials}, 'n_steps' = {n_steps}; both must be >= 1")
    if isinstance(substeps, bool) or int(substeps) != substeps or substeps < 0:
        raise ValueError(f"parameter 'substeps' = {substeps!r}; it must be an integer >= 0")
    out = {
        "x0": rng.standard_normal(n_trials),
        "w": rng.standard_normal((n_trials, n_steps)),
        "xi": rng.standard_normal((n_trials, n_steps)),
        "init": rng.standard_normal((n_trials, 2)),
    }
    if substeps:
        out["w_sub"] = rng.standard_normal((n_trials, 2 * int(substeps) * n_steps))
    out["phase"] = rng.uniform(0.0, 1.0, n_trials)
    return out


def on_sample_clock(phase, dt: float):
    """The sample slot a uniform phase (T) falls in: ``floor(phase / dt) dt``, uniform over the slots of the scan.

    The paper samples the scan every ``dt = T / 20``, a clock synchronous with the sweep, so a filter switches on at
    a sample slot and every sample's interval ends at or before the flyback. Off the clock, the interval holding the
    flyback averages the pulse's two far tails, which the filters' model of a sample (the pulse at the interval
    centre) does not describe.
    """
    return np.floor(np.asarray(phase, dtype=float) / dt) * dt


def _starts(start, n_trials: int) -> np.ndarray:
    """Switch-on phases (T) as a column (n_trials, 1): ``None`` is phase 0 for every run."""
    if start is None:
        return np.zeros((n_trials, 1))
    start = np.asarray(start, dtype=float)
    if start.shape not in ((), (n_trials,)) or not np.all(np.isfinite(start)):
        raise ValueError(f"parameter 'start' has shape {start.shape}; it must be finite, a number or ({n_trials},)")
    return np.broadcast_to(start, (n_trials,))[:, None]


def simulate(scan: DissectorScan, message: GaussMarkovMessage, noises: dict, start=None):
    """Truth and sampled observations (eq. (5)), exact discretisation of the message.

    Parameters
    ----------
    noises : dict from :func:`draw_noises` (``x0``, ``w``, ``xi``)
    start : None, float or ndarray (n_trials,)   the sweep's phase at switch-on per run (T; None: 0)

    Returns
    -------
    x : ndarray, shape (n_trials, n_steps + 1)   coordinate ``X1(k)``, ``k = 0..n_steps``
    y : ndarray, shape (n_trials, n_steps + 1)   samples ``Y(k)``; ``y[:, 0]`` is NaN (no sample at k=0)
    """
    f, q = message.exact(scan.dt)
    w, xi = noises["w"], noises["xi"]
    n_trials, n_steps = w.shape
    x = np.empty((n_trials, n_steps + 1))
    x[:, 0] = message.sigma * noises["x0"]
    for k in range(n_steps):
        x[:, k + 1] = f * x[:, k] + np.sqrt(q) * w[:, k]
    k, phi = np.arange(1, n_steps + 1), _starts(start, n_trials)
    y = np.full_like(x, np.nan)
    y[:, 1:] = (
        scan.amplitude * scan.shape(x[:, 1:], k, phi) + np.sqrt(scan.sample_variance(x[:, 1:], k, None, phi)) * xi
    )  # (eq. 5)
    return x, y


def _integrated_path(
    scan: DissectorScan, message: GaussMarkovMessage, noises: dict, score_at: str, drift=None, start=None
):
    """The message on half sub-steps and each sample's pulse and noise intensity averaged over its interval.

    Returns ``x`` (n_trials, n_steps + 1): ``x(0)`` then the message at the centre ``(k - 1/2) dt`` or the end
    ``k dt`` of sample ``k``'s interval (``score_at``), ``shape`` and ``intensity`` (n_trials, n_steps): the
    means of ``S`` and ``N`` over the ``m`` sub-interval centres of sample ``k = 1..n_steps``, the sweep at phase
    ``start`` (per run, T; None: 0) at ``t = 0``.
    """
    check_choice("score_at", score_at, SCORING_TIMES)
    if "w_sub" not in noises:
        raise ValueError("parameter 'noises' lacks 'w_sub': draw it with draw_noises(..., substeps >= 1)")
    if not np.isclose(scan.time_offset, -0.5 * scan.dt):
        raise ValueError(f"parameter 'scan.time_offset' = {scan.time_offset!r}; it must be -dt/2 = {-0.5 * scan.dt}")
    w = noises["w_sub"]
    n_trials, n_steps = noises["xi"].shape
    m = w.shape[1] // (2 * n_steps)
    if m < 1 or w.shape[1] != 2 * m * n_steps:
        raise ValueError(f"noises['w_sub'] has {w.shape[1]} columns; it must be 2 m n_steps = 2 m {n_steps}")
    f, q = message.exact(0.5 * scan.dt / m)
    x_half = np.empty((n_trials, w.shape[1] + 1))  # times i dt / (2 m)
    x_half[:, 0] = message.sigma * noises["x0"]
    for i in range(w.shape[1]):
        x_half[:, i + 1] = f * x_half[:, i] + np.sqrt(q) * w[:, i]
    if drift is not None:  # a motion outside the message model, added to the truth (times i dt / (2 m))
        x_half = x_half + drift(np.arange(x_half.shape[1]) * 0.5 * scan.dt / m)
    x_mid = x_half[:, 1::2]  # sub-interval centres
    t_mid = (np.arange(m * n_steps) + 0.5) * scan.dt / m
    u = np.mod(t_mid + _starts(start, n_trials), 1.0) - scan.pulse_centre - x_mid
    shape = np.exp(-0.5 * (u / scan.pulse_sigma) ** 2)
    intensity = scan.n0 * (1.0 + scan.signal_noise_ratio * shape)
    mean = lambda a: a.reshape(n_trials, n_steps, m).mean(axis=2)
    x = x_half[:, :: 2 * m].copy()
    if score_at == "interval_centre":
        x[:, 1:] = x_half[:, m :: 2 * m]  # times (k - 1/2) dt
    return x, mean(shape), mean(intensity)


def truth_and_pulse(
    scan: DissectorScan,
    message: GaussMarkovMessage,
    noises: dict,
    sample_model: str = "integrated",
    score_at: str = "interval_centre",
    drift=None,
    start=None,
):
    """The truth and the mean pulse ``S`` each sample sees, under either sample model (common draws ``noises``).

    The pulse does not depend on ``psi_A`` or ``P``, so one call serves every operating point: the samples of a
    point are :func:`samples_from_pulse` of it. ``"integrated"``: as :func:`simulate_integrated` (pulse averaged
    over the interval; truth at ``score_at``); ``"point"``: as :func:`simulate` (pulse and truth at ``k dt``).

    Returns
    -------
    x : ndarray, shape (n_trials, n_steps + 1)     truth (column 0: ``X1(0)``)
    pulse : ndarray, shape (n_trials, n_steps)     mean normalised pulse of samples ``k = 1..n_steps``

    ``drift``: optional callable of times ``t`` (T, shape (K,)) returning a motion (T, broadcastable to
    (n_trials, K)) added to the message: a target that moves outside the filters' model. ``start``: the sweep's
    phase at switch-on per run (T, shape (n_trials,) or a number; None: 0), e.g. ``noises["phase"]``.
    """
    check_choice("sample_model", sample_model, SAMPLE_MODELS)
    if sample_model == "integrated":
        x, pulse, _ = _integrated_path(scan, message, noises, score_at, drift, start)
        return x, pulse
    x, _ = simulate(scan, message, {**noises, "xi": np.zeros_like(noises["xi"])})
    if drift is not None:
        x = x + drift(np.arange(x.shape[1]) * scan.dt)
    return x, scan.shape(x[:, 1:], np.arange(1, x.shape[1]), _starts(start, x.shape[0]))


def samples_from_pulse(scan: DissectorScan, pulse, xi):
    """Samples ``Y(k) = A S_k + sqrt(N0 (1 + P/(1-P) S_k) / dt) xi_k`` (eqs. (2), (5)) from mean pulses ``S_k``.

    The noise intensity is linear in ``S``, so its interval mean is the intensity of the mean pulse.

    Parameters
    ----------
    pulse, xi : ndarray, shape (n_trials, n_steps)

    Returns
    -------
    ndarray, shape (n_trials, n_steps + 1)   column 0 NaN (no sample at ``k = 0``)
    """
    y = np.full((pulse.shape[0], pulse.shape[1] + 1), np.nan)
    y[:, 1:] = scan.amplitude * pulse + np.sqrt(scan.n0 * (1.0 + scan.signal_noise_ratio * pulse) / scan.dt) * xi
    return y


def simulate_integrated(
    scan: DissectorScan, message: GaussMarkovMessage, noises: dict, score_at: str = "interval_centre", start=None
):
    """Truth and integrate-and-dump observations: sample ``k`` is the current averaged over ``((k-1) dt, k dt]``.

    The message is simulated exactly on half sub-steps of ``dt / m`` (``m`` from the shape of
    ``noises["w_sub"]``); the pulse and the noise intensity are evaluated at the centres of the ``m``
    sub-intervals (midpoint rule) while the message moves, so

        Y(k) = mean_j A S(x_j, t_j) + sqrt(mean_j N(x_j, t_j) / dt) xi_k,

    which is exactly the mean of ``m`` integrated sub-samples of noise variance ``N_j m / dt`` (a sum
    of independent Gaussians). The filters model this sample as the pulse and intensity of the message at the
    interval centre (midpoint rule), so the truth returned by default is the message at ``(k - 1/2) dt``, the
    time their estimate refers to; ``score_at="interval_end"`` returns it at ``k dt`` (the newest datum).

    Parameters
    ----------
    scan : DissectorScan   ``time_offset`` must be ``-dt / 2`` (filters model the pulse at the interval centre)
    noises : dict from :func:`draw_noises` with ``substeps >= 1`` (``x0``, ``xi``, ``w_sub``)
    score_at : {"interval_centre", "interval_end"}   the time of the truth ``x[:, k]``, ``k >= 1``
    start : None, float or ndarray (n_trials,)        the sweep's phase at switch-on per run (T; None: 0)

    Returns
    -------
    x : ndarray, shape (n_trials, n_steps + 1)   ``X1(0)``, then ``X1`` at the centre (or end) of each interval
    y : ndarray, shape (n_trials, n_steps + 1)   samples; ``y[:, 0]`` is NaN
    """
    x, shape, intensity = _integrated_path(scan, message, noises, score_at, None, start)
    y = np.full_like(x, np.nan)
    y[:, 1:] = scan.amplitude * shape + np.sqrt(intensity / scan.dt) * noises["xi"]
    return x, y


def counts_from_pulse(scan: DissectorScan, pulse, rng: np.random.Generator):
    """Samples from photo-electron counts with the mean pulses ``pulse`` (n_trials, n_steps) (a study beyond
    the paper, of its Gaussian noise model at low counts): ``n_k ~ Poisson((I_b + A S_k) dt / q)``,
    ``Y(k) = q n_k / dt - I_b`` with ``I_b = A (1-P)/P`` and ``q = N0 / I_b`` (the Gaussian model's mean ``A S_k``
    and variance ``N_k / dt``, the Poisson shape).

    Returns
    -------
    y : ndarray, shape (n_trials, n_steps + 1)   column 0 NaN
    background_counts : float                    mean background electrons per sample, ``I_b dt / q``
    """
    if not scan.contrast > 0:
        raise ValueError(f"parameter 'scan.contrast' = {scan.contrast!r}; photon counts need P > 0")
    i_b = scan.amplitude / scan.signal_noise_ratio
    charge = scan.n0 / i_b
    y = np.full((pulse.shape[0], pulse.shape[1] + 1), np.nan)
    y[:, 1:] = charge * rng.poisson((i_b + scan.amplitude * pulse) * scan.dt / charge) / scan.dt - i_b
    return y, i_b * scan.dt / charge


def simulate_photon_counts(
    scan: DissectorScan,
    message: GaussMarkovMessage,
    noises: dict,
    rng: np.random.Generator,
    score_at: str = "interval_centre",
    start=None,
):
    """Truth and samples from photo-electron counts instead of Gaussian noise (a study beyond the paper).

    Shot noise is the count statistics of the photo-electrons: with background current ``I_b`` and
    charge ``q`` per electron, ``N0 = q I_b`` and ``P / (1-P) = A / I_b`` (eq. (2)), so
    ``I_b = A (1-P)/P`` and ``q = N0 / I_b``. Sample ``k`` counts ``n_k ~ Poisson((I_b + A S_k) dt / q)``
    electrons over its interval (``S_k`` the pulse averaged over the interval as in
    :func:`simulate_integrated`) and reports the current less the known background,
    ``Y(k) = q n_k / dt - I_b``: the same mean ``A S_k`` and variance ``N_k / dt`` as the Gaussian
    model, with the Poisson shape (skewed at low counts).

    Parameters
    ----------
    scan : DissectorScan   contrast ``P > 0`` (no signal current at ``P = 0``); ``time_offset = -dt / 2``
    noises : dict          as for :func:`simulate_integrated` (``xi`` is not used)
    rng : numpy.random.Generator   draws the counts

    Returns
    -------
    x, y : as :func:`simulate_integrated`
    background_counts : float   mean background electrons per sample, ``I_b dt / q``
    """
    if not scan.contrast > 0:
        raise ValueError(f"parameter 'scan.contrast' = {scan.contrast!r}; photon counts need P > 0")
    x, shape, _ = _integrated_path(scan, message, noises, score_at, None, start)
    return (x, *counts_from_pulse(scan, shape, rng))


def simulate_two_rates(
    scan: DissectorScan,
    message: GaussMarkovMessage,
    factor: int,
    rng: np.random.Generator,
    n_trials: int,
    n_steps: int,
    score_at: str = "interval_centre",
    draw_phase: bool = False,
):
    """The same continuous-time experiment sampled at ``dt`` and at ``dt_f = dt / factor`` (claim C000-8).

    The message is simulated exactly on a grid of step ``dt_f / 2``. Fine sample ``j`` is the
    observation integrated over ``(j dt_f, (j+1) dt_f]`` (midpoint rule: pulse and noise intensity
    at the interval centre, noise variance ``N / dt_f``); the coarse sample ``k`` is the mean of
    the ``factor`` fine samples in ``((k-1) dt, k dt]``, i.e. integrate-and-dump of the same
    continuous observation, with noise variance ``N / dt``. Both filters model the pulse at the
    centre of their sample's interval (``time_offset = -dt/2`` for the coarse scan), so by default
    each estimate is compared with the message at the centre of its interval, the time its model
    refers to (``score_at="interval_end"``: at the end, the newest datum). The coarse results then
    differ from the fine ones only by discretisation (pulse, noise intensity and message averaged
    over the interval, Euler transitions of the filters).

    Parameters
    ----------
    scan : DissectorScan   the coarse scan; ``time_offset`` must be ``-dt / 2``
    factor : int           integer >= 2
    n_steps : int          coarse steps; coarse samples ``k = 1..n_steps``
    score_at : {"interval_centre", "interval_end"}   the time of the truths ``x_coarse``, ``x_fine``
    draw_phase : bool      draw each run's sweep phase at switch-on uniform over the coarse scan's sample slots
                           (:func:`on_sample_clock`) from ``rng`` (after the other draws, so they do not change);
                           False: phase 0 for every run

    Returns
    -------
    dict with ``x_coarse``, ``y_coarse`` (n_trials, n_steps + 1; column 0 is the start, ``y`` NaN),
    ``x_fine``, ``y_fine`` (n_trials, n_steps factor), ``x_mid`` (n_trials, n_steps factor: the message
    at the centre of each fine interval, where the pulse and noise intensity are evaluated),
    ``t_coarse``, ``t_fine`` (times the estimates refer to), ``scan_fine`` (the fine :class:`DissectorScan`) and
    ``start`` (n_trials,) the switch-on phases (T; the filters' ``start``).
    """
    if isinstance(factor, bool) or int(factor) != factor or factor < 2:
        raise ValueError(f"parameter 'factor' = {factor!r}; it must be an integer >= 2")
    check_choice("score_at", score_at, SCORING_TIMES)
    if not np.isclose(scan.time_offset, -0.5 * scan.dt):
        raise ValueError(f"parameter 'scan.time_offset' = {scan.time_offset!r}; it must be -dt/2 = {-0.5 * scan.dt}")
    factor = int(factor)
    dt_f = scan.dt / factor
    scan_fine = DissectorScan(
        scan.n0, scan.contrast, scan.amplitude, dt_f, scan.pulse_sigma, scan.pulse_centre, time_offset=0.5 * dt_f
    )
    n_fine = n_steps * factor
    f, q = message.exact(0.5 * dt_f)
    w = rng.standard_normal((n_trials, 2 * n_fine))
    x_half = np.empty((n_trials, 2 * n_fine + 1))  # times i dt_f / 2
    x_half[:, 0] = message.sigma * rng.standard_normal(n_trials)
    for i in range(2 * n_fine):
        x_half[:, i + 1] = f * x_half[:, i] + np.sqrt(q) * w[:, i]
    x_mid = x_half[:, 1::2]  # centres (j + 1/2) dt_f
    j = np.arange(n_fine)
    xi = rng.standard_normal((n_trials, n_fine))
    start = on_sample_clock(rng.uniform(0.0, 1.0, n_trials), scan.dt) if draw_phase else np.zeros(n_trials)
    y_fine = (
        scan.amplitude * scan_fine.shape(x_mid, j, start[:, None])
        + np.sqrt(scan_fine.sample_variance(x_mid, j, None, start[:, None])) * xi
    )
    y_coarse = np.full((n_trials, n_steps + 1), np.nan)
    y_coarse[:, 1:] = y_fine.reshape(n_trials, n_steps, factor).mean(axis=2)  # integrate and dump
    x_coarse = x_half[:, :: 2 * factor].copy()  # times k dt
    t_coarse = np.arange(n_steps + 1) * scan.dt
    if score_at == "interval_centre":
        x_coarse[:, 1:] = x_half[:, factor :: 2 * factor]  # times (k - 1/2) dt
        t_coarse[1:] -= 0.5 * scan.dt
        x_fine, t_fine = x_mid, (j + 0.5) * dt_f
    else:
        x_fine, t_fine = x_half[:, 2::2], (j + 1) * dt_f
    return {
        "x_coarse": x_coarse,
        "y_coarse": y_coarse,
        "x_fine": x_fine,
        "y_fine": y_fine,
        "x_mid": x_mid,
        "t_coarse": t_coarse,
        "t_fine": t_fine,
        "scan_fine": scan_fine,
        "start": start,
    }
