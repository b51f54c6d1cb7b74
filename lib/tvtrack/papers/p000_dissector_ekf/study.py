"""The measurement functions of paper 000 that the explorer calls, and the study drivers behind the figures.

:func:`measure` is one full-size run of the study at a configuration of the register (:mod:`.register`) with all
random draws from ``numpy.random.default_rng(seed)``: it returns every checkable claim's measured parts. The same
seed gives the same draws (common random numbers) under every configuration, so conditions are paired.
Filter runs are memoised per process on everything they depend on (the configuration entries they read, the
seed and the sizes), so a one-at-a-time exploration recomputes only what the changed entry touches.

Times are in units of the scan interval ``T``; variances in ``T^2``. The paper's stated values (Martyshevsky
1995, "Results of the modelling"): ``sigma_1 = 0.1``, ``alpha_0 T = 0.15``, ``beta_0 T = 15``, ``dt = 0.05``,
``T_u = T/2``, ``D(0) = diag(0.2, 1)``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from scipy import stats

from ... import jit
from ...verdicts import ByReading
from ...estimate import Estimate
from ...montecarlo import mean_square_ci, quantile_ci, ratio_ci, rms_ci
from ...counts import proportion_ci
from .sizes import Sizes
from .claims import COST_READINGS, fig2_points
from .cost import operation_ratio, run_steps_variant1, run_steps_variant2
from .cpu_time import paired_time_ratio
from .lock_loss import keep, keep_pair
from .readings import (
    AT_09,
    ACCOUNTING,
    C2_CARD,
    C2_EVERY,
    CS_CONSISTENT,
    CS_LITERAL,
    ENSEMBLE_MEAN,
    LOCK_DEFAULT,
    NOISE_EFFECT,
    WINDOW_DEFAULT,
)
from .model import (
    GaussMarkovMessage,
    counts_from_pulse,
    draw_noises,
    on_sample_clock,
    samples_from_pulse,
    scan_at_snr,
    simulate_two_rates,
    truth_and_pulse,
)
from .reference import grid_filter, pcrlb_variance, scan_crlb
from .settling import acquisition_times_from_scans, median_ratio_ci, scan_averages

__all__ = [
    "Sizes",
    "MESSAGE",
    "psi_at",
    "measure",
    "MEASURED_CLAIMS",
    "steady_runs",
    "CONTRAST_CONVENTIONS",
    "cost_ratio",
    "measure_cost",
    "record_inputs",
    "cfg_message",
    "common_draws",
    "switch_on_phases",
    "phase_nodes",
    "truth_paths",
    "operating_scan",
    "photon_samples",
    "filter_errors",
    "ratio_to_star",
    "acquired_at",
]

#: The paper's message: sigma_1 = 0.1 T, alpha_0 T = 0.15 (eqs. (3), (4)).
MESSAGE = GaussMarkovMessage(0.1, 0.15)
#: The register's "sigma_1" operating point: the paper's "typical" sigma_1 = 0.1 T, or an image spread over the
#: micro-raster (sigma_1 = 0.2 T: within +-T/2 of the centre 98 % of the time), alpha_0 T = 0.15 in both.
MESSAGES = {"0.1 T": MESSAGE, "0.2 T": GaussMarkovMessage(0.2, 0.15)}
#: The claims :func:`measure` measures, in the order it returns them.
MEASURED_CLAIMS = ("C000-1", "C000-2", "C000-3", "C000-5", "C000-6", "C000-7", "C000-8", "C000-9")
#: The "steady window" alternative: every sample after this time (T), the transient from D11(0) = 0.2 over.
STEADY_AFTER_T = 5.0
#: The "manoeuvre" regime: a weave of amplitude 0.1 T (= sigma_1) and this period (T), a random phase per run.
WEAVES = {"none": None, "weave 0.1 T / 5 T": 5.0, "weave 0.1 T / 2 T": 2.0}
#: The drifting background: its noise intensity N0 (1 + 0.5 sin(2 pi t / 10 T + phase)), a random phase per run.
BACKGROUND_DRIFT, BACKGROUND_PERIOD_T = 0.5, 10.0
BETA_0, D11_0, D22_0, PULSE_DURATION = 15.0, 0.2, 1.0, 0.5
#: What is held fixed as P varies; psi_A scales as P/sqrt(1-P) (total current) or P/(1-P) (background current).
CONTRAST_CONVENTIONS = ("fixed N0", "fixed total current", "fixed background")


_MEMO: dict = {}


def _memo(key, compute):
    if key not in _MEMO:
        if len(_MEMO) > 4000:
            _MEMO.clear()
        _MEMO[key] = compute()
    return _MEMO[key]


def psi_at(psi_anchor: float, contrast: float, convention: str) -> float:
    """psi_A at contrast ``P`` when psi_A = ``psi_anchor`` at the paper's boundary P = 0.5.

    Fixed N0: only P/(1-P) changes, psi_A stays. Fixed total current A + I_b (shot noise N0 ~ I_b): psi_A ~
    P/sqrt(1-P). Fixed background current I_b with A = I_b P/(1-P): psi_A ~ P/(1-P). At P = 0 every convention
    keeps the anchor (there the ratio to sigma_x^2* is 1 by construction).
    """
    if convention not in CONTRAST_CONVENTIONS:
        raise ValueError(f"parameter 'convention' = {convention!r}; it must be one of {CONTRAST_CONVENTIONS}")
    if convention == "fixed N0" or contrast == 0:
        return float(psi_anchor)
    g = (lambda p: p / np.sqrt(1 - p)) if convention == "fixed total current" else (lambda p: p / (1 - p))
    return float(psi_anchor * g(contrast) / g(0.5))


def cfg_message(cfg) -> GaussMarkovMessage:
    """The message (eqs. (3), (4)) of the configuration's "sigma_1" operating point (the paper's by default)."""
    return MESSAGES[cfg.get("sigma_1", "0.1 T")]


def _data_key(cfg):
    return (cfg["sample model"], cfg["scoring time"], cfg.get("sigma_1", "0.1 T"), cfg.get("manoeuvre", "none"))


def _drift(cfg, seed, n_trials):
    """The configuration's manoeuvre as a callable of times (T) for :func:`.model.truth_and_pulse`, or None."""
    period = WEAVES[cfg.get("manoeuvre", "none")]
    if period is None:
        return None
    phase = np.random.default_rng([seed, 57]).uniform(0.0, 2 * np.pi, (n_trials, 1))
    return lambda t: 0.1 * np.sin(2 * np.pi * t / period + phase)


