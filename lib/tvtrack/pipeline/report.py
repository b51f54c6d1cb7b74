"""``REPRODUCTION.md`` and the README's first screen from the runs of ``make reproduce`` (:mod:`.reproduce`).

Inputs: ``papermill_runs/reproduce/<notebook>/`` (a run directory, see :mod:`tvtrack.pipeline.runner`; another
profile's runs live in ``papermill_runs/reproduce-<profile>/``, :func:`.paths.reproduce_dir`). Outputs:
``REPRODUCTION.md`` at the repository root (or in the profile's folder), rebuilt by :func:`write_report`
(``python -m tvtrack report``), with two pictures saved beside the runs (``figures/forest.png``: every claim's
measured interval against the paper's band; ``figures/robustness.png``: claims by register entries, coloured by
verdict); and the README's results block between :data:`README_BEGIN` and :data:`README_END`, regenerated once
every notebook has a paper-profile run. The README block carries no date (the date is in ``REPRODUCTION.md``
and on the site), so a ``make reproduce`` whose numbers reproduce leaves ``git status`` clean.

Claim text is generated (statements, rule text, register values such as ``sigma*2``): everything written to
Markdown goes through :func:`md_escape`.
"""

from __future__ import annotations

import json
import math
import os
import re
import time
from collections import Counter
from pathlib import Path
from typing import Any

from .paths import PAPER_PROFILE, REPO_ROOT, reproduce_dir as _reproduce_dir
from ..results import VERDICTS
from ..verdicts import LABELS
from ..plotting import VERDICT_COLOURS as _CORE_VERDICT_COLOURS
from .runner import list_notebooks, read_run

__all__ = [
    "REPRODUCE_DIR",
    "REPORT_PATH",
    "README_PATH",
    "README_BEGIN",
    "README_END",
    "ALL_VERDICTS",
    "ALL_LABELS",
    "write_report",
    "md_escape",
    "format_measured",
    "robustness_label",
    "robustness_where",
    "coverage_text",
    "part_labels",
    "verdict_summary",
    "results_paragraph",
    "update_readme",
    "collect_runs",
    "first_screen",
    "first_screen_table",
    "forest_items",
    "forest_plot",
    "robustness_matrix",
    "robustness_picture",
    "profiles_shown",
]

REPRODUCE_DIR = _reproduce_dir()
REPORT_PATH = REPO_ROOT / "REPRODUCTION.md"
README_PATH = REPO_ROOT / "README.md"
README_BEGIN = "<!-- begin generated results -->"
README_END = "<!-- end generated results -->"
NO_LABEL = "—"
"""Shown for a claim without a robustness record (not checkable, or a run from before the verdict standard)."""
ALL_VERDICTS = tuple(VERDICTS) + tuple(v for v in ("undecided",) if v not in VERDICTS)
"""Every verdict a record may carry: the core's, and ``undecided`` (issue 22) where the core predates it."""
ALL_LABELS = tuple(reversed(LABELS)) + tuple(lab for lab in ("unexplored",) if lab not in LABELS)
"""Every robustness label a record may carry, strongest first (``unexplored``: no regime or operating point
was varied)."""
VERDICT_COLOURS = {
    **{
        "reproduced": "#009E73",
        "partly": "#E69F00",
        "not reproduced": "#D55E00",
        "undecided": "#999999",
        "not checkable": "#56B4E9",
    },
    **_CORE_VERDICT_COLOURS,
}
"""One colour per verdict, the palette of :mod:`tvtrack.plotting` (figures, recordings, report and site)."""
LABEL_MARKERS = {"robust": "o", "depends": "D", "unstable": "X", "unexplored": "s", NO_LABEL: "."}

_MD_SPECIAL = re.compile(r"([\\`*_{}\[\]<>|~#])")


def md_escape(text: Any) -> str:
    """Generated text made literal in Markdown (``sigma*2`` stays ``sigma*2``, a ``|`` does not split a table
    cell, ``<b>`` is not HTML); line breaks become spaces."""
    return _MD_SPECIAL.sub(r"\\\1", " ".join(str(text).split()))


def format_measured(value: Any) -> str:
    """Short text for a claim's ``measured`` field (Estimates as ``v [lo, hi]``)."""
    if isinstance(value, dict) and "value" in value and "ci_low" in value:
        v, lo, hi = value["value"], value.get("ci_low"), value.get("ci_high")
        if v is None:
            return "no value"
        if lo is None or hi is None:
            return _num(v)
        return f"{_num(v)} [{_num(lo)}, {_num(hi)}]"
    if isinstance(value, dict):
        return "; ".join(f"{k}: {format_measured(v)}" for k, v in value.items())
    if isinstance(value, list):
        return ", ".join(format_measured(v) for v in value)
    return _num(value)


