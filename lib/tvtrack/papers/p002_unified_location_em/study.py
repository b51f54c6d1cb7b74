"""Measurement functions of paper 002: what the explorer calls, and the figure data they share.

A *configuration* of the study is a dict ``{register entry name: value}`` (:mod:`.register`); a *seed* makes one
independent full-size replicate. :func:`measure` turns both into ``{claim id: measured}`` where *measured* is what
the claim's rule reads (an :class:`~tvtrack.montecarlo.Estimate`, a list of them for ``Monotone``, a dict of parts
for ``AllOf``). Internally a configuration becomes a set of simulation *jobs*: one :class:`~.simulation.Config`
(``Q``, separation, pixel size, photons, frames) run for one algorithm letter under the settings that letter reads.
Jobs are cached by ``(settings, Config)``, so a register value that changes only the two-stage algorithm reruns
only the two-stage jobs, and a value that changes only a statistic reruns nothing (common random numbers: the
explorer passes the same seed to every configuration of a stage). :func:`measure_batch` collects the jobs of many
configurations and runs the missing ones in worker processes.

Units: sigma (PSF standard deviation) for lengths, frames for time.
"""

from __future__ import annotations

import multiprocessing
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, replace

import numpy as np

from tvtrack.montecarlo import Estimate, ratio_ci
from .simulation import (
    SPREADS,
    CANONICAL_SETTINGS,
    Config,
    StudySettings,
    bootstrap_groups,
    mse_sum,
    position_errors,
    run_config,
    seed_sequence,
    variance_ratio_ci,
    variance_sum,
)

__all__ = [
    "Scale",
    "D_GRID",
    "settings_of",
    "jobs_of",
    "run_jobs",
    "measure",
    "measure_batch",
    "screen_scale",
    "figure_data",
    "errors",
    "gain",
    "spread_sum",
    "exp_estimate",
    "clear_cache",
]

#: Separations d / sigma of the distance axes (card 5.2).
D_GRID = (0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0)
#: Separations (sigma) over which C002-10's "coarser pixels" and "more frames" gains are averaged (up to the
#: register's "close separations" value): the text names d = 1 and 3 sigma.
CLOSE = (1.0, 2.0, 3.0)
#: Settings fields each algorithm letter reads besides the scene's (seed, velocity, noise, photon model, margin).
_READS = {
    "u": ("tol_sigma", "tol_loglik", "max_iter", "merge_sigma", "accelerate"),
    "p": ("tol_sigma", "tol_loglik"),
    "m": ("tol_sigma", "tol_loglik", "max_iter", "merge_sigma", "accelerate", "velocity_knowledge"),
    "e": ("tol_sigma", "tol_loglik", "max_iter", "accelerate", "mark_init", "mark_association"),
    "q": ("tol_sigma", "tol_loglik", "mark_init", "mark_association"),
    "c": ("gate_half_sigma",),
    "s": ("tol_sigma", "max_iter", "accelerate"),
    "w": ("tol_sigma", "max_iter"),
    "k": ("tol_sigma", "max_iter", "accelerate"),
    "1": ("tol_sigma", "max_iter", "accelerate"),
    "b": ("bic_max_iter",),
}
_CANON = CANONICAL_SETTINGS
_SCENE = ("seed", "velocity_sigma", "noise_density", "photon_model", "margin_sigma", "crb_phases", "tracks")
#: The matched practical stop of the "EM stopping" reading (ULA and marks alike).
PRACTICAL_STOP = "plain EM to a log-likelihood gap of 0.1"
_TWO_STAGE = {
    "designation start, labels by start": ("designation", "designation"),
    "previous start + assignment": ("previous", "assignment"),
    "designation start + line association": ("designation", "lines"),
    "no designation: moment start + line association": ("moments", "lines"),
}
#: The "EM stopping" readings: (acceleration, iteration cap, parameter tolerance sigma, log-likelihood gap nats).
#: The practical stop is matched between the ULA and the two-stage marks (issue 39): each EM stops when the
#: log-likelihood it can still gain on its own data is below the same gap, i.e. at the same distance from its
#: maximum in units of its own standard error (a parameter tolerance in sigma stopped the ULA, whose estimate pools
#: T frames, at a larger share of its spread than the marks: x2.2 the added error at T = 50, d = sigma).
_EM = {
    "SQUAREM to 1e-6 sigma": ("squarem", 5000, 1e-6, None),
    "plain EM, cap 100": ("none", 100, 1e-6, None),
    PRACTICAL_STOP: ("none", 5000, 1e-6, 0.1),
}
_CACHE: dict[tuple, dict] = {}


