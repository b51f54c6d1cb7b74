"""Inputs that once crashed the command line (a traceback) or were taken without a check: a file that is not
UTF-8, ``-p`` values that are Python but no value, empty notebook names, a symbolic link loop as ``-o``, damaged
notebooks, an unknown ``TVTRACK_KERNEL``, an unknown profile of ``edit`` and malformed ``new`` arguments. Each is
one line ``error: ...`` before any kernel starts and before anything is written."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import pytest

from conftest import FIXTURE_NOTEBOOK, code_cell, damaged_notebook, one_line_error
from tvtrack.pipeline.cli import _parse_value, main
from tvtrack.pipeline.preflight import NotebookBug, UsageError, check_values
from tvtrack.pipeline.paths import REPO_ROOT

QUICK = ["-p", "n_trials", "20", "-p", "n_frames", "2", "-p", "rerun_mode", "off"]


def tvtrack(*args, env=None, timeout=180):  # a hang guard only: a loaded machine stretches a run
    return subprocess.run(
        [sys.executable, "-m", "tvtrack", *map(str, args)],
        capture_output=True,
        text=True,
        timeout=timeout,
        env={**os.environ, **(env or {})},
    )


def one_line(proc, *fragments, status=(2,)):
    """The single ``error: ...`` line of a refused command, after checking its form."""
    return one_line_error(proc, *fragments, status=status)


@pytest.fixture
def notebook(tmp_path):
    """A copy of the fixture notebook, beside which profiles can be written."""
    nb = tmp_path / "fx.ipynb"
    shutil.copy(FIXTURE_NOTEBOOK, nb)
    return nb


def test_a_profile_or_a_sweep_spec_that_is_not_utf8_is_one_line_naming_it(notebook, tmp_path):
    (tmp_path / "fx.nonutf.toml").write_bytes(b"n_trials = 20\n# \xff\n")
    line = one_line(tvtrack("run", notebook, "--profile", "nonutf", "-o", tmp_path / "r"), "fx.nonutf.toml", "UTF-8")
    assert "0xff" in line and not (tmp_path / "r").exists()
    spec = tmp_path / "spec.toml"
    spec.write_bytes(f'notebook = "{notebook}"\n# \xff\n'.encode("latin-1"))
    one_line(tvtrack("sweep", spec, "-o", tmp_path / "sw"), "spec.toml", "UTF-8")
    assert not (tmp_path / "sw").exists()


def test_p_values_that_are_python_but_no_value_are_one_line(tmp_path):
    for text in ("{[1]: 2}", "not " * 3000 + "1"):
        line = one_line(tvtrack("run", FIXTURE_NOTEBOOK, "-p", "n_trials", text, "-o", tmp_path / "r"), "-p n_trials")
        assert len(line) < 300
    assert not (tmp_path / "r").exists()


def test_p_values_keep_their_documented_reading():
    """A Python literal is its value; anything else is the plain string."""
    assert _parse_value("n", "3") == 3 and _parse_value("n", "2.5") == 2.5 and _parse_value("n", "[1, 2]") == [1, 2]
    assert _parse_value("n", "'off'") == "off" and _parse_value("n", "off") == "off"
    assert _parse_value("n", "True") is True and _parse_value("n", "not 1") == "not 1"


@pytest.mark.parametrize("command", ["run", "edit"])
@pytest.mark.parametrize("name", ["", "/"])
def test_an_empty_notebook_name_is_one_line(command, name):
    one_line(tvtrack(command, name), "no notebook", "notebooks here")


def test_an_output_that_is_a_symbolic_link_loop_or_leads_nowhere_is_one_line(tmp_path):
    from tvtrack.pipeline.runner import run_notebook

    (tmp_path / "loop1").symlink_to("loop2")
    (tmp_path / "loop2").symlink_to("loop1")
    (tmp_path / "nowhere").symlink_to(tmp_path / "absent")
    for out in ("loop1", "nowhere"):
        one_line(tvtrack("run", FIXTURE_NOTEBOOK, *QUICK, "-o", tmp_path / out), "exists already")
    assert not (tmp_path / "absent").exists()
    with pytest.raises(UsageError, match="loop1"):
        run_notebook(FIXTURE_NOTEBOOK, tmp_path / "loop1" / "run")


def _param_syntax(data):
    code_cell(data, 0)["source"] = "seed = 1\nn_trials = (20\n"


def _cell_text(data):
    data["cells"].insert(0, "x")


def _no_cell_type(data):
    data["cells"].insert(0, {"metadata": {}, "source": ""})


def _source_number(data):
    code_cell(data, 0)["source"] = 5


def _tags_text(data):
    code_cell(data, 0)["metadata"]["tags"] = "parameters"


def _exits(data):
    code_cell(data, 1)["source"] = "import sys\nsys.exit(0)\n"


@pytest.mark.parametrize(
    "change, status, fragments",
    [
        (_param_syntax, 1, ["parameters cell", "never closed", "line 2"]),
        (_cell_text, 2, ["not a notebook", "cell 1"]),
        (_no_cell_type, 2, ["not a notebook", "cell 1", "cell_type"]),
        (_source_number, 2, ["not a notebook", "cell 2", "source"]),
        (_tags_text, 2, ["not tagged 'parameters'"]),
        (_exits, 1, ["validation cell", "sys.exit(0)"]),
    ],
)
def test_a_damaged_notebook_is_one_line_naming_it_and_the_cell(tmp_path, change, status, fragments):
    nb = damaged_notebook(tmp_path, "damaged", change)
    one_line(tvtrack("run", nb, "-p", "n_trials", "20", "-o", tmp_path / "r"), "damaged", *fragments, status=(status,))
    assert not (tmp_path / "r").exists()


def test_what_the_validation_cell_prints_does_not_spoil_its_answer(tmp_path):
    def prints(data):
        code_cell(data, 1)["source"] = "".join(code_cell(data, 1)["source"]) + '\nprint("no newline", end="")\n'

    nb = damaged_notebook(tmp_path, "printer", prints)
    check_values(nb, {"n_trials": 20})
    with pytest.raises(UsageError, match="n_trials"):
        check_values(nb, {"n_trials": 0})


def test_a_validation_cell_that_ends_python_is_a_bug_of_the_notebook(tmp_path):
    def quits(data):
        code_cell(data, 1)["source"] = "import os\nos._exit(0)\n"

    with pytest.raises(NotebookBug, match="validation cell of quits"):
        check_values(damaged_notebook(tmp_path, "quits", quits), {})


def test_an_unknown_tvtrack_kernel_is_refused_before_any_run(tmp_path, notebook):
    env = {"TVTRACK_KERNEL": "no-such-kernel"}
    one_line(
        tvtrack("run", notebook, *QUICK, "-o", tmp_path / "r", env=env), "TVTRACK_KERNEL", "no-such-kernel", "python3"
    )
    assert not (tmp_path / "r").exists()
    spec = tmp_path / "spec.toml"
    spec.write_text(f'notebook = "{notebook}"\n[fixed]\nn_trials = 20\n[grid]\nseed = [1, 2]\n')
    one_line(tvtrack("sweep", spec, "-o", tmp_path / "sw", env=env), "TVTRACK_KERNEL")
    assert not (tmp_path / "sw").exists()


def test_an_installed_tvtrack_kernel_passes(monkeypatch):
    from tvtrack.pipeline.kernels import check_kernel_variable

    monkeypatch.setenv("TVTRACK_KERNEL", "python3")
    check_kernel_variable()
    monkeypatch.delenv("TVTRACK_KERNEL")
    check_kernel_variable()


def test_edit_refuses_an_unknown_or_unreadable_profile_also_beside_a_kept_copy(notebook, tmp_path):
    from tvtrack.pipeline.edit import working_copy

    folder = tmp_path / "edit"
    folder.mkdir()
    (folder / "fx.ipynb").write_text("{}")  # the user's copy
    with pytest.raises(UsageError, match="no profile 'nope'"):
        working_copy(notebook, profile="nope", folder=folder)
    (tmp_path / "fx.nonutf.toml").write_bytes(b"n_trials = \xff\n")
    with pytest.raises(UsageError, match="fx.nonutf.toml.*UTF-8"):
        working_copy(notebook, profile="nonutf", fresh=True, folder=folder)
    assert (folder / "fx.ipynb").read_text() == "{}"


@pytest.fixture
def root(tmp_path):
    """A tree to write new papers into, holding a copy of the project's CITATION.cff."""
    shutil.copy(REPO_ROOT / "CITATION.cff", tmp_path / "CITATION.cff")
    return tmp_path


@pytest.mark.parametrize(
    "number, name, title, fragment",
    [
        ("012", "dtitle", "A {{x}}", "paper title"),
        ("012", "dtitle", "Tracking \\q spots", "paper title"),
        ("012", "dtitle", "Two\u2028lines", "paper title"),
        ("005\n", "abc", None, "paper number"),
        ("\u0660\u0660\u0665", "abc", None, "paper number"),
        ("008", "abc\n", None, "paper name"),
        ("009", "a" * 245, None, "paper name"),
    ],
)
def test_new_refuses_malformed_arguments_before_writing_anything(root, number, name, title, fragment):
    from tvtrack.pipeline.new_paper import new_paper

    before = (root / "CITATION.cff").read_text()
    with pytest.raises(UsageError, match=fragment):
        new_paper(number, name, root=root, title=title)
    assert sorted(p.name for p in root.iterdir()) == ["CITATION.cff"]
    assert (root / "CITATION.cff").read_text() == before


def test_new_on_the_command_line_refuses_a_long_name_with_status_2(root, monkeypatch, capsys):
    import tvtrack.pipeline.new_paper as np_mod

    monkeypatch.setattr(np_mod.new_paper, "__defaults__", (root, None))
    assert main(["new", "009", "a" * 245]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: paper name")
    assert sorted(p.name for p in root.iterdir()) == ["CITATION.cff"]


def test_new_that_cannot_write_removes_what_it_wrote(root):
    from tvtrack.pipeline.new_paper import new_paper

    (root / "tests").write_text("a file where the tests folder goes")
    with pytest.raises(OSError):
        new_paper("013", "halfway", root=root)
    assert sorted(p.name for p in root.iterdir()) == ["CITATION.cff", "tests"]
    (root / "tests").unlink()
    assert new_paper("013", "halfway", root=root)  # nothing left behind that says "exists already"
