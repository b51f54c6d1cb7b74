"""The figures of paper 000's notebook: each takes measured values (Estimates or arrays) and returns a figure."""

from __future__ import annotations

import textwrap

import matplotlib.pyplot as plt
import numpy as np

from ...measured import as_estimate

__all__ = ["errorbars", "fig1", "acquisition", "fig2", "fig3", "conditions", "discretisation", "consistency", "panels"]


def errorbars(ax, x, ests, **style):
    """Estimates at abscissae ``x`` with their confidence intervals as error bars."""
    es = [as_estimate(e) for e in ests]
    v = np.array([e.value for e in es])
    return ax.errorbar(x, v, yerr=[v - [e.ci_low for e in es], [e.ci_high for e in es] - v], **style)


def fig1(curves: dict, dt: float, title: str):
    """Fig. 1: sigma_x^2(t) (T^2) of both variants from both starts, their own D11 and the PCRLB."""
    t = np.arange(next(iter(curves.values())).size) * dt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), width_ratios=[1, 2], sharey=True)
    styles = {
        "v1, process means": ("C0", "-"),
        "v2, process means": ("C1", "-"),
        "v1, random N(0, D11(0))": ("C0", "--"),
        "v2, random N(0, D11(0))": ("C1", "--"),
        "v1 own D11": ("C0", ":"),
        "v2 own D11": ("C1", ":"),
        "PCRLB": ("k", "-"),
    }
    for ax in axes:
        for name, (colour, ls) in styles.items():
            ax.semilogy(t, curves[name], color=colour, ls=ls, lw=0.8 if name == "PCRLB" else 1.2, label=name)
        ax.set_xlabel("time t / T")
        ax.grid(alpha=0.3, which="both")
    axes[0].set_xlim(0, 3)
    axes[0].set_ylabel(r"$\sigma_x^2$  ($T^2$)")
    axes[1].legend(fontsize=7, ncol=2)
    fig.suptitle(title)
    return fig


