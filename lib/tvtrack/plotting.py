"""One plotting style and one colour palette for every notebook figure and every Rerun recording.

Compared series get distinct colours from :data:`PALETTE` (Okabe-Ito, colour-blind safe) in a fixed
role order, so "truth" and "estimate" look the same in every paper and in the viewer.
"""

from __future__ import annotations

__all__ = [
    "PALETTE",
    "ROLE_COLOURS",
    "colour",
    "rgb",
    "VERDICT_COLOURS",
    "use_style",
    "errorbars",
    "specification_rows",
    "specification_curve",
]

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


# --- specification curve --------------------------------------------------------------------------------------

_SPEC_KINDS = {"default": 0, "single": 1, "combination": 2, "pinned": 3, "joint": 4}


def _spec_part(record: dict, part: str | None) -> str | None:
    """The part to draw: ``part``, else the weakest-labelled part of an ``all of`` rule, else ``None`` (one part)."""
    parts = (record.get("robustness") or {}).get("parts") or {}
    if part is not None or len(parts) <= 1:
        return part
    order = ("unstable", "depends", "limited", "unexplored", "robust")
    return min(parts, key=lambda n: order.index(parts[n].get("label")) if parts[n].get("label") in order else 9)


def _spec_point(measured, part: str | None, rule: dict) -> tuple[float, float, float] | None:
    """``(value, low, high)`` of a configuration's measured value (or its part's); ``None`` for a vector."""
    import math

    if part is not None and rule.get("kind") == "all_of":
        measured = measured.get(part) if isinstance(measured, dict) else None
    if isinstance(measured, dict) and "value" in measured:
        v, lo, hi = measured.get("value"), measured.get("ci_low"), measured.get("ci_high")
    elif isinstance(measured, (int, float)) and not isinstance(measured, bool):
        v = lo = hi = measured
    else:
        return None
    if v is None or not math.isfinite(float(v)):
        return None
    lo = v if lo is None or not math.isfinite(float(lo)) else lo
    hi = v if hi is None or not math.isfinite(float(hi)) else hi
    return float(v), float(lo), float(hi)


def specification_rows(record: dict, part: str | None = None) -> list[dict]:
    """The configurations of a claim record, one row each: the default (replicates pooled) and every explored
    condition (single entries, combinations, pinned and joint configurations).

    Returns
    -------
    list of dict
        ``{kind, changed {entry: value}, verdict, point (value, low, high) or None}``, the default first.
    """
    rob = record.get("robustness") or {}
    rule = record.get("rule") or {}
    part = _spec_part(record, part)
    parts = rob.get("parts") or {}
    default_verdict = (parts.get(part) or {}).get("verdict") if part else record.get("verdict")
    rows = [
        {
            "kind": "default",
            "changed": {},
            "verdict": default_verdict or record.get("verdict"),
            "point": _spec_point(record.get("measured"), part, rule),
        }
    ]
    for c in rob.get("conditions") or []:
        verdict = (c.get("parts") or {}).get(part, c.get("verdict")) if part else c.get("verdict")
        rows.append(
            {
                "kind": c.get("kind", "single"),
                "changed": dict(c.get("changed") or c.get("choices") or {}),
                "verdict": verdict,
                "point": _spec_point(c.get("measured"), part, rule),
            }
        )
    return rows


def _spec_labels(record: dict, rows: list[dict]) -> list[tuple[str, str, str]]:
    """The dot matrix's rows: ``(entry, value, plain label)`` for every register value some configuration set."""
    entries = {e["name"]: e for e in (record.get("robustness") or {}).get("register") or [] if isinstance(e, dict)}
    seen = []
    for r in rows:
        for k, v in r["changed"].items():
            if (k, str(v)) not in [(a, b) for a, b, _ in seen]:
                e = entries.get(k, {})
                text = (e.get("phrases") or {}).get(str(v)) or f"{e.get('title') or k} = {v}"
                seen.append((k, str(v), text if len(text) <= 48 else text[:47] + "…"))
    return sorted(seen, key=lambda t: (t[0], t[1]))


