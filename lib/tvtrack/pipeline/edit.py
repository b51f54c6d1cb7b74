"""``python -m tvtrack edit NOTEBOOK`` (``make edit NB=...``): a working copy to edit and run in JupyterLab.

The copy is ``papermill_runs/edit/<notebook>.ipynb`` (ignored by git, so autosave never writes outputs into a
tracked notebook), without outputs, with a cell after the ``parameters`` cell (tagged ``injected-parameters``,
as papermill does) that sets the profile's values (default: ``smoke``, small study sizes) and an absolute
``output_dir`` (``papermill_runs/edit/<notebook>-out/``, inside the clone whatever the working directory). The
same cell sets ``RERUN_NOTEBOOK_ASSET=inline`` unless it is set already, so ``rerun_mode = "notebook"`` loads
the viewer that ships with the installed ``rerun-notebook`` package instead of fetching it from app.rerun.io
(which fails offline with "Failed to fetch"). A copy that exists is kept (it holds your edits) unless
``--fresh``; changes meant for the paper notebook are copied back by hand into ``notebooks/`` (outputs cleared).
"""

from __future__ import annotations

import json
from pathlib import Path

from .paths import RUNS_DIR, writable_directory
from .preflight import check_values
from .runner import find_notebook, load_profile

__all__ = ["EDIT_DIR", "OFFLINE_VIEWER_LINE", "working_copy"]

EDIT_DIR = RUNS_DIR / "edit"
OFFLINE_VIEWER_LINE = 'os.environ.setdefault("RERUN_NOTEBOOK_ASSET", "inline")'
"""Set before ``rerun_notebook`` is imported: the inline viewer then loads the bundled JS and Wasm (offline)."""


def _injected_cell(parameters: dict, output_dir: Path, profile: str, source: Path) -> dict:
    lines = [
        f"# Injected by `python -m tvtrack edit` from {source.name} at the {profile} profile: edit freely.",
        "import os",
        OFFLINE_VIEWER_LINE + "  # the inline Rerun viewer from the installed package (offline)",
    ]
    lines += [f"{name} = {value!r}" for name, value in parameters.items()]
    lines.append(f"output_dir = {str(output_dir)!r}")
    return {
        "cell_type": "code",
        "execution_count": None,
        "id": "tvtrack-injected-parameters",
        "metadata": {"tags": ["injected-parameters"]},
        "outputs": [],
        "source": "\n".join(lines) + "\n",
    }


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
    copy = Path(folder) / f"{nb.stem}.ipynb"
    if copy.exists() and not fresh:
        return copy, False
    parameters = load_profile(nb, profile)
    check_values(nb, parameters)
    writable_directory(Path(folder), "edit folder")
    output_dir = (Path(folder) / f"{nb.stem}-out").resolve()
    data = json.loads(nb.read_text())
    for cell in data["cells"]:
        if cell["cell_type"] == "code":
            cell["outputs"], cell["execution_count"] = [], None
    first = next(i for i, c in enumerate(data["cells"]) if c["cell_type"] == "code")
    data["cells"].insert(first + 1, _injected_cell(parameters, output_dir, profile or "paper", nb))
    copy.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n")
    return copy, True
