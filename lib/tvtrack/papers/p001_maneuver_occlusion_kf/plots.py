"""Figures of notebook 001 (Fisenko et al. 2008). Each function draws one figure from study outputs and returns it;
the notebook saves it with its caption. Positions in raster elements, time in seconds."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ...plotting import colour, use_style

__all__ = [
    "block_diagram",
    "detection_histogram",
    "velocity_acceleration",
    "error_and_gain",
    "figure4",
    "loss_sweep_plot",
    "comparators_plot",
]

RESTART_COLOURS = {"A": colour(0), "B": colour(1), "C": colour(2)}
LOSS_SHADE = dict(color="0.92", zorder=0)


def block_diagram():
    """Fig. 1 redrawn from the paper's description (measurer, switch, filter, detector, loss flag)."""
    use_style()
    fig, ax = plt.subplots(figsize=(8, 2.6))
    boxes = {
        "TV coordinate\nmeasurer": (0.02, 0.55),
        "switch\n(commutator)": (0.24, 0.55),
        "Kalman filter\n2nd / 3rd order,\ngain table": (0.46, 0.55),
        "output\ncoordinates": (0.80, 0.55),
        "manoeuvre\ndetector |S| > c(α)": (0.46, 0.05),
        "loss flag\n(oracle here)": (0.24, 0.05),
    }
    for text, (x, y) in boxes.items():
        ax.add_patch(plt.Rectangle((x, y), 0.17, 0.36, fill=False, lw=1.2))
        ax.text(x + 0.085, y + 0.18, text, ha="center", va="center", fontsize=8)
    for (x1, y1), (x2, y2) in [
        ((0.19, 0.73), (0.24, 0.73)),
        ((0.41, 0.73), (0.46, 0.73)),
        ((0.63, 0.73), (0.80, 0.73)),
        ((0.59, 0.55), (0.59, 0.41)),
        ((0.50, 0.41), (0.50, 0.55)),
        ((0.325, 0.41), (0.325, 0.55)),
    ]:
        ax.annotate("", (x2, y2), (x1, y1), arrowprops=dict(arrowstyle="->", lw=1.0))
    ax.annotate(
        "",
        (0.36, 0.91),
        (0.70, 0.91),
        arrowprops=dict(arrowstyle="->", lw=1.0, ls="--", connectionstyle="arc3,rad=0.25"),
    )
    ax.text(0.53, 0.99, "predicted coordinate fed back while lost (zero gains)", ha="center", fontsize=7)
    ax.text(0.60, 0.47, "velocity", fontsize=7)
    ax.text(0.49, 0.47, "order, gains", fontsize=7, ha="right")
    ax.text(0.315, 0.47, "lost / seen", fontsize=7, ha="right")
    ax.set(xlim=(0, 1), ylim=(0, 1.05))
    ax.axis("off")
    return fig


def detection_histogram(det_frames, fps: float, onset_s: float, paper_s: float = 5.5):
    """First detection times (runs x channels), s, against the onset and the paper's 5.5 s."""
    use_style()
    fig, ax = plt.subplots(figsize=(6.5, 3.0))
    d = np.asarray(det_frames).ravel()
    t = d[d >= 0] / fps
    bins = np.arange(np.floor((onset_s - 0.4) * fps), np.ceil((onset_s + 1.6) * fps) + 1) / fps
    ax.hist(np.clip(t, bins[0], bins[-1]), bins=bins, color=colour("estimate"))
    ax.axvline(onset_s, color="k", ls=":", label="onset")
    ax.axvline(paper_s, color=colour(1), ls="--", label=f"paper: {paper_s:g} s")
    ax.set(xlabel="first detection time (s)", ylabel="runs x channels")
    ax.legend(loc="upper right")
    return fig


