"""Figures of notebook 002, drawn from :func:`.study.figure_data` (groups of simulation points and their results).

Every function returns the matplotlib figure; the notebook saves it with its caption. Axes: separation d / sigma,
number of frames T, variances in sigma^2 (log scale), gains as ratios.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np

from tvtrack.montecarlo import mean_ci
from .claim_values import errors, gain, spread_sum

__all__ = [
    "ula_distance_figure",
    "one_object_figure",
    "gain_figure",
    "iterations_figure",
    "bound_figure",
    "failure_figure",
    "bic_figure",
]


def _band(ax, x, ests, label, **kw):
    v = np.array([e.value for e in ests])
    (line,) = ax.plot(x, v, marker="o", ms=3, label=label, **kw)
    ax.fill_between(x, [e.ci_low for e in ests], [e.ci_high for e in ests], color=line.get_color(), alpha=0.2, lw=0)
    return line


def _distance_axes(ax, title, ylabel="total position variance (sigma^2)"):
    ax.set(xlabel="separation d / sigma", ylabel=ylabel, title=title, yscale="log")
    ax.legend(fontsize=7)


def ula_distance_figure(g, res, epoch="first"):
    """Figs 1a, 1b, 1c and 2: the ULA's total position variance against separation, with the CRB (dotted)."""
    fig, axes = plt.subplots(1, 4, figsize=(16, 3.8))
    panels = [
        ("1a", "Fig 1a: Delta = 3 sigma", {f"m_k = {m}": cs for m, cs in g["1a"].items()}),
        ("1b", "Fig 1b: Delta = sigma", {f"m_k = {m}": cs for m, cs in g["1b"].items()}),
        ("1c", "Fig 1c: T = 5", {f"Delta = {p:g} sigma": cs for p, cs in g["1c"].items()}),
        ("2", "Fig 2: Delta = sigma", {f"T = {T}, m_k = {m}": cs for (T, m), cs in g["2"].items()}),
    ]
    for ax, (_, title, curves) in zip(axes, panels):
        for label, cs in curves.items():
            d, cs = list(cs), list(cs.values())
            line = _band(ax, d, [spread_sum(errors(res[c], "ula", epoch)) for c in cs], label)
            ax.plot(d, [res[c]["crb_pos"] for c in cs], ls=":", color=line.get_color())
        _distance_axes(ax, title)
    return fig


def one_object_figure(g, res, frames, epoch="first"):
    """Fig 3a: Var x_o of one object against T for three pixel sizes and the three algorithms."""
    names = {"cr": "two-stage, centre-of-region marks", "em": "two-stage, iterative marks", "ula": "ULA"}
    fig, axes = plt.subplots(1, len(g["3a"]), figsize=(4.3 * len(g["3a"]), 3.6), sharey=True)
    for ax, (pix, by_t) in zip(np.atleast_1d(axes), g["3a"].items()):
        cs = [by_t[T] for T in frames]
        for alg, label in names.items():
            _band(ax, frames, [spread_sum(errors(res[c], alg, epoch)[:, :1]) for c in cs], label)
        ax.plot(frames, [res[c]["crb_x0"] for c in cs], "k:", label="CRB of x_o")
        ax.set(
            xscale="log",
            yscale="log",
            xlabel="number of frames T",
            ylabel="Var x_o (sigma^2)",
            title=f"Fig 3a: one object, Delta = {pix:g} sigma, m_k = 20",
        )
        ax.set_xticks(list(frames), [f"{T:g}" for T in frames])  # the simulated T only: no crowded minor labels
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.legend(fontsize=7)
    return fig


def gain_figure(g, res, rng, n_bootstrap, epoch="first"):
    """Figs 4-6: the two-stage (iterative marks) and the ULA against separation, and the gain rho."""
    groups = {
        "Fig 4a (m_k = 20)": g["4"][20],
        "Fig 4b (m_k = 50)": g["4"][50],
        "Fig 5a (T = 5)": g["5ab"][5],
        "Fig 5b (T = 50)": g["5ab"][50],
        "Fig 6b (Delta = 5 sigma)": g["6"][20],
    }
    fig, axes = plt.subplots(1, 3, figsize=(15, 3.8))
    for i, key in enumerate(("Fig 4a (m_k = 20)", "Fig 5b (T = 50)")):
        d, cs = list(groups[key]), list(groups[key].values())
        for alg, label in (("em", "two-stage, iterative marks"), ("ula", "ULA")):
            _band(axes[i], d, [spread_sum(errors(res[c], alg, epoch)) for c in cs], label)
        axes[i].plot(d, [res[c]["crb_pos"] for c in cs], "k:", label="CRB")
        _distance_axes(axes[i], key)
    for key, by_d in groups.items():
        _band(
            axes[2],
            list(by_d),
            [gain(errors(res[c], "em", epoch), errors(res[c], "ula", epoch), rng, n_bootstrap) for c in by_d.values()],
            key,
        )
    axes[2].axhspan(3.0, 6.0, color="0.88", zorder=0, label="paper's x4-4.5 (C002-11 band)")
    axes[2].axhline(1.0, color="0.3", lw=0.8)
    _distance_axes(axes[2], "gain rho = Sigma^2_two-stage / Sigma^2_ULA", "rho")
    return fig


