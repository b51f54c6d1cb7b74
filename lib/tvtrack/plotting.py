"""One plotting style and one colour palette for every notebook figure and every Rerun recording.

Compared series get distinct colours from :data:`PALETTE` (Okabe-Ito, colour-blind safe) in a fixed
role order, so "truth" and "estimate" look the same in every paper and in the viewer.
"""

from __future__ import annotations

__all__ = ["PALETTE", "ROLE_COLOURS", "colour", "rgb", "series_colours", "VERDICT_COLOURS", "use_style"]

#: Okabe-Ito palette (hex), in the order series are given colours.
PALETTE = ("#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#F0E442", "#000000")

#: Colours by role, used by figures and recordings alike.
ROLE_COLOURS = {
    "truth": "#009E73",  # green
    "estimate": "#0072B2",  # blue
    "measurement": "#E69F00",  # orange
    "gate": "#F0E442",  # yellow
    "prediction": "#CC79A7",  # purple
    "interference": "#D55E00",  # vermillion
    "reference": "#000000",
}

#: Verdict colours (report, site, forest plot).
VERDICT_COLOURS = {
    "reproduced": "#009E73",
    "partly": "#E69F00",
    "not reproduced": "#D55E00",
    "undecided": "#999999",
    "not checkable": "#56B4E9",
}


def colour(i_or_role: int | str) -> str:
    """The palette colour of series ``i`` (cycling), or of a role in :data:`ROLE_COLOURS`."""
    if isinstance(i_or_role, str):
        return ROLE_COLOURS[i_or_role]
    return PALETTE[i_or_role % len(PALETTE)]


def rgb(hex_colour: str) -> tuple[int, int, int]:
    """``"#RRGGBB"`` -> ``(r, g, b)`` in 0..255 (what Rerun takes)."""
    h = hex_colour.lstrip("#")
    return int(h[0:2], 16), int(h[2:4], 16), int(h[4:6], 16)


def series_colours(n: int) -> list[tuple[int, int, int]]:
    """``n`` distinct RGB colours for compared series (x/y errors, variant 1/2, ...)."""
    if n > len(PALETTE):
        raise ValueError(f"{n} compared series: the palette has {len(PALETTE)} distinct colours")
    return [rgb(c) for c in PALETTE[:n]]


def use_style() -> None:
    """Matplotlib defaults for the project's figures: the palette as colour cycle, grid, readable sizes."""
    import matplotlib as mpl
    from cycler import cycler

    mpl.rcParams.update(
        {
            "axes.prop_cycle": cycler(color=list(PALETTE)),
            "axes.grid": True,
            "grid.alpha": 0.3,
            "figure.dpi": 100,
            "font.size": 10,
            "axes.titlesize": 11,
            "axes.labelsize": 10,
            "legend.fontsize": 9,
            "legend.framealpha": 0.85,
            "figure.constrained_layout.use": True,
        }
    )


def errorbars(ax, x, estimates, *, horizontal: bool = False, **style):
    """Estimates with their confidence intervals as error bars: the one helper every paper's plots use.

    Parameters
    ----------
    ax : matplotlib Axes
    x : array_like, shape (k,)
        Abscissae (ordinates with ``horizontal=True``).
    estimates : sequence of k Estimates, numbers or what :func:`tvtrack.verdicts.as_estimate` reads
        The values and their intervals (a number has a zero-width interval).
    horizontal : bool
        Bars along x (values on the x axis, ``x`` on the y axis), e.g. one row per condition.
    **style
        Passed to :meth:`matplotlib.axes.Axes.errorbar` (``fmt``, ``color``, ``capsize``, ``label`` ...).

    Returns
    -------
    matplotlib.container.ErrorbarContainer
    """
    import numpy as np

    from .verdicts import as_estimate

    es = [as_estimate(e) for e in estimates]
    v = np.array([e.value for e in es], dtype=float)
    err = [v - np.array([e.ci_low for e in es], dtype=float), np.array([e.ci_high for e in es], dtype=float) - v]
    if horizontal:
        return ax.errorbar(v, x, xerr=err, **style)
    return ax.errorbar(x, v, yerr=err, **style)
