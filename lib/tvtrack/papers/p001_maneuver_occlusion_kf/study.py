"""Study drivers of paper 001 (Fisenko et al. 2008): the measurement functions the explorer calls and the studies
the notebook shows. The scenario lives in :mod:`.scenario`, the comparators in :mod:`.comparators`, the curves of
Fig. 4 and the loss-time sweep in :mod:`.curves`, C001-9 in :mod:`.spherical`, C001-4's measurement in
:mod:`.tradeoff` and C001-3's closed form in :mod:`.false_alarm`.

A measurement function is ``measure(config, seed, sizes) -> {claim id: measured}``: one full-size run of the
study at ``config`` (a dict with every register entry of :mod:`.register`), every random draw from
``np.random.default_rng(seed)``, the same noise streams whatever the configuration (common random numbers).
``sizes`` holds the notebook's sample sizes and, under ``"defaults"``, the register's default configuration, which
completes a configuration that names only the entries of one exploration (bind ``sizes`` with
``functools.partial``, which stays picklable).

Units: positions in raster elements, velocities in elements/frame, accelerations in elements/frame²; the motion is
the paper's per frame at every frame rate, and only its times in seconds become frames (:mod:`.scenario`).
"""

from __future__ import annotations

import numpy as np
from scipy import signal, stats

from ...filters.alphabeta import gain_schedule, scheduled_filter
from ...estimate import Estimate
from ...montecarlo import mean_ci, paired_difference
from ...projection import as_declared
from .false_alarm import closed_form_check, closed_form_rate, statistic_impulse_response
from .maneuver_detector import (
    detection_time_summary,
    false_alarm_rates,
    first_alarm_within,
    null_quantile_threshold,
    scheduled_statistic_std,
    window_statistic,
    window_sum_of_squares,
)
from .track_modes import TrackModeConfig, run_track_modes
from .sizes import declared
from .scenario import (
    MOTION,
    THRESHOLD_READINGS,
    UMP_COMPARATORS,
    Scenario,
    config_scenario,
    measurements,
    prefix_stable_measurements,
    detector_threshold,
    arming_count,
    cadence_threshold,
    with_defaults,
    run_scheme,
    uniform_truth,
)
from .comparators import comparator_positions, comparator_tuning

__all__ = [
    "detection_time_summary",
    "gls_window_taps",
    "tapped_window_statistic",
    "measure_detection",
    "c3_closed_form_check",
    "tradeoff_runs",
    "scenario_runs",
    "gain_checks",
    "coast_check",
    "sigma_s_readings",
    "measure_tradeoff",
    "detector_benchmark",
    "MOTION",
    "THRESHOLD_READINGS",
    "UMP_COMPARATORS",
    "Scenario",
    "config_scenario",
    "measurements",
    "detector_threshold",
    "arming_count",
    "run_scheme",
    "comparator_positions",
]


def gls_window_taps(K2, n: int, sigma_eps: float = 1.0) -> np.ndarray:
    """Taps (2n,) over ``v[t-2n+1 .. t]`` of the GLS-weighted window difference: ``+w`` on the older window, ``-w``
    on the newer, ``w = C_z⁻¹ 1`` with ``C_z`` the stationary covariance of ``z_k = v_k - v_{k+n}`` of the frozen
    filter with gains ``K2`` (``cov(z_i, z_j) = 2 r(i-j) - r(i-j-n) - r(i-j+n)``); with independent samples
    ``w`` is constant and the statistic is (14)'s S up to scale."""
    from ...filters.alphabeta import lagged_covariances

    r = lagged_covariances(np.asarray(K2, float), sigma_eps, 2 * n)[:, 1, 1]
    d = np.subtract.outer(np.arange(n), np.arange(n))
    Cz = 2 * r[np.abs(d)] - r[np.abs(d - n)] - r[np.abs(d + n)]
    w = np.linalg.solve(Cz, np.ones(n))
    return np.concatenate([w, -w]) / np.abs(w).sum()


def tapped_window_statistic(v, taps) -> np.ndarray:
    """``sum_j taps[j] v[t-2n+1+j]`` along the last axis, NaN before the window is full (shape of v)."""
    taps = np.asarray(taps, float)
    v = np.asarray(v, float)
    out = signal.lfilter(taps[::-1], [1.0], np.nan_to_num(v), axis=-1)
    out[..., : taps.size - 1] = np.nan
    return out


