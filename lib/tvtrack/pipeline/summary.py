"""A sweep's summary: ``summary.csv`` (one row per run) and ``summary.png`` (the ``[summary]`` metric ``y``
against ``x``), and the check, made before any run starts, that ``y`` names a metric the notebook writes.

A run's metrics (``results.json``) may nest: ``{"detection": {"median_s": {"value": 1.2, "ci_low": ...}}}``.
Every number at any depth is a column named by its dotted path (``detection.median_s.value``); strings and
lists are left out of the table.
"""

from __future__ import annotations

import csv
import dataclasses
import difflib
import json
import re
import warnings
from pathlib import Path
from typing import Any

from .preflight import UsageError, code_cells
from .runfiles import load_results, load_run

__all__ = [
    "flatten_metrics",
    "notebook_metric_names",
    "check_summary_table",
    "check_plot_values",
    "check_metric",
    "check_metric_in",
    "collect_summary",
    "SCALES",
]

MAX_DEPTH = 6
#: The axis scales ``[summary] xscale``/``yscale`` may name (Matplotlib's scales that need no arguments).
SCALES = ("linear", "log", "symlog", "logit")
_TEXT_KEYS = ("x", "y", "hue", "xlabel", "ylabel", "title")
_METRIC_CALL = re.compile(r"\.metric\(\s*(f?)(\"[^\"\n]*\"|'[^'\n]*'|[^,\s)]+)")


def flatten_metrics(metrics: dict, prefix: str = "", depth: int = 0) -> dict[str, Any]:
    """``{dotted path: number}`` for every number (int, float, bool, None) at any depth of ``metrics``."""
    out: dict[str, Any] = {}
    for name, value in metrics.items():
        key = f"{prefix}{name}"
        if isinstance(value, (int, float, bool)) or value is None:
            out[key] = value
        elif isinstance(value, dict) and depth < MAX_DEPTH:
            out.update(flatten_metrics(value, key + ".", depth + 1))
    return out


def notebook_metric_names(notebook: Path) -> list[str] | None:
    """The metric names a notebook writes (``results.metric("NAME", ...)`` calls; an f-string's fields read as
    ``{...}``), or ``None`` when a name is computed (a variable) and cannot be read from the source."""
    names: list[str] = []
    for source in code_cells(notebook):
        for fstring, arg in _METRIC_CALL.findall(source):
            if arg[0] not in "\"'":
                return None
            names.append(arg[1:-1] if not fstring else re.sub(r"\{[^}]*\}", "{...}", arg[1:-1]))
    return names or None


def estimate_parts() -> tuple[str, ...]:
    """The parts of a metric recorded as an estimate (``NAME.value``, ``NAME.ci_low``, ...)."""
    from ..montecarlo import Estimate  # heavy (NumPy, SciPy): only when a nested path is checked

    return tuple(f.name for f in dataclasses.fields(Estimate))


def _matches(name: str, y: str) -> bool:
    return _rest(name, y) is not False


def _rest(name: str, y: str) -> str | None | bool:
    """The dotted path of ``y`` below the metric ``name`` (``None``: ``y`` is the metric itself; ``False``: ``y``
    is not under ``name``)."""
    pattern = ".+".join(re.escape(part) for part in name.split("{...}"))
    found = re.fullmatch(pattern + r"(?:\.(.+))?", y)
    return False if found is None else found.group(1)


def _check_part(names: list[str], y: str, where: str, notebook: Path) -> None:
    """Refuse ``y = NAME.PART`` whose PART is a misspelt estimate part (``value`` typed ``valeu``), before any run;
    a part that is no near miss may be a key of a dict metric: the first run's results decide (:mod:`.sweep`)."""
    rests = [_rest(n, y) for n in names if _matches(n, y)]
    if any(r is None or "." in r for r in rests):
        return
    parts = estimate_parts()
    if any(r in parts for r in rests):
        return
    for rest in rests:
        close = difflib.get_close_matches(rest, parts, n=1, cutoff=0.75)
        if close:
            head = y[: -len(rest) - 1]
            raise UsageError(
                f"{where}{notebook.stem}: {y!r}: an estimate has no part {rest!r}; did you mean "
                f"'{head}.{close[0]}'? (its parts: {', '.join(parts)})"
            )


def check_summary_table(summary: dict, where: str = "") -> None:
    """Refuse a ``[summary]`` value of the wrong type before any run: the names and labels are strings, the
    scales are among :data:`SCALES`.

    Parameters
    ----------
    summary : dict
        The spec's ``[summary]`` table (its keys checked already).
    where : str
        Prefix of the message (the spec file and the table).

    Raises
    ------
    UsageError
        One line naming the key, its value and what it may be.
    """
    for key in _TEXT_KEYS:
        if key in summary and not isinstance(summary[key], str):
            what = "a metric name" if key == "y" else "a parameter name" if key in ("x", "hue") else "a text"
            raise UsageError(f"{where}{key} = {summary[key]!r}; it must be {what} (a string)")
    for key in ("xscale", "yscale"):
        if key in summary and summary[key] not in SCALES:
            raise UsageError(f"{where}{key} = {summary[key]!r}; it must be one of {', '.join(repr(s) for s in SCALES)}")


