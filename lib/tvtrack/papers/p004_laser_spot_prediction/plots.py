"""Figures of paper 004. Each function takes study results and returns a matplotlib figure (axes
labelled with units); the notebook saves it with its caption."""

from __future__ import annotations

import textwrap

import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np

from ...filters.polynomial import growing_memory_gains
from ...plotting import colour
from . import predictors as pr
from .prediction_study import PAPER, per_trial_path_mse
from .spot_centre import centroid_mask
from .study import OPTIMAL

__all__ = [
    "plain_log",
    "errorbars",
    "measurement_figure",
    "prediction_figure",
    "comparison_figure",
    "horizon_figure",
    "floor_figure",
    "gains_figure",
    "ranking_figure",
    "calibration_figure",
]

_STYLES = [
    ("o", "-"),
    ("s", "--"),
    ("^", ":"),
    ("v", "-."),
    ("D", "-"),
    ("x", "--"),
    ("+", ":"),
    ("*", "-."),
    ("<", "-"),
    (">", "--"),
    ("p", ":"),
    ("h", "-."),
]


def plain_log(ax, which: str = "xy", subs=(1.0, 2.0, 5.0)) -> None:
    """Log axes with plain-number tick labels (``subs`` x 10^k written out, no 10^x; ``(1.0,)`` for
    axes spanning many decades, whose 1-2-5 labels would overlap)."""
    for name in which:
        axis = getattr(ax, f"{name}axis")
        axis.set_major_locator(matplotlib.ticker.LogLocator(subs=subs))
        axis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        axis.set_minor_formatter(matplotlib.ticker.NullFormatter())


def errorbars(ax, x, estimates, **kw):
    """Estimates (value and 95 % interval) against ``x``."""
    v = np.array([e.value for e in estimates])
    lo = np.array([e.ci_low for e in estimates])
    hi = np.array([e.ci_high for e in estimates])
    return ax.errorbar(x, v, yerr=[v - lo, hi - v], **kw)


def measurement_figure(run, frame: int):
    """Fig. 1-2 redrawn: the gate of path 1 at ``frame`` (window, weighted pixels, measured and true
    centre) and the measured x, y of path 1 against the frame number."""
    trk, cam = run.track, run.camera
    o = trk.origin[0, 0, frame]
    img = trk.gates[frame]
    xy = np.moveaxis(run.z_meas[0, 0], 0, -1)
    truth = np.moveaxis(run.truth[0, 0], 0, -1)
    g = cam.gate_size_px
    mask = centroid_mask(img, o, xy[frame], window_px=cam.window_px, threshold_sigma=cam.threshold_sigma)
    fig, axs = plt.subplots(1, 2, figsize=(10, 3.8), width_ratios=[1, 1.6])
    im = axs[0].imshow(img, cmap="gray", extent=(o[0] - 0.5, o[0] + g - 0.5, o[1] + g - 0.5, o[1] - 0.5))
    fig.colorbar(im, ax=axs[0], label="pixel value (DN)", shrink=0.85)
    axs[0].contour(
        np.arange(g) + o[0], np.arange(g) + o[1], mask.astype(float), levels=[0.5], colors="c", linewidths=0.8
    )
    hw = cam.window_px / 2
    axs[0].add_patch(plt.Rectangle(xy[frame] - hw, 2 * hw, 2 * hw, fill=False, color=colour("gate")))
    axs[0].plot(*xy[frame], "+", color=colour("measurement"), ms=12, label="energy centre")
    axs[0].plot(*truth[frame], "x", color=colour("truth"), ms=8, label="true centre")
    axs[0].set(xlabel="x (px)", ylabel="y (px)", title=f"frame {frame}: gate, window, weighted pixels")
    axs[0].legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, fontsize=8)  # off the image
    k = np.arange(xy.shape[0])
    axs[1].plot(k, xy[:, 0], label="x (curve 1)")
    axs[1].plot(k, xy[:, 1], label="y (curve 2)")
    axs[1].set(xlabel="frame number", ylabel="measured centre (px)", title="energy-centre coordinates, path 1")
    axs[1].legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, fontsize=8)  # off the curves
    return fig