def common_draws(seed, sizes):
    """The common unit draws of a seed (:func:`.model.draw_noises`), each run's switch-on phase among them."""
    return _memo(
        ("draws", seed, sizes),
        lambda: draw_noises(np.random.default_rng(seed), sizes.n_trials, sizes.n_steps, sizes.substeps),
    )


def switch_on_phases(seed, sizes):
    """Each run's sweep phase at switch-on (n_trials,, T), uniform over the scan's sample slots
    (:func:`.model.on_sample_clock`): the truth's and the filters' sweep."""
    return on_sample_clock(common_draws(seed, sizes)["phase"], sizes.dt)


def phase_nodes(sizes):
    """The sample slots a run can switch on at (T), equally likely: what the bounds average over."""
    return np.arange(int(np.ceil(1.0 / sizes.dt - 1e-9))) * sizes.dt


def truth_paths(cfg, seed, sizes, offset=None):
    """Truth and mean pulses of the common draws (one per data model, seed and start), each run's sweep starting at
    its drawn phase (:func:`switch_on_phases`).

    ``offset``: None (the truth from its stationary law), a number (every truth starts there, T) or "uniform" (the
    truth uniform over the micro-raster, [-T/2, T/2], from the same normal draws through their CDF).
    """

    def compute():
        noises = common_draws(seed, sizes)
        if offset == "uniform":
            noises = {**noises, "x0": (stats.norm.cdf(noises["x0"]) - 0.5) / cfg_message(cfg).sigma}
        elif offset is not None:  # truth starts at a fixed offset
            noises = {**noises, "x0": np.full_like(noises["x0"], offset / cfg_message(cfg).sigma)}
        geometry = scan_at_snr(1.0, 0.0, sizes.dt, PULSE_DURATION)
        score = "interval_centre" if cfg["scoring time"] == "interval centre" else "interval_end"
        drift = _drift(cfg, seed, sizes.n_trials)
        x, pulse = truth_and_pulse(
            geometry, cfg_message(cfg), noises, cfg["sample model"], score, drift, switch_on_phases(seed, sizes)
        )
        return x, pulse, noises["xi"], noises["init"]

    return _memo(("path", _data_key(cfg), seed, sizes, offset), compute)