def _missing(what: str) -> Estimate:
    return Estimate(float("nan"), float("nan"), float("nan"), float("nan"), 0, 0.95, what)


def _frame_resolution(e: Estimate, fps: float) -> Estimate:
    """A detection-time quantile with its order-statistic interval widened by half a frame each side: a detection
    at frame f means the statistic crossed the threshold within the frame interval, so time is known to a frame
    (the interval of a quantile of frame-quantised times is otherwise often one frame wide, i.e. degenerate)."""
    h = 0.5 / fps
    return Estimate(
        e.value,
        e.stderr,
        e.ci_low - h,
        e.ci_high + h,
        e.n,
        e.confidence,
        f"{e.method}, widened by half a frame each side (time resolution)",
        sampling_low=e.ci_low,  # the order statistics' interval: pooling shrinks it, not the half frame
        sampling_high=e.ci_high,
    )


def _per_alpha(e: Estimate, alpha: float) -> Estimate:
    """A per-test rate in units of alpha (so one rule serves every alpha of the register)."""
    return Estimate(
        e.value / alpha,
        e.stderr / alpha,
        e.ci_low / alpha,
        e.ci_high / alpha,
        e.n,
        e.confidence,
        "exact" if e.method == "exact" else f"{e.method}, divided by alpha",  # a closed-form number stays exact
    )


def _step_runs(config: dict, sc: Scenario, Tr: int, n_runs: int, rng: np.random.Generator, sigma: float):
    """Measurements (n_runs, 2, Tr) of C001-2's step alternative: a velocity step of ``step_dv`` elements/frame at
    the onset, both channels, away from the manoeuvre's sign."""
    return measurements(_step_truth(config, sc, Tr), config["noise"], n_runs, rng, sigma)


def _step_truth(config: dict, sc: Scenario, Tr: int) -> np.ndarray:
    """Noise-free positions (2, Tr) of C001-2's step alternative, elements: uniform motion, then a velocity step
    of ``step_dv`` elements/frame at the onset, away from the manoeuvre's sign (per frame at every frame rate, as
    the paper's motion)."""
    t = np.arange(Tr)
    dv = float(config["step_dv"])
    return np.stack([v0 * t + np.sign(a) * dv * np.clip(t - sc.onset, 0, None) for v0, a in MOTION])


def _ump_comparator_statistics(name: str, v_null, v_alt, G, n: int, sigma: float):
    """C001-2's other invariant statistic on no-manoeuvre and manoeuvre velocities (..., Tr): the sum of squares Q,
    or |w·z| with the GLS taps of the frozen TRACK2 filter (``UMP_COMPARATORS``)."""
    if name == UMP_COMPARATORS[0]:
        return window_sum_of_squares(v_null, n), window_sum_of_squares(v_alt, n)
    taps = gls_window_taps(G[-1], n, sigma)
    return np.abs(tapped_window_statistic(v_null, taps)), np.abs(tapped_window_statistic(v_alt, taps))


