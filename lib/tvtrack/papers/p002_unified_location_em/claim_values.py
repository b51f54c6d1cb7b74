"""What each claim of paper 002 computes from the simulated points: the statistics and one function per claim.

:func:`measure_claims` turns the results of a configuration's simulation points (:func:`.study._points`, read
through ``res[Config]``) into ``{claim id: measured}`` for the claims asked. Each claim draws its bootstrap
resamples from its own stream (``seed_sequence(seed, ("bootstrap", claim id))``), so a claim's interval is the
same whether it is measured alone or with the others (``measure(config, seed, claims=...)``), and :data:`NEEDS`
names the simulation points each claim reads, so a subset runs only its own jobs.

Units: sigma (PSF standard deviation) for lengths, frames for time.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tvtrack.estimate import Estimate
from tvtrack.measured import fold_about
from tvtrack.montecarlo import ratio_ci
from .readings import (
    COORDINATE6,
    FIG1_PANEL,
    T_DEPENDENCE6,
    TRIMMED,
    c1_point,
    c10_close,
    c5_pair,
    c11_separations,
    c6_point,
    c15_close,
    photons6,
)
from . import gain_coverage as _gc
from . import ratio_coverage as _rc
from .gain_coverage import stated
from .summaries import SPREADS, bootstrap_groups, mse_sum, position_errors, variance_ratio_ci, variance_sum
from .sim_config import seed_sequence
from ._spread_kernel import variance_sum_rows

__all__ = [
    "errors",
    "spread_sum",
    "spread_total",
    "mean_log_gain",
    "frame_dependence",
    "gain_interval_coverage",
    "efficiency",
    "gain",
    "exp_estimate",
    "scaled",
    "fold_change",
    "coarser_pixels",
    "epoch_and_spread",
    "NEEDS",
    "LETTERS",
    "needed_points",
    "needed_letters",
    "measure_claims",
]


# -- statistics -----------------------------------------------------------------------------------------------


def errors(r: dict, alg: str, epoch: str = "first") -> np.ndarray:
    """Per-trial errors (n, 2Q) of one algorithm at one epoch (``first``, ``mid``, ``last``; sigma) or of its
    velocities (``velocity``; sigma/frame)."""
    return position_errors(r, alg, epoch)


def spread_sum(e, statistic: str = "variance") -> Estimate:
    """The summed spread of errors (n, k): variance sum, MSE sum, or (``statistic="trimmed"``) the 10 %-trimmed
    variance sum with a percentile bootstrap interval (all in sigma^2)."""
    if statistic == "trimmed":
        rng = np.random.default_rng(seed_sequence(0, ("trimmed spread",)))
        return bootstrap_groups([np.asarray(e, float)], SPREADS["trimmed_variance"], rng, 2000)
    return mse_sum(e) if statistic == "MSE" else variance_sum(e)


def _statistic(config: dict) -> str:  # the register's statistic; "trimmed" where "gross errors" drops the largest
    return "trimmed" if config.get("gross errors", "kept") == TRIMMED else config["statistic"]


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


def spread_total(e, spread: str = "variance"):
    """The spread of position errors summed over the coordinates, per row (no interval).

    Parameters
    ----------
    e : numpy.ndarray
        Errors (R, n_trials, n_coordinates), in sigma.
    spread : str
        ``"variance"`` (over the trials, ``ddof=1``) or another key of ``SPREADS`` (``"mse"``,
        ``"trimmed_variance"``, ``"median_square"``).

    Returns
    -------
    numpy.ndarray
        The summed spread (R,), sigma^2.
    """
    return variance_sum_rows(e) if spread == "variance" else SPREADS[spread](e)


def mean_log_gain(pairs_hi, pairs_lo, rng, n_bootstrap, spread: str = "variance") -> Estimate:
    """The ratio of two geometric-mean gains: exp(mean log rho over the ``hi`` groups - mean log rho over the ``lo``
    groups), rho a group's spread ratio numerator / denominator.

    Parameters
    ----------
    pairs_hi, pairs_lo : list of numpy.ndarray
        One array per point, the paired [numerator | denominator] errors side by side on the last axis (sigma);
        rows are resampled jointly, groups independently.
    rng : numpy.random.Generator
        The seeded generator of the bootstrap.
    n_bootstrap : int
        Bootstrap resamples.
    spread : str
        The spread read (:func:`spread_total`).

    Returns
    -------
    Estimate
        The gain ratio (unit-free) with its bootstrap interval.
    """
    k = len(pairs_hi)

    def stat(*g):
        def mlog(h):
            return np.mean(
                [
                    np.log(
                        spread_total(x[..., : x.shape[-1] // 2], spread)
                        / spread_total(x[..., x.shape[-1] // 2 :], spread)
                    )
                    for x in h
                ],
                axis=0,
            )

        return mlog(g[:k]) - mlog(g[k:])

    e = bootstrap_groups(list(pairs_hi) + list(pairs_lo), stat, rng, n_bootstrap)
    return exp_estimate(stated(e, "log gain", min(k, len(pairs_lo)), spread))


def frame_dependence(groups_hi, groups_lo, rng, n_bootstrap, spread: str = "variance", gap: bool = False) -> Estimate:
    """C002-6's contrast: the mean frame dependence of the ``hi`` groups minus that of the ``lo`` groups, a group's
    dependence |ln(u / v)| (or, ``gap``, |u - v|), u and v the spreads of its two halves.

    Parameters
    ----------
    groups_hi, groups_lo : list of numpy.ndarray
        One array per separation, the errors at the fewer and the more frames side by side on the last axis (sigma);
        rows are resampled jointly, groups independently.
    rng : numpy.random.Generator
        The seeded generator of the bootstrap.
    n_bootstrap : int
        Bootstrap resamples.
    spread : str
        The spread read (:func:`spread_total`).
    gap : bool
        The absolute dependence |u - v| (sigma^2) instead of the relative |ln(u / v)|.

    Returns
    -------
    Estimate
        The contrast (unit-free, sigma^2 under ``gap``) with its bootstrap interval; the relative one states its
        measured coverage (:mod:`.gain_coverage`).
    """
    k = len(groups_hi)

    def dep(a):
        u, v = spread_total(a[..., : a.shape[-1] // 2], spread), spread_total(a[..., a.shape[-1] // 2 :], spread)
        return np.abs(u - v) if gap else np.abs(np.log(u / v))

    def stat(*gr):
        return np.mean([dep(a) for a in gr[:k]], axis=0) - np.mean([dep(a) for a in gr[k:]], axis=0)

    e = bootstrap_groups(list(groups_hi) + list(groups_lo), stat, rng, n_bootstrap)
    return e if gap else stated(e, "frame dependence", min(k, len(groups_lo)), spread)


def gain_interval_coverage(
    statistic: str,
    case: str,
    n: int,
    groups: int,
    experiments: int = _gc.N_EXPERIMENTS,
    n_bootstrap: int = _gc.SIM_BOOTSTRAP,
    correlation: float = 0.0,
) -> float:
    """The share of the first ``experiments`` simulated experiments of ``case`` (``n`` trials a group, ``groups``
    groups a side, :func:`.gain_coverage.draw_groups`) whose interval of ``statistic`` (``"log gain"``:
    :func:`mean_log_gain`, ``"frame dependence"``: :func:`frame_dependence`, ``n_bootstrap`` resamples) holds the
    true value: what :data:`.gain_coverage.COVERAGE` tabulates."""
    fn = mean_log_gain if statistic == "log gain" else frame_dependence
    truth, hits = _gc.STATISTICS[statistic], 0
    for r in range(experiments):
        hi, lo = _gc.draw_groups(case, n, r, groups, correlation)
        e = fn(hi, lo, np.random.default_rng([_rc.SEED, n, groups, r]), n_bootstrap)
        hits += e.ci_low <= truth <= e.ci_high
    return hits / experiments


def efficiency(e, bound: float, statistic: str) -> Estimate:
    """An estimator's efficiency: its spread over a bound (1 at the bound).

    Parameters
    ----------
    e : numpy.ndarray
        Position errors (n_trials, n_coordinates), in sigma.
    bound : float
        The bound on the summed variance (sigma^2).
    statistic : str
        The spread read: variance or MSE sum (:func:`spread_sum`).

    Returns
    -------
    Estimate
        The ratio (unit-free) with its interval.
    """
    return scaled(spread_sum(e, statistic), 1.0 / bound)


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


# -- the claims -----------------------------------------------------------------------------------------------


@dataclass
class _Ctx:
    """What every claim function reads: the configuration, its point groups ``g``, the results ``res[Config]``,
    the claim's bootstrap stream and the readings of the epoch and the statistic."""

    config: dict
    g: dict
    res: object
    rng: np.random.Generator
    B: int
    D: list

    def __post_init__(self):
        self.ep, self.st = self.config["epoch"], _statistic(self.config)
        self.sp = _spread(self.st)  # the log gains and C002-6's spreads read the same statistic as the gains

    def ula(self, c):
        return errors(self.res[c], "ula", self.ep)

    def gain(self, num, den, paired=True, sd=False):
        """A ratio of spreads of the statistic read; ``sd``: its square root (a ratio of standard deviations)."""
        return variance_ratio_ci(num, den, self.rng, self.B, paired=paired, spread=self.sp, sqrt=sd)

    def log_gain(self, hi, lo):
        return mean_log_gain(hi, lo, self.rng, self.B, self.sp)

    def r_m(self, key, d):
        return self.ula(self.g[key][10][d]), self.ula(self.g[key][20][d])

    def x1(self, pix, alg):
        return position_errors(self.res[self.g["3a"][pix][int(self.config["T of the Fig 3a claims"])]], alg, self.ep)[
            :, :1
        ]

    def rho(self, c, sd=False):
        r = self.res[c]
        return self.gain(errors(r, "em", self.ep), errors(r, "ula", self.ep), sd=sd)

    def side(self, c):
        r = self.res[c]
        return np.hstack([errors(r, "em", self.ep), errors(r, "ula", self.ep)])


