"""``python -m tvtrack new NNN name``: a new paper's package, notebook, tests and smoke profile from a template.

The template (``templates/paper``) is a complete, small paper: one placeholder claim decided by a rule over a
one-entry register, explored with the core explorer, a figure, a recording and tests. As generated it passes
``make lint``, ``make test`` and the paper contract (:mod:`tvtrack.contract`); ``docs/adding_a_paper.md`` walks
through what to change. Nothing here imports a paper.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

from .outputs import replace_text
from .paths import REPO_ROOT
from .preflight import UsageError

__all__ = ["TEMPLATE_DIR", "new_paper", "notebook_from_cells"]

TEMPLATE_DIR = Path(__file__).resolve().parent / "templates" / "paper"
_NUMBER = re.compile(r"^\d{3}$")
_NAME = re.compile(r"^[a-z][a-z0-9_]*[a-z0-9]$")
_CELL = re.compile(r"^# %%(?: (\[markdown\]|parameters))?\s*$")


def notebook_from_cells(text: str) -> dict:
    """An nbformat-4 notebook (a dict, no outputs) from the template's cell format: ``# %%`` opens a code cell,
    ``# %% parameters`` the parameters cell, ``# %% [markdown]`` a Markdown cell whose first line, when it has no
    ``#``, is the title (``# `` is added)."""
    cells: list[dict] = []
    for line in text.splitlines():
        m = _CELL.match(line)
        if m:
            kind = "markdown" if m.group(1) == "[markdown]" else "code"
            cells.append({"cell_type": kind, "tags": ["parameters"] if m.group(1) == "parameters" else [], "lines": []})
        elif cells:
            cells[-1]["lines"].append(line)
    out = []
    for i, c in enumerate(cells):
        source = "\n".join(c["lines"]).strip("\n")
        cell = {"cell_type": c["cell_type"], "id": f"cell-{i:02d}", "metadata": {}, "source": source}
        if c["tags"]:
            cell["metadata"] = {"tags": c["tags"]}
        if c["cell_type"] == "code":
            cell |= {"execution_count": None, "outputs": []}
        out.append(cell)
    if out and out[0]["cell_type"] == "markdown" and not out[0]["source"].startswith("#"):
        out[0]["source"] = "# " + out[0]["source"]
    return {
        "cells": out,
        "metadata": {
            "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
            "language_info": {"name": "python"},
        },
        "nbformat": 4,
        "nbformat_minor": 5,
    }


def _fill(text: str, values: dict[str, str]) -> str:
    for key, value in values.items():
        text = text.replace("{{" + key + "}}", value)
    left = re.findall(r"\{\{\w+\}\}", text)
    if left:
        raise ValueError(f"template placeholders without a value: {sorted(set(left))}")
    return text


_REFERENCE = """  - type: article
    title: "{title}"
    authors:
      - name: "TODO: the paper's authors"
    year: 2026
"""


def new_paper(number: str, name: str, root: Path = REPO_ROOT, title: str | None = None) -> list[Path]:
    """Write paper ``number`` (three digits) called ``name`` (lower case, digits, ``_``) under ``root``.

    Writes ``lib/tvtrack/papers/p<NNN>_<name>/`` (package), ``notebooks/<NNN>_<name>.ipynb``,
    ``tests/papers/test_<NNN>_<name>.py`` and ``papermill_runs/profiles/<NNN>_<name>.smoke.toml``, and adds a
    placeholder reference to ``root/CITATION.cff`` when there is one. Returns the paths written.

    Raises
    ------
    UsageError
        A malformed number or name, or a paper of that number or a file to write that exists already.
    """
    if not _NUMBER.match(number):
        raise UsageError(f"paper number {number!r} must be three digits, e.g. 005")
    if not _NAME.match(name):
        raise UsageError(f"paper name {name!r} must be lower case letters, digits and '_', e.g. spot_tracker")
    if title is not None and ('"' in title or "\n" in title or not title.strip()):
        raise UsageError(f"paper title {title!r} must be one line without double quotes")
    root = Path(root)
    stem, package = f"{number}_{name}", f"p{number}_{name}"
    papers = root / "lib" / "tvtrack" / "papers"
    taken = sorted(p.name for p in papers.glob(f"p{number}_*")) if papers.is_dir() else []
    if taken:
        raise UsageError(f"paper {number} exists already: {', '.join(taken)}")
    values = {"NNN": number, "name": name, "stem": stem, "package": package, "title": title or name.replace("_", " ")}
    targets = {
        **{
            papers / package / t.name.removesuffix(".tmpl"): t
            for t in sorted((TEMPLATE_DIR / "package").glob("*.py.tmpl"))
        },
        root / "tests" / "papers" / f"test_{stem}.py": TEMPLATE_DIR / "test.py.tmpl",
        root / "papermill_runs" / "profiles" / f"{stem}.smoke.toml": TEMPLATE_DIR / "smoke.toml.tmpl",
    }
    notebook = root / "notebooks" / f"{stem}.ipynb"
    existing = [str(p) for p in [*targets, notebook] if p.exists()]
    if existing:
        raise UsageError(f"would overwrite {', '.join(existing)}")
    written = []
    for path, template in targets.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(_fill(template.read_text(), values))
        written.append(path)
    nb = notebook_from_cells(_fill((TEMPLATE_DIR / "notebook.cells.tmpl").read_text(), values))
    notebook.parent.mkdir(parents=True, exist_ok=True)
    notebook.write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n")
    written.append(notebook)
    cff = root / "CITATION.cff"
    if cff.is_file():
        replace_text(cff, cff.read_text().rstrip("\n") + "\n" + _REFERENCE.format(title=values["title"]))
        written.append(cff)
    return written
