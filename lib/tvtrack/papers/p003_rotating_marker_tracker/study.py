"""Measurement functions of notebook 003 (what the explorer calls) and the direct-count estimators they use.

Two measurement functions, each a pure function of ``(config, seed)`` with every draw from generators seeded by
``seed`` (common random numbers: the same streams whatever the configuration):

- :func:`measure_tracking` -- the claims without interferers (C003-1 to C003-4, C003-9): Fig. 1 and Fig. 2 runs,
  the rotation-locked error (with a far and a near control frequency and over the coordinate-loop bandwidth),
  the background sweep and the edge-versus-quadrant runs;
- :func:`measure_interference` -- the loss-of-lock claims (C003-5 to C003-7, C003-10 to C003-12): loss curves of
  the rotating marker and of the static baseline with one and five interferers, the gate ablation, the
  uncompensated runs and the law-following decoy, all on one SIR grid with the same runs at every SIR.

Every verdict reads direct counts, never a fitted tail: the probability of loss at a grid SIR is a count with its
Clopper-Pearson interval (zero events: the one-sided bound they certify); a threshold is the geometric mean of the
per-run breaking SIRs (each run is interval-censored between the last grid SIR where it lost lock and the first
where it kept it), with a Student-t interval widened by half the grid step, and it is flagged ``extrapolated``
(undecided) when a run breaks outside the grid.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...montecarlo import Estimate, mean_ci, proportion_ci, ratio_ci, rms_ci, zero_events_bound
from .discriminators import quadrant_slope_fit
from .lock import CRITERIA, LossCriterion, first_loss, loss_criteria
from .loops import phase_locked_amplitude, stack_gains
from .scene import (
    Scenario,
    interference_runs,
    median_residual,
    place_interferers,
    run_scenario,
    scenario_truth,
    state_errors,
)

__all__ = [
    "SIR_GRID",
    "UNCOMPENSATED_GRID",
    "BXY_GRID",
    "LINEAR_BAND",
    "Sizes",
    "scenario",
    "criterion",
    "loss_share",
    "log_thresholds",
    "threshold",
    "threshold_bound",
    "threshold_ratio",
    "fold_distance",
    "measure_tracking",
    "measure_interference",
    "exposure_study",
    "median_example",
]

SIR_GRID = (0.5, 0.75, 1.0, 4 / 3, 2.0, 3.0, 4.5, 6.75)  # post-compensation SIR, steps of 1.33-1.5
UNCOMPENSATED_GRID = (1.0, 2.0, 4.0, 8.0, 16.0)  # SIR_0 without compensation (kappa = 1)
LINEAR_BAND = (0.9, 1.1)  # C003-9: quadrant slope / 2dD counted "linear" (the rule and the s-curve caption)
BXY_GRID = (2.0, 5.0, 10.0, 20.0)  # coordinate-loop bandwidths of the C003-2 mechanism, Hz
RADIUS_OFFSETS = {"r0": 0.0, "r0 - D/2": -0.5, "r0 + D/2": 0.5}  # interferer radius, offsets in units of D
# rotation-rate laws (depth, Hz): "mean rotation frequency 8 rev/s" (l. 185) says omega varies; its law is unstated
ROTATION_LAWS = {
    "constant": (0.0, 0.5),
    "modulated": (0.1, 0.5),
    "modulated fast": (0.15, 1.0),
    "modulated strong": (0.2, 1.0),
}
# background compensation: the paper's kappa model or a temporal median of the first two revolutions (card 8.5)
COMPENSATION_MODELS = {"kappa": "kappa", "temporal median": "median"}
# what SIR means for the law-following decoy of C003-12: the brightness a stationary interferer keeps after
# compensation (the paper's SIR, l. 198, read for the decoy: equal brightness at the tracker), or the brightness it
# emits (equal emitters: compensation cannot remove a moving decoy, so it reaches the tracker 1/kappa brighter)
DECOY_BRIGHTNESS = ("residual", "emitted")
# C003-9: the quadrant slope read over +-D/2 (the card) or at small errors +-D/8, +-D/4 (the slope at zero error)
SLOPE_RANGES = {"+-D/2": "fit_slope_halfD", "small errors": "slope_at_zero"}
# "bandwidth" read as the -3 dB bandwidth (design) or as the noise-equivalent bandwidth: factors on the -3 dB design
# of the xy, r (first order: B_n = K/4 -> K = 4 B_n) and omega loops (2nd order, zeta 0.707: B_n = 0.53 w_n)
BANDWIDTH_READINGS = {"-3 dB": (1.0, 1.0, 1.0), "noise-equivalent": (2 / np.pi, 2 / np.pi, 0.617)}
# Fig. 2 laws (omega depth, omega Hz, r depth, r Hz): the card's, and rates inside the stated loop bandwidths
FIG2_LAWS = {"card": (0.1, 0.5, 0.15, 0.05), "omega 2 Hz": (0.1, 2.0, 0.15, 0.05), "r 0.2 Hz": (0.1, 0.5, 0.25, 0.2)}


@dataclass(frozen=True)
class Sizes:
    """Sizes of one measurement (one full-size replicate).

    Attributes
    ----------
    trials : int
        Runs per curve point (interference) and per tracking case.
    fig1_s, fig2_s : float
        Run lengths of the Fig. 1 and Fig. 2 configurations (s).
    transient_s : float
        Transient excluded from steady-state statistics (s).
    rotation_hz : float
        Marker rotation rate (rev/s; the paper's 8).
    horizon_s : float
        Run length T of the interference runs (s); the register's ``horizon`` entry doubles it.
    """

    trials: int = 5
    fig1_s: float = 5.0
    fig2_s: float = 12.0
    transient_s: float = 2.0
    rotation_hz: float = 8.0
    horizon_s: float = 5.0


def scenario(config: dict, sizes: Sizes = Sizes(), **over) -> Scenario:
    """The :class:`Scenario` of a register configuration (entries absent from ``config`` keep their defaults).

    Keys read: ``motion``, ``motion_scale``, ``rotation_rate``, ``phase_loop``, ``residual_background``,
    ``noise``, ``fps``, ``spot``, ``exposure``, ``compensation``, ``interferer_radius``, ``placement``, ``horizon``, ``edge_norm``,
    ``decoy_brightness``.
    """
    c = config
    base = Scenario()
    scale = float(c.get("motion_scale", 1.0))
    kappa = base.kappa
    radius = c.get("interferer_radius", "r0")
    om_depth, om_hz = ROTATION_LAWS[c.get("rotation_rate", "constant")]
    bw = BANDWIDTH_READINGS[c.get("bandwidth_reading", "-3 dB")]
    kw = dict(
        motion=c.get("motion", "card"),
        x_std=base.x_std * scale,
        y_amplitude=base.y_amplitude * scale,
        y_freq=float(c.get("sinusoid_hz", base.y_freq)),
        omega_mod=om_depth,
        omega_mod_hz=om_hz,
        b_xy=base.b_xy * bw[0],
        b_r=base.b_r * bw[1],
        b_omega=base.b_omega * bw[2],
        realise_phase_bandwidth=c.get("phase_loop", "designed") == "realised",
        background_std=1.0 / (kappa * float(c.get("residual_background", 50.0))),
        noise_std=float(c.get("noise", base.noise_std)),
        fps=float(c.get("fps", base.fps)),
        spot=c.get("spot", base.spot),
        exposure=c.get("exposure", base.exposure),
        compensation=COMPENSATION_MODELS[c.get("compensation", "kappa")],
        duration_s=sizes.horizon_s * (2.0 if c.get("horizon", "T") == "2T" else 1.0),
        interferer_radius_offset=RADIUS_OFFSETS[radius] * base.diameter if radius in RADIUS_OFFSETS else 0.0,
        interferer_jitter=base.diameter / 2 if radius == "jitter D/2" else 0.0,
        interferer_centre=c.get("placement", "object"),
        edge_norm=c.get("edge_norm", "slope"),
        interferer_diameter={"D": None, "2D": 2 * base.diameter}[c.get("interferer_size", "D")],
        decoy_gain={"residual": 1.0, "emitted": 1.0 / kappa}[c.get("decoy_brightness", DECOY_BRIGHTNESS[0])],
        rotation_hz=sizes.rotation_hz,
    )
    kw.update(over)
    return Scenario(**kw)


def criterion(config: dict, sc: Scenario) -> LossCriterion:
    """The loss criterion of a configuration: ``loss_window_s`` (s) and ``loss_radius`` ("gate half-size" or
    "D/2"), the share of the window off the marker fixed at one half."""
    radius = sc.gate_half if config.get("loss_radius", "gate half-size") == "gate half-size" else sc.diameter / 2
    return LossCriterion(radius, max(1, int(round(float(config.get("loss_window_s", 0.5)) * sc.fps))), 0.5)


def _estimate(value, lo, hi, n, method, extrapolated=False) -> Estimate:
    return Estimate(float(value), float("nan"), float(lo), float(hi), int(n), 0.95, method, bool(extrapolated))


def loss_share(events) -> Estimate:
    """Share of runs with the event (loss, capture), from the direct count.

    ``k`` of ``n`` with the exact Clopper-Pearson 95 % interval; zero events give ``[0, b]`` with ``b`` the
    one-sided bound they certify (:func:`tvtrack.montecarlo.zero_events_bound`), and ``n`` events ``[1 - b, 1]``.

    Parameters
    ----------
    events : array_like of bool, shape (n,)
    """
    e = np.asarray(events, bool).ravel()
    n, k = e.size, int(e.sum())
    if k == 0:
        return _estimate(0.0, 0.0, zero_events_bound(n), n, "count: zero events, one-sided 95 % bound")
    if k == n:
        return _estimate(1.0, 1 - zero_events_bound(n), 1.0, n, "count: all events, one-sided 95 % bound")
    return proportion_ci(k, n)


def log_thresholds(lost, sirs) -> tuple[np.ndarray, np.ndarray]:
    """Per-run log breaking SIR from the losses on a SIR grid (the same runs at every SIR).

    A run that lost lock at the grid SIRs below ``s_k`` and kept it from ``s_k`` on broke between ``s_{k-1}`` and
    ``s_k``; its log threshold is the midpoint ``(ln s_{k-1} + ln s_k) / 2``. A non-monotone run counts its losses:
    ``ln s_0 + sum_i lost_i (ln s_{i+1} - ln s_i)`` is the upper end, minus half the step below it.

    Parameters
    ----------
    lost : array_like of bool, shape (m, n)
        Loss of lock at each of ``m`` grid SIRs (increasing) for ``n`` runs.
    sirs : array_like, shape (m,)

    Returns
    -------
    tau : ndarray, shape (n,)
        Log thresholds.
    censored : ndarray of bool, shape (n,)
        Runs that broke outside the grid (lost at its top, or kept lock at its bottom).
    """
    L = np.asarray(lost, bool)
    ls = np.log(np.asarray(sirs, float))
    steps = np.diff(ls)
    k = L[:-1].sum(axis=0)  # grid steps climbed (index of the first kept SIR)
    upper = ls[0] + (L[:-1] * steps[:, None]).sum(axis=0)
    below = np.where(k > 0, steps[np.maximum(k - 1, 0)], steps[0])
    tau = upper - below / 2
    censored = L[-1] | ~L[0]
    return tau, censored


def _half_step(sirs) -> float:
    return float(np.max(np.diff(np.log(np.asarray(sirs, float)))) / 2)


def threshold(lost, sirs) -> Estimate:
    """Geometric-mean breaking SIR of the runs, from :func:`log_thresholds`.

    ``exp(mean tau)`` with the Student-t 95 % interval of the mean widened by half the largest grid step on each
    side (each run's threshold is known only to within its grid step); ``extrapolated`` when any run broke outside
    the grid (the mean would then rest on a guess).
    """
    tau, cens = log_thresholds(lost, sirs)
    h = _half_step(sirs)
    m = mean_ci(tau)
    return _estimate(
        np.exp(m.value),
        np.exp(m.ci_low - h),
        np.exp(m.ci_high + h),
        tau.size,
        "geometric mean of per-run breaking SIRs (grid-censored), t interval + half a grid step",
        extrapolated=bool(cens.any()),
    )


def threshold_bound(lost, sirs) -> Estimate:
    """The side of the paper's value a threshold certifies, from the same runs as :func:`threshold`.

    :func:`threshold` is ``extrapolated`` (undecided) as soon as one run broke outside the grid; but a run that kept
    lock at the grid's bottom broke below it, and one that lost lock at its top broke above it, so censoring on one
    side still bounds the geometric mean on the other: with runs censored below, ``[0, exp(upper t bound of the
    mean with those runs at the bottom + h)]``; censored above, ``[exp(lower t bound with those runs at the top - h),
    inf]`` (``h`` half the largest grid step, as in :func:`threshold`). Without censoring it equals
    :func:`threshold`; censored on both sides it stays ``extrapolated``. The value is :func:`threshold`'s.
    """
    L = np.asarray(lost, bool)
    ls = np.log(np.asarray(sirs, float))
    tau, _ = log_thresholds(L, sirs)
    point = threshold(L, sirs)
    low_c, high_c = ~L[0], L[-1]  # kept lock at the bottom (broke below) / lost at the top (broke above)
    if not (low_c.any() or high_c.any()):
        return point
    h = _half_step(sirs)
    lo = 0.0 if low_c.any() else float(np.exp(mean_ci(np.where(high_c, ls[-1], tau)).ci_low - h))
    hi = float("inf") if high_c.any() else float(np.exp(mean_ci(np.where(low_c, ls[0], tau)).ci_high + h))
    return _estimate(
        point.value,
        lo,
        hi,
        tau.size,
        f"bound certified by the censoring: {int(low_c.sum())} run(s) broke below the grid, "
        f"{int(high_c.sum())} above it; t bound + half a grid step",
        extrapolated=bool(low_c.any() and high_c.any()),
    )


def threshold_ratio(lost_a, lost_b, sirs) -> Estimate:
    """Ratio of the geometric-mean thresholds of two curves run on the same draws (paired per run).

    ``exp(mean(tau_a - tau_b))`` with the paired t interval widened by half the largest grid step;
    ``extrapolated`` when a run of either curve broke outside the grid -- except where the censoring certifies a
    bound: when the runs of ``a`` broke outside the grid only below it and those of ``b`` only above it, each
    censored run's log threshold is at most (``a``) or at least (``b``) the grid's edge, so the ratio is bounded
    above: ``[0, exp(upper t bound of mean(ub_a - lb_b) + h)]`` (value: the bound's point), like the zero-events
    bound of a share.
    """
    La, Lb = np.asarray(lost_a, bool), np.asarray(lost_b, bool)
    ta, ca = log_thresholds(La, sirs)
    tb, cb = log_thresholds(Lb, sirs)
    h = _half_step(sirs)
    steps = np.diff(np.log(np.asarray(sirs, float)))
    if (ca.any() or cb.any()) and not La[-1].any() and Lb[0].all():
        ub = np.where(~La[0], ta + steps[0] / 2, ta)  # a: kept lock at the bottom, threshold below it
        lb = np.where(Lb[-1], tb + steps[-1] / 2, tb)  # b: lost at the top, threshold above it
        m = mean_ci(ub - lb)
        return _estimate(
            np.exp(m.value),
            0.0,
            np.exp(m.ci_high + h),
            ta.size,
            f"upper bound: {int((~La[0]).sum())} run(s) of the first curve kept lock at the grid's bottom, "
            f"{int(Lb[-1].sum())} of the second lost it at its top; paired t bound + half a grid step",
        )
    m = mean_ci(ta - tb)
    return _estimate(
        np.exp(m.value),
        np.exp(m.ci_low - h),
        np.exp(m.ci_high + h),
        ta.size,
        "paired ratio of geometric-mean thresholds, t interval + half a grid step",
        extrapolated=bool(ca.any() or cb.any()),
    )


def extend_grid(
    curves: dict, sirs, run, step: float = 1.5, max_points: int = 2, trigger=None
) -> tuple[np.ndarray, dict]:
    """Adaptive grid points for thresholds that would break outside the grid (C003-12 was undecided for them).

    While some run of some curve kept lock at the grid's bottom (or lost it at its top), the curves with such runs
    are run at one more SIR, the bottom over ``step`` (the top times ``step``), up to ``max_points`` on each side.
    A curve not run there is filled by monotonicity, exactly where it is known: every one of its runs lost lock at
    the old bottom, so it loses below it (kept lock at the old top, so it keeps it above). With the same draws at
    every SIR (common random numbers) the extended curves stay paired run by run. With ``trigger`` (keys), a side is
    extended only while one of those curves needs it (the others' censoring may certify a bound instead, see
    :func:`threshold_ratio`).

    Parameters
    ----------
    curves : dict of key -> ndarray of bool, shape (m, n)
        Loss indicators on ``sirs``.
    sirs : array_like, shape (m,)
    run : callable
        ``run(keys, sir) -> {key: ndarray of bool, shape (n,)}``: the named curves' runs at one more SIR.

    Returns
    -------
    sirs : ndarray, shape (m',)
    curves : dict of key -> ndarray of bool, shape (m', n)
    """
    s = list(np.asarray(sirs, float))
    out = {k: np.asarray(v, bool) for k, v in curves.items()}
    for side in ("low", "high"):
        for _ in range(max_points):
            edge = 0 if side == "low" else -1
            need = [k for k, v in out.items() if (~v[edge] if side == "low" else v[edge]).any()]
            if not need or (trigger is not None and not set(need) & set(trigger)):
                break
            sir = s[0] / step if side == "low" else s[-1] * step
            new = run(need, sir)
            for k, v in out.items():
                row = np.asarray(new[k], bool) if k in new else np.full(v.shape[1], side == "low")
                out[k] = np.vstack([row[None], v]) if side == "low" else np.vstack([v, row[None]])
            s = [sir] + s if side == "low" else s + [sir]
    return np.asarray(s), out


def _rng(stream: int, seed: int) -> np.random.Generator:
    return np.random.default_rng([int(stream), int(seed)])


# ----------------------------------------------------------------------------------------------------------------
# tracking claims


def _miss_stats(h, k0: int, crit: LossCriterion) -> tuple[np.ndarray, np.ndarray]:
    ms = np.mean(h.miss[:, k0:].astype(float) ** 2, axis=1)
    return ms, first_loss(h.miss, crit, h.inside) >= 0


def measure_tracking(config: dict, seed: int, sizes: Sizes = Sizes()) -> dict:
    """One replicate of the tracking claims at ``config``.

    Returns
    -------
    dict
        ``{"C003-1": {"x_r", "y_r", "lost"}, "C003-2": {"far", "near", "wide_loops"}, "C003-3": {"omega", "r"},
        (``far``, ``near``: rotation-locked amplitude of the x_r error over the amplitude locked to a control phase at
        1.5 f_rot and at f_rot + 1 Hz; ``wide_loops``: the near ratio at each bandwidth of :data:`BXY_GRID`)
        "C003-4": {"spread", "compensation"}, "C003-9": {"square_linear", "disc_linear", "edge_square",
        "edge_disc"}}``; Estimates (``wide_loops`` a list over :data:`BXY_GRID`, the slopes exact numbers), and
        ``"_figure"`` with arrays of the first run for the notebook's figures.
    """
    n = sizes.trials
    sc1 = scenario(config, sizes, duration_s=sizes.fig1_s)
    k0 = int(round(sizes.transient_s * sc1.fps))
    crit = criterion(config, sc1)
    out, fig = {}, {}
    # Fig. 1 at every coordinate-loop bandwidth of the C003-2 mechanism, one batch on the same draws (stream 1)
    grid = tuple(b * sc1.b_xy / Scenario().b_xy for b in BXY_GRID)  # the grid follows the bandwidth reading
    gains = [replace(sc1, b_xy=b).gains() for b in grid]
    tr, _, h = run_scenario([_rng(1, seed) for _ in grid], n * len(grid), sc1, gains=stack_gains(gains, n), n_common=n)
    e = state_errors(tr, h)
    ex, th = e[:, k0:, 0], tr.theta[:, k0:]
    f_near = (sc1.rotation_hz + 1.0) / sc1.rotation_hz
    locked = phase_locked_amplitude(ex, th).reshape(len(BXY_GRID), n)
    near_ctl = phase_locked_amplitude(ex, f_near * th).reshape(len(BXY_GRID), n)
    j = BXY_GRID.index(Scenario().b_xy)  # was: "if sc1.b_xy in BXY_GRID else 0", which silently judged C003-1 at 2 Hz
    sel = slice(j * n, (j + 1) * n)
    out["C003-1"] = {
        "x_r": rms_ci(e[sel, k0:, 0]),
        "y_r": rms_ci(e[sel, k0:, 1]),
        "lost": loss_share(first_loss(h.miss[sel], crit, h.inside[sel]) >= 0),
    }
    out["C003-2"] = {
        "far": ratio_ci(locked[j], phase_locked_amplitude(ex[sel], 1.5 * th[sel])),
        "near": ratio_ci(locked[j], near_ctl[j]),
        "wide_loops": [ratio_ci(a, c) for a, c in zip(locked, near_ctl)],
    }
    # the locked ripple's own trend with the loop width, paired on the same draws: B_xy 10 Hz over 2 Hz
    out["_ripple_trend"] = ratio_ci(locked[j], locked[BXY_GRID.index(2.0)])
    quad_ms = {"disc" if sc1.spot == "disc" else "square": np.mean(h.miss[sel, k0:].astype(float) ** 2, axis=1)}
    fig.update(
        t=tr.t,
        xr=tr.xr[j * n],
        yr=tr.yr[j * n],
        est=h.estimate[j * n, :, :2],
        err=e[j * n, :, :2],
        locked=locked.mean(axis=1),
    )
    # Fig. 2: varying rotation rate and radius
    om, om_hz, rm, rm_hz = FIG2_LAWS[config.get("fig2_law", "card")]
    sc2 = replace(sc1, duration_s=sizes.fig2_s, omega_mod=om, omega_mod_hz=om_hz, radius_mod=rm, radius_mod_hz=rm_hz)
    tr, _, h = run_scenario(_rng(2, seed), n, sc2)
    k2 = int(round(max(sizes.transient_s, 0.25 * sizes.fig2_s) * sc2.fps))
    e = state_errors(tr, h)[:, k2:]
    out["C003-3"] = {"omega": rms_ci(e[:, :, 4] / sc2.omega0), "r": rms_ci(e[:, :, 2])}
    fig.update(t2=tr.t, omega=tr.omega[0], omega_hat=h.estimate[0, :, 4], r=tr.r[0], r_hat=h.estimate[0, :, 2])
    # C003-4: background sweep (compensated) and the ablation without compensation, one batch on the same draws
    cases = ((50.0, 8.0), (100.0, 8.0), (50.0, 4.0), (50.0, 16.0))
    blocks = [dict(kappa=sc1.kappa, background_std=1.0 / (sc1.kappa * r), corr_length=c) for r, c in cases]
    blocks.append(dict(kappa=1.0, background_std=1.0 / 5.0, corr_length=8.0))
    h = run_scenario([_rng(3, seed) for _ in blocks], n * len(blocks), sc1, keep_full=False, n_common=n, blocks=blocks)[
        2
    ]
    ms, lo = _miss_stats(h, k0, crit)
    ms, lo = ms.reshape(len(blocks), n), lo.reshape(len(blocks), n)
    rms = [mean_ci(np.sqrt(m)) for m in ms[:-1]]
    lost = {"compensated": lo[0], "none": lo[-1]}
    hi, lo = max(rms, key=lambda x: x.value), min(rms, key=lambda x: x.value)
    spread = _estimate(
        hi.value / lo.value,
        max(hi.ci_low / lo.ci_high, 0.0),
        hi.ci_high / max(lo.ci_low, 1e-12),
        hi.n,
        "max/min of per-case RMS miss; interval from the per-case 95 % bounds (conservative)",
    )
    out["C003-4"] = {"spread": spread, "compensation": _share_difference(lost["none"], lost["compensated"])}
    fig["background_rms"] = [r.value for r in rms]
    # C003-9: static slopes (deterministic) and edge vs quadrant in closed loop on the Fig. 1 draws (stream 1)
    part9 = {}
    for spot in ("square", "disc"):
        s = replace(sc1, spot=spot)
        fit = quadrant_slope_fit(s.spot_renderer(), s.diameter, s.gate_half)
        part9[f"{spot}_linear"] = fit[SLOPE_RANGES[config.get("slope_range", "+-D/2")]] / s.slope()
        if spot not in quad_ms:
            quad_ms[spot] = _miss_stats(run_scenario(_rng(1, seed), n, s, keep_full=False)[2], k0, crit)[0]
        edge = _miss_stats(run_scenario(_rng(1, seed), n, replace(s, form="edge"), keep_full=False)[2], k0, crit)[0]
        part9[f"edge_{spot}"] = ratio_ci(edge, quad_ms[spot])
    out["C003-9"] = part9
    out["_figure"] = fig
    return out


def _share_difference(a, b) -> Estimate:
    """Paired difference of two loss shares on the same runs (Student t on per-run differences; all-equal runs:
    the zero-events bound on discordant runs)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = a - b
    if np.all(d == d[0]):
        bnd = zero_events_bound(d.size)
        return _estimate(
            d[0],
            d[0] - bnd if d[0] <= 0 else 1 - bnd,
            min(d[0] + bnd, 1.0) if d[0] < 1 else 1.0,
            d.size,
            "no discordant runs: one-sided 95 % bound",
        )
    m = mean_ci(d)
    return _estimate(m.value, max(m.ci_low, -1.0), min(m.ci_high, 1.0), d.size, "paired t on per-run differences")


# ----------------------------------------------------------------------------------------------------------------
# interference claims


def _curve(sc: Scenario, sirs, n: int, seed: int, crit: LossCriterion, counts=None, criteria: bool = False):
    """Loss indicators of ``n`` runs at each SIR (stream 10: common draws), shape (m, n); with ``counts``
    (interferer numbers) one batch of blocks, shape (len(counts), m, n). With ``criteria`` also the loss criteria
    each loss meets (:func:`.lock.loss_criteria`, capture judged off the marker), shape (..., m, n, 3)."""
    k = 1 if counts is None else len(counts)
    blocks = None if counts is None else [{"n_interferers": c} for c in counts]
    runs = interference_runs([_rng(10, seed) for _ in range(k)], n, sc, sirs, blocks=blocks)
    fl = first_loss(runs["miss"], crit, runs["inside"])
    shape = (len(sirs), n) if counts is None else (k, len(sirs), n)
    lost = (fl >= 0).reshape(shape)
    if not criteria:
        return lost, None
    met = loss_criteria(
        fl,
        runs["gate"],
        runs["interferers"],
        runs["miss"],
        runs["omega_error"],
        crit.window,
        sc.diameter / 2 + 0.5,
        crit.fraction,
    )
    return lost, met.reshape(shape + (3,))


def measure_interference(config: dict, seed: int, sizes: Sizes = Sizes()) -> dict:
    """One replicate of the loss-of-lock claims at ``config`` (all curves on :data:`SIR_GRID`, same draws).

    The thresholds of C003-7's ``rise``, C003-12 and ``_map`` read the rotating, static and decoy curves on the grid
    extended where a run broke outside it (:func:`extend_grid`, up to two points on each side; ``"_grid"``).

    Returns
    -------
    dict
        ``{"C003-5": {"no_loss", "no_capture"}, "C003-6": {"finite", "loss_free", "not_lower"},
        "C003-7": {"loss_free", "not_lower", "rise"}, "C003-10": {"gate", "compensation"},
        "C003-11": {"dynamics", "selection", "bandwidth"} (mean-square miss without interferers,
        B_xy 20 Hz over 5 Hz), "C003-12": {"one", "five", "imitator"}}``, ``"_map"`` (the thresholds of the
        rotating and static markers with one and five interferers), ``"_map_bound"`` (the same thresholds as the
        bounds their grid censoring certifies, :func:`threshold_bound`), ``"_mechanisms"`` (counts of the losses meeting
        each loss criterion) and ``"_curves"`` (the loss indicators).
    """
    n, sirs = sizes.trials, np.asarray(SIR_GRID)
    at = {s: i for i, s in enumerate(SIR_GRID)}
    base = scenario(config, sizes)
    D = base.diameter
    crit = criterion(config, base)
    static_half = {"3D": 1.5 * D, "2D": D}[config.get("static_gate", "3D")]
    curves = {}
    (curves["rotating", 1], curves["rotating", 5]), met_r = _curve(base, sirs, n, seed, crit, (1, 5), True)
    st = replace(base, rotating=False, gate_half=static_half, form=config.get("static_form", "quadrant"))
    (curves["static", 1], curves["static", 5]), met_s = _curve(st, sirs, n, seed, criterion(config, st), (1, 5), True)
    capt = met_r[1, :, :, 0]
    for gf in (1.5, 5.0):
        g = replace(base, n_interferers=5, gate_half=gf * D / 2)
        curves["gate", gf], _ = _curve(g, sirs, n, seed, criterion(config, g))
    curves["decoy"], _ = _curve(replace(base, decoy_offset=2 * D), sirs, n, seed, crit)
    usirs = np.asarray(UNCOMPENSATED_GRID)
    curves["uncompensated"], _ = _curve(replace(base, n_interferers=5, kappa=1.0), usirs, n, seed, crit)
    k0 = int(round(sizes.transient_s * base.fps))
    bw = (5.0, 20.0)
    h = run_scenario(
        [_rng(1, seed) for _ in bw],
        2 * n,
        base,
        keep_full=False,
        n_common=n,
        gains=stack_gains([replace(base, b_xy=b).gains() for b in bw], n),
    )[2]
    ms = np.mean(h.miss[:, k0:].astype(float) ** 2, axis=1).reshape(2, n)
    bw_ratio = ratio_ci(ms[1], ms[0])  # B_xy 20 Hz over 5 Hz, with its direction (kept in "_bandwidth_ratio")
    r1, r5 = curves["rotating", 1], curves["rotating", 5]

    def more(keys, sir):  # the C003-7/-12 curves at one more SIR, only the families asked for (same draws)
        got = {}
        for fam, sc_f in (("rotating", base), ("static", st)):
            if any(k[0] == fam for k in keys):
                lost, _ = _curve(sc_f, [sir], n, seed, criterion(config, sc_f), (1, 5))
                got[fam, 1], got[fam, 5] = lost[0, 0], lost[1, 0]
        if "decoy" in keys:
            got["decoy"] = _curve(replace(base, decoy_offset=2 * D), [sir], n, seed, crit)[0][0]
        return got

    pair_keys = [("rotating", 1), ("rotating", 5), ("static", 1), ("static", 5), "decoy"]
    # one adaptive point a side, and only when the rotating marker's own runs break outside the grid: the static
    # marker's and the decoy's breaking below it certify an upper bound on C003-12's ratios (threshold_ratio)
    xsirs, xc = extend_grid({k: curves[k] for k in pair_keys}, sirs, more, max_points=1, trigger=pair_keys[:2])
    comp_ratio = _compensation_factor(curves["uncompensated"], usirs, r5, sirs, base.kappa)
    out = {
        "C003-5": {"no_loss": loss_share(r5[at[3.0]]), "no_capture": loss_share(capt[at[3.0]])},
        "C003-6": {
            "finite": loss_share(r1[at[0.5]]),
            "loss_free": loss_share(r1[at[2.0]]),
            "not_lower": loss_share(r1[at[4 / 3]]),
        },
        "C003-7": {
            "loss_free": loss_share(r5[at[3.0]]),
            "not_lower": loss_share(r5[at[2.0]]),
            "rise": threshold_ratio(xc["rotating", 5], xc["rotating", 1], xsirs),
        },
        "C003-10": {
            # the side a grid-censored threshold certifies decides (threshold_bound), as in the prose's map
            "gate": [
                threshold_bound(curves["gate", 1.5], sirs),
                threshold_bound(r5, sirs),
                threshold_bound(curves["gate", 5.0], sirs),
            ],
            "compensation": compensation_reading(
                comp_ratio,
                base.kappa,
                config.get("compensation_reading", "one-sided"),
            ),
        },
        "C003-11": {
            "dynamics": loss_share(curves["gate", 1.5][-1]),
            "selection": threshold_ratio(curves["gate", 5.0], r5, sirs),
            # l. 192 says the errors depend substantially on the bandwidths, not which way: two-sided (fold distance)
            "bandwidth": fold_distance(bw_ratio, 1.0),
        },
        "C003-12": {
            "one": threshold_ratio(xc["static", 1], xc["rotating", 1], xsirs),
            "five": threshold_ratio(xc["static", 5], xc["rotating", 5], xsirs),
            "imitator": threshold_ratio(xc["decoy"], xc["rotating", 1], xsirs),
        },
    }
    out["_bandwidth_ratio"] = bw_ratio
    out["_mechanisms"] = {
        f"{m} {k}": _mechanisms(curves[m, k], met[j])
        for m, met in (("rotating", met_r), ("static", met_s))
        for j, k in enumerate((1, 5))
    }
    out["_map"] = {f"{m} {k}": threshold(xc[m, k], xsirs) for m in ("rotating", "static") for k in (1, 5)}
    # the side of a paper value each _map threshold certifies, also when runs broke outside the grid (prose)
    out["_map_bound"] = {f"{m} {k}": threshold_bound(xc[m, k], xsirs) for m in ("rotating", "static") for k in (1, 5)}
    out["_grid"] = [
        float(x) for x in xsirs
    ]  # the SIR grid with its adaptive points (the thresholds of _map, C003-7 rise, C003-12)
    out["_curves"] = {("/".join(map(str, k)) if isinstance(k, tuple) else k): v for k, v in curves.items()}
    return out


def _mechanisms(lost, met) -> dict:
    """Counts of the losses (all SIRs) and of those meeting each loss criterion (a loss may meet several)."""
    lost = np.asarray(lost, bool)
    m = np.asarray(met, bool)[lost]
    return {
        "losses": int(lost.sum()),
        **{c: int(m[:, j].sum()) for j, c in enumerate(CRITERIA)},
        "none (drift)": int((~m.any(axis=1)).sum()),
    }


COMPENSATION_READINGS = ("one-sided", "two-sided")


def compensation_reading(ratio: Estimate, kappa: float, reading: str) -> Estimate:
    """C003-10's compensation ratio as its reading judges it (the rule: at most ``2 kappa``, i.e. compensation lowers
    the SIR_0 threshold at least about 1/kappa-fold, within the rule's factor 2).

    The paper (l. 198): "Если использование процедуры компенсации фоновых излучений эквивалентно уменьшению яркости
    фона на порядок, то пороговое отношение сигнал/помеха, имевшее место до компенсации фона и гарантирующее отсутствие
    срывов слежения, ... уменьшается до 0,2-0,3" ("if compensation is equivalent to reducing the background by an
    order of magnitude, the no-loss threshold SIR before compensation ... decreases to 0.2-0.3"), and l. 208 names
    compensation one of the main factors of the robustness. The order of magnitude is a hypothesis, not a measured
    ratio: "one-sided" (the paper's reading, the default) keeps the ratio as measured, and a ratio below ``kappa``
    (the uncompensated tracker fails even harder) meets the rule. "two-sided" (the card's "about 1/kappa-fold")
    judges the ratio's fold distance from ``kappa``: ``kappa exp|log(q / kappa)|`` (``q`` itself for ``q >= kappa``,
    ``kappa^2 / q`` below it), at most ``2 kappa`` exactly when ``q`` lies within a factor 2 of ``kappa``; an
    interval straddling ``kappa`` starts at ``kappa``.

    Parameters
    ----------
    ratio : Estimate
        Compensated over uncompensated SIR_0 threshold (:func:`_compensation_factor`).
    kappa : float
        Compensation residual.
    reading : {"one-sided", "two-sided"}
    """
    if reading not in COMPENSATION_READINGS:
        raise ValueError(f"parameter 'reading' = {reading!r}; it must be one of {COMPENSATION_READINGS}")
    if reading == "one-sided":
        return ratio
    return fold_distance(ratio, kappa)


def fold_distance(ratio: Estimate, reference: float) -> Estimate:
    """A ratio's fold distance from ``reference``, either direction: ``k exp|log(q / k)|`` (``q`` itself for
    ``q >= k``, ``k^2 / q`` below it), so a two-sided rule ("depends on", "about k") is one band on one number.

    The interval maps end by end; an interval straddling ``k`` starts at ``k`` (no measurable distance), and a
    bound ``[0, b]`` certifies a distance of at least ``fold(b)``.

    Parameters
    ----------
    ratio : Estimate
        A ratio (positive), with its 95 % interval.
    reference : float
        The ratio of no change (``1`` for C003-11's bandwidth part, ``kappa`` for C003-10's two-sided reading).
    """
    k = float(reference)

    def fold(q):
        return q if q >= k else (k * k / q if q > 0 else np.inf)

    lo, hi = ratio.ci_low, ratio.ci_high
    ends = sorted((fold(lo), fold(hi)))
    value = fold(ratio.value)
    return replace(
        ratio,
        value=value if np.isfinite(value) else ends[0],
        ci_low=k if lo < k < hi else ends[0],
        ci_high=ends[1],
        method=ratio.method + f"; fold distance from {k:g} either way, {k:g} exp|log(q / {k:g})|",
    )


def _compensation_factor(lost_unc, usirs, lost_comp, sirs, kappa: float) -> Estimate:
    """Compensated SIR_0 threshold (``kappa`` x its SIR threshold) over the uncompensated SIR_0 threshold: about
    ``kappa`` if compensation is worth its 1/kappa background reduction (C003-10), 0 if the raw background alone
    breaks lock.

    When a run without compensation lost lock at every grid SIR_0, its threshold lies above the grid: the ratio is
    then bounded above by the compensated threshold's upper bound over the grid's top (a direct-count bound,
    reported as ``[0, bound]``); a run that broke below the grid leaves the ratio undecided (extrapolated).
    """
    unc = np.asarray(lost_unc, bool)
    comp = threshold(lost_comp, sirs)
    if unc[-1].any():
        hi = kappa * comp.ci_high / float(usirs[-1])
        return _estimate(
            0.0,
            0.0,
            hi,
            unc.shape[1],
            f"{int(unc[-1].sum())} of {unc.shape[1]} uncompensated runs "
            f"lost even at SIR_0 {usirs[-1]:g}: bound from the grid's top",
            extrapolated=comp.extrapolated,
        )
    u = threshold(unc, usirs)
    return _estimate(
        kappa * comp.value / u.value,
        kappa * comp.ci_low / u.ci_high,
        kappa * comp.ci_high / u.ci_low,
        u.n,
        "ratio of thresholds, interval from their bounds",
        extrapolated=bool(u.extrapolated or comp.extrapolated),
    )


# ----------------------------------------------------------------------------------------------------------------
# beyond the paper: frame-rate smear, matched exposure of the static baseline, temporal-median compensation


def exposure_study(seed: int, sizes: Sizes, sizes_i: Sizes, fps: float) -> dict:
    """Frame-rate smear (card 8.5) and the static baseline at matched exposure, at frame rate ``fps``.

    Both exposure models on the same draws: ``"instant"`` (the marker sampled at the frame time) and ``"integrated"``
    (the sensor integrates over the frame, so the rotating marker is smeared along the arc ``2 pi f_rot r / fps`` it
    turns in a frame, while the static baseline's emitter, held still, keeps its spot: the same spot energy per frame,
    sensor noise and exposure model for both markers, i.e. matched exposure).

    Returns
    -------
    dict
        ``{exposure: {"x_r_rms_px": Estimate (Fig. 1 RMS x_r error, px), "thresholds": {"rotating 1", "rotating 5",
        "static 1", "static 5"}: Estimate (the bound each threshold's grid censoring certifies, SIR)}}`` and
        ``"arc_px"``: the marker's arc per frame (px).
    """
    out = {}
    for e in ("instant", "integrated"):
        cfg = {"fps": float(fps), "exposure": e}
        out[e] = {
            "x_r_rms_px": measure_tracking(cfg, seed, sizes)["C003-1"]["x_r"],
            "thresholds": measure_interference(cfg, seed, sizes_i)["_map_bound"],
        }
    sc = scenario({"fps": float(fps)}, sizes)
    out["arc_px"] = float(sc.omega0 * sc.radius / sc.fps)
    return out


def median_example(seed: int, sc: Scenario) -> dict:
    """One trial of the temporal-median compensation (card 8.5) for :func:`.plots.median_figure`: the truth, the
    interferers about its start and the residual the median of the first ``sc.median_revolutions`` revolutions leaves
    (:func:`.scene.median_residual`; the static scene cancels, so the interferers leave nothing).

    Returns
    -------
    dict
        ``residual`` (rows, cols), ``truth`` (one trial), ``interferers`` (count, 2) px, ``n_frames``, ``noise_std``.
    """
    rng = _rng(50, seed)
    n_frames = int(np.ceil(sc.median_revolutions * sc.fps / sc.rotation_hz))
    truth = scenario_truth(rng, 1, replace(sc, duration_s=max(sc.duration_s, (n_frames + 1) / sc.fps)))
    q = place_interferers(rng, 1, sc.n_interferers, truth.center[:, 0], sc.radius)
    shape = (sc.image_size, sc.image_size)
    res = median_residual(rng, truth, n_frames, shape, sc.spot, sc.diameter, sc.brightness, sc.noise_std)
    return dict(residual=res[0], truth=truth, interferers=q[0], n_frames=n_frames, noise_std=sc.noise_std)
