"""``python -m tvtrack new NNN name`` (:mod:`tvtrack.pipeline.new_paper`): the paper it writes passes ruff, its own
tests, the paper contract and the notebook checks, and its notebook runs at smoke size through the runner."""

from __future__ import annotations

import importlib
import json
import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from load import wall_budget

import test_notebooks as tn
import tvtrack.papers
from tvtrack import contract
from tvtrack.pipeline.cli import main
from tvtrack.pipeline.new_paper import new_paper, notebook_from_cells
from tvtrack.pipeline.paths import REPO_ROOT
from tvtrack.pipeline.preflight import UsageError
from tvtrack.pipeline.runner import run_notebook
from tvtrack.results import load_results

NUMBER, NAME = "905", "spot_demo"
STEM, PACKAGE = f"{NUMBER}_{NAME}", f"p{NUMBER}_{NAME}"
BIN = Path(sys.executable).parent


@pytest.fixture(scope="module")
def tree(tmp_path_factory):
    """A tree holding only the generated paper (and a copy of the project's CITATION.cff)."""
    root = tmp_path_factory.mktemp("new_paper")
    shutil.copy(REPO_ROOT / "CITATION.cff", root / "CITATION.cff")
    written = new_paper(NUMBER, NAME, root=root, title="A demo spot tracker")
    return root, written


@pytest.fixture
def paper(tree, monkeypatch):
    """The generated package importable as ``tvtrack.papers.p905_spot_demo``, here and in kernels started now."""
    root, _ = tree
    folder = str(root / "lib" / "tvtrack" / "papers")
    monkeypatch.setenv("TVTRACK_PAPER_PATH", folder)
    monkeypatch.setattr(tvtrack.papers, "__path__", [*tvtrack.papers.__path__, folder])
    yield importlib.import_module(f"tvtrack.papers.{PACKAGE}")
    for m in [m for m in sys.modules if m.startswith(f"tvtrack.papers.{PACKAGE}")]:
        del sys.modules[m]


def test_it_writes_the_package_notebook_tests_profile_and_a_reference(tree):
    root, written = tree
    rel = sorted(str(p.relative_to(root)) for p in written)
    assert rel == sorted(
        [f"lib/tvtrack/papers/{PACKAGE}/{m}.py" for m in ("__init__", "claims", "params", "plots", "recording")]
        + [f"lib/tvtrack/papers/{PACKAGE}/{m}.py" for m in ("paper", "register", "study")]
        + [f"notebooks/{STEM}.ipynb", f"tests/papers/test_{STEM}.py", f"papermill_runs/profiles/{STEM}.smoke.toml"]
        + ["CITATION.cff"]
    )
    assert "A demo spot tracker" in (root / "CITATION.cff").read_text()
    assert not list(root.rglob("*.tmpl")) and "{{" not in "".join(p.read_text() for p in written)


def test_the_generated_paper_passes_ruff(tree):
    root, _ = tree
    config = ["--config", str(REPO_ROOT / "pyproject.toml")]
    for args in (["check", "lib", "tests", "notebooks"], ["format", "--check", "lib", "tests"]):
        done = subprocess.run([BIN / "ruff", *args, *config], cwd=root, capture_output=True, text=True)
        assert done.returncode == 0, done.stdout + done.stderr


def test_the_generated_paper_conforms_to_the_contract(paper):
    assert contract.check(paper) == []
    assert contract.check_paper(paper.PAPER) == []  # runs its measurement at smoke size
    assert paper.PAPER.parameters()["spot_sigma_px"].unit == "px" and paper.PAPER.smoke_profile()["n_trials"] == 20
    assert list(paper.CLAIMS) == [f"C{NUMBER}-1"] and paper.REGISTER.names == ["read noise"]


def test_the_generated_tests_pass(tree, paper):
    root, _ = tree
    env = os.environ | {"PYTHONPATH": os.pathsep.join([str(REPO_ROOT / "lib"), os.environ.get("PYTHONPATH", "")])}
    done = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", str(root / "tests" / "papers")],
        cwd=root,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0 and "5 passed" in done.stdout, done.stdout[-3000:] + done.stderr[-2000:]


