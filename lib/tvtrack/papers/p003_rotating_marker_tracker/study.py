"""Measurement functions of notebook 003 (what the explorer calls); the direct-count estimators they use live in
:mod:`.estimators`.

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
where it kept it), with a Student-t interval widened by half the grid step (a ratio of two thresholds on the same
runs by up to a whole step: half of each run's step in each curve), and it is flagged ``extrapolated`` (undecided) when a run breaks outside the grid.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...estimate import Estimate
from ...montecarlo import mean_ci, ratio_ci, rms_ci
from ...projection import as_declared
from .curves import SIR_GRID, UNCOMPENSATED_GRID, curve_part, interference_claims, loss_mechanisms
from .discriminators import quadrant_slope_fit
from .draws import stream_rng
from .lock import LossCriterion, first_loss
from .lockstep import run_together
from .loops import phase_locked_amplitude, stack_gains
from .memo import memo, memo_together, scenario_key
from .scene import Scenario, prepare_scenario, run_scenario, state_errors
from .estimators import (
    extend_grid,
    grid_in_lock,
    interval_estimate,
    loss_share,
    share_difference,
    threshold,
    threshold_bound,
)

__all__ = [
    "stream_rng",
    "SIR_GRID",
    "UNCOMPENSATED_GRID",
    "BXY_GRID",
    "LINEAR_BAND",
    "RIPPLE_TREND",
    "BANDWIDTH_PAIR",
    "Sizes",
    "scenario",
    "interference_scenario",
    "screen_sizes",
    "criterion",
    "loss_share",
    "threshold",
    "threshold_bound",
    "measure_tracking",
    "measure_interference",
]

LINEAR_BAND = (0.9, 1.1)  # C003-9: quadrant slope / 2dD counted "linear" (the rule and the s-curve caption)
BXY_GRID = (2.0, 5.0, 10.0, 20.0)  # coordinate-loop bandwidths of the C003-2 mechanism, Hz
RIPPLE_TREND = (20.0, 10.0)  # C003-2: the locked ripple at the widest B_xy over the paper's, runs in lock at both, Hz
BANDWIDTH_PAIR = (5.0, 20.0)  # C003-11: the coordinate-loop bandwidths whose mean-square misses are compared, Hz
RADIUS_OFFSETS = {"r0": 0.0, "r0 - D/2": -0.5, "r0 + D/2": 0.5}  # interferer radius, offsets in units of D
# rotation-rate laws (depth, Hz): "mean rotation frequency 8 rev/s" (l. 185) says omega varies; its law is unstated
ROTATION_LAWS = {
    "constant": (0.0, 0.5),
    "modulated": (0.1, 0.5),
    "modulated fast": (0.15, 1.0),
    "modulated strong": (0.2, 1.0),
}
# background compensation: the paper's kappa model or a temporal median of the first two revolutions (beyond the paper)
COMPENSATION_MODELS = {"kappa": "kappa", "temporal median": "median"}
# what SIR means for the law-following decoy of C003-12: the brightness a stationary interferer keeps after
# compensation (the paper's SIR, l. 198, read for the decoy: equal brightness at the tracker), or the brightness it
# emits (equal emitters: compensation cannot remove a moving decoy, so it reaches the tracker 1/kappa brighter)
DECOY_BRIGHTNESS = ("residual", "emitted")
# C003-9: the quadrant slope read over +-D/2 (this project's default) or at small errors +-D/8, +-D/4 (the slope at
# zero error)
SLOPE_RANGES = {"+-D/2": "fit_slope_halfD", "small errors": "slope_at_zero"}
# "bandwidth" read as the -3 dB bandwidth (design) or as the noise-equivalent bandwidth: factors on the -3 dB design
# of the xy, r (first order: B_n = K/4 -> K = 4 B_n) and omega loops (2nd order, zeta 0.707: B_n = 0.53 w_n)
BANDWIDTH_READINGS = {"-3 dB": (1.0, 1.0, 1.0), "noise-equivalent": (2 / np.pi, 2 / np.pi, 0.617)}
# Fig. 2 laws (omega depth, omega Hz, r depth, r Hz): this project's defaults, and rates inside the stated loop
# bandwidths
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


def screen_sizes(sizes: Sizes) -> Sizes:
    """The joint design's cheaper screen (:func:`tvtrack.explore.explore`'s ``screen``): half the runs (at least the
    5 at which the intervals' coverage is measured) and half the run lengths, the transient kept shorter than the
    Fig. 1 run. Measured at paper size: 0.50 of the interference and 0.62 of the tracking cost per joint configuration.
    """
    fig1 = max(sizes.fig1_s / 2, sizes.transient_s + 1.0)
    return replace(
        sizes,
        trials=max(5, sizes.trials // 2),
        fig1_s=fig1,
        fig2_s=max(sizes.fig2_s / 2, fig1),
        horizon_s=sizes.horizon_s / 2,
    )


def scenario(config: dict, sizes: Sizes = Sizes(), **over) -> Scenario:
    """The :class:`Scenario` of a register configuration (entries absent from ``config`` keep their defaults).

    Keys read: ``motion``, ``motion_scale``, ``rotation_rate``, ``phase_loop``, ``residual_background``,
    ``noise``, ``fps``, ``spot``, ``exposure``, ``compensation``, ``interferer_radius``, ``interferer_layout``, ``placement``, ``horizon``, ``edge_norm``,
    ``decoy_brightness`` (``interference_motion`` is read by :func:`interference_scenario`).
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
        interferer_layout=c.get("interferer_layout", "even"),
        edge_norm=c.get("edge_norm", "slope"),
        interferer_diameter={"D": None, "2D": 2 * base.diameter}[c.get("interferer_size", "D")],
        decoy_gain={"residual": 1.0, "emitted": 1.0 / kappa}[c.get("decoy_brightness", DECOY_BRIGHTNESS[0])],
        rotation_hz=sizes.rotation_hz,
    )
    kw.update(over)
    return Scenario(**kw)