def measure_detection(config: dict, seed: int, sizes: dict, claims=None) -> dict:
    """C001-1 (detection time), C001-2 (size, invariance, unbiasedness, optimality) and C001-3 (the paper's
    independence threshold) from one full-size run. Per-test rates are in units of the configuration's alpha.

    Config entries read: ``frame_rate_hz``, ``window_n``, ``k_bound2``, ``alpha``, ``arming``, ``threshold``,
    ``paper_sigma``, ``noise``, ``alternative``, ``roc_delay_s``, ``step_dv``, ``ump_comparator``. Sizes:
    ``n_trials`` (scenario runs, both channels), ``n_fa_runs`` (no-manoeuvre runs), ``fa_duration_s``,
    ``sigma_eps``. ``claims``: the claim ids to measure (None: all); the others' work is skipped, never their
    random draws that a later claim's stream follows, so each asked claim is the same number as in a full run
    (tested bit for bit).
    """
    asked = set(GROUP_DETECTION if claims is None else claims) & set(GROUP_DETECTION)
    if not asked:
        return {}
    config = with_defaults(config, sizes)
    sc = config_scenario(config)
    n, kb2, sigma = int(config["window_n"]), int(config["k_bound2"]), sizes["sigma_eps"]
    arm_k, _ = arming_count(config["arming"], kb2, n, sc.onset)
    rng = np.random.default_rng(seed)
    # the scenario runs up to the loss, both channels
    Tl = sc.f_loss
    z = measurements(sc.truth[:, :Tl, 0], config["noise"], sizes["n_trials"], rng, sigma)  # (runs, 2, Tl)
    out = {"C001-1": _c001_1(config, sc, z, arm_k, sigma)} if "C001-1" in asked else {}
    if asked <= {"C001-1"}:
        return out
    # no-manoeuvre runs of channel x (uniform motion) on their own stream, drawn frame by frame: C001-3 reads their
    # first T3 frames, which neither C001-2's alternative nor its response delay (the runs' length T0) can move
    T3 = max(int(round(sizes["fa_duration_s"] * sc.fps)), arm_k + 1)
    if "C001-2" in asked:  # the alternative's runs end roc_delay_s after the onset
        Tr = sc.onset + int(round(float(config["roc_delay_s"]) * sc.fps)) + 1
    T0 = max(T3, Tr) if "C001-2" in asked else T3
    truth0 = uniform_truth(T0)
    z0 = prefix_stable_measurements(truth0, config["noise"], sizes["n_fa_runs"], _child_rng(seed, 4), sigma)
    G0 = gain_schedule(1, kb2, T0)
    v0_hat = scheduled_filter(z0, G0)[..., 1]
    S0 = window_statistic(v0_hat, n)
    f0 = np.arange(T0)
    armed0 = f0 >= arm_k - 1
    null = (S0, armed0, armed0 & (f0 < sc.onset), T0, arm_k)
    if "C001-2" in asked:
        ramp = config["alternative"] == "ramp"
        za = z[..., :Tr] if ramp else _step_runs(config, sc, Tr, sizes["n_trials"], rng, sigma)
        shift = 50 * rng.standard_normal((5, n))
        alt = (sc.truth[:, :Tr, 0] if ramp else _step_truth(config, sc, Tr), _child_rng(seed, 2))
        out["C001-2"] = _c001_2(config, sc, sigma, za, v0_hat, G0, null, shift, Tr, alt)
    if "C001-3" in asked:
        null3 = (S0[:, :T3], armed0[:T3], null[2][:T3], T3, arm_k)
        out["C001-3"] = _c001_3(config, sigma, G0[:T3], null3, _child_rng(seed, 3))
    return out


# each claim at its configuration projected onto DEPENDS; as_declared applied here, not as a decorator:
# mutmut 3 mutates no decorated function (docs/mutation.md)
measure_detection = as_declared(("C001-1", "C001-2", "C001-3"), declared)(measure_detection)


#: The claims :func:`measure_detection` measures.
GROUP_DETECTION = ("C001-1", "C001-2", "C001-3")


def _c001_1(config: dict, sc: Scenario, z, arm_k: int, sigma: float) -> dict:
    """C001-1's parts on the scenario runs z (runs, 2, Tl): the scheme with the reading's threshold."""
    n, kb2, alpha, Tl = int(config["window_n"]), int(config["k_bound2"]), float(config["alpha"]), sc.f_loss
    c1 = detector_threshold(config["threshold"], np.ones(Tl, bool), kb2, n, alpha, sigma)
    c1 = cadence_threshold(c1, config["test_cadence"], n, arm_k)
    cfg = TrackModeConfig(k_bound2=kb2, window=n, threshold=c1, threshold_index="frame", arm_k=arm_k)
    det = run_track_modes(z, np.ones(Tl, bool), cfg, sigma, covariance=False).detection_frame
    s = detection_time_summary(det, sc.onset, Tl, sc.fps)
    return {
        "median": _frame_resolution(s["median_s"], sc.fps) if s["median_s"] else _missing("fewer than two detections"),
        "early": s["false_alarm_before_onset"],
        "missed": s["missed_by_loss"],
    }