def epoch_and_spread(config: dict) -> tuple[str, str]:
    """The epoch (:func:`errors`' ``epoch``) and the spread (:func:`spread_total`'s) the gains read at ``config``."""
    return config["epoch"], _spread(_statistic(config))


def _small6(config: dict, D) -> list:
    return [d for d in D if d <= float(config["small separations of C002-6 (sigma)"])]


def _c1(x: _Ctx):
    m1, p1 = c1_point(x.config)
    return [spread_sum(x.ula(x.g[FIG1_PANEL[p1]][m1][d]), x.st) for d in x.D]


def _c2(x: _Ctx):
    far, near = x.r_m("1a", 6.0), x.r_m("1a", 1.0)
    return {"weakens": x.log_gain([np.hstack(far)], [np.hstack(near)]), "far apart": x.gain(*far, paired=False)}


_DS3 = (1.0, 2.0, 3.0, 6.0)


def _c3(x: _Ctx):
    return x.log_gain([np.hstack(x.r_m("1b", d)) for d in _DS3], [np.hstack(x.r_m("1a", d)) for d in _DS3])


def _c4(x: _Ctx):
    loss = {p_: np.hstack([x.ula(x.g["1c"][p_][1.0]), x.ula(x.g["1c"][p_][6.0])]) for p_ in (5.0, 3.0)}
    return x.log_gain([loss[5.0]], [loss[3.0]])


