"""Shared fixtures: smoke-profile runs of every notebook, executed once per test session."""

from __future__ import annotations

import fcntl
import os
import pickle
import shutil
import signal
from pathlib import Path

import pytest

# Compiled kernels (tvtrack.jit) are kept where the pipeline keeps them, the clone's .jit-cache/ (in a folder named by
# a digest of the package's sources: an edit compiles afresh), set before tvtrack is imported and inherited by
# the xdist workers and every kernel a test starts: a kernel compiled once (a smoke run, a test, an earlier
# session, make reproduce) is loaded by the other processes instead of compiled again.
os.environ.setdefault("TVTRACK_JIT_CACHE", str(Path(__file__).resolve().parents[1] / ".jit-cache"))

import tvtrack  # noqa: E402 - after the compiled-kernel folder is set
from tvtrack.pipeline import lean_imports  # noqa: E402
from tvtrack.pipeline.runner import list_notebooks, run_notebook  # noqa: E402

lean_imports.nbformat()  # the test modules' own `import nbformat` then costs nothing (see lean_imports)

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

# BLAS threads under pytest-xdist: `make test` runs a worker per core, and each worker (with the kernels and pools it
# starts) would otherwise run a BLAS thread per core as well: on two busy cores that made BLAS-bound work (004's
# networks) several times slower. Each worker gets cores // workers, as `tvtrack reproduce` gives its kernels; a
# value the caller set stands. numba keeps its threads: a test compares its kernel on one thread and on all.
BLAS_VARS = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
# numba runs 001's parallel loops on GNU OpenMP threads here (``numba.threading_layer()`` is "omp"), whose idle
# threads spin between loops by default; beside a second test worker that spinning is CPU the other worker needs
# (tests/papers/test_001_cost.py on loaded cores: 42-51 user CPU s spinning, 39 passive). Results do not depend on
# it (the kernels' outputs are the same on any thread count, tested); a value the caller set stands.
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def pytest_configure(config):
    workers = getattr(config.option, "numprocesses", None)
    if isinstance(workers, int) and workers > 1 and not os.environ.get("PYTEST_XDIST_WORKER"):
        for var in BLAS_VARS:  # set in the controller, before the workers start and load BLAS
            os.environ.setdefault(var, str(max(1, len(os.sched_getaffinity(0)) // workers)))


#: The test files that take longest, run first (longest first, in this order), the rest after them in collection
#: order. ``make test`` hands whole files to its two workers (``--dist loadfile``) in collection order
#: (``--no-loadscope-reorder``; by default xdist would order files by their number of tests, which put the longest
#: files, few tests each, last, where one of them could run alone at the end): so the short files fill in at the end.
#: The first two share no compiled kernel: test_declared_entries compiles 001's and 002's kernels (tvtrack.jit) once,
#: alone, into the session's cache, and the smoke runs and paper tests that follow load them instead of compiling
#: them again at the same time in the other worker. A file missing here only runs later; a file listed and gone is
#: ignored.
LONGEST_FIRST = (
    "test_declared_entries.py",
    "test_scale.py",
    "test_notebooks.py",
    "test_site_browser.py",
    "test_intervals.py",
    "test_pipeline_faults.py",
    "test_runner.py",
    "test_runner_interrupts.py",
    "test_cli.py",
    "papers/test_004_lag_tuning.py",
    "papers/test_002_study.py",
    "papers/test_002_readings_act.py",
    "test_pipeline_kernels.py",
    "papers/test_004_study.py",
    "viewer/test_viewer_recordings.py",
    "papers/test_001_cost.py",
    "papers/test_003_speed.py",
)


def pytest_collection_modifyitems(config, items):
    """The files of :data:`LONGEST_FIRST` first, in its order; each file's tests keep their order."""
    rank = {name: i for i, name in enumerate(LONGEST_FIRST)}
    here = Path(__file__).parent

    def key(item):
        try:
            return rank.get(Path(item.path).relative_to(here).as_posix(), len(rank))
        except ValueError:  # a file outside tests/ (make bench's benchmarks/)
            return len(rank)

    items.sort(key=key)  # stable


FIXTURES = Path(__file__).parent / "fixtures"
FIXTURE_NOTEBOOK = FIXTURES / "fixture_centroid.ipynb"
FIXTURE_SWEEP = FIXTURES / "fixture_sweep.toml"

NOTEBOOK_NAMES = [nb.stem for nb in list_notebooks()]


@pytest.fixture(scope="session")
def smoke_run(tmp_path_factory):
    """``smoke_run(name) -> RunOutcome``: the notebook's smoke-profile run, executed on first
    use and shared by every test of the session (contract checks, recording checks, viewer).

    Under pytest-xdist (``make test`` runs two workers) the workers share one run per notebook: the first
    worker to ask runs it under a file lock and leaves its outcome beside it. A worker that finds the run it
    wants under way in the other worker runs a notebook nobody has started meanwhile (every smoke run is needed
    by the session), and waits only when none is left."""
    cache = {}
    shared = bool(os.environ.get("PYTEST_XDIST_WORKER"))
    root = (tmp_path_factory.getbasetemp().parent if shared else tmp_path_factory.mktemp("smoke")) / "smoke-shared"
    root.mkdir(parents=True, exist_ok=True)

    def attempt(name: str, wait: bool):
        """The outcome (run here, or read from the worker that ran it); None when another holds it and not wait."""
        with open(root / f"{name}.lock", "w") as lock:
            try:  # the lock is released when the file closes
                fcntl.flock(lock, fcntl.LOCK_EX if wait else fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                return None
            done = root / f"{name}.outcome.pkl"
            if done.exists():
                outcome = pickle.loads(done.read_bytes())
            else:
                outcome = run_notebook(name, root / name, profile="smoke")
                done.write_bytes(pickle.dumps(outcome))
        cache[name] = outcome
        return outcome

    def get(name: str):
        while name not in cache and attempt(name, wait=False) is None:
            free = [n for n in NOTEBOOK_NAMES if n not in cache and not (root / f"{n}.outcome.pkl").exists()]
            if not any(attempt(n, wait=False) is not None for n in free if n != name):
                attempt(name, wait=True)  # nothing else to do: wait for the other worker's run
        return cache[name]

    return get


#: The fixture notebook's two runs the site and report tests read: one that finishes, one its validation refuses.
FIXTURE_RUNS = {"fixture_centroid": {"n_trials": 10, "n_frames": 3}, "broken": {"n_trials": 0}}


@pytest.fixture(scope="session")
def fixture_runs(tmp_path_factory) -> Path:
    """A folder holding the runs of :data:`FIXTURE_RUNS` (``fixture_centroid``: ok; ``broken``: failed), made once
    per session; under pytest-xdist once for both workers, as :func:`smoke_run`. Tests copy the runs they use
    (:func:`copy_fixture_runs`) and never write here."""
    shared = bool(os.environ.get("PYTEST_XDIST_WORKER"))
    parent = tmp_path_factory.getbasetemp().parent if shared else tmp_path_factory.mktemp("fixture-runs")
    root = parent / "fixture-runs-shared"
    with open(parent / "fixture-runs-shared.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        if not (parent / "fixture-runs-shared.done").exists():
            shutil.rmtree(root, ignore_errors=True)  # what a worker killed midway left
            for name, params in FIXTURE_RUNS.items():
                outcome = run_notebook(FIXTURE_NOTEBOOK, root / name, params)
                assert outcome.ok == (name == "fixture_centroid"), (name, outcome.error)
            (parent / "fixture-runs-shared.done").write_text("")
    return root


def copy_fixture_runs(fixture_runs: Path, folder: Path) -> Path:
    """``folder/fixture_centroid`` and ``folder/broken``, copies of the session's :func:`fixture_runs`."""
    for name in FIXTURE_RUNS:
        shutil.copytree(fixture_runs / name, folder / name)
    return folder


def one_line_error(proc, *fragments, status=(2,)) -> str:
    """The single ``error: ...`` line of a refused command: its exit status in ``status``, no traceback, every one
    of ``fragments`` in the line."""
    assert proc.returncode in status, (proc.returncode, proc.stdout, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), proc.stderr
    assert "Traceback" not in proc.stderr + proc.stdout
    for fragment in fragments:
        assert fragment in lines[0], (fragment, lines[0])
    return lines[0]


def minimal_claim(cid: str = "C1-1", verdict: str = "reproduced") -> dict:
    """A claim record with every key a report needs, for run files written by hand."""
    return {
        "id": cid,
        "statement": "A claim.",
        "paper_value": "1",
        "rule": {"kind": "in_band", "text": "in [0, 2]", "low": 0.0, "high": 2.0},
        "acceptance": "in [0, 2]",
        "measured": {"value": 1.5, "ci_low": 1.2, "ci_high": 1.8, "n": 50},
        "verdict": verdict,
        "note": "",
        "robustness": None,
    }


def finished_run(root: Path, name: str = "p1", record: dict | None = None, results: dict | None = None) -> Path:
    """``root/name``: a finished smoke run as the runner leaves it (``run.json`` lists its files), with a hand-made
    ``results.json`` of one :func:`minimal_claim`; ``record`` and ``results`` override their keys."""
    import json

    run = root / name
    run.mkdir(parents=True)
    data = {"notebook": name, "citation": "A: p", "seed": 1, "runtime_s": 10.0, "git_commit": None, "metrics": {}}
    data.update({"figures": [], "recording": None, "claims": [minimal_claim()], **(results or {})})
    (run / "results.json").write_text(json.dumps(data))
    (run / "notebook.ipynb").write_text(json.dumps({"nbformat": 4, "nbformat_minor": 5, "metadata": {}, "cells": []}))
    base = {"notebook": name, "profile": "smoke", "status": "ok", "runtime_s": 12.0, "finished_utc": "2026-12-01"}
    files = sorted(p.name for p in run.iterdir()) + ["run.json"]
    (run / "run.json").write_text(json.dumps({**base, "files": files, **(record or {})}))
    return run


def damaged_notebook(folder: Path, name: str, change) -> Path:
    """``folder/name.ipynb``: a copy of the fixture notebook, its JSON changed by ``change(data)``."""
    import json

    data = json.loads(FIXTURE_NOTEBOOK.read_text())
    change(data)
    path = folder / f"{name}.ipynb"
    path.write_text(json.dumps(data))
    return path


def code_cell(data: dict, index: int) -> dict:
    """The ``index``-th code cell of a notebook's JSON."""
    return [c for c in data["cells"] if c["cell_type"] == "code"][index]


def cli_here(capsys, *args):
    """``python -m tvtrack ARGS`` run in this process (no interpreter start): ``returncode``, ``stdout`` and
    ``stderr``, as :func:`subprocess.run` gives them, for :func:`one_line_error`."""
    from types import SimpleNamespace

    from tvtrack.pipeline import cli

    capsys.readouterr()
    code = cli.main([str(a) for a in args])
    out, err = capsys.readouterr()
    return SimpleNamespace(returncode=code, stdout=out, stderr=err)
