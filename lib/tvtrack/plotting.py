"""One plotting style and one colour palette for every notebook figure and every Rerun recording.

Compared series get distinct colours from :data:`PALETTE` (Okabe-Ito, colour-blind safe) in a fixed
role order, so "truth" and "estimate" look the same in every paper and in the viewer.
"""

from __future__ import annotations

from .numbers import setting

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
FLIP_COLOUR = "#CC0000"
"""The ring around a configuration the claim's page names as a flip."""


def _spec_part(record: dict, part: str | None) -> str | None:
    """The part to draw: ``part``, else the part the claim's sentence is about (:func:`tvtrack.wording.main_part`);
    ``None`` for a claim of one part."""
    from .wording import main_part

    parts = (record.get("robustness") or {}).get("parts") or {}
    if part is not None or len(parts) <= 1:
        return part
    return main_part(record)


def _spec_point(measured, part: str | None, rule: dict) -> tuple[float, float, float] | None:
    """``(value, low, high)`` of a configuration's measured value (or its part's); ``None`` for a vector."""
    import math

    from .measured import record_end
    from .value_words import rule_in_force

    rule, measured = rule_in_force(rule, measured)
    if part is not None and rule.get("kind") == "all_of":
        measured = measured.get(part) if isinstance(measured, dict) else None
    if isinstance(measured, dict) and "value" in measured:
        v, lo, hi = measured.get("value"), record_end(measured, "ci_low"), record_end(measured, "ci_high")
    elif isinstance(measured, (int, float)) and not isinstance(measured, bool):
        v = lo = hi = measured
    else:
        return None
    if v is None or not math.isfinite(float(v)):
        return None
    lo = v if lo is None or math.isnan(float(lo)) else lo  # an open end stays infinite: drawn off the scale
    hi = v if hi is None or math.isnan(float(hi)) else hi
    return float(v), float(lo), float(hi)


def _key(changed: dict) -> tuple:
    return tuple(sorted((str(k), str(v)) for k, v in changed.items()))


def specification_rows(record: dict, part: str | None = None) -> list[dict]:
    """The configurations of a claim record, one row each and each configuration once: the default (replicates
    pooled) and every explored condition (single entries, combinations, pinned and joint configurations), then
    every flip the record names that no condition holds (drawn without a value).

    Returns
    -------
    list of dict
        ``{kind, changed {entry: value}, verdict, point (value, low, high) or None, flip}``, the default first;
        ``flip`` is True for a configuration the claim's page names as a flip.
    """
    from .wording import claim_flips

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
            "flip": False,
        }
    ]
    seen = {()}
    for c in sorted(rob.get("conditions") or [], key=lambda c: _SPEC_KINDS.get(c.get("kind", "single"), 5)):
        changed = dict(c.get("changed") or c.get("choices") or {})
        if _key(changed) in seen:
            continue
        seen.add(_key(changed))
        verdict = (c.get("parts") or {}).get(part, c.get("verdict")) if part else c.get("verdict")
        point = _spec_point(c.get("measured"), part, rule)
        rows.append({"kind": c.get("kind", "single"), "changed": changed, "verdict": verdict, "point": point})
    flips = {_key(f["changed"]): f for f in claim_flips(record, part if part in parts else None) if f["changed"]}
    for r in rows:
        r["flip"] = _key(r["changed"]) in flips
    for k, f in flips.items():
        if k not in seen:
            rows.append({"kind": f.get("kind") or "joint", "changed": f["changed"], "verdict": f.get("verdict"),
                         "point": None, "flip": True})  # fmt: skip
    return rows


def _spec_labels(record: dict, rows: list[dict]) -> list[tuple[str, str, str]]:
    """The dot matrix's rows: ``(entry, value, plain label)`` for every register value any configuration set, the
    label whole (wrapped, never cut)."""
    import textwrap

    entries = {e["name"]: e for e in (record.get("robustness") or {}).get("register") or [] if isinstance(e, dict)}
    seen: dict[tuple[str, str], str] = {}
    for r in rows:
        for k, v in r["changed"].items():
            if (k, str(v)) not in seen:
                e = entries.get(k, {})
                text = (e.get("phrases") or {}).get(str(v)) or setting(e.get("title") or k, v)
                seen[(k, str(v))] = textwrap.fill(text, 56)
    return sorted((k, v, t) for (k, v), t in seen.items())