def interference_scenario(config: dict, sizes: Sizes = Sizes(), **over) -> Scenario:
    """The :class:`Scenario` of the interference runs: :func:`scenario`, with the object held still where
    ``interference_motion`` is "hovering" (a reading of Fig. 3 that the Fig. 1 runs, whose object moves, never
    read)."""
    if config.get("interference_motion", "moving") == "hovering":
        over = {"x_std": 0.0, "y_amplitude": 0.0, **over}
    return scenario(config, sizes, **over)


def criterion(config: dict, sc: Scenario) -> LossCriterion:
    """The loss criterion of a configuration: ``loss_window_s`` (s) and ``loss_radius`` ("gate half-size" or
    "D/2"), the share of the window off the marker fixed at one half."""
    radius = sc.gate_half if config.get("loss_radius", "gate half-size") == "gate half-size" else sc.diameter / 2
    return LossCriterion(radius, max(1, int(round(float(config.get("loss_window_s", 0.5)) * sc.fps))), 0.5)


# ----------------------------------------------------------------------------------------------------------------
# tracking claims


def _miss_stats(h, k0: int, crit: LossCriterion) -> tuple[np.ndarray, np.ndarray]:
    ms = np.mean(h.miss[:, k0:].astype(float) ** 2, axis=1)
    return ms, first_loss(h.miss, crit, h.inside) >= 0


T_CLAIMS = ("C003-1", "C003-2", "C003-3", "C003-4", "C003-9")
I_CLAIMS = ("C003-5", "C003-6", "C003-7", "C003-10", "C003-11", "C003-12")


def _declared(args, kwargs):
    """``(DEPENDS, default)``: each claim is measured at its configuration projected onto its DEPENDS."""
    from .register import DEPENDS, REGISTER

    return DEPENDS, REGISTER.default()


