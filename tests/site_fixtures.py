"""A small runs directory for the site tests: one real run of the fixture notebook, a run written before the
verdict standard, a failed run and a sweep summary (built once per test session)."""

from __future__ import annotations

import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from conftest import FIXTURE_NOTEBOOK  # noqa: E402
from tvtrack.pipeline.runner import run_notebook  # noqa: E402

OLD_CLAIM = {"id": "C911-1", "statement": "An old claim.", "paper_value": "2", "acceptance": "within 10 % of 2",
             "measured": {"value": 2.1, "ci_low": 1.9, "ci_high": 2.3}, "verdict": "partly", "note": "old schema"}


def make_runs_dir(root):
    """``root/reproduce/{fixture_centroid, old_schema, broken}`` and ``root/fixture_sweep/summary.{csv,png}``."""
    reproduce = root / "reproduce"
    assert run_notebook(FIXTURE_NOTEBOOK, reproduce / "fixture_centroid", {"n_trials": 10, "n_frames": 3}).ok
    old = reproduce / "old_schema"
    old.mkdir()
    (old / "run.json").write_text(json.dumps({"notebook": "old_schema", "profile": "paper", "status": "ok",
                                              "runtime_s": 3.0, "finished_utc": "2026-11-20T09:00:00Z"}))
    (old / "results.json").write_text(json.dumps({"notebook": "old_schema", "citation": "Old: a paper", "seed": 1,
                                                  "runtime_s": 2.0, "git_commit": None, "claims": [OLD_CLAIM],
                                                  "figures": [{"file": "old.png", "caption": "An old figure."}],
                                                  "recording": None}))
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([0, 1], [1, 0])
    fig.savefig(old / "old.png")
    plt.close(fig)
    (old / "notebook.ipynb").write_text(json.dumps({
        "nbformat": 4, "nbformat_minor": 5, "metadata": {},
        "cells": [{"cell_type": "markdown", "id": "m1", "metadata": {},
                   "source": "The gain $G = \\frac{\\sigma_1^2}{\\sigma_2^2}$ and\n\n$$\\hat x_k = x_k + \\varepsilon$$"},
                  {"cell_type": "code", "id": "c1", "metadata": {}, "execution_count": 1, "outputs": [],
                   "source": "results.claim(id='C911-1', ...)"}]}))
    assert not run_notebook(FIXTURE_NOTEBOOK, reproduce / "broken", {"n_trials": 0}).ok
    sweep = root / "fixture_sweep"
    sweep.mkdir()
    (sweep / "summary.csv").write_text("id,status,spot_sigma_px,centroid_rms_px.value\n"
                                       "a1,ok,1.0,0.05\nb2,ok,2.0,0.09\nc3,failed,3.0,\n")
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([1, 2], [0.05, 0.09])
    fig.savefig(sweep / "summary.png")
    plt.close(fig)
    return root


@pytest.fixture(scope="session")
def runs_dir(tmp_path_factory):
    return make_runs_dir(tmp_path_factory.mktemp("site-runs"))


@pytest.fixture(scope="session")
def built_site(runs_dir):
    from tvtrack.pipeline.site import build_site

    return build_site(runs_dir).parent