def _c5(x: _Ctx):
    d5 = float(x.config["separation of C002-5 (sigma)"])
    hi5, lo5 = c5_pair(x.config)
    g5 = x.g["5"]
    return [x.gain(x.ula(g5[(hi5, T)][d5]), x.ula(g5[(lo5, T)][d5]), paired=False) for T in (5, 10, 50)]


def _c6(x: _Ctx):
    small = _small6(x.config, x.D)
    cols = COORDINATE6[x.config.get("coordinate of C002-6", "both")]
    t_lo, t_hi = c6_point(x.config)[1]
    gap = x.config.get("T dependence of C002-6", T_DEPENDENCE6[0]) == T_DEPENDENCE6[1]

    def rt(m):
        g2 = x.g["2"]
        return [np.hstack([x.ula(g2[(t_lo, m)][d])[:, cols], x.ula(g2[(t_hi, m)][d])[:, cols]]) for d in small]

    m_hi, m_lo = photons6(x.config)
    return frame_dependence(rt(m_hi), rt(m_lo), x.rng, x.B, x.sp, gap)


def _pc(config: dict) -> float:
    return float(config["coarse Delta of C002-7, C002-8 (sigma)"])


def _c7(x: _Ctx):
    pc = _pc(x.config)
    return {
        "fine pixels": x.gain(x.x1(1.0, "em"), x.x1(1.0, "ula")),
        "coarse pixels": x.gain(x.x1(pc, "em"), x.x1(pc, "ula")),
    }