def _child_rng(seed: int, key: int) -> np.random.Generator:
    """A child stream of the run's seed: 2 for C001-2's conditional closed form (Student-t scales), 3 for C001-3's,
    4 for the no-manoeuvre runs. Each claim's draws are then the same whichever other claims are asked and
    whatever the others' entries are."""
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(key,)))


def _c001_2(config: dict, sc: Scenario, sigma: float, za, v0_hat, G0, null: tuple, shift, Tr: int, alt) -> dict:
    """C001-2's parts: size with the exact sigma_S; unbiasedness and power against the UMP comparator on the
    TRACK2 filter (no switch); ``za`` (runs, 2, Tr) the alternative's runs, ``null`` the no-manoeuvre statistic
    ``(S0, armed0, pre0, T0, arm_k)``, ``shift`` (5, n) the invariance check's offsets, ``alt`` the alternative's
    noise-free positions (2, Tr) and the closed form's generator.

    Unbiasedness is the test's alarm rate after the onset, ``P(|S_t| > c_t)`` averaged over the two channels and
    the armed frames after the onset: a rare event (about alpha per test), so it is computed from the statistic's
    distribution (:func:`.false_alarm.closed_form_rate` with the alternative's mean ``E[S_t] = x H``), exact for
    the Gaussian error models, never from the handful of alarms a Monte Carlo counts (the counted rate is its
    cross-check, and bounds the quantised model)."""
    n, kb2, alpha = int(config["window_n"]), int(config["k_bound2"]), float(config["alpha"])
    S0, armed0, pre0, T0, arm_k = null
    c_exact0 = detector_threshold("exact", np.ones(T0, bool), kb2, n, alpha, sigma)
    size = false_alarm_rates(S0, c_exact0, armed0, pre0, T0 - 1, arm_k - 1)["per_test_pooled"]
    va = scheduled_filter(za, G0[:Tr])[..., 1]
    sig_t = scheduled_statistic_std(G0[:Tr], n, sigma)
    sig_t = np.where(np.isfinite(sig_t), sig_t, np.inf)
    arm_r = np.arange(Tr) >= arm_k - 1
    Q0, Qa = _ump_comparator_statistics(
        config.get("ump_comparator", UMP_COMPARATORS[0]), v0_hat[:, :Tr], va, G0, n, sigma
    )
    q_scale = np.full(Tr, np.inf)
    q_scale[arm_r] = Q0[:, arm_r].mean(axis=0)
    stat_S, stat_S0 = np.abs(window_statistic(va, n)) / sig_t, np.abs(S0[:, :Tr]) / sig_t
    stat_Q, stat_Q0 = Qa / q_scale, Q0 / q_scale
    hits_S = first_alarm_within(stat_S, null_quantile_threshold(stat_S0, arm_r, alpha), arm_r, sc.onset)
    hits_Q = first_alarm_within(stat_Q, null_quantile_threshold(stat_Q0, arm_r, alpha), arm_r, sc.onset)
    post = arm_r & (np.arange(Tr) >= sc.onset)
    counted = mean_ci((stat_S[..., post] > stats.norm.isf(alpha / 2)).mean(axis=-1).reshape(-1))
    H = statistic_impulse_response(G0[:Tr], n)
    post &= np.isfinite(H).all(axis=0)
    mean = np.asarray(alt[0], float) @ np.nan_to_num(H)
    c_t = stats.norm.isf(alpha / 2) * sig_t
    unbiased = closed_form_rate(H, c_t, post, config["noise"], sigma, rng=alt[1], mc=counted, mean=mean)
    v_test = v0_hat[:5, -2 * n :]
    invariance = float(
        np.max(
            np.abs(
                window_statistic(v_test + np.concatenate([shift, shift], axis=1), n)[:, -1]
                - window_statistic(v_test, n)[:, -1]
            )
        )
    )
    return {
        "size": _per_alpha(size, alpha),
        "invariance": invariance,
        "unbiased": _per_alpha(unbiased, alpha),
        "UMP": paired_difference(hits_S.reshape(-1).astype(float), hits_Q.reshape(-1).astype(float)),
    }