def bound_time(cfg) -> str:
    """Where the PCRLB refers (:func:`.reference.pcrlb_variance`): the time the reading scores the errors at (the end
    of an integrated sample's interval, or the sample's own time)."""
    end = cfg["scoring time"] == "interval end" and cfg["sample model"] == "integrated"
    return "interval_end" if end else "sample"


def operating_scan(cfg, psi, contrast, sizes):
    """The scan at ``psi`` (psi_A) and contrast P with the configuration's sigma_sh convention (sample period T)."""
    sig = "per_sample" if cfg["sigma_sh"] == "per sample" else "unit_bandwidth"
    return scan_at_snr(psi, contrast, sizes.dt, PULSE_DURATION, sig)


def photon_samples(cfg, seed, scan, pulse, xi):
    """The samples of one operating point under the photon model (Gaussian noise, or photo-electron counts where
    there is a signal current to count, P > 0)."""
    if cfg["photon model"] == "Poisson counts" and scan.contrast > 0:
        return counts_from_pulse(scan, pulse, np.random.default_rng([seed, 31]))[0]
    y = samples_from_pulse(scan, pulse, xi)
    if cfg.get("background", "stationary") != "stationary":  # a slowly drifting background the filters do not model
        n, k = pulse.shape
        phase = np.random.default_rng([seed, 41]).uniform(0.0, 2 * np.pi, (n, 1))
        t = (np.arange(1, k + 1) - 0.5) * scan.dt
        b = 1.0 + BACKGROUND_DRIFT * np.sin(2 * np.pi * t / BACKGROUND_PERIOD_T + phase)
        mean = scan.amplitude * pulse
        y[:, 1:] = mean + (y[:, 1:] - mean) * np.sqrt(
            (b + scan.signal_noise_ratio * pulse) / (1 + scan.signal_noise_ratio * pulse)
        )
    return y


def _cs(cfg) -> str:
    """Variant 1's signal-noise scale (:func:`.cost.variant1_step`'s ``signal_noise_scale``) of the configuration."""
    return "literal" if cfg.get("signal-noise scale", CS_CONSISTENT) == CS_LITERAL else "consistent"


def filter_errors(cfg, seed, sizes, psi, contrast, filt, offset=None, init="process means"):
    """One filter at one operating point, summarised (the memo keeps summaries, not the (n_trials, K) histories).

    ``filt``: "v1", "v2", "ignoring" (variant 2 assuming P = 0) or "stationary" (variant 2 on P = 0 data).

    Returns
    -------
    dict  ``steady`` (n_trials,) steady-window mean squared error; ``scans`` (n_trials, n_scans) each scan's mean
    squared error; ``curve`` and ``d_curve`` (n_steps + 1,) the ensemble mean squared error and mean D11 (T^2)
    """
    reads = {
        "v1": ("sigma_sh", "G22", "photon model", "background", "signal-noise scale"),
        "v2": ("sigma_sh", "v2 noise at", "photon model", "background"),
        "ignoring": ("sigma_sh", "photon model", "background"),
        "stationary": ("sigma_sh", "background"),
    }[filt]
    key = ("err", _data_key(cfg), tuple(cfg.get(r) for r in reads), seed, sizes, psi, contrast, filt, offset, init)

    def compute():
        x, pulse, xi, draws_init = truth_paths(cfg, seed, sizes, offset)
        scan = operating_scan(cfg, psi, 0.0 if filt == "stationary" else contrast, sizes)
        y = photon_samples(cfg, seed, scan, pulse, xi)
        random_init, phi = init != "process means", switch_on_phases(seed, sizes)
        if filt == "v1":
            start = (
                np.stack([np.sqrt(D11_0) * draws_init[:, 0], np.sqrt(D22_0) * draws_init[:, 1]], 1)
                if random_init
                else None
            )
            e, d = run_steps_variant1(
                scan, cfg_message(cfg), y, (D11_0, D22_0), start, BETA_0, cfg["G22"], None, _cs(cfg), phi
            )
        else:
            start = np.sqrt(D11_0) * draws_init[:, 0] if random_init else None
            assumed = 0.0 if filt == "ignoring" else None
            iterations = 1 if (filt == "v2" and cfg["v2 noise at"] == "updated estimate") else 0
            e, d = run_steps_variant2(scan, cfg_message(cfg), y, D11_0, start, assumed, iterations, None, phi)
        sq = (x - e) ** 2
        return {
            "steady": sq[:, sizes.window()].mean(axis=1),
            "d_steady": d[:, sizes.window()].mean(axis=1),
            "steady_after": sq[:, np.arange(sq.shape[1]) * sizes.dt > STEADY_AFTER_T].mean(axis=1),
            "scans": scan_averages(sq, sizes.steps_per_scan),
            "curve": sq.mean(axis=0),
            "d_curve": d.mean(axis=0),
        }

    out = _memo(key, compute)
    if cfg.get("steady window", WINDOW_DEFAULT) != WINDOW_DEFAULT:  # the whole run after the transient
        out = {**out, "steady": out["steady_after"]}
    return out