@dataclass(frozen=True)
class Scale:
    """Sizes of one replicate (the profile's, not the register's: every configuration uses the same).

    Attributes
    ----------
    n_trials : int
        Monte Carlo trials per simulation point.
    n_iter_trials : int
        Trials per point of the plain-EM iteration study (C002-13, C002-14) and of the multi-start check.
    separations : tuple of float
        The distance axis d / sigma (must hold 1, 2, 3, 6 and 8 for the claims; 0.5 is the "very close" end).
    fig3_frames : tuple of int
        The frame axis of Fig 3 (must hold 5, 10 and 50).
    crb_phases : int
        Sub-pixel phases averaged in each bound.
    n_bootstrap : int
        Bootstrap resamples of every ratio interval.
    n_workers : int
        Worker processes of :func:`run_jobs`.
    max_iter : int, optional
        A lower EM iteration cap than the register's (the smoke profile only: it bounds the slow tails).
    """

    n_trials: int = 100
    n_iter_trials: int = 40
    separations: tuple = D_GRID
    fig3_frames: tuple = (2, 5, 10, 20, 50)
    crb_phases: int = 64
    n_bootstrap: int = 2000
    n_workers: int = 1
    max_iter: int | None = None


def clear_cache() -> None:
    """Forget every cached simulation job (tests; memory)."""
    _CACHE.clear()


def settings_of(config: dict, seed: int, scale: Scale) -> StudySettings:
    """The simulation settings of a register configuration and a replicate seed."""
    init, assoc = _TWO_STAGE[config["two-stage"]]
    accel, cap, tol, gap = _EM[config["EM stopping"]]
    cap = cap if scale.max_iter is None else min(cap, scale.max_iter)
    vx, vy = (float(v) for v in str(config["velocity (sigma/frame)"]).split(","))
    return replace(
        _CANON,
        seed=int(seed),
        velocity_sigma=(vx, vy),
        noise_density=float(config["noise (photons/sigma^2/frame)"]),
        photon_model=config["photon model"],
        designation_sd_sigma=float(config["designation error (sigma)"]),
        tol_sigma=tol,
        tol_loglik=gap,
        max_iter=cap,
        accelerate=accel,
        mark_init=init,
        mark_association=assoc,
        crb_phases=scale.crb_phases,
        n_trials=scale.n_trials,
        n_bootstrap=scale.n_bootstrap,
        velocity_knowledge=config["velocity knowledge"],
        tracks=config["tracks"],
    )


def _job_settings(settings: StudySettings, letter: str, scale: Scale, q: int = 2) -> StudySettings:
    """``settings`` with every field that ``letter`` does not read reset to a canonical value (the cache key).
    The plain-EM iteration counts (``p``, ``q``) run to the paper's convergence whatever the register's stopping
    reading; only the scale's cap (smoke profile) bounds them."""
    keep = set(_SCENE) | set(_READS[letter])
    out = replace(_CANON, **{k: getattr(settings, k) for k in keep})
    if q == 1:  # one object: nothing to cross
        out = replace(out, tracks="parallel")
    if letter in "pq":  # the counts' own tolerance is the "EM tolerance of Fig 7" row (a Config variant)
        out = replace(out, tol_sigma=_CANON.tol_sigma, tol_loglik=_CANON.tol_loglik)
    if letter in "pq" and scale.max_iter is not None:
        out = replace(out, max_iter=min(out.max_iter, scale.max_iter))
    return out


class _Points:
    """Builds the :class:`Config` of a simulation point from a register configuration and records it."""

    def __init__(self, config: dict, scale: Scale):
        self.dsd = float(config["designation error (sigma)"])
        self.scale = scale
        self.asked: list[Config] = []

    def __call__(self, q, d, pix, m, T, algs, n=None, variant=()) -> Config:
        c = Config(
            int(q),
            float(d),
            float(pix),
            int(m),
            int(T),
            algs,
            self.dsd,
            None,
            None,
            int(n or self.scale.n_trials),
            "explore",
            0.0,
            tuple(variant),
        )
        self.asked.append(c)
        return c


