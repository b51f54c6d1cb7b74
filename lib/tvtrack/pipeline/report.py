"""``REPRODUCTION.md`` from the runs of ``make reproduce`` (:mod:`tvtrack.pipeline.reproduce`).

Inputs: ``papermill_runs/reproduce/<notebook>/`` (a run directory, see :mod:`tvtrack.pipeline.runner`)
and ``REPRODUCTION.md`` at the repository root, rebuilt from those directories by
:func:`write_report` (``python -m tvtrack report``).
"""

from __future__ import annotations

import json
import os
import time
from collections import Counter
from pathlib import Path
from typing import Any

from .paths import REPO_ROOT, RUNS_DIR
from ..results import VERDICTS
from .runner import list_notebooks, read_run

__all__ = ["REPRODUCE_DIR", "REPORT_PATH", "write_report", "format_measured"]

REPRODUCE_DIR = RUNS_DIR / "reproduce"
REPORT_PATH = REPO_ROOT / "REPRODUCTION.md"


def format_measured(value: Any) -> str:
    """Short text for a claim's ``measured`` field (Estimates as ``v [lo, hi]``)."""
    if isinstance(value, dict) and "value" in value and "ci_low" in value:
        v, lo, hi = value["value"], value.get("ci_low"), value.get("ci_high")
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
    return str(text).replace("|", "\\|").replace("\n", " ")


def write_report(reproduce_dir: Path = REPRODUCE_DIR, path: Path = REPORT_PATH,
                 notebooks: list[str] | None = None) -> Path:
    """Rebuild ``REPRODUCTION.md`` from the run directories under ``reproduce_dir``
    (one section per notebook of ``notebooks``, default: all in ``notebooks/``)."""
    if notebooks is None:
        notebooks = [nb.stem for nb in list_notebooks()]
    sections, counts = [], Counter()
    for name in notebooks:
        run_dir = reproduce_dir / name
        rel = os.path.relpath(run_dir, path.parent)
        record = read_run(run_dir)
        if record is None:
            sections.append(f"## {name}\n\nNot run yet: `make reproduce` (or `python -m tvtrack reproduce --only {name}`).\n")
            continue
        if record.get("status") != "ok":
            sections.append(f"## {name}\n\n**Run failed** after {record.get('runtime_s', 0):.0f} s: "
                            f"`{_cell(record.get('error'))}` (see [{rel}/error.txt]({rel}/error.txt)).\n")
            continue
        data = json.loads((run_dir / "results.json").read_text())
        counts.update(c["verdict"] for c in data["claims"])
        lines = [f"## {name}", "", f"*{data['citation']}*", "",
                 f"Profile `{record.get('profile')}`, seed {data['seed']}, runtime {record['runtime_s']:.0f} s "
                 f"(notebook {data['runtime_s']:.0f} s), commit `{data.get('git_commit')}`. "
                 f"[Executed notebook]({rel}/notebook.ipynb) · [results.json]({rel}/results.json)"]
        if data.get("recording"):
            lines[-1] += f" · [recording]({rel}/{data['recording']}) (open with `rerun {rel}/{data['recording']}`)"
        tally = Counter(c["verdict"] for c in data["claims"])
        lines += ["", " · ".join(f"{tally.get(v, 0)} {v}" for v in VERDICTS), "",
                  "| claim | verdict | statement | paper | acceptance | measured | note |",
                  "| --- | --- | --- | --- | --- | --- | --- |"]
        for c in data["claims"]:
            lines.append("| " + " | ".join(_cell(x) for x in (
                c["id"], f"**{c['verdict']}**", c["statement"], c["paper_value"], c["acceptance"],
                format_measured(c["measured"]), c.get("note", ""))) + " |")
        if data.get("figures"):
            lines += ["", "Figures:", ""]
            lines += [f"- [{_cell(f['caption'])}]({rel}/{f['file']})" for f in data["figures"]]
        sections.append("\n".join(lines) + "\n")
    total = sum(counts.values())
    head = ["# Reproduction report", ""]
    if not notebooks:
        head += ["No notebooks in `notebooks/` yet: nothing to reproduce.", ""]
    else:
        head += [f"**Claims: {counts['reproduced']} reproduced · {counts['partly']} partly · "
                 f"{counts['not reproduced']} not reproduced · {counts['not checkable']} not checkable** "
                 f"({total} claims, {len(notebooks)} notebooks)", "",
                 f"Written {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} from `papermill_runs/reproduce/` "
                 "by `make reproduce` (rebuild with `python -m tvtrack report`). Verdicts come from the "
                 "notebooks' own Monte Carlo runs; see each notebook for the reasoning.", ""]
    path.write_text("\n".join(head + sections))
    return path