def _asked(claims, ids) -> set:
    """The claims of ``ids`` a measurement computes: all with ``claims=None``, else those asked."""
    return set(ids) if claims is None else set(ids) & set(claims)


def measure_tracking(config: dict, seed: int, sizes: Sizes = Sizes(), claims=None) -> dict:
    """One replicate of the tracking claims at ``config``.

    ``claims`` (ids, None for all) names the claims to compute: the runs only other claims read are skipped (the
    Fig. 1 batch feeds C003-1, C003-2 and C003-9, the Fig. 2 runs C003-3, the background sweep C003-4, the edge runs
    C003-9); what is computed is the same, bit for bit, whatever else is asked. Parts whose inputs a configuration
    leaves as they were are taken from the run that computed them (:func:`.memo.memo`).

    Returns
    -------
    dict
        ``{"C003-1": {"x_r", "y_r", "lost"}, "C003-2": {"far", "near", "wide_loops"}, "C003-3": {"omega", "r"},
        (``far``, ``near``: rotation-locked amplitude of the x_r error over the amplitude locked to a control phase at
        1.5 f_rot and at f_rot + 1 Hz; ``wide_loops``: the near ratio at each bandwidth of :data:`BXY_GRID`)
        "C003-4": {"spread", "compensation"}, "C003-9": {"square_linear", "disc_linear", "edge_square",
        "edge_disc"}}``; Estimates (``wide_loops`` a list over :data:`BXY_GRID`, the slopes exact numbers), and
        ``"_figure"`` with arrays of the first run for the notebook's figures (its Fig. 1 and Fig. 2 parts where those
        runs were made), ``"_ripple_trend"`` with the Fig. 1 batch.
    """
    asked = _asked(claims, T_CLAIMS)
    n = sizes.trials
    sc1 = scenario(config, sizes, duration_s=sizes.fig1_s)
    k0 = int(round(sizes.transient_s * sc1.fps))
    crit = criterion(config, sc1)
    out, fig, quad_ms = {}, {}, {}
    om, om_hz, rm, rm_hz = FIG2_LAWS[config.get("fig2_law", "card")]
    sc2 = replace(sc1, duration_s=sizes.fig2_s, omega_mod=om, omega_mod_hz=om_hz, radius_mod=rm, radius_mod_hz=rm_hz)
    k2 = int(round(max(sizes.transient_s, 0.25 * sizes.fig2_s) * sc2.fps))
    runs = [_fig1_spec(sc1, n, seed, k0, crit)] if asked & {"C003-1", "C003-2", "C003-9"} else []
    runs += [_fig2_spec(sc2, n, seed, k2)] if "C003-3" in asked else []
    runs += [_background_spec(sc1, n, seed, k0, crit)] if "C003-4" in asked else []
    runs += [_miss_spec(s, n, seed, k0, crit) for s in _form_runs(sc1)] if "C003-9" in asked else []
    _together([_part(x) for x in runs])  # side by side in one frame loop where they can; the calls below find them
    if asked & {"C003-1", "C003-2", "C003-9"}:
        f1 = _kept(_fig1_spec(sc1, n, seed, k0, crit))
        out.update({k: f1[k] for k in ("C003-1", "C003-2", "_ripple_trend", "_lock_by_bandwidth")})
        quad_ms, fig = dict(f1["quad_ms"]), dict(f1["figure"])
    if "C003-3" in asked:  # Fig. 2: varying rotation rate and radius
        f2 = _kept(_fig2_spec(sc2, n, seed, k2))
        out["C003-3"] = f2["C003-3"]
        fig.update(f2["figure"])
    if "C003-4" in asked:  # background sweep (compensated) and the ablation without compensation, same draws
        out["C003-4"], fig["background_rms"] = _kept(_background_spec(sc1, n, seed, k0, crit))
    if "C003-9" in asked:
        out["C003-9"] = _discriminator_forms(config, sc1, n, seed, k0, crit, quad_ms)
    out["_figure"] = fig
    return {k: v for k, v in out.items() if k in asked or k.startswith("_")}