def _share_count(record: dict, part: str | None, rows: list[dict]) -> tuple[int, int, int]:
    """``(agree, decided, explored)``: the part's share as its record counts it (what the claim's sentence says),
    else counted from the rows."""
    parts = (record.get("robustness") or {}).get("parts") or {}
    p = parts.get(part) if part else (next(iter(parts.values()), None) if len(parts) == 1 else None)
    share = (p or {}).get("share") or {}
    if share.get("design") or share.get("decided"):
        return int(share["agree"]), int(share.get("decided") or 0), int(share.get("design") or share["decided"])
    explored = [r for r in rows[1:] if r["kind"] in ("single", "joint")]
    decided = [r for r in explored if r["verdict"] in ("reproduced", "not reproduced")]
    return sum(r["verdict"] == rows[0]["verdict"] for r in decided), len(decided), len(explored)


def specification_curve(record: dict, part: str | None = None):
    """A claim's specification curve (Simonsohn, Simmons & Nelson 2020, *Nature Human Behaviour* 4, 1208-1214).

    Top: the measured value with its 95 % interval under every explored configuration that has one (the default
    with its replicates pooled, single register values, smallest combinations, pinned and joint configurations),
    sorted by value, coloured by verdict, the rule's band shaded and the default marked; a log scale where the
    values span decades, and an interval that runs off the scale clipped with an arrow at the edge; a
    configuration without a value (a vector, or a flip with no measurement kept) by its verdict in a strip at the
    bottom; each flip the claim's page names ringed. Below: a dot matrix with a row for every register value any
    configuration set.

    Parameters
    ----------
    record : dict or tvtrack.results.Claim
        A claim as ``results.json`` stores it (``id, rule, measured, verdict, robustness``), or as
        :meth:`tvtrack.results.Results.claim` returns it.
    part : str, optional
        The part of an ``all of`` rule to draw; default the part the claim's sentence is about.

    Returns
    -------
    (matplotlib.figure.Figure, str)
        The figure and a caption generated from the record; the caption counts the configurations as the claim's
        sentence does.
    """
    import matplotlib.pyplot as plt

    from .value_words import rule_in_force

    if not isinstance(record, dict):  # a Claim object: its JSON form
        from .results import to_jsonable

        record = to_jsonable(vars(record))
    part = _spec_part(record, part)
    rule = rule_in_force(record.get("rule") or {}, record.get("measured"))[0]
    prule = (rule.get("parts") or {}).get(part, rule) if part and rule.get("kind") == "all_of" else rule
    rows = specification_rows(record, part)
    numeric = any(r["point"] is not None for r in rows)
    order = {"reproduced": 0, "undecided": 1, "partly": 2, "not reproduced": 3}
    rows = sorted(
        rows,
        key=lambda r: (r["point"] is None, r["point"][0] if r["point"] else 0.0, order.get(r["verdict"], 4),
                       _SPEC_KINDS.get(r["kind"], 5)),
    )  # fmt: skip
    labels = _spec_labels(record, rows)
    n = len(rows)
    lines = sum(t.count("\n") + 1 for _, _, t in labels)
    width = min(16.0, max(6.5, 3.2 + 0.16 * n))
    fig, (top, bottom) = plt.subplots(
        2,
        1,
        figsize=(width, 3.0 + 0.16 * max(lines, 1) + 0.06 * len(labels)),
        sharex=True,
        gridspec_kw={"height_ratios": [2.2, 0.35 + 0.16 * max(lines, 1) + 0.06 * len(labels)], "hspace": 0.06},
        layout="none",
    )
    # fixed margins, not a layout engine (it draws the figure once more: most of a site build's time)
    longest = max((len(line) for _, _, t in labels for line in t.split("\n")), default=10)
    height = fig.get_size_inches()[1]
    fig.subplots_adjust(left=min(0.55, (0.5 + 0.052 * longest) / width), right=0.98, top=1 - 0.32 / height,
                        bottom=0.32 / height)  # fmt: skip
    d = next(i for i, r in enumerate(rows) if r["kind"] == "default")
    clipped = (_spec_values if numeric else _spec_verdicts)(top, rows, d, prule)
    top.legend(fontsize=7, loc="upper left")
    top.set_title(f"{record.get('id', '')}{f' ({part})' if part else ''}", fontsize=9, loc="left")
    _spec_matrix(bottom, rows, labels)
    bottom.set_xlabel("configurations, sorted" + (" by value" if numeric else " by verdict"), fontsize=8)
    return fig, _spec_caption(record, part, prule, rows, numeric, clipped)