def _num(v: Any) -> str:
    if isinstance(v, bool) or v is None:
        return str(v)
    if isinstance(v, (int, float)):
        return f"{v:.4g}"
    return str(v)


def _cell(text: Any) -> str:
    return md_escape(text)


def robustness_label(claim: dict) -> str:
    """The claim's robustness label, or :data:`NO_LABEL` when it has no record (not checkable,
    or a ``results.json`` written before the verdict standard)."""
    record = claim.get("robustness")
    return record.get("label", NO_LABEL) if record else NO_LABEL


def robustness_where(claim: dict) -> str:
    """Where the claim's verdict differs from the default reading ("" when robust or unrecorded)."""
    record = claim.get("robustness")
    return "; ".join(record.get("where", [])) if record else ""


def coverage_text(claim: dict) -> str:
    """The record's sentence saying what its label covers ("robust over 14 readings x 3 replicates: ..."), or
    for a record without one (before issue 22) what it counted: other readings and seeds."""
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
    """``[(part, verdict, label)]`` from the record's ``parts`` (issue 22: a label per part of a rule); empty for
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


def verdict_summary(claims: list[dict]) -> str:
    """``"3 reproduced (2 robust, 1 depends) · 1 partly (1 unstable) · ..."``: each verdict's
    count with its robustness labels (a claim without a record counts as "no record")."""
    parts = []
    for verdict in ALL_VERDICTS:
        these = [c for c in claims if c["verdict"] == verdict]
        if verdict == "undecided" and not these:
            continue
        labels = Counter(robustness_label(c) for c in these)
        detail = [f"{labels[label]} {label}" for label in ALL_LABELS if labels[label]]
        if verdict != "not checkable" and labels[NO_LABEL]:
            detail.append(f"{labels[NO_LABEL]} no record")
        parts.append(f"{len(these)} {verdict}" + (f" ({', '.join(detail)})" if detail else ""))
    return " · ".join(parts)


def collect_runs(reproduce_dir: Path, notebooks: list[str]) -> dict[str, tuple[dict | None, dict | None]]:
    """``{name: (run.json, results.json)}`` for each notebook; ``None`` where missing (not run, or failed)."""
    runs = {}
    for name in notebooks:
        run_dir = Path(reproduce_dir) / name
        record = read_run(run_dir)
        data = None
        if record is not None and record.get("status") == "ok":
            data = json.loads((run_dir / "results.json").read_text())
        runs[name] = (record, data)
    return runs


def profiles_shown(runs: dict[str, tuple[dict | None, dict | None]]) -> str:
    """ "paper", or the profiles of the runs shown when they are not all paper-scale ("smoke", "paper and smoke")."""
    names = sorted({(record or {}).get("profile") or PAPER_PROFILE for record, data in runs.values() if data})
    return " and ".join(names) if names else PAPER_PROFILE


# --- the first screen: what does not reproduce, and what depends ------------------------------------------------

_FIRST_ORDER = {"not reproduced": 0, "undecided": 1}


def first_screen(runs: dict[str, tuple[dict | None, dict | None]]) -> list[dict]:
    """The claims a researcher asks about first, one row each: every claim that does not reproduce or is
    undecided, then every other checkable claim whose verdict depends on a reading or is unstable.

    Rows: ``{paper, id, statement, paper_value, measured, verdict, label}`` (measured with its interval)."""
    rows = []
    for name, (_, data) in runs.items():
        for c in (data or {}).get("claims", []):
            label = robustness_label(c)
            if c["verdict"] in _FIRST_ORDER or (c["verdict"] != "not checkable" and label in ("depends", "unstable")):
                rows.append(
                    {
                        "paper": name,
                        "id": c["id"],
                        "statement": c["statement"],
                        "paper_value": c.get("paper_value", ""),
                        "measured": format_measured(c["measured"]),
                        "verdict": c["verdict"],
                        "label": label,
                        "where": robustness_where(c),
                    }
                )
    return sorted(rows, key=lambda r: (_FIRST_ORDER.get(r["verdict"], 2), r["paper"], _claim_order(r["id"])))


def _claim_order(cid: str):
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", cid)]


def first_screen_table(rows: list[dict]) -> str:
    """The rows of :func:`first_screen` as a Markdown table (text escaped), or a sentence when there are none."""
    if not rows:
        return "Every checkable claim reproduces, robustly or without a robustness record."
    lines = [
        "| claim | statement | paper | measured [95 % interval] | verdict | label |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    lines += [
        f"| {r['paper'][:3]} {r['id']} | {md_escape(r['statement'])} | {md_escape(r['paper_value'])} | "
        f"{md_escape(r['measured'])} | **{r['verdict']}** | {r['label']} |"
        for r in rows
    ]
    return "\n".join(lines)


# --- the pictures --------------------------------------------------------------------------------------------------


def _estimate(value: Any) -> tuple[float, float, float] | None:
    """``(value, low, high)`` of an Estimate-like dict or a plain number; ``None`` otherwise."""
    if isinstance(value, dict) and "value" in value:
        v, lo, hi = value.get("value"), value.get("ci_low"), value.get("ci_high")
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


def forest_items(runs: dict[str, tuple[dict | None, dict | None]]) -> list[dict]:
    """One row per checkable claim (one per part for an ``all of`` rule) that has an interval and a band:
    ``{name, verdict, label, band, value, low, high}`` with the value and interval on the band's scale
    (:func:`_relative`: the paper's band is [0, 1])."""
    items = []
    for name, (_, data) in runs.items():
        for c in (data or {}).get("claims", []):
            if c["verdict"] == "not checkable":
                continue
            rule, measured = c.get("rule") or {}, c["measured"]
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
    """Claims (rows) by register entries (columns): in each cell the verdict that differs from the claim's own
    when that entry takes another value (any condition varying it), else the claim's verdict; ``None`` where the
    claim was not explored over the entry. Works on records with ``register`` (issue 22) or ``choices``."""
    entries: list[str] = []
    rows, cells = [], []
    for c in claims:
        if c["verdict"] == "not checkable" or not c.get("robustness"):
            continue
        names = register_names(c)
        entries += [n for n in names if n not in entries]
        row = {}
        for cond in c["robustness"].get("conditions", []):
            choices = cond.get("choices") or cond.get("config") or {}
            for entry in choices:
                differs = cond.get("verdict") != c["verdict"]
                if differs or entry not in row:
                    row[entry] = cond.get("verdict") if differs else c["verdict"]
                    if differs:
                        row[f"!{entry}"] = True
        for n in names:
            row.setdefault(
                n,
                c["verdict"]
                if any(n in (cond.get("choices") or {}) for cond in c["robustness"].get("conditions", []))
                else None,
            )
        rows.append(c["id"])
        cells.append(row)
    return rows, entries, [[row.get(e) for e in entries] for row in cells]


def robustness_picture(runs: dict[str, tuple[dict | None, dict | None]], path: Path) -> Path | None:
    """One panel per notebook: its claims (rows) by its register entries (columns), each cell coloured by the
    verdict under that entry's other values (see :func:`robustness_matrix`; blank: not explored)."""
    panels = []
    for name, (_, data) in runs.items():
        rows, entries, cells = robustness_matrix((data or {}).get("claims", []))
        if rows and entries:
            panels.append((name, rows, entries, cells))
    if not panels:
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    heights = [max(len(rows), 1) * 0.22 + 1.6 for _, rows, _, _ in panels]
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
            [j + 0.5 for j in range(len(entries))], [e[:24] for e in entries], rotation=35, ha="right", fontsize=7
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
        + [Patch(color="#f4f4f4", label="not explored")],
        loc="lower center",
        ncol=len(used) + 1,
        fontsize=7,
        frameon=False,
    )
    fig.suptitle("Claims by register entries: the verdict when the entry takes its other values", fontsize=9)
    fig.tight_layout(rect=(0, 0.03, 1, 0.98))
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