# as_declared applied here, not as a decorator: mutmut 3 mutates no decorated function (docs/mutation.md)
measure_tracking = as_declared(T_CLAIMS, _declared)(measure_tracking)


def _fig1(sc1: Scenario, n: int, seed: int, k0: int, crit: LossCriterion) -> dict:
    """Fig. 1 at every coordinate-loop bandwidth of the C003-2 mechanism, one batch on the same draws (stream 1):
    C003-1, C003-2, the locked ripple's trend, the quadrant runs' mean-square miss by spot (``quad_ms``, for C003-9)
    and the first run's arrays (``figure``)."""
    return _run(_fig1_spec(sc1, n, seed, k0, crit))


def _fig1_spec(sc1: Scenario, n: int, seed: int, k0: int, crit: LossCriterion) -> tuple:
    """:func:`_fig1` as ``(key, run_scenario's arguments, its keywords, finish(truth, history))``."""
    grid = tuple(b * sc1.b_xy / Scenario().b_xy for b in BXY_GRID)  # the grid follows the bandwidth reading
    gains = [replace(sc1, b_xy=b).gains() for b in grid]
    return (
        ("fig1", scenario_key(sc1), n, seed, k0, crit),
        ([stream_rng(1, seed) for _ in grid], n * len(grid), sc1),
        dict(gains=stack_gains(gains, n), n_common=n),
        lambda tr, h: _fig1_outcome(sc1, n, k0, crit, tr, h),
    )


def _fig1_outcome(sc1: Scenario, n: int, k0: int, crit: LossCriterion, tr, h) -> dict:
    e = state_errors(tr, h)
    ex, th = e[:, k0:, 0], tr.theta[:, k0:]
    f_near = (sc1.rotation_hz + 1.0) / sc1.rotation_hz
    locked = phase_locked_amplitude(ex, th).reshape(len(BXY_GRID), n)
    near_ctl = phase_locked_amplitude(ex, f_near * th).reshape(len(BXY_GRID), n)
    j = BXY_GRID.index(Scenario().b_xy)  # was: "if sc1.b_xy in BXY_GRID else 0", which silently judged C003-1 at 2 Hz
    sel = slice(j * n, (j + 1) * n)
    lost = (first_loss(h.miss, crit, h.inside) >= 0).reshape(len(BXY_GRID), n)
    wide = grid_in_lock(lost, locked, near_ctl, BXY_GRID, RIPPLE_TREND)  # the trend over the loops that keep lock
    return {
        "C003-1": {"x_r": rms_ci(e[sel, k0:, 0]), "y_r": rms_ci(e[sel, k0:, 1]), "lost": loss_share(lost[j])},
        "C003-2": {
            "far": ratio_ci(locked[j], phase_locked_amplitude(ex[sel], 1.5 * th[sel])),
            "near": ratio_ci(locked[j], near_ctl[j]),
            "wide_loops": wide["trend"],
        },
        # the locked ripple's own trend with the loop width, paired on the same draws in lock: 20 Hz over 10 Hz
        "_ripple_trend": wide["pair"],
        "_lock_by_bandwidth": wide["lost"],
        "quad_ms": {"disc" if sc1.spot == "disc" else "square": np.mean(h.miss[sel, k0:].astype(float) ** 2, axis=1)},
        "figure": dict(
            t=tr.t,
            xr=tr.xr[j * n].copy(),
            yr=tr.yr[j * n].copy(),
            est=h.estimate[j * n, :, :2].copy(),
            err=e[j * n, :, :2].copy(),
            locked=locked.mean(axis=1),
        ),
    }


def _fig2(sc2: Scenario, n: int, seed: int, k2: int) -> dict:
    """Fig. 2 (varying rotation rate and radius, stream 2): C003-3 and the first run's arrays (``figure``)."""
    return _run(_fig2_spec(sc2, n, seed, k2))


