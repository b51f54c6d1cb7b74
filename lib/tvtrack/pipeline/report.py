"""``REPRODUCTION.md`` from the runs of ``make reproduce`` (:mod:`tvtrack.pipeline.reproduce`).

Inputs: ``papermill_runs/reproduce/<notebook>/`` (a run directory, see :mod:`tvtrack.pipeline.runner`)
and ``REPRODUCTION.md`` at the repository root, rebuilt from those directories by
:func:`write_report` (``python -m tvtrack report``), which also regenerates the README's results
paragraph between :data:`README_BEGIN` and :data:`README_END` once every notebook has a paper-profile run.
"""

from __future__ import annotations

import json
import os
import re
import time
from collections import Counter
from pathlib import Path
from typing import Any

from .paths import REPO_ROOT, RUNS_DIR
from ..results import VERDICTS
from ..verdicts import LABELS

#: Labels in reading order, strongest first.
DISPLAY_LABELS = tuple(reversed(LABELS))
from .runner import list_notebooks, read_run

__all__ = ["REPRODUCE_DIR", "REPORT_PATH", "README_PATH", "README_BEGIN", "README_END", "write_report",
           "format_measured", "robustness_label", "robustness_where", "verdict_summary", "results_paragraph",
           "update_readme", "collect_runs"]

REPRODUCE_DIR = RUNS_DIR / "reproduce"
REPORT_PATH = REPO_ROOT / "REPRODUCTION.md"
README_PATH = REPO_ROOT / "README.md"
README_BEGIN = "<!-- begin generated results -->"
README_END = "<!-- end generated results -->"
NO_LABEL = "—"
"""Shown for a claim without a robustness record (not checkable, or a run from before the verdict standard)."""


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


def robustness_label(claim: dict) -> str:
    """The claim's robustness label, or :data:`NO_LABEL` when it has no record (not checkable,
    or a ``results.json`` written before the verdict standard)."""
    record = claim.get("robustness")
    return record["label"] if record else NO_LABEL


def robustness_where(claim: dict) -> str:
    """Where the claim's verdict differs from the default reading ("" when robust or unrecorded)."""
    record = claim.get("robustness")
    return "; ".join(record.get("where", [])) if record else ""


def verdict_summary(claims: list[dict]) -> str:
    """``"3 reproduced (2 robust, 1 depends) · 1 partly (1 unstable) · ..."``: each verdict's
    count with its robustness labels (a claim without a record counts as "no record")."""
    parts = []
    for verdict in VERDICTS:
        these = [c for c in claims if c["verdict"] == verdict]
        if verdict == "undecided" and not these:
            continue
        labels = Counter(robustness_label(c) for c in these)
        detail = [f"{labels[label]} {label}" for label in DISPLAY_LABELS if labels[label]]
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


