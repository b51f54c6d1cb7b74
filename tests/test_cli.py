"""User errors on the command line: one line ``error: ...`` on stderr, exit status 2, no traceback,
before any kernel starts."""

import socket
import subprocess
import sys
import time

import pytest
from load import wall_budget

from conftest import one_line_error, FIXTURE_NOTEBOOK, FIXTURE_SWEEP


def tvtrack(*args, timeout=60):
    return subprocess.run(
        [sys.executable, "-m", "tvtrack", *map(str, args)], capture_output=True, text=True, timeout=timeout
    )


def assert_one_line_error(proc, *fragments):
    return one_line_error(proc, *fragments)


def spec(tmp_path, body, name="spec.toml"):
    path = tmp_path / name
    path.write_text(f'notebook = "{FIXTURE_NOTEBOOK}"\n{body}')
    return path


def test_typo_in_a_parameter_name_suggests_the_closest_and_starts_nothing(tmp_path):
    proc = tvtrack("run", "004_laser_spot_prediction", "-p", "n_trails", "3", "-o", tmp_path / "r", timeout=5)
    assert_one_line_error(proc, "'n_trails'", "'n_trials'", "004_laser_spot_prediction")
    assert not (tmp_path / "r").exists()


def test_bad_value_is_refused_by_the_notebooks_own_validation(tmp_path):
    proc = tvtrack("run", FIXTURE_NOTEBOOK, "-p", "gate_size_px", "99", "-o", tmp_path / "r")
    assert_one_line_error(proc, "gate_size_px", "99", "[5, 31]")
    assert not (tmp_path / "r").exists()


def test_missing_notebook_and_profile():
    assert_one_line_error(tvtrack("run", "no_such_notebook"), "no_such_notebook", "004_laser_spot_prediction")
    assert_one_line_error(tvtrack("run", "004_laser_spot_prediction", "--profile", "smok"), "'smok'", "smoke")


def test_output_directory_that_exists_or_cannot_be_created(tmp_path):
    (tmp_path / "taken").mkdir()
    assert_one_line_error(tvtrack("run", FIXTURE_NOTEBOOK, "-o", tmp_path / "taken"), "exists already")
    (tmp_path / "file").write_text("x")
    assert_one_line_error(tvtrack("run", FIXTURE_NOTEBOOK, "-o", tmp_path / "file" / "sub" / "run"), "cannot create")
    assert_one_line_error(tvtrack("sweep", FIXTURE_SWEEP, "-o", tmp_path / "file" / "sweep"), "cannot create")


def test_bad_jobs():
    assert_one_line_error(tvtrack("sweep", FIXTURE_SWEEP, "--jobs", "0"), "--jobs", "'0'")
    assert_one_line_error(tvtrack("reproduce", "--jobs", "-1"), "--jobs")
    assert_one_line_error(tvtrack("reproduce", "--only", "999_nothing"), "999_nothing")


def test_invalid_specs_name_the_file_and_what_is_wrong(tmp_path):
    broken = spec(tmp_path, "[grid]\nspot_sigma_px = = [1.0]\n[fixed]\nn_trials = 5\n", "broken.toml")
    assert_one_line_error(tvtrack("sweep", broken), "broken.toml", "line")
    uneven = spec(tmp_path, "[zip]\nspot_sigma_px = [1.0, 2.0]\nread_noise_e = [1.0]\n", "uneven.toml")
    assert_one_line_error(tvtrack("sweep", uneven), "uneven.toml", "same length")
    typo = spec(tmp_path, "[grid]\nspot_sigma = [1.0, 2.0]\n", "typo.toml")
    assert_one_line_error(tvtrack("sweep", typo), "typo.toml", "[grid]", "'spot_sigma'", "'spot_sigma_px'")
    bad_x = spec(
        tmp_path, '[grid]\nspot_sigma_px = [1.0]\n[summary]\nx = "sigma"\ny = "centroid_rms_px.value"\n', "bad_x.toml"
    )
    assert_one_line_error(tvtrack("sweep", bad_x), "bad_x.toml", "[summary]", "'sigma'")
    assert_one_line_error(tvtrack("sweep", tmp_path / "missing.toml"), "missing.toml")


def test_unreachable_scheduler_names_the_address_and_how_to_start_one(tmp_path):
    with socket.socket() as s:  # a loopback port with nothing listening
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    address = f"tcp://127.0.0.1:{port}"
    t0 = time.time()
    line = assert_one_line_error(
        tvtrack(
            "sweep", FIXTURE_SWEEP, "--executor", "dask", "--scheduler", address, "-o", tmp_path / "s", timeout=120
        ),
        address,
    )
    assert time.time() - t0 < wall_budget(15)
    assert "dask scheduler" in line