def _fig2_spec(sc2: Scenario, n: int, seed: int, k2: int) -> tuple:
    key = ("fig2", scenario_key(sc2), n, seed, k2)
    return key, (stream_rng(2, seed), n, sc2), {}, lambda tr, h: _fig2_outcome(sc2, k2, tr, h)


def _fig2_outcome(sc2: Scenario, k2: int, tr, h) -> dict:
    e = state_errors(tr, h)[:, k2:]
    return {
        "C003-3": {"omega": rms_ci(e[:, :, 4] / sc2.omega0), "r": rms_ci(e[:, :, 2])},
        "figure": dict(
            t2=tr.t,
            omega=tr.omega[0].copy(),
            omega_hat=h.estimate[0, :, 4].copy(),
            r=tr.r[0].copy(),
            r_hat=h.estimate[0, :, 2].copy(),
        ),
    }


def _background_sweep(sc1: Scenario, n: int, seed: int, k0: int, crit: LossCriterion) -> tuple[dict, list]:
    """C003-4: the compensated background sweep (residual d/(kappa sigma_f) 50, 100; correlation 4, 8, 16 px) and the
    ablation without compensation (d/sigma_f = 5), one batch on the same draws (stream 3).

    Returns ``({"spread", "compensation"}, per-case RMS miss in px)``."""
    return _run(_background_spec(sc1, n, seed, k0, crit))


def _background_spec(sc1: Scenario, n: int, seed: int, k0: int, crit: LossCriterion) -> tuple:
    cases = ((50.0, 8.0), (100.0, 8.0), (50.0, 4.0), (50.0, 16.0))
    blocks = [dict(kappa=sc1.kappa, background_std=1.0 / (sc1.kappa * r), corr_length=c) for r, c in cases]
    blocks.append(dict(kappa=1.0, background_std=1.0 / 5.0, corr_length=8.0))
    return (
        ("background", scenario_key(sc1), n, seed, k0, crit),
        ([stream_rng(3, seed) for _ in blocks], n * len(blocks), sc1),
        dict(keep_full=False, n_common=n, blocks=blocks),
        lambda tr, h: _background_outcome(h, len(blocks), n, k0, crit),
    )


def _background_outcome(h, m: int, n: int, k0: int, crit: LossCriterion) -> tuple[dict, list]:
    ms, lo = _miss_stats(h, k0, crit)
    ms, lo = ms.reshape(m, n), lo.reshape(m, n)
    rms = [mean_ci(np.sqrt(m)) for m in ms[:-1]]
    big, small = max(rms, key=lambda x: x.value), min(rms, key=lambda x: x.value)
    spread = interval_estimate(
        big.value / small.value,
        max(big.ci_low / small.ci_high, 0.0),
        big.ci_high / max(small.ci_low, 1e-12),
        big.n,
        "max/min of per-case RMS miss; interval from the per-case 95 % bounds (conservative)",
    )
    return {"spread": spread, "compensation": share_difference(lo[-1], lo[0])}, [r.value for r in rms]


def _miss_ms(sc: Scenario, n: int, seed: int, k0: int, crit: LossCriterion) -> np.ndarray:
    """Per-run mean-square marker miss (px^2, frames from ``k0``) of ``n`` runs of ``sc`` on the Fig. 1 draws."""
    return _kept(_miss_spec(sc, n, seed, k0, crit))


def _miss_spec(sc: Scenario, n: int, seed: int, k0: int, crit: LossCriterion) -> tuple:
    key = ("miss_ms", scenario_key(sc), n, seed, k0, crit)
    return key, (stream_rng(1, seed), n, sc), dict(keep_full=False), lambda tr, h: _miss_stats(h, k0, crit)[0]


def _form_runs(sc1: Scenario) -> list:
    """The C003-9 runs beyond the Fig. 1 batch (:func:`_discriminator_forms`): the quadrant form with the other spot,
    the edge form with both."""
    other = replace(sc1, spot="square" if sc1.spot == "disc" else "disc")
    return [other] + [replace(sc1, spot=spot, form="edge") for spot in ("square", "disc")]