#: The photon counts C002-6 compares (an adversarial register row): ``"20 vs 10"`` (Fig 2) or ``"10 vs 5"`` ("at
#: least from some critical level": a level below Fig 2's).
PHOTONS6 = {"20 vs 10": (20, 10), "10 vs 5": (10, 5)}
#: Columns of the per-trial errors ``(x1, y1, x2, y2)`` that C002-6's "sum of variances of the coordinate" reads
#: (an adversarial register row): the objects are separated along ``y``.
COORDINATE6 = {
    "both": slice(None),
    "along the separation": slice(1, None, 2),
    "across the separation": slice(0, None, 2),
}


def photons6(config: dict) -> tuple[int, int]:
    """The (more, fewer) target photons per frame whose T dependences C002-6 compares."""
    return PHOTONS6[config.get("m_k pair of C002-6", "20 vs 10")]


#: The frame counts whose variance ratio r_T C002-6 reads (an adversarial register row): Fig 2's ``"5 vs 10"``, or
#: ``"5 vs 50"``, the range of Figs 3a and 5 ("the number of analysed frames" over the study's whole T axis).
FRAMES6 = {"5 vs 10": (5, 10), "5 vs 50": (5, 50)}


#: How C002-6 reads "the dependence on T" (an adversarial register row): relative, |ln r_T| (the gap between the T
#: curves on a log axis), or absolute, |Sigma^2(T_lo) - Sigma^2(T_hi)| in sigma^2 (the gap on a linear axis).
T_DEPENDENCE6 = ("relative (log ratio)", "absolute (variance gap)")


def c6_point(config: dict) -> tuple[float, tuple[int, int]]:
    """C002-6's pixel size Delta / sigma (Fig 2: 1; an adversarial register row) and its frame pair."""
    return float(config.get("Delta of C002-6 (sigma)", 1.0)), FRAMES6[config.get("T pair of C002-6", "5 vs 10")]


#: The "EM tolerance of Fig 7" reading (an adversarial register row): the practical stop of the iteration counts of
#: Fig 7, the log-likelihood gap (nats) each EM (ULA and per-frame marks alike) may leave, matched as in "EM
#: stopping"; ``None`` keeps the study's own 1e-6 sigma.
FIG7_TOLERANCE = {"1e-6 sigma": None, "log-likelihood gap 0.01": 0.01, "log-likelihood gap 0.1": 0.1}


#: Fig 1's panels by pixel size Delta / sigma.
FIG1_PANEL = {3.0: "1a", 1.0: "1b"}


def c1_point(config: dict) -> tuple[int, float]:
    """C002-1's point of Fig 1: ``(m_k, Delta / sigma)`` from the register (default 20 photons, Fig 1a)."""
    return int(config.get("m_k of C002-1", 20)), float(config.get("Delta of C002-1 (sigma)", 3.0))


def fig7_variant(config: dict) -> tuple:
    """The :class:`Config` ``variant`` of the Fig 7 points (C002-13, C002-14): the register's stopping tolerance
    of the iteration counts, or ``()`` at the default (the default's cache keys and draws are unchanged; a variant
    sees the same scenes, common random numbers)."""
    tol = FIG7_TOLERANCE[config.get("EM tolerance of Fig 7", "1e-6 sigma")]
    return () if tol is None else (("tol_loglik", float(tol)),)


