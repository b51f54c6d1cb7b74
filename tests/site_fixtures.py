"""A small runs directory for the site tests: one real run of the fixture notebook, a run written before the
verdict standard, a failed run and a sweep summary (built once per test session; the two runs of the fixture notebook are the session's, copied)."""

from __future__ import annotations

import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from conftest import copy_fixture_runs  # noqa: E402

OLD_CLAIM = {
    "id": "C911-1",
    "statement": "An old claim.",
    "paper_value": "2",
    "acceptance": "within 10 % of 2",
    "measured": {"value": 2.1, "ci_low": 1.9, "ci_high": 2.3},
    "verdict": "partly",
    "note": "old schema",
}


NEW_CLAIM = {
    "id": "C912-1",
    "statement": "The error is sigma*2 <b>not bold</b> & small.",
    "paper_value": "<= 2 px",
    "rule": {"kind": "in_band", "text": "error in [0, 2] px", "low": 0.0, "high": 2.0},
    "acceptance": "error in [0, 2] px",
    "measured": {"value": 2.6, "ci_low": 2.4, "ci_high": 2.8},
    "verdict": "not reproduced",
    "note": "",
    "robustness": {
        "label": "depends",
        "where": ["reproduced when motion = gentle*2"],
        "coverage": "depends over 6 readings x 3 replicates: motion, noise",
        "register": [{"name": "motion"}, {"name": "noise"}],
        "parts": {"error": {"verdict": "not reproduced", "label": "depends"}},
        "conditions": [
            {"choices": {"motion": "gentle*2"}, "verdict": "reproduced"},
            {"choices": {"noise": "poisson"}, "verdict": "not reproduced"},
        ],
    },
}
UNDECIDED_CLAIM = {
    "id": "C912-2",
    "statement": "The rate is tiny.",
    "paper_value": "1e-6",
    "rule": {"kind": "in_band", "text": "rate in [0, 1e-5]", "low": 0.0, "high": 1e-5},
    "acceptance": "rate in [0, 1e-5]",
    "measured": {"value": None, "ci_low": None, "ci_high": None},
    "verdict": "undecided",
    "note": "",
    "robustness": {"label": "unexplored", "where": []},
}