def steady_runs(cfg, seed, sizes, psi, contrast, filt):
    """Per-trial steady-state mean squared error, shape (n_trials,), of one filter at one point (T^2)."""
    return filter_errors(cfg, seed, sizes, psi, contrast, filt)["steady"]


def _ratio(a, b, statistic):
    a, b = keep_pair(a, b)  # the runs in lock only while lock_loss.in_lock is active; else as given
    if np.allclose(a, b, rtol=1e-9, atol=0.0):
        return Estimate(1.0, 0.0, 1.0, 1.0, a.size, 0.95, "exact")  # the same filter on the same runs
    return ratio_ci(a, b) if statistic == "mean" else median_ratio_ci(a, b)


def ratio_to_star(cfg, seed, sizes, contrast, filt="v2"):
    """sigma_x^2 / sigma_x^2* at contrast P (psi_A from the convention), paired on the same runs."""
    psi = psi_at(cfg["psi_A"], contrast, cfg["contrast convention"])
    a = steady_runs(cfg, seed, sizes, psi, contrast, filt)
    return _ratio(a, steady_runs(cfg, seed, sizes, psi, contrast, "stationary"), cfg["statistic"])


def _ratio_to_accounting(cfg, seed, sizes, contrast):
    """The filter ignoring the signal noise over variant 2 at contrast P (psi_A from the convention), paired on the
    same data: what accounting for the signal noise gains (1 exactly at P = 0, where the two are one filter)."""
    psi = psi_at(cfg["psi_A"], contrast, cfg["contrast convention"])
    a = steady_runs(cfg, seed, sizes, psi, contrast, "ignoring")
    return _ratio(a, steady_runs(cfg, seed, sizes, psi, contrast, "v2"), cfg["statistic"])


def _c1(cfg, seed, sizes):
    """C000-1 from the paper's start (truth stationary, inside the micro-raster; D11(0) = 0.2), per variant.

    "90 % of runs acquired": the fraction of runs not in lock for good by ``acquire_by_T`` (Clopper-Pearson; zero
    runs give the bound they certify). "ensemble mean within 10 %": sigma_x^2 over the scan ending at
    ``acquire_by_T`` over the steady sigma_x^2 (paired ratio over runs). Tagged with the reading
    (:meth:`tvtrack.verdicts.ByReading.tag`): each reading's rule judges its own quantity.
    """
    parts = {}
    scan_end = int(round(sizes.acquire_by_T * sizes.steps_per_scan * sizes.dt))  # scans up to acquire_by_T
    for filt in ("v1", "v2"):
        start = "uniform" if cfg["initial position"] == "uniform in the micro-raster" else None
        run = filter_errors(
            cfg, seed, sizes, cfg["psi_A"], cfg["contrast"], filt, offset=start, init=cfg["initial estimate"]
        )
        if cfg["convergence criterion"] == ENSEMBLE_MEAN:  # its own rule judges it (.claims, a ByReading rule)
            parts[f"variant {filt[1]}"] = ratio_ci(run["scans"][:, scan_end - 1], run["steady"])
            continue
        t = acquired_at(cfg, seed, sizes, filt, run)
        parts[f"variant {filt[1]}"] = proportion_ci(int(np.sum(t > sizes.acquire_by_T + 1e-9)), t.size)
    return ByReading.tag(cfg["convergence criterion"], parts)