def velocity_acceleration(t_s, truth, mean_v, sd_v, mean_a, sd_a, p_detected, loss, selected: str, zoom=(4.5, 6.5)):
    """Fig. 2 for one channel: velocity (a) with a zoom on ``zoom`` (b), acceleration and the detector output (c).

    ``mean_v``, ``mean_a``: {restart: (T,)} Monte Carlo means; ``sd_v``, ``sd_a``: (T,) SD of the selected rule;
    ``p_detected``: (T,) fraction of runs detected by t; ``truth`` (T, 3); ``loss`` (start, end) s.
    """
    use_style()
    fig, axs = plt.subplots(3, 1, figsize=(7.5, 8.0))
    for ax, (lo, hi) in zip(axs[:2], ((t_s[0], t_s[-1]), zoom)):
        m = (t_s >= lo) & (t_s <= hi)
        ax.axvspan(*loss, **LOSS_SHADE, label="object lost")
        ax.fill_between(
            t_s[m],
            (mean_v[selected] - sd_v)[m],
            (mean_v[selected] + sd_v)[m],
            color="0.6",
            alpha=0.4,
            zorder=1,
            label=f"± SD (restart {selected})",
        )
        ax.plot(t_s[m], truth[m, 1], "k", lw=1.5, label="1: true")
        for r, v in mean_v.items():
            ax.plot(t_s[m], v[m], color=RESTART_COLOURS[r], lw=1.0, label=f"2: filter output, mean (restart {r})")
        ax.set(xlabel="time (s)", ylabel="velocity (elements/frame)", xlim=(lo, hi))
    axs[1].set_ylim(
        truth[(t_s >= zoom[0]) & (t_s <= zoom[1]), 1].min() - 0.6,
        truth[(t_s >= zoom[0]) & (t_s <= zoom[1]), 1].max() + 0.6,
    )
    axs[0].set_title("(a) velocity")
    axs[1].set_title(f"(b) velocity, zoom on {zoom[0]:g}-{zoom[1]:g} s")
    axs[0].legend(loc="upper left", fontsize=7)
    ax = axs[2]
    ax.axvspan(*loss, **LOSS_SHADE)
    ax.fill_between(t_s, mean_a[selected] - sd_a, mean_a[selected] + sd_a, color="0.6", alpha=0.4, zorder=1)
    ax.plot(t_s, truth[:, 2], "k", lw=1.5, label="true")
    for r, a in mean_a.items():
        ax.plot(t_s, a, color=RESTART_COLOURS[r], lw=1.0, label=f"estimate, mean (restart {r})")
    ax.plot(t_s, 0.3 * p_detected, color=colour(4), ls=":", lw=1.2, label="3: P(detected by t) x 0.3")
    ax.set_yscale("symlog", linthresh=1.0)
    ax.set(xlabel="time (s)", ylabel="acceleration (elements/frame²)", title="(c) acceleration, detector output")
    ax.legend(loc="upper right", fontsize=7)
    return fig