def _points(config: dict, scale: Scale, figures: bool = False):
    """The simulation points the claims read (and, with ``figures``, the figures' whole curves), as named groups of
    ``{d: Config}`` (``{T: Config}`` for Fig 3a). The claims read only the separations they compare, so a replicate
    simulates what decides a verdict; the figures add the rest of their axes once (first replicate)."""
    P = _Points(config, scale)
    D = tuple(scale.separations)
    T1, m1c = int(config["T of Figs 1a,b"]), int(config["m_k of Fig 1c"])
    pix, T4, m5 = (
        float(config["Delta of Figs 4, 5, 7 (sigma)"]),
        int(config["T of Figs 4, 6, 7"]),
        int(config["m_k of Fig 5"]),
    )
    close = [d for d in CLOSE if d <= float(config["close separations of C002-10 (sigma)"])]
    close = sorted(set(close) | {1.0, 3.0})  # C002-11 reads d = 1 and 3 sigma
    small = [d for d in D if d <= float(config["small separations of C002-6 (sigma)"])]
    d5, T3 = float(config["separation of C002-5 (sigma)"]), int(config["T of the Fig 3a claims"])
    core = (1.0, 2.0, 3.0, 6.0)
    pick = (lambda ds: D) if figures else (lambda ds: [d for d in D if d in ds])
    m1, p1 = c1_point(config)  # C002-1 reads its panel's whole distance axis
    p6, T6 = c6_point(config)

    def fig1(p_, m):
        return {d: P(2, d, p_, m, T1, "u") for d in (D if (p_, m) == (p1, m1) else pick(core))}

    g = {
        "1a": {m: fig1(3.0, m) for m in (10, 20)},
        "1b": {m: fig1(1.0, m) for m in (10, 20)},
        "1c": {p_: {d: P(2, d, p_, m1c, 5, "u") for d in pick((1.0, 6.0))} for p_ in (3.0, 5.0)},
        "2": {
            (T, m): {d: P(2, d, p6, m, T, "u") for d in pick(small)}
            for T in sorted({5, 10, *T6} if figures else T6)
            for m in sorted(photons6(config))
        },
        "5": {(p_, T): {d5: P(2, d5, p_, 20, T, "u")} for p_ in (1.0, 3.0) for T in (5, 10, 50)},
        "3a": {
            p_: {T: P(1, 0.0, p_, 20, T, "uec") for T in (sorted({*scale.fig3_frames, T3}) if figures else (T3,))}
            for p_ in (1.0, 3.0, 5.0)
        },
        "4": {m: {d: P(2, d, pix, m, T4, "ue") for d in D} for m in ((20, 50) if figures else (20,))},
        "5ab": {T: {d: P(2, d, pix, m5, T, "ue") for d in close} for T in (5, 50)},
        "head_map": {d: P(2, d, pix, m5, 50, "m") for d in (1.0, 3.0)},
        "head_known": (
            {d: P(2, d, pix, m5, 50, "k") for d in (1.0, 3.0)} if config["velocity knowledge"] == "designated" else {}
        ),
        "6": {20: {d: P(2, d, 5.0, 20, T4, "ue") for d in close}},
        "good": {p_: P(2, 8.0, p_, int(config.get("m_k of C002-12", 20)), T4, "ue") for p_ in (0.5, 1.0)},
        "7": {
            d: P(2, d, pix, 20, T4, "upq", n=scale.n_iter_trials, variant=fig7_variant(config))
            for d in sorted({min(D), max(D)} | ({2.0} if figures else set()))
        },
    }
    if figures:
        g["ms"] = {d: P(2, d, pix, 20, T4, "s", n=scale.n_iter_trials) for d in (min(D), 1.0)}
        g["w"] = {d: P(2, d, pix, 20, T4, "uw1", n=scale.n_iter_trials) for d in (1.0, 2.0, 4.0)}
        g["bic"] = {d: P(2, d, pix, 20, T4, "b", n=scale.n_iter_trials) for d in D}  # unknown Q (card 8.3)
    return g, P.asked


def jobs_of(config: dict, seed: int, scale: Scale, figures: bool = False) -> list[tuple[StudySettings, Config]]:
    """The simulation jobs ``(settings, single-letter Config)`` of one configuration and seed, without repeats."""
    settings = settings_of(config, seed, scale)
    out = {}
    for c in _points(config, scale, figures)[1]:
        for a in c.algs:
            job = (_job_settings(settings, a, scale, c.q), c._replace(algs=a))
            out[job] = None
    return list(out)


def _run_job(job):
    return run_config(*job)