def prediction_figure(run, name: str = PAPER, zoom: int = 120):
    """Figs. 3-4 redrawn: measured and predicted x of path 1, a zoom, and the prediction error with
    the paper's +-2 px band."""
    m = int(run.config["horizon"])
    fc = run.forecasts[name][0, 0]
    z = run.z[0, 0]
    k = np.arange(z.shape[-1])
    e = pr.forecast_errors(run.forecasts[name], run.z_meas, m)[0, 0]
    lo = max(run.size.eval_start, z.shape[-1] // 2 - zoom // 2)
    hi = min(z.shape[-1] - m, lo + zoom)
    fig, axs = plt.subplots(3, 1, figsize=(9, 7.5))
    axs[0].plot(k, z[0], lw=0.8, color=colour("measurement"), label="measured x")
    axs[0].plot(k + m, fc[0], lw=0.8, ls="--", color=colour("prediction"), label=f"predicted {m} frame(s) ahead")
    axs[0].set(xlabel="frame number", ylabel="x centre (px)", title="Fig. 3 redrawn: measured and predicted, path 1")
    axs[0].legend(fontsize=8)
    axs[1].plot(k[lo:hi], z[0, lo:hi], "o-", ms=3, lw=0.8, color=colour("measurement"), label="measured x")
    axs[1].plot(k[lo:hi], fc[0, lo - m : hi - m], "s--", ms=3, lw=0.8, color=colour("prediction"), label="predicted x")
    axs[1].set(xlabel="frame number", ylabel="x centre (px)", title="Fig. 4 redrawn: zoom")
    axs[1].legend(fontsize=8)
    axs[2].plot(k, e[0], lw=0.6, label="x")
    axs[2].plot(k, e[1], lw=0.6, label="y")
    axs[2].axhspan(-2, 2, color="g", alpha=0.12, label="+-2 px (paper)")
    axs[2].set(xlabel="frame number", ylabel="prediction error (px)", title="prediction error, path 1")
    axs[2].legend(fontsize=8, ncol=3)
    return fig


def comparison_figure(run, names):
    """Per-path RMS one-step error of each method (box over paths), with the paper's 1-2 px band."""
    m = int(run.config["horizon"])
    data = [np.sqrt(per_trial_path_mse(run.forecasts[n], run.z_meas, m, run.size.eval_start)[0]) for n in names]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.boxplot(
        data,
        orientation="horizontal",
        tick_labels=list(names),
        showmeans=True,
        meanprops=dict(marker="^", markerfacecolor="k", markeredgecolor="k", markersize=5),
    )
    ax.axvspan(1, 2, color="g", alpha=0.12, label="paper's claim: 1-2 px")
    ax.set_xscale("log")
    plain_log(ax, "x", subs=(1.0, 2.0, 3.0, 5.0))
    ax.set_xlabel(f"per-path RMS of the {m}-frame prediction error per axis (px)")
    ax.invert_yaxis()
    ax.legend(loc="lower right")
    return fig


def horizon_figure(hz: dict, horizons):
    """RMS error against the horizon for every method (re-tuned per horizon), distinct marker and line
    style per method so coinciding curves stay visible."""
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    for j, (name, d) in enumerate(hz["rms"].items()):
        mk, ls = _STYLES[j % len(_STYLES)]
        shift = 1 + 0.012 * (j - len(hz["rms"]) / 2)  # a small offset keeps identical curves apart
        errorbars(
            ax,
            np.asarray(horizons, float) * shift,
            [d[h] for h in horizons],
            marker=mk,
            ls=ls,
            ms=4,
            capsize=2,
            lw=2.0 if name == PAPER else 1.0,
            color="k" if name == OPTIMAL else colour(j % 7),  # black (the palette's last) is the bound's alone
            label=name,
        )
    ax.axhspan(1, 2, color="g", alpha=0.12, label="1-2 px (paper)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_log(ax)
    ax.set_xlabel("prediction horizon m (frames)")
    ax.set_ylabel("RMS prediction error per axis (px)")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def floor_figure(run, floor_grid, late_start: int):
    """Left: RMS error against the floor N_f (all paths) and the optimal predictor; right: RMS over paths
    against the frame, without and with the cross-validated floor (C004-6). Returns ``(figure, caption)``; the
    caption gives each curve's RMS over the first and the second half of the scored frames, so it says whether the
    no-floor error grows over the frames or sits at another level."""
    m = int(run.config["horizon"])
    s = run.size.eval_start
    rms = [
        np.sqrt(per_trial_path_mse(pr.growing_memory_forecast(run.z, m, 2, nf), run.z_meas, m, s)[0].mean())
        for nf in floor_grid
    ]
    opt = np.sqrt(per_trial_path_mse(run.forecasts[OPTIMAL], run.z_meas, m, s)[0].mean())
    fig, axs = plt.subplots(1, 2, figsize=(10, 3.6))
    axs[0].plot(floor_grid, rms, "o-", label="growing memory, frozen gains $g_{N_f}$")
    axs[0].axhline(opt, color="k", ls=":", label="optimal predictor")
    axs[0].set_xscale("log")
    axs[0].set_yscale("log")
    plain_log(axs[0], "x")
    plain_log(axs[0], "y", subs=(1.0, 2.0, 3.0, 5.0))  # less than a decade: a label near the optimal line
    axs[0].set(xlabel="floor $N_f$ (samples)", ylabel=f"RMS {m}-frame prediction error (px)")
    axs[0].legend(fontsize=8)
    k = np.arange(run.z.shape[-1])
    for lab, e in floor_errors(run).items():
        axs[1].plot(k[s:], np.sqrt(np.mean(e[..., s:] ** 2, axis=(0, 1))), lw=0.6, label=lab)
    axs[1].axvline(late_start, color="gray", ls="--", lw=0.8, label="late half starts")
    axs[1].set_yscale("log")
    plain_log(axs[1], "y")
    axs[1].set(xlabel="frame number", ylabel="RMS error over paths and axes (px)")
    axs[1].legend(fontsize=8)
    return fig, floor_caption(floor_halves(run, late_start), int(np.argmin(rms)), floor_grid)


def floor_errors(run) -> dict:
    """The one-step errors (px, NaN as 0) of the paper's filter without a floor and with the cross-validated one."""
    m = int(run.config["horizon"])
    return {
        lab: np.nan_to_num(pr.forecast_errors(fc, run.z_meas, m)[0])
        for fc, lab in (
            (pr.growing_memory_forecast(run.z, m, 2, None), "no floor"),
            (run.forecasts[PAPER], "floor (cross-validated)"),
        )
    }


def floor_halves(run, late_start: int) -> dict:
    """{curve: [RMS over the first half of the scored frames, over the second]} (px) of :func:`floor_errors`."""
    s = run.size.eval_start
    halves = ((s, late_start), (late_start, None))
    return {lab: [float(np.sqrt(np.mean(e[..., a:b] ** 2))) for a, b in halves] for lab, e in floor_errors(run).items()}


def floor_caption(halves: dict, best: int, floor_grid) -> str:
    """The floor figure's caption from its numbers: ``halves`` {curve: [RMS over the first half, over the second]}
    (px), ``best`` the index of the smallest error on ``floor_grid``."""
    (a0, a1), (b0, b1) = halves["no floor"], halves["floor (cross-validated)"]
    change, what = a1 / a0, floor_trend(halves)
    return (
        f"Left: RMS one-step error against the floor $N_f$ (all shipped paths; smallest at $N_f$ = "
        f"{floor_grid[best]:g}) and the optimal predictor. Right: RMS over paths and axes against the frame, without "
        f"and with the cross-validated floor. Without a floor the filter errs {a0:.2f} px over the first half of the "
        f"scored frames and {a1:.2f} px over the second ({change:.2f} times), with the floor {b0:.2f} and {b1:.2f} "
        f"px: what to see is that the no-floor error {what} (changes within a factor 1.25 read as one level)."
    )


def floor_trend(halves: dict) -> str:
    """How the no-floor error moves from the first half of the scored frames to the second (``halves`` as
    :func:`floor_halves`): a change within a factor 1.25 reads as one level."""
    a0, a1 = halves["no floor"]
    if a1 / a0 > 1.25:
        return "grows over the frames"
    if a1 / a0 < 0.8:
        return "shrinks over the frames"
    return "stays at about one level over the frames, above the floored filter's"


def c004_6_caveat(halves: dict) -> str:
    """C004-6's caveat: its rule reads "degrades" as erring more than with the floor; whether the no-floor error
    also worsens over the run is what ``halves`` (:func:`floor_halves`, the shipped paths) says."""
    (a0, a1), trend = halves["no floor"], floor_trend(halves)
    return (
        "'Degrades' is judged as erring more than the filter with the floor; on the shipped paths the error without "
        f"a floor {trend} ({a0:.2f} px over the first half of the scored frames, {a1:.2f} px over the second), so "
        + ("it also worsens over the run." if a1 / a0 > 1.25 else "it does not worsen over the run.")
    )


def gains_figure(ratios: dict, floor: int):
    """Left: growing-memory gains g_N against N with the 9/N law; right: the measured filtered-position
    variance over sigma^2 g_N1 at the checked N (C004-5)."""
    fig, axs = plt.subplots(1, 2, figsize=(9, 3.3))
    nn = np.arange(1, 201)
    g = growing_memory_gains(2, 200)
    for i, lab in enumerate(["g1 (position)", "g2 (velocity)", "g3 (acceleration)"]):
        axs[0].plot(nn, g[:, i], label=lab)
    axs[0].plot(nn, 9 / nn, "k:", label="9/N")
    axs[0].axvline(floor, color="gray", ls="--", label=f"floor N_f = {floor}")
    axs[0].set_xscale("log")
    axs[0].set_yscale("log")
    plain_log(axs[0], "x")
    plain_log(axs[0], "y", subs=(1.0,))  # six decades: decade labels only
    axs[0].set(xlabel="samples used N", ylabel="gain g_N")
    axs[0].legend(fontsize=7)
    keys = [k for k in ratios if k.startswith("variance at N=")]
    n = [int(k.split("=")[1]) for k in keys]
    errorbars(axs[1], n, [ratios[k] for k in keys], fmt="o")
    axs[1].axhline(1.0, color="k", ls=":")
    axs[1].set_xscale("log")
    plain_log(axs[1], "x")
    axs[1].set(xlabel="samples used N", ylabel="Var(x_est) / (sigma^2 g_N1)")
    return fig


def budget_figure(budget: dict):
    """Centre error of the windowed centroid and of the Gaussian-fit MLE (static spots) against the
    Cramer-Rao bound, versus read noise."""
    lv = list(budget)
    fig, ax = plt.subplots(figsize=(6, 3.8))
    ax.plot(lv, [budget[v]["centroid"] for v in lv], "o-", label="windowed centroid (used)")
    ax.plot(lv, [budget[v]["mle"] for v in lv], "^--", label="Gaussian-fit MLE")
    ax.plot(lv, [budget[v]["crb"] for v in lv], "k:", label="Cramer-Rao bound (one frame)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_log(ax)
    ax.set(xlabel="read noise (DN RMS)", ylabel="centre error RMS per axis (px)")
    ax.legend(fontsize=8)
    return fig


def ranking_figure(exploration, claim_ids=("C004-3", "C004-3b")):
    """The paired MSE ratio (baseline / filter) of every baseline of the ranking claims, at the default
    (replicates pooled) and under every one-at-a-time condition of the register; above 1: the filter is better.
    A condition shows the claims it was measured for (a condition that changes only what one claim reads, e.g. the
    networks' lags, measures only that claim)."""
    rows = [
        (
            "the register's default (pooled replicates)",
            {b: e for c in claim_ids for b, e in exploration.measured(c).items()},
        )
    ]
    default = exploration.default
    register = getattr(exploration, "register", None)
    if register is None:
        from .register import build

        register = build()
    for r in exploration.runs:
        if r.stage == "single" and any(c in r.outputs for c in claim_ids):
            label = textwrap.fill(register.describe(r.changed(default)), 60)  # each value by its phrase
            rows.append((label, {b: e for c in claim_ids if c in r.outputs for b, e in r.outputs[c].items()}))
    names = list(rows[0][1])
    fig, ax = plt.subplots(figsize=(9, 0.42 * len(rows) + 1.5))
    step = 0.7 / max(len(names), 1)  # the baselines of a row spread symmetrically about its tick
    for j, b in enumerate(names):
        mk, _ = _STYLES[j % len(_STYLES)]
        y = np.array([i for i, (_, row) in enumerate(rows) if b in row])
        est = [row[b] for _, row in rows if b in row]
        v = np.array([e.value for e in est])
        ax.errorbar(
            v,
            y + step * (j - (len(names) - 1) / 2),
            xerr=[v - [e.ci_low for e in est], [e.ci_high for e in est] - v],
            fmt=mk,
            ms=4,
            capsize=1.5,
            lw=0.8,
            color=colour(j),
            label=b,
        )
    ax.axvline(1.0, color="k", lw=0.8)
    ax.set_xscale("log")
    lo, hi = ax.get_xlim()
    plain_log(ax, "x", subs=(1.0,) if hi / lo > 300 else (1.0, 2.0, 5.0))  # 1-2-5 labels overlap over many decades
    ax.set_yticks(np.arange(len(rows)), [lab for lab, _ in rows], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("baseline MSE / filter MSE (paired over paths, 95 % CI); above 1: the filter is better")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def calibration_figure(cal, band=(1.0, 2.0)):
    """The calibration's evaluations: the paper filter's RMS one-step error against the bandwidth factor (log-log),
    the paper's band, the target and the root found."""
    b, r = np.array(sorted(cal.evaluations)).T
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(b, r, "o-", color=colour(0), label="paper's filter, floor cross-validated")
    ax.axhspan(*band, color="g", alpha=0.12, label=f"paper's {band[0]:g}-{band[1]:g} px")
    ax.axhline(cal.target_px, color="k", lw=0.8, ls=":", label=f"target {cal.target_px:g} px")
    ax.axvline(cal.scale, color=colour(1), lw=1.2, ls="--", label=f"root: factor {cal.scale:.3g}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    plain_log(ax)
    ax.set_xlabel("bandwidth factor (every corner frequency x this; 1 = slow wander, fastest corner 0.5 Hz)")
    ax.set_ylabel("RMS one-step prediction error per axis (px)")
    ax.legend(fontsize=8, loc="upper left")
    return fig
