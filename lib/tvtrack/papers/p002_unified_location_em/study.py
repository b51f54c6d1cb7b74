"""Measurement functions of paper 002: what the explorer calls, and the figure data they share.

A *configuration* of the study is a dict ``{register entry name: value}`` (:mod:`.register`); a *seed* makes one
independent full-size replicate. :func:`measure` turns both into ``{claim id: measured}`` where *measured* is what
the claim's rule reads (an :class:`~tvtrack.montecarlo.Estimate`, a list of them for ``Monotone``, a dict of parts
for ``AllOf``). Internally a configuration becomes a set of simulation *jobs*: one :class:`~.simulation.Config`
(``Q``, separation, pixel size, photons, frames) run for one algorithm letter under the settings that letter reads.
Jobs are cached by ``(settings, Config)``, so a register value that changes only the two-stage algorithm reruns
only the two-stage jobs, and a value that changes only a statistic reruns nothing (common random numbers: the
explorer passes the same seed to every configuration of a stage). :func:`measure_batch` collects the jobs of many
configurations and runs the missing ones in worker processes. Asked for some claims only (``claims=``), a
measurement runs only the jobs those claims read (:data:`.claim_values.NEEDS`; of a point only the algorithms they
read, :data:`.claim_values.LETTERS`) and gives them the values a measurement of every claim gives, bit for bit
(each claim bootstraps from its own stream, each algorithm runs apart on the point's scenes). The claims'
statistics live in :mod:`.claim_values`, the register's point readings in :mod:`.readings`.

Units: sigma (PSF standard deviation) for lengths, frames for time.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ...jobs import fork_pool
from .claim_values import (
    measure_claims,
    needed_letters,
)
from .readings import (
    CLOSE,
    D_GRID,
    c1_point,
    c5_pair,
    c11_separations,
    c6_point,
    c15_close,
    fig7_variant,
    photons6,
)
from .sim_config import CANONICAL_SETTINGS, Config, StudySettings
from .simulation import run_config

__all__ = [
    "Scale",
    "D_GRID",
    "settings_of",
    "jobs_of",
    "run_jobs",
    "rerun",
    "measure",
    "measure_batch",
    "screen_scale",
    "figure_data",
    "clear_cache",
    "cached",
    "remember",
]

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
    "r": (),  # the bounds read the scene only
}
_CANON = CANONICAL_SETTINGS
_SCENE = ("seed", "velocity_sigma", "noise_density", "photon_model", "margin_sigma", "crb_phases", "tracks")
#: The practical stop of the "EM stopping" reading: the same log-likelihood gap for the ULA and each frame's mark
#: (not the same added error; the register's why says why).
PRACTICAL_STOP = "plain EM to a log-likelihood gap of 0.1"
#: The register default of "EM stopping" (its cap is the run's).
DEFAULT_STOP = "SQUAREM to 1e-6 sigma"
_TWO_STAGE = {
    "designation start, labels by start": ("designation", "designation"),
    "previous start + assignment": ("previous", "assignment"),
    "designation start + line association": ("designation", "lines"),
    "no designation: moment start + line association": ("moments", "lines"),
}
#: The "EM stopping" readings: (acceleration, iteration cap, parameter tolerance sigma, log-likelihood gap nats).
#: The default runs the ULA and the marks to convergence. Under the practical stop each EM stops when the
#: log-likelihood it can still gain on its own data is below the same gap; that leaves the two algorithms unequal
#: added errors (the two-stage's marks all stop short towards their designated starts), so it is a reading of the
#: paper's stopping rule, never the default comparison.
_EM = {
    "SQUAREM to 1e-6 sigma": ("squarem", 5000, 1e-6, None),
    "plain EM, cap 100": ("none", 100, 1e-6, None),
    PRACTICAL_STOP: ("none", 5000, 1e-6, 0.1),
}
_CACHE: dict[tuple, dict] = {}
#: C002-5's six ULA points run this many times the trials of a point: its unpaired variance ratios at three frame
#: counts decide nothing in one replicate of 80 trials (10 of 10 undecided, seed 1999's replicates), 3 replicates
#: pooled reproduced it in 31 of 120 choices and the sizing, projecting from a few, stopped undecided in a third of
#: the orders though all 10 pooled reproduce it; 9 pooled decide it every time (10 of 10 choices).
C5_TRIALS = 3


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
    cap_factor : int
        The run's EM iteration cap (the register's, or ``max_iter`` where lower) multiplied by this (a study of what
        the cap changes, :mod:`.flip_caps_check`); a reading that sets its own cap ("plain EM, cap 100") keeps it
        where it is the lower.
    """

    n_trials: int = 100
    n_iter_trials: int = 40
    separations: tuple = D_GRID
    fig3_frames: tuple = (2, 5, 10, 20, 50)
    crb_phases: int = 64
    n_bootstrap: int = 2000
    n_workers: int = 1
    max_iter: int | None = None
    cap_factor: int = 1


