"""A sweep checks what it is given before any run: it writes only into a new, empty or sweep's folder and deletes
no file it did not write; a spec value of the wrong type, a seed outside the notebooks' rule or a summary scale
Matplotlib has not is one line ``error: ...`` naming the spec file and key (exit status 2), with no run started and
no folder written."""

import json
import subprocess
import sys

import pytest

from conftest import one_line_error, FIXTURE_NOTEBOOK
from tvtrack.pipeline.outputs import MARKER
from tvtrack.pipeline.preflight import UsageError, check_values_many
from tvtrack.pipeline.sweep import check_sweep_folder, expand, load_spec, run_sweep
from tvtrack.pipeline.sweepcheck import SEED_MAX

QUICK = '[fixed]\nn_trials = 20\nn_frames = 2\nrerun_mode = "off"\n'


def tvtrack(*args, timeout=120):
    return subprocess.run(
        [sys.executable, "-m", "tvtrack", *map(str, args)], capture_output=True, text=True, timeout=timeout
    )


def one_line(proc, *fragments):
    """The one ``error:`` line of a refused command (exit status 2, no traceback), holding every fragment."""
    return one_line_error(proc, *fragments)


def write_spec(tmp_path, body, name="spec.toml", notebook=True):
    path = tmp_path / name
    path.write_text((f'notebook = "{FIXTURE_NOTEBOOK}"\n' if notebook else "") + body)
    return path


def snapshot(folder):
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


# --- the sweep's folder -----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "files, fragment",
    [
        ({"summary.csv": "my own summary\n", "spec.toml": "# mine\n"}, "not a sweep's folder"),
        ({"notes.md": "my notes\n"}, "not a sweep's folder"),
        ({"summary.png": "mine", "runs/abc/notes.md": "mine"}, "not a sweep's folder"),
        ({MARKER: json.dumps({"kind": "site", "files": ["index.html"]}), "index.html": "x"}, "a site tvtrack built"),
        (
            {MARKER: json.dumps({"kind": "sweep", "files": ["spec.toml"]}), "summary.csv": "mine\n"},
            "holds summary.csv, which no sweep wrote there",
        ),
    ],
    ids=["user summary and spec", "user notes", "user runs folder", "a site", "marked sweep with a user file"],
)
def test_a_sweep_refuses_a_folder_it_did_not_make_and_leaves_it_as_it_was(tmp_path, files, fragment):
    out = tmp_path / "userdir"
    for rel, text in files.items():
        (out / rel).parent.mkdir(parents=True, exist_ok=True)
        (out / rel).write_text(text)
    before = snapshot(out)
    spec = write_spec(tmp_path, QUICK + '[summary]\nx = "n_trials"\ny = "centroid_rms_px.value"\n')
    one_line(tvtrack("sweep", spec, "-o", out), f"-o {out}", fragment)
    assert snapshot(out) == before and sorted(p.name for p in out.iterdir()) == sorted({r.split("/")[0] for r in files})


def test_a_file_as_the_sweep_folder_is_refused(tmp_path):
    (tmp_path / "afile").write_text("mine")
    with pytest.raises(UsageError, match="it is a file"):
        check_sweep_folder(tmp_path / "afile")
    assert (tmp_path / "afile").read_text() == "mine"


def test_a_sweep_folder_from_before_sweeps_were_marked_is_still_a_sweep(tmp_path):
    out = tmp_path / "old"
    (out / "runs" / "0123456789ab").mkdir(parents=True)
    (out / "runs" / "0123456789ab" / "run.json").write_text("{}")
    (out / "runs" / ".tmp-0123456789ab-01234567").mkdir()
    for name in ("spec.toml", "summary.csv", "summary.png"):
        (out / name).write_text("written by a sweep")
    check_sweep_folder(out)  # no error
    (out / "runs" / "0123456789ab" / "run.json").unlink()  # a folder no run wrote: not a sweep's
    with pytest.raises(UsageError, match="not a sweep's folder"):
        check_sweep_folder(out)


