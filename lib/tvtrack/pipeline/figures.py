"""The claims as the report and the site draw and count them: the verdict and label words in their order, the label
a reader sees for a claim, and the two overview pictures (every claim against its band; claims by register entries)
in the colours of :data:`tvtrack.plotting.VERDICT_COLOURS`.

Reads ``results.json`` claim dicts only (schema: :mod:`tvtrack.results`).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from ..plotting import VERDICT_COLOURS
from ..results import record_end, shown_label
from ..verdicts import LABELS, VERDICTS, is_decisive

__all__ = [
    "NO_LABEL",
    "ALL_VERDICTS",
    "ALL_LABELS",
    "LABEL_MARKERS",
    "robustness_label",
    "robustness_where",
    "coverage_text",
    "part_labels",
    "register_names",
    "forest_items",
    "forest_plot",
    "robustness_matrix",
    "robustness_picture",
]

NO_LABEL = "—"
"""Shown for a claim without a robustness record (not checkable, or a run from before the verdict standard)."""
ALL_VERDICTS = tuple(VERDICTS) + tuple(v for v in ("undecided",) if v not in VERDICTS)
"""Every verdict a record may carry: the core's, and ``undecided`` where the core predates it."""
_LABEL_ORDER = ("robust", "limited", "unexplored", "depends", "unstable", "provisional")
ALL_LABELS = tuple(
    lab for lab in _LABEL_ORDER if lab in LABELS or lab in ("limited", "unexplored", "provisional")
) + tuple(lab for lab in LABELS if lab not in _LABEL_ORDER)
"""Every label a reader may see, strongest first (``provisional``: a design too small to label, a smoke run;
``limited``: holds under every reading of the paper but not in a named world beyond it)."""
LABEL_MARKERS = {
    "robust": "o",
    "limited": "P",
    "depends": "D",
    "unstable": "X",
    "unexplored": "s",
    "provisional": "v",
    NO_LABEL: ".",
}


def robustness_label(claim: dict) -> str:
    """The label a reader sees (:func:`tvtrack.results.shown_label`): the record's, ``provisional`` for a design
    too small to label, or :data:`NO_LABEL` without a record (not checkable, or a run from before the verdict
    standard)."""
    return shown_label(claim) if claim.get("robustness") else NO_LABEL


def robustness_where(claim: dict) -> str:
    """Where the claim's verdict differs from the default reading ("" when robust or unrecorded)."""
    record = claim.get("robustness")
    return "; ".join(record.get("where", [])) if record else ""


def coverage_text(claim: dict) -> str:
    """The record's sentence saying what its label covers ("robust over 14 readings x 3 replicates: ..."), or
    for a record without one (an older record) what it counted: other readings and seeds."""
    record = claim.get("robustness")
    if not record:
        return ""
    if record.get("coverage"):
        return str(record["coverage"])
    n_cond, n_seed = len(record.get("conditions", [])), len(record.get("replicates", record.get("seeds", [])))
    tested = [
        f"{n} {what}{'s' if n != 1 else ''}" for n, what in ((n_cond, "other reading"), (n_seed, "replicate")) if n
    ]
    return f"{record.get('label', NO_LABEL)} over {' and '.join(tested)}" if tested else ""


def part_labels(claim: dict) -> list[tuple[str, str, str]]:
    """``[(part, verdict, label)]`` from the record's ``parts`` (a label per part of a rule); empty for
    records without parts."""
    parts = (claim.get("robustness") or {}).get("parts") or {}
    if isinstance(parts, list):
        parts = {p.get("name", str(i)): p for i, p in enumerate(parts)}
    return [
        (str(name), str(p.get("verdict", "")), str(p.get("label", "")))
        for name, p in parts.items()
        if isinstance(p, dict)
    ]


def register_names(claim: dict) -> list[str]:
    """Names of the register entries the claim's record was explored over (``register``, or the older
    ``choices``)."""
    record = claim.get("robustness") or {}
    entries = record.get("register") or record.get("choices") or []
    if isinstance(entries, dict):
        entries = entries.get("entries", list(entries.values()))
    return [str(e["name"]) if isinstance(e, dict) else str(e) for e in entries]


# --- the pictures --------------------------------------------------------------------------------------------------


def _estimate(value: Any) -> tuple[float, float, float] | None:
    """``(value, low, high)`` of an Estimate-like dict or a plain number; ``None`` otherwise."""
    if isinstance(value, dict) and "value" in value:
        v, lo, hi = value.get("value"), record_end(value, "ci_low"), record_end(value, "ci_high")
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        v = lo = hi = value
    else:
        return None
    try:
        v, lo, hi = float(v), float(v if lo is None else lo), float(v if hi is None else hi)
    except (TypeError, ValueError):
        return None
    return (v, lo, hi) if math.isfinite(v) else None


