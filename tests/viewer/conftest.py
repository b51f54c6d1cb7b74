"""Fixtures of the viewer check: one headless Rerun viewer per session, and smoke runs of the
test-fixture notebooks (which have no smoke profile). Paper notebooks' smoke runs come from the
session-wide ``smoke_run`` fixture in ``tests/conftest.py``, shared with the generic notebook test,
so no notebook runs twice.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tvtrack.pipeline.paths import REPO_ROOT
from tvtrack.pipeline.runner import list_notebooks, run_notebook

# test-fixture notebook -> parameter overrides that make it a smoke run
FIXTURE_RUNS = {REPO_ROOT / "tests" / "fixtures" / "fixture_centroid.ipynb": {"n_trials": 20}}


def viewer_notebooks() -> list[Path]:
    """Every paper notebook in ``notebooks/`` plus the fixture notebooks, in name order."""
    return list_notebooks() + [nb for nb in FIXTURE_RUNS if nb.is_file()]


def pytest_generate_tests(metafunc):
    """Parametrise ``viewer_notebook`` over :func:`viewer_notebooks`."""
    if "viewer_notebook" in metafunc.fixturenames:
        notebooks = viewer_notebooks()
        metafunc.parametrize("viewer_notebook", notebooks, ids=[nb.stem for nb in notebooks])


@pytest.fixture(scope="session")
def fixture_smoke_run(tmp_path_factory):
    """``fixture_smoke_run(path) -> RunOutcome`` for a notebook of ``FIXTURE_RUNS``, run once."""
    cache = {}
    root = tmp_path_factory.mktemp("viewer_fixture_runs")

    def get(notebook: Path):
        if notebook not in cache:
            cache[notebook] = run_notebook(notebook, root / notebook.stem, FIXTURE_RUNS[notebook])
        return cache[notebook]

    return get


@pytest.fixture
def notebook_run(smoke_run, fixture_smoke_run):
    """``notebook_run(path) -> RunOutcome``: the shared smoke run of a paper notebook, or the
    fixture notebook's own run."""
    return lambda nb: fixture_smoke_run(nb) if nb in FIXTURE_RUNS else smoke_run(nb.stem)


@pytest.fixture(scope="session")
def headless_viewer():
    """One native Rerun viewer, headless on a fresh port, for the whole session.

    Skips (with the reason and what to install) where no Vulkan driver is present, unless
    ``TVTRACK_REQUIRE_VIEWER=1`` (set in CI, where the driver is installed), which fails instead.
    """
    from tvtrack.pipeline.viewer import HeadlessViewer, ViewerUnavailable

    viewer = HeadlessViewer()
    try:
        viewer.start()
    except ViewerUnavailable as exc:
        message = f"Rerun viewer check cannot run: {exc}"
        if os.environ.get("TVTRACK_REQUIRE_VIEWER") == "1":
            pytest.fail(message + " (TVTRACK_REQUIRE_VIEWER=1)", pytrace=False)
        pytest.skip(message)
    try:
        yield viewer
    finally:
        viewer.close()