def _c8(x: _Ctx):
    pc = _pc(x.config)
    return {
        "worse than fine pixels": x.gain(x.x1(pc, "ula"), x.x1(1.0, "ula"), paired=False),
        "better than the marks": x.gain(x.x1(pc, "ula"), x.x1(pc, "em")),
    }


def _c9(x: _Ctx):
    p9 = float(x.config["Delta of the C002-9 order (sigma)"])
    return {
        "centre-of-region >= iterative marks": x.gain(x.x1(p9, "cr"), x.x1(p9, "em")),
        "iterative marks >= ULA": x.gain(x.x1(p9, "em"), x.x1(p9, "ula")),
    }


def coarser_pixels(config: dict, g: dict, res, rng: np.random.Generator, n_bootstrap: int) -> Estimate:
    """C002-10's part "coarser pixels" at ``config``: the geometric mean of rho over the close separations at Fig 6b's
    pixels over that at Fig 4a's (unit-free; interval from ``n_bootstrap`` resamples of ``rng``) from ``g``, ``res``."""
    x = _Ctx(config, g, res, rng, n_bootstrap, [])
    close = c10_close(config)
    return x.log_gain([x.side(g["6"][20][d]) for d in close], [x.side(g["4"][20][d]) for d in close])


def _c10(x: _Ctx):
    close, g = c10_close(x.config), x.g
    return {
        "closer": [x.rho(g["4"][20][d]) for d in x.D],
        "coarser pixels": coarser_pixels(x.config, g, x.res, x.rng, x.B),
        "more frames": x.log_gain([x.side(g["5ab"][50][d]) for d in close], [x.side(g["5ab"][5][d]) for d in close]),
    }


def _c11(x: _Ctx):
    use_map = x.config["ULA"] == "MAP (designation prior)"
    known = x.config["velocity knowledge"] == "designated"
    sd = x.config["accuracy ratio of C002-11"] == "SD"  # "x4 difference in accuracy" as a ratio of SDs

    def head(d):
        c = x.g["head"][d]
        if use_map:
            u = errors(x.res[x.g["head_map"][d]], "map", x.ep)
        elif known:
            u = errors(x.res[x.g["head_known"][d]], "ula_vd", x.ep)
        else:
            return x.rho(c, sd)
        return x.gain(errors(x.res[c], "em_vd" if known else "em", x.ep), u, sd=sd)

    d1, d3 = c11_separations(x.config)  # 1 and 3 sigma, or 1 and 3 pixels under the pixel reading
    return {"d = 1 sigma (paper x4.5)": head(d1), "d = 3 sigma (paper x4)": head(d3)}


def _c12(x: _Ctx):
    return {f"Delta = {p_:g} sigma": x.rho(c) for p_, c in x.g["good"].items()}


def _iterations(x: _Ctx):
    it = {d: x.res[c] for d, c in x.g["7"].items()}
    return it, min(it), max(it)