def _band(rule: dict) -> tuple[float | None, float | None] | None:
    """The paper's band ``(low, high)`` of an in-band rule (either end may be ``None``: open)."""
    if not isinstance(rule, dict) or "low" not in rule and "high" not in rule:
        return None
    lo, hi = rule.get("low"), rule.get("high")
    lo = None if lo is None or not math.isfinite(float(lo)) else float(lo)
    hi = None if hi is None or not math.isfinite(float(hi)) else float(hi)
    return None if lo is None and hi is None else (lo, hi)


def _relative(x: float, band: tuple[float | None, float | None]) -> float:
    """Position of ``x`` on a scale where the band is [0, 1] (one-sided bands: the finite end at 0 or 1, one unit
    = the end's magnitude)."""
    lo, hi = band
    if lo is not None and hi is not None and hi > lo:
        return (x - lo) / (hi - lo)
    if lo is not None:
        return (x - lo) / (abs(lo) or 1.0)
    return 1.0 + (x - hi) / (abs(hi) or 1.0)


def _reading_rule(rule: dict, measured: Any) -> tuple[dict, Any]:
    """The rule that judged ``measured`` and what it judged: a rule chosen by a reading (``by_reading``) opened to
    the reading's own rule (the default's where the reading has none of its own) and the value measured under it."""
    if rule.get("kind") == "by_reading" and isinstance(measured, dict) and set(measured) == {"reading", "measured"}:
        chosen = (rule.get("rules") or {}).get(str(measured["reading"])) or rule.get("default") or {}
        return _reading_rule(chosen, measured["measured"])
    return rule, measured


def forest_items(runs: dict[str, tuple[dict | None, dict | None]]) -> list[dict]:
    """One row per checkable claim (one per part for an ``all of`` rule) that has an interval and a band:
    ``{name, verdict, label, band, value, low, high}`` with the value and interval on the band's scale
    (:func:`_relative`: the paper's band is [0, 1])."""
    items = []
    for name, (_, data) in runs.items():
        for c in (data or {}).get("claims", []):
            if c["verdict"] == "not checkable":
                continue
            rule, measured = _reading_rule(c.get("rule") or {}, c["measured"])
            pairs = [(c["id"], rule, measured, c["verdict"])]
            if rule.get("kind") == "all_of" and isinstance(measured, dict):
                parts = dict(((p, (v, lab)) for p, v, lab in part_labels(c)))
                pairs = [
                    (f"{c['id']} {part}", sub, measured.get(part), parts.get(part, (c["verdict"], ""))[0])
                    for part, sub in (rule.get("parts") or {}).items()
                ]
            for label_text, sub, value, verdict in pairs:
                band, est = _band(sub), _estimate(value)
                if band is None or est is None:
                    continue
                v, lo, hi = (_relative(x, band) for x in est)
                items.append(
                    {
                        "name": f"{name[:3]} {label_text}",
                        "verdict": verdict or c["verdict"],
                        "label": robustness_label(c),
                        "band": band,
                        "value": v,
                        "low": min(lo, hi),
                        "high": max(lo, hi),
                    }
                )
    return items