# --- REPRODUCTION.md -----------------------------------------------------------------------------------------------


def _details(c: dict) -> str:
    """One claim's rule, where its verdict differs, what the label covers, its parts and note: the text behind the
    compact table (a ``<details>`` block)."""
    bits = [f"rule: {md_escape(c.get('acceptance', ''))}"]
    if robustness_where(c):
        bits.append(f"where it differs: {md_escape(robustness_where(c))}")
    if coverage_text(c):
        bits.append(f"covers: {md_escape(coverage_text(c))}")
    parts = part_labels(c)
    if parts:
        bits.append("parts: " + "; ".join(f"{md_escape(p)} {v}, {lab}" for p, v, lab in parts))
    if c.get("note"):
        bits.append(f"note: {md_escape(c['note'])}")
    return f"- **{c['id']}** " + " · ".join(bits)


def write_report(
    reproduce_dir: Path = REPRODUCE_DIR,
    path: Path = REPORT_PATH,
    notebooks: list[str] | None = None,
    readme: Path | None = None,
) -> Path:
    """Rebuild ``REPRODUCTION.md`` from the run directories under ``reproduce_dir``
    (one section per notebook of ``notebooks``, default: all in ``notebooks/``).

    The report opens with the profile it shows and its date, the first screen (:func:`first_screen`), the forest
    plot and the robustness picture (saved in ``reproduce_dir/figures/``), then one section per notebook with a
    compact table and each claim's rule and coverage behind a click. With ``readme``, also regenerate that file's
    results block (:func:`update_readme`) when every notebook has a successful paper-profile run; otherwise the
    README is left as it is and the reason is printed.
    """
    if notebooks is None:
        notebooks = [nb.stem for nb in list_notebooks()]
    runs = collect_runs(reproduce_dir, notebooks)
    sections, claims = [], []
    for name in notebooks:
        run_dir = Path(reproduce_dir) / name
        rel = os.path.relpath(run_dir, path.parent)
        record, data = runs[name]
        if record is None:
            sections.append(
                f"## {name}\n\nNot run yet: `make reproduce` (or `python -m tvtrack reproduce --only {name}`).\n"
            )
            continue
        if data is None:
            sections.append(
                f"## {name}\n\n**Run failed** after {record.get('runtime_s', 0):.0f} s: "
                f"`{str(record.get('error')).replace('`', chr(39))}` "
                f"(see [{rel}/error.txt]({rel}/error.txt)).\n"
            )
            continue
        claims += data["claims"]
        lines = [
            f"## {name}",
            "",
            f"*{md_escape(data['citation'])}*",
            "",
            f"Profile `{record.get('profile')}`, seed {data['seed']}, runtime {record['runtime_s']:.0f} s "
            f"(notebook {data['runtime_s']:.0f} s), commit `{data.get('git_commit')}`. "
            f"[Executed notebook]({rel}/notebook.ipynb) · [results.json]({rel}/results.json)",
        ]
        if data.get("recording"):
            lines[-1] += (
                f" · [recording]({rel}/{data['recording']}) (in the browser: "
                f"`python -m tvtrack view {rel}`; desktop: `rerun {rel}/{data['recording']}`)"
            )
        lines += [
            "",
            verdict_summary(data["claims"]),
            "",
            "| claim | verdict | robustness | where the verdict differs | statement | paper | measured |",
            "| --- | --- | --- | --- | --- | --- | --- |",
        ]
        for c in data["claims"]:
            lines.append(
                "| "
                + " | ".join(
                    (
                        c["id"],
                        f"**{c['verdict']}**",
                        robustness_label(c),
                        _cell(robustness_where(c)),
                        _cell(c["statement"]),
                        _cell(c["paper_value"]),
                        _cell(format_measured(c["measured"])),
                    )
                )
                + " |"
            )
        lines += ["", "<details><summary>Rules, coverage and notes</summary>", ""]
        lines += [_details(c) for c in data["claims"]]
        lines += ["", "</details>"]
        if data.get("figures"):
            lines += ["", "Figures:", ""]
            lines += [f"- [{_cell(f['caption'])}]({rel}/{f['file']})" for f in data["figures"]]
        sections.append("\n".join(lines) + "\n")
    shown = profiles_shown(runs)
    head = ["# Reproduction report", ""]
    if not notebooks:
        head += ["No notebooks in `notebooks/` yet: nothing to reproduce.", ""]
    else:
        counts = Counter(c["verdict"] for c in claims)
        labels = Counter(robustness_label(c) for c in claims if c["verdict"] != "not checkable")
        folder = os.path.relpath(reproduce_dir, path.parent)
        head += [
            f"**Profile shown: {shown}** (runs in `{folder}/`)"
            + ("" if shown == PAPER_PROFILE else ": **not the paper-scale numbers**")
            + ". "
            f"Written {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} by `make reproduce` "
            "(rebuild with `python -m tvtrack report`).",
            "",
            "**Claims: "
            + " · ".join(f"{counts[v]} {v}" for v in ALL_VERDICTS if v != "undecided" or counts[v])
            + f"** ({len(claims)} claims, {len(notebooks)} notebooks); of the checkable verdicts **"
            + " · ".join(f"{labels[lab]} {lab}" for lab in ALL_LABELS)
            + "**"
            + (f" · {labels[NO_LABEL]} without a robustness record" if labels[NO_LABEL] else ""),
            "",
            f"By verdict: {verdict_summary(claims)}.",
            "",
            "## The claims that do not reproduce, and the verdicts that depend",
            "",
            first_screen_table(first_screen(runs)),
            "",
        ]
        figures = Path(reproduce_dir) / "figures"
        forest = forest_plot(forest_items(runs), figures / "forest.png")
        picture = robustness_picture(runs, figures / "robustness.png")
        if forest:
            head += [
                f"![forest plot: every claim's measured interval against the paper's band]"
                f"({os.path.relpath(forest, path.parent)})",
                "",
                "Every claim with an interval and a band: the measured 95 % interval (line) and value (marker: "
                "the robustness label) on the scale of the paper's band (shaded, [0, 1]), coloured by verdict.",
                "",
            ]
        if picture:
            head += [
                f"![robustness: claims by register entries]({os.path.relpath(picture, path.parent)})",
                "",
                "Each notebook's claims by the register entries they were explored over: a cell's colour is the "
                "verdict when that entry takes its other values (the claim's own verdict where none differs).",
                "",
            ]
        head += [
            "Verdicts come from the notebooks' own Monte Carlo runs at the default reading of what each paper "
            "left unstated; *robust*: the same verdict, part by part, under every register value tried (one at "
            "a time and joint samples) and every independent replicate (each claim's coverage says which); "
            "*unexplored*: no regime, operating point or model of the simulated world was varied; *depends*: "
            "the verdict changes under another value (the table says where); *unstable*: independent "
            "replicates disagree at the default. See each notebook for the reasoning.",
            "",
        ]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(head + sections))
    if readme is not None:
        incomplete = [
            name for name, (record, data) in runs.items() if data is None or record.get("profile") != PAPER_PROFILE
        ]
        if incomplete:
            print(
                f"{readme.name}: results block left as it is (no successful paper-profile run of "
                f"{', '.join(incomplete)}; `make reproduce` runs them)"
            )
        else:
            update_readme(readme, results_paragraph(runs))
            print(f"{readme.name}: results block regenerated")
    return path


