"""Shared fixtures: smoke-profile runs of every notebook, executed once per test session."""

from __future__ import annotations

from pathlib import Path

import pytest

import tvtrack
from tvtrack.pipeline.runner import list_notebooks, run_notebook

REPO = Path(__file__).resolve().parents[1]
# A tvtrack imported from another checkout would test the wrong code (and run its notebooks).
if not Path(tvtrack.__file__).resolve().is_relative_to(REPO / "lib"):
    raise pytest.UsageError(
        f"tests in {REPO} import tvtrack from {tvtrack.__file__}; "
        f"install this checkout (pip install -e .) or set PYTHONPATH={REPO / 'lib'}"
    )

FIXTURES = Path(__file__).parent / "fixtures"
FIXTURE_NOTEBOOK = FIXTURES / "fixture_centroid.ipynb"
FIXTURE_SWEEP = FIXTURES / "fixture_sweep.toml"

NOTEBOOK_NAMES = [nb.stem for nb in list_notebooks()]


@pytest.fixture(scope="session")
def smoke_run(tmp_path_factory):
    """``smoke_run(name) -> RunOutcome``: the notebook's smoke-profile run, executed on first
    use and shared by every test of the session (contract checks, recording checks, viewer)."""
    cache = {}
    root = tmp_path_factory.mktemp("smoke")

    def get(name: str):
        if name not in cache:
            cache[name] = run_notebook(name, root / name, profile="smoke")
        return cache[name]

    return get