def test_a_sweep_marks_its_folder_and_resumes_into_it_beside_the_users_notes(tmp_path):
    spec = write_spec(tmp_path, QUICK + '[summary]\nx = "n_trials"\ny = "centroid_rms_px.value"\n')
    out = tmp_path / "mine"
    first = run_sweep(spec, output=out, progress=False)
    assert first.n_ok == 1
    marker = json.loads((out / MARKER).read_text())
    assert marker["kind"] == "sweep" and marker["files"] == ["spec.toml", "summary.csv", "summary.png"]
    (out / "notes.md").write_text("my notes")
    again = run_sweep(spec, output=out, progress=False)
    assert (again.n_skipped, again.n_ok) == (1, 1) and (out / "notes.md").read_text() == "my notes"


def _failed_run(spec, out, extra=None, files=("run.json", "error.txt", "notebook.ipynb", "figures/a.png")):
    """A failed run of the spec's one run, as the runner leaves it (``files`` listed in its run.json), with the
    ``extra`` files of a user; returns its folder."""
    (run,) = expand(load_spec(spec))
    folder = out / "runs" / run.run_id
    (folder / "figures").mkdir(parents=True)
    record = {"status": "failed", "error": "RuntimeError: x", "runtime_s": 1.0, "parameters": run.parameters}
    (folder / "run.json").write_text(json.dumps({**record, "files": list(files)}))
    for rel in [*files[1:], *(extra or {})]:
        (folder / rel).write_text((extra or {}).get(rel, "by the run"))
    return folder


def test_a_failed_run_with_a_users_file_in_it_is_refused_and_kept_whole(tmp_path):
    spec = write_spec(tmp_path, QUICK)
    out = tmp_path / "sw"
    folder = _failed_run(spec, out, extra={"notes.md": "analysis notes"})
    before = snapshot(folder)
    one_line(tvtrack("sweep", spec, "-o", out), str(folder), "notes.md", "did not write", "move it out")
    assert snapshot(folder) == before


def test_a_failed_run_is_tried_again_after_deleting_only_what_it_wrote(tmp_path):
    spec = write_spec(tmp_path, QUICK)
    out = tmp_path / "sw"
    folder = _failed_run(spec, out)
    summary = run_sweep(spec, output=out, progress=False)
    assert summary.n_ok == 1 and json.loads((folder / "run.json").read_text())["status"] == "ok"
    assert not (folder / "figures" / "a.png").exists()


@pytest.mark.parametrize(
    "content, fragment",
    [({"notes.md": "mine"}, "no run wrote it"), ({}, None)],
    ids=["a user's folder", "an empty folder"],
)
def test_a_run_folder_without_run_json_is_never_deleted(tmp_path, content, fragment):
    spec = write_spec(tmp_path, QUICK)
    (run,) = expand(load_spec(spec))
    folder = tmp_path / "sw" / "runs" / run.run_id
    folder.mkdir(parents=True)
    for rel, text in content.items():
        (folder / rel).write_text(text)
    (tmp_path / "sw" / MARKER).write_text(json.dumps({"kind": "sweep", "files": ["spec.toml"]}))
    if fragment:
        one_line(tvtrack("sweep", spec, "-o", tmp_path / "sw"), str(folder), fragment)
        assert snapshot(folder) == {"notes.md": b"mine"}
    else:  # nothing in it to lose: the run goes there
        assert run_sweep(spec, output=tmp_path / "sw", progress=False).n_ok == 1


def test_a_legacy_failed_run_that_lists_no_files_is_refused(tmp_path):
    spec = write_spec(tmp_path, QUICK)
    out = tmp_path / "sw"
    folder = _failed_run(spec, out)
    record = json.loads((folder / "run.json").read_text())
    del record["files"]
    (folder / "run.json").write_text(json.dumps(record))
    before = snapshot(folder)
    one_line(tvtrack("sweep", spec, "-o", out), str(folder), "lists no files")
    assert snapshot(folder) == before


# --- seeds ------------------------------------------------------------------------------------------------


def test_the_seed_rule_is_the_notebooks():
    from tvtrack.parameters import COMMON_RULES

    assert SEED_MAX == COMMON_RULES["seed"].high  # the pipeline's copy of the core's rule
    errors = check_values_many(FIXTURE_NOTEBOOK, [{"seed": -1}, {"seed": SEED_MAX + 1}, {"seed": SEED_MAX}])
    assert errors[0] and errors[1] and "'seed'" in errors[0] and not errors[2]


