"""Checks made before any kernel starts: parameter names against the notebook's ``parameters``
cell, and parameter values through the notebook's own validation cell.

A notebook's first code cell (tagged ``parameters``) holds one assignment per parameter; the next
code cell imports the library and calls ``validate_parameters(globals(), ...)`` together with any
cross-parameter check, raising ``ValueError`` that names the parameters. That cell must be cheap
and do no simulation (docs/contributing.md, "Writing a notebook"), so it can run here, in a subprocess with a
throw-away ``output_dir``, before a run starts.
"""

from __future__ import annotations

import difflib
import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any, Iterable

from ..results import cell_literals

__all__ = [
    "UsageError",
    "CELL_TYPES",
    "check_notebook",
    "check_cells",
    "code_cells",
    "NotebookBug",
    "parameter_defaults",
    "check_names",
    "check_values",
    "check_values_many",
    "refuse_output_dir",
    "OUTPUT_DIR_REASON",
    "name_given",
    "refuse_unknown_keys",
]


class UsageError(ValueError):
    """A mistake in what the user asked for: shown as one line ``error: ...``, exit status 2."""


class NotebookBug(RuntimeError):
    """A notebook's validation cell failed other than with ``ValueError``: a bug in the notebook
    (shown as one line, exit status 1)."""


#: The cell types of an nbformat-4 notebook.
CELL_TYPES = ("code", "markdown", "raw")
NOTEBOOK_FORM = "a notebook is a JSON object with 'cells', 'metadata', 'nbformat' = 4 and 'nbformat_minor'"


def check_notebook(notebook: Path, data: Any) -> None:
    """Refuse what papermill cannot run as an nbformat-4 notebook, in one line naming the file and what is missing.

    Parameters
    ----------
    notebook : pathlib.Path
        The ``.ipynb`` file (named in the message).
    data : object
        Its JSON: an object with a list of ``cells`` (:func:`check_cells`), an object ``metadata`` that names the
        notebook's language (``kernelspec.language`` or ``language_info.name``), ``nbformat`` = 4 and an integer
        ``nbformat_minor`` >= 0.

    Raises
    ------
    UsageError
        The first thing missing or of the wrong kind.
    """
    where = f"{notebook}: not a notebook:"
    if not isinstance(data, dict):
        raise UsageError(f"{where} the file holds a JSON {type(data).__name__}; {NOTEBOOK_FORM}")
    for key, kind in (("cells", list), ("metadata", dict)):
        if not isinstance(data.get(key), kind):
            what = "no" if key not in data else f"a {type(data[key]).__name__} as its"
            raise UsageError(f"{where} {what} '{key}'; {NOTEBOOK_FORM}")
    version, minor = data.get("nbformat"), data.get("nbformat_minor")
    if type(version) is not int or version != 4:
        got = "no 'nbformat'" if "nbformat" not in data else f"'nbformat' = {version!r}"
        raise UsageError(f"{where} {got}; it must be 4 (Jupyter's notebook format: open and save it in JupyterLab)")
    if type(minor) is not int or minor < 0:
        got = "no 'nbformat_minor'" if "nbformat_minor" not in data else f"'nbformat_minor' = {minor!r}"
        raise UsageError(f"{where} {got}; it must be an integer >= 0 (5 for Jupyter's current format)")
    meta = data["metadata"]
    for key in ("kernelspec", "language_info"):
        if not isinstance(meta.get(key, {}), dict):
            raise UsageError(f"{where} 'metadata' has a '{key}' that is not a JSON object")
    if not any(
        isinstance(v, str) and v for v in (_language_of(meta, "kernelspec"), _language_of(meta, "language_info"))
    ):
        raise UsageError(
            f"{where} its 'metadata' names no language (a 'kernelspec' with a 'language', or a 'language_info' "
            "with a 'name', e.g. \"python\"); open and save it in JupyterLab to add them"
        )
    check_cells(notebook, data["cells"])


def _language_of(metadata: dict, key: str) -> Any:
    """The language ``metadata[key]`` names (``kernelspec.language``, ``language_info.name``), or ``None``."""
    return metadata.get(key, {}).get("language" if key == "kernelspec" else "name")