def _spec_caption(record: dict, part, prule: dict, rows: list[dict], numeric: bool, clipped: int) -> str:
    unit = prule.get("unit") or ""
    quantity = prule.get("quantity") or prule.get("measure") or "measured value"
    agree, decided, explored = _share_count(record, part, rows)
    flips = sum(r["flip"] for r in rows)
    valueless = sum(r["point"] is None for r in rows) if numeric else 0
    return (
        f"{record.get('id', '')}{f', part {part}' if part else ''}: the {quantity}"
        + (f" ({unit})" if unit and unit != quantity and not unit.startswith("(") and numeric else "")
        + f" under each of the {len(rows)} configurations the record keeps (the default with its replicates pooled,"
        f" a diamond, and {len(rows) - 1} explored)"
        + (", sorted by value with 95 % intervals" if numeric else ", by verdict")
        + ", coloured by verdict"
        + ("; shaded: the rule's band" if numeric and prule.get("kind") in ("in_band", "within_factor") else "")
        + (f"; {clipped} interval{'s' * (clipped != 1)} run off the scale (arrows)" if clipped else "")
        + (f"; {valueless} without a value, by verdict at the bottom" if valueless else "")
        + (f"; ringed: the {flips} flip{'s' * (flips != 1)} the page names" if flips else "")
        + (
            f". {agree} agree with the default, {decided - agree} flip and {explored - decided} stay undecided of the "
            f"{explored} explored configurations, as the claim's sentence says"
            if explored
            else ""
        )
        + ". Below: the register values each configuration changed (dark dots), one row for every value set."
    )


def _spec_scale(ax, v, prule: dict) -> tuple[float, float]:
    """Log scale where the values (not their intervals) are positive and span decades; y-limits from the values,
    the band's ends and the interval ends near them (an interval reaching far beyond is clipped)."""
    import numpy as np

    band = [b for b in (prule.get("low"), prule.get("high")) if isinstance(b, (int, float)) and np.isfinite(b)]
    values, ends = v[:, 0], v[:, 1:].ravel()
    if values.min() > 0 and values.max() / values.min() > 30:
        ax.set_yscale("log")
        core = np.concatenate([values, [b for b in band if b > 0]])
        lo, hi = float(core.min()), float(core.max())
        near = ends[(ends >= lo / 10) & (ends <= hi * 10)]
        return float(min(lo, near.min(initial=lo))) / 1.5, float(max(hi, near.max(initial=hi))) * 1.5
    core = np.concatenate([values, band]) if band else values
    lo, hi = float(core.min()), float(core.max())
    span = hi - lo if hi > lo else max(abs(hi), 1.0) * 0.5
    near = ends[(ends >= lo - span) & (ends <= hi + span)]
    lo, hi = min(lo, near.min(initial=lo)), max(hi, near.max(initial=hi))
    pad = 0.08 * (hi - lo) if hi > lo else max(abs(hi), 1.0) * 0.1
    return lo - pad, hi + pad


