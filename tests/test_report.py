import pytest

from conftest import FIXTURE_NOTEBOOK
from tvtrack.pipeline.report import format_measured, write_report
from tvtrack.pipeline.runner import run_notebook


@pytest.fixture(scope="module")
def reproduce_dir(tmp_path_factory):
    root = tmp_path_factory.mktemp("reproduce")
    assert run_notebook(FIXTURE_NOTEBOOK, root / "fixture_centroid", {"n_trials": 10, "n_frames": 3}).ok
    assert not run_notebook(FIXTURE_NOTEBOOK, root / "broken", {"n_trials": 0}).ok
    return root


def test_report_counts_claims_and_links_outputs(reproduce_dir, tmp_path):
    path = write_report(reproduce_dir, tmp_path / "REPRODUCTION.md", notebooks=["fixture_centroid", "broken", "absent"])
    text = path.read_text()
    assert "**Claims: 1 reproduced · 0 partly · 0 not reproduced · 0 not checkable** (1 claims, 3 notebooks)" in text
    assert "| C900-1 | **reproduced** |" in text
    assert "centroid_errors.png" in text and "recording.rrd" in text
    assert "**Run failed**" in text and "parameter 'n_trials' = 0" in text
    assert "## absent\n\nNot run yet" in text


def test_report_without_notebooks_says_so(tmp_path):
    text = write_report(tmp_path, tmp_path / "R.md", notebooks=[]).read_text()
    assert "No notebooks in `notebooks/` yet" in text


def test_format_measured():
    assert format_measured({"value": 1.23456, "ci_low": 1.1, "ci_high": 1.3, "n": 5}) == "1.235 [1.1, 1.3]"
    assert format_measured({"a": 2, "b": {"value": 0.5, "ci_low": None, "ci_high": None}}) == "a: 2; b: 0.5"