def specification_curve(record: dict, part: str | None = None, max_rows: int = 14):
    """A claim's specification curve (Simonsohn, Simmons & Nelson 2020, *Nature Human Behaviour* 4, 1208-1214).

    Top: the measured value with its 95 % interval under every explored configuration (the default with its
    replicates pooled, single register values, smallest combinations, pinned and joint configurations), sorted by
    value, coloured by verdict, the rule's band shaded and the default marked. Below: a dot matrix of which
    register values each configuration set (one row per value; at most ``max_rows``, the most used).
    A part measured as a vector (a trend) has no single value: the top panel shows each configuration's verdict.

    Parameters
    ----------
    record : dict or tvtrack.results.Claim
        A claim as ``results.json`` stores it (``id, rule, measured, verdict, robustness``), or as
        :meth:`tvtrack.results.Results.claim` returns it.
    part : str, optional
        The part of an ``all of`` rule to draw; default the weakest-labelled part.
    max_rows : int
        The most register values shown in the dot matrix.

    Returns
    -------
    (matplotlib.figure.Figure, str)
        The figure and a caption generated from the record.
    """
    import matplotlib.pyplot as plt

    if not isinstance(record, dict):  # a Claim object: its JSON form
        from .results import to_jsonable

        record = to_jsonable(vars(record))
    part = _spec_part(record, part)
    rule = record.get("rule") or {}
    prule = (rule.get("parts") or {}).get(part, rule) if part else rule
    rows = specification_rows(record, part)
    numeric = all(r["point"] is not None for r in rows)
    if numeric:
        rows = sorted(rows, key=lambda r: r["point"][0])
    else:
        order = {"reproduced": 0, "undecided": 1, "partly": 2, "not reproduced": 3}
        rows = sorted(rows, key=lambda r: (order.get(r["verdict"], 4), _SPEC_KINDS.get(r["kind"], 5)))
    labels = _spec_labels(record, rows)
    use = {lab: sum(1 for r in rows if str(r["changed"].get(lab[0])) == lab[1]) for lab in labels}
    labels = sorted(sorted(labels, key=lambda lab: -use[lab])[:max_rows], key=lambda t: (t[0], t[1]))
    n = len(rows)
    width = min(16.0, max(6.5, 3.2 + 0.16 * n))
    fig, (top, bottom) = plt.subplots(
        2,
        1,
        figsize=(width, 3.0 + 0.22 * max(len(labels), 1)),
        sharex=True,
        gridspec_kw={"height_ratios": [2.2, 0.35 + 0.22 * max(len(labels), 1)], "hspace": 0.06},
        layout="none",
    )
    # fixed margins, not a layout engine (it draws the figure once more: most of a site build's time)
    longest = max((len(t) for _, _, t in labels), default=10)
    height = fig.get_size_inches()[1]
    fig.subplots_adjust(left=min(0.55, (0.5 + 0.052 * longest) / width), right=0.98, top=1 - 0.32 / height,
                        bottom=0.32 / height)  # fmt: skip
    d = next(i for i, r in enumerate(rows) if r["kind"] == "default")
    (_spec_values if numeric else _spec_verdicts)(top, rows, d, prule)
    top.legend(fontsize=7, loc="upper left")
    top.set_title(f"{record.get('id', '')}{f' ({part})' if part else ''}: every explored configuration", fontsize=9)
    _spec_matrix(bottom, rows, labels)
    bottom.set_xlabel("configurations, sorted" + (" by value" if numeric else " by verdict"), fontsize=8)
    unit = prule.get("unit") or ""
    quantity = prule.get("quantity") or prule.get("measure") or "measured value"
    same = sum(r["verdict"] == rows[d]["verdict"] for r in rows)
    caption = (
        f"{record.get('id', '')}{f', part {part}' if part else ''}: the {quantity}"
        + (f" ({unit})" if unit and numeric else "")
        + f" under each of {n} configurations (the default, replicates pooled, marked by a diamond; single register "
        f"values, combinations and joint samples), {'sorted by value with 95 % intervals' if numeric else 'by verdict'}"
        f", coloured by verdict; {same} of {n} give the default's verdict"
        + ("; shaded: the rule's band" if numeric and prule.get("kind") in ("in_band", "within_factor") else "")
        + ". Below: the register values each configuration changed (dark dots)."
    )
    return fig, caption