def _spec_values(ax, rows: list[dict], d: int, prule: dict) -> int:
    """The top panel of a numeric curve: values with their intervals (clipped at the scale, arrows where they run
    off), the band shaded, the default ``d`` marked, configurations without a value by verdict at the bottom, the
    named flips ringed. Returns the number of clipped intervals."""
    import textwrap

    import numpy as np

    x_all = np.arange(len(rows))
    has = np.array([r["point"] is not None for r in rows])
    x = x_all[has]
    colours = [VERDICT_COLOURS.get(r["verdict"], "#444444") for r in rows]
    v = np.array([r["point"] for r in rows if r["point"] is not None])
    ymin, ymax = _spec_scale(ax, v, prule)
    lo, hi = np.clip(v[:, 1], ymin, ymax), np.clip(v[:, 2], ymin, ymax)
    ax.vlines(x, lo, hi, colors=[colours[i] for i in x], lw=1.6)
    ax.scatter(x, v[:, 0], c=[colours[i] for i in x], s=22, zorder=3)
    off_hi, off_lo = v[:, 2] > ymax, v[:, 1] < ymin
    if off_hi.any():
        ax.scatter(x[off_hi], np.full(off_hi.sum(), ymax), marker="^", s=30, color="#444444", zorder=4,
                   label="interval runs off the scale")  # fmt: skip
    if off_lo.any():
        ax.scatter(x[off_lo], np.full(off_lo.sum(), ymin), marker="v", s=30, color="#444444", zorder=4,
                   label=None if off_hi.any() else "interval runs off the scale")  # fmt: skip
    if (~has).any():
        ax.scatter(x_all[~has], np.full((~has).sum(), ymin), marker="x", s=36, zorder=4,
                   c=[colours[i] for i in x_all[~has]], label="no value kept: its verdict")  # fmt: skip
    lo_b, hi_b = (
        b if isinstance(b, (int, float)) and np.isfinite(b) else None for b in (prule.get("low"), prule.get("high"))
    )
    if lo_b is not None or hi_b is not None:
        band_lo = ymin if lo_b is None or (ax.get_yscale() == "log" and lo_b <= 0) else lo_b
        band_hi = ymax if hi_b is None else hi_b
        if band_hi > band_lo:
            ax.axhspan(band_lo, band_hi, color="#dfe8f5", zorder=0, label="the rule's band")
    ax.set_ylim(ymin, ymax)
    unit, quantity = prule.get("unit") or "", prule.get("quantity") or prule.get("measure") or "measured value"
    said = unit and unit != quantity and not unit.startswith("(")
    ax.set_ylabel(textwrap.fill(f"{quantity}" + (f" ({unit})" if said else ""), 34), fontsize=8)
    if prule.get("kind") == "ordering":  # no band: the reference the paper's ordering is judged against
        ref = 1.0 if prule.get("measure") == "ratio" else 0.0
        if ymin < ref < ymax:
            side = "above" if prule.get("relation", ">") == ">" else "below"
            ax.axhline(ref, color="#666666", lw=1, ls="--", zorder=1, label=f"no difference (the paper: {side})")
    if rows[d]["point"] is not None:
        ax.scatter([d], [rows[d]["point"][0]], marker="D", s=70, facecolors="none", edgecolors="black", zorder=4,
                   label="default")  # fmt: skip
    _ring_flips(ax, rows, lambda i: min(max(rows[i]["point"][0], ymin), ymax) if rows[i]["point"] else ymin)
    return int(off_hi.sum() + off_lo.sum())


def _ring_flips(ax, rows: list[dict], y) -> None:
    """A red ring around each configuration the claim's page names as a flip."""
    at = [i for i, r in enumerate(rows) if r.get("flip")]
    if at:
        ax.scatter(at, [y(i) for i in at], marker="o", s=140, facecolors="none", edgecolors=FLIP_COLOUR,
                   linewidths=1.4, zorder=5, label="a flip the page names")  # fmt: skip


def _spec_verdicts(ax, rows: list[dict], d: int, prule: dict) -> int:
    """The top panel of a curve without one value per configuration (a trend): each configuration's verdict."""
    levels = ["reproduced", "undecided", "partly", "not reproduced"]
    y = [levels.index(r["verdict"]) if r["verdict"] in levels else len(levels) for r in rows]
    ax.scatter(range(len(rows)), y, c=[VERDICT_COLOURS.get(r["verdict"], "#444444") for r in rows], s=30)
    ax.set_yticks(range(len(levels)), levels, fontsize=8)
    ax.set_ylim(len(levels) - 0.5, -0.5)
    ax.scatter([d], [y[d]], marker="D", s=80, facecolors="none", edgecolors="black", zorder=4, label="default")
    _ring_flips(ax, rows, lambda i: y[i])
    return 0


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

    from .measured import as_estimate

    es = [as_estimate(e) for e in estimates]
    v = np.array([e.value for e in es], dtype=float)
    err = [v - np.array([e.ci_low for e in es], dtype=float), np.array([e.ci_high for e in es], dtype=float) - v]
    if horizontal:
        return ax.errorbar(v, x, xerr=err, **style)
    return ax.errorbar(x, v, yerr=err, **style)
