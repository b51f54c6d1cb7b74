"""Shared fixtures: smoke-profile runs of every notebook, executed once per test session."""

from __future__ import annotations

import fcntl
import os
import pickle
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
    use and shared by every test of the session (contract checks, recording checks, viewer).

    Under pytest-xdist (``make test`` runs two workers) the workers share one run per notebook: the first
    worker to ask runs it under a file lock and leaves its outcome beside it; the other waits and reads it."""
    cache = {}
    shared = bool(os.environ.get("PYTEST_XDIST_WORKER"))
    root = (tmp_path_factory.getbasetemp().parent if shared else tmp_path_factory.mktemp("smoke")) / "smoke-shared"
    root.mkdir(parents=True, exist_ok=True)

    def get(name: str):
        if name in cache:
            return cache[name]
        with open(root / f"{name}.lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
            done = root / f"{name}.outcome.pkl"
            if done.exists():
                outcome = pickle.loads(done.read_bytes())
            else:
                outcome = run_notebook(name, root / name, profile="smoke")
                done.write_bytes(pickle.dumps(outcome))
        cache[name] = outcome
        return outcome

    return get