@pytest.mark.notebook
def test_the_generated_notebook_runs_at_smoke_size_and_passes_the_notebook_checks(tree, paper, monkeypatch):
    root, _ = tree
    monkeypatch.setattr(tn, "NOTEBOOK_DIR", root / "notebooks")
    monkeypatch.setattr(tn, "PROFILE_DIR", root / "papermill_runs" / "profiles")
    for check in (
        tn.test_parameters_cell_follows_the_contract,
        tn.test_validation_is_the_next_code_cell,
        tn.test_smoke_profile_exists_and_names_known_parameters,
        tn.test_no_verdict_is_typed_in_a_code_cell,
        tn.test_notebook_keeps_the_budget_of_a_short_paper,
        tn.test_notebook_opens_with_findings_and_ends_with_conclusions,
        tn.test_parameter_ranges_are_written_once,
    ):
        check(STEM)
    smoke = tomllib.loads((root / "papermill_runs" / "profiles" / f"{STEM}.smoke.toml").read_text())
    outcome = run_notebook(root / "notebooks" / f"{STEM}.ipynb", root / "runs" / STEM, smoke)
    assert outcome.ok, f"{outcome.error}\n{(outcome.run_dir / 'error.txt').read_text()}"
    assert outcome.runtime_s < wall_budget(60), f"the smoke run took {outcome.runtime_s:.0f} s"
    for check in (
        tn.test_smoke_run_writes_valid_results_and_recording,
        tn.test_executed_notebook_shows_every_figure_inline_with_its_caption,
        tn.test_executed_notebook_has_no_bare_reprs_or_warnings,
        tn.test_executed_notebook_fills_its_findings_before_any_figure,
    ):
        check(STEM, lambda name: outcome)
    data = load_results(outcome.run_dir / "results.json")
    (claim,) = data["claims"]
    assert claim["id"] == f"C{NUMBER}-1" and [e["name"] for e in data["register"]] == ["read noise"]
    assert 0 < claim["measured"]["value"] < 0.5  # the placeholder world: a bright spot, a fraction of a pixel
    # what the viewer check reads from the file (no viewer needed): opens on the timeline with data, framed
    from dataclasses import replace

    from tvtrack.pipeline.viewer import Expectation, layout_problems, read_layout

    expect = replace(Expectation(), **paper.recording.VIEWER_EXPECTATIONS)
    assert layout_problems(read_layout(outcome.run_dir / "recording.rrd"), expect) == []


def test_it_refuses_a_bad_number_or_name_and_never_overwrites(tree):
    root, _ = tree
    with pytest.raises(UsageError, match="three digits"):
        new_paper("5", NAME, root=root)
    with pytest.raises(UsageError, match="lower case"):
        new_paper("906", "Spot-Demo", root=root)
    with pytest.raises(UsageError, match=f"paper {NUMBER} exists already: {PACKAGE}"):
        new_paper(NUMBER, "other_name", root=root)
    (root / "notebooks" / "906_other.ipynb").write_text("{}")
    with pytest.raises(UsageError, match="would overwrite .*906_other.ipynb"):
        new_paper("906", "other", root=root)
    assert not (root / "lib" / "tvtrack" / "papers" / "p906_other").exists()


def test_the_command_line_names_the_files_it_writes(tmp_path, monkeypatch, capsys):
    import tvtrack.pipeline.new_paper as np_mod

    monkeypatch.setattr(np_mod, "REPO_ROOT", tmp_path)
    monkeypatch.setattr(np_mod.new_paper, "__defaults__", (tmp_path, None))
    assert main(["new", "907", "cli_demo", "--title", "Another demo"]) == 0
    out = capsys.readouterr().out
    assert f"wrote {tmp_path / 'notebooks' / '907_cli_demo.ipynb'}" in out and "docs/adding_a_paper.md" in out
    # what to run next, and where: the tree it wrote into
    assert f"in {tmp_path}," in out and "tests/papers/test_907_cli_demo.py" in out
    assert "tvtrack run 907_cli_demo --profile smoke" in out
    assert main(["new", "907", "cli_demo"]) == 2
    assert "paper 907 exists already" in capsys.readouterr().err


def test_the_cell_format_makes_a_valid_notebook_without_outputs():
    import nbformat

    nb = notebook_from_cells("# %% [markdown]\nTitle\n\n## Findings\n# %% parameters\nseed = 1  # s\n# %%\nx = 1\n")
    node = nbformat.reads(json.dumps(nb), as_version=4)
    nbformat.validate(node)
    assert [c.cell_type for c in node.cells] == ["markdown", "code", "code"]
    assert node.cells[0].source.startswith("# Title") and node.cells[1].metadata.tags == ["parameters"]
    assert all(c.outputs == [] and c.execution_count is None for c in node.cells if c.cell_type == "code")


def test_the_guides_python_examples_are_formatted_and_run(tmp_path):
    import re

    blocks = re.findall(r"```python\n(.*?)```", (REPO_ROOT / "docs" / "adding_a_paper.md").read_text(), re.S)
    assert blocks
    for i, code in enumerate(blocks):
        path = tmp_path / f"example_{i}.py"
        path.write_text(code)
        done = subprocess.run(
            [BIN / "ruff", "format", "--check", "--diff", "--config", str(REPO_ROOT / "pyproject.toml"), str(path)],
            capture_output=True,
            text=True,
        )
        assert done.returncode == 0, done.stdout + done.stderr
        namespace: dict = {}
        exec(compile(code, str(path), "exec"), namespace)  # noqa: S102 - the guide's own example
    assert namespace["REGISTER"].names == ["motion", "alpha"] and set(namespace["DEPENDS"]["C005-1"]) == {
        "motion",
        "alpha",
    }