def clear_cache() -> None:
    """Forget every cached simulation job (tests; memory)."""
    _CACHE.clear()


def cached(job) -> dict | None:
    """The cached result of a simulation job ``(settings, Config)`` (:func:`jobs_of`), or None where it has not run
    in this process."""
    return _CACHE.get(job)


def remember(job, result: dict) -> None:
    """Cache ``result`` as job ``job``'s (a study that knows the result without running it, :mod:`.flip_caps_check`)."""
    _CACHE[job] = result


def settings_of(config: dict, seed: int, scale: Scale) -> StudySettings:
    """The simulation settings of a register configuration and a replicate seed."""
    init, assoc = _TWO_STAGE[config["two-stage"]]
    accel, cap, tol, gap = _EM[config["EM stopping"]]
    run_cap = _EM[DEFAULT_STOP][1] if scale.max_iter is None else min(_EM[DEFAULT_STOP][1], scale.max_iter)
    # the run's cap (times the study's factor) binds every EM; a reading with its own cap ("plain EM, cap 100")
    # keeps it where that is lower
    cap = min(cap, run_cap * scale.cap_factor) if cap < _EM[DEFAULT_STOP][1] else run_cap * scale.cap_factor
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
    if letter in "pq" and scale.cap_factor != 1:
        out = replace(out, max_iter=out.max_iter * scale.cap_factor)
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
    close = sorted(set(close) | {1.0, 3.0})  # Fig 5's curves hold d = 1 and 3 sigma
    heads = c11_separations(config)
    small = [d for d in D if d <= float(config["small separations of C002-6 (sigma)"])]
    d5, T3 = float(config["separation of C002-5 (sigma)"]), int(config["T of the Fig 3a claims"])
    core = (1.0, 2.0, 3.0, 6.0)
    pick = (lambda ds: D) if figures else (lambda ds: [d for d in D if d in ds])
    m1, p1 = c1_point(config)  # C002-1 reads its panel's whole distance axis
    p6, T6 = c6_point(config)
    r = "r" if figures else ""  # the bounds (letter r): the figures draw them; of the claims only C002-15 reads them

    def fig1(p_, m):
        return {d: P(2, d, p_, m, T1, "u" + r) for d in (D if (p_, m) == (p1, m1) else pick(core))}

    g = {
        "1a": {m: fig1(3.0, m) for m in (10, 20)},
        "1b": {m: fig1(1.0, m) for m in (10, 20)},
        "1c": {p_: {d: P(2, d, p_, m1c, 5, "u" + r) for d in pick((1.0, 6.0))} for p_ in (3.0, 5.0)},
        "2": {
            (T, m): {d: P(2, d, p6, m, T, "u" + r) for d in pick(small)}
            for T in sorted({5, 10, *T6} if figures else T6)
            for m in sorted(photons6(config))
        },
        "5": {
            (p_, T): {d5: P(2, d5, p_, 20, T, "u", n=C5_TRIALS * scale.n_trials)}
            for p_ in c5_pair(config)
            for T in (5, 10, 50)
        },
        "3a": {
            p_: {T: P(1, 0.0, p_, 20, T, "uec" + r) for T in (sorted({*scale.fig3_frames, T3}) if figures else (T3,))}
            for p_ in (1.0, 3.0, 5.0)
        },
        "4": {m: {d: P(2, d, pix, m, T4, "ue" + r) for d in D} for m in ((20, 50) if figures else (20,))},
        "5ab": {T: {d: P(2, d, pix, m5, T, "ue" + r) for d in close} for T in (5, 50)},
        "head": {d: P(2, d, pix, m5, 50, "ue") for d in heads},  # C002-11 (at 1 and 3 sigma: Fig 5b's points)
        "head_map": {d: P(2, d, pix, m5, 50, "m") for d in heads},
        "head_known": (
            {d: P(2, d, pix, m5, 50, "k") for d in heads} if config["velocity knowledge"] == "designated" else {}
        ),
        "6": {20: {d: P(2, d, 5.0, 20, T4, "ue" + r) for d in close}},
        "c15": {d: P(2, d, pix, 20, T4, "ur") for d in sorted({c15_close(config), 2.0, 4.0})},
        "good": {p_: P(2, 8.0, p_, int(config.get("m_k of C002-12", 20)), T4, "ue") for p_ in (0.5, 1.0)},
        "7": {
            d: P(2, d, pix, 20, T4, "upq", n=scale.n_iter_trials, variant=fig7_variant(config))
            for d in sorted({min(D), max(D)} | ({2.0} if figures else set()))
        },
    }
    if figures:
        g["ms"] = {d: P(2, d, pix, 20, T4, "s", n=scale.n_iter_trials) for d in (min(D), 1.0)}
        g["w"] = {d: P(2, d, pix, 20, T4, "uw1", n=scale.n_iter_trials) for d in (1.0, 2.0, 4.0)}
        g["bic"] = {d: P(2, d, pix, 20, T4, "b", n=scale.n_iter_trials) for d in D}  # unknown Q (beyond the paper)
    return g, P.asked