def _run(spec):
    """A spec's value computed alone (``run_scenario``)."""
    _, args, kw, finish = spec
    tr, _, h = run_scenario(*args, **kw)
    return finish(tr, h)


def _part(spec):
    """A spec as a part of :func:`.memo.memo_together`."""
    _, args, kw, finish = spec
    return spec[0], lambda: prepare_scenario(*args, **kw), lambda p, r: finish(r[0], r[2])


def _kept(spec):
    """A spec's value, kept by its key (computed alone where not kept yet)."""
    return memo_together([_part(spec)], run_together)[0]


def _discriminator_forms(config: dict, sc1: Scenario, n: int, seed: int, k0: int, crit, quad_ms: dict) -> dict:
    """C003-9: the quadrant slopes over 2dD (deterministic, read over ``slope_range``) and the edge form's mean-square
    miss over the quadrant form's in closed loop, for both spots, on the Fig. 1 draws (stream 1; ``quad_ms`` holds
    the quadrant runs already made, by spot)."""
    part9 = {}
    for spot in ("square", "disc"):
        s = replace(sc1, spot=spot)
        fit = quadrant_slope_fit(s.spot_renderer(), s.diameter, s.gate_half)
        part9[f"{spot}_linear"] = fit[SLOPE_RANGES[config.get("slope_range", "+-D/2")]] / s.slope()
        if spot not in quad_ms:
            quad_ms[spot] = _miss_ms(s, n, seed, k0, crit)
        part9[f"edge_{spot}"] = ratio_ci(_miss_ms(replace(s, form="edge"), n, seed, k0, crit), quad_ms[spot])
    return part9


# ----------------------------------------------------------------------------------------------------------------
# interference claims


def _curve(sc: Scenario, sirs, n: int, seed: int, crit: LossCriterion, counts=None, criteria: bool = False):
    """Loss indicators of ``n`` runs at each SIR (stream 10: common draws), shape (m, n); with ``counts``
    (interferer numbers, or ``("decoy", offset)``: no stationary interferer and the law-following decoy at that
    offset, px) one batch of blocks, shape (len(counts), m, n); each block gets the runs it would get alone. With
    ``criteria`` also the loss criteria each loss meets (:func:`.lock.loss_criteria`, capture judged off the marker),
    shape (..., m, n, 3)."""
    return memo_together([curve_part(sc, sirs, n, seed, crit, counts, criteria)], run_together)[0]


# the loss curves each interference claim reads (the rotating marker's, with one and five interferers, all do)
_I_NEEDS = {
    "C003-5": set(),
    "C003-6": set(),
    "C003-7": set(),
    "C003-10": {"gate", "uncompensated"},
    "C003-11": {"gate", "bandwidth"},
    "C003-12": {"static", "decoy"},
}