def check_cells(notebook: Path, cells: list) -> None:
    """Refuse cells that are not notebook cells, in one line naming the notebook and the cell.

    Parameters
    ----------
    notebook : pathlib.Path
        The ``.ipynb`` file (named in the message).
    cells : list
        Its ``cells``: each a JSON object with a ``cell_type`` (code, markdown or raw), a ``source`` (a string or a
        list of strings) and a ``metadata`` object; a code cell's ``outputs``, where present, a list of JSON
        objects, a cell's ``attachments`` a JSON object.

    Raises
    ------
    UsageError
        The first cell that is not one.
    """
    for index, cell in enumerate(cells, start=1):
        where = f"{notebook}: not a notebook: cell {index}"
        if not isinstance(cell, dict):
            raise UsageError(f"{where} is {type(cell).__name__}, not a JSON object with 'cell_type' and 'source'")
        if cell.get("cell_type") not in CELL_TYPES:
            got = "no 'cell_type'" if "cell_type" not in cell else f"'cell_type' = {cell['cell_type']!r}"
            raise UsageError(f"{where} has {got}; a cell is code, markdown or raw")
        source = cell.get("source")
        if not (isinstance(source, str) or isinstance(source, list) and all(isinstance(s, str) for s in source)):
            what = "no 'source'" if "source" not in cell else "a 'source' that is not a string or a list of strings"
            raise UsageError(f"{where} has {what}; a cell's 'source' is a string or a list of strings")
        if not isinstance(cell.get("metadata"), dict):
            what = "no 'metadata'" if "metadata" not in cell else "a 'metadata' that is not a JSON object"
            raise UsageError(f"{where} has {what}; a cell's 'metadata' is a JSON object ({{}} when empty)")
        outputs = cell.get("outputs", []) if cell["cell_type"] == "code" else []
        if not isinstance(outputs, list) or not all(isinstance(o, dict) for o in outputs):
            raise UsageError(f"{where} has 'outputs' that are not a list of JSON objects ([] when empty)")
        if not isinstance(cell.get("attachments", {}), dict):
            raise UsageError(f"{where} has 'attachments' that are not a JSON object")


def code_cells(notebook: Path) -> list[str]:
    """The sources of a notebook's code cells, read as plain JSON (nbformat's import alone takes seconds).

    Parameters
    ----------
    notebook : pathlib.Path
        The ``.ipynb`` file.

    Returns
    -------
    list of str
        One source per code cell, the ``parameters`` cell first.

    Raises
    ------
    UsageError
        When a cell is not a notebook cell, or the first code cell is not tagged ``parameters``.
    """
    data = json.loads(Path(notebook).read_text())
    if not isinstance(data, dict) or not isinstance(data.get("cells"), list):
        raise UsageError(f"{notebook}: not a notebook: a notebook is a JSON object with a list of 'cells'")
    check_cells(notebook, data["cells"])
    cells = [c for c in data["cells"] if c["cell_type"] == "code"]
    tags = cells[0].get("metadata", {}).get("tags", []) if cells else []
    if not isinstance(tags, list) or "parameters" not in tags:
        raise UsageError(f"{notebook.name}: the first code cell is not tagged 'parameters'")
    return ["".join(c["source"]) if isinstance(c["source"], list) else c["source"] for c in cells]


def parameter_defaults(notebook: Path) -> dict[str, Any]:
    """``{name: default}`` from the notebook's ``parameters`` cell (literal values only).

    Raises
    ------
    NotebookBug
        The ``parameters`` cell is not valid Python (named with the notebook and the line).
    """
    source = code_cells(notebook)[0]
    try:
        return cell_literals(source)
    except SyntaxError as exc:
        raise NotebookBug(
            f"the parameters cell of {notebook.stem} is not valid Python: {exc.msg} (line {exc.lineno} of the cell; "
            "a bug in the notebook)"
        ) from exc
    except (ValueError, TypeError, RecursionError, MemoryError) as exc:  # null bytes, {[1]: 2}, deep nesting
        raise NotebookBug(
            f"the parameters cell of {notebook.stem} cannot be read: {type(exc).__name__}: {exc} "
            "(a bug in the notebook)"
        ) from exc


def check_names(notebook: Path, names: Iterable[str], where: str = "") -> None:
    """Raise :class:`UsageError` for a name the notebook's ``parameters`` cell does not define,
    suggesting the closest names."""
    names = list(names)
    refuse_output_dir(names, where)
    known = parameter_defaults(notebook)
    for name in names:
        if name not in known:
            close = difflib.get_close_matches(name, list(known), n=3, cutoff=0.6)
            hint = (
                f"; did you mean {' or '.join(repr(c) for c in close)}?"
                if close
                else f"; its parameters are {', '.join(sorted(known))}"
                if known
                else "; its parameters cell assigns none"
            )
            raise UsageError(f"{where}{notebook.stem} has no parameter {name!r}{hint}")


def refuse_unknown_keys(table: dict, allowed: Iterable[str], where: str = "") -> None:
    """Raise :class:`UsageError` for the first key of ``table`` not in ``allowed``, suggesting the closest."""
    allowed = sorted(allowed)
    for key in table:
        if key not in allowed:
            close = difflib.get_close_matches(key, allowed, n=2, cutoff=0.6)
            hint = f"did you mean {' or '.join(repr(c) for c in close)}?" if close else f"allowed: {', '.join(allowed)}"
            raise UsageError(f"{where}unknown key {key!r}; {hint}")


_PREFLIGHT = r"""
import json, sys
answers = []
for index, (cells, override_sets) in enumerate(json.loads(sys.stdin.read())):
    print(f"notebook {index}", file=sys.stderr, flush=True)  # names the notebook of a traceback below it
    answers.append([])
    for overrides in override_sets:
        namespace = {"__name__": "__preflight__"}
        try:
            exec(compile(cells[0], "<parameters cell>", "exec"), namespace)
            namespace.update(overrides)
            try:
                exec(compile(cells[1], "<validation cell>", "exec"), namespace)
            except ValueError as exc:
                answers[-1].append(str(exc))
                continue
        except SystemExit as exc:
            print(f"SystemExit: it calls sys.exit({exc.code!r})", file=sys.stderr)
            sys.exit(3)
        answers[-1].append(None)
with open(sys.argv[1], "w") as fh:  # a file, not stdout: what the cells print does not mix with the answers
    json.dump(answers, fh)
"""