def acquired_at(cfg, seed, sizes, filt, run):
    """Acquisition times (T) of a run; out of lock: a scan's mean square above lock_factor^2 x the steady mean
    square of the same filter from the paper's start."""
    ref = filter_errors(cfg, seed, sizes, cfg["psi_A"], cfg["contrast"], filt)["steady"].mean()
    factor = 2.0 if cfg.get("lock threshold", LOCK_DEFAULT) == "2 x steady RMS" else sizes.lock_factor
    return acquisition_times_from_scans(run["scans"], factor**2 * ref, sizes.steps_per_scan * sizes.dt)


def _c2(cfg, seed, sizes):
    """C000-2: steady RMS error over the micro-raster size at psi_A = 20, P = 0 and 0.5 (and, under the reading
    "C000-2 contrasts" = :data:`C2_EVERY`, both variants at every other contrast of Fig. 3), tagged with the
    reading."""
    size = 1.0 if cfg["micro-raster size"] == "T" else PULSE_DURATION
    reading = cfg.get("C000-2 contrasts", C2_CARD)
    points = [("P=0", 0.0, "stationary"), ("P=0.5 variant 1", 0.5, "v1"), ("P=0.5 variant 2", 0.5, "v2")]
    if reading == C2_EVERY:
        points += [
            (f"P={p:g} variant {f[1]}", p, f) for p in sizes.contrast_grid if p not in (0, 0.5) for f in ("v1", "v2")
        ]
    out = {}
    for name, p, filt in points:
        e = rms_ci(
            np.sqrt(keep(filter_errors(cfg, seed, sizes, 20.0, p, filt)["steady"]))[:, None]
        )  # in lock: lock_loss
        out[name] = Estimate(
            e.value / size, e.stderr / size, e.ci_low / size, e.ci_high / size, e.n, e.confidence, e.method
        )
    return ByReading.tag(reading, out)


def _c3(cfg, seed, sizes):
    """C000-3: v1 / v2 steady variance over the Fig. 3 contrasts (at psi_A) and the Fig. 2 SNRs (at P; the point
    that is Fig. 3's P = 0.5 at the default psi_A is left to Fig. 3, :func:`.claims.fig2_points`), tagged with the
    "contrast" it was measured at and then with the "signal-noise scale": at P = 0 with c_s = N0 P/(1-P) the Fig. 2
    parts are the same filter twice and are not measured; with c_s = A (eq. (6) as printed) variant 1 still models a
    signal noise at P = 0, so they are."""
    field = "d_steady" if cfg.get("C000-3 accuracy", "Monte Carlo error") == "filters' own D11" else "steady"

    def runs(psi, p, filt):
        return filter_errors(cfg, seed, sizes, psi, p, filt)[field]

    parts = {}
    for p in sizes.contrast_grid:
        psi = psi_at(cfg["psi_A"], p, cfg["contrast convention"])
        parts[f"P={p:g}"] = _ratio(runs(psi, p, "v1"), runs(psi, p, "v2"), cfg["statistic"])
    scale = cfg.get("signal-noise scale", CS_CONSISTENT)
    if cfg["contrast"] != 0 or scale == CS_LITERAL:
        for psi in fig2_points(sizes.contrast_grid, sizes.psi_grid):
            parts[f"psi_A={psi:g}"] = _ratio(
                runs(psi, cfg["contrast"], "v1"), runs(psi, cfg["contrast"], "v2"), cfg["statistic"]
            )
    return ByReading.tag(cfg["contrast"], ByReading.tag(scale, parts))