def test_debug_shows_the_traceback():
    proc = tvtrack("--debug", "run", "no_such_notebook")
    assert proc.returncode != 0 and "Traceback" in proc.stderr and "UsageError" in proc.stderr


@pytest.mark.parametrize(
    "notebook, parameter, value, names",
    [
        ("000_dissector_ekf", "dt", "0", ["dt"]),
        # a bound computed from another parameter must not crash when that parameter is not a number
        ("001_maneuver_occlusion_kf", "duration_s", "abc", ["duration_s"]),
    ],
)
def test_paper_notebook_cross_parameter_checks_are_one_line_errors(notebook, parameter, value, names):
    proc = tvtrack("run", notebook, "-p", parameter, value)
    assert_one_line_error(proc, *names)


def test_scheduler_address_without_a_port_is_one_line(tmp_path):
    for address in ("tcp://127.0.0.1", "127.0.0.1", "tcp://127.0.0.1:"):
        assert_one_line_error(
            tvtrack(
                "sweep", FIXTURE_SWEEP, "--executor", "dask", "--scheduler", address, "-o", tmp_path / "s", timeout=30
            ),
            repr(address),
            "no port",
        )
    assert_one_line_error(
        tvtrack(
            "sweep",
            FIXTURE_SWEEP,
            "--executor",
            "dask",
            "--scheduler",
            "tcp://host:http",
            "-o",
            tmp_path / "s",
            timeout=30,
        ),
        "'http'",
    )
    assert not (tmp_path / "s").exists()


@pytest.mark.parametrize("reply", [None, b"HTTP/1.0 200 OK\r\nContent-Length: 5\r\n\r\nhello"], ids=["silent", "http"])
def test_a_port_where_something_else_listens_is_one_line_within_15_s(tmp_path, reply):
    """Something that is not Dask listens on loopback (a silent service, a web server): one line naming it."""
    import threading

    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)

    def answer():
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return
            if reply:
                conn.recv(1024)
                conn.sendall(reply)

    threading.Thread(target=answer, daemon=True).start()
    address = f"tcp://127.0.0.1:{server.getsockname()[1]}"
    t0 = time.time()
    try:
        proc = tvtrack(
            "sweep", FIXTURE_SWEEP, "--executor", "dask", "--scheduler", address, "-o", tmp_path / "s", timeout=60
        )
    finally:
        server.close()
    assert time.time() - t0 < wall_budget(15)
    line = assert_one_line_error(proc, address)
    assert "not a Dask scheduler" in line and "dask scheduler" in line


def test_site_output_that_cannot_be_written_is_one_line(tmp_path):
    (tmp_path / "file").write_text("x")
    assert_one_line_error(
        tvtrack("site", "--runs", tmp_path, "-o", tmp_path / "file" / "site"), "cannot write", "file/site"
    )
    assert_one_line_error(tvtrack("site", "--runs", tmp_path, "-o", tmp_path / "file"), "is a file")
    assert (tmp_path / "file").read_text() == "x"


def test_output_dir_cannot_be_set_with_p_and_the_line_says_why(tmp_path):
    line = assert_one_line_error(
        tvtrack("run", FIXTURE_NOTEBOOK, "-p", "output_dir", "x", "-o", tmp_path / "r"), "'output_dir'", "-o"
    )
    assert "run's own directory" in line
    in_spec = spec(tmp_path, '[fixed]\noutput_dir = "x"\n')
    assert_one_line_error(tvtrack("sweep", in_spec, "-o", tmp_path / "s"), "'output_dir'", "-o")
    assert not (tmp_path / "r").exists() and not (tmp_path / "s").exists()


def test_sweep_values_are_checked_before_any_run_starts(tmp_path):
    bad = spec(tmp_path, "[fixed]\nn_trials = 5\n[grid]\nspot_sigma_px = [1.0, -2.0, 9.0]\n")
    t0 = time.time()
    line = assert_one_line_error(
        tvtrack("sweep", bad, "--jobs", "2", "-o", tmp_path / "s"), "spot_sigma_px", "-2.0", "no run started"
    )
    assert "1 more of the 3 parameter sets" in line
    assert time.time() - t0 < wall_budget(30)
    assert not (tmp_path / "s").exists()


def test_a_refusal_names_the_parameter_the_user_set():
    """001: window_n = 200 is refused by a check on fa_duration_s; the line leads with window_n."""
    line = assert_one_line_error(tvtrack("run", "001_maneuver_occlusion_kf", "-p", "window_n", "200"), "window_n")
    assert line.index("window_n") < line.index("fa_duration_s") if "fa_duration_s" in line else True