def forest_plot(items: list[dict], path: Path) -> Path | None:
    """Every claim's measured value and 95 % interval against the paper's band (shaded, [0, 1] on this scale),
    coloured by verdict and marked by robustness label; ``None`` when no claim has an interval and a band."""
    if not items:
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    clip = (-2.0, 3.0)
    fig, ax = plt.subplots(figsize=(7.5, 0.9 + 0.22 * len(items)))
    ax.axvspan(0, 1, color="#dfe8f5", zorder=0)
    for k, it in enumerate(reversed(items)):
        colour = VERDICT_COLOURS.get(it["verdict"], "#000000")
        lo, hi, v = (min(max(x, clip[0]), clip[1]) for x in (it["low"], it["high"], it["value"]))
        lo_band, hi_band = it["band"]
        if lo_band is None:
            ax.plot([clip[0], 1], [k, k], color="#dfe8f5", lw=6, zorder=0)
        if hi_band is None:
            ax.plot([0, clip[1]], [k, k], color="#dfe8f5", lw=6, zorder=0)
        ax.plot([lo, hi], [k, k], color=colour, lw=2)
        ax.plot([v], [k], marker=LABEL_MARKERS.get(it["label"], "."), color=colour, ms=6, mec="black", mew=0.5)
    ax.set_yticks(range(len(items)), [it["name"] for it in reversed(items)], fontsize=7)
    ax.set_xlim(*clip)
    ax.set_xlabel("measured value on the scale of the paper's band (band = [0, 1], shaded; clipped at the edges)")
    verdicts = [v for v in ALL_VERDICTS if any(it["verdict"] == v for it in items)]
    labels = [lab for lab in (*ALL_LABELS, NO_LABEL) if any(it["label"] == lab for it in items)]
    handles = [Line2D([], [], color=VERDICT_COLOURS.get(v, "k"), lw=2, label=v) for v in verdicts]
    handles += [Line2D([], [], color="grey", marker=LABEL_MARKERS[lab], ls="", label=lab) for lab in labels]
    ax.legend(
        handles=handles,
        fontsize=7,
        loc="upper center",
        bbox_to_anchor=(0.5, -0.6 / len(items) - 0.08),
        ncol=min(len(handles), 5),
        frameon=False,
    )
    ax.set_title("Every claim: measured 95 % interval against the paper's band", fontsize=9)
    ax.grid(axis="x", alpha=0.3)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def robustness_matrix(claims: list[dict]) -> tuple[list[str], list[str], list[list[str | None]]]:
    """Claims (rows) by register entries (columns), from the one-at-a-time design: in each cell the decided
    verdict that differs from the claim's own when that entry alone takes another value (the first such condition),
    else the claim's verdict where a condition varying the entry decided as the default did, else ``undecided``
    (no condition varying it decided); ``None`` where no condition varied the entry alone. Joint conditions are
    left out: a flip that needs two entries changed together belongs to neither column. Records written before
    conditions named what they changed (``choices``) are read the same way."""
    entries: list[str] = []
    rows, cells = [], []
    for c in claims:
        if c["verdict"] == "not checkable" or not c.get("robustness"):
            continue
        names = register_names(c)
        entries += [n for n in names if n not in entries]
        seen: dict[str, list[str]] = {}
        for cond in c["robustness"].get("conditions", []):
            changed = cond.get("changed") if "changed" in cond else cond.get("choices")
            if not isinstance(changed, dict) or len(changed) != 1 or cond.get("kind", "single") != "single":
                continue
            seen.setdefault(next(iter(changed)), []).append(str(cond.get("verdict")))
        row = {}
        for entry, verdicts in seen.items():
            differs = [v for v in verdicts if is_decisive(v) and v != c["verdict"]]
            agrees = any(v == c["verdict"] and is_decisive(v) for v in verdicts)
            row[entry] = differs[0] if differs else c["verdict"] if agrees else "undecided"
        rows.append(c["id"])
        cells.append(row)
    return rows, entries, [[row.get(e) for e in entries] for row in cells]


def _short(text: str, chars: int) -> str:
    return text if len(text) <= chars else text[: chars - 1] + "…"


def robustness_picture(runs: dict[str, tuple[dict | None, dict | None]], path: Path) -> Path | None:
    """One panel per notebook: its claims (rows) by its register entries (columns), each cell coloured by the
    verdict when that entry alone takes another value (see :func:`robustness_matrix`; blank: not varied alone)."""
    panels = []
    for name, (_, data) in runs.items():
        rows, entries, cells = robustness_matrix((data or {}).get("claims", []))
        if rows and entries:
            panels.append((name, rows, entries, cells))
    if not panels:
        return None
    titles = {  # the entries by their titles (plain words), not their register keys
        str(e["name"]): str(e.get("title") or e["name"])
        for _record, data in runs.values()
        for c in (data or {}).get("claims", [])
        for e in (c.get("robustness") or {}).get("register") or []
        if isinstance(e, dict) and "name" in e
    }
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    heights = [  # rows, and room for the rotated entry titles below them
        max(len(rows), 1) * 0.22 + 1.0 + 0.035 * max(len(_short(titles.get(e, e), 32)) for e in entries)
        for _, rows, entries, _ in panels
    ]
    fig, axes = plt.subplots(
        len(panels), 1, figsize=(8, sum(heights)), squeeze=False, gridspec_kw={"height_ratios": heights}
    )
    for ax, (name, rows, entries, cells) in zip(axes[:, 0], panels):
        for i, row in enumerate(cells):
            for j, verdict in enumerate(row):
                colour = VERDICT_COLOURS.get(verdict, "#ffffff") if verdict else "#f4f4f4"
                ax.add_patch(plt.Rectangle((j, i), 1, 1, color=colour, ec="white", lw=1))
        ax.set_xlim(0, len(entries))
        ax.set_ylim(len(rows), 0)
        ax.set_xticks(
            [j + 0.5 for j in range(len(entries))],
            [_short(titles.get(e, e), 32) for e in entries],
            rotation=35,
            ha="right",
            fontsize=7,
        )
        ax.set_yticks([i + 0.5 for i in range(len(rows))], rows, fontsize=7)
        ax.set_title(name, fontsize=8, loc="left")
        ax.tick_params(length=0)
    used = sorted(
        {v for _, _, _, cells in panels for row in cells for v in row if v},
        key=lambda v: ALL_VERDICTS.index(v) if v in ALL_VERDICTS else 99,
    )
    fig.legend(
        handles=[Patch(color=VERDICT_COLOURS.get(v, "k"), label=v) for v in used]
        + [Patch(color="#f4f4f4", label="not varied alone")],
        loc="lower center",
        ncol=len(used) + 1,
        fontsize=7,
        frameon=False,
    )
    fig.suptitle("Claims by register entries: the verdict when that entry alone takes another value", fontsize=9)
    fig.tight_layout(rect=(0, 0.03, 1, 0.98))
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