def measure_interference(config: dict, seed: int, sizes: Sizes = Sizes(), claims=None) -> dict:
    """One replicate of the loss-of-lock claims at ``config`` (all curves on :data:`SIR_GRID`, same draws).

    The thresholds of C003-7's ``rise``, C003-12 and ``_map`` read the rotating, static and decoy curves on the grid
    extended where a run broke outside it (:func:`extend_grid`, up to two points on each side; ``"_grid"``).
    ``claims`` (ids, None for all) names the claims to compute: the curves only other claims read are not run
    (:data:`_I_NEEDS`); what is computed is the same, bit for bit, whatever else is asked. Curves whose inputs a
    configuration leaves as they were are taken from the run that computed them (:func:`.memo.memo`).

    Returns
    -------
    dict
        ``{"C003-5": {"no_loss", "no_capture"}, "C003-6": {"finite", "loss_free", "not_lower"},
        "C003-7": {"loss_free", "not_lower", "rise"}, "C003-10": {"gate", "compensation"},
        "C003-11": {"dynamics", "selection", "bandwidth"} (mean-square miss without interferers,
        B_xy 20 Hz over 5 Hz), "C003-12": {"one", "five", "imitator"}}``, ``"_map"`` (the thresholds of the
        rotating and static markers with one and five interferers), ``"_map_bound"`` (the same thresholds as the
        bounds their grid censoring certifies, :func:`threshold_bound`), ``"_mechanisms"`` (counts of the losses meeting
        each loss criterion) and ``"_curves"`` (the loss indicators); ``_map`` and ``_map_bound`` only with the static
        curves (C003-12 asked), ``_bandwidth_ratio`` only with C003-11.
    """
    asked = _asked(claims, I_CLAIMS)
    need = set().union(*(_I_NEEDS[c] for c in asked)) if asked else set()
    n, sirs = sizes.trials, np.asarray(SIR_GRID)
    base = interference_scenario(config, sizes)
    D = base.diameter
    crit = criterion(config, base)
    static_half = {"3D": 1.5 * D, "2D": D}[config.get("static_gate", "3D")]
    curves, met = {}, {}
    # the decoy's runs (C003-12) ride in the rotating marker's batch as a third block: the same runs as alone
    fam = (1, 5, ("decoy", 2 * D)) if "decoy" in need else (1, 5)
    st = replace(base, rotating=False, gate_half=static_half, form=config.get("static_form", "quadrant"))
    gates = {gf: replace(base, n_interferers=5, gate_half=gf * D / 2) for gf in (1.5, 5.0)}
    usirs, unc = np.asarray(UNCOMPENSATED_GRID), replace(base, n_interferers=5, kappa=1.0)
    k0 = int(round(sizes.transient_s * base.fps))
    _together(  # the curves and runs not kept yet, side by side in one frame loop; the calls below find them
        [curve_part(base, sirs, n, seed, crit, fam, True)]
        + ([curve_part(st, sirs, n, seed, criterion(config, st), (1, 5), True)] if "static" in need else [])
        + ([curve_part(g, sirs, n, seed, criterion(config, g)) for g in gates.values()] if "gate" in need else [])
        + ([curve_part(unc, usirs, n, seed, crit)] if "uncompensated" in need else [])
        + ([_bandwidth_part(base, n, seed, k0)] if "bandwidth" in need else [])
    )
    lost_r, met_r = _curve(base, sirs, n, seed, crit, fam, True)
    curves["rotating", 1], curves["rotating", 5], met["rotating"] = lost_r[0], lost_r[1], met_r[:2]
    if "static" in need:
        (curves["static", 1], curves["static", 5]), met["static"] = _curve(
            st, sirs, n, seed, criterion(config, st), (1, 5), True
        )
    capt = met["rotating"][1, :, :, 0]
    if "gate" in need:
        for gf, g in gates.items():
            curves["gate", gf], _ = _curve(g, sirs, n, seed, criterion(config, g))
    if "decoy" in need:
        curves["decoy"] = lost_r[2]
    if "uncompensated" in need:
        curves["uncompensated"], _ = _curve(unc, usirs, n, seed, crit)
    bw_ratio = None
    if "bandwidth" in need:
        bw_ratio = memo(_bandwidth_part(base, n, seed, k0)[0], lambda: _bandwidth_ratio(base, n, seed, k0))

    def more(keys, sir):  # the C003-7/-12 curves at one more SIR, only the families asked for (same draws)
        got = {}
        for fam, sc_f in (("rotating", base), ("static", st)):
            if any(k[0] == fam for k in keys):
                lost, _ = _curve(sc_f, [sir], n, seed, criterion(config, sc_f), (1, 5))
                got[fam, 1], got[fam, 5] = lost[0, 0], lost[1, 0]
        if "decoy" in keys:
            got["decoy"] = _curve(replace(base, decoy_offset=2 * D), [sir], n, seed, crit)[0][0]
        return got

    pair_keys = [k for k in [("rotating", 1), ("rotating", 5), ("static", 1), ("static", 5), "decoy"] if k in curves]
    # one adaptive point a side, and only when the rotating marker's own runs break outside the grid: the static
    # marker's and the decoy's breaking below it certify an upper bound on C003-12's ratios (threshold_ratio); the
    # rotating curves' extension does not depend on which other curves are extended with them
    xsirs, xc = extend_grid({k: curves[k] for k in pair_keys}, sirs, more, max_points=1, trigger=pair_keys[:2])
    out = interference_claims(config, base, curves, capt, xc, xsirs, bw_ratio, asked)
    if bw_ratio is not None:
        out["_bandwidth_ratio"] = bw_ratio
    out["_mechanisms"] = {
        f"{m} {k}": loss_mechanisms(curves[m, k], met[m][j]) for m in met for j, k in enumerate((1, 5))
    }
    if "static" in met:
        out["_map"] = {f"{m} {k}": threshold(xc[m, k], xsirs) for m in ("rotating", "static") for k in (1, 5)}
        # the side of a paper value each _map threshold certifies, also when runs broke outside the grid (prose)
        out["_map_bound"] = {
            f"{m} {k}": threshold_bound(xc[m, k], xsirs) for m in ("rotating", "static") for k in (1, 5)
        }
    out["_grid"] = [
        float(x) for x in xsirs
    ]  # the SIR grid with its adaptive points (the thresholds of _map, C003-7 rise, C003-12)
    out["_curves"] = {("/".join(map(str, k)) if isinstance(k, tuple) else k): v for k, v in curves.items()}
    return out


