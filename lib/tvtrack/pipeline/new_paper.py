"""``python -m tvtrack new NNN name``: a new paper's package, notebook, tests and smoke profile from a template.

The template (``templates/paper``) is a complete, small paper: one placeholder claim decided by a rule over a
one-entry register, explored with the core explorer, a figure, a recording and tests. As generated it passes
``make lint``, ``make test`` and the paper contract (:mod:`tvtrack.contract`); ``docs/adding_a_paper.md`` walks
through what to change. Nothing here imports a paper.
"""

from __future__ import annotations

import contextlib
import json
import re
from pathlib import Path

from .outputs import replace_text
from .paths import REPO_ROOT
from .preflight import UsageError

__all__ = ["TEMPLATE_DIR", "new_paper", "notebook_from_cells"]

TEMPLATE_DIR = Path(__file__).resolve().parent / "templates" / "paper"
_NUMBER = re.compile(r"[0-9]{3}")  # ASCII digits only (``\d`` takes any script's), matched whole (``fullmatch``)
_NAME = re.compile(r"[a-z][a-z0-9_]*[a-z0-9]")
NAME_MAX = 60
"""Longest paper name: its files' names (``<NNN>_<name>.smoke.toml``) stay far below the file systems' 255 bytes."""
_PLACEHOLDER = re.compile(r"\{\{(\w+)\}\}")
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
    """``text`` with each ``{{key}}`` replaced by its value, in one pass: a value is never read as a placeholder.

    Raises
    ------
    ValueError
        The template holds a placeholder without a value (a bug in the template).
    """
    left = sorted({m.group(0) for m in _PLACEHOLDER.finditer(text) if m.group(1) not in values})
    if left:
        raise ValueError(f"template placeholders without a value: {left}")
    return _PLACEHOLDER.sub(lambda m: values[m.group(1)], text)


_REFERENCE = """  - type: article
    title: "{title}"
    authors:
      - name: "TODO: the paper's authors"
    year: 2026
"""


def _check_arguments(number: str, name: str, title: str | None) -> None:
    """Refuse a malformed number, name or title in one line, before anything is written.

    Raises
    ------
    UsageError
        The number is not three ASCII digits, the name not lower case ASCII letters, digits and ``_`` (at most
        :data:`NAME_MAX` characters), or the title not one printable line without ``"``, ``\\``, ``{{`` or
        ``}}`` (it is written into Python docstrings and a double-quoted YAML string, and ``{{`` marks a
        template's placeholder).
    """
    if not _NUMBER.fullmatch(number):
        raise UsageError(f"paper number {number!r} must be three digits 0-9, e.g. 005")
    if not _NAME.fullmatch(name) or len(name) > NAME_MAX:
        raise UsageError(
            f"paper name {name!r} must be lower case letters a-z, digits and '_' (a letter first, at most "
            f"{NAME_MAX} characters), e.g. spot_tracker"
        )
    if title is not None and (
        not title.strip() or not title.isprintable() or any(s in title for s in ('"', "\\", "{{", "}}"))
    ):
        raise UsageError(
            f'paper title {title!r} must be one printable line without double quotes ("), backslashes or '
            "double braces ({{ }})"
        )


def _render(root: Path, number: str, name: str, title: str | None) -> dict[Path, str]:
    """Every file of the new paper and its text, ``CITATION.cff`` (when there is one) last."""
    stem, package = f"{number}_{name}", f"p{number}_{name}"
    papers = root / "lib" / "tvtrack" / "papers"
    values = {"NNN": number, "name": name, "stem": stem, "package": package, "title": title or name.replace("_", " ")}
    texts = {
        papers / package / t.name.removesuffix(".tmpl"): _fill(t.read_text(), values)
        for t in sorted((TEMPLATE_DIR / "package").glob("*.py.tmpl"))
    }
    texts[root / "tests" / "papers" / f"test_{stem}.py"] = _fill((TEMPLATE_DIR / "test.py.tmpl").read_text(), values)
    texts[root / "papermill_runs" / "profiles" / f"{stem}.smoke.toml"] = _fill(
        (TEMPLATE_DIR / "smoke.toml.tmpl").read_text(), values
    )
    nb = notebook_from_cells(_fill((TEMPLATE_DIR / "notebook.cells.tmpl").read_text(), values))
    texts[root / "notebooks" / f"{stem}.ipynb"] = json.dumps(nb, indent=1, ensure_ascii=False) + "\n"
    cff = root / "CITATION.cff"
    if cff.is_file():
        texts[cff] = cff.read_text().rstrip("\n") + "\n" + _REFERENCE.format(title=values["title"])
    return texts


def _write_all(texts: dict[Path, str], cff: Path) -> list[Path]:
    """Write ``texts`` (new files, then ``cff`` replaced whole); a write that fails removes the files and folders
    written before it, so that the same command can be run again."""
    written: list[Path] = []
    made: list[Path] = []
    try:
        for path, text in texts.items():
            if path == cff:
                replace_text(cff, text)
            else:
                made += [d for d in reversed(path.parents) if not d.exists()]
                path.parent.mkdir(parents=True, exist_ok=True)
                with open(path, "x", encoding="utf-8") as fh:  # "x": never over a file that appeared meanwhile
                    written.append(path)
                    fh.write(text)
    except BaseException:
        for path in written:
            path.unlink(missing_ok=True)
        for folder in reversed(made):
            with contextlib.suppress(OSError):
                folder.rmdir()  # only if empty: never a file it did not write
        raise
    return list(texts)


def new_paper(number: str, name: str, root: Path = REPO_ROOT, title: str | None = None) -> list[Path]:
    """Write paper ``number`` (three digits) called ``name`` (lower case, digits, ``_``) under ``root``.

    Writes ``lib/tvtrack/papers/p<NNN>_<name>/`` (package), ``notebooks/<NNN>_<name>.ipynb``,
    ``tests/papers/test_<NNN>_<name>.py`` and ``papermill_runs/profiles/<NNN>_<name>.smoke.toml``, and adds a
    placeholder reference to ``root/CITATION.cff`` when there is one. Returns the paths written.

    Raises
    ------
    UsageError
        A malformed number, name or title, or a paper of that number or a file to write that exists already;
        nothing is written then.
    """
    _check_arguments(number, name, title)
    root = Path(root)
    papers = root / "lib" / "tvtrack" / "papers"
    taken = sorted(p.name for p in papers.glob(f"p{number}_*")) if papers.is_dir() else []
    if taken:
        raise UsageError(f"paper {number} exists already: {', '.join(taken)}")
    cff = root / "CITATION.cff"
    texts = _render(root, number, name, title)
    existing = [str(p) for p in texts if p != cff and p.exists()]
    if existing:
        raise UsageError(f"would overwrite {', '.join(existing)}")
    return _write_all(texts, cff)