def _c5_c7(cfg, seed, sizes):
    """C000-5 (tagged with its reading of "substantially determines") and C000-7 from the ratios to sigma_x^2*
    (C000-5's from the filter ignoring the signal noise over variant 2 under its reading "C000-5 comparison" =
    :data:`ACCOUNTING`)."""
    grid = sizes.contrast_grid
    ratios = [ratio_to_star(cfg, seed, sizes, p) for p in grid]
    r9 = ratios[list(sizes.contrast_grid).index(0.9)]
    c5_ratios = ratios  # C000-5's reading of what it compares; C000-7 reads Fig. 3's ratio under every reading
    if cfg.get("C000-5 comparison", NOISE_EFFECT) == ACCOUNTING:
        c5_ratios = [_ratio_to_accounting(cfg, seed, sizes, p) if p not in (0, 0.5) else None for p in grid]
    c5 = {f"P={p:g}": r for p, r in zip(sizes.contrast_grid, c5_ratios) if 0 < p < 0.5}  # strict: not P = 0.5
    above = (
        [0.9] if cfg.get("substantially determines", AT_09) == AT_09 else [p for p in sizes.contrast_grid if p > 0.5]
    )
    c5.update({f"P={p:g}": c5_ratios[list(sizes.contrast_grid).index(p)] for p in above})
    psi9 = psi_at(cfg["psi_A"], 0.9, cfg["contrast convention"])
    nodes = phase_nodes(sizes)
    crlb = scan_crlb(operating_scan(cfg, psi9, 0.9, sizes), nodes) / scan_crlb(
        operating_scan(cfg, psi9, 0.0, sizes), nodes
    )
    gap = Estimate(crlb - r9.value, r9.stderr, crlb - r9.ci_high, crlb - r9.ci_low, r9.n, r9.confidence, r9.method)
    return ByReading.tag(cfg.get("substantially determines", AT_09), c5), {
        "trend": ratios,
        "measurement vs estimate": gap,
    }


def _c6(cfg, seed, sizes):
    """C000-6: the reading's filter over the reading's "potentially achievable" accuracy at P = 0.9."""
    psi = psi_at(cfg["psi_A"], 0.9, cfg["contrast convention"])
    filt = {"variant 2": "v2", "variant 1": "v1", "ignoring the signal noise": "ignoring"}[cfg["C000-6 filter"]]
    a = steady_runs(cfg, seed, sizes, psi, 0.9, filt)
    reference = cfg["potentially achievable"]
    if reference == "sigma_x^2*":
        return _ratio(a, steady_runs(cfg, seed, sizes, psi, 0.9, "stationary"), cfg["statistic"])
    if reference == "PCRLB":
        scan = operating_scan(cfg, psi, 0.9, sizes)
        bound = pcrlb_variance(scan, cfg_message(cfg), sizes.n_steps, bound_time(cfg), phase_nodes(sizes))
        bound = float(bound[sizes.window()].mean())
        a = keep(a)
        e = mean_square_ci(a) if cfg["statistic"] == "mean" else quantile_ci(a, 0.5)
        return Estimate(
            e.value / bound,
            e.stderr / bound,
            e.ci_low / bound,
            e.ci_high / bound,
            e.n,
            e.confidence,
            e.method + " over the PCRLB (exact)",
        )
    m = sizes.grid_trials

    def grid():
        x, pulse, xi, _ = truth_paths(cfg, seed, sizes)
        scan = operating_scan(cfg, psi, 0.9, sizes)
        y = photon_samples(cfg, seed, scan, pulse, xi)[:m]
        message = cfg_message(cfg)
        phi = switch_on_phases(seed, sizes)[:m]
        mean = grid_filter(scan, message, 0.5, sizes.grid_points, phi).run(y, 0.0, message.sigma**2).mean
        return ((x[:m] - mean) ** 2)[:, sizes.window()].mean(axis=1)

    g = _memo(
        ("grid", _data_key(cfg), cfg["sigma_sh"], cfg["photon model"], cfg.get("background"), seed, sizes, psi), grid
    )
    return _ratio(a[:m], g, cfg["statistic"])


