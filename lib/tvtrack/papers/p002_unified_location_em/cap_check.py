"""Does the EM iteration cap matter? A study beyond the paper, at Fig 6b's configuration (Delta = 5 sigma, m_k = 20).

There the two-stage's per-frame marks reach the EM iteration cap (``max_iter`` of the run) in some frame of a large
share of the trials (:func:`.extras.failure_rates`). :func:`cap_check` reruns the points that Fig 6b and the claims
reading it compare, on the same scenes (a settings variant does not enter the scene seed,
:func:`.sim_config.scene_key`) with a cap :data:`CAP_FACTOR` times larger, and measures what that changes, paired on
the same trials: the two-stage's variance sum, the gain rho and C002-10's part "coarser pixels" (with the verdict its
rule gives at each cap). :func:`cap_paragraph` words the result. A trial that never reached the cap gives the same
estimates bit for bit at the larger cap (an EM trial's iterates do not depend on the other trials, and a SQUAREM cycle
reads only the current state), so only the capped trials change.

Draws: the bootstrap streams are ``numpy.random.default_rng([seed, STREAM, k])``, none of the claims'; the reruns
are not cached (:mod:`.study`'s cache holds what the claims read, unchanged).

Units: sigma (PSF standard deviation) for lengths, sigma^2 for variance sums; rho and the part are unit-free.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from tvtrack.counts import proportion_ci
from tvtrack.estimate import Estimate
from tvtrack.measured import calibrated, is_undecided

from . import claim_values as cv
from .claims import RULES
from .gain_coverage import coverage_note
from .ratio_coverage import ratio_coverage_note
from .readings import c10_close
from .sim_config import base
from .study import rerun
from .summaries import bootstrap_groups

__all__ = [
    "CAP_FACTOR",
    "STREAM",
    "at_larger_cap",
    "paired_change",
    "cap_check",
    "cap_paragraph",
    "cap_metrics",
]

#: The larger cap is this many times the run's (5000 -> 1e6 at the paper profile, 100 -> 20000 at the smoke profile).
CAP_FACTOR = 200
#: The study's own bootstrap streams: ``default_rng([seed, STREAM, k])``.
STREAM = 6002
_PART = "coarser pixels"  # the part of C002-10 that reads Fig 6b's points


def at_larger_cap(res, c, letters: str, cap: int) -> dict:
    """The algorithms ``letters`` of the point ``c`` rerun with the EM iteration cap ``cap`` on the same scenes.

    Parameters
    ----------
    res : study results
        ``res[c]`` and the ``settings`` and ``scale`` the point ran under (:func:`.study.figure_data`).
    c : Config
        The simulation point.
    letters : str
        Algorithm letters (:data:`.sim_config.ALGORITHMS`), e.g. ``"ue"``.
    cap : int
        The EM iteration cap of the rerun (every EM of the letters: the ULA, each frame's mark).

    Returns
    -------
    dict
        The merged results of :func:`.simulation.run_config` (errors in sigma, flags, iterations), not cached.
    """
    return rerun(res, c, letters, max_iter=int(cap))


def paired_change(default, larger, statistic, rng, n_bootstrap: int) -> Estimate:
    """``statistic(larger) - statistic(default)`` with a percentile bootstrap interval, each point's trials
    resampled jointly across the two caps (points independently).

    Parameters
    ----------
    default, larger : list of ndarray
        One array (n_g, k_g) per point: per-trial values at the default and at the larger cap, same trials.
    statistic : callable
        ``statistic(*arrays)`` with arrays (B, n_g, k_g), one per point, returns (B,).
    rng : numpy.random.Generator
        The study's bootstrap stream.
    n_bootstrap : int
        Resamples.

    Returns
    -------
    Estimate
        The change (the statistic's unit); exactly 0 with the interval [0, 0] where no trial differs.
    """
    groups = [np.hstack([a, b]) for a, b in zip(default, larger)]

    def diff(*gs):
        half = [g.shape[-1] // 2 for g in gs]
        return statistic(*[g[..., h:] for g, h in zip(gs, half)]) - statistic(*[g[..., :h] for g, h in zip(gs, half)])

    return bootstrap_groups(groups, diff, rng, n_bootstrap)


def proxied(e: Estimate, note: str) -> Estimate:
    """A paired change's interval as a rule would read it: its own coverage is not measured, so it states the
    coverage measured for this package's cluster bootstrap of the nearest statistic (``note``, e.g.
    :func:`.ratio_coverage.ratio_coverage_note`) and is widened to 95 % where that falls short
    (:func:`tvtrack.measured.calibrated`); an interval of no width (nothing changed) stays as it is."""
    if e.ci_low == e.ci_high:
        return e
    stated = replace(e, method=f"{e.method}; {note}, taken for this paired change (its own not measured)")
    return calibrated(stated, difference=True)  # a change may reach 0: stretched on the linear scale


def _rho(x, sp: str = "variance"):
    """rho per resample of the side-by-side [two-stage | ULA] errors ``x`` (B, n, 2k), spread ``sp``."""
    k = x.shape[-1] // 2
    return cv.spread_total(x[..., :k], sp) / cv.spread_total(x[..., k:], sp)


def _coarser(n_close: int, sp: str):
    """C002-10's "coarser pixels" statistic per resample of side-by-side groups, the ``n_close`` 5-sigma ones
    first: exp(mean log rho of those - mean log rho of the others)."""

    def stat(*gs):
        logs = np.array([np.log(_rho(g, sp)) for g in gs])
        return np.exp(logs[:n_close].mean(axis=0) - logs[n_close:].mean(axis=0))

    return stat


def _share(r: dict, alg: str) -> Estimate:
    """Share of trials in which ``alg`` (``"em"``: the marks, in some frame; ``"ula"``) reached its cap."""
    return proportion_ci(int(r[f"{alg}_flags"][:, 2].sum()), len(r[alg]))


def _point(r0: dict, r1: dict, ep: str, sp: str, rngs, n_bootstrap: int) -> dict:
    """What the larger cap changes at one point (results ``r0`` at the default cap, ``r1`` at the larger; epoch
    ``ep``, spread ``sp``): cap-hit shares at both caps, the trials whose estimates change (and of those the ones
    that had not reached the default cap), the two-stage's variance sum and rho (values at both caps, sigma^2 and
    unit-free) and their paired changes (``rngs``: two bootstrap streams)."""
    e0, e1, u0, u1 = (cv.errors(r, a, ep) for r, a in ((r0, "em"), (r1, "em"), (r0, "ula"), (r1, "ula")))
    capped = r0["em_flags"][:, 2] | r0["ula_flags"][:, 2]
    changed = ~(np.all(e0 == e1, axis=1) & np.all(u0 == u1, axis=1))
    s0, s1 = np.hstack([e0, u0]), np.hstack([e1, u1])

    def var(e):
        return cv.spread_total(e, sp)

    def rho(x):
        return _rho(x, sp)

    return {
        "two-stage cap hit": _share(r0, "em"),
        "ULA cap hit": _share(r0, "ula"),
        "two-stage cap hit, larger cap": _share(r1, "em"),
        "ULA cap hit, larger cap": _share(r1, "ula"),
        "changed trials": int(changed.sum()),
        "changed trials not capped": int((changed & ~capped).sum()),
        "two-stage variance": (float(var(e0[None])[0]), float(var(e1[None])[0])),
        "two-stage variance change": proxied(
            paired_change([e0], [e1], var, rngs[0], n_bootstrap), ratio_coverage_note(len(e0))
        ),
        "rho": (float(rho(s0[None])[0]), float(rho(s1[None])[0])),
        "rho change": proxied(paired_change([s0], [s1], rho, rngs[1], n_bootstrap), ratio_coverage_note(len(s0))),
    }


def cap_check(config: dict, g: dict, res, seed: int, n_bootstrap: int, factor: int = CAP_FACTOR) -> dict:
    """The cap-hit shares at Fig 6b's points and what a cap ``factor`` times larger changes, on the same trials.

    Parameters
    ----------
    config : dict
        The register configuration the points ran at (the notebook's default; its epoch and statistic are read).
    g, res
        :func:`.study.figure_data`'s points and results: ``g["6"][20]`` and ``g["4"][20]`` at C002-10's close
        separations are read and rerun (algorithms ``u`` and ``e``).
    seed : int
        The notebook's seed (the bootstrap streams derive from it).
    n_bootstrap : int
        Bootstrap resamples.
    factor : int
        The larger cap over the run's.

    Returns
    -------
    dict
        ``cap``, ``larger cap`` (EM iterations), ``n`` (trials a point), ``T`` (frames), ``pix`` (Delta / sigma),
        ``m`` (photons per object and frame), ``close`` (d / sigma);
        ``points``: ``{d / sigma: :func:`_point`'s dict}`` at Fig 6b; ``claims``: the claim ids that read Fig 6b's
        points; ``part``: C002-10's "coarser pixels" (``default``, ``larger``: Estimates, ``change``: the paired
        change, ``verdicts``: its rule's at each cap); ``cpu_s``: the study's CPU seconds.
    """
    t0 = time.process_time()
    cap = res.settings.max_iter  # every EM's (the scale's cap already applied)
    big = int(factor) * cap
    close = c10_close(config)
    ep, sp = cv.epoch_and_spread(config)
    pts = {k: {d: g[k][20][d] for d in close} for k in ("6", "4")}
    more = {c: at_larger_cap(res, c, "ue", big) for row in pts.values() for c in row.values()}
    rngs = [np.random.default_rng([seed, STREAM, k]) for k in range(2 * len(close) + 2)]
    points = {}
    for i, (d, c) in enumerate(pts["6"].items()):
        points[d] = _point(res[c], more[c], ep, sp, rngs[2 * i : 2 * i + 2], n_bootstrap)
    part = {  # the claim's own statistic at each cap, on common resamples (two copies of one stream)
        k: cv.coarser_pixels(config, g, r, np.random.default_rng([seed, STREAM, len(rngs)]), n_bootstrap)
        for k, r in (("default", res), ("larger", more))
    }
    sides = [
        [
            np.hstack([cv.errors(r[c], "em", ep), cv.errors(r[c], "ula", ep)])
            for row in pts.values()
            for c in row.values()
        ]
        for r in (res, more)
    ]
    change = paired_change(*sides, _coarser(len(close), sp), rngs[-1], n_bootstrap)
    part["change"] = proxied(change, coverage_note("log gain", change.n, len(close)))
    rule = RULES["C002-10"].parts[_PART]
    part["verdicts"] = (rule.decide(part["default"]), rule.decide(part["larger"]))
    part["default"], part["larger"] = calibrated(part["default"]), calibrated(part["larger"])  # as the rule read them
    return {
        "cap": cap,
        "larger cap": big,
        "n": len(res[pts["6"][close[0]]]["em"]),
        "T": pts["6"][close[0]].T,
        "pix": pts["6"][close[0]].pix,
        "m": pts["6"][close[0]].m,
        "close": close,
        "points": points,
        "claims": _reading(config, g, pts["6"].values(), res.scale.separations),
        "part": part,
        "cpu_s": time.process_time() - t0,
    }


def _reading(config: dict, g: dict, points, separations) -> list:
    """The claim ids (:data:`.claim_values.NEEDS`, on the figures' points ``g``) that read any of ``points``,
    compared without their algorithm letters (the figures' points add the bounds' letter)."""
    mine = {base(c) for c in points}
    return [cid for cid, need in cv.NEEDS.items() if mine & {base(p) for p in need(config, g, list(separations))}]


def _pct(e: Estimate) -> str:
    return f"{e.value:.1%} [{e.ci_low:.1%}, {e.ci_high:.1%}]"


def _signed(e: Estimate) -> str:
    """A change with its interval, signed; "exactly 0" where nothing changed."""
    if e.value == e.ci_low == e.ci_high == 0:
        return "exactly 0"
    return f"{e.value:+.3g} [{e.ci_low:+.3g}, {e.ci_high:+.3g}]"


def _side(e: Estimate) -> str:
    """``"up"`` / ``"down"`` where the 95 % interval of a change excludes 0 (above / below), else ``"none"`` (also
    where it cannot decide: :func:`tvtrack.measured.is_undecided`, e.g. a coverage not measured at its size)."""
    if not (np.isfinite(e.ci_low) and np.isfinite(e.ci_high)) or (e.ci_low != e.ci_high and is_undecided(e)):
        return "none"
    return "up" if e.ci_low > 0 else "down" if e.ci_high < 0 else "none"


def _at(ds) -> str:
    """``"d = 1, 2 and 3 sigma"``."""
    return "d = " + _and(f"{d:g}" for d in ds) + " sigma"


def _and(items) -> str:
    """``"a, b and c"``."""
    items = list(items)
    return ", ".join(items[:-1]) + " and " + items[-1] if len(items) > 1 else items[0]


def _per_d(points: dict, key: str) -> str:
    """``"x% [lo, hi] of the trials at d = 1 sigma, ... and ... at d = 3 sigma"``."""
    shares = [
        f"{_pct(p[key])}{' of the trials' * (i == 0)} at d = {d:g} sigma" for i, (d, p) in enumerate(points.items())
    ]
    return _and(shares)


def _changes(points: dict, key: str, values: str, unit: str) -> str:
    words = {"up": "up", "down": "down", "none": "no measurable change"}
    return _and(
        f"{_signed(p[key])}{unit} at d = {d:g} sigma ({p[values][0]:.3g} -> {p[values][1]:.3g}: {words[_side(p[key])]})"
        for d, p in points.items()
    )


def _gain_sentence(points: dict) -> str:
    """What the default cap does to the ULA's gain, by the side of each separation's paired change of rho."""
    by = {w: [d for d, p in points.items() if _side(p["rho change"]) == w] for w in ("up", "down", "none")}
    what = {
        "up": "understates the ULA's gain rho (rho rises when the EMs run further)",
        "down": "overstates the ULA's gain rho (rho falls when the EMs run further)",
        "none": "leaves the gain rho without a measurable change",
    }
    return "So the default cap " + _and(f"{what[w]} at {_at(ds)}" for w, ds in by.items() if ds) + "."


def _claims_sentence(out: dict) -> str:
    """Which claims read Fig 6b's points, and whether C002-10's "coarser pixels" and its verdict move with the cap."""
    claims, part = out["claims"], out["part"]
    if not claims:
        return "No claim reads these points at the register default."
    if "C002-10" not in claims:
        return f"Of the claims at the register default, {', '.join(claims)} read these points; none is rerun here."
    others = [c for c in claims if c != "C002-10"]
    v0, v1 = part["verdicts"]
    pix = out["pix"]
    moved = _side(part["change"]) != "none"
    text = (
        f'Of the claims at the register default, C002-10 reads these points (part "{_PART}": rho at Delta = {pix:g} '
        f"sigma over rho at Fig 4a's pixels, geometric mean over {_at(out['close'])}): on this replicate (intervals "
        "from this study's own "
        f"resamples, as its rule reads them) it is {_fmt(part['default'])} at the "
        f"default cap and {_fmt(part['larger'])} at the larger one, a paired change of {_signed(part['change'])} "
        f'({"a measurable change" if moved else "no measurable change"}); its rule gives "{v0}" at the default cap '
        f'and "{v1}" at the larger one, so on this replicate that verdict '
        f"{'does not depend' if v0 == v1 else 'depends'} on the cap."
    )
    return text + (f" {', '.join(others)} also read them and are not rerun here." if others else "")


def _fmt(e: Estimate) -> str:
    return f"{e.value:.3g} [{e.ci_low:.3g}, {e.ci_high:.3g}]"


def cap_paragraph(out: dict) -> str:
    """The Markdown paragraph of :func:`cap_check`'s result ``out``: how often the cap is reached, by which algorithm
    at which configuration, what the larger cap changes (paired 95 % intervals) and whether the claims reading the
    points depend on it; every number and every word of direction from ``out``."""
    pts, n, cap, big = out["points"], out["n"], out["cap"], out["larger cap"]
    changed = sum(p["changed trials"] for p in pts.values())
    stray = sum(p["changed trials not capped"] for p in pts.values())
    return " ".join(
        [
            f"**The EM iteration cap.** At Fig 6b's configuration (Delta = {out['pix']:g} sigma, m_k = {out['m']}, "
            f"T = {out['T']}; the figures' replicate, {n} trials a point) the two-stage's per-frame marks reach the "
            f"cap of {cap} EM iterations in some frame in {_per_d(pts, 'two-stage cap hit')}; the ULA reaches it in "
            f"{_per_d(pts, 'ULA cap hit')}.",
            f"Rerun on the same scenes with a cap of {big} iterations, the marks reach it in "
            f"{_per_d(pts, 'two-stage cap hit, larger cap')}, the ULA in {_per_d(pts, 'ULA cap hit, larger cap')}; "
            f"the estimates change in {changed} of the {n * len(pts)} trials"
            + (
                "."
                if changed == 0
                else ", every one of them among those that reached the default cap."
                if stray == 0
                else f", {stray} of them among those that did not reach the default cap."
            ),
            "Paired on the same trials (95 % intervals, widened where a simulation test found the bootstrap "
            "interval of a ratio of variance sums to cover less than 95 % at this number of trials), the larger cap "
            "changes the two-stage's variance sum "
            f"Sigma^2 of the initial positions by {_changes(pts, 'two-stage variance change', 'two-stage variance', ' sigma^2')}"
            f", and the gain rho = Sigma^2_two-stage / Sigma^2_ULA by {_changes(pts, 'rho change', 'rho', '')}.",
            _gain_sentence(pts),
            _claims_sentence(out),
        ]
    )


def cap_metrics(out: dict) -> dict:
    """``{metric name: value}`` of :func:`cap_check`'s result, for ``results.metric``."""
    m = {"cap_check/cap": out["cap"], "cap_check/larger_cap": out["larger cap"], "cap_check/cpu_s": out["cpu_s"]}
    for d, p in out["points"].items():
        for k in ("two-stage cap hit", "ULA cap hit", "two-stage cap hit, larger cap", "ULA cap hit, larger cap"):
            m[f"cap_check/d{d:g}/{k}"] = p[k]
        m[f"cap_check/d{d:g}/two-stage variance change"] = p["two-stage variance change"]
        m[f"cap_check/d{d:g}/rho change"] = p["rho change"]
        m[f"cap_check/d{d:g}/rho at both caps"] = list(p["rho"])
    for k in ("default", "larger", "change"):
        m[f"cap_check/C002-10 {_PART}/{k}"] = out["part"][k]
    m[f"cap_check/C002-10 {_PART}/verdicts"] = list(out["part"]["verdicts"])
    return m