def _axis_kind(value: Any) -> str | None:
    """``"number"``, ``"string"`` or ``"boolean"``: what an axis can place; ``None`` for anything else (a list, a
    table, a date)."""
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, (int, float)):
        return "number"
    return "string" if isinstance(value, str) else None


def check_plot_values(summary: dict, values: dict[str, list], where: str = "") -> None:
    """Refuse, before any run, a ``[summary] x`` whose values the plot cannot place on its axis.

    ``x`` must take numbers, strings or booleans, all of one kind (a sorted axis), and numbers in (0, 1) on a
    ``logit`` axis. ``hue`` may take any value: each of its lines is named by the value (a list by its JSON form).

    Parameters
    ----------
    summary : dict
        The spec's ``[summary]`` table (checked by :func:`check_summary_table`).
    values : dict
        ``{parameter: the values the sweep gives it}`` (``[fixed]`` one, ``[grid]``/``[zip]`` their lists).
    where : str
        Prefix of the message (the spec file and the table).

    Raises
    ------
    UsageError
        One line naming ``x``, the first value refused and what ``x`` may take.
    """
    x = summary.get("x")
    taken = values.get(x, [])
    kinds = [_axis_kind(v) for v in taken]
    allowed = "x must take numbers, strings or booleans, all of one kind"
    for value, kind in zip(taken, kinds):
        if kind is None:
            raise UsageError(
                f"{where}x = {x!r} takes {json.dumps(value, default=str)} ({type(value).__name__}), which the plot "
                f"cannot place on its x axis; {allowed} (a parameter of list values can be the hue: a line per value)"
            )
        if kind != kinds[0]:
            raise UsageError(f"{where}x = {x!r} takes {value!r} beside {taken[0]!r}; {allowed} (a sorted axis)")
        if summary.get("xscale") == "logit" and not (kind == "number" and 0 < value < 1):
            raise UsageError(f"{where}xscale = 'logit' needs x values in (0, 1); x = {x!r} takes {value!r}")


def check_metric(notebook: Path, y: str, where: str = "") -> None:
    """Refuse a summary metric ``y`` whose first part is none of the metrics the notebook writes.

    Raises
    ------
    UsageError
        One line naming ``y``, the closest metric names and the notebook's metrics.
    """
    names = notebook_metric_names(notebook)
    if names is None:
        return
    if any(_matches(n, y) for n in names):
        _check_part(names, y, where, notebook)
        return
    close = difflib.get_close_matches(y.split(".")[0], names, n=2, cutoff=0.6)
    hint = f"did you mean {' or '.join(repr(c) for c in close)}? " if close else ""
    raise UsageError(
        f"{where}{notebook.stem} writes no metric {y!r}; {hint}its metrics: {', '.join(names)} "
        "(a nested value by its dotted path, e.g. NAME.value)"
    )


def check_metric_in(results: Path, y: str, where: str = "") -> None:
    """Refuse ``y`` when an earlier run's ``results.json`` (same notebook, same sweep) holds no number at that
    dotted path, naming the paths it holds under the same metric (or all of them)."""
    try:
        columns = flatten_metrics(json.loads(results.read_text()).get("metrics", {}))
    except (OSError, ValueError, AttributeError):
        return
    if y in columns:
        return
    head = y.split(".")[0]
    same = [c for c in columns if c == head or c.startswith(head + ".")] or list(columns)
    close = difflib.get_close_matches(y, same, n=2, cutoff=0.6)
    hint = f"did you mean {' or '.join(repr(c) for c in close)}? " if close else ""
    shown = ", ".join(same[:20]) + (f" and {len(same) - 20} more" if len(same) > 20 else "")
    raise UsageError(f"{where}the runs' results hold no metric {y!r}; {hint}metrics there: {shown}")