def fold_change(ratio: Estimate) -> Estimate:
    """A positive ratio's fold change from 1 either way, ``max(q, 1 / q)``: a dependence whose direction is not
    stated (C002-13) is one number that grows with the dependence whichever way it runs.

    The ratio's interval widened where its coverage falls short and folded by :func:`tvtrack.measured.fold_about`:
    mapped end by end, from 1 where it holds 1 (no measurable dependence); the estimate keeps the signed ratio,
    which replicates pool before they fold.
    """
    return fold_about(ratio, 1.0)


def _c13(x: _Ctx):
    it, lo, hi = _iterations(x)
    return fold_change(ratio_ci(it[lo]["plain_iter"], it[hi]["plain_iter"], paired=False))


def _c14(x: _Ctx):
    it, lo, hi = _iterations(x)
    T4 = int(x.config["T of Figs 4, 6, 7"])
    ula_work = np.concatenate([it[d]["plain_iter"] * T4 for d in (lo, hi)])
    marks_work = np.concatenate([it[d]["em_plain_iter"] for d in (lo, hi)])
    return ratio_ci(ula_work, marks_work)


def _c15(x: _Ctx) -> dict:
    """Efficiency of the ULA: its spread over the bound at very close and resolved separations, and for the
    velocities ("position and motion parameters of very close objects", conclusions). The bound is the initial
    positions' (epoch "first" whatever the register's), and a trimmed spread is no bound's (the register's
    statistic as read, untrimmed)."""
    config, st = x.config, x.config["statistic"]
    use_bayes = config["bound"] == "van Trees (designation prior)"
    key_pos, key_vel = ("bcrb_pos", "bcrb_vel") if use_bayes else ("crb_pos", "crb_vel")
    parts = {}
    cs, close = x.g["c15"], c15_close(config)
    for d, name in ((close, "very close"), (2.0, "d = 2 sigma"), (4.0, "d = 4 sigma")):
        r = x.res[cs[d]]
        parts[name] = efficiency(errors(r, "ula", "first"), r[key_pos], st)
    r = x.res[cs[close]]
    parts["velocities, very close"] = efficiency(position_errors(r, "ula", "velocity"), r[key_vel], st)
    return parts


#: ``{claim id: function of the claim context}``.
_MEASURES = {
    "C002-1": _c1,
    "C002-2": _c2,
    "C002-3": _c3,
    "C002-4": _c4,
    "C002-5": _c5,
    "C002-6": _c6,
    "C002-7": _c7,
    "C002-8": _c8,
    "C002-9": _c9,
    "C002-10": _c10,
    "C002-11": _c11,
    "C002-12": _c12,
    "C002-13": _c13,
    "C002-14": _c14,
    "C002-15": _c15,
}


def _fig3(config: dict, g: dict, pixels) -> list:
    T3 = int(config["T of the Fig 3a claims"])
    return [g["3a"][p_][T3] for p_ in pixels]


def _head(config: dict, g: dict, D=None) -> list:
    extra = g["head_map"] if config["ULA"] == "MAP (designation prior)" else {}
    if not extra and config["velocity knowledge"] == "designated":
        extra = g["head_known"]
    return list(g["head"].values()) + list(extra.values())