def error_and_gain(t_s, mean_err, sd_err, kappa1, loss, selected: str):
    """Fig. 3 for one channel in two panels sharing time: (a) Monte Carlo mean coordinate error per restart with
    the ±SD band of the selected rule (symmetric-log beyond ±1 element); (b) the gain kappa1 of run 0 (log)."""
    use_style()
    fig, axs = plt.subplots(2, 1, figsize=(7.5, 5.6), sharex=True, height_ratios=[1.6, 1])
    ax = axs[0]
    ax.axvspan(*loss, **LOSS_SHADE, label="object lost (prediction error)")
    ax.fill_between(
        t_s,
        mean_err[selected] - sd_err,
        mean_err[selected] + sd_err,
        color="0.55",
        alpha=0.5,
        zorder=2,
        label=f"± SD (restart {selected})",
    )
    for r, e in mean_err.items():
        ax.plot(t_s, e, color=RESTART_COLOURS[r], lw=1.2, zorder=3, label=f"1: mean error (restart {r})")
    ax.set_yscale("symlog", linthresh=1.0)
    ax.set(ylabel="coordinate error (elements)", title="(a) coordinate error")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7)
    ax = axs[1]
    ax.axvspan(*loss, **LOSS_SHADE)
    for r, k in kappa1.items():
        ax.plot(t_s, np.where(k > 0, k, np.nan), color=RESTART_COLOURS[r], lw=1.0, label=f"2: κ1, run 0 ({r})")
    ax.set_yscale("log")
    ax.set(xlabel="time (s)", ylabel="κ1 (dimensionless)", title="(b) gain κ1 (0 while lost, not drawn)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7)
    return fig


def figure4(curves: dict, mc: dict, bound_sd: float, by_reading: dict, title: str):
    """Fig. 4: (a) dynamic error, RMS and their sum vs k_b3 with the Monte Carlo checks and the SD bound of
    unbiased predictors; (b) curve 3 for every restart rule and occlusion reading."""
    use_style()
    fig, axs = plt.subplots(1, 2, figsize=(11, 4.2))
    kb = curves["kb3"]
    ax = axs[0]
    ax.plot(kb, curves["dyn"], "o-", color=colour(0), label="1: dynamic error (noise-free, signed)")
    ax.errorbar(
        kb, mc["mean"], yerr=1.96 * mc["se"], fmt="none", color=colour(0), capsize=3, label="Monte Carlo mean ± 95 % CI"
    )
    ax.plot(kb, curves["rms"], "s-", color=colour(1), label="2: RMS (covariance recursion)")
    ax.plot(kb, mc["sd"], "x", color=colour(1), label="Monte Carlo SD")
    ax.plot(kb, curves["sum"], "^-", color=colour(2), label="3: |dynamic| + RMS")
    ax.axhline(bound_sd, color="k", ls="--", lw=0.8, label="SD bound of unbiased predictors")
    ax.set_yscale("symlog", linthresh=1.0)
    ax.set(xlabel="k_b3: frame at which the gain lower bound is set", ylabel="prediction error (elements)", title=title)
    ax.legend(fontsize=7, loc="upper right")
    ax = axs[1]
    for (r, occ), cur in by_reading.items():
        ax.plot(
            kb,
            cur["sum"],
            ls="-" if occ.startswith("scenario") else ":",
            color=RESTART_COLOURS[r],
            marker="^",
            ms=3,
            label=f"restart {r}, loss {occ}",
        )
    ax.set_yscale("log")
    ax.set(xlabel="k_b3 (frames)", ylabel="|dynamic| + RMS (elements)", title="(b) curve 3 by reading")
    ax.legend(fontsize=7)
    return fig


def loss_sweep_plot(sweeps: dict, switch_s: float):
    """C001-7: |dynamic| and RMS prediction error after a 10 s loss vs the loss time after the switch."""
    use_style()
    fig, ax = plt.subplots(figsize=(6.5, 3.6))
    for r, sw in sweeps.items():
        dt = sw["loss_s"] - switch_s
        ax.semilogy(dt, np.abs(sw["dyn"]), "o-", color=RESTART_COLOURS[r], label=f"|dynamic|, restart {r}")
        ax.semilogy(dt, sw["rms"], "s--", color=RESTART_COLOURS[r], ms=3, label=f"RMS, restart {r}")
    ax.set(xlabel="loss time − switch time (s)", ylabel="prediction error after a 10 s loss (elements)")
    ax.legend(fontsize=7, ncol=2)
    return fig


def comparators_plot(t_s, rms_t: dict, ratios: dict, loss):
    """C001-4: (a) position RMS over time of the scheme and every tuned comparator (channels pooled); (b) each
    part's ratio, the comparator's error statistic over the scheme's (the dynamic error's mean square for the
    compensation, the register's RMS statistic for the others), with its 95 % interval (above 1: the scheme is
    better)."""
    use_style()
    fig, axs = plt.subplots(1, 2, figsize=(11, 3.8), width_ratios=[1.5, 1])
    ax = axs[0]
    ax.axvspan(*loss, **LOSS_SHADE)
    for i, (name, r) in enumerate(rms_t.items()):
        ax.semilogy(t_s, r, color=colour(i), lw=1.6 if i == 0 else 0.9, label=name)
    ax.set(xlabel="time (s)", ylabel="position RMS error (elements)", title="(a) RMS error over time")
    ax.legend(fontsize=7)
    ax = axs[1]
    names = list(ratios)
    vals = np.array([ratios[n].value for n in names])
    lo = np.array([ratios[n].ci_low for n in names])
    hi = np.array([ratios[n].ci_high for n in names])
    y = np.arange(len(names))
    ax.errorbar(vals, y, xerr=[vals - lo, hi - vals], fmt="o", color=colour(0), capsize=3)
    ax.axvline(1.0, color="k", lw=0.8)
    ax.set_xscale("log")
    ax.set_yticks(y, names, fontsize=8)
    ax.set(xlabel="comparator's error / the scheme's (> 1: scheme better)", title="(b) the C001-4 parts")
    return fig


def detector_benchmark_plot(bench: dict, fa_label: str):
    """Median detection delay against the per-run false-alarm probability, one curve per detector."""
    use_style()
    fig, ax = plt.subplots(figsize=(7, 4.0))
    for i, (name, cur) in enumerate((k, v) for k, v in bench.items() if k != "arming_frame"):
        fin = np.isfinite(cur["median_delay_s"])
        ax.plot(
            cur["per_run_false_alarm"][fin],
            cur["median_delay_s"][fin],
            marker="osd^v<>p"[i % 7],
            ms=4,
            color=colour(i),
            label=name,
        )
    ax.set_xscale("log")
    ax.set(xlabel=f"per-run false-alarm probability ({fa_label})", ylabel="median detection delay (s)")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig
