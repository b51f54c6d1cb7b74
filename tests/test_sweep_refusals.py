"""What ``run`` and ``sweep`` refuse before any work, and what they no longer trip over after it: a notebook file
papermill cannot run (no ``metadata``, no language, an ``nbformat`` other than 4, a cell without ``source`` or
``metadata``) is one line naming the file; a summary ``x`` the plot cannot place is one line naming ``x``, while a
``hue`` of list values gets a line per value; a plot Matplotlib cannot draw leaves the runs and ``summary.csv``
standing; a folder that changed between the sweep's first look and its lock is checked again under the lock; a
notebook ``seed`` that is no literal integer is one line. All in this process, no kernel started."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import FIXTURE_NOTEBOOK, cli_here, code_cell, damaged_notebook, one_line_error
from tvtrack.pipeline import preflight, runner, sweep
from tvtrack.pipeline.outputs import MARKER
from tvtrack.pipeline.preflight import UsageError
from tvtrack.pipeline.summary import collect_summary
from tvtrack.pipeline.sweep import RunSpec, load_spec

QUICK = '[fixed]\nn_trials = 20\nn_frames = 2\nrerun_mode = "off"\n'


@pytest.fixture
def no_work(monkeypatch):
    """Any notebook run or validation-cell subprocess fails the test: a refusal comes before either."""

    def ran(*args, **kwargs):
        raise AssertionError("work started before the refusal")

    monkeypatch.setattr(runner, "run_notebook", ran)
    monkeypatch.setattr(sweep, "run_notebook", ran)
    monkeypatch.setattr(preflight, "check_values_each", ran)


def spec_file(tmp_path: Path, body: str, notebook: Path = FIXTURE_NOTEBOOK, name: str = "spec.toml") -> Path:
    path = tmp_path / name
    path.write_text(f'notebook = "{notebook}"\n{body}')
    return path


# --- notebooks papermill cannot run ------------------------------------------------------------------------


DAMAGE = {
    "no_metadata": (lambda d: d.pop("metadata"), ["no 'metadata'"]),
    "metadata_a_list": (lambda d: d.update(metadata=[]), ["'metadata'", "list"]),
    "no_language": (lambda d: d.update(metadata={}), ["names no language", "kernelspec", "language_info"]),
    "kernelspec_a_string": (lambda d: d["metadata"].update(kernelspec="python3"), ["'kernelspec'", "JSON object"]),
    "no_cells": (lambda d: d.pop("cells"), ["no 'cells'"]),
    "no_nbformat": (lambda d: d.pop("nbformat"), ["no 'nbformat'", "must be 4"]),
    "nbformat_3": (lambda d: d.update(nbformat=3), ["'nbformat' = 3", "must be 4"]),
    "nbformat_text": (lambda d: d.update(nbformat="4"), ["'nbformat' = '4'", "must be 4"]),
    "no_nbformat_minor": (lambda d: d.pop("nbformat_minor"), ["no 'nbformat_minor'", "integer >= 0"]),
    "cell_without_source": (lambda d: code_cell(d, 0).pop("source"), ["cell 2", "no 'source'"]),
    "cell_without_metadata": (lambda d: code_cell(d, 1).pop("metadata"), ["cell 3", "no 'metadata'"]),
    "cell_of_no_type": (lambda d: d["cells"][0].update(cell_type="text"), ["cell 1", "'text'", "code, markdown"]),
    "outputs_a_number": (lambda d: code_cell(d, 1).update(outputs=5), ["cell 3", "'outputs'", "list of JSON objects"]),
    "no_parameters_cell": (lambda d: code_cell(d, 0)["metadata"].update(tags=[]), ["not tagged 'parameters'"]),
}


@pytest.mark.parametrize("name", list(DAMAGE))
def test_a_notebook_papermill_cannot_run_is_one_line_naming_it_before_any_work(tmp_path, capsys, no_work, name):
    change, fragments = DAMAGE[name]
    nb = damaged_notebook(tmp_path, name, change)
    one_line_error(cli_here(capsys, "run", nb, "-p", "n_trials", "20", "-o", tmp_path / "r"), nb.name, *fragments)
    spec = spec_file(tmp_path, QUICK, nb)
    one_line_error(cli_here(capsys, "sweep", spec, "-o", tmp_path / "sw"), nb.name, *fragments)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([nb.name, spec.name])


def test_the_notebooks_that_run_still_pass_the_check_without_a_kernel(tmp_path):
    for nb in [FIXTURE_NOTEBOOK, *runner.list_notebooks()]:
        assert runner.find_notebook(nb) == Path(nb).resolve()
    lean = damaged_notebook(tmp_path, "lean", lambda d: d.update(metadata={"language_info": {"name": "python"}}))
    assert runner.find_notebook(lean) == lean.resolve()  # a language named by language_info alone is enough


def test_a_parameters_cell_that_assigns_nothing_says_so(tmp_path, capsys, no_work):
    nb = damaged_notebook(tmp_path, "bare", lambda d: code_cell(d, 0).update(source="# nothing here\n"))
    line = one_line_error(cli_here(capsys, "run", nb, "-p", "n_trials", "20"), "bare has no parameter 'n_trials'")
    assert line.endswith("its parameters cell assigns none")


# --- the summary plot ----------------------------------------------------------------------------------------


@pytest.fixture
def list_notebook(tmp_path) -> Path:
    """The fixture notebook with a parameter of list values, ``weights`` (read by nothing)."""
    return damaged_notebook(
        tmp_path, "lists", lambda d: code_cell(d, 0)["source"].append("\nweights = [1.0]  # reals\n")
    )


def test_a_summary_x_of_list_values_is_refused_before_any_run_naming_x(tmp_path, list_notebook):
    grid = "[grid]\nweights = [[1.0], [1.0, 2.0]]\n"
    spec = spec_file(tmp_path, QUICK + grid + '[summary]\nx = "weights"\ny = "centroid_rms_px.value"\n', list_notebook)
    with pytest.raises(UsageError, match=r"\[summary\] x = 'weights' takes \[1.0\] \(list\).*all of one kind"):
        load_spec(spec)
    mixed = spec_file(tmp_path, QUICK + '[grid]\nrerun_mode = ["off", 1]\n', name="mixed.toml")
    mixed.write_text(mixed.read_text().replace('rerun_mode = "off"\n', "") + '[summary]\nx = "rerun_mode"\ny = "a"\n')
    with pytest.raises(UsageError, match=r"x = 'rerun_mode' takes 1 beside 'off'; x must take numbers"):
        load_spec(mixed)


def test_a_summary_hue_of_list_values_is_taken_and_drawn_a_line_per_value(tmp_path, list_notebook):
    grid = "[grid]\nspot_sigma_px = [1.0, 2.0]\nweights = [[1.0], [1.0, 2.0]]\n"
    summary = '[summary]\nx = "spot_sigma_px"\ny = "centroid_rms_px.value"\nhue = "weights"\n'
    spec = load_spec(spec_file(tmp_path, QUICK + grid + summary, list_notebook))
    runs = sweep.expand(spec)
    for i, run in enumerate(runs):
        folder = tmp_path / "sw" / "runs" / run.run_id
        folder.mkdir(parents=True)
        (folder / "run.json").write_text(json.dumps({"status": "ok", "runtime_s": 1.0}))
        metric = {"value": 0.1 * (i + 1), "ci_low": 0.05, "ci_high": 0.5}
        (folder / "results.json").write_text(json.dumps({"metrics": {"centroid_rms_px": metric}, "claims": []}))
    _, plot = collect_summary(tmp_path / "sw", runs, spec.summary)
    assert plot is not None and plot.stat().st_size > 1000


def _rows(folder: Path, values: dict[float, float], hue=None) -> list[RunSpec]:
    """Finished runs by hand in ``folder/runs``: ``{x: y}``, the hue parameter ``h`` set to ``hue``."""
    runs = []
    for i, (x, y) in enumerate(values.items()):
        run = RunSpec("nb", None, {"x": x, "h": hue, "seed": 1}, f"run{i:08d}")
        (folder / "runs" / run.run_id).mkdir(parents=True)
        (folder / "runs" / run.run_id / "run.json").write_text(json.dumps({"status": "ok", "runtime_s": 1.0}))
        (folder / "runs" / run.run_id / "results.json").write_text(json.dumps({"metrics": {"p": y}, "claims": []}))
        runs.append(run)
    return runs


def test_a_plot_matplotlib_cannot_draw_is_left_out_with_why_and_the_summary_stands(tmp_path):
    runs = _rows(tmp_path, {0.2: 0.0, 0.4: 1.0}, hue=1)
    (tmp_path / "summary.png").write_text("an earlier sweep's plot")
    summary = {"x": "x", "y": "p", "yscale": "logit", "hue": "h"}
    csv_path, plot = collect_summary(tmp_path, runs, summary)
    assert plot is None and not (tmp_path / "summary.png").exists() and csv_path.is_file()
    notes: list[str] = []
    collect_summary(tmp_path, runs, summary, None, notes)
    assert len(notes) == 1 and "cannot draw 'p' against 'x'" in notes[0] and "'logit'" in notes[0]


def test_a_logit_x_axis_needs_x_values_in_0_1_before_any_run(tmp_path):
    body = QUICK + '[grid]\nspot_sigma_px = [0.5, 1.0]\n[summary]\nx = "spot_sigma_px"\ny = "centroid_rms_px.value"\n'
    with pytest.raises(UsageError, match=r"xscale = 'logit' needs x values in \(0, 1\); x = 'spot_sigma_px' takes 1.0"):
        load_spec(spec_file(tmp_path, body + 'xscale = "logit"\n'))
    load_spec(spec_file(tmp_path, body + 'xscale = "log"\n'))


# --- the folder, checked again under its lock --------------------------------------------------------------


@pytest.mark.parametrize(
    "files, fragment",
    [
        ({"spec.toml": "# my own spec\n"}, "not a sweep's folder"),
        ({MARKER: json.dumps({"kind": "site", "files": ["index.html"]}), "index.html": "a site"}, "a site tvtrack"),
    ],
    ids=["a user's file", "a site"],
)
def test_a_folder_written_into_between_the_first_check_and_the_lock_is_refused_under_it(
    tmp_path, capsys, monkeypatch, no_work, files, fragment
):
    out = tmp_path / "sw"

    def meanwhile(*args, **kwargs):  # another process writes into the folder while this sweep checks its values
        out.mkdir(exist_ok=True)
        for rel, text in files.items():
            (out / rel).write_text(text)

    monkeypatch.setattr(sweep, "preflight", meanwhile)
    spec = spec_file(tmp_path, QUICK + '[summary]\nx = "n_trials"\ny = "centroid_rms_px.value"\n')
    one_line_error(cli_here(capsys, "sweep", spec, "-o", out), f"-o {out}", fragment)
    assert {p.name: p.read_text() for p in out.iterdir()} == files  # nothing written, no runs/ left behind


def test_a_run_folder_made_between_the_check_and_the_runs_lock_is_one_line_and_kept(tmp_path, capsys, monkeypatch):
    out = tmp_path / "r"
    monkeypatch.setattr(preflight, "check_values_each", lambda sets, timeout_s=120: [[None] * len(o) for _, o in sets])

    def meanwhile(folder):  # the user (or another run) makes the folder after `run` found it free
        out.mkdir()
        (out / "notes.md").write_text("mine")

    monkeypatch.setattr(runner, "remove_stale_temporaries", meanwhile)
    one_line_error(
        cli_here(capsys, "run", FIXTURE_NOTEBOOK, "-p", "n_trials", "20", "-o", out), str(out), "exists already"
    )
    assert [p.name for p in out.iterdir()] == ["notes.md"] and (out / "notes.md").read_text() == "mine"


# --- the notebook's own seed --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "line, fragment",
    [
        ("seed = 2**3\n", "sets no literal integer seed"),
        ("seed = None\n", "sets no literal integer seed"),
        ('seed = "abc"\n', "the base seed 'abc' (notebook) is not an integer"),
    ],
)
def test_a_notebook_seed_a_sweep_cannot_number_from_is_one_line(tmp_path, capsys, no_work, line, fragment):
    nb = damaged_notebook(tmp_path, "seeded", lambda d: code_cell(d, 0)["source"].__setitem__(0, line))
    one_line_error(cli_here(capsys, "sweep", spec_file(tmp_path, QUICK, nb), "-o", tmp_path / "sw"), fragment)
    assert not (tmp_path / "sw").exists()


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        (lambda t: "\ufeff" + t, "Unexpected UTF-8 BOM"),  # Jupyter and papermill read no byte-order mark
        (lambda t: t.replace('"nbformat_minor": 5', '"nbformat_minor": 1' + "0" * 5000), "not a notebook"),
    ],
    ids=["byte-order mark", "an integer of 5001 digits"],
)
def test_a_notebook_json_cannot_read_as_papermill_does_is_one_line(tmp_path, capsys, no_work, text, fragment):
    nb = tmp_path / "odd.ipynb"
    nb.write_text(text(Path(FIXTURE_NOTEBOOK).read_text()), encoding="utf-8")
    one_line_error(cli_here(capsys, "run", nb, "-o", tmp_path / "r"), nb.name, fragment)
    assert not (tmp_path / "r").exists()