def _c001_3(config: dict, sigma: float, G0, null: tuple, rng: np.random.Generator) -> Estimate:
    """C001-3: the paper's independence threshold, sigma read as the filter-output or the raw-increment RMS; its
    per-test rate in units of alpha (the Gaussian closed form, checked against the null runs)."""
    n, kb2, alpha = int(config["window_n"]), int(config["k_bound2"]), float(config["alpha"])
    S0, armed0, pre0, T0, arm_k = null
    reading = "independent" if config["paper_sigma"] == "filter-output velocity" else "raw increments"
    c_paper = detector_threshold(reading, np.ones(T0, bool), kb2, n, alpha, sigma)
    mc3 = false_alarm_rates(S0, c_paper, armed0, pre0, T0 - 1, arm_k - 1)["per_test_pooled"]
    cf3 = closed_form_rate(
        statistic_impulse_response(G0, n), c_paper, armed0, config["noise"], sigma, rng=rng, runs=2000, mc=mc3
    )
    return _per_alpha(cf3, alpha)


def c3_closed_form_check(config: dict, seed: int, sizes: dict) -> dict:
    """C001-3's closed form against a Monte Carlo of the same per-test rate (in units of alpha) on
    ``n_fa_runs`` fresh no-manoeuvre runs of ``fa_duration_s``: :func:`.false_alarm.closed_form_check`."""
    config = with_defaults(config, sizes)
    sc = config_scenario(config)
    n, kb2, alpha, sigma = int(config["window_n"]), int(config["k_bound2"]), float(config["alpha"]), sizes["sigma_eps"]
    arm_k, _ = arming_count(config["arming"], kb2, n, sc.onset)
    rng = np.random.default_rng(seed)
    T0 = max(int(round(sizes["fa_duration_s"] * sc.fps)), arm_k + 1)
    z0 = measurements(uniform_truth(T0), config["noise"], sizes["n_fa_runs"], rng, sigma)
    G0 = gain_schedule(1, kb2, T0)
    S0 = window_statistic(scheduled_filter(z0, G0)[..., 1], n)
    f0 = np.arange(T0)
    armed0 = f0 >= arm_k - 1
    reading = "independent" if config["paper_sigma"] == "filter-output velocity" else "raw increments"
    c = detector_threshold(reading, np.ones(T0, bool), kb2, n, alpha, sigma)
    mc = false_alarm_rates(S0, c, armed0, armed0 & (f0 < sc.onset), T0 - 1, arm_k - 1)["per_test_pooled"]
    cf = closed_form_rate(statistic_impulse_response(G0, n), c, armed0, config["noise"], sigma, rng=rng, mc=mc)
    return closed_form_check(_per_alpha(cf, alpha), _per_alpha(mc, alpha))


def tradeoff_runs(config: dict, seed: int, sizes: dict) -> dict:
    """The scheme and every tuned comparator on the same test runs (channel x and y).

    Returns
    -------
    dict
        ``scenario``; ``positions`` ``{name: (runs, 2, T)}`` for ``"adaptive"``, ``"2nd order without the
        switch"`` (the scheme's own TRACK2 filter, never switching) and each comparator tuned for the config's
        ``rms_span``; ``tuning`` (settings, training RMS, on-edge flags); ``z`` the measurements.
    """
    config = with_defaults(config, sizes)
    sc = config_scenario(config)
    sigma = sizes["sigma_eps"]
    rng = np.random.default_rng(seed)
    z = measurements(sc.truth[:, :, 0], config["noise"], sizes["n_tradeoff_trials"], rng, sigma)
    tuning = comparator_tuning(config, sizes)[config["rms_span"]]
    pos = {
        "adaptive": run_scheme(z, sc, config, sizes, covariance=False).x[..., 0],
        "2nd order without the switch": comparator_positions(
            "fixed 2nd order", (int(config["k_bound2"]),), z, sc, sigma
        ),
    }
    for name, (setting, _, _) in tuning.items():
        pos[name] = comparator_positions(name, setting, z, sc, sigma)
    return {"scenario": sc, "positions": pos, "tuning": tuning, "z": z}


def scenario_runs(config: dict, seed: int, sizes: dict, restarts=("A", "B", "C")) -> dict:
    """The paper's scenario (both channels, ``sizes["n_trials"]`` runs) through the scheme under each restart rule,
    with the covariance (gate): ``{"scenario", "z", "outs": {restart: TrackModeOutput}}``."""
    config = with_defaults(config, sizes)
    sc = config_scenario(config)
    z = measurements(
        sc.truth[:, :, 0], config["noise"], sizes["n_trials"], np.random.default_rng(seed), sizes["sigma_eps"]
    )
    return {"scenario": sc, "z": z, "outs": {r: run_scheme(z, sc, config | {"restart": r}, sizes) for r in restarts}}