OUTPUT_DIR_REASON = (
    "'output_dir' is where a run writes and tvtrack sets it to the run's own directory; "
    "choose that directory with -o (sweeps: -o SWEEP_DIR) instead"
)


def refuse_output_dir(names: Iterable[str], where: str = "") -> None:
    """Raise :class:`UsageError` if ``output_dir`` is among the parameters set (it would be ignored)."""
    if "output_dir" in set(names):
        raise UsageError(f"{where}{OUTPUT_DIR_REASON}")


def name_given(message: str, given: dict[str, Any]) -> str:
    """The validation message, led by what the user set when it names none of it (the notebook's check may
    name the other parameter of an inconsistent pair: 001 ``window_n = 200`` against ``fa_duration_s``)."""
    if not given or any(f"'{name}'" in message for name in given):  # the notebooks quote the names they check
        return message
    shown = ", ".join(f"{name} = {value!r}" for name, value in given.items())
    return f"{shown} does not fit the other parameters: {message}"


def check_values_many(notebook: Path, override_sets: list[dict[str, Any]], timeout_s: float = 120) -> list[str | None]:
    """Run the notebook's parameters and validation cells once per override set, all in one subprocess.

    Returns
    -------
    list of str or None
        Per set, the validation cell's ``ValueError`` message, or ``None`` when the values pass.

    Raises
    ------
    NotebookBug
        The validation cell failed otherwise: a bug in the notebook, not in the user's input.
    """
    return check_values_each([(notebook, override_sets)], timeout_s)[0]


def check_values_each(sets: list[tuple[Path, list[dict[str, Any]]]], timeout_s: float = 120) -> list[list[str | None]]:
    """:func:`check_values_many` for several notebooks, in one subprocess (one start-up of Python for all).

    Parameters
    ----------
    sets : list of (Path, list of dict)
        Per notebook, its override sets.
    timeout_s : float
        Limit for the whole subprocess, in seconds.

    Returns
    -------
    list of list of str or None
        Per notebook and override set, the validation cell's ``ValueError`` message, or ``None``.

    Raises
    ------
    NotebookBug
        A validation cell failed otherwise (named by its notebook): a bug in the notebook, not in the user's input.
    """
    cells = [code_cells(nb) for nb, _ in sets]
    for (nb, _), own in zip(sets, cells):
        if len(own) < 2:
            raise UsageError(f"{nb.name}: no validation cell after the parameters cell")
    with tempfile.TemporaryDirectory(prefix="tvtrack-preflight-") as work:
        scratch, answers = os.path.join(work, "output"), Path(work) / "answers.json"
        os.mkdir(scratch)
        payload = [(own[:2], [{**o, "output_dir": scratch} for o in sets_]) for own, (_, sets_) in zip(cells, sets)]
        try:
            proc = subprocess.run(
                [sys.executable, "-c", _PREFLIGHT, str(answers)],
                input=json.dumps(payload, default=str),
                capture_output=True,
                text=True,
                cwd=scratch,
                env={**os.environ, "MPLBACKEND": "Agg"},
                timeout=timeout_s,
            )
        except subprocess.TimeoutExpired:
            names = ", ".join(nb.stem for nb, _ in sets)
            raise NotebookBug(
                f"the validation cell of {names} did not finish within {timeout_s:g} s (it must be cheap and do no "
                "simulation; a bug in the notebook)"
            ) from None
        answered = answers.read_text() if proc.returncode == 0 and answers.is_file() else None
    if answered is None:
        lines = proc.stderr.strip().splitlines() or ["(no message)"]
        started = [int(line.split()[1]) for line in lines if re.fullmatch(r"notebook \d+", line)]
        stem = sets[started[-1] if started else 0][0].stem
        why = lines[-1] if proc.returncode != 0 else "Python ended before it answered (os._exit?)"
        raise NotebookBug(
            f"the validation cell of {stem} failed: {why} (a bug in the notebook; --debug shows the traceback)"
        )
    return json.loads(answered)


def check_values(
    notebook: Path, overrides: dict[str, Any], timeout_s: float = 120, given: dict[str, Any] | None = None
) -> None:
    """Run the notebook's parameters and validation cells with ``overrides`` in a subprocess.

    ``given`` (default: ``overrides``) are the values the user typed; a message that names none of them is
    led by them, so the user sees which of their values the check is about.

    Raises
    ------
    UsageError
        The validation cell raised ``ValueError`` (a bad value or an inconsistent combination);
        the message is the notebook's own.
    NotebookBug
        The validation cell failed otherwise: a bug in the notebook, not in the user's input.
    """
    (error,) = check_values_many(notebook, [overrides], timeout_s)
    if error:
        raise UsageError(f"{notebook.stem}: {name_given(error, overrides if given is None else given)}")