def _c8(cfg, seed, sizes):
    """C000-8: sigma_x^2(dt) / sigma_x^2(dt / factor) - 1 over the Figs. 2-3 range, both variants, one continuous
    experiment (integrated samples at both rates, each estimate scored at its newest datum: the same information).

    Each (psi_A, P) of ``sizes.dt_points`` is run at that psi_A: the sentence («ошибки за счет дискретизации не
    превышали 3 %») is about the simulation's step, not about a point of Fig. 3, so C000-8 reads no "contrast
    convention" (under "fixed background" its P = 0.9 point moved to psi_A = 180 while its part still said 20).
    The memo keeps each variant's result, not the two-rate data (regenerated from the same seed when a reading of
    one variant changes)."""
    parts = {}
    iterations = 1 if cfg["v2 noise at"] == "updated estimate" else 0
    reads = {"v1": (cfg["G22"], _cs(cfg)), "v2": (iterations,)}
    for psi_p, p in sizes.dt_points:  # each point at its own psi_A under every "contrast convention"
        keys = {
            name: ("dt", cfg["sigma_sh"], cfg.get("sigma_1", "0.1 T"), seed, sizes, psi_p, p, name, reads[name])
            for name in ("v1", "v2")
        }
        got = {name: _MEMO[key] for name, key in keys.items() if key in _MEMO}
        missing = [name for name in keys if name not in got]
        if missing:
            scan = operating_scan(cfg, psi_p, p, sizes)
            d = simulate_two_rates(
                scan,
                cfg_message(cfg),
                sizes.dt_factor,
                np.random.default_rng([seed, 8]),
                sizes.dt_trials,
                int(round(sizes.dt_duration_T / sizes.dt)),
                score_at="interval_end",
                draw_phase=True,
            )
            win_c = d["t_coarse"] > 2 * sizes.dt_duration_T / 3
            win_f = d["t_fine"] > 2 * sizes.dt_duration_T / 3
            for name in missing:

                def run(s, y, name=name, phi=d["start"]):
                    if name == "v1":
                        return run_steps_variant1(
                            s, cfg_message(cfg), y, (D11_0, D22_0), None, BETA_0, cfg["G22"], None, _cs(cfg), phi
                        )[0]
                    return run_steps_variant2(s, cfg_message(cfg), y, D11_0, None, None, iterations, None, phi)[0]

                a = ((d["x_coarse"] - run(scan, d["y_coarse"])) ** 2)[:, win_c].mean(axis=1)
                b = ((d["x_fine"] - run(d["scan_fine"], d["y_fine"])) ** 2)[:, win_f].mean(axis=1)
                r = ratio_ci(a, b)
                got[name] = _memo(
                    keys[name],
                    lambda r=r: Estimate(
                        r.value - 1, r.stderr, r.ci_low - 1, r.ci_high - 1, r.n, r.confidence, r.method
                    ),
                )
        for name in ("v1", "v2"):
            parts[f"variant {name[1]} at psi_A={psi_p:g}, P={p:g}"] = got[name]
    return parts


def _c9(cfg, seed, sizes):
    """C000-9: steady sigma_x^2 over the Fig. 2 SNRs per variant (the ensemble mean, or the median run)."""
    stat = mean_square_ci if cfg["statistic"] == "mean" else (lambda a: quantile_ci(a, 0.5))
    return {
        f"variant {f[1]}": [
            stat(keep(steady_runs(cfg, seed, sizes, psi, cfg["contrast"], f))) for psi in sizes.psi_grid
        ]
        for f in ("v1", "v2")
    }


def measure(config: dict, seed: int, sizes: Sizes = Sizes(), claims: frozenset | None = None) -> dict:  # noqa: B008 - frozen
    """One full-size run of the study at ``config`` (every register entry present), draws from ``seed``.

    ``claims`` (claim ids, ``None`` for all): measure only these (:func:`tvtrack.explore.explore` asks a condition
    for the claims that read an entry it changes, a screened run's confirmation for the claims that may flip).
    Each claim draws from its own streams of ``seed``, so a claim's value does not depend on which others are
    measured with it.

    Returns
    -------
    dict  {claim id: measured}: C000-1, -2, -3, -5, -6, -7, -8, -9 (each a dict of parts, an Estimate or a
    list of Estimates, as the claim's rule in the notebook reads it), those of ``claims`` only when given (C000-5
    and C000-7 come together: one computation)
    """

    from ...register import project
    from .register import DEPENDS, REGISTER

    def reads(claim):  # the configuration projected onto the claim's DEPENDS: every other entry at its default
        return project(config, DEPENDS[claim], REGISTER.default())

    want = set(MEASURED_CLAIMS) if claims is None else set(claims)
    out = {}
    if want & {"C000-5", "C000-7"}:  # C000-5 declares what C000-7 does and its own reading of "substantially"
        c5, out["C000-7"] = _c5_c7(reads("C000-5" if "C000-5" in want else "C000-7"), seed, sizes)
        if "C000-5" in want:
            out["C000-5"] = c5
    single = {"C000-1": _c1, "C000-2": _c2, "C000-3": _c3, "C000-6": _c6, "C000-8": _c8, "C000-9": _c9}
    for cid, fn in single.items():
        if cid in want:
            out[cid] = fn(reads(cid), seed, sizes)
    return {cid: out[cid] for cid in MEASURED_CLAIMS if cid in out}