#: ``{claim id: function (config, point groups g, separations D) -> the Configs the claim reads}``.
NEEDS = {
    "C002-1": lambda c, g, D: [g[FIG1_PANEL[c1_point(c)[1]]][c1_point(c)[0]][d] for d in D],
    "C002-2": lambda c, g, D: [g["1a"][m][d] for m in (10, 20) for d in (6.0, 1.0)],
    "C002-3": lambda c, g, D: [g[k][m][d] for k in ("1a", "1b") for m in (10, 20) for d in _DS3],
    "C002-4": lambda c, g, D: [g["1c"][p_][d] for p_ in (5.0, 3.0) for d in (1.0, 6.0)],
    "C002-5": lambda c, g, D: [p for row in g["5"].values() for p in row.values()],
    "C002-6": lambda c, g, D: [p for row in g["2"].values() for p in row.values()],
    "C002-7": lambda c, g, D: _fig3(c, g, (1.0, _pc(c))),
    "C002-8": lambda c, g, D: _fig3(c, g, (1.0, _pc(c))),
    "C002-9": lambda c, g, D: _fig3(c, g, (float(c["Delta of the C002-9 order (sigma)"]),)),
    "C002-10": lambda c, g, D: (
        [g["4"][20][d] for d in D] + [g[k][s][d] for k, s in (("6", 20), ("5ab", 50), ("5ab", 5)) for d in c10_close(c)]
    ),
    "C002-11": _head,
    "C002-12": lambda c, g, D: list(g["good"].values()),
    "C002-13": lambda c, g, D: list(g["7"].values()),
    "C002-14": lambda c, g, D: list(g["7"].values()),
    "C002-15": lambda c, g, D: list(g["c15"].values()),
}


def _c11_letters(config: dict) -> str:
    """C002-11's algorithms: the marks with the ULA, or with its MAP or known-velocity twin instead (then the ULA's
    letter of the headline points is not read)."""
    if config["ULA"] == "MAP (designation prior)" or config["velocity knowledge"] == "designated":
        return "emk"
    return "ue"


#: ``{claim id: function (config) -> the algorithm letters the claim reads of its points}`` where it reads fewer than
#: its points hold (the others read every letter): C002-7 and -8 compare the iterative marks with the ULA (not the
#: centre of region), C002-13 counts the plain ULA's steps and C002-14 those and the plain marks'.
LETTERS = {
    "C002-7": lambda c: "ue",
    "C002-8": lambda c: "ue",
    "C002-11": _c11_letters,
    "C002-13": lambda c: "p",
    "C002-14": lambda c: "pq",
}


def needed_points(config: dict, g: dict, D, claims=None) -> list:
    """The simulation points (:class:`~.simulation.Config`) that the ``claims`` (None: all) read, without repeats,
    in the claims' order."""
    asked = _MEASURES if claims is None else [c for c in _MEASURES if c in claims]
    return list(dict.fromkeys(p for cid in asked for p in NEEDS[cid](config, g, list(D))))


def needed_letters(config: dict, g: dict, D, claims=None) -> dict:
    """``{point: the algorithm letters of it that the claims (None: all) read}`` (:data:`LETTERS`), the points in
    :func:`needed_points`' order and each one's letters in its own order; a point none of whose letters is read is
    left out. The algorithms of a point run as separate jobs on the same scenes, so leaving one out changes no
    other's numbers."""
    asked = _MEASURES if claims is None else [c for c in _MEASURES if c in claims]
    read: dict = {}
    for cid in asked:
        keep = LETTERS[cid](config) if cid in LETTERS else None
        for p in NEEDS[cid](config, g, list(D)):
            read.setdefault(p, set()).update(a for a in p.algs if keep is None or a in keep)
    return {p: "".join(a for a in p.algs if a in s) for p, s in read.items() if s}


def measure_claims(config: dict, g: dict, res, seed: int, n_bootstrap: int, D, claims=None) -> dict:
    """``{claim id: measured}`` of one configuration for the ``claims`` asked (None: all; see the notebook for
    each rule). Each claim draws from its own bootstrap stream, so its value does not depend on which others are
    asked."""
    out = {}
    for cid, fn in _MEASURES.items():
        if claims is None or cid in claims:
            rng = np.random.default_rng(seed_sequence(seed, ("bootstrap", cid)))
            out[cid] = fn(_Ctx(config, g, res, rng, n_bootstrap, list(D)))
    return out


if __name__ == "__main__":  # prints gain_coverage.COVERAGE (several CPU minutes)
    for _stat in _gc.STATISTICS:
        for _size in _gc.COVERAGE[_stat]:
            _cov = ", ".join(f"{gain_interval_coverage(_stat, c, *_size):.3f}" for c in _rc.CASES)
            print(f"    {_stat!r} {_size}: ({_cov}),", flush=True)
