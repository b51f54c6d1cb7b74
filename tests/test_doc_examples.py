"""The commands and the sweep spec the docs show are accepted as shown: each passes the checks a real call makes
before any kernel starts (names, values by the notebook's own validation cell, the summary's metric). An example a
reader copies and sees refused is a bug of the docs."""

from __future__ import annotations

import ast
import re
import shlex

import pytest

from conftest import REPO
from tvtrack.pipeline.preflight import check_names, check_values
from tvtrack.pipeline.runner import find_notebook
from tvtrack.pipeline.sweep import expand, load_spec, preflight

#: The prose documents a reader runs commands from.
DOCS = sorted([REPO / "README.md", *(REPO / "docs").rglob("*.md")])


def _fenced(lang: str) -> list[tuple[str, str]]:
    """``[(doc name, block)]``: every fenced block of ``lang`` in :data:`DOCS`."""
    return [
        (doc.relative_to(REPO).as_posix(), m.group(1))
        for doc in DOCS
        for m in re.finditer(rf"```{lang}\n(.*?)```", doc.read_text(), re.S)
    ]


def _literal(text: str):
    """A ``-p`` value as the CLI reads it: a Python literal, else the plain string."""
    try:
        return ast.literal_eval(text)
    except (ValueError, SyntaxError):
        return text


def _run_lines() -> list:
    """Every ``tvtrack run NOTEBOOK ... -p NAME VALUE`` line of the docs' shell blocks, as its arguments."""
    out = []
    for doc, block in _fenced("bash"):
        for line in block.splitlines():
            words = shlex.split(line.split("#")[0])
            if "tvtrack" in words and words[words.index("tvtrack") + 1 : words.index("tvtrack") + 2] == ["run"]:
                args = words[words.index("tvtrack") + 2 :]
                if "-p" in args:
                    out.append(pytest.param(args, id=f"{doc}:{' '.join(args[:1] + args[1:5])}"))
    return out


def test_the_docs_show_a_sweep_spec_and_a_run_with_values():
    assert any("notebook =" in b for _, b in _fenced("toml")) and _run_lines()


@pytest.mark.parametrize("args", _run_lines())
def test_a_run_command_the_docs_show_is_accepted(args):
    notebook = find_notebook(args[0])
    given = {args[i + 1]: args[i + 2] for i, a in enumerate(args) if a == "-p"}
    check_names(notebook, given)
    check_values(notebook, {k: _literal(v) for k, v in given.items()})


@pytest.mark.parametrize("block", [b for _, b in _fenced("toml") if "notebook =" in b], ids=lambda b: b.split('"')[1])
def test_a_sweep_spec_the_docs_show_is_accepted(tmp_path, block):
    path = tmp_path / "shown.toml"
    path.write_text(block)
    spec = load_spec(path)  # names, the summary's axes and metric
    runs = expand(spec)
    assert len(runs) > 1
    preflight(spec, runs)  # every value, by the notebook's validation cell


def test_the_check_refuses_the_examples_the_docs_showed_before(tmp_path):
    """What these tests catch: the spec and the run line the docs once showed (a parameter 004 does not have, values
    outside its ranges)."""
    from tvtrack.pipeline.preflight import UsageError

    path = tmp_path / "old.toml"
    path.write_text(
        'notebook = "004_laser_spot_prediction"\nprofile = "smoke"\nrepeats = 2\n[fixed]\nn_trials = 20\n'
        '[grid]\nhorizon_frames = [1, 2, 5, 10]\n[summary]\nx = "horizon_frames"\ny = "rms_error_px.value"\n'
    )
    with pytest.raises(UsageError, match="horizon_frames"):
        load_spec(path)
    with pytest.raises(UsageError, match="n_trials"):
        check_values(find_notebook("004_laser_spot_prediction"), {"seed": 7, "n_trials": 50})
