"""One smoke-profile run per notebook per test session (used by the ``smoke_run`` fixture).

Kept apart from ``conftest.py`` so test modules can import :func:`smoke_notebooks` for
parametrisation.
"""

from __future__ import annotations

from pathlib import Path

from tvtrack.paths import REPO_ROOT
from tvtrack.runner import RunOutcome, find_notebook, list_notebooks, run_notebook

FIXTURE_NOTEBOOKS = [REPO_ROOT / "tests" / "fixtures" / "fixture_centroid.ipynb"]

# notebook stem -> (profile, parameter overrides) for notebooks without a smoke profile
SMOKE_SETTINGS = {"fixture_centroid": (None, {"n_trials": 20})}


def smoke_notebooks() -> list[Path]:
    """Every paper notebook in ``notebooks/`` plus the test fixtures, in name order."""
    return list_notebooks() + [nb for nb in FIXTURE_NOTEBOOKS if nb.is_file()]


class SmokeRuns:
    """Runs each notebook's smoke profile once into ``root/<stem>`` and remembers the outcome."""

    def __init__(self, root: Path):
        self.root = Path(root)
        self._outcomes: dict[Path, RunOutcome] = {}

    def __call__(self, notebook: str | Path) -> RunOutcome:
        nb = find_notebook(notebook)
        if nb not in self._outcomes:
            profile, parameters = SMOKE_SETTINGS.get(nb.stem, ("smoke", {}))
            self._outcomes[nb] = run_notebook(nb, self.root / nb.stem, parameters, profile)
        return self._outcomes[nb]