def make_runs_dir(root, fixture_runs):
    """``root/reproduce/{fixture_centroid, old_schema, new_schema, broken}`` (new_schema: records with
    parts, coverage and register, text that must be escaped, an undecided claim) and
    ``root/fixture_sweep/summary.{csv,png}``; fixture_centroid and broken are copies of the session's
    ``fixture_runs`` (tests/conftest.py)."""
    reproduce = copy_fixture_runs(fixture_runs, root / "reproduce")
    old = reproduce / "old_schema"
    old.mkdir()
    (old / "run.json").write_text(
        json.dumps(
            {
                "notebook": "old_schema",
                "profile": "paper",
                "status": "ok",
                "runtime_s": 3.0,
                "finished_utc": "2026-11-20T09:00:00Z",
            }
        )
    )
    (old / "results.json").write_text(
        json.dumps(
            {
                "notebook": "old_schema",
                "citation": "Old: a paper",
                "seed": 1,
                "runtime_s": 2.0,
                "git_commit": None,
                "claims": [OLD_CLAIM],
                "figures": [{"file": "old.png", "caption": "An old figure."}],
                "recording": None,
            }
        )
    )
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([0, 1], [1, 0])
    fig.savefig(old / "old.png")
    plt.close(fig)
    (old / "notebook.ipynb").write_text(
        json.dumps(
            {
                "nbformat": 4,
                "nbformat_minor": 5,
                "metadata": {},
                "cells": [
                    {
                        "cell_type": "markdown",
                        "id": "m1",
                        "metadata": {},
                        "source": "The gain $G = \\frac{\\sigma_1^2}{\\sigma_2^2}$ and\n\n$$\\hat x_k = x_k + \\varepsilon$$",
                    },
                    {
                        "cell_type": "code",
                        "id": "c1",
                        "metadata": {},
                        "execution_count": 1,
                        "outputs": [],
                        "source": "results.claim(id='C911-1', ...)",
                    },
                ],
            }
        )
    )
    new = reproduce / "new_schema"
    new.mkdir()
    (new / "run.json").write_text(
        json.dumps(
            {
                "notebook": "new_schema",
                "profile": "paper",
                "status": "ok",
                "runtime_s": 4.0,
                "finished_utc": "2026-11-25T01:00:00Z",
            }
        )
    )
    (new / "results.json").write_text(
        json.dumps(
            {
                "notebook": "new_schema",
                "citation": "New: a paper",
                "seed": 1,
                "runtime_s": 3.0,
                "git_commit": None,
                "figures": [],
                "claims": [NEW_CLAIM, UNDECIDED_CLAIM],
                "recording": None,
            }
        )
    )
    (new / "notebook.ipynb").write_text(
        json.dumps(
            {
                "nbformat": 4,
                "nbformat_minor": 5,
                "metadata": {},
                "cells": [
                    {
                        "cell_type": "code",
                        "id": "n1",
                        "metadata": {},
                        "execution_count": 1,
                        "outputs": [],
                        "source": "results.claim(id='C912-1', ...)",
                    }
                ],
            }
        )
    )
    smoke = root / "reproduce-smoke" / "old_schema"
    smoke.mkdir(parents=True)
    for name in ("run.json", "results.json", "notebook.ipynb"):
        text = (old / name).read_text()
        (smoke / name).write_text(text.replace('"profile": "paper"', '"profile": "smoke"'))
    sweep = root / "fixture_sweep"
    sweep.mkdir()
    (sweep / "summary.csv").write_text(
        "id,status,spot_sigma_px,centroid_rms_px.value\na1,ok,1.0,0.05\nb2,ok,2.0,0.09\nc3,failed,3.0,\n"
    )
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([1, 2], [0.05, 0.09])
    fig.savefig(sweep / "summary.png")
    plt.close(fig)
    return root


@pytest.fixture(scope="session")
def runs_dir(tmp_path_factory, fixture_runs):
    return make_runs_dir(tmp_path_factory.mktemp("site-runs"), fixture_runs)


@pytest.fixture(scope="session")
def built_site(runs_dir):
    from tvtrack.pipeline.site import build_site

    return build_site(runs_dir).parent


def make_explored_runs(root, claims=None):
    """``root/reproduce/001_explored``: one run whose claims carry the explorer's record (shares, flips by phrase,
    runs to decide, a smoke-size design, a long deterministic vector; :mod:`record_fixtures`), or ``claims``."""
    from record_fixtures import CLAIMS

    CLAIMS = CLAIMS if claims is None else claims  # noqa: N806 - the fixture's own list, or the caller's

    run = root / "reproduce" / "001_explored"
    run.mkdir(parents=True)
    (run / "run.json").write_text(
        json.dumps(
            {
                "notebook": "001_explored",
                "profile": "paper",
                "status": "ok",
                "runtime_s": 5.0,
                "finished_utc": "2026-11-28T10:00:00Z",
            }
        )
    )
    (run / "results.json").write_text(
        json.dumps(
            {
                "notebook": "001_explored",
                "citation": "Explored: a paper",
                "seed": 1,
                "runtime_s": 4.0,
                "git_commit": None,
                "figures": [],
                "claims": CLAIMS,
                "recording": None,
            }
        )
    )
    cells = [
        {
            "cell_type": "code",
            "id": f"e{k}",
            "metadata": {},
            "execution_count": k + 1,
            "outputs": [],
            "source": f"results.claim(id='{c['id']}', ...)",
        }
        for k, c in enumerate(CLAIMS)
    ]
    (run / "notebook.ipynb").write_text(
        json.dumps({"nbformat": 4, "nbformat_minor": 5, "metadata": {}, "cells": cells})
    )
    return root


@pytest.fixture(scope="session")
def explored_site(tmp_path_factory):
    from tvtrack.pipeline.site import build_site

    return build_site(make_explored_runs(tmp_path_factory.mktemp("explored-runs"))).parent