def run_jobs(jobs, n_workers: int = 1) -> None:
    """Run the jobs not yet cached (longest first) in ``n_workers`` forked processes."""
    todo = [j for j in dict.fromkeys(jobs) if j not in _CACHE]
    todo.sort(key=lambda j: -j[1].T * j[1].n * (1 + 2 * (j[1].algs in "epqs")))
    if n_workers > 1 and len(todo) > 1:
        with ProcessPoolExecutor(n_workers, mp_context=multiprocessing.get_context("fork")) as pool:
            for j, r in zip(todo, pool.map(_run_job, todo, chunksize=1)):
                _CACHE[j] = r
    else:
        for j in todo:
            _CACHE[j] = _run_job(j)


class _Results:
    """``res[c]``: the merged results of every letter of a point (from the cache)."""

    def __init__(self, settings: StudySettings, scale: Scale):
        self.settings = settings
        self.scale = scale

    def __getitem__(self, c: Config) -> dict:
        out = {}
        for a in c.algs:
            r = _CACHE[(_job_settings(self.settings, a, self.scale, c.q), c._replace(algs=a))]
            out.update({k: v for k, v in r.items() if k != "timing"})
            out.setdefault("timing", {}).update({k: v for k, v in r["timing"].items() if v})
        return out


# -- statistics -----------------------------------------------------------------------------------------------


def errors(r: dict, alg: str, epoch: str = "first") -> np.ndarray:
    """Per-trial errors (n, 2Q) of one algorithm at one epoch (``first``, ``mid``, ``last``; sigma) or of its
    velocities (``velocity``; sigma/frame)."""
    return position_errors(r, alg, epoch)


#: The "gross errors" reading that trims the 10 % largest per-trial squared errors (an adversarial register row).
TRIMMED = "trimmed 10 %"


def spread_sum(e, statistic: str = "variance") -> Estimate:
    """The summed spread of errors (n, k): variance sum, MSE sum, or (``statistic="trimmed"``) the 10 %-trimmed
    variance sum with a percentile bootstrap interval (all in sigma^2)."""
    if statistic == "trimmed":
        rng = np.random.default_rng(seed_sequence(0, ("trimmed spread",)))
        return bootstrap_groups([np.asarray(e, float)], SPREADS["trimmed_variance"], rng, 2000)
    return mse_sum(e) if statistic == "MSE" else variance_sum(e)


def _spread(statistic: str) -> str:
    return {"MSE": "mse", "trimmed": "trimmed_variance"}.get(statistic, "variance")


def gain(num, den, rng, n_bootstrap, statistic="variance", paired=True) -> Estimate:
    """``Sigma^2_num / Sigma^2_den`` with a bootstrap interval; ``statistic="SD ratio"`` takes the square root."""
    return variance_ratio_ci(
        num, den, rng, n_bootstrap, paired=paired, spread=_spread(statistic), sqrt=statistic == "SD ratio"
    )


def exp_estimate(e: Estimate) -> Estimate:
    """An estimate of a log quantity mapped back by exp (the interval maps exactly)."""
    v = float(np.exp(e.value))
    return Estimate(v, v * e.stderr, float(np.exp(e.ci_low)), float(np.exp(e.ci_high)), e.n, e.confidence, e.method)


def _vsum(e, spread: str = "variance"):
    return e.var(axis=1, ddof=1).sum(axis=-1) if spread == "variance" else SPREADS[spread](e)