def test_edit_gives_a_working_copy_at_the_smoke_profile_outside_tracked_files(tmp_path):
    import json
    import shutil

    from tvtrack.pipeline.edit import EDIT_DIR, working_copy
    from tvtrack.pipeline.kernels import clone_kernel_name

    nb = tmp_path / "fixture_centroid.ipynb"
    shutil.copy(FIXTURE_NOTEBOOK, nb)
    (tmp_path / "fixture_centroid.smoke.toml").write_text("n_trials = 7\nn_frames = 3\n")
    copy, written = working_copy(nb, folder=tmp_path / "edit")
    assert written and copy == tmp_path / "edit" / "fixture_centroid.ipynb"
    data = json.loads(copy.read_text())
    code = [c for c in data["cells"] if c["cell_type"] == "code"]
    assert len(code) == len([c for c in json.loads(nb.read_text())["cells"] if c["cell_type"] == "code"])
    params = code[0]
    # one cell holds the smoke values themselves: no override below, nothing of the paper's values left
    assert params["metadata"]["tags"] == ["parameters"]
    assert not any("injected-parameters" in c["metadata"].get("tags", []) for c in code)
    source = params["source"]
    assert "n_trials = 7  # Monte Carlo trials" in source and "n_frames = 3  # frames per trial" in source
    assert "n_trials = 200" not in source and "n_frames = 20" not in source
    assert "RERUN_NOTEBOOK_ASSET" in source and repr(str(tmp_path / "edit" / "fixture_centroid-out")) in source
    assert data["metadata"]["kernelspec"]["name"] == clone_kernel_name()
    assert all(not c["outputs"] for c in code)
    # a reader edits the parameters cell, then Runs All from another working directory: the edit takes effect
    # and outputs land in the copy's own -out folder
    copy.write_text(copy.read_text().replace("n_trials = 7", "n_trials = 9"))
    import nbformat
    from nbclient import NotebookClient

    book = nbformat.read(copy, as_version=4)
    NotebookClient(book, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}).execute()
    results = json.loads((tmp_path / "edit" / "fixture_centroid-out" / "results.json").read_text())
    assert results["parameters"]["n_trials"] == 9 and results["parameters"]["n_frames"] == 3
    # an existing copy holds the user's edits: kept unless fresh
    assert working_copy(nb, folder=tmp_path / "edit") == (copy, False) and "n_trials = 9" in copy.read_text()
    assert working_copy(nb, folder=tmp_path / "edit", fresh=True) == (copy, True) and "n_trials = 7" in copy.read_text()
    # the default folder is ignored by git: autosave never touches a tracked file
    ignored = subprocess.run(["git", "check-ignore", "-q", str(EDIT_DIR / "x.ipynb")], cwd=EDIT_DIR.parents[1])
    assert ignored.returncode == 0


def test_the_parameters_cell_keeps_comments_and_replaces_multiline_values():
    from tvtrack.pipeline.edit import parameters_cell

    source = 'a = 1  # first, "quoted # not a comment"\nb = [\n    1,\n    2,\n]  # a list\nc = "x # y"\n'
    out = parameters_cell(source, {"b": [3], "c": "z", "d": 4.0}, ["# header"])
    assert out == "# header\na = 1  # first, \"quoted # not a comment\"\nb = [3]  # a list\nc = 'z'\nd = 4.0\n"


def test_edit_refuses_an_unknown_notebook_or_profile():
    assert_one_line_error(tvtrack("edit", "no_such_notebook"), "no_such_notebook")
    assert_one_line_error(tvtrack("edit", FIXTURE_NOTEBOOK, "--profile", "smok"), "'smok'")


def test_the_inline_viewer_loads_the_bundled_assets_offline():
    """With the variable the working copy (and the tvtrack-repro kernel) sets, rerun-notebook inlines its own
    widget.js and Wasm instead of pointing the browser at app.rerun.io ("Failed to fetch" offline)."""
    from tvtrack.pipeline.edit import OFFLINE_VIEWER_LINE

    probe = (
        "import os\n" + OFFLINE_VIEWER_LINE + "\nimport rerun_notebook as r\n"
        "print(r.ASSET_IS_URL, 'app.rerun.io' in r.ESM_MOD[:100000], len(r.ESM_MOD) > 10_000_000)"
    )
    out = subprocess.run(
        [sys.executable, "-c", probe],
        capture_output=True,
        text=True,
        timeout=120,
        env={k: v for k, v in __import__("os").environ.items() if k != "RERUN_NOTEBOOK_ASSET"},
    )
    assert out.stdout.split()[-3:] == ["False", "False", "True"], out.stdout + out.stderr


def test_report_and_site_of_a_profile_without_runs_are_one_line(tmp_path):
    # both name the command that makes them, for all notebooks and for one
    one = "python -m tvtrack reproduce --profile nope --only NAME"
    assert_one_line_error(tvtrack("report", "--profile", "nope"), "no runs at the nope profile", "PROFILE=nope", one)
    assert_one_line_error(tvtrack("site", "--runs", tmp_path, "--profile", "nope"), "no runs at the nope profile", one)
    assert not (tmp_path / "site-nope").exists()