def gain_checks(out, sc: Scenario, k_bound3: int) -> dict:
    """C001-5's implementation checks: increases of kappa1 on consecutive visible frames outside the order switches,
    and the runs x channels that switched at least ``k_bound3`` frames before the loss and sit at the 3rd-order
    bound's kappa1 at the last frame before it."""
    k1 = out.gains[..., 0]
    both = sc.visible[1:] & sc.visible[:-1]
    dk = np.diff(k1, axis=-1)
    det = out.detection_frame
    switch = np.zeros(dk.shape, bool)
    hit = det >= 0
    idx = np.nonzero(hit)
    switch[idx + (np.clip(det[hit], 0, sc.T - 2),)] = True
    increases = int(np.sum((dk > 1e-15) & both & ~switch))
    long_enough = hit & (sc.f_loss - 1 - det >= k_bound3)
    at_bound = np.isclose(k1[..., sc.f_loss - 1], gain_schedule(2, k_bound3)[-1, 0])
    return {
        "increases_outside_switches": increases,
        "long_enough": int(long_enough.sum()),
        "at_bound": int((at_bound & long_enough).sum()),
    }


def coast_check(out, sc: Scenario) -> dict:
    """C001-6: the largest difference between the actual error while lost and ``F^m`` times the error at the last
    seen frame (E2), and the size of the errors, elements."""
    from ...filters.polynomial import taylor_transition

    err = out.x - sc.truth[None]
    m = np.arange(1, sc.f_back - sc.f_loss + 1)
    Fm = np.stack([np.linalg.matrix_power(taylor_transition(2), int(k)) for k in m])
    pred = np.einsum("mij,...j->...mi", Fm, err[..., sc.f_loss - 1, :])
    actual = err[..., sc.f_loss : sc.f_back, :]
    return {"max_abs_deviation": float(np.max(np.abs(pred - actual))), "error_scale": float(np.max(np.abs(actual)))}


def sigma_s_readings(config: dict, sizes: dict) -> dict:
    """sigma_S (elements/frame) at the detector's first test (the frame of TRACK2 count ``arm_k`` of the
    configuration's arming rule, :func:`arming_count`) under each threshold reading, the lag-1 correlation of the
    frozen TRACK2 filter's output velocity, and the per-test rate the paper's independence threshold gives at
    stationarity (Gaussian: 2 Phi(-c_ind / sigma_S))."""
    from ...filters.alphabeta import lagged_covariances

    config = with_defaults(config, sizes)
    n, kb2, alpha = int(config["window_n"]), int(config["k_bound2"]), float(config["alpha"])
    arm_k, _ = arming_count(config["arming"], kb2, n, config_scenario(config).onset)
    K2 = gain_schedule(1, kb2)[-1]
    C = lagged_covariances(K2, sizes["sigma_eps"], 2)
    z_a = stats.norm.isf(alpha / 2)
    sig = {  # frames 0 .. arm_k - 1: the last is the first tested
        r: float(detector_threshold(r, np.ones(arm_k, bool), kb2, n, alpha, sizes["sigma_eps"])[-1] / z_a)
        for r in THRESHOLD_READINGS
    }
    return {
        "sigma_S": sig,
        "rho_v1": float(C[1, 1, 1] / C[0, 1, 1]),
        "pfa_independent": float(2 * stats.norm.sf(sig["independent"] / sig["stationary"] * z_a)),
    }


def measure_tradeoff(config: dict, seed: int, sizes: dict, claims=None) -> dict:
    """C001-4's measurement: :func:`.tradeoff.measure_tradeoff` (the dynamic error's transient and the RMS the
    register's ``rms_statistic`` reads, as separate parts); ``{}`` when ``claims`` does not ask for C001-4."""
    from .tradeoff import measure_tradeoff as measure

    return measure(config, seed, sizes) if claims is None or "C001-4" in claims else {}


