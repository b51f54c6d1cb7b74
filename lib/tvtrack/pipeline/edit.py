"""``python -m tvtrack edit NOTEBOOK`` (``make edit NB=...``): a working copy to edit and run in JupyterLab.

The copy is ``papermill_runs/edit/<notebook>.ipynb`` (ignored by git, so autosave never writes outputs into a
tracked notebook), without outputs. Its ``parameters`` cell itself holds the profile's values (default:
``smoke``, small study sizes) and an absolute ``output_dir`` (``papermill_runs/edit/<notebook>-out/``, inside
the clone whatever the working directory): one cell, no override below it, so what a reader edits there is what
runs. The same cell sets ``RERUN_NOTEBOOK_ASSET=inline`` unless it is set already, so ``rerun_mode =
"notebook"`` loads the viewer that ships with the installed ``rerun-notebook`` package instead of fetching it
from app.rerun.io (which fails offline with "Failed to fetch"). The copy names the clone's own kernel
(:func:`.kernels.clone_kernel_name`, installed by ``make kernel`` into the clone's environment). A copy that
exists is kept (it holds your edits) unless ``--fresh``; changes meant for the paper notebook are copied back
by hand into ``notebooks/`` (outputs cleared).
"""

from __future__ import annotations

import ast
import io
import json
import tokenize
from pathlib import Path

from .kernels import clone_kernel_name
from .paths import REPO_ROOT, RUNS_DIR, writable_directory
from .preflight import check_values
from .runner import find_notebook, load_profile

__all__ = ["EDIT_DIR", "OFFLINE_VIEWER_LINE", "working_copy", "parameters_cell"]

EDIT_DIR = RUNS_DIR / "edit"
OFFLINE_VIEWER_LINE = 'os.environ.setdefault("RERUN_NOTEBOOK_ASSET", "inline")'
"""Set before ``rerun_notebook`` is imported: the inline viewer then loads the bundled JS and Wasm (offline)."""


def _comment(lines: list[str]) -> str:
    """The trailing ``# comment`` of the last line of a statement (``""`` if none)."""
    try:
        tokens = list(tokenize.generate_tokens(io.StringIO("\n".join(lines) + "\n").readline))
    except (tokenize.TokenError, SyntaxError):
        return ""
    last = len(lines)
    return next(("  " + t.string for t in tokens if t.type == tokenize.COMMENT and t.start[0] == last), "")


def parameters_cell(source: str, values: dict, header: list[str]) -> str:
    """``source`` (a ``parameters`` cell) with each assignment of a name in ``values`` replaced by that value
    (its comment kept), names it does not assign appended, and ``header`` lines first."""
    lines = source.splitlines()
    done = set()
    for node in sorted(ast.parse(source).body, key=lambda n: -n.lineno):  # bottom up: line numbers stay valid
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            name = node.targets[0].id
            if name in values:
                comment = _comment(lines[node.lineno - 1 : node.end_lineno])
                lines[node.lineno - 1 : node.end_lineno] = [f"{name} = {values[name]!r}{comment}"]
                done.add(name)
    lines += [f"{name} = {value!r}" for name, value in values.items() if name not in done]
    return "\n".join(header + lines) + "\n"


def working_copy(
    notebook: str | Path, profile: str = "smoke", fresh: bool = False, folder: Path = EDIT_DIR
) -> tuple[Path, bool]:
    """Write (or find) the working copy of ``notebook`` at ``profile``.

    Returns
    -------
    (Path, bool)
        The copy's path and whether it was written now (``False``: an existing copy was kept).

    Raises
    ------
    UsageError
        Unknown notebook or profile, profile values the notebook refuses, a folder that cannot be written.
    """
    nb = find_notebook(notebook)
    parameters = load_profile(nb, profile)  # an unknown profile is refused also when the copy is kept
    copy = Path(folder) / f"{nb.stem}.ipynb"
    if copy.exists() and not fresh:
        return copy, False
    check_values(nb, parameters)
    writable_directory(Path(folder), "edit folder")
    output_dir = (Path(folder) / f"{nb.stem}-out").resolve()
    data = json.loads(nb.read_text())
    for cell in data["cells"]:
        if cell["cell_type"] == "code":
            cell["outputs"], cell["execution_count"] = [], None
    first = next(c for c in data["cells"] if c["cell_type"] == "code")
    source = first["source"] if isinstance(first["source"], str) else "".join(first["source"])
    header = [
        f"# Working copy by `python -m tvtrack edit` from {nb.name}: the {profile or 'paper'} profile's values, "
        "edit them here.",
        "import os",
        "",
        OFFLINE_VIEWER_LINE + "  # the inline Rerun viewer from the installed package (offline)",
    ]
    first["source"] = parameters_cell(source, {**parameters, "output_dir": str(output_dir)}, header)
    data.setdefault("metadata", {})["kernelspec"] = {
        "name": clone_kernel_name(),
        "display_name": f"Python (tvtrack-repro, {REPO_ROOT.name} at {REPO_ROOT.parent})",
        "language": "python",
    }
    copy.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n")
    return copy, True