def results_paragraph(runs: dict[str, tuple[dict | None, dict | None]]) -> str:
    """The README's results block (Markdown) from :func:`collect_runs`: the counts by verdict and robustness,
    then the first screen (:func:`first_screen_table`). No date: the block changes only when a verdict, a label
    or a number does, so ``git status`` after ``make reproduce`` is itself a reproducibility check."""
    done = {name: (record, data) for name, (record, data) in runs.items() if data is not None}
    missing = sorted(set(runs) - set(done))
    flat = [c for _, data in done.values() for c in data["claims"]]
    if not flat:
        return (
            "No results yet: `make reproduce` runs every notebook at paper scale and `python -m tvtrack report` "
            "writes this block from them."
        )
    counts = Counter(c["verdict"] for c in flat)
    labels = Counter(robustness_label(c) for c in flat if c["verdict"] != "not checkable")
    verdicts = " · ".join(f"{counts[v]} {v}" for v in ALL_VERDICTS if v != "undecided" or counts[v])
    label_text = ", ".join(f"{labels[lab]} {lab}" for lab in ALL_LABELS)
    lines = [
        f"{len(flat)} claims ({profiles_shown(done)} profile): **{verdicts}**; of the checkable verdicts "
        f"{label_text}"
        + (f", {labels[NO_LABEL]} without a robustness record" if labels[NO_LABEL] else "")
        + ". The claims that do not reproduce, and those whose verdict depends on a reading of what the paper "
        "left unstated or changes between replicates:"
    ]
    if missing:
        lines[0] = f"Not included (no successful run): {', '.join(missing)}. " + lines[0]
    lines += [
        "",
        first_screen_table(first_screen(done)),
        "",
        "Every claim with its rule, interval and coverage: `REPRODUCTION.md` (written by `make reproduce`) and "
        "the site's ledger (`make site`).",
    ]
    return "\n".join(lines)


def update_readme(readme: Path, paragraph: str) -> None:
    """Replace the text between :data:`README_BEGIN` and :data:`README_END` in ``readme``."""
    text = Path(readme).read_text()
    pattern = re.compile(re.escape(README_BEGIN) + r".*?" + re.escape(README_END), re.S)
    if not pattern.search(text):
        raise ValueError(f"{readme}: no '{README_BEGIN}' ... '{README_END}' markers to put the results between")
    new = pattern.sub(lambda _: f"{README_BEGIN}\n{paragraph}\n{README_END}", text, count=1)
    if new != text:  # an unchanged block leaves the file (and its timestamp) alone
        Path(readme).write_text(new)
