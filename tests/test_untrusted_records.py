"""Run files and output markers are read as untrusted: a file name they list never reaches outside its folder, a
damaged one deletes nothing and stops a command in one line before any work."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import finished_run, minimal_claim, one_line_error

from tvtrack.pipeline import outputs, site
from tvtrack.pipeline import reproduce as rep
from tvtrack.pipeline.outputs import MARKER, replace_folder
from tvtrack.pipeline.preflight import UsageError
from tvtrack.pipeline.report import collect_runs
from tvtrack.pipeline.runfiles import DamagedRun

NOTEBOOK = "004_laser_spot_prediction"
OTHER = "000_dissector_ekf"


def tvtrack(*args, timeout=120):
    return subprocess.run(
        [sys.executable, "-m", "tvtrack", *map(str, args)], capture_output=True, text=True, timeout=timeout
    )


def one_line(proc, *fragments) -> str:
    return one_line_error(proc, *fragments)


def _claim(cid: str = "C1-1") -> dict:
    return minimal_claim(cid)


def _fresh(tmp_path: Path) -> Path:
    new = tmp_path / "new"
    new.mkdir()
    (new / "run.json").write_text(json.dumps({"status": "ok", "runtime_s": 1.0, "files": ["run.json"]}))
    return new


# --- replacing a run folder ------------------------------------------------------------------------------------


def test_a_truncated_run_json_deletes_nothing_of_the_run_it_replaces(tmp_path):
    run = finished_run(tmp_path / "reproduce-smoke")
    (run / "my_notes.md").write_text("mine")
    (run / "run.json").write_text((run / "run.json").read_text()[:40])
    left = replace_folder(_fresh(tmp_path), run, legacy_run=True)
    (old,) = run.parent.glob(".old-p1-*")
    assert (old / "my_notes.md").read_text() == "mine" and str(old / "my_notes.md") in left
    assert {p.name for p in old.iterdir()} == {"my_notes.md", "notebook.ipynb", "results.json", "run.json"}


@pytest.mark.parametrize("entry", ["../../victim.txt", "ABSOLUTE", "sub/../../victim.txt"])
def test_a_listed_file_outside_the_folder_is_never_deleted(tmp_path, entry):
    victim = tmp_path / "victim.txt"
    victim.write_text("user data")
    run = finished_run(tmp_path / "reproduce-smoke")
    entry = str(victim) if entry == "ABSOLUTE" else entry
    record = json.loads((run / "run.json").read_text())
    (run / "run.json").write_text(json.dumps({**record, "files": [*record["files"], entry]}))
    replace_folder(_fresh(tmp_path), run, legacy_run=True)
    assert victim.read_text() == "user data"


def test_listed_inside_keeps_names_to_the_folder(tmp_path):
    (tmp_path / "f").mkdir()
    (tmp_path / "f" / "out").symlink_to(tmp_path)
    assert outputs.listed_inside(tmp_path / "f", "a/b.png") and outputs.listed_inside(tmp_path / "f", "results.json")
    for bad in ("../x", "/etc/passwd", "", ".", "out/x", 5, None, ["a"]):
        assert not outputs.listed_inside(tmp_path / "f", bad), bad


# --- reproduce: checked before any run -------------------------------------------------------------------------


def _no_runs(monkeypatch) -> list:
    ran = []
    monkeypatch.setattr(rep, "_run_notebooks", lambda nbs, *a: ran.extend(nbs) or [])
    monkeypatch.setattr(rep, "write_report", lambda *a, **k: Path("REPRODUCTION.md"))
    return ran


def test_reproduce_refuses_a_run_json_listing_a_file_outside_before_any_run(tmp_path, monkeypatch):
    ran = _no_runs(monkeypatch)
    victim = tmp_path / "victim.txt"
    victim.write_text("user data")
    run = finished_run(tmp_path / "reproduce-smoke", NOTEBOOK)
    record = json.loads((run / "run.json").read_text())
    (run / "run.json").write_text(json.dumps({**record, "files": [*record["files"], "../../victim.txt"]}))
    with pytest.raises(UsageError, match=r"run\.json: 'files' lists '\.\./\.\./victim\.txt'"):
        rep.reproduce(profile="smoke", only=[NOTEBOOK], jobs=1, runs_dir=tmp_path, force=True)
    assert ran == [] and victim.read_text() == "user data"


def test_reproduce_only_checks_the_other_runs_the_report_reads_before_running(tmp_path, monkeypatch):
    ran = _no_runs(monkeypatch)
    other = tmp_path / "reproduce-smoke" / OTHER
    other.mkdir(parents=True)
    (other / "run.json").write_text('{"status": "ok", "runti')
    with pytest.raises(DamagedRun, match=f"{OTHER}/run.json: not valid JSON"):
        rep.reproduce(profile="smoke", only=[NOTEBOOK], jobs=1, runs_dir=tmp_path)
    assert ran == []


def test_reproduce_with_an_unknown_profile_creates_nothing(tmp_path, monkeypatch):
    ran = _no_runs(monkeypatch)
    with pytest.raises(UsageError, match="no profile 'nope'"):
        rep.reproduce(profile="nope", only=[NOTEBOOK], jobs=1, runs_dir=tmp_path)
    assert ran == [] and list(tmp_path.iterdir()) == []


# --- site: markers and records name files inside their folder only ----------------------------------------------


def test_site_refuses_a_marker_listing_a_file_outside_the_site(tmp_path):
    (tmp_path / "reproduce").mkdir()
    folder = tmp_path / "sites" / "m1"
    folder.mkdir(parents=True)
    (folder / "index.html").write_text("old site")
    victim = tmp_path / "sites" / "victim2.txt"
    victim.write_text("user data")
    for entry in ("../victim2.txt", str(victim)):
        (folder / MARKER).write_text(json.dumps({"kind": "site", "files": ["index.html", entry]}))
        one_line(tvtrack("site", "--runs", tmp_path, "-o", folder), f"{folder / MARKER}", repr(entry), "relative")
        assert victim.read_text() == "user data" and (folder / "index.html").read_text() == "old site"


def test_site_refuses_a_figure_or_recording_outside_the_run(tmp_path):
    outside = tmp_path / "victim4.txt"
    outside.write_text("from outside the run")
    out = tmp_path / "sites" / "fig" / "out"
    out.parent.mkdir(parents=True)
    (out.parent / "victim4.txt").write_text("user file")
    run = finished_run(
        tmp_path / "reproduce-smoke", results={"figures": [{"file": "../../victim4.txt", "caption": "x"}]}
    )
    line = one_line(tvtrack("site", "--runs", tmp_path, "--profile", "smoke", "-o", out), f"{run}/results.json")
    assert "figure 1" in line and "'../../victim4.txt'" in line
    assert (out.parent / "victim4.txt").read_text() == "user file" and not out.exists()
    data = json.loads((run / "results.json").read_text())
    (run / "results.json").write_text(json.dumps({**data, "figures": [], "recording": "/etc/passwd"}))
    with pytest.raises(DamagedRun, match="'recording' '/etc/passwd'"):
        site.build_site(tmp_path, out, "smoke")


# --- report and site: run files of the wrong shape ---------------------------------------------------------------

SHAPES = [
    ("run.json", {"profile": 5}, "profile 5"),
    ("results.json", {"claims": [_claim(5)]}, "id 5"),
    ("results.json", {"claims": [_claim("../../x")]}, "id '../../x'"),
    ("results.json", {"claims": [{**_claim(), "robustness": "x"}]}, "'robustness' is a JSON str"),
    ("results.json", {"claims": [{**_claim(), "rule": "x"}]}, "'rule' is a JSON str"),
    ("results.json", {"runtime_s": "x"}, "runtime_s 'x'"),
    ("results.json", {"figures": "x"}, "'figures' is a JSON str"),
    ("results.json", {"figures": [{"file": 5, "caption": "x"}]}, "figure 1 names the file 5"),
    ("results.json", {"figures": [{"file": "a.png"}]}, "figure 1 is not an object with a file name and a caption"),
    ("results.json", {"recording": 5}, "'recording' 5"),
]


@pytest.mark.parametrize(("name", "change", "said"), SHAPES, ids=[s[2] for s in SHAPES])
def test_a_run_file_of_the_wrong_shape_is_one_line_naming_the_file_and_field(tmp_path, name, change, said):
    run = finished_run(tmp_path / "reproduce-smoke")
    data = json.loads((run / name).read_text())
    (run / name).write_text(json.dumps({**data, **change}))
    with pytest.raises(DamagedRun, match=f"{run / name}: ") as caught:
        collect_runs(run.parent, ["p1"])
    assert said in str(caught.value)


def test_a_damaged_notebook_or_recording_is_one_line_naming_it(tmp_path):
    run = finished_run(tmp_path / "reproduce-smoke")
    for text in ('{"cells": [', "[]"):
        (run / "notebook.ipynb").write_text(text)
        with pytest.raises(DamagedRun, match="notebook.ipynb: not an executed notebook"):
            site.read_notebook(run)
    (run / "notebook.ipynb").write_text(json.dumps({"nbformat": 4, "nbformat_minor": 5, "metadata": {}, "cells": []}))
    (run / "recording.rrd").write_bytes(b"garbage")
    data = json.loads((run / "results.json").read_text())
    (run / "results.json").write_text(json.dumps({**data, "recording": "recording.rrd"}))
    line = one_line(tvtrack("site", "--runs", tmp_path, "--profile", "smoke", "-o", tmp_path / "s"), "recording.rrd")
    assert "not a readable recording" in line and not (tmp_path / "s").exists()
