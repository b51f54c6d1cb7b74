"""Shared fixtures: smoke-profile runs of every notebook, executed once per test session."""

from __future__ import annotations

import fcntl
import os
import pickle
import shutil
import signal
import tempfile
from pathlib import Path

import pytest

# Compiled kernels (tvtrack.jit) are kept for this session in a folder of its own, set before tvtrack is imported
# and inherited by the xdist workers and every kernel a test starts: a kernel compiled once (a smoke run, a test)
# is loaded by the other processes instead of compiled again. A session never reads an earlier session's code.
_OWN_JIT_CACHE = None
if "TVTRACK_JIT_CACHE" not in os.environ:
    _OWN_JIT_CACHE = os.environ["TVTRACK_JIT_CACHE"] = tempfile.mkdtemp(prefix="tvtrack-test-jit-")


def pytest_unconfigure(config):
    if _OWN_JIT_CACHE:  # only the process that made the folder (the xdist controller) removes it
        shutil.rmtree(_OWN_JIT_CACHE, ignore_errors=True)


import tvtrack  # noqa: E402 - after the compiled-kernel folder is set
from tvtrack.pipeline.runner import list_notebooks, run_notebook  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
# A tvtrack imported from another checkout would test the wrong code (and run its notebooks).
if not Path(tvtrack.__file__).resolve().is_relative_to(REPO / "lib"):
    raise pytest.UsageError(
        f"tests in {REPO} import tvtrack from {tvtrack.__file__}; "
        f"install this checkout (pip install -e .) or set PYTHONPATH={REPO / 'lib'}"
    )

# A shell starts a background job (`make test &`, a CI step in the background) with Ctrl-C ignored, and every
# process it starts inherits that: the tests that send Ctrl-C to a run, a sweep or the viewer would see it
# ignored. Python's own handler here is reset to the default in each child at exec, as in a terminal.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

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