def jobs_of(
    config: dict, seed: int, scale: Scale, figures: bool = False, claims=None
) -> list[tuple[StudySettings, Config]]:
    """The simulation jobs ``(settings, single-letter Config)`` of one configuration and seed, without repeats:
    those of the points the ``claims`` read (None: every claim), or with ``figures`` every point of the figures."""
    settings = settings_of(config, seed, scale)
    g, asked = _points(config, scale, figures)
    points = {c: c.algs for c in asked} if figures else needed_letters(config, g, scale.separations, claims)
    out = {}
    for c, letters in points.items():
        for a in letters:
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
        with fork_pool(n_workers) as pool:
            for j, r in zip(todo, pool.map(_run_job, todo, chunksize=1)):
                _CACHE[j] = r
    else:
        for j in todo:
            _CACHE[j] = _run_job(j)


class _Results:
    """``res[c]``: the merged results of the letters of a point that ran (from the cache; a measurement of some claims
    runs only the letters they read, :func:`.claim_values.needed_letters`, and a key of another letter is then
    missing)."""

    def __init__(self, settings: StudySettings, scale: Scale):
        self.settings = settings
        self.scale = scale

    def __getitem__(self, c: Config) -> dict:
        out = {}
        jobs = [(_job_settings(self.settings, a, self.scale, c.q), c._replace(algs=a)) for a in c.algs]
        if not any(j in _CACHE for j in jobs):
            raise KeyError(f"no algorithm of {c} ran")
        for job in (j for j in jobs if j in _CACHE):
            r = _CACHE[job]
            out.update({k: v for k, v in r.items() if k != "timing"})
            out.setdefault("timing", {}).update({k: v for k, v in r["timing"].items() if v})
        return out


def rerun(res, c: Config, letters: str, **variant) -> dict:
    """The algorithms ``letters`` of the point ``c`` of ``res`` (:func:`figure_data`'s results) rerun on the same
    scenes under the settings ``variant`` (e.g. ``max_iter=10**6``; a variant does not enter the scene seed), not
    cached: the merged results of :func:`.simulation.run_config` (errors in sigma, flags, iterations)."""
    out = {}
    for a in letters:
        job = _job_settings(res.settings, a, res.scale, c.q)
        merged = {**dict(c.variant or ()), **variant}  # a point's own variant (e.g. Fig 7's tolerance) is kept
        out.update(run_config(job, c._replace(algs=a, variant=tuple(sorted(merged.items())))))
    return out


def measure_batch(configs, seeds, scale: Scale = Scale(), claims=None) -> list[dict]:
    """:func:`measure` for many configurations at once: their jobs are collected, the missing ones run in
    ``scale.n_workers`` processes, then each configuration's claims are measured. ``claims``: one set of claim
    ids per configuration (None, or None for one configuration: all claims); only the jobs those claims read run,
    and each asked claim's value is the one a measurement of every claim gives, bit for bit."""
    from ...projection import claim_groups
    from .register import DEPENDS, REGISTER

    asked = [None] * len(configs) if claims is None else list(claims)
    if len(asked) != len(configs):
        raise ValueError(f"{len(asked)} claim sets for {len(configs)} configurations")
    # each claim at its configuration projected onto its DEPENDS (a track geometry reaches only the claims that
    # declare it, the other two-object claims keep the paper's parallel tracks): one group per distinct projection
    default = REGISTER.default()
    groups = [claim_groups(c, k, DEPENDS, default) for c, k in zip(configs, asked)]
    jobs = [j for gs, s in zip(groups, seeds) for c, k in gs for j in jobs_of(c, s, scale, claims=k)]
    run_jobs(jobs, scale.n_workers)
    out = []
    for gs, s in zip(groups, seeds):
        out.append({})
        for c, k in gs:
            g, _ = _points(c, scale)
            res = _Results(settings_of(c, s, scale), scale)
            out[-1].update(measure_claims(c, g, res, int(s), scale.n_bootstrap, scale.separations, k))
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


def measure(config: dict, seed: int, scale: Scale = Scale(), claims=None) -> dict:
    """One full-size replicate of the study at ``config`` (every register entry present) with all random draws
    from ``seed``: ``{claim id: measured}`` for the ``claims`` asked (a set of claim ids; None: all)."""
    return measure_batch([config], [seed], scale, None if claims is None else [claims])[0]


def figure_data(config: dict, seed: int, scale: Scale = Scale()) -> tuple[dict, _Results]:
    """The simulation points (named groups of :class:`Config`) and their results at ``config`` and ``seed``, for
    the figures (runs what is not cached)."""
    run_jobs(jobs_of(config, seed, scale, figures=True), scale.n_workers)
    return _points(config, scale, figures=True)[0], _Results(settings_of(config, seed, scale), scale)


#: The paper's claims: statement and the paper's value.
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