@pytest.mark.parametrize(
    "body, fragments",
    [
        (QUICK + "[grid]\nseed = [1, -1]\n", ["[grid] seed: -1", "[0, 2**63-1]", "no run started"]),
        (QUICK + "[zip]\nseed = [1, true]\nspot_sigma_px = [1.0, 2.0]\n", ["[zip] seed: True", "no run started"]),
        ("repeats = 2\n" + QUICK + f"seed = {SEED_MAX}\n", ["repeats = 2", f"seed {SEED_MAX + 1}", "no run started"]),
        ("repeats = 2\n" + QUICK + "seed = 1.7\n", ["[fixed] seed: 1.7", "no run started"]),
        ("repeats = 2\n" + QUICK + 'seed = "abc"\n', ["[fixed] seed: 'abc'", "no run started"]),
        ("seed = 3\n" + QUICK, ["'seed' = 3 at the top level", "[fixed]"]),
    ],
    ids=["negative in a grid", "a bool in a zip", "repeats past the top", "a real", "a string", "top level"],
)
def test_a_seed_outside_the_rule_is_one_line_before_any_run(tmp_path, body, fragments):
    spec = write_spec(tmp_path, body)
    one_line(tvtrack("sweep", spec, "-o", tmp_path / "out"), "spec.toml", *fragments)
    assert not (tmp_path / "out").exists()


# --- types of the spec's values ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "body, fragments",
    [
        ("notebook = 5\n", ["'notebook' = 5", "a non-empty string"]),
        (f'notebook = ["{FIXTURE_NOTEBOOK}"]\n', ["'notebook' = [", "a non-empty string"]),
        (f'notebook = "{FIXTURE_NOTEBOOK}"\nprofile = 5\n', ["'profile' = 5"]),
        (f'notebook = "{FIXTURE_NOTEBOOK}"\nrepeats = true\n', ["'repeats' = True"]),
        (f'notebook = "{FIXTURE_NOTEBOOK}"\ngrid = [1, 2]\n', ["'grid' = [1, 2]", "a table"]),
        (f'notebook = "{FIXTURE_NOTEBOOK}"\nzip = 3\n', ["'zip' = 3", "a table"]),
        (f'notebook = "{FIXTURE_NOTEBOOK}"\nfixed = 3\n', ["'fixed' = 3", "a table"]),
        (f'notebook = "{FIXTURE_NOTEBOOK}"\nsummary = "xy"\n', ["'summary' = 'xy'", "a table"]),
        (QUICK.join([f'notebook = "{FIXTURE_NOTEBOOK}"\n', '[summary]\nx = 5\ny = "a"\n']), ["[summary] x = 5"]),
        (
            QUICK.join([f'notebook = "{FIXTURE_NOTEBOOK}"\n', '[summary]\nx = "n_trials"\ny = "a"\nxlabel = [1]\n']),
            ["[summary] xlabel = [1]"],
        ),
    ],
    ids=[
        "notebook int",
        "notebook list",
        "profile int",
        "repeats bool",
        "grid",
        "zip",
        "fixed",
        "summary",
        "x",
        "xlabel",
    ],
)
def test_a_spec_value_of_the_wrong_type_is_one_line_naming_the_key(tmp_path, body, fragments):
    spec = write_spec(tmp_path, body, notebook=False)
    one_line(tvtrack("sweep", spec, "-o", tmp_path / "out"), "spec.toml", *fragments)
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("key, value", [("xscale", '"bogus"'), ("yscale", "5")])
def test_a_summary_scale_matplotlib_has_not_is_refused_with_the_spec(tmp_path, key, value):
    spec = write_spec(tmp_path, QUICK + f'[summary]\nx = "n_trials"\ny = "centroid_rms_px.value"\n{key} = {value}\n')
    one_line(tvtrack("sweep", spec, "-o", tmp_path / "out"), "spec.toml", f"[summary] {key} = ", "'log'")
    assert not (tmp_path / "out").exists()