def _mean_log_gain(pairs_hi, pairs_lo, rng, n_bootstrap, spread: str = "variance") -> Estimate:
    """exp(mean log rho over the ``hi`` groups - mean log rho over the ``lo`` groups); each group holds the
    paired [num | den] errors of one point side by side (rows resampled jointly, groups independently)."""
    k = len(pairs_hi)

    def stat(*g):
        def mlog(h):
            return np.mean(
                [
                    np.log(_vsum(x[..., : x.shape[-1] // 2], spread) / _vsum(x[..., x.shape[-1] // 2 :], spread))
                    for x in h
                ],
                axis=0,
            )

        return mlog(g[:k]) - mlog(g[k:])

    return exp_estimate(bootstrap_groups(list(pairs_hi) + list(pairs_lo), stat, rng, n_bootstrap))


def _efficiency(e, bound: float, statistic: str) -> Estimate:
    """Spread over the bound; under the "SD ratio" reading the square root (a ratio of standard deviations)."""
    v = scaled(spread_sum(e, statistic), 1.0 / bound)
    if statistic == "SD ratio":
        r = np.sqrt(max(v.value, 0.0))
        return Estimate(
            r,
            v.stderr / (2 * max(r, 1e-300)),
            float(np.sqrt(max(v.ci_low, 0.0))),
            float(np.sqrt(max(v.ci_high, 0.0))),
            v.n,
            v.confidence,
            v.method + ", square root",
        )
    return v


# -- the claims -----------------------------------------------------------------------------------------------


def _claims(config: dict, g: dict, res: _Results, seed: int, scale: Scale) -> dict:
    """``{claim id: measured}`` of one configuration (see the notebook for each rule)."""
    rng = np.random.default_rng(seed_sequence(seed, ("bootstrap",)))
    B, ep, st = scale.n_bootstrap, config["epoch"], config["statistic"]
    if config.get("gross errors", "kept") == TRIMMED:
        st = "trimmed"
    sp = "trimmed_variance" if st == "trimmed" else "variance"  # the log-gain parts read variances otherwise
    D = list(scale.separations)
    ula = lambda c: errors(res[c], "ula", ep)
    m1, p1 = c1_point(config)
    out = {"C002-1": [spread_sum(ula(g[FIG1_PANEL[p1]][m1][d]), st) for d in D]}

    def r_m(key, d):
        return ula(g[key][10][d]), ula(g[key][20][d])

    far, near = r_m("1a", 6.0), r_m("1a", 1.0)
    out["C002-2"] = {
        "weakens": _mean_log_gain([np.hstack(far)], [np.hstack(near)], rng, B, sp),
        "far apart": gain(*far, rng, B, st, paired=False),
    }
    ds3 = (1.0, 2.0, 3.0, 6.0)
    out["C002-3"] = _mean_log_gain(
        [np.hstack(r_m("1b", d)) for d in ds3], [np.hstack(r_m("1a", d)) for d in ds3], rng, B, sp
    )
    loss = {p_: np.hstack([ula(g["1c"][p_][1.0]), ula(g["1c"][p_][6.0])]) for p_ in (5.0, 3.0)}
    out["C002-4"] = _mean_log_gain([loss[5.0]], [loss[3.0]], rng, B, sp)
    d5 = float(config["separation of C002-5 (sigma)"])
    out["C002-5"] = [
        gain(ula(g["5"][(3.0, T)][d5]), ula(g["5"][(1.0, T)][d5]), rng, B, st, paired=False) for T in (5, 10, 50)
    ]
    small = [d for d in D if d <= float(config["small separations of C002-6 (sigma)"])]

    cols = COORDINATE6[config.get("coordinate of C002-6", "both")]

    t_lo, t_hi = c6_point(config)[1]

    def rt(m):
        return [np.hstack([ula(g["2"][(t_lo, m)][d])[:, cols], ula(g["2"][(t_hi, m)][d])[:, cols]]) for d in small]

    gap = config.get("T dependence of C002-6", T_DEPENDENCE6[0]) == T_DEPENDENCE6[1]

    def stat6(*gr):
        def dep(x):
            a, b = _vsum(x[..., : x.shape[-1] // 2], sp), _vsum(x[..., x.shape[-1] // 2 :], sp)
            return np.abs(a - b) if gap else np.abs(np.log(a / b))

        return np.mean([dep(x) for x in gr[: len(small)]], axis=0) - np.mean([dep(x) for x in gr[len(small) :]], axis=0)

    m_hi, m_lo = photons6(config)
    out["C002-6"] = bootstrap_groups(rt(m_hi) + rt(m_lo), stat6, rng, B)
    T3 = int(config["T of the Fig 3a claims"])

    def x1(pix, alg):
        return position_errors(res[g["3a"][pix][T3]], alg, ep)[:, :1]

    pc = float(config["coarse Delta of C002-7, C002-8 (sigma)"])
    out["C002-7"] = {
        "fine pixels": gain(x1(1.0, "em"), x1(1.0, "ula"), rng, B, st),
        "coarse pixels": gain(x1(pc, "em"), x1(pc, "ula"), rng, B, st),
    }
    out["C002-8"] = {
        "worse than fine pixels": gain(x1(pc, "ula"), x1(1.0, "ula"), rng, B, st, paired=False),
        "better than the marks": gain(x1(pc, "ula"), x1(pc, "em"), rng, B, st),
    }
    p9 = float(config["Delta of the C002-9 order (sigma)"])
    out["C002-9"] = {
        "centre-of-region >= iterative marks": gain(x1(p9, "cr"), x1(p9, "em"), rng, B, st),
        "iterative marks >= ULA": gain(x1(p9, "em"), x1(p9, "ula"), rng, B, st),
    }
    use_map = config["ULA"] == "MAP (designation prior)"
    known = config["velocity knowledge"] == "designated"
    twin = "em_vd" if known else "em"

    def rho(c):
        r = res[c]
        return gain(errors(r, "em", ep), errors(r, "ula", ep), rng, B, st)

    def side(c):
        r = res[c]
        return np.hstack([errors(r, "em", ep), errors(r, "ula", ep)])

    close = [d for d in CLOSE if d <= float(config["close separations of C002-10 (sigma)"])]
    out["C002-10"] = {
        "closer": [rho(g["4"][20][d]) for d in D],
        "coarser pixels": _mean_log_gain(
            [side(g["6"][20][d]) for d in close], [side(g["4"][20][d]) for d in close], rng, B, sp
        ),
        "more frames": _mean_log_gain(
            [side(g["5ab"][50][d]) for d in close], [side(g["5ab"][5][d]) for d in close], rng, B, sp
        ),
    }

    def head(d):
        c = g["5ab"][50][d]
        if use_map:
            u = errors(res[g["head_map"][d]], "map", ep)
        elif known:
            u = errors(res[g["head_known"][d]], "ula_vd", ep)
        else:
            return rho(c)
        return gain(errors(res[c], twin, ep), u, rng, B, st)

    out["C002-11"] = {"d = 1 sigma (paper x4.5)": head(1.0), "d = 3 sigma (paper x4)": head(3.0)}
    out["C002-12"] = {f"Delta = {p_:g} sigma": rho(c) for p_, c in g["good"].items()}
    it = {d: res[c] for d, c in g["7"].items()}
    lo, hi = min(it), max(it)
    out["C002-13"] = ratio_ci(it[lo]["plain_iter"], it[hi]["plain_iter"], paired=False)
    T4 = int(config["T of Figs 4, 6, 7"])
    ula_work = np.concatenate([it[d]["plain_iter"] * T4 for d in (lo, hi)])
    marks_work = np.concatenate([it[d]["em_plain_iter"] for d in (lo, hi)])
    out["C002-14"] = ratio_ci(ula_work, marks_work)
    out["C002-15"] = _c15(
        config, g, res, "first", config["statistic"]
    )  # a trimmed spread is no bound's    # the CRB is the initial positions' bound
    return out


def _c15(config, g, res, ep, st) -> dict:
    """Efficiency of the ULA: its spread over the bound at very close and resolved separations, and for the
    velocities ("position and motion parameters of very close objects", conclusions)."""
    use_bayes = config["bound"] == "van Trees (designation prior)"
    key_pos, key_vel = ("bcrb_pos", "bcrb_vel") if use_bayes else ("crb_pos", "crb_vel")
    parts = {}
    cs = g["4"][20]
    for d, name in ((1.0, "d = 1 sigma (very close)"), (2.0, "d = 2 sigma"), (4.0, "d = 4 sigma")):
        r = res[cs[d]]
        parts[name] = _efficiency(errors(r, "ula", ep), r[key_pos], st)
    r = res[cs[1.0]]
    parts["velocities, d = 1 sigma"] = _efficiency(position_errors(r, "ula", "velocity"), r[key_vel], st)
    return parts


def measure_batch(configs, seeds, scale: Scale = Scale()) -> list[dict]:
    """:func:`measure` for many configurations at once: their jobs are collected, the missing ones run in
    ``scale.n_workers`` processes, then each configuration's claims are measured."""
    jobs = [j for c, s in zip(configs, seeds) for j in jobs_of(c, s, scale)]
    run_jobs(jobs, scale.n_workers)
    out = []
    for c, s in zip(configs, seeds):
        g, _ = _points(c, scale)
        out.append(_claims(c, g, _Results(settings_of(c, s, scale), scale), int(s), scale))
    return out


def screen_scale(scale: Scale, fraction: float = 0.25, n_bootstrap: int = 1000) -> Scale:
    """The cheaper scale of the joint design's screen (``explore(..., screen=partial(measure_batch, scale=...))``):
    ``fraction`` of the trials of every point (at least 8; 4 for the iteration study), ``n_bootstrap`` resamples and
    a quarter of the bound's sub-pixel phases (at least 8). The screen only sorts configurations: each whose verdict
    is not decisively the default's is re-measured at full size."""
    if not 0 < fraction <= 1:
        raise ValueError(f"fraction = {fraction} must be in (0, 1]")
    return replace(
        scale,
        n_trials=max(8, round(scale.n_trials * fraction)),
        n_iter_trials=max(4, round(scale.n_iter_trials * fraction)),
        n_bootstrap=min(n_bootstrap, scale.n_bootstrap),
        crb_phases=max(8, scale.crb_phases // 4),
    )


def measure(config: dict, seed: int, scale: Scale = Scale()) -> dict:
    """One full-size replicate of the study at ``config`` (every register entry present) with all random draws
    from ``seed``: ``{claim id: measured}``."""
    return measure_batch([config], [seed], scale)[0]


def figure_data(config: dict, seed: int, scale: Scale = Scale()) -> tuple[dict, _Results]:
    """The simulation points (named groups of :class:`Config`) and their results at ``config`` and ``seed``, for
    the figures (runs what is not cached)."""
    run_jobs(jobs_of(config, seed, scale, figures=True), scale.n_workers)
    return _points(config, scale, figures=True)[0], _Results(settings_of(config, seed, scale), scale)


#: The paper's claims: statement and the paper's value (paper card 002, section 7).
CLAIMS = {
    "C002-1": ("Accuracy falls as the objects get closer (Fig 1).", "qualitative"),
    "C002-2": (
        "As the objects get closer the dependence of the variance on the photon number weakens (Fig 1a,b).",
        "qualitative; r_m ~ 2 far apart",
    ),
    "C002-3": ("With smaller pixels the dependence on the photon number strengthens (Fig 1a vs 1b).", "qualitative"),
    "C002-4": ("As the objects get closer, errors grow faster for larger pixels (Fig 1c).", "qualitative"),
    "C002-5": ("With more frames the influence of pixel size weakens (Figs 1c, 2a).", "qualitative"),
    "C002-6": ("With fewer target photons the dependence on T weakens (grouped sample; Fig 2).", "qualitative"),
    "C002-7": ("One object: the ULA beats two-stage processing only for large pixels (Fig 3a).", "qualitative"),
    "C002-8": (
        "One object: the ULA partly offsets poor primary processing but does not fully compensate it.",
        "qualitative",
    ),
    "C002-9": ("Implied ordering of Fig 3a: centre-of-region >= iterative marks >= ULA.", "curve order"),
    "C002-10": (
        "Multi-target: the ULA gain grows as objects get closer, pixels larger and frames more (Figs 4-6).",
        "qualitative",
    ),
    "C002-11": (
        "At T = 50 the accuracy difference reaches x4 at separation 3 and x4.5 at separation 1 (Fig 5).",
        "x4 (d = 3 sigma), x4.5 (d = 1 sigma)",
    ),
    "C002-12": (
        "For separations > 8 sigma and Delta/sigma < 1 the two algorithms' accuracies practically coincide.",
        "rho ~ 1",
    ),
    "C002-13": (
        "The number of ULA iterations depends on the separation (Fig 7; direction not stated).",
        "a curve (lost)",
    ),
    "C002-14": ("The ULA is more laborious than two-stage processing.", "qualitative"),
    "C002-15": (
        "For very close objects with known Q the ULA gives practically potential accuracy of position and "
        "motion parameters.",
        "'practically potential'",
    ),
}


def scaled(est: Estimate, factor: float) -> Estimate:
    """``est`` times a positive constant (value, standard error and interval)."""
    return Estimate(
        est.value * factor,
        est.stderr * factor,
        est.ci_low * factor,
        est.ci_high * factor,
        est.n,
        est.confidence,
        est.method,
    )