def collect_summary(
    sweep_dir: Path,
    runs: list,
    summary: dict | None = None,
    errors: dict[str, str] | None = None,
    notes: list[str] | None = None,
) -> tuple[Path, Path | None]:
    """Write ``summary.csv`` (one row per run: id, status, error, parameters, metrics, verdicts)
    and, if ``summary`` names ``x`` and ``y``, ``summary.png``.

    ``status`` is ``ok``, ``failed`` (the run's directory holds its error) or ``absent`` (no directory: the
    run was not done, or its outputs could not be written; ``errors`` maps such a run's id to why). A plot
    Matplotlib cannot draw from the runs' values (a ``logit`` axis whose values reach 0 or 1) is left out, and why
    is appended to ``notes``: the runs and ``summary.csv`` stand."""
    rows = []
    errors = errors or {}
    for run in runs:
        run_dir = sweep_dir / "runs" / run.run_id
        rec = load_run(run_dir) or {"status": "absent", "error": errors.get(run.run_id, "not run")}
        row: dict[str, Any] = {
            "run_id": run.run_id,
            "status": rec.get("status"),
            "error": rec.get("error") or "",
            "runtime_s": rec.get("runtime_s"),
        }
        row.update(run.parameters)
        if rec.get("status") == "ok":
            data = load_results(run_dir, for_report=False)  # a damaged file: one line naming it (:mod:`.runfiles`)
            row.update(flatten_metrics(data.get("metrics", {})))
            row.update({f"verdict {c['id']}": c["verdict"] for c in data.get("claims", [])})
        rows.append(row)
    columns: list[str] = []
    for row in rows:
        columns += [k for k in row if k not in columns]
    csv_path = sweep_dir / "summary.csv"
    with csv_path.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=columns)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (json.dumps(v) if isinstance(v, (list, dict)) else v) for k, v in row.items()})
    plot = _summary_plot(sweep_dir, rows, summary, [] if notes is None else notes) if summary else None
    return csv_path, plot


def _plot_key(value: Any) -> str:
    """A hue value as a key of its line: its JSON form, so that a list or a table names a line too, and ``1``,
    ``1.0`` and ``true`` name three."""
    return json.dumps(value, sort_keys=True, default=str)


def _summary_plot(sweep_dir: Path, rows: list[dict], summary: dict, notes: list[str]) -> Path | None:
    """``summary.png``: ``y`` against ``x``, a line per ``hue`` value; ``None`` (and why, in ``notes``) where the
    runs' values give Matplotlib nothing it can draw."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x, y, hue = summary["x"], summary["y"], summary.get("hue")
    ok = [r for r in rows if r.get("status") == "ok" and r.get(y) is not None and x in r]
    if not ok:
        return None
    groups: dict[str, list[dict]] = {}
    for r in ok:
        groups.setdefault(_plot_key(r.get(hue)) if hue else "", []).append(r)
    fig, ax = plt.subplots(figsize=(6, 4))
    path = sweep_dir / "summary.png"
    try:
        with warnings.catch_warnings():  # Matplotlib's remarks on values a log or logit axis cannot show: not on stderr
            warnings.simplefilter("ignore", UserWarning)
            warnings.simplefilter("ignore", RuntimeWarning)
            try:
                _draw(ax, groups, summary, sweep_dir.name)
                fig.canvas.draw()  # what Matplotlib cannot draw fails here, before the file is opened
            except (ValueError, TypeError, OverflowError) as exc:
                scales = f"xscale {summary.get('xscale', 'linear')!r}, yscale {summary.get('yscale', 'linear')!r}"
                notes.append(f"Matplotlib cannot draw {y!r} against {x!r} ({scales}): {type(exc).__name__}: {exc}")
                path.unlink(missing_ok=True)  # an earlier sweep's plot (the sweep's own file) would not match the csv
                return None
            fig.savefig(path, dpi=110, bbox_inches="tight")
        return path
    finally:
        plt.close(fig)


def _draw(ax, groups: dict[str, list[dict]], summary: dict, title: str) -> None:
    """A line (and its confidence band, where every run has one) per group of rows, the mean ``y`` at each ``x``;
    the axes' scales, labels, title and legend from ``summary``."""
    import numpy as np

    x, y, hue = summary["x"], summary["y"], summary.get("hue")
    base = y[: -len(".value")] if y.endswith(".value") else None
    for items in groups.values():
        xs = sorted({r[x] for r in items})
        mean = [np.mean([r[y] for r in items if r[x] == v]) for v in xs]
        value = items[0].get(hue) if hue else None
        label = f"{hue} = {_plot_key(value) if isinstance(value, (list, dict)) else value}" if hue else None
        (line,) = ax.plot(xs, mean, marker="o", label=label)
        if base and all(r.get(f"{base}.ci_low") is not None and r.get(f"{base}.ci_high") is not None for r in items):
            lo = [np.mean([r[f"{base}.ci_low"] for r in items if r[x] == v]) for v in xs]
            hi = [np.mean([r[f"{base}.ci_high"] for r in items if r[x] == v]) for v in xs]
            ax.fill_between(xs, lo, hi, alpha=0.2, color=line.get_color())
    ax.set_xscale(summary.get("xscale", "linear"))
    ax.set_yscale(summary.get("yscale", "linear"))
    ax.set_xlabel(summary.get("xlabel", x))
    ax.set_ylabel(summary.get("ylabel", y))
    ax.set_title(summary.get("title", title))
    if hue:
        ax.legend()
    ax.grid(alpha=0.3)