def _spec_values(ax, rows: list[dict], d: int, prule: dict) -> None:
    """The top panel of a numeric curve: values with their intervals, the band shaded, the default ``d`` marked."""
    import textwrap

    import numpy as np

    x = np.arange(len(rows))
    colours = [VERDICT_COLOURS.get(r["verdict"], "#444444") for r in rows]
    v = np.array([r["point"] for r in rows])
    ax.vlines(x, v[:, 1], v[:, 2], colors=colours, lw=1.6)
    ax.scatter(x, v[:, 0], c=colours, s=22, zorder=3)
    if (v[:, 1] > 0).all() and v[:, 2].max() / max(v[:, 1].min(), 1e-300) > 100:
        ax.set_yscale("log")
    ymin, ymax = ax.get_ylim()
    lo, hi = (
        b if isinstance(b, (int, float)) and np.isfinite(b) else None for b in (prule.get("low"), prule.get("high"))
    )
    if lo is not None or hi is not None:
        band_lo = ymin if lo is None or (ax.get_yscale() == "log" and lo <= 0) else lo
        band_hi = ymax if hi is None else hi
        if band_hi > band_lo:
            ax.axhspan(band_lo, band_hi, color="#dfe8f5", zorder=0, label="the rule's band")
        ax.set_ylim(ymin, ymax)
    unit, quantity = prule.get("unit") or "", prule.get("quantity") or prule.get("measure") or "measured value"
    ax.set_ylabel(textwrap.fill(f"{quantity}" + (f" ({unit})" if unit else ""), 34), fontsize=8)
    ax.scatter([d], [v[d, 0]], marker="D", s=70, facecolors="none", edgecolors="black", zorder=4, label="default")


def _spec_verdicts(ax, rows: list[dict], d: int, prule: dict) -> None:
    """The top panel of a curve without one value per configuration (a trend): each configuration's verdict."""
    levels = ["reproduced", "undecided", "partly", "not reproduced"]
    y = [levels.index(r["verdict"]) if r["verdict"] in levels else len(levels) for r in rows]
    ax.scatter(range(len(rows)), y, c=[VERDICT_COLOURS.get(r["verdict"], "#444444") for r in rows], s=30)
    ax.set_yticks(range(len(levels)), levels, fontsize=8)
    ax.set_ylim(len(levels) - 0.5, -0.5)
    ax.scatter([d], [y[d]], marker="D", s=80, facecolors="none", edgecolors="black", zorder=4, label="default")


def _spec_matrix(ax, rows: list[dict], labels: list[tuple[str, str, str]]) -> None:
    """The dot matrix: one row per register value, a dark dot where a configuration set it."""
    import numpy as np

    grid = np.array([[str(r["changed"].get(k)) == val for r in rows] for k, val, _ in labels], dtype=bool)
    jj, ii = np.nonzero(~grid) if labels else ([], [])
    ax.scatter(ii, jj, s=6, color="#dddddd")
    jj, ii = np.nonzero(grid) if labels else ([], [])
    ax.scatter(ii, jj, s=18, color="#333333")
    ax.set_yticks(range(len(labels)), [t for _, _, t in labels], fontsize=7)
    ax.set_ylim(len(labels) - 0.5 if labels else 0.5, -0.5)
    ax.set_xticks([])
    ax.grid(False)


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
