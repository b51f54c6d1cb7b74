"""Shared fixtures: one smoke-profile run per notebook per test session, and one headless viewer.

``smoke_run(notebook)`` executes a notebook's smoke profile the first time it is asked for and
returns the cached :class:`tvtrack.runner.RunOutcome` afterwards, so every test that needs a
notebook's smoke output (the viewer check here, the generic notebook test) shares one run.
Test fixtures that have no ``smoke`` profile are listed in ``smoke_runs.SMOKE_SETTINGS``.
"""

from __future__ import annotations

import os

import pytest

from smoke_runs import SmokeRuns


@pytest.fixture(scope="session")
def smoke_run(tmp_path_factory) -> SmokeRuns:
    """``smoke_run(notebook) -> RunOutcome``: the notebook's smoke run, executed once per session."""
    return SmokeRuns(tmp_path_factory.mktemp("smoke_runs"))


@pytest.fixture(scope="session")
def headless_viewer():
    """One native Rerun viewer, headless on a fresh port, for the whole session.

    Skips (with the reason and what to install) where no Vulkan driver is present, unless
    ``TVTRACK_REQUIRE_VIEWER=1`` (set in CI, where the driver is installed), which fails instead.
    """
    from tvtrack.viewer import HeadlessViewer, ViewerUnavailable

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