def measure_cost(config: dict, seed: int, n_trials: int, n_steps: int = 200) -> dict:
    """C000-4 at ``config``, tagged with its "C000-4 cost measure" (:meth:`tvtrack.verdicts.ByReading.tag`): the
    arithmetic operations per filter step of variant 1 over variant 2 (:func:`.cost.operation_ratio`; the default
    reading, shown, not judged: :func:`.claims.cost_rule`), or the CPU-time ratio :func:`cost_ratio` of the compiled
    steps over ``n_trials`` runs of ``n_steps`` samples (``"C000-4 batch" = "all trials"``) or over one run of
    ``n_trials * n_steps`` samples; variant 2 re-evaluates eq. (9)'s noise at the update when ``"v2 noise at"`` says.

    Returns
    -------
    dict  {"C000-4": tag(reading, variant 1 / variant 2: the exact operation-count ratio (float), or the CPU-time
    ratio with the interval of its repeated paired timings (:class:`~tvtrack.estimate.Estimate`; NaN uncompiled))}
    """
    iterations = 1 if config["v2 noise at"] == "updated estimate" else 0
    reading = config.get("C000-4 cost measure", COST_READINGS[0])
    if reading == COST_READINGS[0]:
        return {"C000-4": ByReading.tag(reading, operation_ratio(iterations))}
    one = config["C000-4 batch"] == "one trial"
    ratio = cost_ratio(n_trials, n_steps, seed, noise_iterations=iterations, one_trial=one)
    return {"C000-4": ByReading.tag(reading, ratio)}


def cost_ratio(
    n_trials: int, n_steps: int, seed: int, repeats: int = 11, noise_iterations: int = 0, one_trial: bool = False
) -> Estimate:
    """CPU time of variant 1 over variant 2 on the same samples at psi_A = 20, P = 0.5 (claim C000-4), with the
    interval of ``repeats`` paired timings (:func:`.cpu_time.paired_time_ratio`); ``noise_iterations``
    re-evaluations of variant 2's noise intensity at the updated estimate.

    Both variants run as their compiled straight-line steps (:mod:`._kernels`, the operations :mod:`.cost` counts,
    in the same order), so the time is the arithmetic's, with no interpreter between operations: ``n_trials`` runs
    of ``n_steps`` samples, or (``one_trial``) one tracked object over ``n_trials * n_steps`` samples. Interpreted
    steps would time the interpreter's call overhead: without compiled steps (:func:`tvtrack.jit.enabled` false)
    the ratio is NaN (undecided).
    """
    if not jit.enabled():
        nan = float("nan")
        return Estimate(nan, nan, nan, nan, 0, 0.95, "none (no compiled steps: the interpreter would be timed)")
    scan = scan_at_snr(20.0, 0.5, 0.05, PULSE_DURATION)
    shape = (1, n_trials * n_steps) if one_trial else (n_trials, n_steps)
    noises = draw_noises(np.random.default_rng(seed), *shape, 1)
    _, pulse = truth_and_pulse(scan, MESSAGE, noises)
    y = samples_from_pulse(scan, pulse, noises["xi"])
    v1 = lambda y: run_steps_variant1(scan, MESSAGE, y, (D11_0, D22_0), None, BETA_0, compiled=True)  # noqa: E731
    v2 = lambda y: run_steps_variant2(scan, MESSAGE, y, D11_0, None, None, noise_iterations, compiled=True)  # noqa: E731
    return paired_time_ratio(v1, v2, y, repeats)


def record_inputs(config: dict, seed: int, sizes: Sizes):
    """The scan, truth, mean pulses and noise draws of the default run (for :func:`.recording.record_trial`, which
    records trial 0: the scan's time offset carries that trial's switch-on phase)."""
    x, pulse, xi, _ = truth_paths(config, seed, sizes)
    scan = operating_scan(config, config["psi_A"], config["contrast"], sizes)
    return replace(scan, time_offset=scan.time_offset + float(switch_on_phases(seed, sizes)[0])), x, pulse, xi