def detector_benchmark(config: dict, seed: int, sizes: dict, windows=(10, 25, 50), fa_targets=None) -> dict:
    """Delay against per-run false alarms of the paper's |S| (several half-windows), Q and three innovation tests
    (chi-square over n frames, two-sided CUSUM with drift 0.5, the Willsky-Jones GLR for a velocity jump) on the
    TRACK2 filter: thresholds from no-manoeuvre runs of ``fa_duration_s`` for each per-run false-alarm target,
    median first-alarm delay after the onset on the scenario's runs up to the loss (a study beyond the paper). The
    no-manoeuvre runs last at least as long as those (a shorter ``fa_duration_s`` has no null statistic for the last
    frames).

    Every detector is armed by the configuration's arming rule for its own window (:func:`arming_count`), so each
    tests before the onset; a detector first armed after the onset would "detect" at its first test in every run.

    Returns
    -------
    dict
        ``{name: curve}`` with the curves of :func:`tvtrack.detect.innovation.delay_false_alarm_curve`, and
        ``"arming_frame"``: ``{name: first tested frame}``.
    """
    from ...detect.innovation import (
        chi2_window,
        cusum,
        delay_false_alarm_curve,
        glr_velocity_jump,
        normalised_innovations,
        velocity_jump_signature,
    )

    config = with_defaults(config, sizes)
    sc = config_scenario(config)
    n, kb2, sigma = int(config["window_n"]), int(config["k_bound2"]), sizes["sigma_eps"]
    targets = np.array([0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5]) if fa_targets is None else np.asarray(fa_targets)
    rng = np.random.default_rng(seed)
    Tl = sc.f_loss
    T0 = max(int(round(sizes["fa_duration_s"] * sc.fps)), Tl)  # the null runs at least as long as the alternative's
    z = measurements(sc.truth[:, :Tl, 0], config["noise"], sizes["n_trials"], rng, sigma)
    z0 = measurements(uniform_truth(T0), config["noise"], sizes["n_fa_runs"], rng, sigma)
    G = gain_schedule(1, kb2, max(Tl, T0))
    s_alt, s_null = scheduled_filter(z, G[:Tl]), scheduled_filter(z0, G[:T0])
    u_alt = normalised_innovations(z, s_alt, G[:Tl], sigma)
    u_null = normalised_innovations(z0, s_null, G[:T0], sigma)
    stats_ = {}
    for w in sorted(set(windows) | {n}):
        a, _ = arming_count(config["arming"], kb2, w, sc.onset)
        sig = scheduled_statistic_std(G[:T0], w, sigma)
        sig = np.where(np.isfinite(sig) & (sig > 0), sig, np.inf)
        stats_[f"|S|, n={w}"] = (
            np.abs(window_statistic(s_alt[..., 1], w)) / sig[:Tl],
            np.abs(window_statistic(s_null[..., 1], w)) / sig,
            a,
        )
    a, _ = arming_count(config["arming"], kb2, n, sc.onset)
    q0 = window_sum_of_squares(s_null[..., 1], n)
    q_mean = np.full(T0, np.inf)
    q_mean[a - 1 :] = q0[:, a - 1 :].mean(axis=0)
    stats_[f"Q, n={n}"] = (window_sum_of_squares(s_alt[..., 1], n) / q_mean[:Tl], q0 / q_mean, a)
    stats_[f"chi-square, L={n}"] = (chi2_window(u_alt, n), chi2_window(u_null, n), a)
    stats_["CUSUM, k=0.5"] = (cusum(u_alt, 0.5, a - 1), cusum(u_null, 0.5, a - 1), a)
    sigj = velocity_jump_signature(gain_schedule(1, kb2)[-1], sigma, n)
    stats_[f"GLR velocity jump, L={n}"] = (glr_velocity_jump(u_alt, sigj), glr_velocity_jump(u_null, sigj), a)
    out = {"arming_frame": {}}
    for name, (alt, null, a) in stats_.items():
        out[name] = delay_false_alarm_curve(
            alt,
            null,
            np.arange(Tl) >= a - 1,
            np.arange(T0) >= a - 1,
            sc.onset,
            targets,
            sc.fps,
            float(config["roc_delay_s"]),
        )
        out["arming_frame"][name] = a - 1
    return out