def write_report(reproduce_dir: Path = REPRODUCE_DIR, path: Path = REPORT_PATH,
                 notebooks: list[str] | None = None, readme: Path | None = None) -> Path:
    """Rebuild ``REPRODUCTION.md`` from the run directories under ``reproduce_dir``
    (one section per notebook of ``notebooks``, default: all in ``notebooks/``).

    With ``readme``, also regenerate that file's results paragraph (:func:`update_readme`) when
    every notebook has a successful paper-profile run; otherwise the README is left as it is and
    the reason is printed.
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
            sections.append(f"## {name}\n\nNot run yet: `make reproduce` (or `python -m tvtrack reproduce --only {name}`).\n")
            continue
        if data is None:
            sections.append(f"## {name}\n\n**Run failed** after {record.get('runtime_s', 0):.0f} s: "
                            f"`{_cell(record.get('error'))}` (see [{rel}/error.txt]({rel}/error.txt)).\n")
            continue
        claims += data["claims"]
        lines = [f"## {name}", "", f"*{data['citation']}*", "",
                 f"Profile `{record.get('profile')}`, seed {data['seed']}, runtime {record['runtime_s']:.0f} s "
                 f"(notebook {data['runtime_s']:.0f} s), commit `{data.get('git_commit')}`. "
                 f"[Executed notebook]({rel}/notebook.ipynb) · [results.json]({rel}/results.json)"]
        if data.get("recording"):
            lines[-1] += (f" · [recording]({rel}/{data['recording']}) (in the browser: "
                          f"`python -m tvtrack view {rel}`; desktop: `rerun {rel}/{data['recording']}`)")
        lines += ["", verdict_summary(data["claims"]), "",
                  "| claim | verdict | robustness | where the verdict differs | statement | paper | acceptance "
                  "| measured | note |",
                  "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        for c in data["claims"]:
            lines.append("| " + " | ".join(_cell(x) for x in (
                c["id"], f"**{c['verdict']}**", robustness_label(c), robustness_where(c), c["statement"],
                c["paper_value"], c["acceptance"], format_measured(c["measured"]), c.get("note", ""))) + " |")
        if data.get("figures"):
            lines += ["", "Figures:", ""]
            lines += [f"- [{_cell(f['caption'])}]({rel}/{f['file']})" for f in data["figures"]]
        sections.append("\n".join(lines) + "\n")
    head = ["# Reproduction report", ""]
    if not notebooks:
        head += ["No notebooks in `notebooks/` yet: nothing to reproduce.", ""]
    else:
        counts = Counter(c["verdict"] for c in claims)
        labels = Counter(robustness_label(c) for c in claims if c["verdict"] != "not checkable")
        head += [f"**Claims: {' · '.join(f'{counts[v]} {v}' for v in VERDICTS if counts[v] or v != 'undecided')}** "
                 f"({len(claims)} claims, {len(notebooks)} notebooks); of the checkable verdicts "
                 f"**{' · '.join(f'{labels[lb]} {lb}' for lb in DISPLAY_LABELS)}**"
                 + (f" · {labels[NO_LABEL]} without a robustness record" if labels[NO_LABEL] else ""), "",
                 f"By verdict: {verdict_summary(claims)}.", "",
                 f"Written {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} from `papermill_runs/reproduce/` "
                 "by `make reproduce` (rebuild with `python -m tvtrack report`). Verdicts come from the "
                 "notebooks' own Monte Carlo runs at the default reading of what each paper left unstated; "
                 "*robust*: the same verdict, part by part, under every register value tried (one at a time and "
                 "joint samples) and every independent replicate; *unexplored*: no regime, operating point or "
                 "model of the simulated world was varied; *depends*: the verdict changes under another value "
                 "(the column says where); *unstable*: independent replicates disagree at the default. See each "
                 "notebook for the reasoning.", ""]
    path.write_text("\n".join(head + sections))
    if readme is not None:
        incomplete = [name for name, (record, data) in runs.items()
                      if data is None or record.get("profile") != "paper"]
        if incomplete:
            print(f"{readme.name}: results paragraph left as it is (no successful paper-profile run of "
                  f"{', '.join(incomplete)}; `make reproduce` runs them)")
        else:
            update_readme(readme, results_paragraph(runs))
            print(f"{readme.name}: results paragraph regenerated")
    return path


def _short(text: str, limit: int = 160) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= limit else text[:limit - 1].rstrip() + "…"


def _dependence(claim: dict) -> str:
    """How far a headline verdict holds: robust, where it changes, or that it was not tested."""
    record = claim.get("robustness")
    if not record:
        return "no robustness record"
    if record["label"] == "robust":
        n_cond, n_seed = len(record.get("conditions", [])), len(record.get("replicates", record.get("seeds", [])))
        tested = []
        if n_cond:
            tested.append(f"{n_cond} other reading{'s' if n_cond > 1 else ''}")
        if n_seed:
            tested.append(f"{n_seed} seeds")
        return "robust" + (f" ({' and '.join(tested)})" if tested else "")
    return f"{record['label']}: " + "; ".join(record["where"])


def results_paragraph(runs: dict[str, tuple[dict | None, dict | None]]) -> str:
    """The README's results paragraph (Markdown) from :func:`collect_runs`: the counts by verdict and
    robustness, then every claim that does not reproduce, and every other claim whose verdict
    depends on a reading or a seed, each with its dependence."""
    done = {name: (record, data) for name, (record, data) in runs.items() if data is not None}
    missing = sorted(set(runs) - set(done))
    claims = [(name, c) for name, (_, data) in done.items() for c in data["claims"]]
    if not claims:
        return ("No results yet: `make reproduce` runs every notebook at paper scale and `python -m tvtrack report` "
                "writes this paragraph from them.")
    dates = sorted(record.get("finished_utc", "")[:10] for record, _ in done.values())
    profiles = sorted({record.get("profile") for record, _ in done.values()})
    flat = [c for _, c in claims]
    counts = Counter(c["verdict"] for c in flat)
    labels = Counter(robustness_label(c) for c in flat if c["verdict"] != "not checkable")
    lines = [f"At a glance ({', '.join(profiles)} profile, runs of {dates[0]}"
             + (f" to {dates[-1]}" if dates[-1] != dates[0] else "")
             + "; generated by `python -m tvtrack report`, the full table is in `REPRODUCTION.md`): "
             f"{len(flat)} claims, **{counts['reproduced']} reproduced · {counts['partly']} partly · "
             f"{counts['not reproduced']} not reproduced · {counts['not checkable']} not checkable**. "
             f"Of the checkable verdicts {labels['robust']} are robust (the same under every defensible reading of "
             f"what the paper left unstated and every seed), {labels['depends']} depend on a reading and "
             f"{labels['unstable']} change with the seed"
             + (f"; {labels[NO_LABEL]} have no robustness record" if labels[NO_LABEL] else "") + "."]
    if missing:
        lines[0] += f" Not included (no successful run): {', '.join(missing)}."
    failing = [(n, c) for n, c in claims if c["verdict"] == "not reproduced"]
    if failing:
        lines += ["", "The claims that do not reproduce:", ""]
        lines += [f"- **{n[:3]} {c['id']}**: {_short(c['statement'])} Measured {_short(format_measured(c['measured']), 80)}"
                  f" ({_short(c['acceptance'], 100)}); {_dependence(c)}." for n, c in failing]
    shaky = [(n, c) for n, c in claims if c["verdict"] != "not reproduced"
             and robustness_label(c) in ("depends", "unstable")]
    if shaky:
        lines += ["", "Verdicts that change under another reading or seed:", ""]
        lines += [f"- **{n[:3]} {c['id']}** {c['verdict']}: {_short(c['statement'], 100)} {_dependence(c)}."
                  for n, c in shaky]
    return "\n".join(lines)


def update_readme(readme: Path, paragraph: str) -> None:
    """Replace the text between :data:`README_BEGIN` and :data:`README_END` in ``readme``."""
    text = Path(readme).read_text()
    pattern = re.compile(re.escape(README_BEGIN) + r".*?" + re.escape(README_END), re.S)
    if not pattern.search(text):
        raise ValueError(f"{readme}: no '{README_BEGIN}' ... '{README_END}' markers to put the results between")
    Path(readme).write_text(pattern.sub(lambda _: f"{README_BEGIN}\n{paragraph}\n{README_END}", text, count=1))