def acquisition(offsets, acq: dict, acquire_by: float):
    """90 % acquisition time (T) and fraction of runs not in lock at the end against the initial offset (T)."""
    fig, (ax, axl) = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True, height_ratios=[2, 1])
    for i, (name, a) in enumerate(acq.items()):
        errorbars(
            ax,
            np.asarray(offsets) + 0.004 * i,
            a["q90"],
            color=f"C{i}",
            marker="o",
            ms=3,
            capsize=2,
            label=f"variant {name[1]}",
        )
        axl.plot(offsets, a["lost"], f"C{i}o-", ms=3, label=f"variant {name[1]}")
    ax.axhline(acquire_by, color="k", lw=0.8, ls="--", label=f"{acquire_by:g} T")
    for a in (ax, axl):
        for edge in (-0.5, 0.5):
            a.axvline(edge, color="grey", lw=0.8, ls=":")
        a.axvline(0.0, color="k", lw=0.5)
    ax.set_ylabel("90 % of runs acquired by (T)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8)
    axl.set_xlabel(
        r"signed initial offset of the object $X_1(0)$ (T; the filters start at 0; micro-raster edges +-0.5)"
    )
    axl.set_ylabel("not in lock at the end")
    for a in (ax, axl):
        a.grid(alpha=0.3, which="both")
    return fig


def fig2(psi_grid, by_variant: dict, title: str):
    """Fig. 2: steady sigma_x^2 (T^2) against psi_A, log-log, one curve per variant."""
    fig, ax = plt.subplots(figsize=(7, 4))
    for i, (name, ests) in enumerate(by_variant.items()):
        errorbars(
            ax, np.asarray(psi_grid) * (1 + 0.03 * i), ests, color=f"C{i}", marker="o", ms=3, capsize=2, label=name
        )
    ax.set(
        xscale="log", yscale="log", xlabel=r"$\psi_A = A/\sigma_ш$", ylabel=r"steady $\sigma_x^2$  ($T^2$)", title=title
    )
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    return fig


def fig3(contrast_grid, curves: dict, title: str):
    """Fig. 3 as the paper draws it: left, the steady sigma_x^2 (T^2) of both variants against contrast P with the
    stationary-noise sigma_x^2* and the PCRLB; right, sigma_x^2 / sigma_x^2* of both variants with the PCRLB's own
    ratio; the paper's P = 0.5 and 0.9 marked (``curves`` from :func:`.studies.fig3_curves`)."""
    fig, (ax, axr) = plt.subplots(1, 2, figsize=(11, 4))
    p = np.asarray(contrast_grid, dtype=float)
    for i, v in enumerate(("variant 1", "variant 2")):
        style = dict(color=f"C{i}", marker="os"[i], ms=4, capsize=2, label=v)
        errorbars(ax, p + 0.005 * i, curves["sigma_x^2"][v], **style)
        errorbars(axr, p + 0.005 * i, curves["ratio"][v], **style)
    errorbars(ax, p, curves["sigma_x^2*"], color="k", marker="_", ms=8, capsize=2, ls="--", label=r"$\sigma_x^{2*}$")
    ax.plot(p, curves["PCRLB"], "k-", lw=0.8, label="PCRLB")
    axr.plot(p, np.asarray(curves["PCRLB"]) / curves["PCRLB"][0], "k-", lw=0.8, label="PCRLB(P) / PCRLB(0)")
    ax.set(yscale="log", xlabel="contrast P", ylabel=r"steady $\sigma_x^2$  ($T^2$)")
    axr.set(yscale="log", xlabel="contrast P", ylabel=r"$\sigma_x^2 / \sigma_x^{2*}$  (ratio)")
    for a in (ax, axr):
        for q in (0.5, 0.9):
            a.axvline(q, color="grey", lw=0.8, ls=":")
        a.legend(fontsize=8)
        a.grid(alpha=0.3, which="both")
    fig.suptitle(title)
    return fig


def conditions(labels, ests, line: float, xlabel: str, title: str):
    """One claim's measured value under every condition of its exploration (horizontal error bars, log x)."""
    labels = [textwrap.fill(str(t), 70) for t in labels]
    rows = np.array([t.count("\n") + 1.0 for t in labels])  # each label's height in text lines, with a gap
    fig, ax = plt.subplots(figsize=(9, 0.18 * rows.sum() + 1.2))
    es = [as_estimate(e) for e in ests]
    y = np.cumsum(rows) - rows / 2  # a multi-line label gets the room it needs (no overlap)
    ax.set_ylim(0, rows.sum())
    v = np.array([e.value for e in es])
    ax.errorbar(v, y, xerr=[v - [e.ci_low for e in es], [e.ci_high for e in es] - v], fmt="o", ms=3, capsize=2)
    ax.axvline(line, color="k", lw=1)
    ax.set_xlim(
        min(0.5 * min(e.ci_low for e in es if e.ci_low > 0), 0.5 * line), 2 * max(line, max(e.ci_high for e in es))
    )
    ax.set_yticks(y, labels, fontsize=7)
    ax.set(xscale="log", xlabel=xlabel, title=title)
    ax.grid(alpha=0.3, which="both", axis="x")
    return fig


def discretisation(parts: dict, band: float, title: str):
    """sigma_x^2(dt) / sigma_x^2(dt_f) - 1 (%) per part (variant, psi_A, P), with the paper's band."""
    fig, ax = plt.subplots(figsize=(8, 3.8))
    names = list(parts)
    errorbars(ax, np.arange(len(names)), [_scaled(parts[n], 100) for n in names], fmt="o", capsize=3)
    ax.axhspan(-100 * band, 100 * band, color="C2", alpha=0.15, label=f"paper: within {100 * band:g} %")
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xticks(np.arange(len(names)), names, rotation=30, ha="right", fontsize=7)
    ax.set(ylabel=r"$\sigma_x^2(\Delta t)/\sigma_x^2(\Delta t_f) - 1$  (%)", title=title)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def _scaled(e, factor):
    e = as_estimate(e)
    return {"value": e.value * factor, "ci_low": e.ci_low * factor, "ci_high": e.ci_high * factor}


def consistency(psi_grid, nees: dict):
    """Mean steady NEES (1 = consistent) against psi_A, per scoring time (solid: interval centre) and variant."""
    fig, ax = plt.subplots(figsize=(7, 4))
    for j, (scoring, by_variant) in enumerate(nees.items()):
        for i, (name, ests) in enumerate(by_variant.items()):
            errorbars(
                ax,
                np.asarray(psi_grid) * (1 + 0.03 * (2 * j + i)),
                ests,
                color=f"C{i}",
                ls="-" if j == 0 else "--",
                marker="o",
                ms=3,
                capsize=2,
                label=f"{name}, scored at the {scoring}",
            )
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set(xscale="log", xlabel=r"$\psi_A = A/\sigma_ш$", ylabel="mean steady NEES (1 = consistent)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    return fig


def panels(specs, title: str):
    """One row of panels, each ``(x, {label: [Estimate]}, xlabel, ylabel, log_x, reference line or None[, log_y])``:
    the curves with their 95 % intervals (the beyond-the-paper studies of :mod:`.beyond`)."""
    fig, axes = plt.subplots(1, len(specs), figsize=(5.5 * len(specs), 4), squeeze=False)
    for ax, (x, curves, xlabel, ylabel, log_x, line, *log_y) in zip(axes[0], specs):
        x = np.asarray(x, dtype=float)
        for i, (label, ests) in enumerate(curves.items()):
            shift = x * (1 + 0.02 * i) if log_x else x + 0.005 * i * (np.ptp(x) or 1.0)
            errorbars(ax, shift, ests, color=f"C{i}", marker="o", ms=3, capsize=2, label=label)
        if line is not None:
            ax.axhline(line, color="k", lw=0.8, ls="--")
        ax.set(
            xscale="log" if log_x else "linear", yscale="log" if any(log_y) else "linear", xlabel=xlabel, ylabel=ylabel
        )
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3, which="both")
    fig.suptitle(title)
    return fig