# as_declared applied here, not as a decorator: mutmut 3 mutates no decorated function (docs/mutation.md)
measure_interference = as_declared(I_CLAIMS, _declared)(measure_interference)


def _bandwidth_ratio(base: Scenario, n: int, seed: int, k0: int) -> Estimate:
    """C003-11: mean-square marker miss (frames from ``k0``, no interferers) with the wider loop of
    :data:`BANDWIDTH_PAIR` over the narrower, paired on the Fig. 1 draws (stream 1), with its direction (the rule reads
    its fold distance, :func:`tvtrack.measured.fold_about`)."""
    return _bandwidth_outcome(
        run_scenario(*_bandwidth_runs(base, n, seed), keep_full=False, **_bandwidth_kw(base, n))[2], n, k0
    )


def _bandwidth_runs(base: Scenario, n: int, seed: int) -> tuple:
    return [stream_rng(1, seed) for _ in BANDWIDTH_PAIR], 2 * n, base


def _bandwidth_kw(base: Scenario, n: int) -> dict:
    return dict(n_common=n, gains=stack_gains([replace(base, b_xy=b).gains() for b in BANDWIDTH_PAIR], n))


def _bandwidth_part(base: Scenario, n: int, seed: int, k0: int):
    """:func:`_bandwidth_ratio` as a part of :func:`.memo.memo_together`: ``(key, prepare, finish)``."""
    return (
        ("bandwidth", scenario_key(base), n, seed, k0),
        lambda: prepare_scenario(*_bandwidth_runs(base, n, seed), keep_full=False, **_bandwidth_kw(base, n)),
        lambda p, r: _bandwidth_outcome(r[2], n, k0),
    )


def _bandwidth_outcome(h, n: int, k0: int) -> Estimate:
    ms = np.mean(h.miss[:, k0:].astype(float) ** 2, axis=1).reshape(2, n)
    return ratio_ci(ms[1], ms[0])


def _together(parts) -> None:
    """Run the ``parts`` (``(key, prepare, finish)``) of a measurement not kept yet side by side in one frame loop
    (:func:`.lockstep.run_together`: each with its own numbers, bit for bit) and keep them (:func:`.memo.memo_together`)
    for the calls that follow."""
    memo_together(parts, run_together)