def iterations_figure(g, res):
    """Fig 7: plain-EM iterations of the ULA against separation (mean with 95 % interval, 90th percentile), and
    the per-frame marks' plain-EM iterations per frame."""
    ds = sorted(g["7"])
    fig, ax = plt.subplots(figsize=(5.5, 3.6))
    it = [res[g["7"][d]]["plain_iter"] for d in ds]
    _band(ax, ds, [mean_ci(x) for x in it], "ULA, plain EM (mean)")
    ax.plot(ds, [np.quantile(x, 0.9) for x in it], "--", lw=0.8, label="ULA, 90th percentile")
    T = res[g["7"][ds[0]]]["T"]
    _band(ax, ds, [mean_ci(res[g["7"][d]]["em_plain_iter"] / T) for d in ds], "marks, plain EM per frame (mean)")
    ax.set(
        xlabel="separation d / sigma",
        ylabel="EM iterations to tolerance",
        yscale="log",
        title="Fig 7: iterations vs separation",
    )
    ax.legend(fontsize=7)
    return fig


def bound_figure(g, res, epoch="first"):
    """The bound at coarse pixels: MSE of both algorithms against the CRB and the van Trees bound with the
    designation prior, Fig 4a's pixel size and Delta = 5 sigma (Fig 6b)."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8), sharey=True)
    for ax, (title, by_d) in zip(axes, (("Fig 4a's pixels", g["4"][20]), ("Delta = 5 sigma (Fig 6b)", g["6"][20]))):
        d, cs = list(by_d), list(by_d.values())
        for alg, label in (("em", "two-stage MSE"), ("ula", "ULA MSE")):
            _band(ax, d, [spread_sum(errors(res[c], alg, epoch), "MSE") for c in cs], label)
        ax.plot(d, [res[c]["crb_pos"] for c in cs], "k:", label="CRB (unbiased estimators)")
        ax.plot(d, [res[c]["bcrb_pos"] for c in cs], "k--", label="van Trees bound (designation prior)")
        _distance_axes(ax, title, "total position MSE (sigma^2)")
    return fig


def failure_figure(rates):
    """Failure, label-swap and cap-hit rates (:func:`.extras.failure_rates`) against separation, one panel per rate,
    one curve per figure configuration and algorithm (ULA solid, two-stage dashed)."""
    kinds = ("failure", "label swap", "cap hit")
    fig, axes = plt.subplots(1, 3, figsize=(14, 3.8), sharey=True)
    n_curves = 2 * len(rates)
    for ax, kind in zip(axes, kinds):
        for k, (label, rows) in enumerate(rates.items()):
            d = np.array(list(rows), dtype=float)
            for a, (alg, ls) in enumerate((("ULA", "-"), ("two-stage", "--"))):
                if f"{alg} {kind}" not in next(iter(rows.values())):
                    continue  # Fig 7's plain EM: cap hits only
                ests = [rows[x][f"{alg} {kind}"] for x in rows]
                v = np.array([e.value for e in ests])
                err = [v - [e.ci_low for e in ests], np.array([e.ci_high for e in ests]) - v]
                shift = 0.03 * (2 * k + a - (n_curves - 1) / 2)  # side by side, so the intervals stay apart
                ax.errorbar(
                    d + shift,
                    v,
                    yerr=err,
                    ls=ls,
                    color=f"C{k}",
                    marker="o",
                    ms=3,
                    capsize=2,
                    lw=1,
                    label=f"{alg}, {label}",
                )
        ax.set(xlabel="separation d / sigma", ylabel="share of trials", title=kind, ylim=(-0.02, 1.02))
    axes[-1].legend(fontsize=6)  # the cap-hit panel holds every curve (Fig 7: cap hits only)
    return fig


def bic_figure(shares):
    """Share of trials in which BIC picks each number of objects (:func:`.extras.bic_correct_q`) against
    separation; two objects are there."""
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    d = list(shares)
    for name in next(iter(shares.values())):
        _band(ax, d, [shares[x][name] for x in d], name)
    ax.set(xlabel="separation d / sigma", ylabel="share of trials choosing Q'", ylim=(-0.02, 1.02))
    ax.legend(fontsize=7)
    return fig
